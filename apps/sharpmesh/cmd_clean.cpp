// sharpmesh clean CLOUD -o OUT: the toolbox of the thesis's Appendix A, in
// the order of its pipeline (Fig. A.2): outliers, simplification, smoothing,
// normal estimation, normal orientation.
#include <optional>

#include "cli.h"
#include "sharpmesh/io.h"
#include "sharpmesh/pointset.h"
#include "sharpmesh/timing.h"

namespace sharpmesh::cli {

namespace {

/// The flags of `clean`, as given.
struct Options {
  std::string input, output;
  std::vector<int> classes;
  double outlier_percentage = -1;
  int outlier_k = 24;
  double outlier_sigmas = -1;
  int sigma_k = 150;
  bool sigma_relative = false;
  std::optional<double> grid_cell;  ///< multiples of the average spacing
  double random_percentage = -1;
  int smooth_k = 0;
  std::string normals;
  int normal_k = 18;
  bool orient = false;
  int orient_k = 18;
  std::string orient_method = "tangent";
  bool no_winding_repair = false;
  std::uint64_t seed = 0;
  bool ascii = false;
};

void run_clean(const Options& o, const CommonOptions& common) {
  check_output(o.output, "points");
  check_output(common.report, "report");
  CleanOptions options;
  if (o.outlier_percentage >= 0) options.outliers = PercentageOutlierOptions{o.outlier_k, o.outlier_percentage};
  if (o.outlier_sigmas != -1) options.outliers_sigma = SigmaOutlierOptions{o.sigma_k, o.outlier_sigmas, o.sigma_relative};
  options.grid_cell = o.grid_cell;
  if (o.random_percentage >= 0) options.random_percentage = o.random_percentage;
  options.seed = o.seed;
  if (o.smooth_k != 0) options.smoothing = JetSmoothingOptions{o.smooth_k};
  if (!o.normals.empty())
    options.normals = NormalEstimationOptions{o.normals == "pca" ? NormalMethod::Pca : NormalMethod::Jet, o.normal_k};
  if (o.normals == "shifted") options.crease_aware_normals = ShiftedNormalOptions{};
  if (o.orient)
    options.orientation = o.orient_method == "cgal" ? CleanOptions::Orientation::CgalMst : CleanOptions::Orientation::TangentMst;
  options.orient_k = o.orient_k;
  options.repair_enclosed = !o.no_winding_repair;
  options.check();
  ProgressPrinter printer(common.quiet);
  std::vector<StageTiming> stages;
  PointSet points;
  {
    StageTimer stage(stages, "read");
    points = read_cloud(o.input, o.classes);
  }
  check_point_set(points, 1, o.input.c_str());
  CleanStats stats;
  try {
    stats = clean_point_set(points, options, printer.callback());
  } catch (const InvalidInput& e) {
    throw InvalidInput(o.input + ": " + e.what());
  }
  stages.insert(stages.end(), stats.stages.begin(), stats.stages.end());
  nlohmann::json counts = {{"input", stats.input}, {"output", stats.output}};
  if (options.outliers) counts["removed_outliers"] = stats.removed_outliers;
  if (options.outliers_sigma) counts["removed_outliers_sigma"] = stats.removed_outliers_sigma;
  if (options.grid_cell) counts["removed_grid"] = stats.removed_grid;
  if (options.random_percentage) counts["removed_random"] = stats.removed_random;
  if (options.orientation == CleanOptions::Orientation::CgalMst) counts["unoriented_removed"] = stats.unoriented_removed;
  if (options.orientation == CleanOptions::Orientation::TangentMst) counts["orientation_components"] = stats.orientation_components;
  if (options.orientation == CleanOptions::Orientation::TangentMst && options.repair_enclosed) counts["enclosed_flipped_normals"] = stats.enclosed_flipped;
  {
    StageTimer stage(stages, "write");
    write_point_set(o.output, points, o.ascii ? PlyFormat::Ascii : PlyFormat::Binary);
  }
  if (!common.quiet) printer.message("clean: " + std::to_string(stats.input) + " -> " +
                                      std::to_string(points.size()) + " points, written to " + o.output);
  write_report(common.report, {{"command", "clean"},
                                {"input", o.input},
                                {"output", o.output},
                                {"parameters",
                                 {{"outliers", o.outlier_percentage}, {"outlier_k", o.outlier_k},
                                  {"outliers_sigma", o.outlier_sigmas}, {"sigma_k", o.sigma_k}, {"sigma_relative", o.sigma_relative},
                                  {"grid_cell_in_average_spacings", o.grid_cell ? nlohmann::json(*o.grid_cell) : nlohmann::json()}, {"random", o.random_percentage},
                                  {"seed", o.seed}, {"smooth_k", o.smooth_k}, {"normals", o.normals},
                                  {"normal_k", o.normal_k}, {"orient", o.orient}, {"orient_k", o.orient_k}, {"orient_method", o.orient_method}}},
                                {"counts", counts},
                                {"stages", stages_json(stages)}});
}

}  // namespace

Command add_clean(CLI::App& app) {
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("clean", "Point-set toolbox (thesis App. A): outliers, simplification, smoothing, normals");
  sub->add_option("CLOUD", o->input, "Input point cloud (.ply, .xyz, .pwn, .off, .las, .laz)")->required();
  add_classes_option(*sub, o->classes);
  sub->add_option("-o,--output", o->output, "Output point cloud (.ply binary, or .xyz)")->required();
  auto g1 = "1. Outlier removal";
  sub->add_option("--outliers", o->outlier_percentage, "Remove this % of points with the largest average squared kNN distance (App. A.4; e.g. 5)")
      ->check(CLI::Range(0.0, 100.0))->group(g1);
  sub->add_option("--outlier-k", o->outlier_k, "Neighbours for --outliers")->check(CLI::PositiveNumber)->capture_default_str()->group(g1);
  sub->add_option("--outliers-sigma", o->outlier_sigmas, "Remove points whose average squared kNN distance exceeds mean + S standard deviations (6.3.1: 3)")
      ->group(g1);
  sub->add_flag("--sigma-relative", o->sigma_relative,
               "Beyond the thesis: score each point's kNN distance against its neighbours' (median), so regions that are only "
               "sparser are kept")->group(g1);
  sub->add_option("--sigma-k", o->sigma_k, "Neighbours for --outliers-sigma (6.3.1: 150)")->check(CLI::PositiveNumber)->capture_default_str()->group(g1);
  auto g2 = "2. Simplification";
  sub->add_option("--grid", o->grid_cell, "Keep one point per grid cell of this size, in multiples of the average spacing (App. A.5)")->group(g2);
  sub->add_option("--random", o->random_percentage, "Remove this % of the points at random (App. A.5)")->check(CLI::Range(0.0, 100.0))->group(g2);
  sub->add_option("--seed", o->seed, "Seed of --random")->capture_default_str()->group(g2);
  auto g3 = "3. Smoothing";
  sub->add_option("--smooth", o->smooth_k, "Jet smoothing over K nearest neighbours (App. A.6; 24 for real scans)")->group(g3);
  auto g4 = "4. Normals";
  sub->add_option("--normals", o->normals,
                  "Estimate normals: pca or jet (App. A.7), or shifted: jet normals (oriented if --orient), then replaced by the "
                  "best-fitting 10-point plane among those of the 18 nearest points, which does not straddle creases (clean or nearly clean clouds)")
      ->check(CLI::IsMember({"pca", "jet", "shifted"}))->group(g4);
  sub->add_option("--normal-k", o->normal_k, "Neighbours for --normals")->capture_default_str()->group(g4);
  sub->add_flag("--orient", o->orient, "Orient normals by minimum spanning tree (App. A.8); unorientable points are removed")->group(g4);
  sub->add_option("--orient-k", o->orient_k, "Neighbours for --orient")->capture_default_str()->group(g4);
  sub->add_option("--orient-method", o->orient_method,
                  "tangent: MST whose weights also penalise leaving the tangent planes (no flips across thin walls); "
                  "cgal: CGAL's mst_orient_normals (weights 1 - |ni.nj|)")
      ->check(CLI::IsMember({"tangent", "cgal"}))->capture_default_str()->group(g4);
  sub->add_flag("--no-winding-repair", o->no_winding_repair,
                "With --orient-method tangent: keep the regions whose outer side the rest of the cloud encloses (by its generalized "
                "winding number; by default they are flipped)")
      ->group(g4);
  sub->add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
  common->add_to(*sub);

  auto run = [o, common] { run_clean(*o, *common); };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
