#include "pipeline/data_fit.h"

#include <algorithm>
#include <cmath>

#include "pointset/knn.h"
#include "sharpmesh/eval.h"

namespace sharpmesh::detail {

DataFit fit_to_data(const SurfaceMesh& mesh, const std::vector<Vec3>& points, double off_distance) {
  DataFit fit;
  if (mesh.faces.empty() || points.empty()) return fit;
  const std::vector<double> d = distances_to_mesh(points, mesh);
  for (std::size_t i = 0; i < d.size(); ++i) {
    fit.max_distance = std::max(fit.max_distance, d[i]);
    if (d[i] > off_distance) fit.off.push_back(static_cast<std::uint32_t>(i));
  }
  return fit;
}

std::size_t flip_around(PointSet& oriented, const std::vector<std::uint32_t>& ids, double radius) {
  const KnnIndex index(oriented.points);
  std::vector<char> flip(oriented.size(), 0);
  std::vector<std::uint32_t> near;
  for (std::uint32_t i : ids) {
    flip[i] = 1;
    index.within(oriented.points[i], radius, near);
    for (std::uint32_t j : near)
      if (dot(oriented.normals[i], oriented.normals[j]) > std::sqrt(0.5)) flip[j] = 1;
  }
  std::size_t flips = 0;
  for (std::size_t i = 0; i < oriented.size(); ++i)
    if (flip[i]) oriented.normals[i] = -1.0 * oriented.normals[i], ++flips;
  return flips;
}

}  // namespace sharpmesh::detail
