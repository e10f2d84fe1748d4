// Beyond the thesis: the facets along a protected edge. Their edge
// vertices sit on the sharp polyline, but their third vertex lies on the
// Poisson surface, which is rounded (and overshoots) within a few spacings
// of the edge, so these facets lean by several degrees (the gap of thesis
// 7.5, seen from the other side). Each such vertex is projected onto the
// plane fitted to the input points around it whose normals agree with the
// mesh there, i.e. onto the face it belongs to.

#include <algorithm>
#include <cmath>
#include <map>

#include "core/plane_fit.h"
#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/meshing.h"
#include "core/parallel.h"

namespace sharpmesh {

std::size_t flatten_next_to_features(SurfaceMesh& mesh, const std::vector<Polyline>& feature_edges,
                                     const std::vector<Vec3>& points, const std::vector<Vec3>& normals,
                                     const FlatteningOptions& options) {
  if (!(options.radius > 0) || !(options.max_move >= 0) || !std::isfinite(options.radius))
    throw InvalidArgument("flattening radius must be positive");
  if (normals.size() != points.size()) throw InvalidArgument("flattening needs one normal per point");
  if (feature_edges.empty() || points.empty() || mesh.faces.empty()) return 0;

  std::map<std::array<double, 3>, std::uint32_t> index_of;
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) index_of.emplace(mesh.vertices[v], v);
  std::vector<char> on_feature(mesh.vertices.size(), 0);
  for (const Polyline& line : feature_edges)
    for (const Vec3& p : line)
      if (auto it = index_of.find(p); it != index_of.end()) on_feature[it->second] = 1;

  // Area-weighted vertex normals, and the vertices sharing a facet with a feature vertex.
  std::vector<Vec3> vertex_normal(mesh.vertices.size(), Vec3{0, 0, 0});
  std::vector<char> candidate(mesh.vertices.size(), 0);
  for (const Triangle& t : mesh.faces) {
    const Vec3 n = cross(mesh.vertices[t[1]] - mesh.vertices[t[0]], mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const bool touches = on_feature[t[0]] || on_feature[t[1]] || on_feature[t[2]];
    for (std::uint32_t v : t) {
      vertex_normal[v] = vertex_normal[v] + n;
      if (touches && !on_feature[v]) candidate[v] = 1;
    }
  }
  std::vector<std::uint32_t> moving;
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v)
    if (candidate[v] && norm(vertex_normal[v]) > 0) moving.push_back(v);

  const detail::KnnIndex index(points);
  const double cos_max = std::cos(options.max_angle_deg * M_PI / 180.0);
  std::vector<Vec3> target(moving.size());
  std::vector<char> moved(moving.size(), 0);
  detail::parallel_for(moving.size(), [&](std::size_t m) {
    const Vec3& p = mesh.vertices[moving[m]];
    const Vec3 n = (1.0 / norm(vertex_normal[moving[m]])) * vertex_normal[moving[m]];
    std::vector<std::uint32_t> ids;
    index.within(p, options.radius, ids);
    std::sort(ids.begin(), ids.end());
    std::vector<Eigen::Vector3d> face;
    for (std::uint32_t i : ids)
      if (std::abs(dot(normals[i], n)) >= cos_max * norm(normals[i])) face.emplace_back(points[i][0], points[i][1], points[i][2]);
    detail::Plane plane;
    double rms = 0;
    if (!detail::fit_plane(face, plane, rms) || rms > options.max_residual) return;
    const Eigen::Vector3d q(p[0], p[1], p[2]);
    const double offset = (q - plane.point).dot(plane.normal);
    if (std::abs(offset) > options.max_move) return;
    const Eigen::Vector3d r = q - offset * plane.normal;
    target[m] = {r.x(), r.y(), r.z()};
    moved[m] = 1;
  });
  // A move that turns one of the vertex's facets by more than 30 degrees
  // (a coarse mesh, where the plane is far from the facets) is dropped, so
  // no facet folds over.
  std::vector<std::vector<std::uint32_t>> faces_of(mesh.vertices.size());
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
    for (std::uint32_t v : mesh.faces[f])
      if (candidate[v]) faces_of[v].push_back(f);
  const double cos_turn = std::cos(30.0 * M_PI / 180.0);
  auto facet_normal = [&](const Triangle& t, std::uint32_t v, const Vec3& at) {
    auto position = [&](std::uint32_t w) { return w == v ? at : mesh.vertices[w]; };
    return cross(position(t[1]) - position(t[0]), position(t[2]) - position(t[0]));
  };
  std::size_t count = 0;
  for (std::size_t m = 0; m < moving.size(); ++m) {
    if (!moved[m]) continue;
    const std::uint32_t v = moving[m];
    const bool folds = std::any_of(faces_of[v].begin(), faces_of[v].end(), [&](std::uint32_t f) {
      const Vec3 before = facet_normal(mesh.faces[f], v, mesh.vertices[v]);
      const Vec3 after = facet_normal(mesh.faces[f], v, target[m]);
      return !(dot(before, after) > cos_turn * norm(before) * norm(after));
    });
    if (folds) continue;
    mesh.vertices[v] = target[m];
    ++count;
  }
  return count;
}

}  // namespace sharpmesh
