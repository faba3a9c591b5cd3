// Validation and fan walk of one vertex split, shared by the PM replay and
// the DAG's split simulator so that both refuse the same records with the
// same messages. The walk is bounded by vs's face count, so a corrupt fan
// (a cycle that never meets vl) cannot loop.
#include "lib/simplify/split_fan.h"

#include <string>

#include "lib/simplify/vec_math.h"

namespace lodbake {

uint32_t face_with_next(const std::vector<Triangle>& triangles,
                        const std::vector<std::vector<uint32_t>>& vertex_faces, uint32_t v,
                        uint32_t next) {
  for (uint32_t f : vertex_faces[v]) {
    const Triangle& t = triangles[f];
    if (t[(corner_of(t, v) + 1) % 3] == next) return f;
  }
  return kNoVertex;
}

uint32_t face_with_prev(const std::vector<Triangle>& triangles,
                        const std::vector<std::vector<uint32_t>>& vertex_faces, uint32_t v,
                        uint32_t prev) {
  for (uint32_t f : vertex_faces[v]) {
    const Triangle& t = triangles[f];
    if (t[(corner_of(t, v) + 2) % 3] == prev) return f;
  }
  return kNoVertex;
}

Status collect_moved_faces(const std::vector<Triangle>& triangles,
                           const std::vector<std::vector<uint32_t>>& vertex_faces,
                           uint32_t vertex_count, const VertexSplit& s, size_t index,
                           std::vector<uint32_t>* moved) {
  const uint32_t vt = vertex_count;
  // Built only for an error: this runs once per split of every replay.
  auto where = [index] { return "vertex split " + std::to_string(index) + ": "; };
  const uint32_t vs = s.vs;
  const uint32_t vl = s.vl;
  const uint32_t vr = s.vr;
  if (vs >= vt || (vl != kNoVertex && vl >= vt) || (vr != kNoVertex && vr >= vt)) {
    return invalid_input(where() + "vertex index out of range (" + std::to_string(vt) +
                         " vertices)");
  }
  if (vl == kNoVertex && vr == kNoVertex) return invalid_input(where() + "both wings are missing");
  if (vl == vs || vr == vs || vl == vr) return invalid_input(where() + "repeated vertex");
  for (uint32_t w : {vl, vr}) {
    if (w != kNoVertex && face_with_next(triangles, vertex_faces, vs, w) == kNoVertex &&
        face_with_prev(triangles, vertex_faces, vs, w) == kNoVertex) {
      return invalid_input(where() + "wing vertex " + std::to_string(w) +
                           " is not adjacent to the split vertex");
    }
  }
  const size_t first_moved = moved->size();
  const size_t limit = vertex_faces[vs].size();
  auto fan_does_not_end = [&]() {
    moved->resize(first_moved);
    return invalid_input(where() + "the fan around vertex " + std::to_string(vs) + " does not end");
  };
  bool reached_vl = false;
  if (vr != kNoVertex) {
    uint32_t next = vr;
    for (;;) {
      const uint32_t f = face_with_next(triangles, vertex_faces, vs, next);
      if (f == kNoVertex) break;
      if (moved->size() - first_moved >= limit) return fan_does_not_end();
      moved->push_back(f);
      const Triangle& t = triangles[f];
      next = t[(corner_of(t, vs) + 2) % 3];
      if (next == vl) {
        reached_vl = true;
        break;
      }
    }
  }
  if (vl != kNoVertex && !reached_vl) {
    uint32_t prev = vl;
    for (;;) {
      const uint32_t f = face_with_prev(triangles, vertex_faces, vs, prev);
      if (f == kNoVertex) break;
      if (moved->size() - first_moved >= limit) return fan_does_not_end();
      moved->push_back(f);
      const Triangle& t = triangles[f];
      prev = t[(corner_of(t, vs) + 1) % 3];
    }
  }
  return Status::ok();
}

}  // namespace lodbake
