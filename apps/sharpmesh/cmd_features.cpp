// sharpmesh features CLOUD -o OUT.polylines.txt: sharp-edge polylines and
// junctions (thesis 7.2), timed per stage as in Table 7.1.
#include <cstdio>
#include <variant>

#include "cli.h"
#include "option_flags.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/features.h"
#include "sharpmesh/io.h"
#include "sharpmesh/option_fields.h"
#include "sharpmesh/pointset.h"
#include "sharpmesh/report.h"

namespace sharpmesh::cli {

Command add_features(CLI::App& app) {
  struct Options {
    std::string input, output, edge_points;
    std::vector<int> classes;
    FeatureOptions features;
    WallOptions walls;
    bool ascii = false;
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("features", "Sharp-edge polylines and junctions of a point cloud (thesis 7.2)");
  sub->add_option("CLOUD", o->input, "Input point cloud (.ply, .xyz, .pwn, .off, .las, .laz)")->required();
  add_classes_option(*sub, o->classes);
  sub->add_option("-o,--output", o->output, "Output polylines (CGAL text format: n x1 y1 z1 ... per line)")->required();
  sub->add_option("--edge-points", o->edge_points, "Write every point with its class, edge direction and eigenvalue ratios (.ply)");
  sub->add_flag("--ascii", o->ascii, "Write --edge-points as ASCII PLY");
  add_option_fields(*sub, o->features, feature_option_fields());
  add_option_fields(*sub, o->walls, wall_option_fields());
  common->add_to(*sub);
  auto run = [o, common] {
    check_output(o->output, "polylines");
    check_output(o->edge_points, "points");
    check_output(common->report, "report");
    o->features.check();
    o->walls.check();
    const auto start = std::chrono::steady_clock::now();
    PointSet points = read_cloud(o->input, o->classes);
    ProgressPrinter printer(common->quiet);
    const WallResult walls = o->walls.mode == WallMode::Off ? WallResult{}
                             : fill_vertical_walls(points, average_spacing(points), o->walls, printer.callback());
    FeatureOptions features = o->features;
    if (o->walls.mode != WallMode::Off) features.max_offset_radius = offset_radius_bound(features, walls.airborne);
    const FeatureResult result = extract_features(points, features, printer.callback());
    write_polylines(o->output, result.graph.polylines);
    if (!o->edge_points.empty()) write_feature_points(o->edge_points, points.points, result.points, o->ascii ? PlyFormat::Ascii : PlyFormat::Binary);
    const double diagonal = bounding_box(points.points).diagonal();
    nlohmann::json report = nlohmann::json::parse(feature_report_json(result, o->features, diagonal));
    if (!common->quiet) {
      const auto& c = report["counts"];
      char line[256];
      std::snprintf(line, sizeof line, "features: %zu edge points, %zu corner points -> %zu clusters -> %zu polylines, %zu corners, %zu cusps, %zu darts",
                    c["edge_points"].get<std::size_t>(), c["corner_points"].get<std::size_t>(), c["clusters"].get<std::size_t>(),
                    c["polylines"].get<std::size_t>(), c["corners"].get<std::size_t>(), c["cusps"].get<std::size_t>(),
                    c["darts"].get<std::size_t>());
      printer.message(line);
      for (const StageTiming& s : result.stages) {
        std::snprintf(line, sizeof line, "  %-12s %8.2f s  %8.1f MiB peak", s.name.c_str(), s.seconds, s.peak_rss_bytes / 1048576.0);
        printer.message(line);
      }
    }
    report["walls"] = {{"airborne", walls.airborne}, {"filled", walls.filled}, {"upper_points", walls.upper_points},
                       {"added_points", walls.added_points}};
    for (const OptionField<WallOptions>& f : wall_option_fields())
      report["parameters"][f.name] = std::visit([](const auto& v) { return nlohmann::json(v); }, f.get(o->walls));
    report["command"] = "features";
    report["input"] = o->input;
    report["output"] = o->output;
    report["seconds"] = seconds_since(start);
    write_report(common->report, report);
  };
  return {sub, run, common};
}

Command add_eval_features(CLI::App& app) {
  struct Options {
    std::string input, reference;
    FeatureEvalOptions eval;
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("eval-features", "Recall and precision of sharp-edge polylines against a reference mesh's sharp edges");
  sub->add_option("POLYLINES", o->input, "Extracted polylines (CGAL text format)")->required();
  sub->add_option("-r,--reference", o->reference, "Reference mesh: its sharp edges are the ground truth")->required();
  sub->add_option("--sharp-angle", o->eval.sharp_angle, "Sharp-edge threshold of the reference, degrees from flat")->capture_default_str();
  sub->add_option("--tolerance", o->eval.tolerance, "Distance under which an edge counts as found, fraction of the diagonal")->capture_default_str();
  common->add_to(*sub, false);
  sub->add_option("--json,--report", common->report, "Write the evaluation as JSON");
  auto run = [o, common] {
    check_output(common->report, "report");
    const std::vector<Polyline> lines = read_polylines(o->input);
    const SurfaceMesh reference = read_mesh(o->reference);
    // Junctions of degree >= 3: the polyline ends shared by three or more polylines.
    const std::vector<Vec3> corners = polyline_corners(lines);
    const FeatureEvaluation e = evaluate_features(lines, corners, reference, o->eval);
    if (!common->quiet) {
      std::printf("recall            %.4f   (ground truth length %.6g within %.3g%% of the diagonal)\n", e.recall, e.truth_length, 100 * o->eval.tolerance);
      std::printf("precision         %.4f   (extracted length %.6g)\n", e.precision, e.extracted_length);
      std::printf("truth->extracted  mean %.4g%%  max %.4g%% of the diagonal\n", 100 * e.truth_to_extracted_mean / e.diagonal, 100 * e.truth_to_extracted_max / e.diagonal);
      std::printf("extracted->truth  mean %.4g%%  max %.4g%% of the diagonal\n", 100 * e.extracted_to_truth_mean / e.diagonal, 100 * e.extracted_to_truth_max / e.diagonal);
      std::printf("corners           %zu of %zu recalled\n", e.recalled_corners, e.truth_corners);
    }
    auto frac = [&](double v) { return v / e.diagonal; };
    write_report(common->report,
                 {{"command", "eval-features"}, {"input", o->input}, {"reference", o->reference},
                  {"parameters", {{"sharp_angle", o->eval.sharp_angle}, {"tolerance", o->eval.tolerance}}},
                  {"evaluation",
                   {{"recall", e.recall}, {"precision", e.precision}, {"truth_length", e.truth_length},
                    {"extracted_length", e.extracted_length}, {"diagonal", e.diagonal},
                    {"truth_to_extracted_mean", frac(e.truth_to_extracted_mean)}, {"truth_to_extracted_max", frac(e.truth_to_extracted_max)},
                    {"extracted_to_truth_mean", frac(e.extracted_to_truth_mean)}, {"extracted_to_truth_max", frac(e.extracted_to_truth_max)},
                    {"truth_corners", e.truth_corners}, {"recalled_corners", e.recalled_corners},
                    {"distances_unit", "fraction of the reference's bounding-box diagonal"}}}});
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
