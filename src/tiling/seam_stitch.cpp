// Making the two sides of a seam the same chains of the same vertices, and
// welding the tiles into one mesh (tiling/tiling.h).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <unordered_map>

#include "tiling/tiling.h"

namespace sharpmesh::detail {
namespace {

/// The nearest point of chain segment `s` (from vertex s to s + 1) to p.
struct OnChain {
  std::size_t segment = 0;
  double t = 0;          ///< along the segment, in [0, 1]
  double distance = std::numeric_limits<double>::infinity();
  double position() const { return static_cast<double>(segment) + t; }
};

OnChain nearest_on_chain(const SurfaceMesh& mesh, const SeamChain& chain, const Vec3& p) {
  OnChain best;
  const std::size_t segments = chain.closed ? chain.vertices.size() : chain.vertices.size() - 1;
  for (std::size_t s = 0; s < segments; ++s) {
    const Vec3& a = mesh.vertices[chain.vertices[s]];
    const Vec3& b = mesh.vertices[chain.vertices[(s + 1) % chain.vertices.size()]];
    const Vec3 ab = b - a;
    const double length2 = dot(ab, ab);
    const double t = length2 > 0 ? std::clamp(dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
    const double d = norm(a + t * ab - p);
    if (d < best.distance) best = {s, t, d};
  }
  return best;
}

/// The farthest vertex of `from` from the chain `to`; on an open `to`, over
/// the vertices facing it only (not those beyond its ends, whose nearest
/// point is an end), infinite when fewer than half of them face it.
double chain_distance(const SurfaceMesh& from_mesh, const SeamChain& from, const SurfaceMesh& to_mesh, const SeamChain& to) {
  double worst = 0;
  std::size_t facing = 0;
  const std::size_t last_segment = to.vertices.size() - 2;
  for (std::uint32_t v : from.vertices) {
    const OnChain c = nearest_on_chain(to_mesh, to, from_mesh.vertices[v]);
    if (!to.closed && ((c.segment == 0 && c.t == 0) || (c.segment == last_segment && c.t == 1))) continue;
    worst = std::max(worst, c.distance);
    ++facing;
  }
  return 2 * facing >= from.vertices.size() ? worst : std::numeric_limits<double>::infinity();
}

/// Splits, in `mesh`, the facet with half-edge (a, b) at `points` (in order
/// from a to b): a fan from its third corner. False when no facet has it.
bool split_edge(SurfaceMesh& mesh, std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t>& facet_of, std::uint32_t a,
                std::uint32_t b, const std::vector<std::uint32_t>& points) {
  if (points.empty()) return true;
  const auto it = facet_of.find({a, b});
  if (it == facet_of.end()) return false;
  const std::size_t f = it->second;
  const Triangle t = mesh.faces[f];
  int c = 0;
  while (c < 3 && !(t[c] == a && t[(c + 1) % 3] == b)) ++c;
  if (c == 3) return false;  // the facet was split along another of its edges
  const std::uint32_t w = t[(c + 2) % 3];
  std::vector<std::uint32_t> path{a};
  path.insert(path.end(), points.begin(), points.end());
  path.push_back(b);
  mesh.faces[f] = {path[0], path[1], w};
  for (std::size_t k = 1; k + 1 < path.size(); ++k) mesh.faces.push_back({path[k], path[k + 1], w});
  facet_of.erase(it);
  return true;
}

std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> facets_by_half_edge(const SurfaceMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> facet_of;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int c = 0; c < 3; ++c) facet_of[{mesh.faces[f][c], mesh.faces[f][(c + 1) % 3]}] = f;
  return facet_of;
}

/// What one chain's stitch changes: above's vertices moved onto below's
/// chain, and each side's boundary edges split at the other side's vertices.
struct SeamPlan {
  std::vector<std::pair<std::uint32_t, Vec3>> moves;
  std::vector<std::pair<std::pair<std::uint32_t, std::uint32_t>, std::vector<Vec3>>> below_splits, above_splits;
};

/// The moves and splits that make `b` (above's chain) and `a` (below's) the
/// same vertices: above's vertex within `merge` of one of below's, unclaimed
/// and with no facet of above turned over by the move, becomes it; the
/// others move to their nearest point of `a`. "" or why the chains differ.
std::string plan_chain(const SurfaceMesh& below, const SurfaceMesh& above, const SeamChain& a, const SeamChain& b, int axis, double plane,
                     double tolerance, double merge, SeamPlan& plan, SeamStitch& result) {
  const double m = static_cast<double>(a.closed ? a.vertices.size() : a.vertices.size() - 1);
  std::vector<OnChain> at(b.vertices.size());
  for (std::size_t j = 0; j < b.vertices.size(); ++j) {
    at[j] = nearest_on_chain(below, a, above.vertices[b.vertices[j]]);
    // A vertex of above that lies on one of below's: the same vertex.
    const std::size_t s = at[j].segment;
    const double length = norm(below.vertices[a.vertices[(s + 1) % a.vertices.size()]] - below.vertices[a.vertices[s]]);
    if (at[j].t * length <= 1e-9 * tolerance) at[j].t = 0;
    if ((1 - at[j].t) * length <= 1e-9 * tolerance) at[j] = {(s + 1) % a.vertices.size(), 0.0, at[j].distance};
    if (!a.closed && at[j].segment == a.vertices.size() - 1) at[j] = {a.vertices.size() - 2, 1.0, at[j].distance};
  }
  auto place = [&](const OnChain& c) {
    const Vec3& p = below.vertices[a.vertices[c.segment]];
    const Vec3& q = below.vertices[a.vertices[(c.segment + 1) % a.vertices.size()]];
    Vec3 x = c.t == 0 ? p : c.t == 1 ? q : p + c.t * (q - p);
    x[axis] = plane;
    return x;
  };
  if (merge > 0) {
    // Above's vertex near one of below's becomes it (one each), unless that
    // turns a facet of above over: fewer and fatter facets along the seam.
    std::vector<bool> claimed(a.vertices.size(), false);
    for (const OnChain& c : at)
      if (c.t == 0) claimed[c.segment] = true;
    std::vector<OnChain> merged = at;
    std::unordered_map<std::uint32_t, std::size_t> on_chain;
    for (std::size_t j = 0; j < b.vertices.size(); ++j) on_chain[b.vertices[j]] = j;
    for (std::size_t j = 0; j < b.vertices.size(); ++j) {
      if (at[j].t == 0 || at[j].t == 1) continue;
      const std::size_t k = at[j].t < 0.5 ? at[j].segment : (at[j].segment + 1) % a.vertices.size();
      const double d = norm(above.vertices[b.vertices[j]] - below.vertices[a.vertices[k]]);
      if (d > merge || claimed[k]) continue;
      claimed[k] = true;
      merged[j] = !a.closed && k == a.vertices.size() - 1 ? OnChain{k - 1, 1.0, d} : OnChain{k, 0.0, d};
    }
    auto position = [&](std::uint32_t v, const std::vector<OnChain>& places) {
      const auto it = on_chain.find(v);
      return it == on_chain.end() ? above.vertices[v] : place(places[it->second]);
    };
    for (int pass = 0; pass < 3; ++pass) {  // a revert changes the facets around it too
      bool reverted = false;
      for (const Triangle& f : above.faces) {
        bool moved = false;
        for (std::uint32_t v : f) moved = moved || (on_chain.count(v) && merged[on_chain[v]].position() != at[on_chain[v]].position());
        if (!moved) continue;
        const Vec3 before = cross(position(f[1], at) - position(f[0], at), position(f[2], at) - position(f[0], at));
        const Vec3 after = cross(position(f[1], merged) - position(f[0], merged), position(f[2], merged) - position(f[0], merged));
        if (dot(before, after) > 0) continue;
        for (std::uint32_t v : f)
          if (on_chain.count(v)) merged[on_chain[v]] = at[on_chain[v]];
        reverted = true;
      }
      if (!reverted) break;
    }
    at = std::move(merged);
  }
  // Open chains (a surface with a boundary crossing the cut) end where each
  // side's data ends, not at the same place: above's vertices beyond the
  // end of below's chain (their nearest point is its end) stay as they are,
  // but for the one nearest the overlap, and the two sides are welded over
  // the overlap only; past it both remain the mesh's boundary.
  std::size_t first = 0, last = b.vertices.size() - 1;
  if (!b.closed) {
    for (std::size_t j = 0; j < b.vertices.size(); ++j)
      if (at[j].position() >= m) first = j;
    for (std::size_t j = b.vertices.size(); j-- > 0;)
      if (at[j].position() <= 0) last = j;
    if (first >= last) return "the open chains on the two sides of the cut do not overlap";
  }
  // Above's chain runs against below's: its places must fall strictly,
  // once round a closed chain.
  double turned = 0;
  const std::size_t steps = b.closed ? b.vertices.size() : last;
  for (std::size_t j = first; j < steps; ++j) {
    double fall = at[j].position() - at[(j + 1) % b.vertices.size()].position();
    if (b.closed && fall <= 0) fall += m;
    if (!(fall > 0)) {
      return "the chains on the two sides of the cut run in different orders";
    }
    turned += fall;
  }
  if (b.closed && std::abs(turned - m) > 1e-9 * m) {
    return "a chain above the cut winds round the chain below more than once";
  }
  for (std::size_t j = first; j <= last; ++j) result.max_move = std::max(result.max_move, at[j].distance);
  // Below's edges take above's vertices that fall inside them.
  std::map<std::size_t, std::vector<std::pair<double, Vec3>>> inside;
  for (std::size_t j = first; j <= last; ++j) {
    const Vec3 x = place(at[j]);
    plan.moves.push_back({b.vertices[j], x});
    if (at[j].t > 0 && at[j].t < 1) inside[at[j].segment].push_back({at[j].t, x});
  }
  for (auto& [segment, points] : inside) {
    std::sort(points.begin(), points.end(), [](const auto& l, const auto& r) { return l.first < r.first; });
    std::vector<Vec3> xs;
    for (const auto& p : points) xs.push_back(p.second);
    plan.below_splits.push_back({{a.vertices[segment], a.vertices[(segment + 1) % a.vertices.size()]}, xs});
  }
  // Above's edges take below's vertices between their two ends' places:
  // below's vertex k sits at place k, and above's edge runs down from the
  // place of its start to that of its end (round the chain when closed).
  for (std::size_t j = first; j < steps; ++j) {
    const double from = at[j].position(), to = at[(j + 1) % b.vertices.size()].position();
    double span = from - to;
    if (b.closed && span <= 0) span += m;
    std::vector<Vec3> xs;
    for (double k = std::ceil(from) - 1; from - k < span; k -= 1) {
      const double wrapped = k < 0 ? k + m : k;
      const std::size_t index = static_cast<std::size_t>(std::llround(wrapped)) % a.vertices.size();
      Vec3 x = below.vertices[a.vertices[index]];
      x[axis] = plane;
      xs.push_back(x);
    }
    plan.above_splits.push_back({{b.vertices[j], b.vertices[(j + 1) % b.vertices.size()]}, xs});
  }
  return "";
}

}  // namespace

SeamStitch stitch_seam(SurfaceMesh& below, SurfaceMesh& above, int axis, double plane, double tolerance, double merge) {
  SeamStitch result;
  const std::vector<SeamChain> lower = chains_on_plane(below, axis, plane);
  const std::vector<SeamChain> upper = chains_on_plane(above, axis, plane);
  if (lower.size() != upper.size()) {
    result.failure = std::to_string(lower.size()) + " chains below the cut, " + std::to_string(upper.size()) + " above it";
    return result;
  }
  // One to one: each chain below with the chain above nearest to it both ways.
  std::vector<std::size_t> partner(lower.size());
  std::vector<bool> taken(upper.size(), false);
  for (std::size_t i = 0; i < lower.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_j = upper.size();
    for (std::size_t j = 0; j < upper.size(); ++j) {
      if (taken[j] || lower[i].closed != upper[j].closed) continue;
      const double d = std::max(chain_distance(above, upper[j], below, lower[i]), chain_distance(below, lower[i], above, upper[j]));
      if (d < best) best = d, best_j = j;
    }
    if (best_j == upper.size() || !(best <= tolerance)) {
      result.failure = "a chain below the cut has no chain above within the tolerance";
      return result;
    }
    taken[best_j] = true;
    partner[i] = best_j;
  }
  // Plan every chain first, change the meshes only when all of them fit.
  std::vector<SeamPlan> plans(lower.size());
  for (std::size_t i = 0; i < lower.size(); ++i) {
    const SeamChain& a = lower[i];
    const SeamChain& b = upper[partner[i]];
    std::string failure = plan_chain(below, above, a, b, axis, plane, tolerance, merge, plans[i], result);
    if (!failure.empty() && merge > 0) {  // merging changed the order: every vertex kept
      plans[i] = SeamPlan{};
      failure = plan_chain(below, above, a, b, axis, plane, tolerance, 0, plans[i], result);
    }
    if (!failure.empty()) {
      result.failure = failure;
      return result;
    }
  }
  // Applied to copies: a facet missing on either side leaves both unchanged.
  SurfaceMesh new_below = below, new_above = above;
  auto below_facets = facets_by_half_edge(new_below);
  auto above_facets = facets_by_half_edge(new_above);
  using Splits = std::vector<std::pair<std::pair<std::uint32_t, std::uint32_t>, std::vector<Vec3>>>;
  auto apply = [&](SurfaceMesh& mesh, std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t>& facets, const Splits& splits) {
    for (const auto& [edge, xs] : splits) {
      std::vector<std::uint32_t> ids;
      for (const Vec3& x : xs) {
        ids.push_back(static_cast<std::uint32_t>(mesh.vertices.size()));
        mesh.vertices.push_back(x);
      }
      if (!split_edge(mesh, facets, edge.first, edge.second, ids)) return false;
      result.inserted += ids.size();
    }
    return true;
  };
  for (const SeamPlan& plan : plans) {
    if (!apply(new_below, below_facets, plan.below_splits) || !apply(new_above, above_facets, plan.above_splits)) {
      result.failure = "a facet has two boundary edges on the cut";
      result.inserted = 0;
      return result;
    }
    for (const auto& [v, x] : plan.moves) new_above.vertices[v] = x;
  }
  // A facet with two corners at one place would weld degenerate; merging
  // is what can make one (a corner merged where the other side's vertex was
  // also inserted): the seam is stitched again with every vertex kept.
  auto collapses = [](const SurfaceMesh& mesh) {
    for (const Triangle& t : mesh.faces)
      if (mesh.vertices[t[0]] == mesh.vertices[t[1]] || mesh.vertices[t[1]] == mesh.vertices[t[2]] ||
          mesh.vertices[t[0]] == mesh.vertices[t[2]])
        return true;
    return false;
  };
  if (collapses(new_below) || collapses(new_above)) {
    if (merge > 0) return stitch_seam(below, above, axis, plane, tolerance, 0);
    result.failure = "stitching would make a facet with two corners at one place";
    result.inserted = 0;
    return result;
  }
  below = std::move(new_below);
  above = std::move(new_above);
  result.chains = lower.size();
  result.stitched = true;
  return result;
}

SurfaceMesh weld_parts(const std::vector<SurfaceMesh>& parts, int axis, const std::vector<double>& cuts) {
  SurfaceMesh out;
  struct Key {
    std::uint64_t bits[3];
    bool operator==(const Key& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const { return k.bits[0] * 0x9e3779b97f4a7c15ull ^ (k.bits[1] + 0x632be5ab) * 31 ^ k.bits[2]; }
  };
  std::unordered_map<Key, std::uint32_t, Hash> on_cuts;
  for (const SurfaceMesh& part : parts) {
    std::vector<std::uint32_t> index(part.vertices.size());
    for (std::size_t v = 0; v < part.vertices.size(); ++v) {
      const Vec3& p = part.vertices[v];
      const bool on_cut = std::find(cuts.begin(), cuts.end(), p[axis]) != cuts.end();
      if (on_cut) {
        Key key;
        for (int a = 0; a < 3; ++a) std::memcpy(&key.bits[a], &p[a], sizeof(double));
        auto [at, added] = on_cuts.try_emplace(key, static_cast<std::uint32_t>(out.vertices.size()));
        if (added) out.vertices.push_back(p);
        index[v] = at->second;
      } else {
        index[v] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(p);
      }
    }
    for (const Triangle& t : part.faces) out.faces.push_back({index[t[0]], index[t[1]], index[t[2]]});
  }
  return out;
}

}  // namespace sharpmesh::detail
