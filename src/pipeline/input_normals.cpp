// Normals a file carries, checked before Poisson trusts them (beyond the
// thesis: files in the wild carry zero or inconsistently signed normals).
#include <algorithm>
#include <cmath>

#include "pipeline/stages.h"

namespace sharpmesh::detail {

/// Normals read from a file are checked before Poisson trusts them: files
/// in the wild carry zero normals or normals whose lines are right but
/// whose signs flip from face to face (Poisson's surface then breaks up
/// into shreds along the creases). Usable normals are made unit;
/// when fewer than half are usable they are ignored and estimated instead.
/// Otherwise PCA normals, which turn smoothly across creases, are oriented
/// by the tangent MST (App. A.8), anchored by the occupancy as the
/// estimated normals are (a knife edge would otherwise invert a face and
/// the file's right signs look inconsistent), and compared with the file's signs: at
/// between 10% and 90% agreement the signs are inconsistent, and each input
/// normal takes the sign of the oriented PCA normal (its line is kept).
/// Consistently inward normals, near 0%, are kept as given.
InputNormals check_input_normals(PointSet& cloud, const ReconstructOptions& options, double& agreement, const Progress& progress) {
  std::size_t usable = 0;
  for (Vec3& n : cloud.normals) {
    const double length = norm(n);
    if (std::isfinite(length) && length > 0) {
      n = (1.0 / length) * n;
      ++usable;
    } else {
      n = {0, 0, 0};
    }
  }
  if (2 * usable < cloud.size()) return InputNormals::Unusable;
  const int last = static_cast<int>(cloud.size()) - 1;
  PointSet reference{cloud.points, {}, {}};
  NormalEstimationOptions pca = options.normals;
  pca.method = NormalMethod::Pca;
  pca.k = std::min(pca.k, last);
  estimate_normals(reference, pca, progress);
  const std::vector<signed char> anchors =
      occupancy_anchors(reference, average_spacing(reference, std::min(options.spacing_k, last), progress), 0.0,
                        std::min(options.orientation.k, last));
  orient_normals_tangent_mst(reference, std::min(options.orientation.k, last), anchors, progress);
  std::size_t agree = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) agree += dot(reference.normals[i], cloud.normals[i]) > 0;
  agreement = static_cast<double>(agree) / static_cast<double>(usable);
  const double consensus = options.tuning.input_normal_consensus;
  if (agreement <= 1 - consensus || agreement >= consensus) return InputNormals::Used;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (dot(reference.normals[i], cloud.normals[i]) < 0) cloud.normals[i] = -1.0 * cloud.normals[i];
  return InputNormals::Reoriented;
}

}  // namespace sharpmesh::detail
