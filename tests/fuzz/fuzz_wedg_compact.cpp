// Fuzz target for the compact WEDG decoder (codec 1, against BASE). Input:
// a u32 byte count n, n bytes of a raw BASE payload, then a compact WEDG
// payload (the corpus holds a real pair written by lodbake-pack).
#include "formats/container/section_registry.h"
#include "tests/fuzz/fuzz_compact_section.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::fuzz::check_base_compact_section(lodbake::kWedgTag, data, size);
  return 0;
}
