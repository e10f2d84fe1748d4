// Shared pieces of the command-line program: common flags, progress display,
// JSON reports, and the registry of subcommands. The library never prints;
// only this layer does (DESIGN.md, "Geogram").
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sharpmesh/errors.h"
#include "sharpmesh/progress.h"
#include "sharpmesh/reconstruct.h"

namespace sharpmesh::cli {

/// Flags every command has: --threads, --quiet, --report.
struct CommonOptions {
  int threads = 0;
  bool quiet = false;
  std::string report;
  void add_to(CLI::App& app, bool with_report = true);
};

/// A subcommand: its parser and the action to run once parsing succeeded.
struct Command {
  CLI::App* app = nullptr;
  std::function<void()> run;
  std::shared_ptr<CommonOptions> common;
};

/// `--classes 2,6`: the LAS classes of a LAS/LAZ input to keep (ground and
/// buildings, say); real LiDAR needs vegetation and noise left out.
void add_classes_option(CLI::App& app, std::vector<int>& classes);
/// `--allow-invalid` and `--ascii` of the commands that write a mesh checked
/// for crossing facets.
void add_mesh_output_flags(CLI::App& app, bool& allow_invalid, bool& ascii);
/// Reads the input cloud, keeping `classes` only when given (LAS/LAZ only).
PointSet read_cloud(const std::string& path, const std::vector<int>& classes);

Command add_info(CLI::App& app);
Command add_clean(CLI::App& app);
Command add_sample(CLI::App& app);
Command add_eval(CLI::App& app);
Command add_reconstruct(CLI::App& app);
Command add_features(CLI::App& app);
Command add_eval_features(CLI::App& app);
Command add_make_scene(CLI::App& app);
Command add_eval_stereo(CLI::App& app);
Command add_stereo(CLI::App& app);
Command add_view(CLI::App& app);
Command add_render(CLI::App& app);
Command add_decimate(CLI::App& app);


/// Progress on stderr: a live percentage on a terminal, one line per stage otherwise.
class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool quiet);
  ~ProgressPrinter();
  Progress callback();
  void message(const std::string& text);

 private:
  struct State;
  std::shared_ptr<State> state_;
};

/// Adds the stages to a report: name, seconds, peak memory in MiB.
nlohmann::json stages_json(const std::vector<StageTiming>& stages);
/// Writes the report atomically if a path was given.
void write_report(const std::string& path, const nlohmann::json& report);
/// A length in data units and as a fraction of the diagonal.
nlohmann::json length_json(double value, double diagonal);

/// Fails (exit 2) before any work when an output cannot be written.
void check_output(const std::string& path, const char* kind);

double seconds_since(const std::chrono::steady_clock::time_point& start);

}  // namespace sharpmesh::cli
