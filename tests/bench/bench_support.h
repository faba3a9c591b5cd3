// Timing helpers shared by the benchmarks: wall time since a start point,
// process CPU time, and the median of repeated runs (the upper middle run for
// an even count, so that the figure is always one measured run); and running
// a peer's command-line tool (OpenMesh's mkbalancedpm and VDPM analyzer) as a
// timed subprocess.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <string>
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

/// True when `path` names a program this process may run (a peer tool the
/// benchmark runs when its Debian package is installed).
inline bool tool_installed(const std::string& path) {
  return ::access(path.c_str(), X_OK) == 0;
}

/// One word quoted for /bin/sh.
inline std::string shell_quoted(const std::string& word) {
  std::string quoted = "'";
  for (char c : word)
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// What run_tool() measured.
struct ToolRun {
  int exit_status = -1;     ///< of the first failing run, else 0; -1 when it could not start
  double wall_seconds = 0;  ///< median over the runs
  double cpu_seconds = 0;   ///< median child CPU (user + system) over the runs
};

/// Runs `argv` (program first) through /bin/sh `runs` times with stdout and
/// stderr to `log`, stopping at the first run that fails. The CPU time is
/// the waited-for children's usage, robust when other work shares the cores.
inline ToolRun run_tool(const std::vector<std::string>& argv, const std::string& log,
                        int runs = 1) {
  std::string command;
  for (const std::string& word : argv)
    command += (command.empty() ? "" : " ") + shell_quoted(word);
  command += " > " + shell_quoted(log) + " 2>&1";
  ToolRun run;
  std::vector<double> times, cpu;
  for (int r = 0; r < runs; ++r) {
    const Clock::time_point start = Clock::now();
    const double cpu_start = cpu_seconds(RUSAGE_CHILDREN);
    const int status = std::system(command.c_str());
    times.push_back(seconds_since(start));
    cpu.push_back(cpu_seconds(RUSAGE_CHILDREN) - cpu_start);
    if (status != 0) {
      run.exit_status = status == -1 ? -1 : WIFEXITED(status) ? WEXITSTATUS(status) : 128;
      return run;
    }
  }
  run.exit_status = 0;
  run.wall_seconds = median(std::move(times));
  run.cpu_seconds = median(std::move(cpu));
  return run;
}

}  // namespace lodbake::bench
