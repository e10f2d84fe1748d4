// Algorithm 1 (thesis 7.2.1): eigen-analysis of the convolved VCM.
#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>

#include "sharpmesh/features.h"

namespace sharpmesh {

std::vector<PointFeature> classify_points(const std::vector<Matrix3>& cvcm, double t1, double t2) {
  std::vector<PointFeature> out(cvcm.size());
  for (std::size_t i = 0; i < cvcm.size(); ++i) {
    Eigen::Matrix3d m;
    for (int k = 0; k < 9; ++k) m(k / 3, k % 3) = cvcm[i][k];
    // Eigen sorts eigenvalues increasingly: lambda2 <= lambda1 <= lambda0.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(m);
    const Eigen::Vector3d lambda = solver.eigenvalues().cwiseMax(0.0);
    PointFeature& f = out[i];
    if (!(lambda(2) > 0)) continue;  // an empty measure: nothing to say, keep "smooth"
    const double tiny = std::numeric_limits<double>::min();
    f.ratio01 = lambda(2) / std::max(lambda(1), tiny);
    f.ratio12 = lambda(1) / std::max(lambda(0), tiny);
    const Eigen::Vector3d e0 = solver.eigenvectors().col(2), e2 = solver.eigenvectors().col(0);
    f.normal = {e0(0), e0(1), e0(2)};
    f.direction = {e2(0), e2(1), e2(2)};
    if (f.ratio01 > t1) f.type = PointClass::Smooth;
    else if (f.ratio12 >= t2) f.type = PointClass::Edge;
    else f.type = PointClass::Corner;
  }
  return out;
}

}  // namespace sharpmesh
