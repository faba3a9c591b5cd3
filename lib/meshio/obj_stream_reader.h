// An OBJ reader that streams the file instead of holding it, for
// out-of-core runs (lib/outofcore): positions in one pass, triangles in
// another (which may run again), through a buffer of whole lines. It reads
// positions and faces only, with the in-memory reader's rules
// (obj_reader.cpp): the same scanner, 1-based and relative indices resolved
// against the elements read so far, polygons split by PolygonTriangulator.
// Texture coordinate and normal statements and indices are checked as the
// in-memory reader checks them, so a file this reader takes, that one takes
// too, with the same positions and triangles.
#pragma once

#include <cstdint>
#include <functional>
#include <istream>
#include <memory>
#include <vector>

#include "formats/mesh/triangle_mesh.h"
#include "formats/support/status.h"

namespace lodbake {

class ObjStreamReader {
 public:
  /// A reader of the OBJ text in `in` (`size` bytes). `in` must outlive it.
  /// Fails with kUnsupported on UTF-16 text (the in-memory reader decodes it).
  static Result<std::unique_ptr<ObjStreamReader>> open(std::istream* in, uint64_t size);

  /// Counts of the last for_each_vertex() pass ('f' statements, not
  /// triangles).
  uint64_t vertex_count() const { return vertices_; }
  uint64_t face_count() const { return faces_; }

  /// One pass calling `vertex(index, xyz)` for every 'v', stopping at the
  /// first error it returns. Fails on a malformed or non-finite 'v', 'vt' or
  /// 'vn', and on a file without faces.
  Status for_each_vertex(const std::function<Status(uint64_t, const float*)>& vertex);
  /// One pass calling `triangle(face_index, {a, b, c})` for every triangle
  /// of every face, stopping at the first error it returns. `positions` are
  /// the ones for_each_vertex() gave (polygons need them to be split). Fails
  /// on a malformed face or an index out of range, naming the line.
  Status for_each_triangle(const std::vector<Vec3f>& positions,
                           const std::function<Status(uint64_t, const uint32_t*)>& triangle);

 private:
  ObjStreamReader(std::istream* in, uint64_t size) : in_(in), size_(size) {}
  class Pass;

  std::istream* in_;
  uint64_t size_;
  uint64_t vertices_ = 0;
  uint64_t faces_ = 0;
};

}  // namespace lodbake
