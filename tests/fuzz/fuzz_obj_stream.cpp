// Fuzz target for the streaming OBJ reader of out-of-core runs
// (lib/meshio/obj_stream_reader.h). On success: finite positions numbered
// in order, every triangle's indices in range, a second triangle pass
// reading the same triangles, and the in-memory reader accepting the file
// with the same positions and triangles (the streaming reader follows its
// rules). On failure the message must be one non-empty line.
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "lib/meshio/mesh_readers.h"
#include "lib/meshio/obj_stream_reader.h"
#include "tests/fuzz/mesh_invariants.h"

namespace {

using lodbake::Status;
using lodbake::Triangle;
using lodbake::Vec3f;
using lodbake::fuzz::require;

Status read_triangles(lodbake::ObjStreamReader* reader, const std::vector<Vec3f>& positions,
                      std::vector<Triangle>* out) {
  return reader->for_each_triangle(positions, [&](uint64_t, const uint32_t* t) {
    require(t[0] < positions.size() && t[1] < positions.size() && t[2] < positions.size());
    out->push_back({t[0], t[1], t[2]});
    return Status::ok();
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::istringstream in(text);
  auto opened = lodbake::ObjStreamReader::open(&in, size);
  if (!opened.is_ok()) {
    lodbake::fuzz::check_error(opened.status());
    return 0;
  }
  lodbake::ObjStreamReader& reader = *opened.value();
  std::vector<Vec3f> positions;
  const Status read = reader.for_each_vertex([&](uint64_t i, const float* p) {
    require(i == positions.size());
    for (int k = 0; k < 3; ++k)
      require(p[k] - p[k] == 0.0f);
    positions.push_back({p[0], p[1], p[2]});
    return Status::ok();
  });
  if (!read.is_ok()) {
    lodbake::fuzz::check_error(read);
    return 0;
  }
  require(positions.size() == reader.vertex_count());
  std::vector<Triangle> first, second;
  const Status faces = read_triangles(&reader, positions, &first);
  if (!faces.is_ok()) {
    lodbake::fuzz::check_error(faces);
    return 0;
  }
  require(read_triangles(&reader, positions, &second).is_ok());
  require(first == second);
  lodbake::ImportReport report;
  auto mesh = lodbake::parse_obj(data, size, &report);
  require(mesh.is_ok());
  require(mesh.value().positions == positions);
  require(mesh.value().triangles == first);
  return 0;
}
