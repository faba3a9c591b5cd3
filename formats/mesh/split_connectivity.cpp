// Hoppe 1996 ("Progressive meshes", section 3: the vertex split vsplit(vs,
// vl, vr)) applied to an indexed face set with per-vertex face lists. Each
// list is scanned linearly: fans average six faces, so a search beats any
// index, and the kMaxFanFaces cap bounds the scans.
#include "formats/mesh/split_connectivity.h"

#include <algorithm>

#include "formats/mesh/progressive_mesh.h"

namespace lodbake {
namespace {

int corner(const Triangle& t, uint32_t v) {
  return t[0] == v ? 0 : t[1] == v ? 1 : 2;
}

bool contains(const std::vector<uint32_t>& list, uint32_t v) {
  return std::find(list.begin(), list.end(), v) != list.end();
}

}  // namespace

SplitConnectivity::SplitConnectivity(uint32_t vertex_count, const std::vector<Triangle>& triangles)
    : vertex_faces_(vertex_count) {
  faces_.reserve(triangles.size());
  for (const Triangle& t : triangles)
    add_face(t);
}

void SplitConnectivity::add_face(const Triangle& t) {
  const uint32_t f = static_cast<uint32_t>(faces_.size());
  faces_.push_back(t);
  for (int k = 0; k < 3; ++k) {
    if ((k < 1 || t[k] != t[0]) && (k < 2 || t[k] != t[1])) vertex_faces_[t[k]].push_back(f);
  }
}

bool SplitConnectivity::neighbours(uint32_t vs, std::vector<uint32_t>* ring) const {
  ring->clear();
  const std::vector<uint32_t>& faces = vertex_faces_[vs];
  if (faces.empty() || faces.size() > kMaxFanFaces) return false;
  // (a, b) of each face (vs, a, b), in vs's face list order.
  uint32_t a[kMaxFanFaces];
  uint32_t b[kMaxFanFaces];
  bool used[kMaxFanFaces] = {};
  size_t pairs = 0;
  for (uint32_t f : faces) {
    const Triangle& t = faces_[f];
    const int c = corner(t, vs);
    const uint32_t x = t[(c + 1) % 3];
    const uint32_t y = t[(c + 2) % 3];
    if (x == vs || y == vs || x == y) continue;  // a degenerate face has no fan edge
    a[pairs] = x;
    b[pairs] = y;
    ++pairs;
  }
  if (pairs == 0) return false;
  uint32_t start = kNoVertex;
  uint32_t smallest = kNoVertex;
  for (size_t i = 0; i < pairs; ++i) {
    smallest = std::min(smallest, a[i]);
    if (a[i] < start && std::find(b, b + pairs, a[i]) == b + pairs) start = a[i];
  }
  if (start == kNoVertex) start = smallest;
  uint32_t current = start;
  size_t walked = 0;
  bool returned = false;
  for (;;) {
    size_t i = 0;
    while (i < pairs && (used[i] || a[i] != current))
      ++i;
    if (!contains(*ring, current)) ring->push_back(current);
    if (i == pairs) break;
    used[i] = true;
    ++walked;
    current = b[i];
    if (current == start) {
      returned = true;
      break;
    }
  }
  const size_t first_rest = ring->size();
  for (size_t i = 0; i < pairs; ++i) {
    if (used[i]) continue;
    for (uint32_t v : {a[i], b[i]}) {
      if (!contains(*ring, v)) ring->push_back(v);
    }
  }
  std::sort(ring->begin() + static_cast<std::ptrdiff_t>(first_rest), ring->end());
  return returned && walked == pairs;
}

void SplitConnectivity::split(uint32_t vs, uint32_t vl, uint32_t vr) {
  const uint32_t vt = vertex_count();
  vertex_faces_.emplace_back();
  std::vector<uint32_t>& faces = vertex_faces_[vs];
  std::vector<uint32_t> moved;
  if (faces.size() <= kMaxFanFaces) {
    bool taken[kMaxFanFaces] = {};
    // The untaken face of vs whose corner `offset` places after vs is v.
    auto find = [&](int offset, uint32_t v) {
      for (size_t i = 0; i < faces.size(); ++i) {
        const Triangle& t = faces_[faces[i]];
        if (!taken[i] && t[(corner(t, vs) + offset) % 3] == v) return i;
      }
      return faces.size();
    };
    bool reached_vl = false;
    if (vr != kNoVertex) {
      uint32_t next = vr;
      for (size_t i = find(1, next); i < faces.size(); i = find(1, next)) {
        taken[i] = true;
        moved.push_back(faces[i]);
        const Triangle& t = faces_[faces[i]];
        next = t[(corner(t, vs) + 2) % 3];
        if (next == vl) {
          reached_vl = true;
          break;
        }
      }
    }
    if (vl != kNoVertex && !reached_vl) {
      uint32_t prev = vl;
      for (size_t i = find(2, prev); i < faces.size(); i = find(2, prev)) {
        taken[i] = true;
        moved.push_back(faces[i]);
        const Triangle& t = faces_[faces[i]];
        prev = t[(corner(t, vs) + 1) % 3];
      }
    }
  }
  for (uint32_t f : moved) {
    Triangle& t = faces_[f];
    t[corner(t, vs)] = vt;
    faces.erase(std::find(faces.begin(), faces.end(), f));
    // A face holding vt already (only a degenerate hostile one) stays listed once.
    if (!contains(vertex_faces_[vt], f)) vertex_faces_[vt].push_back(f);
  }
  if (vl != kNoVertex) add_face({vs, vt, vl});
  if (vr != kNoVertex) add_face({vt, vs, vr});
}

}  // namespace lodbake
