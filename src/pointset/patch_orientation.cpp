// Beyond the thesis (App. A.8): whole patches of normals that the MST
// inverted, found by the geometry of the creases around them.
//
// The MST decides each sign from one edge by n_i . n_j >= 0. Across an acute
// crease (dihedral angle under 90 degrees) consistent normals have
// n_i . n_j < 0, and the jet normals of the crease points turn the short way
// between the two faces' normal lines: every sign decision along the crease
// is locally right and the whole face beyond it ends inverted (CGAL's
// tetrahedron.off at 50k points: the slanted face, 37% of the normals).
//
// Two points on the two planes of a crease, with consistent normals, each
// lie on the inner side of the other's tangent plane at a convex crease and
// on the outer side at a concave one: (u . n_i)(u . n_j) <= 0 whatever the
// angle, u = p_j - p_i. Here the reliable normals are grouped into patches
// (same sign, within 45 degrees, along tangent edges); chords up to 3
// spacings long between points of two patches whose normals differ by more
// than 25 degrees vote -(u . n_i)(u . n_j) on the two patches' consistency.
// Votes under 5 are dropped (a few chords between the far ends of two
// faces). The patch signs follow a maximum spanning tree of the votes; then
// a patch is flipped when the votes of its neighbours are mostly against it
// (less than -0.5 of their total weight) and at least two neighbours
// disagree, worst first, until none is left. A chord that spans two creases
// (a flange, a step and a cone on spool.off) breaks the two-plane model, but
// such votes are outweighed. Of 39 CGAL models at 50k points (replayed on
// the MST's output) and fandisk at 200k, only tetrahedron.off (its slanted
// face, 37% of the normals) and 3torus.off (39% inverted -> 0.2%) changed.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <queue>
#include <tuple>

#include <boost/pending/disjoint_sets.hpp>

#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"
#include "core/parallel.h"

namespace sharpmesh {
namespace {

constexpr double kSamePatchCos = 0.7071;  // neighbours within 45 degrees share a patch
constexpr double kMaxTangentSine = 0.5;   // ... along edges within 30 degrees of both tangent planes
constexpr double kCreaseCos = 0.9;        // chords vote between normals more than 25 degrees apart
constexpr double kChordSpacings = 3;
constexpr double kAgainst = 0.5;
// Votes between two patches below this are not evidence: a few chords
// between the far ends of two faces whose crease bands are wider than the
// chords (fandisk 200k: 14 chords summing to 0.1 flipped a face of 15k
// points). The tetrahedron's acute creases give about 50 per spacing.
constexpr double kMinVote = 5;

/// Largest |u . n| over the two normals, u the unit chord from a to b.
double steepness(const Vec3& u, const Vec3& na, const Vec3& nb) { return std::max(std::abs(dot(u, na)), std::abs(dot(u, nb))); }

// Patch signs along a maximum spanning tree of the votes, from the largest
// patch of each connected group: the strongest evidence first, as the MST
// does with single edges (3torus.off, a polyhedral triple torus: the MST
// left 39% of the reliable normals inverted, patch by patch; 0.2% after).
// Pinned patches (their anchors know the sign) start the tree all at once
// and keep their sign: on parts thinner than the chords, chords reach
// across the material and their votes are not the two-plane model's (on a
// generated ribbed plate 1.5 spacings thick they invert a third of the
// normals the anchors set right; docs/design-notes.md).
std::map<std::uint32_t, int> patch_signs(const std::map<std::uint32_t, std::vector<std::pair<std::uint32_t, double>>>& around,
                                         const std::vector<std::uint32_t>& patch, const std::vector<char>& reliable,
                                         const std::map<std::uint32_t, int>& pinned) {
  const std::size_t n = patch.size();
  std::map<std::uint32_t, int> sign = pinned;
  auto sign_of = [&](std::uint32_t q) {
    const auto it = sign.find(q);
    return it == sign.end() ? 1 : it->second;
  };
  {
    std::map<std::uint32_t, std::size_t> size;
    for (std::uint32_t i = 0; i < n; ++i)
      if (reliable[i]) ++size[patch[i]];
    std::vector<std::uint32_t> starts;
    for (const auto& entry : around) starts.push_back(entry.first);
    std::stable_sort(starts.begin(), starts.end(), [&](std::uint32_t a, std::uint32_t b) { return size[a] > size[b]; });
    std::map<std::uint32_t, char> reached;
    using Link = std::tuple<double, std::uint32_t, std::uint32_t, double>;  // |vote|, from, to, vote
    std::priority_queue<Link> from_pinned;
    for (const auto& [q, s] : pinned) {
      reached[q] = 1;
      const auto links = around.find(q);
      if (links != around.end())
        for (const auto& [other, vote] : links->second) from_pinned.emplace(std::abs(vote), q, other, vote);
    }
    for (std::size_t s = 0; s <= starts.size(); ++s) {
      std::priority_queue<Link> queue;
      if (s == 0) {
        queue = std::move(from_pinned);
      } else {
        const std::uint32_t start = starts[s - 1];
        if (reached[start]) continue;
        reached[start] = 1;
        for (const auto& [other, vote] : around.at(start)) queue.emplace(std::abs(vote), start, other, vote);
      }
      while (!queue.empty()) {
        const auto [strength, from, to, vote] = queue.top();
        queue.pop();
        if (reached[to]) continue;
        reached[to] = 1;
        sign[to] = vote >= 0 ? sign_of(from) : -sign_of(from);
        for (const auto& [other, next] : around.at(to))
          if (!reached[other]) queue.emplace(std::abs(next), to, other, next);
      }
    }
  }
  // Then, worst first, each patch that most of its neighbours' votes are against.
  for (std::size_t round = 0; round < around.size(); ++round) {
    double worst = -kAgainst;
    std::uint32_t flip = n;
    for (const auto& [q, list] : around) {
      if (pinned.count(q)) continue;
      double total = 0, balance = 0;
      for (const auto& [other, vote] : list) total += std::abs(vote);
      int against = 0;
      for (const auto& [other, vote] : list) {
        const double agreement = vote * sign_of(q) * sign_of(other);
        balance += agreement;
        against += agreement < -0.05 * total;
      }
      if (total > 0 && against >= 2 && balance / total < worst) worst = balance / total, flip = q;
    }
    if (flip == n) break;
    sign[flip] = -sign_of(flip);
  }
  return sign;
}

// Which of the two consistent orientations faces out: at the points
// farthest along each axis direction the outward normal points that way.
// (The MST's rule, the highest point's normal up, is a coin toss at an apex
// whose faces are vertical.)
void face_outward(const std::vector<Vec3>& p, const std::vector<Vec3>& normal, std::vector<int>& point_sign) {
  const std::size_t n = p.size();
  if (std::any_of(point_sign.begin(), point_sign.end(), [](int s) { return s < 0; })) {
    const std::size_t extreme = std::max<std::size_t>(10, n / 200);
    double outward = 0;
    std::vector<std::uint32_t> order(n);
    for (int axis = 0; axis < 3; ++axis)
      for (double direction : {-1.0, 1.0}) {
        std::iota(order.begin(), order.end(), 0u);
        std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(std::min(extreme, n)), order.end(),
                          [&](std::uint32_t a, std::uint32_t b) { return direction * p[a][axis] > direction * p[b][axis]; });
        for (std::size_t r = 0; r < std::min(extreme, n); ++r) outward += point_sign[order[r]] * direction * normal[order[r]][axis];
      }
    if (outward < 0)
      for (int& s : point_sign) s = -s;
  }
}

}  // namespace

std::size_t repair_inverted_patches(PointSet& points, const std::vector<std::uint32_t>& unreliable, double spacing, int k,
                                    const std::vector<signed char>& anchored) {
  check_point_set(points, 4, "patch orientation");
  if (!points.has_normals()) throw InvalidArgument("patch orientation: the points have no normals");
  if (!(spacing > 0) || !std::isfinite(spacing)) throw InvalidArgument("patch orientation: the spacing must be positive");
  const std::size_t n = points.size();
  if (!anchored.empty() && anchored.size() != n) throw InvalidArgument("patch orientation: one anchor entry per point is needed");
  auto is_anchored = [&](std::uint32_t i) { return !anchored.empty() && anchored[i] != 0; };
  std::vector<char> reliable(n, 1);
  for (std::uint32_t i : unreliable)
    if (i < n) reliable[i] = 0;
  const detail::KnnIndex index(points.points);
  const std::vector<Vec3>& p = points.points;
  std::vector<Vec3>& normal = points.normals;

  // Patches: reliable normals joined along tangent edges of the kNN graph.
  std::vector<std::vector<std::uint32_t>> neighbours(n);
  detail::parallel_for(n, [&](std::uint32_t i) {
    std::vector<double> squared;
    index.nearest(p[i], k + 1, neighbours[i], squared);
  });
  auto unit_chord = [&](std::uint32_t i, std::uint32_t j, Vec3& u) {
    const double length = distance(p[i], p[j]);
    if (!(length > 0)) return false;
    u = (1.0 / length) * (p[j] - p[i]);
    return true;
  };
  boost::disjoint_sets_with_storage<> patches(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!reliable[i]) continue;
    for (std::uint32_t j : neighbours[i]) {
      Vec3 u;
      if (j == i || !reliable[j] || !unit_chord(i, j, u)) continue;
      if (dot(normal[i], normal[j]) > kSamePatchCos && steepness(u, normal[i], normal[j]) < kMaxTangentSine) patches.union_set(i, j);
    }
  }
  std::vector<std::uint32_t> patch(n);
  for (std::uint32_t i = 0; i < n; ++i) patch[i] = static_cast<std::uint32_t>(patches.find_set(i));
  // Only points next to another patch or a crease point start chords.
  std::vector<char> border(n, 0);
  for (std::uint32_t i = 0; i < n; ++i)
    if (reliable[i])
      for (std::uint32_t j : neighbours[i]) border[i] |= !reliable[j] || patch[j] != patch[i];

  // Crease votes between patches (each chord once: from its border end, or
  // from the smaller index when both ends are border points).
  using Vote = std::pair<std::pair<std::uint32_t, std::uint32_t>, double>;
  std::vector<std::vector<Vote>> chord_votes(n);
  detail::parallel_for(n, [&](std::uint32_t i) {
    if (!border[i]) return;
    std::vector<std::uint32_t> near;
    index.within(p[i], kChordSpacings * spacing, near);
    for (std::uint32_t j : near) {
      Vec3 u;
      if (!reliable[j] || patch[i] == patch[j] || (border[j] && j <= i)) continue;
      if (std::abs(dot(normal[i], normal[j])) >= kCreaseCos || !unit_chord(i, j, u)) continue;
      chord_votes[i].push_back({std::minmax(patch[i], patch[j]), -dot(u, normal[i]) * dot(u, normal[j])});
    }
  });
  std::map<std::pair<std::uint32_t, std::uint32_t>, double> votes;
  for (const std::vector<Vote>& list : chord_votes)
    for (const auto& [pair, vote] : list) votes[pair] += vote;
  std::map<std::uint32_t, std::vector<std::pair<std::uint32_t, double>>> around;
  for (const auto& [pair, vote] : votes) {
    if (std::abs(vote) < kMinVote) continue;
    around[pair.first].push_back({pair.second, vote});
    around[pair.second].push_back({pair.first, vote});
  }

  // A patch holding anchored points is pinned: the anchored MST gave them
  // their anchors' signs, and a patch's normals agree in sign.
  std::map<std::uint32_t, int> pinned;
  for (std::uint32_t i = 0; i < n; ++i)
    if (reliable[i] && is_anchored(i)) pinned[patch[i]] = 1;
  const std::map<std::uint32_t, int> sign = patch_signs(around, patch, reliable, pinned);
  auto sign_of = [&](std::uint32_t q) {
    const auto it = sign.find(q);
    return it == sign.end() ? 1 : it->second;
  };

  // Reliable normals take their patch's sign; the others follow the majority
  // of their reliable neighbours.
  std::size_t flipped = 0;
  std::vector<int> point_sign(n, 1);
  for (std::uint32_t i = 0; i < n; ++i)
    if (reliable[i]) point_sign[i] = sign_of(patch[i]);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (reliable[i] || is_anchored(i)) continue;
    int balance = 0;
    for (std::uint32_t j : neighbours[i])
      if (reliable[j]) balance += point_sign[j];
    if (balance < 0) point_sign[i] = -1;
  }
  if (pinned.empty()) face_outward(p, normal, point_sign);
  for (std::uint32_t i = 0; i < n; ++i)
    if (point_sign[i] < 0 && !is_anchored(i)) normal[i] = -1.0 * normal[i], ++flipped;
  return flipped;
}

}  // namespace sharpmesh
