#include "pipeline/data_fit.h"

#include <algorithm>
#include <cmath>

#include "core/knn.h"
#include "core/triangle_distance.h"

namespace sharpmesh::detail {

DataFit fit_to_data(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const std::vector<Vec3>& normals,
                    double off_distance) {
  DataFit fit;
  if (mesh.faces.empty() || points.empty()) return fit;
  const TriangleDistance tree(mesh);
  const std::vector<double> d = tree.distances(points);
  for (std::size_t i = 0; i < d.size(); ++i) {
    fit.max_distance = std::max(fit.max_distance, d[i]);
    if (!(d[i] > off_distance)) continue;
    fit.off.push_back(static_cast<std::uint32_t>(i));
    if (normals.size() == points.size() && dot(normals[i], tree.closest_normal(points[i])) < 0)
      fit.off_and_against.push_back(static_cast<std::uint32_t>(i));
  }
  const KnnIndex index(points);
  std::vector<std::uint32_t> ids;
  std::vector<double> squared;
  for (const Vec3& v : mesh.vertices) {
    index.nearest(v, 1, ids, squared);
    if (squared[0] > off_distance * off_distance) ++fit.invented_vertices;
  }
  return fit;
}

std::vector<std::uint32_t> within_reach(const std::vector<Vec3>& points, const std::vector<std::uint32_t>& ids,
                                        const std::vector<std::uint32_t>& near, double reach) {
  std::vector<std::uint32_t> out;
  if (near.empty()) return out;
  std::vector<Vec3> centres;
  for (std::uint32_t i : near) centres.push_back(points[i]);
  const KnnIndex index(centres);
  std::vector<std::uint32_t> nearest;
  std::vector<double> squared;
  for (std::uint32_t i : ids) {
    index.nearest(points[i], 1, nearest, squared);
    if (squared[0] <= reach * reach) out.push_back(i);
  }
  return out;
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
