// Runs a job that is split into two parts on the calling thread and one
// persistent worker thread. The parts are always the same two, whatever the
// number of threads, so that a result built from them in part order is the
// same with one thread or two: the engine's output stays byte-identical
// across machines and thread settings. The worker sleeps between jobs (a
// simplification alternates short parallel steps with a sequential walk,
// and a spinning worker would take a core from other jobs of a baking
// pipeline for nothing).
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace lodbake {
namespace simplify_internal {

class TwoWaySplit {
 public:
  // `threads`: 1 runs both parts on the caller; 2 or more (or 0, meaning
  // every core, when the machine has two) use the worker.
  explicit TwoWaySplit(unsigned threads);
  ~TwoWaySplit();
  TwoWaySplit(const TwoWaySplit&) = delete;
  TwoWaySplit& operator=(const TwoWaySplit&) = delete;

  bool parallel() const { return parallel_; }
  // True when run(part, worth_it) would use the worker.
  bool splits(bool worth_it) const { return parallel_ && worth_it; }

  // Calls part(0) and part(1) and returns when both have returned; part(1)
  // runs on the worker when `parallel()` and `worth_it`. An exception of
  // either part is rethrown here (the first part's when both throw).
  void run(const std::function<void(int)>& part, bool worth_it = true);

 private:
  void work();

  bool parallel_ = false;
  std::thread worker_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  const std::function<void(int)>* job_ = nullptr;  // set while the worker has a part to run
  bool finished_ = false;
  bool stop_ = false;
  std::exception_ptr worker_error_;
};

}  // namespace simplify_internal
}  // namespace lodbake
