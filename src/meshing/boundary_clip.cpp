// Open surfaces, beyond the thesis (8.2): the trim removes facets whose
// centre is far from the data, but the facets left along the boundary
// still overhang the data by up to the trim distance. Here the band of
// facets between the boundary and the data is cut along the level set
// "distance to the nearest input point = clip distance", so the boundary
// follows the data's own edge.
#include <algorithm>
#include <cmath>
#include <queue>
#include <unordered_map>

#include "core/mesh_graph.h"
#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {
namespace {

double distance_to_points(const detail::KnnIndex& index, const Vec3& p) {
  std::vector<std::uint32_t> ids;
  std::vector<double> d2;
  index.nearest(p, 1, ids, d2);
  return d2.empty() ? 0 : std::sqrt(d2[0]);
}

}  // namespace

std::size_t clip_boundary_to_points(SurfaceMesh& mesh, const std::vector<Vec3>& points, double min_distance) {
  if (!(min_distance > 0)) throw InvalidArgument("clip distance must be positive");
  if (points.empty() || mesh.faces.empty()) return 0;
  const auto edges = detail::edge_incidences(mesh);
  std::vector<std::vector<std::uint32_t>> neighbours(mesh.faces.size());
  std::vector<char> on_boundary(mesh.faces.size(), 0);
  for (const auto& e : edges) {
    if (e.faces.size() == 1) on_boundary[e.faces[0]] = 1;
    if (e.faces.size() != 2) continue;
    neighbours[e.faces[0]].push_back(e.faces[1]);
    neighbours[e.faces[1]].push_back(e.faces[0]);
  }
  if (std::none_of(on_boundary.begin(), on_boundary.end(), [](char b) { return b != 0; })) return 0;

  const detail::KnnIndex index(points);
  std::vector<double> dist(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) dist[v] = distance_to_points(index, mesh.vertices[v]);
  // Noise moves the surface away from the points it was fitted to: the
  // cut is never closer than twice the median vertex-to-data distance.
  std::vector<double> sorted = dist;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double clip_distance = std::max(min_distance, 2 * sorted[sorted.size() / 2]);
  auto outside = [&](std::uint32_t v) { return dist[v] > clip_distance; };
  auto has_outside = [&](std::size_t f) {
    const Triangle& t = mesh.faces[f];
    return outside(t[0]) || outside(t[1]) || outside(t[2]);
  };

  // The band: facets with a vertex beyond the clip distance, connected to
  // the boundary through such facets. Sparse spots inside stay untouched.
  std::vector<char> in_band(mesh.faces.size(), 0);
  std::queue<std::size_t> queue;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (on_boundary[f] && has_outside(f)) in_band[f] = 1, queue.push(f);
  if (queue.empty()) return 0;
  while (!queue.empty()) {
    const std::size_t f = queue.front();
    queue.pop();
    for (std::uint32_t g : neighbours[f])
      if (!in_band[g] && has_outside(g)) in_band[g] = 1, queue.push(g);
  }

  // Crossing of an edge from an inside to an outside vertex, by bisection
  // on the true distance; shared by the two facets of the edge.
  std::unordered_map<std::uint64_t, std::uint32_t> crossing_of;
  auto crossing = [&](std::uint32_t inside, std::uint32_t out) {
    const std::uint64_t key = detail::edge_key(inside, out);
    if (auto it = crossing_of.find(key); it != crossing_of.end()) return it->second;
    Vec3 lo = mesh.vertices[inside], hi = mesh.vertices[out];
    for (int i = 0; i < 24; ++i) {
      const Vec3 mid = 0.5 * (lo + hi);
      (distance_to_points(index, mid) > clip_distance ? hi : lo) = mid;
    }
    const auto id = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back(0.5 * (lo + hi));
    crossing_of.emplace(key, id);
    return id;
  };

  std::vector<Triangle> faces;
  faces.reserve(mesh.faces.size());
  std::size_t clipped = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle t = mesh.faces[f];
    if (!in_band[f]) {
      faces.push_back(t);
      continue;
    }
    ++clipped;
    // The part of the facet within the clip distance: walk its corners in
    // order, keeping inside corners and the crossings of mixed edges.
    std::vector<std::uint32_t> polygon;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (!outside(a)) polygon.push_back(a);
      if (outside(a) != outside(b)) polygon.push_back(outside(a) ? crossing(b, a) : crossing(a, b));
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) faces.push_back({polygon[0], polygon[k], polygon[k + 1]});
  }
  detail::set_faces_and_compact(mesh, std::move(faces));
  return clipped;
}

}  // namespace sharpmesh
