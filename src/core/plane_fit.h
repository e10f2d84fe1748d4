// Least-squares plane through a set of points (the eigenvector of the
// smallest eigenvalue of their covariance), shared by the stages that fit
// planes to the data: edge-point sharpening, feature flattening, the noise
// estimate and the walls' flatness test.
#pragma once

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh::detail {

struct Plane {
  Eigen::Vector3d normal, point;
};

/// False with fewer than 6 points; `rms` is the RMS distance of the points to the plane.
inline bool fit_plane(const std::vector<Eigen::Vector3d>& pts, Plane& plane, double& rms) {
  if (pts.size() < 6) return false;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : pts) c += p;
  c /= static_cast<double>(pts.size());
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) m += (p - c) * (p - c).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(m);
  plane = {solver.eigenvectors().col(0), c};
  rms = std::sqrt(std::max(0.0, solver.eigenvalues()(0)) / static_cast<double>(pts.size()));
  return true;
}

/// Eigenvalues, ascending, of the scatter matrix of points[ids] about their
/// centroid (the sum of squared offsets: divide by the count for variances).
inline Eigen::Vector3d scatter_eigenvalues(const std::vector<Vec3>& points, const std::vector<std::uint32_t>& ids) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (std::uint32_t i : ids) c += Eigen::Vector3d(points[i][0], points[i][1], points[i][2]);
  c /= static_cast<double>(ids.size());
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (std::uint32_t i : ids) {
    const Eigen::Vector3d d = Eigen::Vector3d(points[i][0], points[i][1], points[i][2]) - c;
    m += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(m);
  return solver.eigenvalues().cwiseMax(0.0);
}

}  // namespace sharpmesh::detail
