// Exact-position welding with an open-addressing hash table (linear probing,
// load factor at most 1/2) that stores vertex indices only: the positions
// themselves live in first-appearance order in positions_, which is the
// order the caller sees. Keys are the coordinates' bit patterns with -0.0
// mapped to +0.0, because "exactly equal positions" means equal values and
// the two zeros compare equal.
#include "lib/meshio/position_welder.h"

#include <cstring>
#include <utility>

namespace lodbake {
namespace {

constexpr uint32_t kEmptySlot = UINT32_MAX;

uint32_t key_bits(float f) {
  if (f == 0.0f) return 0;  // +0.0 and -0.0
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof(bits));
  return bits;
}

size_t hash_position(const Vec3f& p) {
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (float f : p) {
    h ^= key_bits(f);
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
  return static_cast<size_t>(h);
}

bool same_position(const Vec3f& a, const Vec3f& b) {
  return key_bits(a[0]) == key_bits(b[0]) && key_bits(a[1]) == key_bits(b[1]) &&
         key_bits(a[2]) == key_bits(b[2]);
}

}  // namespace

PositionWelder::PositionWelder(size_t expected_corners) {
  size_t capacity = 64;
  while (capacity < expected_corners * 2)
    capacity *= 2;
  rehash(capacity);
  positions_.reserve(expected_corners);
}

size_t PositionWelder::find_slot(const Vec3f& p) const {
  size_t slot = hash_position(p) & mask_;
  while (table_[slot] != kEmptySlot && !same_position(positions_[table_[slot]], p)) {
    slot = (slot + 1) & mask_;
  }
  return slot;
}

void PositionWelder::rehash(size_t capacity) {
  table_.assign(capacity, kEmptySlot);
  mask_ = capacity - 1;
  for (uint32_t i = 0; i < positions_.size(); ++i)
    table_[find_slot(positions_[i])] = i;
}

uint32_t PositionWelder::add(const Vec3f& p) {
  size_t slot = find_slot(p);
  if (table_[slot] != kEmptySlot) {
    ++welded_;
    return table_[slot];
  }
  const auto index = static_cast<uint32_t>(positions_.size());
  positions_.push_back(p);
  table_[slot] = index;
  if (positions_.size() * 2 > table_.size()) rehash(table_.size() * 2);
  return index;
}

std::vector<Vec3f> PositionWelder::take_positions() {
  std::vector<Vec3f> out = std::move(positions_);
  positions_.clear();
  table_.assign(table_.size(), kEmptySlot);
  welded_ = 0;
  return out;
}

}  // namespace lodbake
