// Two-sided distances between a mesh and a reference (Metro-style sampling),
// and sharp-edge fidelity (thesis 7.5, 8.2).

#include <cmath>

#include "core/triangle_distance.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"

namespace sharpmesh {
namespace {

struct OneSided {
  double max = 0, sum = 0, sum_squares = 0;
  std::size_t count = 0;
};

OneSided distances_to(const std::vector<Vec3>& queries, const detail::TriangleDistance& target) {
  const std::vector<double> d = target.distances(queries);
  OneSided out;  // summed in order: the result does not depend on the thread count
  for (double x : d) {
    out.max = std::max(out.max, x);
    out.sum += x;
    out.sum_squares += x * x;
  }
  out.count = d.size();
  return out;
}

std::vector<Vec3> samples_and_vertices(const SurfaceMesh& mesh, std::size_t count, std::uint64_t seed) {
  SampleOptions options;
  options.count = count;
  options.seed = seed;
  std::vector<Vec3> points = sample_mesh(mesh, options).points;
  points.insert(points.end(), mesh.vertices.begin(), mesh.vertices.end());
  return points;
}

}  // namespace

std::vector<double> distances_to_mesh(const std::vector<Vec3>& points, const SurfaceMesh& mesh) {
  if (mesh.faces.empty()) throw InvalidInput("the mesh has no faces");
  return detail::TriangleDistance(mesh).distances(points);
}

void DistanceOptions::check() const {
  if (samples == 0) throw InvalidArgument("the number of distance samples must be positive");
  if (!(sharp_angle > 0 && sharp_angle < 180)) throw InvalidArgument("sharp angle must be in (0, 180) degrees");
}

DistanceReport compare_meshes(const SurfaceMesh& mesh, const SurfaceMesh& reference, const DistanceOptions& options,
                              const Progress& progress) {
  options.check();
  if (mesh.faces.empty()) throw InvalidInput("the mesh to evaluate has no faces");
  if (reference.faces.empty()) throw InvalidInput("the reference mesh has no faces");
  DistanceReport report;
  report.diagonal = bounding_box(reference.vertices).diagonal();
  report_progress(progress, "distances", 0.0);
  const detail::TriangleDistance to_reference(reference), to_mesh(mesh);
  const OneSided forward = distances_to(samples_and_vertices(mesh, options.samples, options.seed), to_reference);
  report_progress(progress, "distances", 0.4);
  const OneSided backward = distances_to(samples_and_vertices(reference, options.samples, options.seed + 1), to_mesh);
  report_progress(progress, "distances", 0.8);
  report.mesh_to_reference_max = forward.max;
  report.reference_to_mesh_max = backward.max;
  report.mesh_to_reference_mean = forward.sum / forward.count;
  report.reference_to_mesh_mean = backward.sum / backward.count;
  report.hausdorff = std::max(forward.max, backward.max);
  report.mean = (forward.sum + backward.sum) / (forward.count + backward.count);
  report.rms = std::sqrt((forward.sum_squares + backward.sum_squares) / (forward.count + backward.count));

  // Sharp-edge fidelity: points every diagonal/2000 along the reference's sharp edges.
  const std::vector<Polyline> edges = sharp_edges(reference, options.sharp_angle);
  const double step = report.diagonal / 2000.0;
  std::vector<Vec3> edge_points;
  for (const Polyline& line : edges) {
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const double length = distance(line[i], line[i + 1]);
      report.sharp_edge_length += length;
      const int steps = std::max(1, static_cast<int>(std::ceil(length / step)));
      for (int s = 0; s < steps; ++s) edge_points.push_back(line[i] + (static_cast<double>(s) / steps) * (line[i + 1] - line[i]));
    }
    edge_points.push_back(line.back());
  }
  report.sharp_edge_count = edges.size();
  if (!edge_points.empty()) {
    const OneSided sharp = distances_to(edge_points, to_mesh);
    report.sharp_mean = sharp.sum / sharp.count;
    report.sharp_max = sharp.max;
  }
  report_progress(progress, "distances", 1.0);
  return report;
}

}  // namespace sharpmesh
