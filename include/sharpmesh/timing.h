// Wall time and peak resident memory per pipeline stage (a Geogram-style
// stopwatch). The kernel's high-water mark of the process is never reset, so
// `/usr/bin/time -v`, getrusage and a benchmark's peak memory stay true; a
// stage's own peak is that mark when the stage raised it, otherwise the
// highest resident size a sampler saw during the stage.
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace sharpmesh {

struct StageTiming {
  std::string name;
  double seconds = 0;
  std::size_t peak_rss_bytes = 0;  ///< peak resident memory during the stage
};

/// Peak resident set size of the process so far (the kernel's VmHWM), in bytes.
std::size_t peak_rss_bytes();
/// Current resident set size of the process, in bytes.
std::size_t current_rss_bytes();

/// Times a scope; appends its StageTiming to `out` when stopped or destroyed.
class StageTimer {
 public:
  StageTimer(std::vector<StageTiming>& out, std::string name);
  ~StageTimer();
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  void stop();

 private:
  class Sampler;
  std::vector<StageTiming>& out_;
  std::string name_;
  std::chrono::steady_clock::time_point start_;
  std::size_t process_peak_at_start_ = 0;
  std::unique_ptr<Sampler> sampler_;
  bool stopped_ = false;
};

}  // namespace sharpmesh
