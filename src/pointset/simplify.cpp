// Point-set simplification (App. A.5): grid clustering and random removal;
// beyond the thesis, thinning of near-coincident points.
#include <CGAL/grid_simplify_point_set.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "core/cgal_bridge.h"
#include "core/knn.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh {

std::size_t grid_simplify(PointSet& points, double cell_size) {
  if (!(cell_size > 0) || !std::isfinite(cell_size))
    throw InvalidArgument("grid simplification: cell size must be positive (got " + format_number(cell_size) + ")");
  // Points at one location (a single point included) fill one cell; the
  // set's check below refuses them as degenerate input.
  const bool finite = std::all_of(points.points.begin(), points.points.end(), [](const Vec3& p) {
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  });
  const double diagonal = finite && !points.empty() ? bounding_box(points.points).diagonal() : 0.0;
  if (finite && !points.empty() && diagonal == 0) {
    std::vector<bool> first(points.size(), false);
    first[0] = true;
    points.keep_if(first);
    return first.size() - 1;
  }
  check_point_set(points, 1, "grid simplification");
  if (diagonal / cell_size > 1e7)
    throw InvalidArgument("grid simplification: cell size " + format_number(cell_size) + " is below 1e-7 of the diagonal");
  const std::vector<detail::Point3> cgal_points = detail::to_cgal(points.points);
  std::vector<std::uint32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0u);
  const detail::IndexedPointMap position{&cgal_points};
  auto first_removed = CGAL::grid_simplify_point_set(order, cell_size, CGAL::parameters::point_map(position));
  std::vector<bool> keep(points.size(), true);
  for (auto it = first_removed; it != order.end(); ++it) keep[*it] = false;
  const std::size_t removed = static_cast<std::size_t>(order.end() - first_removed);
  points.keep_if(keep);
  return removed;
}

std::size_t thin_close_points(PointSet& points, double min_distance) {
  check_point_set(points, 1, "thinning");
  if (!(min_distance > 0) || !std::isfinite(min_distance))
    throw InvalidArgument("thinning: minimum distance must be positive (got " + format_number(min_distance) + ")");
  const detail::KnnIndex index(points.points);
  std::vector<bool> keep(points.size(), true);
  std::vector<std::uint32_t> near;
  std::size_t removed = 0;
  // In input order: a kept point removes the later points within reach, so
  // kept points are at least min_distance apart and the result is the same
  // on every run.
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!keep[i]) continue;
    index.within(points.points[i], min_distance, near);
    for (std::uint32_t j : near)
      if (j > i && keep[j] && distance(points.points[i], points.points[j]) < min_distance) keep[j] = false, ++removed;
  }
  if (removed > 0) points.keep_if(keep);
  return removed;
}

std::size_t remove_duplicate_points(PointSet& points) {
  std::vector<std::uint32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0u);
  // Stable: among equal positions the first in file order comes first and stays.
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return points.points[a] < points.points[b]; });
  std::vector<bool> keep(points.size(), true);
  std::size_t removed = 0;
  for (std::size_t i = 1; i < order.size(); ++i)
    if (points.points[order[i]] == points.points[order[i - 1]]) keep[order[i]] = false, ++removed;
  if (removed > 0) points.keep_if(keep);
  return removed;
}

// CGAL's random_simplify_point_set draws from std::rand, which cannot be seeded
// per call; this keeps the same semantics with a seeded generator so that
// results are reproducible.
std::size_t random_simplify(PointSet& points, double percentage, std::uint64_t seed) {
  if (!(percentage >= 0 && percentage <= 100))
    throw InvalidArgument("random simplification: percentage must be in [0, 100] (got " + format_number(percentage) + ")");
  const std::size_t n = points.size();
  const std::size_t remove = static_cast<std::size_t>(std::floor(n * percentage / 100.0));
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < remove; ++i) {  // partial Fisher-Yates: the first `remove` are dropped
    std::uniform_int_distribution<std::size_t> pick(i, n - 1);
    std::swap(order[i], order[pick(rng)]);
  }
  std::vector<bool> keep(n, true);
  for (std::size_t i = 0; i < remove; ++i) keep[order[i]] = false;
  points.keep_if(keep);
  return remove;
}

}  // namespace sharpmesh
