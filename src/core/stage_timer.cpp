#include "sharpmesh/timing.h"

#include <fstream>
#include <sstream>

namespace sharpmesh {
namespace {
void reset_peak_rss();
}  // namespace


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

namespace {
void reset_peak_rss() {
  std::ofstream clear("/proc/self/clear_refs");
  if (clear) clear << "5";  // "5" resets the peak RSS (Linux >= 4.0)
}
}  // namespace

StageTimer::StageTimer(std::vector<StageTiming>& out, std::string name)
    : out_(out), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {
  reset_peak_rss();
}

StageTimer::~StageTimer() { stop(); }

void StageTimer::stop() {
  if (stopped_) return;
  stopped_ = true;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  out_.push_back({name_, seconds, peak_rss_bytes()});
}

}  // namespace sharpmesh
