// Fuzz target for a bare DAGE payload: summary, decode, validation, and the
// canonical round trip (a payload that decodes re-encodes to the same bytes).
#include <cstdint>

#include "formats/sections/dage.h"
#include "tests/fuzz/fuzz_section_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  using namespace lodbake::fuzz;
  Result<DageSummary> summary = read_dage_summary(data, size);
  DageSummary decoded_summary;
  Result<VsplitDag> dag = decode_dage(data, size, &decoded_summary);
  if (!dag.is_ok()) {
    require_decode_error(dag.status(), "DAGE decode error without LBK-E023");
    return 0;
  }
  require(summary.is_ok(), "DAGE decodes but its summary does not");
  require(summary.value().node_count == dag.value().node_count() &&
              summary.value().edge_count == dag.value().edge_count(),
          "DAGE summary disagrees with the graph");
  (void)validate_dage(dag.value());
  Result<Bytes> again = encode_dage(dag.value());
  require(again.is_ok(), "decoded DAGE cannot be encoded");
  require_same_bytes(again.value(), data, size, "DAGE is not canonical");
  return 0;
}
