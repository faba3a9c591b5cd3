// Fuzz target for the streaming PLY reader of out-of-core runs
// (lib/meshio/ply_stream_reader.h). On success: as many positions as the
// header's vertex count, all finite, every triangle's indices in range, and
// a second pass reading the same triangles; and the in-memory reader must
// accept the file too (it takes everything this one does). On failure the
// message must be one non-empty line.
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/ply_stream_reader.h"
#include "tests/fuzz/mesh_invariants.h"

namespace {

using lodbake::Status;
using lodbake::Triangle;
using lodbake::fuzz::require;

// The triangles of one pass, or the failure.
Status read_triangles(lodbake::PlyStreamReader* reader, std::vector<Triangle>* out) {
  return reader->for_each_triangle([&](uint64_t, const uint32_t* t) {
    require(t[0] < reader->vertex_count() && t[1] < reader->vertex_count() &&
            t[2] < reader->vertex_count());
    out->push_back({t[0], t[1], t[2]});
    return Status::ok();
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::istringstream in(text);
  auto opened = lodbake::PlyStreamReader::open(&in, size);
  if (!opened.is_ok()) {
    lodbake::fuzz::check_error(opened.status());
    return 0;
  }
  lodbake::PlyStreamReader& reader = *opened.value();
  uint64_t vertices = 0;
  const Status read = reader.for_each_vertex([&](uint64_t i, const float* p) {
    require(i == vertices);
    for (int k = 0; k < 3; ++k)
      require(p[k] - p[k] == 0.0f);
    ++vertices;
  });
  if (!read.is_ok()) {
    lodbake::fuzz::check_error(read);
    return 0;
  }
  require(vertices == reader.vertex_count());
  std::vector<Triangle> first, second;
  const Status faces = read_triangles(&reader, &first);
  if (!faces.is_ok()) {
    lodbake::fuzz::check_error(faces);
    return 0;
  }
  require(read_triangles(&reader, &second).is_ok());
  require(first == second);
  lodbake::ImportReport report;
  require(lodbake::parse_ply(data, size, &report).is_ok());
  return 0;
}
