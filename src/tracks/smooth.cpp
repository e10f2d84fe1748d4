// Jet smoothing with Gaussian weights (thesis 6.3.1, after Cazals & Pouget
// 2003): around each point p0, a weighted tangent plane through p0, a
// weighted least-squares quadric z = a x^2 + b y^2 + c xy + d x + e y + f
// over it, and p0 moved onto the quadric along its normal at the origin.

#include <Eigen/Dense>
#include <cmath>

#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_reconstruct.h"
#include "core/parallel.h"

namespace sharpmesh {
namespace {

/// The smoothed position of point `i` from its neighbours (the first is i itself).
Vec3 smoothed(const std::vector<Vec3>& points, std::size_t i, const std::vector<std::uint32_t>& ids,
              const std::vector<double>& d2) {
  const Eigen::Vector3d p0(points[i][0], points[i][1], points[i][2]);
  double h = 0;
  for (double v : d2) h += std::sqrt(v);
  h /= static_cast<double>(d2.size() - 1);  // mean distance to the k others
  if (!(h > 0)) return points[i];
  // Coordinates in units of h, so that the Gaussian is exp(-x^2/2) as in the thesis.
  std::vector<Eigen::Vector3d> q(ids.size());
  std::vector<double> w(ids.size());
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (std::size_t j = 0; j < ids.size(); ++j) {
    const Vec3& p = points[ids[j]];
    q[j] = (Eigen::Vector3d(p[0], p[1], p[2]) - p0) / h;
    w[j] = std::exp(-0.5 * q[j].squaredNorm());
    m += w[j] * q[j] * q[j].transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m);
  const Eigen::Vector3d n = eig.eigenvectors().col(0);  // smallest eigenvalue: the normal
  const Eigen::Vector3d u = eig.eigenvectors().col(2), v = eig.eigenvectors().col(1);
  Eigen::Matrix<double, 6, 6> ata = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> atz = Eigen::Matrix<double, 6, 1>::Zero();
  for (std::size_t j = 0; j < q.size(); ++j) {
    const double x = q[j].dot(u), y = q[j].dot(v), z = q[j].dot(n);
    Eigen::Matrix<double, 6, 1> row;
    row << x * x, y * y, x * y, x, y, 1.0;
    ata += w[j] * row * row.transpose();
    atz += w[j] * z * row;
  }
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solver(ata);
  if (solver.info() != Eigen::Success) return points[i];
  const Eigen::Matrix<double, 6, 1> c = solver.solve(atz);
  if (!c.allFinite()) return points[i];
  // Orthogonal projection of p0 (the origin) onto the quadric's tangent plane
  // at (0, 0, f), whose normal is (-d, -e, 1).
  const double d = c[3], e = c[4], f = c[5];
  const double t = f / (1.0 + d * d + e * e);
  const Eigen::Vector3d moved = p0 + h * t * (-d * u - e * v + n);
  if (!moved.allFinite()) return points[i];
  return {moved[0], moved[1], moved[2]};
}

}  // namespace

void jet_smooth_gaussian(std::vector<Vec3>& points, int k, const Progress& progress) {
  if (k < 6) throw InvalidArgument("jet smoothing needs k >= 6 neighbours (a quadric has 6 coefficients), got " + format_number(k));
  if (points.size() < static_cast<std::size_t>(k) + 1) return;  // too few points to fit anything
  const detail::KnnIndex index(points);
  std::vector<Vec3> out(points.size());
  detail::parallel_chunks(
      points.size(), 64,
      [&](std::size_t begin, std::size_t end) {
        std::vector<std::uint32_t> ids;
        std::vector<double> d2;
        for (std::size_t i = begin; i != end; ++i) {
          index.nearest(points[i], k + 1, ids, d2);
          out[i] = smoothed(points, i, ids, d2);
        }
      },
      progress, "jet smoothing", 4096);
  points = std::move(out);
}

}  // namespace sharpmesh
