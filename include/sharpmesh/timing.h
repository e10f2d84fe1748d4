// Wall time and peak resident memory per pipeline stage (a Geogram-style
// stopwatch). Peak memory is per stage: the kernel's high-water mark is
// reset when a stage starts (Linux /proc/self/clear_refs).
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace sharpmesh {

struct StageTiming {
  std::string name;
  double seconds = 0;
  std::size_t peak_rss_bytes = 0;  ///< peak resident memory during the stage
};

/// Current peak resident set size of the process, in bytes.
std::size_t peak_rss_bytes();

/// Times a scope; appends its StageTiming to `out` when stopped or destroyed.
class StageTimer {
 public:
  StageTimer(std::vector<StageTiming>& out, std::string name);
  ~StageTimer();
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  void stop();

 private:
  std::vector<StageTiming>& out_;
  std::string name_;
  std::chrono::steady_clock::time_point start_;
  bool stopped_ = false;
};

}  // namespace sharpmesh
