// Distance queries to a triangle mesh (CGAL AABB tree behind a plain
// interface). Queries are thread-safe once constructed.
#pragma once

#include <memory>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh::detail {

class TriangleDistance {
 public:
  explicit TriangleDistance(const SurfaceMesh& mesh);
  ~TriangleDistance();
  TriangleDistance(const TriangleDistance&) = delete;
  TriangleDistance& operator=(const TriangleDistance&) = delete;
  double squared_distance(const Vec3& q) const;
  Vec3 closest_point(const Vec3& q) const;
  /// Unit normal (by the vertex order) of the triangle closest to q.
  Vec3 closest_normal(const Vec3& q) const;
  /// Distances (not squared) of many points, in parallel.
  std::vector<double> distances(const std::vector<Vec3>& queries) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sharpmesh::detail
