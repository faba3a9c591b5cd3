// Fuzz target for a bare STRP payload: summary and decode agree, and what
// decodes re-encodes to bytes that decode to the same strips.
#include <cstdint>

#include "formats/sections/strp.h"
#include "tests/fuzz/fuzz_section_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lodbake;
  using namespace lodbake::fuzz;
  Result<StrpSummary> summary = read_strp_summary(data, size);
  Result<TriangleStrips> strips = decode_strp(data, size);
  if (!strips.is_ok()) {
    require_decode_error(strips.status(), "STRP decode error without LBK-E023");
    return 0;
  }
  require(summary.is_ok(), "STRP decodes but its summary does not");
  require(summary.value().strip_count == strips.value().strip_count(), "summary strip count");
  require(summary.value().index_count == strips.value().indices.size(), "summary index count");
  Result<Bytes> again = encode_strp(strips.value());
  require(again.is_ok(), "decoded strips do not encode");
  Result<TriangleStrips> redecoded = decode_strp(again.value().data(), again.value().size());
  require(redecoded.is_ok() && redecoded.value() == strips.value(), "STRP round trip");
  (void)strip_triangles(strips.value());
  return 0;
}
