// Internal steps of feature recovery (thesis 7.2.2, 7.2.3), CGAL-free.
#pragma once

#include <functional>
#include <vector>

#include "pointset/knn.h"
#include "sharpmesh/features.h"

namespace sharpmesh::detail {

/// A cluster of edge points (indices into the edge-point arrays) and the
/// extremity points found beyond its ends.
struct EdgeCluster {
  std::vector<std::uint32_t> members;
  std::vector<std::uint32_t> extremities;
};

/// RMS distance from p to its k nearest other points of `index`.
double rho_k(const KnnIndex& index, const Vec3& p, int k, std::vector<std::uint32_t>& ids, std::vector<double>& d2);

/// Projects each edge point onto the intersection line of the two planes
/// fitted to the smooth points within `radius` (split by normal); the
/// direction becomes that line's. Points without two planes at least
/// `min_angle_deg` apart, or whose planes fit worse than `max_residual`
/// (RMS), are removed. Returns the number removed.
std::size_t sharpen_edge_points(const PointSet& cloud, const std::vector<PointFeature>& features, const KnnIndex& index,
                                double radius, double min_angle_deg, double max_residual, std::vector<std::uint32_t>& edge_ids,
                                std::vector<Vec3>& positions, std::vector<Vec3>& directions);

/// Algorithm 2; close pairs are within max(rho_k, min_radius).
std::vector<EdgeCluster> cluster_edge_points(const std::vector<Vec3>& points, const std::vector<Vec3>& directions, int k,
                                             double theta_deg, std::size_t min_size, double min_radius, std::size_t& pruned);

/// A polyline with the edge direction at each vertex.
struct TracedPolyline {
  std::vector<Vec3> vertices;
  std::vector<Vec3> directions;
  bool closed = false;
  double length() const;
};

/// Successor procedure from a seed in both directions, PCA smoothing, and
/// lengthening with the extremity points (7.2.3). r_p = rho_k(p), at least
/// `min_radius` (thinned clusters can be denser than the cloud's spacing).
TracedPolyline trace_polyline(const EdgeCluster& cluster, const std::vector<Vec3>& points, const std::vector<Vec3>& directions,
                              int successor_k, double min_radius);

/// Junction recovery (7.2.3): merges nearby endpoints into darts, cusps and
/// corners, closes loops, joins collinear pieces, splits polylines that pass
/// through a junction.
/// `distance_to_data`, when given, checks each meeting point: ends whose
/// lines meet farther than `max_offset` from the data stay apart, as darts.
FeatureGraph connect_polylines(std::vector<TracedPolyline> polylines, double junction_factor,
                               const std::function<double(const Vec3&)>& distance_to_data = {}, double max_offset = 0);

}  // namespace sharpmesh::detail
