#include "pointset/winding_number.h"

#include <algorithm>
#include <cmath>

namespace sharpmesh::detail {
namespace {

constexpr std::uint32_t kLeafSize = 16;
constexpr int kMaxDepth = 24;
// A cluster is one dipole when the query is this many of its radii away:
// Barnes and Hut's opening criterion; a larger ratio hardly changes the
// winding numbers of an inverted region and costs more time.
constexpr double kFarRatio = 2;
constexpr double kInverseFourPi = 0.25 / M_PI;

double softened_term(const Vec3& p, const Vec3& n, double area, const Vec3& q, double softening2) {
  const Vec3 d = p - q;
  const double r2 = dot(d, d) + softening2;
  return area * dot(d, n) / (r2 * std::sqrt(r2));
}

}  // namespace

WindingNumber::WindingNumber(const std::vector<Vec3>& points, const std::vector<Vec3>& normals,
                             const std::vector<double>& areas, double softening)
    : points_(points), normals_(normals), areas_(areas), softening2_(softening * softening), order_(points.size()) {
  for (std::uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  nodes_.reserve(2 * points.size() / kLeafSize + 16);
  if (!points.empty()) build(0, static_cast<std::uint32_t>(points.size()), 0);
}

std::uint32_t WindingNumber::build(std::uint32_t begin, std::uint32_t end, int depth) {
  const std::uint32_t id = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Node node;
  node.begin = begin, node.end = end;
  double area = 0;
  Vec3 lo = points_[order_[begin]], hi = lo;
  for (std::uint32_t k = begin; k < end; ++k) {
    const std::uint32_t i = order_[k];
    area += areas_[i];
    node.centre = node.centre + areas_[i] * points_[i];
    node.dipole = node.dipole + areas_[i] * normals_[i];
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], points_[i][a]), hi[a] = std::max(hi[a], points_[i][a]);
  }
  node.centre = area > 0 ? (1.0 / area) * node.centre : 0.5 * (lo + hi);
  for (std::uint32_t k = begin; k < end; ++k) node.radius = std::max(node.radius, distance(points_[order_[k]], node.centre));
  if (end - begin > kLeafSize && depth < kMaxDepth && node.radius > 0) {
    // Split at the box centre into octants (in place).
    const Vec3 mid = 0.5 * (lo + hi);
    auto octant = [&](std::uint32_t i) {
      return (points_[i][0] > mid[0] ? 1 : 0) | (points_[i][1] > mid[1] ? 2 : 0) | (points_[i][2] > mid[2] ? 4 : 0);
    };
    std::stable_sort(order_.begin() + begin, order_.begin() + end,
                     [&](std::uint32_t a, std::uint32_t b) { return octant(a) < octant(b); });
    std::vector<std::uint32_t> children;
    for (std::uint32_t k = begin; k < end;) {
      std::uint32_t stop = k;
      const int o = octant(order_[k]);
      while (stop < end && octant(order_[stop]) == o) ++stop;
      children.push_back(build(k, stop, depth + 1));
      k = stop;
    }
    // Children were appended depth-first: record them by index.
    node.first_child = static_cast<std::uint32_t>(child_lists_.size());
    node.child_count = static_cast<std::uint32_t>(children.size());
    child_lists_.insert(child_lists_.end(), children.begin(), children.end());
  }
  nodes_[id] = node;
  return id;
}

double WindingNumber::at(const Vec3& q) const {
  if (nodes_.empty()) return 0;
  double sum = 0;
  std::uint32_t stack[8 * kMaxDepth + 8];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    const Vec3 d = node.centre - q;
    const double r2 = dot(d, d);
    if (r2 > kFarRatio * kFarRatio * node.radius * node.radius) {
      sum += dot(d, node.dipole) / (r2 * std::sqrt(r2));
    } else if (node.child_count == 0) {
      for (std::uint32_t k = node.begin; k < node.end; ++k) {
        const std::uint32_t i = order_[k];
        sum += softened_term(points_[i], normals_[i], areas_[i], q, softening2_);
      }
    } else {
      for (std::uint32_t c = 0; c < node.child_count; ++c) stack[top++] = child_lists_[node.first_child + c];
    }
  }
  return sum * kInverseFourPi;
}

double winding_number_of(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, const std::vector<double>& areas,
                         const std::vector<std::uint32_t>& ids, const Vec3& q, double softening) {
  double sum = 0;
  for (std::uint32_t i : ids) sum += softened_term(points[i], normals[i], areas[i], q, softening * softening);
  return sum * kInverseFourPi;
}

}  // namespace sharpmesh::detail
