#include "lib/simplify/two_way_split.h"

#include <chrono>
#include <system_error>

namespace lodbake {
namespace simplify_internal {

TwoWaySplit::TwoWaySplit(unsigned threads) {
  if (threads == 0) threads = std::thread::hardware_concurrency();
  parallel_ = threads >= 2;
  // A machine without threads (or a container that forbids them) still
  // simplifies, on one.
  if (parallel_) {
    try {
      worker_ = std::thread([this] { work(); });
    } catch (const std::system_error&) {
      parallel_ = false;
    }
  }
}

TwoWaySplit::~TwoWaySplit() {
  if (!worker_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    pending_.store(true, std::memory_order_release);
  }
  wake_.notify_one();
  worker_.join();
}

void TwoWaySplit::run(const std::function<void(int)>& part, bool worth_it) {
  if (!parallel_ || !worth_it) {
    part(0);
    part(1);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = &part;
    pending_.store(true, std::memory_order_release);
    worker_error_ = nullptr;
    finished_.store(false, std::memory_order_relaxed);
  }
  wake_.notify_one();
  std::exception_ptr own_error;
  try {
    part(0);
  } catch (...) {
    own_error = std::current_exception();
  }
  // The caller waits awake: woken from a sleep by the worker, it would be
  // moved to the worker's CPU, and the next job's parts would share it. The
  // parts are about equal, so the wait is short; yielding lets another job
  // of the machine run meanwhile.
  while (!finished_.load(std::memory_order_acquire))
    std::this_thread::yield();
  if (own_error) std::rethrow_exception(own_error);
  if (worker_error_) std::rethrow_exception(worker_error_);
}

void TwoWaySplit::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (job_ == nullptr && !stop_) {
      // Stay awake a while for the next job: waking an idle CPU costs up
      // to milliseconds on a virtual machine, more than a part takes.
      lock.unlock();
      const auto until = std::chrono::steady_clock::now() + kStayAwake;
      // Yielding between checks gives the CPU to the caller or another job
      // whenever they share it.
      while (!pending_.load(std::memory_order_acquire) &&
             std::chrono::steady_clock::now() < until) {
        std::this_thread::yield();
      }
      lock.lock();
    }
    wake_.wait(lock, [this] { return stop_ || job_ != nullptr; });
    if (stop_) return;
    const std::function<void(int)>* job = job_;
    job_ = nullptr;
    pending_.store(false, std::memory_order_relaxed);
    lock.unlock();
    std::exception_ptr error;
    try {
      (*job)(1);
    } catch (...) {
      error = std::current_exception();
    }
    worker_error_ = error;
    finished_.store(true, std::memory_order_release);
    lock.lock();
  }
}

}  // namespace simplify_internal
}  // namespace lodbake
