// Accuracy and completeness of a multi-view reconstruction against a
// reference surface (Strecha et al. 2008; thesis 6.5, Fig. 6.8).

#include <algorithm>
#include <cmath>

#include "core/triangle_distance.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "core/ray_caster.h"
#include "core/parallel.h"

namespace sharpmesh {
namespace {

std::vector<double> cumulative(std::vector<double> d, const std::vector<double>& thresholds, double& median) {
  std::sort(d.begin(), d.end());
  median = d.empty() ? 0 : d[d.size() / 2];
  std::vector<double> fractions;
  for (double t : thresholds) {
    const auto within = std::upper_bound(d.begin(), d.end(), t) - d.begin();
    fractions.push_back(d.empty() ? 0.0 : static_cast<double>(within) / static_cast<double>(d.size()));
  }
  return fractions;
}

}  // namespace

void StereoEvalOptions::check() const {
  if (samples == 0) throw InvalidArgument("the number of samples must be positive");
  if (thresholds.empty()) throw InvalidArgument("at least one threshold is needed");
  for (std::size_t i = 0; i < thresholds.size(); ++i)
    if (!(thresholds[i] > 0) || (i > 0 && thresholds[i] <= thresholds[i - 1]))
      throw InvalidArgument("thresholds must be positive and increasing");
}

StereoEvaluation evaluate_stereo(const SurfaceMesh& mesh, const SurfaceMesh& reference, const std::vector<Camera>& cameras,
                                 const StereoEvalOptions& options, const Progress& progress) {
  options.check();
  if (mesh.faces.empty()) throw InvalidInput("the mesh to evaluate has no faces");
  if (reference.faces.empty()) throw InvalidInput("the reference mesh has no faces");
  if (cameras.empty()) throw InvalidInput("no cameras: visibility of the reference cannot be decided");
  report_progress(progress, "visibility", 0.0);
  SampleOptions sampling;
  sampling.count = options.samples;
  sampling.seed = options.seed;
  const std::vector<Vec3> reference_samples = sample_mesh(reference, sampling).points;
  const detail::RayCaster reference_rays(reference);
  std::vector<char> visible(reference_samples.size(), 0);
  detail::parallel_chunks(reference_samples.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i != end; ++i)
      for (const Camera& c : cameras) {
        Vec2 p;
        if (c.project(reference_samples[i], p) && c.in_image(p) && !reference_rays.occluded(c.center(), reference_samples[i])) {
          visible[i] = 1;
          break;
        }
      }
  });
  std::vector<Vec3> seen;
  for (std::size_t i = 0; i < reference_samples.size(); ++i)
    if (visible[i]) seen.push_back(reference_samples[i]);
  if (seen.empty()) throw InvalidInput("no camera sees the reference surface");
  StereoEvaluation e;
  e.scene_size = bounding_box(seen).diagonal();
  for (double t : options.thresholds) e.thresholds.push_back(t * e.scene_size);
  report_progress(progress, "completeness", 0.3);
  const detail::TriangleDistance to_mesh(mesh);
  e.completeness_distances = to_mesh.distances(seen);
  e.completeness = cumulative(e.completeness_distances, e.thresholds, e.completeness_median);
  e.visible_reference_samples = seen.size();
  e.visible_reference = std::move(seen);
  report_progress(progress, "accuracy", 0.6);
  sampling.seed = options.seed + 1;
  const std::vector<Vec3> result_samples = sample_mesh(mesh, sampling).points;
  const detail::TriangleDistance to_reference(reference);
  e.accuracy = cumulative(to_reference.distances(result_samples), e.thresholds, e.accuracy_median);
  e.result_samples = result_samples.size();
  report_progress(progress, "accuracy", 1.0);
  return e;
}

}  // namespace sharpmesh
