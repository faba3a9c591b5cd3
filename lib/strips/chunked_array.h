// An append-only array in fixed-size chunks, for the SETS builder's large
// record arrays (nodes, arcs, successors). A std::vector doubles its block:
// up to half of it is unused capacity, and while it grows the old and the
// new blocks are both held, so a vector of N bytes can peak at 3N/2 to 3N.
// Chunks are never moved: the slack is under one chunk and growing copies
// nothing. Indexing costs one more load (the chunk table, small and hot).
// Internal to lib/strips.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace lodbake {
namespace strips_internal {

template <typename T>
class ChunkedArray {
 public:
  static constexpr size_t kShift = 14;  // 16,384 elements a chunk
  static constexpr size_t kChunk = size_t{1} << kShift;
  static constexpr size_t kMask = kChunk - 1;

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T& operator[](size_t i) { return chunks_[i >> kShift][i & kMask]; }
  const T& operator[](size_t i) const { return chunks_[i >> kShift][i & kMask]; }
  T& back() { return (*this)[size_ - 1]; }
  void push_back(const T& value) {
    if ((size_ & kMask) == 0 && (size_ >> kShift) == chunks_.size())
      chunks_.push_back(std::unique_ptr<T[]>(new T[kChunk]));
    (*this)[size_++] = value;
  }
  /// Frees every chunk.
  void release() {
    std::vector<std::unique_ptr<T[]>>().swap(chunks_);
    size_ = 0;
  }

 private:
  std::vector<std::unique_ptr<T[]>> chunks_;
  size_t size_ = 0;
};

}  // namespace strips_internal
}  // namespace lodbake
