// Edge-point sharpening, beyond the thesis. Edge points (Algorithm 1) lie on
// the faces beside a sharp edge, in a band as wide as the convolution
// radius, so polylines through them run inside convex edges and outside
// concave ones: the "gap" of thesis 7.5 (Fig. 7.18). Around each edge point,
// the smooth points split into two groups by normal; a plane fitted to each
// group gives the edge as their intersection line, onto which the point is
// projected. Averaging over whole patches also averages noise out.
//
// Two failures of that fit are caught. Next to a face narrower than the
// band (a chamfer, the rim of a flange) no point of the narrow face is
// smooth, so the two planes found are the wide faces on either side and
// their intersection is a virtual corner off the data by about half the
// chamfer's width (couplingdown 50k: polylines 1-1.5 spacings off, and the
// mesh followed them). And two parallel faces (both sides of a flange) fall
// into one group. So a fit is taken at once only when it lies close to the
// data; otherwise the point is fitted again by sequential RANSAC planes on
// the positions of all its neighbours, which finds the narrow face once the
// wide ones are removed, and the nearest intersection of two of those
// planes that both faces reach and that lies on the data is the edge. The
// first fit is kept when no plane pair qualifies and it is not clearly off
// the data; otherwise the point is dropped.
//
// Corner points (FeatureOptions::fit_corner_points) go straight to the
// RANSAC planes, and only a pair at least corner_min_angle_deg apart whose
// line passes within corner_shift is taken: next to a corner and on faces
// narrower than r, the convolved VCM sees three patches, yet most such
// points lie on one edge's two faces.
#include <Eigen/Eigenvalues>


#include <cmath>

#include "core/plane_fit.h"
#include "features/feature_graph_builder.h"
#include "core/parallel.h"

namespace sharpmesh::detail {
namespace {

Eigen::Vector3d eig(const Vec3& v) { return {v[0], v[1], v[2]}; }

/// Closest point to q on the intersection line of two planes: minimises
/// |x - q|^2 subject to na.x = na.ca and nb.x = nb.cb (x = q + s na + t nb).
Eigen::Vector3d closest_on_intersection(const Plane& pa, const Plane& pb, const Eigen::Vector3d& q) {
  const double ra = pa.normal.dot(pa.point - q), rb = pb.normal.dot(pb.point - q), c = pa.normal.dot(pb.normal);
  const double det = 1 - c * c;
  const double s = (ra - c * rb) / det, t = (rb - c * ra) / det;
  return q + s * pa.normal + t * pb.normal;
}

struct EdgeFit {
  Eigen::Vector3d position = Eigen::Vector3d::Zero(), direction = Eigen::Vector3d::Zero();
};

enum class GroupFit { Fitted, FewSmooth, OnePlane, Residual, Angle };

/// The thesis-side fit: two groups of smooth normals (sign-invariant 2-means).
GroupFit fit_smooth_groups(const PointSet& cloud, const std::vector<PointFeature>& features, const std::vector<std::uint32_t>& ids,
                       const Vec3& p, const SharpeningOptions& o, EdgeFit& fit) {
  const double cos_min = std::cos(o.min_angle_deg * M_PI / 180.0);
  std::vector<std::uint32_t> smooth;
  for (std::uint32_t i : ids)
    if (features[i].type == PointClass::Smooth) smooth.push_back(i);
  if (smooth.size() < 12) return GroupFit::FewSmooth;
  // Seeds of the two groups: the two smooth normals farthest apart.
  Eigen::Vector3d a = eig(features[smooth[0]].normal), b = a;
  double worst = 1;
  for (std::uint32_t i : smooth) {
    const double c = std::abs(a.dot(eig(features[i].normal)));
    if (c < worst) {
      worst = c;
      b = eig(features[i].normal);
    }
  }
  if (worst > cos_min) return GroupFit::OnePlane;  // one plane only: not a sharp edge
  std::vector<Eigen::Vector3d> group[2];
  for (int round = 0; round < 2; ++round) {
    group[0].clear();
    group[1].clear();
    Eigen::Matrix3d sum[2] = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
    for (std::uint32_t i : smooth) {
      const Eigen::Vector3d nrm = eig(features[i].normal);
      const int g = std::abs(nrm.dot(a)) >= std::abs(nrm.dot(b)) ? 0 : 1;
      group[g].push_back(eig(cloud.points[i]));
      sum[g] += nrm * nrm.transpose();
    }
    for (int g = 0; g < 2; ++g) {
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
      solver.computeDirect(sum[g]);
      (g == 0 ? a : b) = solver.eigenvectors().col(2);
    }
  }
  Plane pa, pb;
  double rms_a = 0, rms_b = 0;
  if (!fit_plane(group[0], pa, rms_a) || !fit_plane(group[1], pb, rms_b)) return GroupFit::FewSmooth;
  // Near a corner three or more patches meet and two planes do not fit:
  // such points are left out, and junction recovery extends the polylines there.
  if (std::max(rms_a, rms_b) > o.max_residual) return GroupFit::Residual;
  Eigen::Vector3d d = pa.normal.cross(pb.normal);
  const double sin_angle = d.norm();
  if (sin_angle < std::sin(o.min_angle_deg * M_PI / 180.0)) return GroupFit::Angle;
  fit.direction = d / sin_angle;
  fit.position = closest_on_intersection(pa, pb, eig(p));
  return GroupFit::Fitted;
}

/// Deterministic pseudo-random numbers (the result must not depend on the
/// thread count, so each point seeds its own generator).
struct SplitMix {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
};

struct FoundPlane {
  Plane plane;
  std::vector<Eigen::Vector3d> inliers;
};

/// Up to four planes by sequential RANSAC (random triples, most inliers
/// within `tolerance`, refitted by least squares), each with at least
/// `min_support` inliers, which are removed before the next one is sought.
std::vector<FoundPlane> sequential_planes(std::vector<Eigen::Vector3d> remaining, double tolerance, std::size_t min_support,
                                          std::uint64_t seed) {
  constexpr int kPlanes = 4, kTrials = 48;
  SplitMix rng{seed};
  std::vector<FoundPlane> planes;
  while (static_cast<int>(planes.size()) < kPlanes && remaining.size() >= min_support) {
    const std::size_t n = remaining.size();
    std::size_t best_count = 0;
    Eigen::Vector3d best_normal = Eigen::Vector3d::Zero(), best_point = Eigen::Vector3d::Zero();
    for (int trial = 0; trial < kTrials; ++trial) {
      const Eigen::Vector3d& a = remaining[rng.next() % n];
      const Eigen::Vector3d& b = remaining[rng.next() % n];
      const Eigen::Vector3d& c = remaining[rng.next() % n];
      Eigen::Vector3d normal = (b - a).cross(c - a);
      const double area2 = normal.norm();
      // Skip near-collinear triples: a tilted plane through a thin strip.
      if (!(area2 > 0.5 * tolerance * std::max((b - a).norm(), (c - a).norm()))) continue;
      normal /= area2;
      std::size_t count = 0;
      for (const Eigen::Vector3d& x : remaining) count += std::abs(normal.dot(x - a)) <= tolerance;
      if (count > best_count) {
        best_count = count;
        best_normal = normal;
        best_point = a;
      }
    }
    if (best_count < min_support) break;
    FoundPlane found;
    for (int refit = 0; refit < 2; ++refit) {
      found.inliers.clear();
      for (const Eigen::Vector3d& x : remaining)
        if (std::abs(best_normal.dot(x - best_point)) <= tolerance) found.inliers.push_back(x);
      double rms = 0;
      if (!fit_plane(found.inliers, found.plane, rms)) break;
      best_normal = found.plane.normal;
      best_point = found.plane.point;
    }
    if (found.inliers.size() < min_support) break;
    std::vector<Eigen::Vector3d> rest;
    rest.reserve(remaining.size() - found.inliers.size());
    for (const Eigen::Vector3d& x : remaining)
      if (std::abs(found.plane.normal.dot(x - found.plane.point)) > tolerance) rest.push_back(x);
    if (rest.size() == remaining.size()) break;
    remaining = std::move(rest);
    planes.push_back(std::move(found));
  }
  return planes;
}

/// Distance from x to the nearest of the points.
double nearest_distance(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& x) {
  double best = INFINITY;
  for (const Eigen::Vector3d& q : pts) best = std::min(best, (q - x).squaredNorm());
  return std::sqrt(best);
}

}  // namespace

std::size_t sharpen_edge_points(const PointSet& cloud, const std::vector<PointFeature>& features, const KnnIndex& index,
                                const SharpeningOptions& o, std::vector<std::uint32_t>& edge_ids, std::vector<Vec3>& positions,
                                std::vector<Vec3>& directions) {
  const std::size_t n = edge_ids.size();
  std::vector<char> keep(n, 0);
  const double sin_min = std::sin(o.plane_min_angle_deg * M_PI / 180.0);
  const double sin_corner = std::sin(o.corner_min_angle_deg * M_PI / 180.0);
  detail::parallel_chunks(n, 64, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> ids, nearest;
    std::vector<double> d2;
    auto data_offset = [&](const Eigen::Vector3d& x) {
      index.nearest({x(0), x(1), x(2)}, 1, nearest, d2);
      return d2.empty() ? INFINITY : std::sqrt(d2[0]);
    };
    for (std::size_t e = begin; e != end; ++e) {
      const Vec3& p = cloud.points[edge_ids[e]];
      const Eigen::Vector3d q = eig(p);
      EdgeFit fit, primary;
      const bool corner = features[edge_ids[e]].type == PointClass::Corner;
      const double max_shift = corner ? o.corner_shift : o.plane_radius;
      bool fitted = false;
      if (!corner) {  // corner points skip the smooth groups: they see three patches
        index.within(p, o.radius, ids);
        std::sort(ids.begin(), ids.end());
        fitted = fit_smooth_groups(cloud, features, ids, p, o, primary) == GroupFit::Fitted && (primary.position - q).norm() <= o.radius;
      }
      const double primary_offset = fitted ? data_offset(primary.position) : INFINITY;
      bool found = primary_offset <= o.close_to_data;
      if (found) fit = primary;
      if (!found && o.plane_tolerance > 0) {
        index.within(p, o.plane_radius, ids);
        std::sort(ids.begin(), ids.end());
        std::vector<Eigen::Vector3d> local;
        local.reserve(ids.size());
        for (std::uint32_t i : ids) local.push_back(eig(cloud.points[i]));
        const std::vector<FoundPlane> planes = sequential_planes(local, o.plane_tolerance, o.min_plane_support, edge_ids[e]);
        double best = INFINITY;
        for (std::size_t a = 0; a < planes.size(); ++a)
          for (std::size_t b = a + 1; b < planes.size(); ++b) {
            Eigen::Vector3d d = planes[a].plane.normal.cross(planes[b].plane.normal);
            const double sin_angle = d.norm();
            if (sin_angle < (corner ? sin_corner : sin_min)) continue;
            const Eigen::Vector3d x = closest_on_intersection(planes[a].plane, planes[b].plane, q);
            const double offset = (x - q).norm();
            if (offset >= best || offset > max_shift) continue;
            // Both faces reach the line there (their intersection is an edge of
            // the data, not a virtual one), and the line lies on the data.
            if (nearest_distance(planes[a].inliers, x) > o.face_reach || nearest_distance(planes[b].inliers, x) > o.face_reach) continue;
            if (data_offset(x) > o.max_data_offset) continue;
            best = offset;
            fit.position = x;
            fit.direction = d / sin_angle;
            found = true;
          }
      }
      // No plane pair: the smooth groups' line, unless it is clearly off the data.
      if (!found && primary_offset <= o.max_data_offset) {
        fit = primary;
        found = true;
      }
      if (!found) continue;
      positions[e] = {fit.position(0), fit.position(1), fit.position(2)};
      directions[e] = {fit.direction(0), fit.direction(1), fit.direction(2)};
      keep[e] = 1;
    }
  });
  std::size_t out = 0;
  for (std::size_t e = 0; e < n; ++e) {
    if (!keep[e]) continue;
    edge_ids[out] = edge_ids[e];
    positions[out] = positions[e];
    directions[out] = directions[e];
    ++out;
  }
  const std::size_t dropped = n - out;
  edge_ids.resize(out);
  positions.resize(out);
  directions.resize(out);
  return dropped;
}

}  // namespace sharpmesh::detail
