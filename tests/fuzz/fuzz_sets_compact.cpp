// Fuzz target for the compact SETS decoder (codec 1). Input: a compact
// SETS payload (the corpus holds real ones written by lodbake-pack).
#include "formats/container/section_registry.h"
#include "tests/fuzz/fuzz_compact_section.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::fuzz::check_compact_section(lodbake::kSetsTag, data, size);
  return 0;
}
