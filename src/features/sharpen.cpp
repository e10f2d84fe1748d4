// Edge-point sharpening, beyond the thesis. Edge points (Algorithm 1) lie on
// the faces beside a sharp edge, in a band as wide as the convolution
// radius, so polylines through them run inside convex edges and outside
// concave ones: the "gap" of thesis 7.5 (Fig. 7.18). Around each edge point,
// the smooth points split into two groups by normal; a plane fitted to each
// group gives the edge as their intersection line, onto which the point is
// projected. Averaging over whole patches also averages noise out. An edge
// point whose neighbourhood shows no second plane is not on a sharp edge and
// is dropped.
#include <Eigen/Eigenvalues>

#include <tbb/parallel_for.h>

#include <cmath>

#include "core/plane_fit.h"
#include "features/feature_graph_builder.h"

namespace sharpmesh::detail {
namespace {

Eigen::Vector3d eig(const Vec3& v) { return {v[0], v[1], v[2]}; }

}  // namespace

std::size_t sharpen_edge_points(const PointSet& cloud, const std::vector<PointFeature>& features, const KnnIndex& index,
                                double radius, double min_angle_deg, double max_residual, std::vector<std::uint32_t>& edge_ids,
                                std::vector<Vec3>& positions, std::vector<Vec3>& directions) {
  const double cos_min = std::cos(min_angle_deg * M_PI / 180.0);
  const std::size_t n = edge_ids.size();
  std::vector<char> keep(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<std::uint32_t> ids;
    std::vector<Eigen::Vector3d> group[2];
    for (std::size_t e = range.begin(); e != range.end(); ++e) {
      const Vec3& p = cloud.points[edge_ids[e]];
      index.within(p, radius, ids);
      std::sort(ids.begin(), ids.end());
      // Seeds of the two groups: the two smooth normals farthest apart.
      std::vector<std::uint32_t> smooth;
      for (std::uint32_t i : ids)
        if (features[i].type == PointClass::Smooth) smooth.push_back(i);
      if (smooth.size() < 12) continue;
      Eigen::Vector3d a = eig(features[smooth[0]].normal), b = a;
      double worst = 1;
      for (std::uint32_t i : smooth) {
        const double c = std::abs(a.dot(eig(features[i].normal)));
        if (c < worst) { worst = c; b = eig(features[i].normal); }
      }
      if (worst > cos_min) continue;  // one plane only: not a sharp edge
      // Two rounds of sign-invariant 2-means on the normals.
      for (int round = 0; round < 2; ++round) {
        group[0].clear();
        group[1].clear();
        Eigen::Matrix3d sum[2] = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
        for (std::uint32_t i : smooth) {
          const Eigen::Vector3d nrm = eig(features[i].normal);
          const int g = std::abs(nrm.dot(a)) >= std::abs(nrm.dot(b)) ? 0 : 1;
          group[g].push_back(eig(cloud.points[i]));
          sum[g] += nrm * nrm.transpose();
        }
        for (int g = 0; g < 2; ++g) {
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
          solver.computeDirect(sum[g]);
          (g == 0 ? a : b) = solver.eigenvectors().col(2);
        }
      }
      Plane pa, pb;
      double rms_a = 0, rms_b = 0;
      if (!fit_plane(group[0], pa, rms_a) || !fit_plane(group[1], pb, rms_b)) continue;
      // Near a corner three or more patches meet and two planes do not fit:
      // such points are left out, and junction recovery extends the polylines there.
      if (std::max(rms_a, rms_b) > max_residual) continue;
      Eigen::Vector3d d = pa.normal.cross(pb.normal);
      const double sin_angle = d.norm();
      if (sin_angle < std::sin(min_angle_deg * M_PI / 180.0)) continue;
      d /= sin_angle;
      // Closest point to p on the intersection of the two planes: minimise
      // |x - p|^2 subject to na.x = na.ca and nb.x = nb.cb (x = p + s na + t nb).
      const Eigen::Vector3d q = eig(p);
      const double ra = pa.normal.dot(pa.point - q), rb = pb.normal.dot(pb.point - q), c = pa.normal.dot(pb.normal);
      const double det = 1 - c * c;
      const double s = (ra - c * rb) / det, t = (rb - c * ra) / det;
      const Eigen::Vector3d x = q + s * pa.normal + t * pb.normal;
      if ((x - q).norm() > radius) continue;  // the planes meet far away: unreliable
      positions[e] = {x(0), x(1), x(2)};
      directions[e] = {d(0), d(1), d(2)};
      keep[e] = 1;
    }
  });
  std::size_t out = 0;
  for (std::size_t e = 0; e < n; ++e) {
    if (!keep[e]) continue;
    edge_ids[out] = edge_ids[e];
    positions[out] = positions[e];
    directions[out] = directions[e];
    ++out;
  }
  const std::size_t dropped = n - out;
  edge_ids.resize(out);
  positions.resize(out);
  directions.resize(out);
  return dropped;
}

}  // namespace sharpmesh::detail
