#include "lib/simplify/two_way_split.h"

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
    finished_ = false;
    worker_error_ = nullptr;
  }
  wake_.notify_one();
  std::exception_ptr own_error;
  try {
    part(0);
  } catch (...) {
    own_error = std::current_exception();
  }
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return finished_; });
  if (own_error) std::rethrow_exception(own_error);
  if (worker_error_) std::rethrow_exception(worker_error_);
}

void TwoWaySplit::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || job_ != nullptr; });
    if (stop_) return;
    const std::function<void(int)>* job = job_;
    lock.unlock();
    std::exception_ptr error;
    try {
      (*job)(1);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    job_ = nullptr;
    worker_error_ = error;
    finished_ = true;
    done_.notify_one();
  }
}

}  // namespace simplify_internal
}  // namespace lodbake
