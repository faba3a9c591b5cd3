// The threads of a builder's parallel steps, on oneTBB's task scheduler.
//
// Every step splits its work into parts and writes each part's result to a
// place of its own (an index range, a region, a slot per part) that the
// caller combines in part order. Two ways keep the output the same for any
// thread count: a step whose combined result does not depend on where the
// parts are cut (an array written per index, a list concatenated in part
// order, a sum made per owned element in input order) may cut as many parts
// as there are threads (parts()); a step whose result does (a floating-point
// reduction) cuts fixed chunks whose size depends on the input alone
// (for_each_chunk(), reduce_chunks()).
//
// The parts of one call run in isolation: a thread waiting for them never
// picks up an unrelated task of the enclosing arena (another input of a
// bake), which would hold the call up until that task ended.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

namespace lodbake {

/// A half-open index range.
struct IndexRange {
  size_t begin = 0;
  size_t end = 0;
};

/// The `part`-th of `parts` near-equal consecutive pieces of [0, count).
/// \pre part < parts
IndexRange part_range(size_t count, size_t parts, size_t part);

class ParallelScope {
 public:
  /// `threads`: the threads the parts may run on; 0 runs them on the
  /// caller's task arena: every core at the top level, or inside a bake's
  /// `--jobs N` arena the N threads that arena shares among its inputs.
  /// More threads than cores cut as many parts but run them on the cores.
  explicit ParallelScope(unsigned threads = 0);
  ~ParallelScope();
  ParallelScope(const ParallelScope&) = delete;
  ParallelScope& operator=(const ParallelScope&) = delete;

  /// The thread count asked for (0: the caller's arena's), at least 1;
  /// parts() cuts by it.
  unsigned threads() const { return threads_; }

  /// How many parts to cut `count` items into: one per thread, but none
  /// smaller than `min_part` items (1 when count < 2 * min_part).
  size_t parts(size_t count, size_t min_part) const;

  /// Calls part(p) once for every p in [0, parts), on the scope's threads,
  /// and returns when all have returned. An exception of a part is
  /// rethrown here.
  void for_each_part(size_t parts, const std::function<void(size_t)>& part) const;

  /// Calls chunk(c, range) for the chunks of `chunk_size` items of
  /// [0, count), chunk c covering [c * chunk_size, (c + 1) * chunk_size)
  /// (the last one shorter): the cuts depend on `chunk_size` alone.
  /// \pre chunk_size > 0
  void for_each_chunk(size_t count, size_t chunk_size,
                      const std::function<void(size_t, IndexRange)>& chunk) const;

  /// map() over the chunks of for_each_chunk(), its results folded with
  /// combine() from `init` in chunk order: the same value for any thread
  /// count, even when combine() is not associative (floating point).
  template <typename T, typename Map, typename Combine>
  T reduce_chunks(size_t count, size_t chunk_size, T init, Map map, Combine combine) const {
    const size_t chunks = chunk_size == 0 ? 0 : (count + chunk_size - 1) / chunk_size;
    std::vector<T> partial(chunks, init);
    for_each_chunk(count, chunk_size, [&](size_t c, IndexRange range) { partial[c] = map(range); });
    T result = init;
    for (const T& value : partial)
      result = combine(result, value);
    return result;
  }

 private:
  struct Arena;  // a tbb::task_arena, kept out of this header
  unsigned threads_ = 1;
  bool single_thread_ = false;    // the parts run one after the other on the caller
  std::unique_ptr<Arena> arena_;  // null: the caller's arena
};

}  // namespace lodbake
