// The fan hierarchy's editable mesh. Choices:
// - triangles keep their input index for ever, so the node lists of the
//   FANH section can name them; a collapse only renames one corner or kills
//   the triangle, and a dead triangle keeps the corners it died with, which
//   is exactly what the inverse split restores;
// - vertex-to-triangle lists are exact (a killed or renamed triangle is
//   swap-removed from the old corner's list): fans are small, so the removal
//   scan is cheaper than filtering stale entries on every read, and the
//   validity check reads the lists without copying. They live in one 64-byte
//   slot per vertex (IncidenceLists) rather than a std::vector each: the
//   construction visits vertices in error order, i.e. at random, and a slot
//   is one cache miss where a vector was two (header, then block); this cut
//   the dragon's build by about a sixth (docs/benchmarks.md);
// - the validity check is local: a collapse or split changes only triangles
//   of the two vertices' stars, so checking the stars of the corners of
//   those triangles covers every edge, vertex and duplicate it can affect;
//   a corner whose star only sees c renamed to v (it is not otherwise a
//   neighbour of v) keeps an isomorphic star and is skipped
//   (collect_changed()).
#include "lib/fanmerge/fan_mesh_state.h"

#include <algorithm>
#include <new>

namespace lodbake {
namespace fan_internal {

void IncidenceLists::init(size_t n, const std::vector<uint32_t>& capacity) {
  slots_.assign(n, Slot());
  pool_.assign(1, 0);  // offset 0 means "inline"
  for (size_t v = 0; v < n; ++v)
    if (capacity[v] > kInline) grow(slots_[v], capacity[v]);
}

uint32_t* IncidenceLists::grow(Slot& s, uint32_t capacity) {
  const size_t at = pool_.size() + 1;
  // Offsets are 32-bit; the old block is left unused (a list only grows by
  // doubling, so the waste is bounded by the lists' largest sizes).
  if (at + capacity > 0xffffffffu) throw std::bad_alloc();
  pool_.resize(at + capacity);  // may move the pool: copy by offset, after
  pool_[at - 1] = capacity;
  const uint32_t* old = s.where == 0 ? s.items : pool_.data() + s.where;
  std::copy(old, old + s.size, pool_.data() + at);
  s.where = static_cast<uint32_t>(at);
  return pool_.data() + at;
}

void IncidenceLists::push_back(uint32_t v, uint32_t t) {
  Slot& s = slots_[v];
  const uint32_t capacity = s.where == 0 ? kInline : pool_[s.where - 1];
  uint32_t* d = s.size < capacity ? data(s) : grow(s, 2 * capacity);
  d[s.size++] = t;
}

void IncidenceLists::remove(uint32_t v, uint32_t t) {
  Slot& s = slots_[v];
  uint32_t* d = data(s);
  for (uint32_t i = 0; i < s.size; ++i)
    if (d[i] == t) {
      d[i] = d[--s.size];
      return;
    }
}

void FanMeshState::init(const TriangleMesh& mesh) {
  const size_t n = mesh.positions.size();
  corners_ = mesh.triangles;
  alive_.assign(corners_.size(), 1);
  present_.assign(n, 0);
  mark_.assign(n, 0);
  stamp_ = 0;
  std::vector<uint32_t> degree(n, 0);
  for (const Triangle& t : corners_)
    for (uint32_t v : t)
      ++degree[v];
  incident_.init(n, degree);
  for (uint32_t t = 0; t < corners_.size(); ++t)
    for (uint32_t v : corners_[t])
      incident_.push_back(v, t);
  present_count_ = 0;
  for (size_t v = 0; v < n; ++v) {
    present_[v] = degree[v] > 0;
    present_count_ += present_[v];
  }
  alive_count_ = corners_.size();
}

void FanMeshState::star(uint32_t v, std::vector<uint32_t>* out) const {
  const TriangleList list = incident_[v];
  out->assign(list.begin(), list.end());
}

void FanMeshState::collapse(uint32_t c, uint32_t v, const uint32_t* removed, size_t removed_count,
                            const uint32_t* modified, size_t modified_count) {
  for (size_t i = 0; i < removed_count; ++i) {
    const uint32_t t = removed[i];
    alive_[t] = 0;
    for (uint32_t x : corners_[t])
      incident_.remove(x, t);
  }
  alive_count_ -= removed_count;
  for (size_t i = 0; i < modified_count; ++i) {
    const uint32_t t = modified[i];
    for (uint32_t& x : corners_[t])
      if (x == c) x = v;
    incident_.remove(c, t);
    incident_.push_back(v, t);
  }
  present_[c] = 0;
  --present_count_;
}

void FanMeshState::split(uint32_t c, uint32_t v, const uint32_t* removed, size_t removed_count,
                         const uint32_t* modified, size_t modified_count) {
  present_[c] = 1;
  ++present_count_;
  for (size_t i = 0; i < modified_count; ++i) {
    const uint32_t t = modified[i];
    for (uint32_t& x : corners_[t])
      if (x == v) x = c;
    incident_.remove(v, t);
    incident_.push_back(c, t);
  }
  for (size_t i = 0; i < removed_count; ++i) {
    const uint32_t t = removed[i];
    alive_[t] = 1;
    for (uint32_t x : corners_[t])
      incident_.push_back(x, t);
  }
  alive_count_ += removed_count;
}

void FanMeshState::collect_changed(uint32_t c, uint32_t v, const uint32_t* removed,
                                   size_t removed_count, const uint32_t* modified,
                                   size_t modified_count, std::vector<uint32_t>* out) {
  if (++stamp_ == 0) {
    std::fill(mark_.begin(), mark_.end(), 0);
    stamp_ = 1;
  }
  // v's neighbours through triangles that do not hold c (those are the
  // removed ones, whose corners are all collected anyway).
  for (uint32_t t : incident_[v])
    for (uint32_t x : corners_[t])
      mark_[x] = stamp_;
  out->push_back(v);
  out->push_back(c);
  for (size_t i = 0; i < removed_count; ++i)
    for (uint32_t x : corners_[removed[i]])
      if (x != c && x != v) out->push_back(x);
  for (size_t i = 0; i < modified_count; ++i)
    for (uint32_t x : corners_[modified[i]])
      if (x != c && x != v && mark_[x] == stamp_) out->push_back(x);
}

bool FanMeshState::stars_valid(const std::vector<uint32_t>& vertices) {
  constexpr uint32_t kNone = 0xffffffffu;
  // Members, not locals: this runs for every collapse of every fine path.
  std::vector<uint32_t>& next = next_;
  std::vector<uint32_t>& prev = prev_;
  std::vector<uint32_t>& successor = successor_;
  for (uint32_t v : vertices) {
    const TriangleList star = incident_[v];
    if (!present_[v]) {
      if (!star.empty()) return false;
      continue;
    }
    const size_t k = star.size();
    if (k == 0) return false;
    next.resize(k);
    prev.resize(k);
    for (size_t i = 0; i < k; ++i) {
      const Triangle& t = corners_[star[i]];
      const int at = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
      next[i] = t[(at + 1) % 3];
      prev[i] = t[(at + 2) % 3];
    }
    // Face i is followed (turning around v) by the face whose next is i's prev.
    successor.assign(k, kNone);
    size_t chain_starts = 0;
    size_t start = 0;
    for (size_t i = 0; i < k; ++i) {
      bool has_pred = false;
      for (size_t j = 0; j < k; ++j) {
        if (j == i) continue;
        if (next[j] == next[i] || prev[j] == prev[i]) return false;
        if (next[j] == prev[i] && prev[j] == next[i]) return false;  // same three vertices
        if (next[j] == prev[i]) successor[i] = static_cast<uint32_t>(j);
        if (prev[j] == next[i]) has_pred = true;
      }
      if (!has_pred) {
        ++chain_starts;
        start = i;
      }
    }
    if (chain_starts > 1) return false;
    size_t walked = 1;
    for (uint32_t j = successor[start]; j != kNone && j != start; j = successor[j])
      if (++walked > k) return false;
    if (walked != k) return false;
  }
  return true;
}

std::vector<Triangle> FanMeshState::alive_triangles() const {
  std::vector<Triangle> out;
  out.reserve(alive_count_);
  for (size_t t = 0; t < corners_.size(); ++t)
    if (alive_[t]) out.push_back(corners_[t]);
  return out;
}

}  // namespace fan_internal
}  // namespace lodbake
