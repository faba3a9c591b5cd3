// Fuzz target for a bare VSPL payload, decoded against a synthetic base mesh
// of the stored base vertex count: summary, decode, validation, and the
// float32 round trip (tests/fuzz/fuzz_section_checks.h).
#include <cstdint>

#include "tests/fuzz/fuzz_section_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::fuzz::check_vspl_payload(data, size, nullptr);
  return 0;
}
