// Fuzz target for parse_off: reader invariants on success, one-line
// messages on failure, and an exact write_off -> parse_off round trip (the
// reader only makes per-vertex attributes, which OFF variants can hold).
#include <cstddef>
#include <cstdint>

#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/mesh_writers.h"
#include "tests/fuzz/text_mesh_fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lodbake::fuzz::check_round_trip(
      data, size,
      [](const uint8_t* d, size_t n) {
        lodbake::ImportReport report;
        return lodbake::parse_off(d, n, &report);
      },
      [](const lodbake::TriangleMesh& mesh) { return lodbake::write_off(mesh); });
  return 0;
}
