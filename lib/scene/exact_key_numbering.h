// Internal to lib/scene: numbering keys of up to 16 bytes in first-seen
// order by exact equality, what welding by exact position needs (the
// scene's shared points, weld_mesh_points(), and the merged mesh's
// vertices, weld_vertices()). Every import runs it over every vertex, so it
// is an open-addressed table of 32-bit numbers sized once (at most half
// full), the keys kept apart by number: the small table stays in cache and
// a key is read only when its slot is taken (docs/lab/weld-points.md).
// Numbers follow first-seen order, so they do not depend on the hash.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lodbake {

struct ExactKey {
  uint64_t lo = 0, hi = 0;  // the key's bytes, zero-padded to 16
  uint32_t tag = 0;         // anything else that must match (a type)
  bool operator==(const ExactKey& o) const { return lo == o.lo && hi == o.hi && tag == o.tag; }
};

class ExactKeyNumbering {
 public:
  // Room for `keys` distinct keys without growing.
  explicit ExactKeyNumbering(uint64_t keys);

  // The number of an equal key seen before, else the next number (0, 1, ...).
  uint32_t number(const ExactKey& key);

  // How many distinct keys have been numbered.
  uint32_t size() const { return static_cast<uint32_t>(keys_.size()); }

 private:
  void grow();

  std::vector<uint32_t> table_;  // numbers by hash; kEmpty where free
  std::vector<ExactKey> keys_;   // keys by number
  size_t mask_ = 0;
};

}  // namespace lodbake
