// Polyline recovery from a cluster (thesis 7.2.3): successor procedure,
// PCA smoothing of vertices and directions, lengthening with extremities.
// Beyond the thesis, a cluster may hold several parallel edges (joined
// through a short edge between them); each is traced as its own polyline.
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

#include "features/feature_graph_builder.h"

namespace sharpmesh::detail {

double TracedPolyline::length() const {
  double total = 0;
  for (std::size_t i = 0; i + 1 < vertices.size(); ++i) total += distance(vertices[i], vertices[i + 1]);
  return total;
}

namespace {

Vec3 unit(const Vec3& v) {
  const double n = norm(v);
  return n > 0 ? (1.0 / n) * v : Vec3{0, 0, 0};
}

// Principal axis and centroid of a set of points.
std::pair<Vec3, Vec3> principal_line(const std::vector<Vec3>& pts) {
  Vec3 c{0, 0, 0};
  for (const Vec3& p : pts) c = c + p;
  c = (1.0 / pts.size()) * c;
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const Vec3& p : pts) {
    const Eigen::Vector3d d(p[0] - c[0], p[1] - c[1], p[2] - c[2]);
    m += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(m);
  const Eigen::Vector3d a = solver.eigenvectors().col(2);
  return {c, Vec3{a(0), a(1), a(2)}};
}

// Distance from q to the line through c along the unit direction h.
double lateral_distance(const Vec3& q, const Vec3& c, const Vec3& h) {
  const Vec3 d = q - c;
  return norm(d - dot(d, h) * h);
}

// PCA smoothing, uniform resampling and lengthening of one traced chain.
TracedPolyline smooth_and_lengthen(const EdgeCluster& cluster, const std::vector<Vec3>& all_points, const std::vector<Vec3>& pts,
                                   const std::vector<Vec3>& dirs, const KnnIndex& index, const std::vector<double>& radius,
                                   const std::vector<std::uint32_t>& order, double min_radius, double lateral_tolerance) {
  std::vector<std::uint32_t> ids;
  TracedPolyline line;
  // PCA smoothing: each vertex moves onto the principal line of its cluster
  // neighbourhood (radius r_p), whose axis becomes its direction. The
  // sharpened points already lie on the edge; over 2 r_p the line of a
  // curved edge is a chord (the centroid of an arc of radius rho and length
  // 2 r_p lies r_p^2 / 6 rho inside), which pulls the rims of small holes
  // into the holes; at r_p the chord stays within the sampling's noise.
  std::vector<Vec3> local;
  for (std::uint32_t v : order) {
    index.within(pts[v], radius[v], ids);
    local.clear();
    for (std::uint32_t q : ids)
      if (!(lateral_tolerance > 0) || lateral_distance(pts[q], pts[v], dirs[v]) <= lateral_tolerance) local.push_back(pts[q]);
    Vec3 position = pts[v], direction = dirs[v];
    if (local.size() >= 3) {
      const auto [c, a] = principal_line(local);
      position = c + dot(pts[v] - c, a) * a;
      direction = a;
    }
    line.vertices.push_back(position);
    line.directions.push_back(direction);
  }
  // Directions follow the polyline.
  for (std::size_t i = 0; i < line.vertices.size(); ++i) {
    const Vec3 along = i + 1 < line.vertices.size() ? line.vertices[i + 1] - line.vertices[i]
                                                   : (i > 0 ? line.vertices[i] - line.vertices[i - 1] : line.directions[i]);
    if (dot(line.directions[i], along) < 0) line.directions[i] = -1.0 * line.directions[i];
  }

  // Resample at a uniform step of min_radius: the thinned cluster is denser
  // than the cloud, and r_junc is measured on the last vertices (7.2.3).
  if (line.vertices.size() >= 2 && min_radius > 0) {
    TracedPolyline even;
    even.vertices.push_back(line.vertices.front());
    even.directions.push_back(line.directions.front());
    double carried = 0;
    for (std::size_t i = 0; i + 1 < line.vertices.size(); ++i) {
      const Vec3 a = line.vertices[i], b = line.vertices[i + 1];
      const double length = distance(a, b);
      double t = min_radius - carried;
      while (t <= length) {
        even.vertices.push_back(a + (t / length) * (b - a));
        even.directions.push_back(line.directions[i]);
        t += min_radius;
      }
      carried = length - (t - min_radius);
    }
    if (distance(even.vertices.back(), line.vertices.back()) > 0.25 * min_radius) {
      even.vertices.push_back(line.vertices.back());
      even.directions.push_back(line.directions.back());
    } else {
      even.vertices.back() = line.vertices.back();
    }
    line = std::move(even);
  }

  // Lengthening: at each end, the centroid of the projections of the
  // extremity points within r_p that lie beyond the end.
  if (!cluster.extremities.empty() && line.vertices.size() >= 2) {
    auto extend = [&](bool at_back) {
      const Vec3 end = at_back ? line.vertices.back() : line.vertices.front();
      const Vec3 outward = at_back ? line.directions.back() : -1.0 * line.directions.front();
      const std::uint32_t end_index = at_back ? order.back() : order.front();
      double sum = 0;
      int count = 0;
      for (std::uint32_t e : cluster.extremities) {
        if (distance(all_points[e], end) >= 2 * radius[end_index]) continue;
        const double t = dot(all_points[e] - end, outward);
        if (t > 0) {
          sum += t;
          ++count;
        }
      }
      if (count == 0) return;
      const Vec3 c = end + (sum / count) * outward;
      if (at_back) {
        line.vertices.push_back(c);
        line.directions.push_back(line.directions.back());
      } else {
        line.vertices.insert(line.vertices.begin(), c);
        line.directions.insert(line.directions.begin(), line.directions.front());
      }
    };
    extend(true);
    extend(false);
  }
  return line;
}

}  // namespace

std::vector<TracedPolyline> trace_polylines(const EdgeCluster& cluster, const std::vector<Vec3>& all_points,
                                            const std::vector<Vec3>& all_directions, int successor_k, double min_radius,
                                            double lateral_tolerance, std::size_t min_points) {
  std::vector<Vec3> pts, dirs;
  for (std::uint32_t m : cluster.members) {
    pts.push_back(all_points[m]);
    dirs.push_back(unit(all_directions[m]));
  }
  const std::size_t n = pts.size();
  const KnnIndex index(pts);
  std::vector<std::uint32_t> ids;
  std::vector<double> d2;
  const int k = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(successor_k), n - 1));
  std::vector<double> radius(n);
  for (std::size_t i = 0; i < n; ++i) radius[i] = std::max(min_radius, rho_k(index, pts[i], k, ids, d2));
  // Beyond the thesis: a point belongs to the line being traced only within
  // `lateral_tolerance` of it. Two parallel edges a few spacings apart (the
  // rims of a wall three spacings high) can join one cluster through the
  // short edge between them; r_p then spans both, and the walk and the PCA
  // smoothing averaged them into one polyline along the wall's middle
  // (couplingdown 50k, 1.3-1.7 spacings off both rims). Members the traced
  // line leaves uncovered are traced again as their own polylines.
  const bool banded = lateral_tolerance > 0;
  auto in_band = [&](std::uint32_t q, std::uint32_t c, const Vec3& h) {
    return !banded || lateral_distance(pts[q], pts[c], h) <= lateral_tolerance;
  };
  std::vector<bool> visited(n, false);
  std::size_t free_count = n;
  auto visit = [&](std::uint32_t q) {
    if (visited[q]) return;
    visited[q] = true;
    --free_count;
  };
  std::vector<TracedPolyline> result;
  std::uint32_t seed = 0;  // the first free member: deterministic
  while (true) {
    while (seed < n && visited[seed]) ++seed;
    if (seed == n || (!result.empty() && free_count < min_points)) break;
    visit(seed);
    // Successor walk from the seed, in both directions.
    auto walk = [&](Vec3 heading) {
      std::vector<std::uint32_t> chain;
      std::uint32_t current = seed;
      while (true) {
        index.within(pts[current], radius[current], ids);
        std::uint32_t best = UINT32_MAX;
        double best_t = 0;
        for (std::uint32_t q : ids) {
          if (visited[q] || !in_band(q, current, heading)) continue;
          const double t = dot(pts[q] - pts[current], heading);
          if (t > 0 && (best == UINT32_MAX || t < best_t || (t == best_t && q < best))) {
            best = q;
            best_t = t;
          }
        }
        if (best == UINT32_MAX) break;
        // Points passed over on the way (projection between p and its
        // successor) are consumed too; points behind p stay for the walk back.
        for (std::uint32_t q : ids) {
          const double t = dot(pts[q] - pts[current], heading);
          if (!visited[q] && t > 0 && t <= best_t && in_band(q, current, heading)) visit(q);
        }
        visit(best);
        chain.push_back(best);
        Vec3 next = dirs[best];
        if (dot(next, heading) < 0) next = -1.0 * next;
        heading = next;
        current = best;
      }
      return chain;
    };
    const std::vector<std::uint32_t> forward = walk(dirs[seed]);
    const std::vector<std::uint32_t> backward = walk(-1.0 * dirs[seed]);
    std::vector<std::uint32_t> order(backward.rbegin(), backward.rend());
    order.push_back(seed);
    order.insert(order.end(), forward.begin(), forward.end());
    // Members beside the traced line, within the band, are its own: they are
    // not traced again.
    if (banded)
      for (std::uint32_t v : order) {
        index.within(pts[v], radius[v], ids);
        for (std::uint32_t q : ids)
          if (lateral_distance(pts[q], pts[v], dirs[v]) <= 1.5 * lateral_tolerance) visit(q);
      }
    result.push_back(smooth_and_lengthen(cluster, all_points, pts, dirs, index, radius, order, min_radius, lateral_tolerance));
    if (!banded) break;  // the thesis: one polyline per cluster
  }
  return result;
}

}  // namespace sharpmesh::detail
