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

bool SplitConnectivity::FaceLists::contains(uint32_t v, uint32_t f) const {
  const uint32_t* d = data(v);
  return std::find(d, d + count(v), f) != d + count(v);
}

void SplitConnectivity::FaceLists::push(uint32_t v, uint32_t f) {
  List& l = lists_[v];
  if (l.spill == kNoSpill && l.count < kInline) {
    l.head[l.count++] = f;
    return;
  }
  if (l.spill == kNoSpill) {
    if (free_spills_.empty()) {
      l.spill = static_cast<uint32_t>(spills_.size());
      spills_.emplace_back();
    } else {
      l.spill = free_spills_.back();
      free_spills_.pop_back();
    }
    spills_[l.spill].assign(l.head, l.head + l.count);
  }
  spills_[l.spill].push_back(f);
  ++l.count;
}

void SplitConnectivity::FaceLists::erase(uint32_t v, uint32_t f) {
  List& l = lists_[v];
  if (l.spill != kNoSpill) {
    std::vector<uint32_t>& spill = spills_[l.spill];
    const auto it = std::find(spill.begin(), spill.end(), f);
    if (it == spill.end()) return;
    spill.erase(it);
    if (spill.size() <= kInline) {
      std::copy(spill.begin(), spill.end(), l.head);
      spill.clear();
      free_spills_.push_back(l.spill);
      l.spill = kNoSpill;
    }
  } else {
    uint32_t* end = l.head + l.count;
    uint32_t* it = std::find(l.head, end, f);
    if (it == end) return;
    std::copy(it + 1, end, it);
  }
  --l.count;
}

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
    if ((k < 1 || t[k] != t[0]) && (k < 2 || t[k] != t[1])) vertex_faces_.push(t[k], f);
  }
}

bool SplitConnectivity::neighbours(uint32_t vs, std::vector<uint32_t>* ring) const {
  ring->clear();
  const size_t face_count = vertex_faces_.count(vs);
  if (face_count == 0 || face_count > kMaxFanFaces) return false;
  const uint32_t* faces = vertex_faces_.data(vs);
  // (a, b) of each face (vs, a, b), in vs's face list order.
  uint32_t a[kMaxFanFaces];
  uint32_t b[kMaxFanFaces];
  bool used[kMaxFanFaces] = {};
  size_t pairs = 0;
  for (size_t i = 0; i < face_count; ++i) {
    const Triangle& t = faces_[faces[i]];
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

void SplitConnectivity::prefetch_faces(uint32_t v) const {
  if (v >= vertex_count()) return;
  const size_t count = std::min<size_t>(vertex_faces_.count(v), 16);
  const uint32_t* faces = vertex_faces_.data(v);
  for (size_t i = 0; i < count; ++i)
    __builtin_prefetch(&faces_[faces[i]]);
}

void SplitConnectivity::split(uint32_t vs, uint32_t vl, uint32_t vr) {
  const uint32_t vt = vertex_count();
  vertex_faces_.add_vertex();
  const size_t face_count = vertex_faces_.count(vs);
  uint32_t moved[kMaxFanFaces];
  size_t moves = 0;
  if (face_count <= kMaxFanFaces) {
    const uint32_t* faces = vertex_faces_.data(vs);
    bool taken[kMaxFanFaces] = {};
    // The untaken face of vs whose corner `offset` places after vs is v.
    auto find = [&](int offset, uint32_t v) {
      for (size_t i = 0; i < face_count; ++i) {
        const Triangle& t = faces_[faces[i]];
        if (!taken[i] && t[(corner(t, vs) + offset) % 3] == v) return i;
      }
      return face_count;
    };
    bool reached_vl = false;
    if (vr != kNoVertex) {
      uint32_t next = vr;
      for (size_t i = find(1, next); i < face_count; i = find(1, next)) {
        taken[i] = true;
        moved[moves++] = faces[i];
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
      for (size_t i = find(2, prev); i < face_count; i = find(2, prev)) {
        taken[i] = true;
        moved[moves++] = faces[i];
        const Triangle& t = faces_[faces[i]];
        prev = t[(corner(t, vs) + 1) % 3];
      }
    }
  }
  for (size_t k = 0; k < moves; ++k) {
    const uint32_t f = moved[k];
    Triangle& t = faces_[f];
    t[corner(t, vs)] = vt;
    vertex_faces_.erase(vs, f);
    // A face holding vt already (only a degenerate hostile one) stays listed once.
    if (!vertex_faces_.contains(vt, f)) vertex_faces_.push(vt, f);
  }
  if (vl != kNoVertex) add_face({vs, vt, vl});
  if (vr != kNoVertex) add_face({vt, vs, vr});
}

}  // namespace lodbake
