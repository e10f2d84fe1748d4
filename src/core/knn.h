// k-nearest-neighbour and radius queries on a fixed point set (CGAL kd-tree
// behind a plain interface). Queries are thread-safe once constructed.
#pragma once

#include <memory>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh::detail {

class KnnIndex {
 public:
  explicit KnnIndex(const std::vector<Vec3>& points);
  ~KnnIndex();
  KnnIndex(const KnnIndex&) = delete;
  KnnIndex& operator=(const KnnIndex&) = delete;

  /// The k nearest points to q (q itself included if it is in the set),
  /// nearest first: indices and squared distances.
  void nearest(const Vec3& q, int k, std::vector<std::uint32_t>& indices, std::vector<double>& squared_distances) const;
  /// All points within `radius` of q, in no particular order.
  void within(const Vec3& q, double radius, std::vector<std::uint32_t>& indices) const;
  std::size_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The thesis's avg (App. A.2): mean distance from each point to its k
/// nearest *other* points, on an existing index of `points`. Summed in
/// order, so the result does not depend on the thread count.
double average_spacing(const std::vector<Vec3>& points, const KnnIndex& index, int k);

/// Each point's mean distance to its k nearest other points (the terms of
/// average_spacing): the local sampling density.
std::vector<double> local_spacings(const std::vector<Vec3>& points, const KnnIndex& index, int k);

}  // namespace sharpmesh::detail
