// Fuzz target for a bare VTRE payload: summary, decode, validation (a
// payload that decodes must pass it), and the round trip through the
// encoder back to the same trees.
#include <cstdint>

#include "formats/sections/vtre.h"
#include "tests/fuzz/fuzz_section_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  using namespace lodbake::fuzz;
  Result<VtreSummary> summary = read_vtre_summary(data, size);
  Result<VertexTrees> trees = decode_vtre(data, size);
  if (!trees.is_ok()) {
    require_decode_error(trees.status(), "VTRE decode error without LBK-E023");
    return 0;
  }
  require(summary.is_ok(), "VTRE decodes but its summary does not");
  require(summary.value().node_count() == trees.value().node_count(),
          "VTRE summary disagrees with the trees");
  require(validate_vtre(trees.value()).empty(), "decoded VTRE fails validation");
  Result<Bytes> again = encode_vtre(trees.value());
  require(again.is_ok(), "decoded VTRE cannot be encoded");
  Result<VertexTrees> back = decode_vtre(again.value().data(), again.value().size());
  require(back.is_ok() && back.value() == trees.value(), "VTRE round trip");
  return 0;
}
