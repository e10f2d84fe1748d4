// sharpmesh clean CLOUD -o OUT: the toolbox of the thesis's Appendix A, in
// the order of its pipeline (Fig. A.2): outliers, simplification, smoothing,
// normal estimation, normal orientation.
#include <cmath>
#include <optional>
#include <cstdio>

#include "cli.h"
#include "sharpmesh/io.h"
#include "sharpmesh/pointset.h"
#include "sharpmesh/timing.h"

namespace sharpmesh::cli {

Command add_clean(CLI::App& app) {
  struct Options {
    std::string input, output;
    double outlier_percentage = -1;
    int outlier_k = 24;
    double outlier_sigmas = -1;
    int sigma_k = 150;
    std::optional<double> grid_cell;  ///< multiples of the average spacing
    double random_percentage = -1;
    int smooth_k = 0;
    std::string normals;
    int normal_k = 18;
    bool orient = false;
    int orient_k = 18;
    std::string orient_method = "tangent";
    std::uint64_t seed = 0;
    bool ascii = false;
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("clean", "Point-set toolbox (thesis App. A): outliers, simplification, smoothing, normals");
  sub->add_option("CLOUD", o->input, "Input point cloud (.ply, .xyz, .pwn, .off, .las)")->required();
  sub->add_option("-o,--output", o->output, "Output point cloud (.ply binary, or .xyz)")->required();
  auto g1 = "1. Outlier removal";
  sub->add_option("--outliers", o->outlier_percentage, "Remove this % of points with the largest average squared kNN distance (App. A.4; e.g. 5)")
      ->check(CLI::Range(0.0, 100.0))->group(g1);
  sub->add_option("--outlier-k", o->outlier_k, "Neighbours for --outliers")->check(CLI::PositiveNumber)->capture_default_str()->group(g1);
  sub->add_option("--outliers-sigma", o->outlier_sigmas, "Remove points whose average squared kNN distance exceeds mean + S standard deviations (6.3.1: 3)")
      ->group(g1);
  sub->add_option("--sigma-k", o->sigma_k, "Neighbours for --outliers-sigma (6.3.1: 150)")->check(CLI::PositiveNumber)->capture_default_str()->group(g1);
  auto g2 = "2. Simplification";
  sub->add_option("--grid", o->grid_cell, "Keep one point per grid cell of this size, in multiples of the average spacing (App. A.5)")->group(g2);
  sub->add_option("--random", o->random_percentage, "Remove this % of the points at random (App. A.5)")->check(CLI::Range(0.0, 100.0))->group(g2);
  sub->add_option("--seed", o->seed, "Seed of --random")->capture_default_str()->group(g2);
  auto g3 = "3. Smoothing";
  sub->add_option("--smooth", o->smooth_k, "Jet smoothing over K nearest neighbours (App. A.6; 24 for real scans)")->group(g3);
  auto g4 = "4. Normals";
  sub->add_option("--normals", o->normals, "Estimate normals: pca or jet (App. A.7)")->check(CLI::IsMember({"pca", "jet"}))->group(g4);
  sub->add_option("--normal-k", o->normal_k, "Neighbours for --normals")->capture_default_str()->group(g4);
  sub->add_flag("--orient", o->orient, "Orient normals by minimum spanning tree (App. A.8); unorientable points are removed")->group(g4);
  sub->add_option("--orient-k", o->orient_k, "Neighbours for --orient")->capture_default_str()->group(g4);
  sub->add_option("--orient-method", o->orient_method,
                  "tangent: MST whose weights also penalise leaving the tangent planes (no flips across thin walls); "
                  "cgal: CGAL's mst_orient_normals (weights 1 - |ni.nj|)")
      ->check(CLI::IsMember({"tangent", "cgal"}))->capture_default_str()->group(g4);
  sub->add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
  common->add_to(*sub);

  auto run = [o, common] {
    check_output(o->output, "points");
    check_output(common->report, "report");
    if (o->outlier_sigmas != -1 && !(o->outlier_sigmas > 0)) throw InvalidArgument("--outliers-sigma must be positive");
    if (o->grid_cell && !(*o->grid_cell > 0 && std::isfinite(*o->grid_cell))) throw InvalidArgument("--grid must be a positive multiple of the average spacing");
    if (o->smooth_k != 0 && o->smooth_k < 6) throw InvalidArgument("--smooth needs at least 6 neighbours to fit a quadric");
    ProgressPrinter printer(common->quiet);
    const Progress progress = printer.callback();
    std::vector<StageTiming> stages;
    nlohmann::json counts;
    PointSet points;
    {
      StageTimer stage(stages, "read");
      points = read_point_set(o->input);
    }
    check_point_set(points, 1, o->input.c_str());
    counts["input"] = points.size();
    if (o->outlier_percentage >= 0) {
      StageTimer stage(stages, "outliers");
      counts["removed_outliers"] = remove_outliers_percentage(points, {o->outlier_k, o->outlier_percentage}, progress);
    }
    if (o->outlier_sigmas > 0) {
      StageTimer stage(stages, "outliers-sigma");
      counts["removed_outliers_sigma"] = remove_outliers_sigma(points, {o->sigma_k, o->outlier_sigmas}, progress);
    }
    if (o->grid_cell) {
      StageTimer stage(stages, "grid simplification");
      const double spacing = average_spacing(points, 6, progress);
      counts["removed_grid"] = grid_simplify(points, *o->grid_cell * spacing);
    }
    if (o->random_percentage >= 0) {
      StageTimer stage(stages, "random simplification");
      counts["removed_random"] = random_simplify(points, o->random_percentage, o->seed);
    }
    if (o->smooth_k > 0) {
      StageTimer stage(stages, "smoothing");
      jet_smooth(points, {o->smooth_k}, progress);
    }
    if (!o->normals.empty()) {
      StageTimer stage(stages, "normals");
      estimate_normals(points, {o->normals == "pca" ? NormalMethod::Pca : NormalMethod::Jet, o->normal_k}, progress);
    }
    if (o->orient) {
      StageTimer stage(stages, "orientation");
      if (o->orient_method == "cgal") counts["unoriented_removed"] = orient_normals_mst(points, {o->orient_k, true}, progress);
      else counts["orientation_components"] = orient_normals_tangent_mst(points, o->orient_k, progress);
    }
    if (points.empty()) throw InvalidInput(o->input + ": no point left after cleaning");
    {
      StageTimer stage(stages, "write");
      write_point_set(o->output, points, o->ascii ? PlyFormat::Ascii : PlyFormat::Binary);
    }
    counts["output"] = points.size();
    if (!common->quiet) printer.message("clean: " + std::to_string(counts["input"].get<std::size_t>()) + " -> " +
                                        std::to_string(points.size()) + " points, written to " + o->output);
    write_report(common->report, {{"command", "clean"},
                                  {"input", o->input},
                                  {"output", o->output},
                                  {"parameters",
                                   {{"outliers", o->outlier_percentage}, {"outlier_k", o->outlier_k},
                                    {"outliers_sigma", o->outlier_sigmas}, {"sigma_k", o->sigma_k},
                                    {"grid_cell_in_average_spacings", o->grid_cell ? nlohmann::json(*o->grid_cell) : nlohmann::json()}, {"random", o->random_percentage},
                                    {"seed", o->seed}, {"smooth_k", o->smooth_k}, {"normals", o->normals},
                                    {"normal_k", o->normal_k}, {"orient", o->orient}, {"orient_k", o->orient_k}, {"orient_method", o->orient_method}}},
                                  {"counts", counts},
                                  {"stages", stages_json(stages)}});
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
