// Recall and precision of extracted sharp-edge polylines against the sharp
// edges of a reference mesh (the benchmark asked for in thesis 8.2).
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/mesh_graph.h"
#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"

namespace sharpmesh {
namespace {

// Points along the polylines every `step` at most, each with the length it stands for.
void densify(const std::vector<Polyline>& lines, double step, std::vector<Vec3>& points, std::vector<double>& weights) {
  for (const Polyline& line : lines)
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const double length = distance(line[i], line[i + 1]);
      const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
      for (int s = 0; s < n; ++s) {
        points.push_back(line[i] + ((s + 0.5) / n) * (line[i + 1] - line[i]));
        weights.push_back(length / n);
      }
    }
}

struct Coverage {
  double covered = 0, total = 0, mean = 0, max = 0;
};

// Distance from each sample to the nearest target point (infinite without targets).
std::vector<double> nearest_distances(const std::vector<Vec3>& samples, const std::vector<Vec3>& target) {
  std::vector<double> out(samples.size(), std::numeric_limits<double>::infinity());
  if (target.empty()) return out;
  const detail::KnnIndex index(target);
  std::vector<std::uint32_t> ids;
  std::vector<double> d2;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    index.nearest(samples[i], 1, ids, d2);
    out[i] = std::sqrt(d2[0]);
  }
  return out;
}

// Length-weighted coverage of the samples by the densified target (error below step/2).
Coverage coverage(const std::vector<Vec3>& samples, const std::vector<double>& weights, const std::vector<Vec3>& target,
                  double tolerance) {
  Coverage c;
  if (samples.empty()) return c;
  const std::vector<double> d = nearest_distances(samples, target);
  double weighted = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    c.total += weights[i];
    weighted += weights[i] * d[i];
    if (d[i] <= tolerance) c.covered += weights[i];
    c.max = std::max(c.max, d[i]);
  }
  c.mean = weighted / c.total;
  return c;
}

}  // namespace

std::vector<Vec3> polyline_corners(const std::vector<Polyline>& polylines, int min_degree) {
  std::vector<Vec3> ends, corners;
  for (const Polyline& p : polylines)
    if (p.size() >= 2 && p.front() != p.back()) {
      ends.push_back(p.front());
      ends.push_back(p.back());
    }
  std::sort(ends.begin(), ends.end());
  for (std::size_t i = 0; i < ends.size();) {
    std::size_t j = i;
    while (j < ends.size() && ends[j] == ends[i]) ++j;
    if (static_cast<int>(j - i) >= min_degree) corners.push_back(ends[i]);
    i = j;
  }
  return corners;
}

std::vector<double> distances_to_polylines(const std::vector<Vec3>& points, const std::vector<Polyline>& polylines,
                                           double step) {
  if (!(step > 0)) throw InvalidArgument("polyline resampling step must be positive");
  std::vector<Vec3> dense;
  std::vector<double> unused;
  densify(polylines, step, dense, unused);
  return nearest_distances(points, dense);
}

void FeatureEvalOptions::check() const {
  if (!(sharp_angle > 0 && sharp_angle < 180)) throw InvalidArgument("sharp angle must be in (0, 180) degrees");
  if (!(tolerance > 0 && tolerance < 1)) throw InvalidArgument("tolerance must be a fraction of the diagonal in (0, 1)");
}

FeatureEvaluation evaluate_features(const std::vector<Polyline>& extracted, const std::vector<Vec3>& extracted_corners,
                                    const SurfaceMesh& reference, const FeatureEvalOptions& options) {
  options.check();
  if (reference.faces.empty()) throw InvalidInput("the reference mesh has no faces");
  FeatureEvaluation e;
  e.diagonal = bounding_box(reference.vertices).diagonal();
  e.tolerance = options.tolerance * e.diagonal;
  const std::vector<Polyline> truth = sharp_edges(reference, options.sharp_angle);
  const double fine = e.tolerance / 20, coarse = e.tolerance / 4;
  std::vector<Vec3> truth_samples, truth_dense, extracted_samples, extracted_dense;
  std::vector<double> truth_w, extracted_w, unused;
  densify(truth, coarse, truth_samples, truth_w);
  densify(truth, fine, truth_dense, unused);
  densify(extracted, coarse, extracted_samples, extracted_w);
  densify(extracted, fine, extracted_dense, unused);
  const Coverage recall = coverage(truth_samples, truth_w, extracted_dense, e.tolerance);
  const Coverage precision = coverage(extracted_samples, extracted_w, truth_dense, e.tolerance);
  e.truth_length = recall.total;
  e.extracted_length = precision.total;
  e.recall = recall.total > 0 ? recall.covered / recall.total : 1.0;
  e.precision = precision.total > 0 ? precision.covered / precision.total : 1.0;
  e.truth_to_extracted_mean = recall.mean;
  e.truth_to_extracted_max = recall.max;
  e.extracted_to_truth_mean = precision.mean;
  e.extracted_to_truth_max = precision.max;
  // Ground-truth corners: polyline ends shared by 3 or more polylines.
  for (const Vec3& corner : polyline_corners(truth)) {
    ++e.truth_corners;
    for (const Vec3& c : extracted_corners)
      if (distance(c, corner) <= e.tolerance) {
        ++e.recalled_corners;
        break;
      }
  }
  return e;
}

}  // namespace sharpmesh
