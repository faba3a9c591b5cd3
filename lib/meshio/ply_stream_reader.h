// A PLY reader that streams the body instead of holding the file: each
// element is visited in one pass over a std::istream, so that a mesh larger
// than memory can be read twice (positions, then faces) without holding its
// triangles (lib/outofcore). The header is parsed and planned by the same
// code as the in-memory reader (ply_header.h, ply_plan.h), so a file both
// readers take means the same mesh; this one takes triangle faces only
// (polygons and tristrips are refused as unsupported), reads no attributes,
// and never allocates from a count in the file.
#pragma once

#include <cstdint>
#include <functional>
#include <istream>
#include <memory>

#include "formats/support/status.h"
#include "lib/meshio/ply_header.h"
#include "lib/meshio/ply_plan.h"

namespace lodbake {

class PlyStreamReader {
 public:
  /// Reads and plans the header of the PLY file in `in` (`size` bytes from
  /// the stream's start). `in` must outlive the reader. Fails like
  /// parse_ply_header() and plan_ply(), and with kUnsupported on a tristrips
  /// element.
  static Result<std::unique_ptr<PlyStreamReader>> open(std::istream* in, uint64_t size);

  uint64_t vertex_count() const { return plan_.vertex_count; }
  uint64_t face_count() const { return plan_.face_count; }

  /// One pass over the body calling `vertex(index, xyz)` for every vertex.
  /// Fails on a non-finite coordinate or a body that ends early.
  Status for_each_vertex(const std::function<void(uint64_t, const float*)>& vertex);
  /// One pass over the body calling `triangle(face_index, {a, b, c})` for
  /// every face, stopping at the first error it returns. Fails on a face
  /// that is not a triangle (kUnsupported), an index out of range, or a body
  /// that ends early.
  Status for_each_triangle(const std::function<Status(uint64_t, const uint32_t*)>& triangle);

 private:
  PlyStreamReader(std::istream* in, uint64_t size, PlyHeader header)
      : in_(in), size_(size), header_(std::move(header)) {}
  enum class Want { kVertices, kFaces };
  Status pass(Want want, const std::function<void(uint64_t, const float*)>& vertex,
              const std::function<Status(uint64_t, const uint32_t*)>& triangle);

  std::istream* in_;
  uint64_t size_;
  PlyHeader header_;  // before plan_, which points into it
  PlyPlan plan_;
};

}  // namespace lodbake
