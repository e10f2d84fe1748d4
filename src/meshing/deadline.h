// A deadline for a CGAL stage that takes a stop flag but no time limit
// (Mesh_3's feature protection): the flag is raised when the time is up,
// by a watchdog thread (for loops that call none of our code) and by
// expired(), which callbacks inside the stage can poll (so that a limit
// already past stops the stage at its first callback, whatever the thread
// scheduling).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace sharpmesh::detail {

class Deadline {
 public:
  using Clock = std::chrono::steady_clock;

  /// `seconds` <= 0: no deadline.
  Deadline(std::atomic<bool>& stop, double seconds) : stop_(stop), limited_(seconds > 0) {
    if (!limited_) return;
    end_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    watchdog_ = std::thread([this] {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!finished_.wait_until(lock, end_, [this] { return done_; })) stop_.store(true, std::memory_order_release);
    });
  }
  Deadline(const Deadline&) = delete;
  Deadline& operator=(const Deadline&) = delete;
  ~Deadline() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    finished_.notify_all();
    if (watchdog_.joinable()) watchdog_.join();
  }

  /// Raises the flag when the time is up; true once it is raised.
  bool expired() const {
    if (limited_ && Clock::now() >= end_) stop_.store(true, std::memory_order_release);
    return stop_.load(std::memory_order_acquire);
  }

 private:
  std::atomic<bool>& stop_;
  bool limited_;
  Clock::time_point end_{};
  std::mutex mutex_;
  std::condition_variable finished_;
  bool done_ = false;
  std::thread watchdog_;
};

}  // namespace sharpmesh::detail
