#include "lib/core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace lodbake {

struct ParallelScope::Arena {
  explicit Arena(int threads) : arena(threads) {}
  tbb::task_arena arena;
};

IndexRange part_range(size_t count, size_t parts, size_t part) {
  // count * part fits: counts stay far below 2^64 / parts.
  return {count * part / parts, count * (part + 1) / parts};
}

ParallelScope::ParallelScope(unsigned threads) {
  if (threads == 0) {
    threads_ = static_cast<unsigned>(std::max(1, tbb::this_task_arena::max_concurrency()));
    single_thread_ = threads_ == 1;
    return;
  }
  threads_ = threads;
  // TBB's workers are at most one per core (beyond that it refuses the
  // request with a warning on stderr): more threads than cores cut more
  // parts, which run on the cores.
  const int cores = std::max(1, tbb::info::default_concurrency());
  const int arena_threads = std::min(static_cast<int>(std::min(threads, 65536u)), cores);
  if (arena_threads > 1) {
    arena_ = std::make_unique<Arena>(arena_threads);
  } else {
    single_thread_ = true;
  }
}

ParallelScope::~ParallelScope() = default;

size_t ParallelScope::parts(size_t count, size_t min_part) const {
  const size_t most = min_part == 0 ? count : count / min_part;
  return std::max<size_t>(1, std::min<size_t>(threads_, most));
}

void ParallelScope::for_each_part(size_t parts, const std::function<void(size_t)>& part) const {
  if (parts <= 1 || single_thread_) {
    for (size_t p = 0; p < parts; ++p)
      part(p);
    return;
  }
  // One task per part (simple_partitioner, grain 1): the parts are already
  // as many as the threads, or coarser chunks.
  auto run = [&] {
    tbb::this_task_arena::isolate([&] {
      tbb::parallel_for(
          tbb::blocked_range<size_t>(0, parts, 1),
          [&](const tbb::blocked_range<size_t>& range) {
            for (size_t p = range.begin(); p != range.end(); ++p)
              part(p);
          },
          tbb::simple_partitioner());
    });
  };
  if (arena_) {
    arena_->arena.execute(run);
  } else {
    run();
  }
}

void ParallelScope::for_each_chunk(size_t count, size_t chunk_size,
                                   const std::function<void(size_t, IndexRange)>& chunk) const {
  const size_t chunks = (count + chunk_size - 1) / chunk_size;
  for_each_part(chunks, [&](size_t c) {
    chunk(c, IndexRange{c * chunk_size, std::min(count, (c + 1) * chunk_size)});
  });
}

}  // namespace lodbake
