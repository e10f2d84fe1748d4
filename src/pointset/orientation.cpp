// Normal orientation by a minimum spanning tree (Hoppe et al. 1992; thesis
// App. A.8) on a Riemannian graph whose weights also penalise edges that
// leave the tangent planes. CGAL's mst_orient_normals weighs an edge by
// 1 - |n_i . n_j| only, so two points facing each other across a thin wall
// (parallel normals) are cheap neighbours and a flip spreads through them:
// 6% of couplingdown's normals (50k points, k = 18) end inverted. Here
// w = 1 - |n_i . n_j| + max(|u . n_i|, |u . n_j|), u the unit edge direction:
// crossing a wall costs about 1 and is taken only when nothing else connects.
#include <algorithm>
#include <cmath>
#include <queue>

#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh {
namespace {

struct Edge {
  std::uint32_t to;
  float weight;
};

}  // namespace

std::size_t orient_normals_tangent_mst(PointSet& points, int k, const Progress& progress) {
  return orient_normals_tangent_mst(points, k, {}, progress);
}

std::size_t orient_normals_tangent_mst(PointSet& points, int k, const std::vector<signed char>& anchors, const Progress& progress) {
  check_point_set(points, 4, "normal orientation");
  NormalOrientationOptions{k, false}.check(points.size());
  if (!points.has_normals()) throw InvalidArgument("normal orientation: the points have no normals to orient");
  const std::size_t n = points.size();
  if (!anchors.empty() && anchors.size() != n) throw InvalidArgument("normal orientation: one anchor vote per point, or none");
  report_progress(progress, "normal orientation", 0.0);
  const detail::KnnIndex index(points.points);
  std::vector<std::vector<Edge>> graph(n);
  std::vector<std::uint32_t> neighbours;
  std::vector<double> squared;
  auto weight = [&](std::uint32_t i, std::uint32_t j) {
    const Vec3& a = points.normals[i];
    const Vec3& b = points.normals[j];
    Vec3 u = points.points[j] - points.points[i];
    const double length = norm(u);
    const double steep = length > 0 ? std::max(std::abs(dot(u, a)), std::abs(dot(u, b))) / length : 1.0;
    return static_cast<float>(1.0 - std::abs(dot(a, b)) + steep);
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    index.nearest(points.points[i], k + 1, neighbours, squared);
    for (std::uint32_t j : neighbours) {
      if (j == i) continue;
      const float w = weight(i, j);
      graph[i].push_back({j, w});
      graph[j].push_back({i, w});  // symmetric: j may not list i among its neighbours
    }
  }
  report_progress(progress, "normal orientation", 0.4);
  // Prim's algorithm: from every anchored point at once (its sign decided
  // by its vote), then from the highest point of each component no anchor
  // reaches, whose normal is turned upwards (as CGAL does for its single seed).
  std::vector<char> done(n, 0);
  using Item = std::pair<float, std::pair<std::uint32_t, std::uint32_t>>;  // weight, (from, to)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  auto grow = [&]() {
    while (!queue.empty()) {
      const auto [from, to] = queue.top().second;
      queue.pop();
      if (done[to]) continue;
      done[to] = 1;
      if (dot(points.normals[from], points.normals[to]) < 0) points.normals[to] = -1.0 * points.normals[to];
      for (const Edge& e : graph[to])
        if (!done[e.to]) queue.push({e.weight, {to, e.to}});
    }
  };
  std::size_t components = 0;
  for (std::uint32_t i = 0; i < anchors.size(); ++i) {
    if (anchors[i] == 0) continue;
    if (anchors[i] < 0) points.normals[i] = -1.0 * points.normals[i];
    done[i] = 1;
    for (const Edge& e : graph[i]) queue.push({e.weight, {i, e.to}});
  }
  if (!queue.empty()) {
    ++components;
    grow();
  }
  std::vector<std::uint32_t> order(n);
  for (std::uint32_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return points.points[a][2] > points.points[b][2]; });
  for (std::uint32_t seed : order) {
    if (done[seed]) continue;
    ++components;
    if (points.normals[seed][2] < 0) points.normals[seed] = -1.0 * points.normals[seed];
    done[seed] = 1;
    for (const Edge& e : graph[seed]) queue.push({e.weight, {seed, e.to}});
    grow();
  }
  report_progress(progress, "normal orientation", 1.0);
  return components;
}

}  // namespace sharpmesh
