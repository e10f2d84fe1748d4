// Trimming where there is no data: Poisson's implicit function is closed by
// construction, so on open scans and open models (CGAL's blade) it invents a
// closing sheet. Facets far from every input point are removed, or, to fill
// gaps in the data without extending its outer edge, those the data neither
// comes near nor surrounds.

#include <algorithm>
#include <cmath>

#include "core/mesh_graph.h"
#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/meshing.h"
#include "core/parallel.h"

namespace sharpmesh {

namespace {

/// Removes the facets `keep(a, b, c)` rejects, then unused vertices.
template <class Keep>
std::size_t remove_facets_unless(SurfaceMesh& mesh, const Keep& keep_facet) {
  std::vector<char> keep(mesh.faces.size(), 1);
  detail::parallel_for(mesh.faces.size(), [&](std::size_t f) {
    const Triangle& t = mesh.faces[f];
    keep[f] = keep_facet(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
  });
  std::vector<Triangle> faces;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (keep[f]) faces.push_back(mesh.faces[f]);
  const std::size_t removed = mesh.faces.size() - faces.size();
  if (removed > 0) detail::set_faces_and_compact(mesh, std::move(faces));
  return removed;
}

/// Whether the directions from c to `around` leave no angular gap of half a
/// turn or more in the plane orthogonal to n (c lies inside their spread).
bool surrounded(const Vec3& c, const Vec3& n, const std::vector<Vec3>& around) {
  const double length = norm(n);
  if (!(length > 0) || around.size() < 3) return false;
  const Vec3 normal = (1.0 / length) * n;
  // An orthonormal frame (u, v) of the plane.
  const Vec3 axis = std::abs(normal[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 u = (1.0 / norm(cross(normal, axis))) * cross(normal, axis);
  const Vec3 v = cross(normal, u);
  std::vector<double> angles;
  for (const Vec3& p : around) {
    const Vec3 d = p - c;
    // Only points near the facet's plane continue its surface (less than
    // 30 degrees off it): a wall or roof next to a sheet of Poisson's in
    // open space does not surround it.
    if (std::abs(dot(d, normal)) > 0.5 * norm(d)) continue;
    const double x = dot(d, u), y = dot(d, v);
    if (x != 0 || y != 0) angles.push_back(std::atan2(y, x));
  }
  if (angles.size() < 3) return false;
  std::sort(angles.begin(), angles.end());
  double widest = angles.front() + 2 * M_PI - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) widest = std::max(widest, angles[i] - angles[i - 1]);
  return widest < M_PI;
}

}  // namespace

std::size_t trim_far_from_points(SurfaceMesh& mesh, const std::vector<Vec3>& points, double max_distance) {
  if (!(max_distance > 0)) throw InvalidArgument("trim distance must be positive");
  if (points.empty() || mesh.faces.empty()) return 0;
  const detail::KnnIndex index(points);
  return remove_facets_unless(mesh, [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    index.nearest((1.0 / 3.0) * (a + b + c), 1, ids, d2);
    return !d2.empty() && d2[0] <= max_distance * max_distance;
  });
}

std::size_t trim_unless_bridging(SurfaceMesh& mesh, const std::vector<Vec3>& points, double max_distance, double bridge) {
  if (!(max_distance > 0 && bridge >= 0 && std::isfinite(max_distance) && std::isfinite(bridge)))
    throw InvalidArgument("trim: the distance must be positive and the bridging reach at least 0");
  if (points.empty() || mesh.faces.empty()) return 0;
  const detail::KnnIndex index(points);
  const bool bridging = bridge > 0 && points.size() >= 8;
  const std::vector<double> spacing = bridging ? detail::local_spacings(points, index, 6) : std::vector<double>{};
  return remove_facets_unless(mesh, [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 centroid = (1.0 / 3.0) * (a + b + c);
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    for (const Vec3* p : {&a, &b, &c, &centroid}) {
      index.nearest(*p, 1, ids, d2);
      if (d2[0] <= max_distance * max_distance) return true;
    }
    if (!bridging) return false;
    // The local spacing: a median, so that one isolated point's wide
    // spacing does not widen the reach.
    index.nearest(centroid, 8, ids, d2);
    std::vector<double> local;
    for (std::uint32_t i : ids) local.push_back(spacing[i]);
    std::nth_element(local.begin(), local.begin() + static_cast<std::ptrdiff_t>(local.size() / 2), local.end());
    std::vector<std::uint32_t> inside;
    index.within(centroid, bridge * local[local.size() / 2], inside);
    std::vector<Vec3> around;
    for (std::uint32_t i : inside) around.push_back(points[i]);
    return surrounded(centroid, cross(b - a, c - a), around);
  });
}

std::size_t remove_components_off_points(SurfaceMesh& mesh, const std::vector<Vec3>& points, double max_distance) {
  if (!(max_distance > 0) || !std::isfinite(max_distance)) throw InvalidArgument("component removal: the distance must be positive");
  if (points.empty() || mesh.faces.empty()) return 0;
  detail::DisjointSets components(mesh.vertices.size());
  for (const Triangle& t : mesh.faces)
    for (int k = 1; k < 3; ++k) components.unite(t[0], t[k]);
  auto root = [&](std::uint32_t v) { return static_cast<std::uint32_t>(components.find(v)); };
  const detail::KnnIndex index(points);
  std::vector<double> distance(mesh.vertices.size(), 0.0);
  detail::parallel_for(mesh.vertices.size(), [&](std::size_t v) {
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    index.nearest(mesh.vertices[v], 1, ids, d2);
    distance[v] = d2.empty() ? 0.0 : std::sqrt(d2[0]);
  });
  std::vector<std::vector<double>> by_component(mesh.vertices.size());
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const Triangle& t : mesh.faces)
    for (std::uint32_t v : t) used[v] = 1;
  for (std::uint32_t v = 0; v < used.size(); ++v)
    if (used[v]) by_component[root(v)].push_back(distance[v]);
  std::vector<char> off(mesh.vertices.size(), 0);
  std::size_t kept_components = 0;
  for (std::uint32_t r = 0; r < by_component.size(); ++r) {
    std::vector<double>& d = by_component[r];
    if (d.empty()) continue;
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
    off[r] = d[d.size() / 2] > max_distance;
    kept_components += !off[r];
  }
  if (kept_components == 0) return 0;  // nothing would be left: the caller's checks report it
  std::vector<Triangle> faces;
  for (const Triangle& t : mesh.faces)
    if (!off[root(t[0])]) faces.push_back(t);
  const std::size_t removed = mesh.faces.size() - faces.size();
  if (removed > 0) detail::set_faces_and_compact(mesh, std::move(faces));
  return removed;
}

std::size_t count_boundary_edges(const SurfaceMesh& mesh) {
  std::size_t count = 0;
  for (const auto& e : detail::edge_incidences(mesh)) count += e.faces.size() == 1;
  return count;
}

}  // namespace sharpmesh
