// Algorithm 2 (thesis 7.2.2): union-find clustering of edge points whose
// directions agree with the segment joining them; extremity points.
#include <algorithm>
#include <cmath>
#include <map>

#include "core/mesh_graph.h"
#include "features/feature_graph_builder.h"
#include "core/knn.h"

namespace sharpmesh::detail {

double rho_k(const KnnIndex& index, const Vec3& p, int k, std::vector<std::uint32_t>& ids, std::vector<double>& d2) {
  index.nearest(p, k + 1, ids, d2);
  double sum = 0;
  int count = 0;
  for (std::size_t j = 1; j < d2.size(); ++j, ++count) sum += d2[j];
  // The thesis prints rho_k = (1/k) sqrt(sum |p - p_l|^2); that value is
  // below the nearest-neighbour distance for k = 20, so no pair would ever be
  // close. We read it as the RMS distance sqrt((1/k) sum |p - p_l|^2).
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}

namespace {

// Angle between a line direction and a segment, in [0, 90] degrees.
double line_angle(const Vec3& direction, const Vec3& segment) {
  const double n = norm(segment) * norm(direction);
  if (!(n > 0)) return 90.0;
  return std::acos(std::min(1.0, std::abs(dot(direction, segment)) / n)) * 180.0 / M_PI;
}

}  // namespace

std::vector<EdgeCluster> cluster_edge_points(const std::vector<Vec3>& points, const std::vector<Vec3>& directions, int k,
                                             double theta_deg, std::size_t min_size, double min_radius, std::size_t& pruned) {
  pruned = 0;
  const std::size_t n = points.size();
  if (n == 0) return {};
  const KnnIndex index(points);
  DisjointSets sets(n);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> extremity_pairs;  // (i, j): j is an extremity of i's cluster
  std::vector<std::uint32_t> ids;
  std::vector<double> d2;
  const int kk = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(k), n - 1));
  for (std::uint32_t i = 0; i < n && kk > 0; ++i) {
    // rho_k, floored at the cloud's sampling scale: sharpened edge points
    // are denser than the cloud along the edge but keep its gaps.
    const double rho = std::max(min_radius, rho_k(index, points[i], kk, ids, d2));
    if (rho > std::sqrt(d2.back())) index.within(points[i], rho, ids), d2.assign(ids.size(), 0.0);
    for (std::size_t m = 0; m < ids.size(); ++m) {
      if (ids[m] == i) continue;
      if (d2[m] == 0.0) d2[m] = squared_distance(points[ids[m]], points[i]);
      if (!(std::sqrt(d2[m]) < rho)) continue;
      const std::uint32_t j = ids[m];
      const Vec3 segment = points[j] - points[i];
      const bool ok_i = line_angle(directions[i], segment) <= theta_deg;
      const bool ok_j = line_angle(directions[j], segment) <= theta_deg;
      if (ok_i && ok_j) sets.unite(i, j);
      else if (ok_i) extremity_pairs.emplace_back(i, j);
    }
  }
  std::map<std::size_t, std::size_t> cluster_of_root;
  std::vector<EdgeCluster> clusters;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::size_t root = sets.find(i);
    auto [it, inserted] = cluster_of_root.try_emplace(root, clusters.size());
    if (inserted) clusters.emplace_back();
    clusters[it->second].members.push_back(i);
  }
  for (const auto& [i, j] : extremity_pairs) {
    const std::size_t root = sets.find(i);
    if (root == sets.find(j)) continue;
    clusters[cluster_of_root[root]].extremities.push_back(j);
  }
  std::vector<EdgeCluster> kept;
  for (EdgeCluster& c : clusters) {
    if (c.members.size() < min_size) {
      ++pruned;
      continue;
    }
    std::sort(c.extremities.begin(), c.extremities.end());
    c.extremities.erase(std::unique(c.extremities.begin(), c.extremities.end()), c.extremities.end());
    kept.push_back(std::move(c));
  }
  // Extremities that belong to a pruned cluster are unlabelled (7.2.2): only
  // members of kept clusters may lengthen a polyline.
  std::vector<bool> in_kept(n, false);
  for (const EdgeCluster& c : kept)
    for (std::uint32_t m : c.members) in_kept[m] = true;
  for (EdgeCluster& c : kept)
    c.extremities.erase(std::remove_if(c.extremities.begin(), c.extremities.end(), [&](std::uint32_t e) { return !in_kept[e]; }),
                        c.extremities.end());
  return kept;
}

}  // namespace sharpmesh::detail
