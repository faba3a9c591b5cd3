// The simplifier's rhythm on ParallelScope (lib/core/parallel.h): a busy
// sequential walk on the calling thread, then a step of two parts. Tells
// whether oneTBB's sleeping workers take a short step late: with both
// threads the step takes one part's time, one after the other twice that.
// Also reports the CPU time the process burns while the caller sleeps
// after a step (the workers' spinning before they sleep). The walk spins,
// as the engine's does; parts spin on the clock, so a thread taken off its
// CPU by another job shows as a longer step.
//
//   bench_parallel_wake [--threads N] [--part US] [--rounds N]
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include "lib/core/parallel.h"

namespace {

using Clock = std::chrono::steady_clock;

double cpu_ms() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) / 1e6;
}

void spin_for(int us) {
  const auto until = Clock::now() + std::chrono::microseconds(us);
  while (Clock::now() < until) {
  }
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))];
}

}  // namespace

int main(int argc, char** argv) {
  unsigned threads = 2;
  int part_us = 1000;
  int rounds = 100;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (std::strcmp(argv[i], "--threads") == 0 && has_value) {
      threads = static_cast<unsigned>(std::strtoul(argv[++i], nullptr, 10));
    } else if (std::strcmp(argv[i], "--part") == 0 && has_value) {
      part_us = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--rounds") == 0 && has_value) {
      rounds = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: bench_parallel_wake [--threads N] [--part US] [--rounds N]\n");
      return 1;
    }
  }
  if (part_us <= 0 || rounds <= 0) {
    std::fprintf(stderr, "bench_parallel_wake: --part and --rounds take counts above 0\n");
    return 1;
  }
  const lodbake::ParallelScope scope(threads);
  const size_t parts = scope.threads();
  std::printf("%u threads, %zu parts of %d us per step, %d rounds\n", scope.threads(), parts,
              part_us, rounds);
  for (int walk_us : {200, 2000, 20000}) {
    std::vector<double> step;
    const double c0 = cpu_ms();
    const auto w0 = Clock::now();
    for (int r = 0; r < rounds; ++r) {
      spin_for(walk_us);
      const auto t0 = Clock::now();
      scope.for_each_part(parts, [&](size_t) { spin_for(part_us); });
      step.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
    }
    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - w0).count();
    std::printf(
        "walk %6d us: step median %6.0f us, p90 %6.0f us (one part %d us); process CPU / wall "
        "%.2f\n",
        walk_us, percentile(step, 0.5), percentile(step, 0.9), part_us, (cpu_ms() - c0) / wall);
  }
  std::vector<double> idle;
  for (int r = 0; r < std::min(rounds, 40); ++r) {
    scope.for_each_part(parts, [&](size_t) { spin_for(part_us); });
    const double c0 = cpu_ms();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    idle.push_back(cpu_ms() - c0);
  }
  std::printf(
      "CPU burnt in the 20 ms after a step, the caller asleep: median %.2f ms, max %.2f ms\n",
      percentile(idle, 0.5), percentile(idle, 1.0));
  return 0;
}
