// A background thread that runs posted jobs one at a time, in the order they were posted (the
// pipelines: workflow::solveHexapodFkFile prints and reads on it while the caller's thread solves).
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

namespace pkm::workflow::detail {

class SerialWorker {
 public:
  SerialWorker() : thread_([this] { run(); }) {}
  /// Runs the jobs still queued, then ends the thread (an exception of theirs is dropped: call
  /// drain() to see it).
  ~SerialWorker() {
    {
      const std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  SerialWorker(const SerialWorker&) = delete;
  SerialWorker& operator=(const SerialWorker&) = delete;

  /// Queues `job` after the jobs posted before it (dropped while a failure awaits drain()).
  void post(std::function<void()> job) {
    {
      const std::lock_guard lock(mutex_);
      if (error_) return;
      jobs_.push_back(std::move(job));
    }
    wake_.notify_all();
  }

  /// Whether a job failed (drain() rethrows it).
  [[nodiscard]] bool failed() {
    const std::lock_guard lock(mutex_);
    return error_ != nullptr;
  }

  /// The worker thread (for its placement on a CPU: thread_placement.hpp).
  std::thread& thread() { return thread_; }

  /// Waits until every posted job has run; rethrows the exception a job threw (the jobs queued
  /// after it, and any posted before this call, are dropped).
  void drain() {
    std::unique_lock lock(mutex_);
    wake_.wait(lock, [this] { return (jobs_.empty() && !busy_) || error_; });
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  }

 private:
  void run() {
    std::unique_lock lock(mutex_);
    while (true) {
      wake_.wait(lock, [this] { return !jobs_.empty() || stopping_; });
      if (jobs_.empty()) return;  // stopping, nothing left
      std::function<void()> job = std::move(jobs_.front());
      jobs_.pop_front();
      busy_ = true;
      lock.unlock();
      std::exception_ptr failure;
      try {
        job();
      } catch (...) {
        failure = std::current_exception();
      }
      lock.lock();
      busy_ = false;
      if (failure) {
        error_ = failure;
        jobs_.clear();
      }
      wake_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> jobs_;
  bool busy_ = false;
  bool stopping_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: started once the members above exist
};

}  // namespace pkm::workflow::detail
