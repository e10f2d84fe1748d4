// Local thickness of the sampled solid (or width of the gap between two
// sheets), beyond the thesis: where two parallel sheets of points face each
// other closer than the mesh size, Delaunay refinement cannot tell them
// apart (a Voronoi edge crosses both with no sign change), so the mesher
// needs denser vertices there (a sizing field driven by the local feature
// size, the thesis's future work in 8.2).

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/plane_fit.h"
#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"
#include "core/parallel.h"

namespace sharpmesh {

std::vector<double> local_thickness(const PointSet& points, double min_thickness, double max_thickness,
                                    std::vector<std::uint32_t>* facing_points) {
  if (points.normals.size() != points.size()) throw InvalidArgument("local thickness needs one normal per point");
  if (!(min_thickness >= 0) || !(max_thickness > min_thickness) || !std::isfinite(max_thickness))
    throw InvalidArgument("local thickness: bad thickness range");
  const double none = std::numeric_limits<double>::infinity();
  std::vector<double> thickness(points.size(), none);
  if (facing_points) {
    facing_points->resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) (*facing_points)[i] = static_cast<std::uint32_t>(i);
  }
  if (points.empty()) return thickness;
  const detail::KnnIndex index(points.points);
  // Noisy points of one sheet also face each other across the noise band:
  // walls thinner than 4x the noise (the median RMS residual of planes
  // fitted to 24 neighbours, on up to 2000 points) are not looked for.
  // Only neighbours within 30 degrees of the point's tangent plane are
  // fitted: on a part made of plates two spacings thick the 24 neighbours
  // reach the far face, and the plate itself read as noise hid every wall.
  const std::size_t samples = std::min<std::size_t>(points.size(), 2000);
  std::vector<double> residual(samples, 0.0);
  detail::parallel_for(samples, [&](std::size_t s) {
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    const std::size_t centre = s * (points.size() / samples);
    const Vec3& p = points.points[centre];
    const Vec3& n = points.normals[centre];
    index.nearest(p, 24, ids, d2);
    std::vector<Eigen::Vector3d> neighbours;
    for (std::uint32_t i : ids) {
      const Vec3 chord = points.points[i] - p;
      if (std::abs(dot(chord, n)) > 0.5 * norm(chord) * norm(n)) continue;
      neighbours.emplace_back(points.points[i][0], points.points[i][1], points.points[i][2]);
    }
    if (neighbours.size() < 8) return;
    detail::Plane plane;
    double rms = 0;
    if (detail::fit_plane(neighbours, plane, rms)) residual[s] = rms;
  });
  std::nth_element(residual.begin(), residual.begin() + samples / 2, residual.end());
  min_thickness = std::max(min_thickness, 4 * residual[samples / 2]);
  if (min_thickness >= max_thickness) return thickness;
  // A point q faces p across the solid when their normals are parallel
  // (either orientation: a wall or a gap) and q lies along p's normal
  // (within 30 degrees), farther than min_thickness.
  const double cos_parallel = std::cos(25.0 * M_PI / 180.0), cos_cone = std::cos(30.0 * M_PI / 180.0);
  // Such a q lies at least cos(30) min_thickness along the normal line. When
  // the range is wide (coarse meshes: max_thickness is d'), the ball of radius
  // max_thickness holds thousands of points of p's own sheet; the cone is
  // then covered by balls along the line, which visit far fewer points,
  // centred at s = t0, 1.25 t0, ... with radius 0.77 s (which contains the
  // cone between s and 1.25 s), nearest first, stopping once a ball can hold
  // nothing closer than the best so far. Same points, same result.
  const double t0 = cos_cone * min_thickness;
  const bool along_the_line = t0 > 0 && max_thickness > 8 * t0;
  detail::parallel_chunks(points.size(), 256, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> ids, nearest;
    std::vector<double> d2;
    for (std::size_t i = begin; i != end; ++i) {
      const Vec3& p = points.points[i];
      const Vec3& n = points.normals[i];
      const double nn = norm(n);
      if (!(nn > 0)) continue;
      double best = none;
      std::uint32_t facing = 0;
      auto consider = [&](std::uint32_t j) {
        const Vec3 d = points.points[j] - p;
        const double length = norm(d);
        if (!(length > min_thickness) || length >= best || length > max_thickness) return;
        const Vec3& m = points.normals[j];
        const double mm = norm(m);
        if (!(mm > 0) || std::abs(dot(n, m)) < cos_parallel * nn * mm) return;
        if (std::abs(dot(d, n)) < cos_cone * length * nn) return;
        best = length;
        facing = j;
      };
      if (!along_the_line) {
        index.within(p, max_thickness, ids);
        for (std::uint32_t j : ids) consider(j);
      } else {
        const Vec3 u = (1.0 / nn) * n;
        for (double side : {1.0, -1.0})
          for (double s = t0;; s *= 1.25) {
            const double radius = 0.77 * s;
            if (s - radius >= best) break;
            index.within(p + (side * s) * u, radius, ids);
            for (std::uint32_t j : ids) consider(j);
            if (1.25 * s >= max_thickness) break;
          }
      }
      // Across a wall or a gap no point lies half-way; inside a noisy sheet one does.
      if (std::isfinite(best)) {
        index.nearest(0.5 * (p + points.points[facing]), 1, nearest, d2);
        if (d2.empty() || d2[0] < 0.09 * best * best) best = none;
      }
      thickness[i] = best;
      if (facing_points && std::isfinite(best)) (*facing_points)[i] = facing;
    }
  });
  return thickness;
}

}  // namespace sharpmesh
