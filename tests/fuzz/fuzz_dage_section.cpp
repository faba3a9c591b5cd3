// Fuzz target for a bare DAGE payload: summary, decode, validation, and the
// canonical round trip (a payload that decodes re-encodes to the same bytes).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "formats/sections/dage.h"

namespace {

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz invariant failed: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  Result<DageSummary> summary = read_dage_summary(data, size);
  DageSummary decoded_summary;
  Result<VsplitDag> dag = decode_dage(data, size, &decoded_summary);
  if (!dag.is_ok()) {
    require(dag.status().code() == 23 || dag.status().kind() == ErrorKind::kRuntime,
            "DAGE decode error without LBK-E023");
    return 0;
  }
  require(summary.is_ok(), "DAGE decodes but its summary does not");
  require(summary.value().node_count == dag.value().node_count() &&
              summary.value().edge_count == dag.value().edge_count(),
          "DAGE summary disagrees with the graph");
  (void)validate_dage(dag.value());
  Result<Bytes> again = encode_dage(dag.value());
  require(again.is_ok(), "decoded DAGE cannot be encoded");
  require(again.value().size() == size &&
              (size == 0 || std::memcmp(again.value().data(), data, size) == 0),
          "DAGE is not canonical");
  return 0;
}
