// Internal steps of feature recovery (thesis 7.2.2, 7.2.3), CGAL-free.
#pragma once

#include <functional>
#include <vector>

#include "core/knn.h"
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

/// Parameters of edge-point sharpening (sharpen.cpp), data units.
struct SharpeningOptions {
  double radius = 0;          ///< neighbourhood of the two smooth groups
  double min_angle_deg = 15;  ///< two faces at least this far apart
  double max_residual = 0;    ///< RMS of the smooth groups' planes
  /// A smooth-groups fit this close to an input point is taken at once;
  /// farther, the plane fallback is tried first; beyond max_data_offset
  /// neither is taken.
  double close_to_data = 0;
  double max_data_offset = 0; ///< a sharpened point this close to an input point at most
  /// Plane fallback (0 tolerance: off): RANSAC inlier distance, neighbourhood,
  /// minimum inliers per plane, and how close to the edge each face's inliers must come.
  double plane_tolerance = 0;
  double plane_radius = 0;
  std::size_t min_plane_support = 8;
  double face_reach = 0;
  double plane_min_angle_deg = 30;  ///< the fallback's planes at least this far apart
  double corner_min_angle_deg = 45;  ///< corner points: the planes at least this far apart
  double corner_shift = 0;  ///< a corner point moves at most this far onto a plane pair's line
};

/// Projects each edge point onto the intersection line of the two planes
/// fitted to the smooth points around it (split by normal), or, where that
/// fails or lands off the data, of the nearest two RANSAC planes of its
/// neighbourhood that both reach their intersection; the direction becomes
/// that line's. Points without such planes are removed. Returns the number removed.
std::size_t sharpen_edge_points(const PointSet& cloud, const std::vector<PointFeature>& features, const KnnIndex& index,
                                const SharpeningOptions& options, std::vector<std::uint32_t>& edge_ids,
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
/// With `lateral_tolerance` > 0, only members within that distance of the
/// line being traced join it, and members it leaves uncovered (at least
/// `min_points` of them) are traced as further polylines; 0 traces one
/// polyline per cluster, as the thesis does.
std::vector<TracedPolyline> trace_polylines(const EdgeCluster& cluster, const std::vector<Vec3>& points,
                                            const std::vector<Vec3>& directions, int successor_k, double min_radius,
                                            double lateral_tolerance = 0, std::size_t min_points = 7);

/// Junction recovery (7.2.3): merges nearby endpoints into darts, cusps and
/// corners, closes loops, joins collinear pieces, splits polylines that pass
/// through a junction.
/// `distance_to_data`, when given, checks each meeting point: ends whose
/// lines meet farther than `max_offset` from the data stay apart, as darts.
/// `max_radius` (0: none) caps r_junc, except between two collinear ends
/// facing each other (one edge traced in two pieces). `lateral` (0: off)
/// bounds how far each end line may pass from the junction (see group_meets).
FeatureGraph connect_polylines(std::vector<TracedPolyline> polylines, double junction_factor,
                               const std::function<double(const Vec3&)>& distance_to_data = {}, double max_offset = 0,
                               double max_radius = 0, double lateral = 0);

}  // namespace sharpmesh::detail
