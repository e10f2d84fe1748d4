// sharpmesh eval-stereo MESH... --scene DIR: accuracy and completeness
// curves against a reference surface seen by calibrated cameras.
#include <cstdio>
#include <sstream>

#include "cli.h"
#include "curve_plot.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"
#include "sharpmesh/stereo_io.h"

namespace sharpmesh::cli {

Command add_eval_stereo(CLI::App& app) {
  struct Options {
    std::vector<std::string> meshes, labels;
    std::string scene, reference, cameras, json, plot, missing;
    double missing_threshold = 0.005;
    StereoEvalOptions eval;
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("eval-stereo",
                                     "Accuracy and completeness of reconstructions against a reference seen by cameras "
                                     "(cumulative error distributions, Strecha et al. 2008)");
  sub->add_option("MESH", o->meshes, "Meshes to evaluate (several methods go on one plot)")->required();
  auto* scene = sub->add_option("--scene", o->scene, "A make-scene folder (ground_truth.ply and sparse/)");
  auto* reference = sub->add_option("--reference", o->reference, "Reference mesh (instead of --scene)");
  auto* cameras = sub->add_option("--cameras", o->cameras, "Cameras: COLMAP model folder, Bundler .out or NVM (with --reference)");
  scene->excludes(reference)->excludes(cameras);
  reference->needs(cameras);
  cameras->needs(reference);
  sub->add_option("--labels", o->labels, "One label per mesh for the plot and the JSON (default: file names)")->delimiter(',');
  sub->add_option("--samples", o->eval.samples, "Samples per surface")->check(CLI::PositiveNumber)->capture_default_str();
  sub->add_option("--seed", o->eval.seed, "Random seed of the samples")->capture_default_str();
  sub->add_option("--thresholds", o->eval.thresholds, "Thresholds as fractions of the scene size (visible reference diagonal)")
      ->delimiter(',')
      ->capture_default_str();
  sub->add_option("--json", o->json, "Write the curves as JSON");
  sub->add_option("--plot", o->plot, "Write a PNG plot of the curves");
  auto* missing_option = sub->add_option("--missing", o->missing,
                  "Write the visible reference samples the mesh misses (farther than --missing-threshold) as a point cloud; one MESH only");
  sub->add_option("--missing-threshold", o->missing_threshold, "Distance beyond which a sample is missing, fraction of the scene size")
      ->check(CLI::PositiveNumber)
      ->capture_default_str()
      ->needs(missing_option);
  common->add_to(*sub);
  auto run = [o, common] {
    if (o->scene.empty() && o->reference.empty()) throw InvalidArgument("give --scene DIR, or --reference MESH with --cameras MODEL");
    if (!o->labels.empty() && o->labels.size() != o->meshes.size()) throw InvalidArgument("--labels needs one label per mesh");
    o->eval.check();
    check_output(o->json, "JSON");
    check_output(o->plot, "plot");
    check_output(o->missing, "points");
    if (!o->missing.empty() && o->meshes.size() != 1) throw InvalidArgument("--missing needs exactly one MESH");
    check_output(common->report, "report");
    const auto start = std::chrono::steady_clock::now();
    const std::string reference_path = o->scene.empty() ? o->reference : o->scene + "/ground_truth.ply";
    const SurfaceMesh reference_mesh = read_mesh(reference_path);
    const StereoModel model = read_stereo_model(o->scene.empty() ? o->cameras : o->scene + "/sparse");
    ProgressPrinter printer(common->quiet);
    nlohmann::json results = nlohmann::json::array();
    std::vector<CurvePanel> panels = {{"Accuracy (result -> reference)", {}}, {"Completeness (visible reference -> result)", {}}};
    StereoEvaluation last;
    for (std::size_t i = 0; i < o->meshes.size(); ++i) {
      const std::string label = o->labels.empty() ? o->meshes[i] : o->labels[i];
      last = evaluate_stereo(read_mesh(o->meshes[i]), reference_mesh, model.cameras, o->eval, printer.callback());
      panels[0].curves.push_back({label, last.accuracy});
      panels[1].curves.push_back({label, last.completeness});
      results.push_back({{"mesh", o->meshes[i]},
                         {"label", label},
                         {"accuracy", last.accuracy},
                         {"completeness", last.completeness},
                         {"accuracy_median", last.accuracy_median},
                         {"completeness_median", last.completeness_median},
                         {"result_samples", last.result_samples}});
      if (!common->quiet) {
        std::fprintf(stderr, "eval-stereo: %s\n  threshold     accuracy  completeness\n", label.c_str());
        for (std::size_t k = 0; k < last.thresholds.size(); ++k)
          std::fprintf(stderr, "  %-9g %9.1f%% %12.1f%%\n", o->eval.thresholds[k], 100 * last.accuracy[k], 100 * last.completeness[k]);
      }
    }
    const nlohmann::json report = {{"command", "eval-stereo"},
                                   {"reference", reference_path},
                                   {"scene_size", last.scene_size},
                                   {"thresholds_fraction", o->eval.thresholds},
                                   {"thresholds", last.thresholds},
                                   {"visible_reference_samples", last.visible_reference_samples},
                                   {"results", results},
                                   {"seconds", seconds_since(start)}};
    if (!o->plot.empty()) {
      std::vector<std::string> labels;
      for (double t : o->eval.thresholds) {
        std::ostringstream s;
        s << 100 * t << "%";
        labels.push_back(s.str());
      }
      write_curve_plot(o->plot, o->eval.thresholds, labels, "error threshold, % of the scene size", panels);
    }
    if (!o->json.empty()) write_text_file(o->json, report.dump(2) + "\n");
    if (!o->missing.empty()) {
      PointSet missing;
      for (std::size_t k = 0; k < last.visible_reference.size(); ++k)
        if (last.completeness_distances[k] > o->missing_threshold * last.scene_size) missing.points.push_back(last.visible_reference[k]);
      write_point_set(o->missing, missing);
    }
    write_report(common->report, report);
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
