// Fuzz target for the compact STRP decoder (codec 1), coded against BASE.
// Input: a u32 byte count n, n bytes of a raw BASE payload, then the
// compact STRP payload (the corpus holds real pairs written by
// lodbake-pack). The encoder decodes what it is given with the raw reader
// first, so the round trip also checks that the decoder's output is a
// valid raw STRP payload.
#include "formats/container/section_registry.h"
#include "tests/fuzz/fuzz_compact_section.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::fuzz::check_base_compact_section(lodbake::kStrpTag, data, size);
  return 0;
}
