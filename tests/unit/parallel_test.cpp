// ParallelScope: every part runs once, cuts that do not depend on the
// thread count where promised, exceptions brought back to the caller.
#include "lib/core/parallel.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace lodbake {
namespace {

TEST(Parallel, PartRangesCoverTheCountInOrder) {
  for (size_t count : {0u, 1u, 7u, 100u, 1001u}) {
    for (size_t parts : {1u, 2u, 3u, 7u, 64u}) {
      size_t next = 0;
      for (size_t p = 0; p < parts; ++p) {
        const IndexRange r = part_range(count, parts, p);
        EXPECT_EQ(r.begin, next);
        EXPECT_LE(r.end - r.begin, count / parts + 1);
        next = r.end;
      }
      EXPECT_EQ(next, count);
    }
  }
}

TEST(Parallel, PartsFollowTheThreadsAndTheMinimumSize) {
  const ParallelScope seven(7);
  EXPECT_EQ(seven.threads(), 7u);
  EXPECT_EQ(seven.parts(100, 1000), 1u);
  EXPECT_EQ(seven.parts(2500, 1000), 2u);
  EXPECT_EQ(seven.parts(1000000, 1000), 7u);
  const ParallelScope one(1);
  EXPECT_EQ(one.parts(1000000, 1000), 1u);
  // 0: the caller's arena, at least one thread.
  EXPECT_GE(ParallelScope(0).threads(), 1u);
}

TEST(Parallel, EveryPartRunsOnceOnTheScopesThreads) {
  for (unsigned threads : {0u, 1u, 2u, 7u}) {
    const ParallelScope scope(threads);
    for (size_t parts : {0u, 1u, 5u, 200u}) {
      std::vector<std::atomic<int>> ran(parts);
      std::mutex mutex;
      std::set<std::thread::id> ids;
      scope.for_each_part(parts, [&](size_t p) {
        ++ran[p];
        std::lock_guard<std::mutex> lock(mutex);
        ids.insert(std::this_thread::get_id());
      });
      for (size_t p = 0; p < parts; ++p)
        EXPECT_EQ(ran[p].load(), 1) << threads << " threads, part " << p << " of " << parts;
      EXPECT_LE(ids.size(), scope.threads());
      if (threads == 1) {
        EXPECT_LE(ids.size(), 1u);
        if (parts > 0) {
          EXPECT_EQ(*ids.begin(), std::this_thread::get_id());
        }
      }
    }
  }
}

// Scope 0 inside an arena (a bake's --jobs arena) takes that arena's
// threads rather than every core: a bake with --jobs N stays at N threads.
TEST(Parallel, ScopeZeroSharesTheEnclosingArena) {
  for (int jobs : {1, 2}) {
    tbb::task_arena arena(jobs);
    arena.execute([&] {
      const ParallelScope scope(0);
      EXPECT_EQ(scope.threads(), static_cast<unsigned>(jobs));
      EXPECT_EQ(scope.parts(1000000, 10), static_cast<size_t>(jobs));
      std::mutex mutex;
      std::set<std::thread::id> ids;
      scope.for_each_part(64, [&](size_t) {
        std::lock_guard<std::mutex> lock(mutex);
        ids.insert(std::this_thread::get_id());
      });
      EXPECT_LE(ids.size(), static_cast<size_t>(jobs));
      if (jobs == 1) {
        EXPECT_EQ(ids, std::set<std::thread::id>{std::this_thread::get_id()});
      }
    });
  }
}

TEST(Parallel, ChunksDependOnTheChunkSizeAlone) {
  for (unsigned threads : {1u, 2u, 7u}) {
    const ParallelScope scope(threads);
    std::vector<IndexRange> chunks(4);
    scope.for_each_chunk(1000, 300, [&](size_t c, IndexRange r) { chunks[c] = r; });
    const size_t expected[4][2] = {{0, 300}, {300, 600}, {600, 900}, {900, 1000}};
    for (size_t c = 0; c < 4; ++c) {
      EXPECT_EQ(chunks[c].begin, expected[c][0]);
      EXPECT_EQ(chunks[c].end, expected[c][1]);
    }
  }
}

// A floating-point sum whose value depends on the order of its terms is
// the same for every thread count.
TEST(Parallel, ReduceChunksIsTheSameForEveryThreadCount) {
  std::vector<double> values(100000);
  uint64_t state = 12345;
  for (double& v : values) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    // Magnitudes from 1e-8 to 1e8: the sum's rounding depends on the order.
    v = static_cast<double>(state >> 11) * 0x1p-53 * (((state >> 3) & 1) ? 1e8 : 1e-8);
  }
  auto sum = [&](unsigned threads) {
    const ParallelScope scope(threads);
    return scope.reduce_chunks(
        values.size(), 4096, 0.0,
        [&](IndexRange r) {
          double s = 0;
          for (size_t i = r.begin; i < r.end; ++i)
            s += values[i];
          return s;
        },
        [](double a, double b) { return a + b; });
  };
  const double one = sum(1);
  EXPECT_GT(one, 0.0);
  // The terms are such that the order matters: summed one by one they
  // round differently (else this test could not fail).
  double straight = 0;
  for (double v : values)
    straight += v;
  EXPECT_NE(one, straight);
  EXPECT_EQ(one, sum(2));
  EXPECT_EQ(one, sum(7));
}

TEST(Parallel, AnExceptionOfAPartReachesTheCaller) {
  for (unsigned threads : {1u, 2u}) {
    const ParallelScope scope(threads);
    EXPECT_THROW(scope.for_each_part(8,
                                     [](size_t p) {
                                       if (p == 5) throw std::runtime_error("part 5");
                                     }),
                 std::runtime_error);
    // Still usable afterwards.
    std::atomic<int> ran{0};
    scope.for_each_part(8, [&](size_t) { ++ran; });
    EXPECT_EQ(ran.load(), 8);
  }
}

}  // namespace
}  // namespace lodbake
