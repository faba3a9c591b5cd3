// Fuzz target for a bare BASE payload: decode, summary, validation, and the
// canonical round trip (tests/fuzz/fuzz_section_checks.h).
#include <cstdint>

#include "tests/fuzz/fuzz_section_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::fuzz::check_base_payload(data, size);
  return 0;
}
