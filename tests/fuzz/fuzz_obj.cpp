// Fuzz target for parse_obj: reader invariants on success, one-line
// messages on failure, and an exact write_obj -> parse_obj round trip.
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
        return lodbake::parse_obj(d, n, &report);
      },
      [](const lodbake::TriangleMesh& mesh) { return lodbake::write_obj(mesh); });
  return 0;
}
