// Timing helpers shared by the benchmarks: wall time since a start point,
// process CPU time, and the median of repeated runs (the upper middle run for
// an even count, so that the figure is always one measured run).
#pragma once

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <vector>

namespace lodbake::bench {

using Clock = std::chrono::steady_clock;

/// Wall seconds from `start` to now.
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// CPU seconds (user + system) of this process (RUSAGE_SELF) or of its
/// waited-for children (RUSAGE_CHILDREN).
inline double cpu_seconds(int who) {
  rusage usage{};
  getrusage(who, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

/// The middle value of `v` (the upper one of the two for an even count); 0 when empty.
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

/// The median wall seconds of `runs` calls of `body`.
inline double median_seconds(int runs, const std::function<void()>& body) {
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    const Clock::time_point start = Clock::now();
    body();
    times.push_back(seconds_since(start));
  }
  return median(std::move(times));
}

}  // namespace lodbake::bench
