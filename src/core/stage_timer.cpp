#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "sharpmesh/timing.h"

namespace sharpmesh {

std::size_t peak_rss_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) {
      std::istringstream in(line.substr(6));
      std::size_t kb = 0;
      in >> kb;
      return kb * 1024;
    }
  }
  return 0;
}

std::size_t current_rss_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

/// Reads the resident size every few milliseconds until stopped. Resetting
/// the kernel's mark per stage instead (/proc/self/clear_refs) would make the
/// process's peak, as `time -v` and benchmarks read it, the last stage's.
/// The sampler only reports: nothing the pipeline decides depends on it.
class StageTimer::Sampler {
 public:
  Sampler() : peak_(current_rss_bytes()), thread_([this] { run(); }) {}
  ~Sampler() { stop(); }
  std::size_t stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_one();
    if (thread_.joinable()) thread_.join();
    return std::max(peak_.load(), current_rss_bytes());
  }

 private:
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::milliseconds(5), [this] { return stopping_; }))
      peak_ = std::max(peak_.load(), current_rss_bytes());
  }
  std::atomic<std::size_t> peak_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
};

StageTimer::StageTimer(std::vector<StageTiming>& out, std::string name)
    : out_(out),
      name_(std::move(name)),
      start_(std::chrono::steady_clock::now()),
      process_peak_at_start_(peak_rss_bytes()),
      sampler_(std::make_unique<Sampler>()) {}

StageTimer::~StageTimer() { stop(); }

void StageTimer::stop() {
  if (stopped_) return;
  stopped_ = true;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::size_t sampled = sampler_->stop();
  // A raised high-water mark was reached during this stage, exactly.
  const std::size_t process_peak = peak_rss_bytes();
  out_.push_back({name_, seconds, process_peak > process_peak_at_start_ ? process_peak : sampled});
}

}  // namespace sharpmesh
