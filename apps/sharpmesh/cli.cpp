#include "cli.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <mutex>

#include "sharpmesh/errors.h"
#include "sharpmesh/io.h"
#include "sharpmesh/las.h"
#include "sharpmesh/timing.h"

namespace sharpmesh::cli {

void add_classes_option(CLI::App& app, std::vector<int>& classes) {
  app.add_option("--classes", classes, "LAS/LAZ input: keep the points of these ASPRS classes only (e.g. 2,6: ground and buildings)")
      ->delimiter(',')->check(CLI::Range(0, 255));
}

void add_mesh_output_flags(CLI::App& app, bool& allow_invalid, bool& ascii) {
  app.add_flag("--allow-invalid", allow_invalid,
               "Write the mesh even if facets still cross others after the repair (by default nothing is written and "
               "the exit status is 1)");
  app.add_flag("--ascii", ascii, "Write ASCII PLY instead of binary");
}

PointSet read_cloud(const std::string& path, const std::vector<int>& classes) {
  if (classes.empty()) return read_point_set(path);
  if (!is_las_path(path)) throw InvalidArgument("--classes needs a .las or .laz input (" + path + " has no classes)");
  PointSet points = read_las_points(path, classes);
  if (points.empty()) throw InvalidInput(path + ": no point has any of the classes given with --classes");
  return points;
}

void CommonOptions::add_to(CLI::App& app, bool with_report) {
  app.add_option("--threads", threads, "Worker threads (0: all cores)")->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_flag("-q,--quiet", quiet, "No progress or summary on stderr/stdout");
  if (with_report) app.add_option("--report", report, "Write a JSON report (parameters, counts, timings, peak memory)");
}

struct ProgressPrinter::State {
  std::mutex mutex;
  bool quiet = false;
  bool tty = false;
  std::string stage;
  int last_percent = -1;
  std::chrono::steady_clock::time_point stage_start;
  bool line_open = false;
};

ProgressPrinter::ProgressPrinter(bool quiet) : state_(std::make_shared<State>()) {
  state_->quiet = quiet;
  state_->tty = ::isatty(STDERR_FILENO);
}

ProgressPrinter::~ProgressPrinter() {
  std::lock_guard<std::mutex> lock(state_->mutex);
  if (state_->line_open) std::fputc('\n', stderr);
}

void ProgressPrinter::message(const std::string& text) {
  if (state_->quiet) return;
  std::lock_guard<std::mutex> lock(state_->mutex);
  if (state_->line_open) {
    std::fputc('\n', stderr);
    state_->line_open = false;
  }
  std::fprintf(stderr, "%s\n", text.c_str());
}

Progress ProgressPrinter::callback() {
  auto state = state_;
  return [state](const std::string& stage, double fraction) {
    if (state->quiet) return true;
    std::lock_guard<std::mutex> lock(state->mutex);
    const auto now = std::chrono::steady_clock::now();
    if (stage != state->stage) {
      if (state->line_open) std::fputc('\n', stderr);
      state->stage = stage;
      state->stage_start = now;
      state->last_percent = -1;
      state->line_open = false;
      if (!state->tty) std::fprintf(stderr, "  %s ...\n", stage.c_str());
    }
    const int percent = static_cast<int>(fraction * 100);
    if (state->tty && percent != state->last_percent) {
      std::fprintf(stderr, "\r  %-28s %3d%%", stage.c_str(), percent);
      std::fflush(stderr);
      state->line_open = true;
    }
    state->last_percent = percent;
    return true;
  };
}

nlohmann::json stages_json(const std::vector<StageTiming>& stages) {
  nlohmann::json out = nlohmann::json::array();
  for (const StageTiming& s : stages)
    out.push_back({{"name", s.name}, {"seconds", s.seconds}, {"peak_memory_mib", s.peak_rss_bytes / (1024.0 * 1024.0)}});
  return out;
}

void write_report(const std::string& path, const nlohmann::json& report) {
  if (path.empty()) return;
  nlohmann::json with_peak = report;
  if (with_peak.is_object()) with_peak["peak_memory_mib"] = peak_rss_bytes() / (1024.0 * 1024.0);  // the process's, as the kernel counts it
  write_text_file(path, with_peak.dump(2) + "\n");
}

nlohmann::json length_json(double value, double diagonal) {
  return {{"value", value}, {"fraction_of_diagonal", diagonal > 0 ? value / diagonal : 0.0}};
}

void check_output(const std::string& path, const char* kind) {
  if (path.empty()) return;
  check_writable(path);
  if (std::string(kind) == "mesh" && !is_mesh_output(path))
    throw InvalidArgument("cannot write a mesh to '" + path + "': use .ply, .off or .obj");
  if (std::string(kind) == "points" && !is_point_set_output(path))
    throw InvalidArgument("cannot write points to '" + path + "': use .ply or .xyz");
}

double seconds_since(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace sharpmesh::cli
