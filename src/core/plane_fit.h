// Least-squares plane through a set of points (the eigenvector of the
// smallest eigenvalue of their covariance), shared by the stages that fit
// planes to the data: edge-point sharpening and feature flattening.
#pragma once

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <vector>

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

}  // namespace sharpmesh::detail
