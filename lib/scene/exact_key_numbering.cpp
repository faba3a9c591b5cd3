#include "lib/scene/exact_key_numbering.h"

namespace lodbake {
namespace {

constexpr uint32_t kEmpty = UINT32_MAX;

uint64_t mix(uint64_t h) {
  // MurmurHash3's 64-bit finalizer.
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ull;
  h ^= h >> 33;
  return h;
}

size_t slot_of(const ExactKey& key, size_t mask) {
  return mix(key.lo ^ mix(key.hi ^ (uint64_t{key.tag} << 32))) & mask;
}

}  // namespace

ExactKeyNumbering::ExactKeyNumbering(uint64_t keys) {
  size_t capacity = 16;
  while (capacity < 2 * keys)
    capacity *= 2;
  table_.assign(capacity, kEmpty);
  mask_ = capacity - 1;
  keys_.reserve(static_cast<size_t>(keys));
}

void ExactKeyNumbering::grow() {
  table_.assign(table_.size() * 2, kEmpty);
  mask_ = table_.size() - 1;
  for (uint32_t n = 0; n < keys_.size(); ++n) {
    size_t i = slot_of(keys_[n], mask_);
    while (table_[i] != kEmpty)
      i = (i + 1) & mask_;
    table_[i] = n;
  }
}

uint32_t ExactKeyNumbering::number(const ExactKey& key) {
  size_t i = slot_of(key, mask_);
  while (table_[i] != kEmpty && !(keys_[table_[i]] == key))
    i = (i + 1) & mask_;
  if (table_[i] != kEmpty) return table_[i];
  // A caller that under-counted still gets a table at most half full.
  if (2 * (keys_.size() + 1) > table_.size()) {
    grow();
    return number(key);
  }
  table_[i] = static_cast<uint32_t>(keys_.size());
  keys_.push_back(key);
  return table_[i];
}

}  // namespace lodbake
