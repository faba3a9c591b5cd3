// Union-find over 0..n-1, shared by the mesh check (components, boundary
// loops, fans around a vertex) and --repair (orientation pieces).
// Path halving and union by size; iterative, so input depth cannot overflow
// the stack. Which element ends up as a set's root is unspecified: callers
// compare roots, they do not give them a meaning.
#pragma once

#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

namespace lodbake {

class DisjointSets {
 public:
  /// n singleton sets.
  explicit DisjointSets(size_t n) { reset(n); }

  /// The root of x's set. \pre x < size.
  size_t find(size_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  /// Joins the sets of a and b; false when they were already one set.
  bool unite(size_t a, size_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
    return true;
  }

  /// Starts over with n singleton sets (reuses the storage).
  void reset(size_t n) {
    parent_.resize(n);
    size_.assign(n, 1);
    std::iota(parent_.begin(), parent_.end(), size_t{0});
  }

 private:
  std::vector<size_t> parent_;
  std::vector<size_t> size_;
};

}  // namespace lodbake
