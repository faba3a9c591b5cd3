// Runs a job that is split into two parts on the calling thread and one
// persistent worker thread. The parts are always the same two, whatever the
// number of threads, so that a result built from them in part order is the
// same with one thread or two: the engine's output stays byte-identical
// across machines and thread settings.
//
// Both threads wait awake. On the 2-vCPU virtual machines this was built on,
// a sleeping thread woken by the other was placed on the waker's CPU, and
// waking an idle vCPU took up to milliseconds, longer than a part: with
// sleeping waits the two parts ran one after the other. So the caller
// waits for the worker's part by yielding, and the worker stays awake for
// kStayAwake after a part (longer than a pass's walk on the benchmark
// meshes) before it sleeps. That costs a second core's time while the
// engine runs, which is why simplify() uses one thread unless asked.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace lodbake {
namespace simplify_internal {

class TwoWaySplit {
 public:
  static constexpr std::chrono::microseconds kStayAwake{3000};

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
  const std::function<void(int)>* job_ = nullptr;  // set until the worker takes its part
  std::atomic<bool> finished_{true};               // the worker's part has returned
  std::atomic<bool> pending_{false};               // a job or the stop is waiting for the worker
  bool stop_ = false;
  std::exception_ptr worker_error_;  // written by the worker before finished_
};

}  // namespace simplify_internal
}  // namespace lodbake
