// Edge-point detection benchmark (issue: feature extraction, item 8).
//
// Samples a CAD mesh (fixed seed, optional uniform noise), labels each point
// by its distance to the mesh's sharp edges, and compares in the same run:
//   - sharpmesh: clamped VCM (7.4) + convolution + Algorithm 1, then the
//     two-plane sharpening filter (what the polylines are built from);
//   - CGAL 5.5: CGAL::compute_vcm + CGAL::vcm_is_on_feature_edge.
// Prints edge-point precision, recall and F1 of both, the wall time of both
// VCM computations and their ratio, and the polyline recall/precision of the
// full `extract_features` (the Section 8.2 benchmark).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/vcm_estimate_edges.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "sharpmesh/eval.h"
#include "sharpmesh/features.h"
#include "sharpmesh/io.h"
#include "sharpmesh/pointset.h"

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Score {
  double precision = 0, recall = 0, f1 = 0;
  std::size_t flagged = 0;
};

// precision: flagged points within `band` of a sharp edge; recall: points
// within band/2 of a sharp edge that are flagged.
Score score(const std::vector<char>& flagged, const std::vector<double>& dist, double band) {
  std::size_t tp = 0, flagged_count = 0, near = 0, near_found = 0;
  for (std::size_t i = 0; i < flagged.size(); ++i) {
    flagged_count += flagged[i];
    tp += flagged[i] && dist[i] <= band;
    if (dist[i] <= band / 2) {
      ++near;
      near_found += flagged[i];
    }
  }
  Score s;
  s.flagged = flagged_count;
  s.precision = flagged_count ? static_cast<double>(tp) / flagged_count : 1.0;
  s.recall = near ? static_cast<double>(near_found) / near : 1.0;
  s.f1 = s.precision + s.recall > 0 ? 2 * s.precision * s.recall / (s.precision + s.recall) : 0;
  return s;
}

// Where to put t1 and t2: the ratios' distribution near the edges (within
// band/2) and far from them (beyond 2 band).
void print_ratio_quantiles(const std::vector<sharpmesh::PointFeature>& features, const std::vector<double>& dist, double band) {
  std::vector<double> near01, far01, near12, far12;
  for (std::size_t i = 0; i < features.size(); ++i) {
    if (dist[i] <= band / 2) {
      near01.push_back(features[i].ratio01);
      near12.push_back(features[i].ratio12);
    } else if (dist[i] > 2 * band) {
      far01.push_back(features[i].ratio01);
      far12.push_back(features[i].ratio12);
    }
  }
  auto print = [](const char* name, std::vector<double> v) {
    std::sort(v.begin(), v.end());
    std::printf("  %-22s", name);
    for (double q : {0.05, 0.25, 0.5, 0.75, 0.95}) std::printf(" q%02d %-9.3g", static_cast<int>(q * 100), v.empty() ? 0.0 : v[static_cast<std::size_t>(q * (v.size() - 1))]);
    std::printf("\n");
  };
  print("l0/l1 near edges", near01);
  print("l0/l1 far from edges", far01);
  print("l1/l2 near edges", near12);
  print("l1/l2 far from edges", far12);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Edge-point detection: sharpmesh versus CGAL::compute_vcm + vcm_is_on_feature_edge"};
  std::string mesh_path;
  std::size_t count = 200000;
  double noise = 0, band = 0, cgal_threshold = 0.16, sharp_angle = 30;
  unsigned seed = 1;
  bool skip_cgal = false, quantiles = false;
  sharpmesh::FeatureOptions options;
  app.add_option("MESH", mesh_path, "CAD mesh with sharp edges")->required();
  app.add_option("-n,--count", count, "Sample size");
  app.add_option("--noise", noise, "Uniform noise, fraction of the diagonal");
  app.add_option("--seed", seed, "Sampling seed");
  app.add_option("--band", band, "Edge band, fraction of the diagonal (0: 0.5%, or 1% with noise)");
  app.add_option("--sharp-angle", sharp_angle, "Dihedral angle of a ground-truth sharp edge, degrees");
  app.add_option("--cgal-threshold", cgal_threshold, "vcm_is_on_feature_edge threshold (CGAL's example: 0.16)");
  app.add_option("--offset-radius", options.offset_radius, "R, fraction of the bounding-sphere radius");
  app.add_option("--convolution-radius", options.convolution_radius, "r, fraction of R (0: automatic)");
  app.add_option("--t1", options.t1);
  app.add_option("--denoise-k", options.denoise_k, "-1 automatic, 0 never");
  app.add_option("--t2", options.t2);
  app.add_flag("--skip-cgal", skip_cgal, "Only run sharpmesh");
  app.add_flag("--quantiles", quantiles, "Print quantiles of the eigenvalue ratios near and far from the sharp edges");
  CLI11_PARSE(app, argc, argv);

  const sharpmesh::SurfaceMesh mesh = sharpmesh::read_mesh(mesh_path);
  sharpmesh::SampleOptions sample_options;
  sample_options.count = count;
  sample_options.noise = noise;
  sample_options.seed = seed;
  const sharpmesh::PointSet cloud = sharpmesh::sample_mesh(mesh, sample_options);
  const double diagonal = sharpmesh::bounding_box(cloud.points).diagonal();
  if (band <= 0) band = noise > 0 ? 0.01 : 0.005;
  const std::vector<sharpmesh::Polyline> truth = sharpmesh::sharp_edges(mesh, sharp_angle);
  const std::vector<double> dist = sharpmesh::distances_to_polylines(cloud.points, truth, 0.0005 * diagonal);
  std::printf("%s: %zu points, noise %g, band %g of the diagonal, %zu sharp edges\n", mesh_path.c_str(), cloud.size(), noise,
              band, truth.size());
  std::printf("%-28s %9s %9s %9s %9s %9s\n", "detector", "flagged", "precision", "recall", "F1", "VCM s");

  // sharpmesh: the full extraction (its detection stage is the VCM+CVCM+classification).
  auto t0 = Clock::now();
  const sharpmesh::FeatureResult result = sharpmesh::extract_features(cloud, options);
  const double ours_total = seconds_since(t0);
  double ours_vcm = 0;
  for (const auto& stage : result.stages)
    if (stage.name == "detection") ours_vcm = stage.seconds;
  std::vector<char> flagged(cloud.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) flagged[i] = result.points[i].type != sharpmesh::PointClass::Smooth;
  const Score ours = score(flagged, dist, band * diagonal);
  std::printf("%-28s %9zu %9.3f %9.3f %9.3f %9.2f\n", "sharpmesh (Algorithm 1)", ours.flagged, ours.precision, ours.recall,
              ours.f1, ours_vcm);

  if (quantiles) print_ratio_quantiles(result.points, dist, band * diagonal);

  double cgal_vcm = 0;
  Score cgal;
  if (!skip_cgal) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    std::vector<Kernel::Point_3> points;
    points.reserve(cloud.size());
    for (const auto& p : cloud.points) points.emplace_back(p[0], p[1], p[2]);
    // The same radii as ours: R and r in data units.
    std::vector<std::array<double, 6>> cov;
    t0 = Clock::now();
    CGAL::compute_vcm(points, cov, result.offset_radius, result.convolution_radius,
                      CGAL::parameters::geom_traits(Kernel()));
    cgal_vcm = seconds_since(t0);
    std::vector<char> cgal_flagged(cloud.size(), 0);
    for (std::size_t i = 0; i < cloud.size(); ++i)
      cgal_flagged[i] = CGAL::vcm_is_on_feature_edge(cov[i], cgal_threshold);
    cgal = score(cgal_flagged, dist, band * diagonal);
    std::printf("%-28s %9zu %9.3f %9.3f %9.3f %9.2f\n", "CGAL compute_vcm", cgal.flagged, cgal.precision, cgal.recall, cgal.f1,
                cgal_vcm);
  }

  // The Section 8.2 benchmark on the polylines.
  std::vector<sharpmesh::Vec3> extracted_corners;
  for (const auto& j : result.graph.junctions)
    if (j.type == sharpmesh::JunctionType::Corner) extracted_corners.push_back(j.position);
  sharpmesh::FeatureEvalOptions eval_options;
  eval_options.sharp_angle = sharp_angle;
  eval_options.tolerance = band;
  const sharpmesh::FeatureEvaluation eval =
      sharpmesh::evaluate_features(result.graph.polylines, extracted_corners, mesh, eval_options);
  std::printf("\nR = %.4g, r = %.4g (%.3g R), noise estimate %.3g%%, spacing %.3g%% of the diagonal, denoise k %d x %d\n", result.offset_radius,
              result.convolution_radius, result.convolution_radius / result.offset_radius,
              100 * result.noise_estimate / diagonal, 100 * result.average_spacing / diagonal, result.denoise_k, result.denoise_passes);
  std::printf("polylines: %zu, recall %.3f, precision %.3f at %g of the diagonal; corners %zu of %zu; stages 1-3 %.2f s\n",
              result.graph.polylines.size(), eval.recall, eval.precision, band, eval.recalled_corners, eval.truth_corners,
              ours_total);
  if (!skip_cgal)
    std::printf("VCM time ratio CGAL/sharpmesh: %.1fx; edge-point F1 sharpmesh %.3f vs CGAL %.3f\n", cgal_vcm / ours_vcm,
                ours.f1, cgal.f1);
  return 0;
}
