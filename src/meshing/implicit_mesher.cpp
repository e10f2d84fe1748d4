// Delaunay refinement of an implicit surface (Boissonnat & Oudot 2005; thesis
// 6.2.1, 7.3) with CGAL's Mesh_3: facet criteria only, the surface facets of
// the complex are the output. Sharp-feature polylines are protected by
// weighted points (7.3.2) placed by Mesh_3's edge protection, with a ball
// size that grows where the polyline lies off the implicit surface (the gap
// of 7.5, Fig. 7.18; the thesis's future work in 8.2).
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_3/Dump_c3t3.h>
#include <CGAL/Mesh_3/Mesher_3.h>
#include <CGAL/Mesh_3/Protect_edges_sizing_field.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_domain_with_polyline_features_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/facets_in_complex_3_to_triangle_mesh.h>

#include <algorithm>
#include <array>
#include <random>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <unordered_set>

#include "core/mesh_graph.h"
#include "core/cgal_bridge.h"
#include "meshing/refinement_retries.h"
#include "core/knn.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {
namespace {

using detail::Kernel;
using Domain = CGAL::Mesh_domain_with_polyline_features_3<CGAL::Labeled_mesh_domain_3<Kernel>>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
using Vertex_handle = Tr::Vertex_handle;

}  // namespace
}  // namespace sharpmesh

// Before it throws on an internal error, CGAL's Mesh_3 writes dump-bug.mesh
// and dump-bug.binary.cgal (1.5 MB) into the working directory; a library
// must not leave files in its caller's folder. The error itself is turned
// into a NumericalFailure below.
template <>
void CGAL::dump_c3t3<sharpmesh::C3t3>(const sharpmesh::C3t3&, std::string) {}

namespace sharpmesh {
namespace {

/// Radius of the protecting ball at a point of a feature: the thesis's
/// 2/3 d', grown to gap_margin x the distance to the implicit surface.
struct BallSizing {
  const ImplicitSurface* surface = nullptr;
  FeatureProtection protection;
  double max_radius = 0;

  /// Distance from p to the implicit surface, or -1 when no surface point
  /// lies within `search` of p (default: 4 x the largest ball radius);
  /// `stalled_search` as in project_onto_surface.
  double gap_at(const Vec3& p, double search = 0, double stalled_search = 0) const {
    Vec3 q;
    const double h = 1e-3 * protection.ball_radius;
    if (!project_onto_surface(*surface, p, 0.5 * protection.ball_radius, search > 0 ? search : 4 * max_radius, h, q, stalled_search))
      return -1;
    return distance(p, q);
  }
  /// Set for the protection: queries are counted against a budget (the
  /// stop flag is raised past it) and every 256th reports progress, which
  /// lets the caller cancel.
  struct QueryBudget {
    std::atomic<bool>* stop = nullptr;
    std::size_t limit = 0;  ///< 0: no limit
    const Progress* progress = nullptr;
    mutable std::atomic<std::size_t> count{0};
  };
  const QueryBudget* budget = nullptr;

  double operator()(const detail::Point3& p, int, const Domain::Index&) const {
    if (budget) {
      const std::size_t n = ++budget->count;
      if (budget->limit > 0 && n > budget->limit) budget->stop->store(true, std::memory_order_release);
      if (n % 256 == 0 && budget->progress) report_progress(*budget->progress, "protecting balls", 0.0);
    }
    if (!protection.adapt_to_gap) return protection.ball_radius;
    const double gap = gap_at(detail::from_cgal(p));
    if (gap < 0) return protection.ball_radius;
    return std::clamp(protection.gap_margin * gap, protection.ball_radius, max_radius);
  }
};

/// A meshing criterion as a field: `uniform` everywhere but within twice
/// the thickness of a thin point (ImplicitMeshingOptions::thin_points),
/// where it is `fraction` of that thickness. As the facet size (a bound on
/// the surface Delaunay ball radius, fraction 1) an empty ball centred on
/// one sheet then cannot reach past the other; as the facet distance
/// (fraction 1/4, not below `floor`, a spacing) a facet cannot stand
/// half-way across the part, where the uniform bound (0.6 d') let a bar
/// thinner than d' be meshed as chords between its faces and come out in
/// pieces. A smaller bound only adds facets.
class ThinPartSizing {
 public:
  ThinPartSizing(double uniform, const std::vector<Vec3>& points, const std::vector<double>& thickness, double fraction = 1.0,
                 double floor = 0.0)
      : uniform_(uniform), fraction_(fraction), floor_(floor), thickness_(std::make_shared<std::vector<double>>(thickness)) {
    if (!points.empty()) index_ = std::make_shared<detail::KnnIndex>(points);
  }
  double operator()(const detail::Point3& p, int, const Domain::Index&) const {
    if (!index_) return uniform_;
    std::vector<std::uint32_t> nearest;
    std::vector<double> squared;
    index_->nearest(detail::from_cgal(p), 1, nearest, squared);
    if (nearest.empty()) return uniform_;
    const double t = (*thickness_)[nearest[0]];
    if (squared[0] > 4 * t * t) return uniform_;
    return std::min(uniform_, std::max(floor_, fraction_ * t));
  }

 private:
  double uniform_;
  double fraction_;
  double floor_;
  std::shared_ptr<const std::vector<double>> thickness_;
  std::shared_ptr<const detail::KnnIndex> index_;
};

/// CGAL's points of the curves_for_protection pieces.
std::vector<std::vector<detail::Point3>> feature_polylines(const std::vector<Polyline>& polylines, double tolerance) {
  std::vector<std::vector<detail::Point3>> out;
  for (const Polyline& line : curves_for_protection(polylines, tolerance)) {
    out.emplace_back();
    for (const Vec3& p : line) out.back().push_back(detail::to_cgal(p));
  }
  return out;
}

/// The grid cell (of size `edge_length`) holding the most vertices stamped
/// after `since` (CGAL's insertion time stamps), as their count and
/// centroid; `since` becomes the newest stamp. Healthy refinement spreads
/// new vertices over the surface, a few per cell; a runaway manifold repair
/// piles them onto one spot.
struct NewVertexCluster {
  std::size_t count = 0;
  Vec3 centre{0, 0, 0};
};
NewVertexCluster densest_new_vertices(const C3t3& c3t3, double edge_length, std::size_t& since) {
  std::map<std::array<long, 3>, NewVertexCluster> cells;
  const Tr& tr = c3t3.triangulation();
  NewVertexCluster best;
  std::size_t newest = since;
  for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) {
    if (v->time_stamp() <= since) continue;
    newest = std::max(newest, v->time_stamp());
    const Vec3 p = detail::from_cgal(tr.point(v).point());
    NewVertexCluster& cell = cells[{static_cast<long>(std::floor(p[0] / edge_length)), static_cast<long>(std::floor(p[1] / edge_length)),
                                    static_cast<long>(std::floor(p[2] / edge_length))}];
    cell.centre = cell.centre + p;
    if (++cell.count > best.count) best = cell;
  }
  if (best.count > 0) best.centre = (1.0 / static_cast<double>(best.count)) * best.centre;
  since = newest;
  return best;
}

// Mesher_3::refine_mesh() step by step (as CGAL's own loop does), so that the
// progress callback can cancel, and so that a refinement that keeps working
// without adding vertices is stopped and its current mesh kept. This happens
// with the manifold option when a non-manifold vertex next to protecting
// balls cannot be repaired: CGAL then rescans it forever (couplingdown 50k).
// Stalled: no new vertex for kStallSteps steps.
// Runaway: CGAL's manifold repair can keep inserting points around a vertex
// next to protecting balls that it cannot make manifold, ever more slowly.
// Every kRunawayWindow new vertices, the cell of the edge length holding
// most of them is found; when two windows in a row put more than an eighth
// of their vertices into the same spot, the refinement ends as `runaway`.
// Healthy refinements spread a window's vertices over the surface (a few
// dozen in the fullest cell); a run-away repair puts about ten times that
// into one cell window after window, and the vertex bound below would only
// catch it after minutes. One window alone is not enough: refining a sharp
// corner can put a burst of vertices around it once, then none. Past
// `runaway_vertices` it ends as well. Both are counts, not times, so the
// result does not depend on the machine.
constexpr std::size_t kRunawayWindow = 1024;
constexpr std::size_t kStallSteps = 20000;

template <class Mesher>
void refine_stepwise(Mesher& mesher, const C3t3& c3t3, double edge_length, std::size_t max_vertices, std::size_t runaway_vertices,
                     const Progress& progress, ImplicitMeshingResult& result, std::optional<Vec3>& runaway_spot) {
  mesher.initialize();
  std::size_t steps = 0, last_growth_step = 0, vertices = c3t3.triangulation().number_of_vertices();
  std::size_t next_density_check = vertices + kRunawayWindow, stamp = 0;  // newest stamp before the window
  for (auto v = c3t3.triangulation().finite_vertices_begin(); v != c3t3.triangulation().finite_vertices_end(); ++v)
    stamp = std::max(stamp, v->time_stamp());  // the initial vertices are not new
  std::optional<Vec3> previous_pile;  // where the last window piled its vertices
  while (!mesher.is_algorithm_done()) {
    mesher.one_step();
    ++steps;
    const std::size_t now = c3t3.triangulation().number_of_vertices();
    if (now > vertices) {
      vertices = now;
      last_growth_step = steps;
    }
    if (max_vertices > 0 && now >= max_vertices) break;
    if (runaway_vertices > 0 && now >= runaway_vertices) {
      result.refinement_runaway = true;
      result.runaway_stopped_at = now;
      break;
    }
    if (now >= next_density_check) {
      next_density_check = now + kRunawayWindow;
      const NewVertexCluster densest = densest_new_vertices(c3t3, edge_length, stamp);
      const bool piled = densest.count > kRunawayWindow / 8;
      if (piled && previous_pile && distance(*previous_pile, densest.centre) < edge_length) {
        result.refinement_runaway = true;
        result.runaway_stopped_at = now;
        runaway_spot = densest.centre;
        break;
      }
      previous_pile = piled ? std::optional<Vec3>(densest.centre) : std::nullopt;
    }
    // A stall is counted in steps, not seconds, so that the mesh does not
    // depend on the machine: Mesh_3's manifold repair can step for ever
    // without inserting a vertex.
    if (steps - last_growth_step > kStallSteps) {
      result.refinement_stalled = true;
      break;
    }
    if (steps % 1024 == 0)
      report_progress(progress, "refinement", max_vertices > 0 ? std::min(0.99, static_cast<double>(now) / static_cast<double>(max_vertices)) : 0.5);
  }
  result.refinement_steps = steps;
}

/// The protecting balls (weighted vertices) as centre and squared radius.
std::vector<std::pair<detail::Point3, double>> protecting_balls(const C3t3& c3t3) {
  std::vector<std::pair<detail::Point3, double>> balls;
  const Tr& tr = c3t3.triangulation();
  for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v)
    if (tr.point(v).weight() > 0) balls.emplace_back(tr.point(v).point(), tr.point(v).weight());
  return balls;
}

/// Whether p lies within the diameter of a protecting ball of its centre.
bool near_a_ball(const std::vector<std::pair<detail::Point3, double>>& balls, const detail::Point3& p) {
  return std::any_of(balls.begin(), balls.end(),
                     [&p](const auto& ball) { return CGAL::squared_distance(p, ball.first) <= 4 * ball.second; });
}

/// Surface seeds for components the protecting balls do not reach: the
/// domain's initial points outside every ball.
void insert_surface_seeds(C3t3& c3t3, const Domain& domain) {
  const auto balls = protecting_balls(c3t3);
  std::vector<std::pair<detail::Point3, Domain::Index>> seeds;
  domain.construct_initial_points_object()(std::back_inserter(seeds));
  for (const auto& [p, index] : seeds) {
    if (near_a_ball(balls, p)) continue;
    const Vertex_handle v = c3t3.triangulation().insert(Tr::Weighted_point(p, 0));
    if (v == Vertex_handle()) continue;
    c3t3.set_dimension(v, 2);
    c3t3.set_index(v, index);
  }
}

/// Data seeds (ImplicitMeshingOptions::data_seeds): each point projected
/// onto the surface, then placed exactly on CGAL's zero set by the domain's
/// own intersection along the gradient (which also gives its surface index),
/// and inserted unless a vertex lies within spacing / 2 or a protecting ball
/// lies within its diameter. Returns the number inserted.
std::size_t insert_data_seeds(C3t3& c3t3, const Domain& domain, const ImplicitSurface& surface,
                              const std::vector<Vec3>& points, const std::vector<double>& spacings, const Progress& progress) {
  Tr& tr = c3t3.triangulation();
  const auto balls = protecting_balls(c3t3);
  auto intersect = domain.construct_intersection_object();
  std::size_t inserted = 0;
  Tr::Cell_handle hint;
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return spacings[a] < spacings[b]; });
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k % 256 == 0) report_progress(progress, "surface seeds", static_cast<double>(k) / static_cast<double>(points.size()));
    const std::size_t i = order[k];
    const double spacing = spacings[i];
    const double h = 1e-3 * spacing;
    Vec3 q;
    if (!project_onto_surface(surface, points[i], 0.25 * spacing, spacing, h, q)) continue;
    Vec3 g = implicit_gradient(surface, q, h);
    const double length = norm(g);
    if (!(length > 0)) continue;
    g = (0.05 * spacing / length) * g;
    const auto hit = intersect(Kernel::Segment_3(detail::to_cgal(q - g), detail::to_cgal(q + g)));
    if (std::get<2>(hit) != 2) continue;
    const detail::Point3 p = std::get<0>(hit);
    if (tr.number_of_vertices() > 0) {
      const Vertex_handle nearest = tr.nearest_power_vertex(p, hint);
      if (nearest != Vertex_handle() && !tr.is_infinite(nearest) &&
          CGAL::squared_distance(p, tr.point(nearest).point()) < 0.25 * spacing * spacing)
        continue;
    }
    if (near_a_ball(balls, p)) continue;
    const Vertex_handle v = tr.insert(Tr::Weighted_point(p, 0), hint);
    if (v == Vertex_handle()) continue;
    hint = v->cell();
    c3t3.set_dimension(v, 2);
    c3t3.set_index(v, std::get<1>(hit));
    ++inserted;
  }
  return inserted;
}

/// Splits the polylines where they lie farther from the implicit surface
/// than the largest ball can reach: those stretches are reported, not
/// protected (a ball that misses the surface leaves its vertex out of the
/// mesh, and nearby balls would pull the mesh towards a wrong polyline).
/// With `rescue_stalled`, points where Newton stalls and the surface is
/// found by the search for a sign change (within half a ball) are kept, and
/// listed in `stalled`.
std::vector<std::vector<detail::Point3>> coverable_parts(const std::vector<std::vector<detail::Point3>>& polylines,
                                                         const ImplicitSurface& surface, const BallSizing& sizing,
                                                         std::vector<UncoveredGap>& uncovered, bool rescue_stalled,
                                                         std::vector<Vec3>& stalled) {
  std::vector<std::vector<detail::Point3>> parts;
  const double reach = 0.8 * sizing.max_radius;
  for (const auto& line : polylines) {
    std::vector<double> gaps(line.size());
    bool all = true;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const Vec3 p = detail::from_cgal(line[i]);
      gaps[i] = sizing.gap_at(p, 2 * surface.bounding_radius());
      if (gaps[i] < 0 && rescue_stalled) {
        gaps[i] = sizing.gap_at(p, 2 * surface.bounding_radius(), 0.5 * sizing.protection.ball_radius);
        if (gaps[i] >= 0) stalled.push_back(p);
      }
      all = all && gaps[i] >= 0 && gaps[i] <= reach;
    }
    if (all) {
      parts.push_back(line);
      continue;
    }
    std::vector<detail::Point3> run;
    UncoveredGap gap;
    Vec3 sum{0, 0, 0};
    int count = 0;
    auto close_gap = [&] {
      if (count == 0) return;
      gap.center = (1.0 / count) * sum;
      uncovered.push_back(gap);
      gap = {};
      sum = {0, 0, 0};
      count = 0;
    };
    for (std::size_t i = 0; i < line.size(); ++i) {
      const bool ok = gaps[i] >= 0 && gaps[i] <= reach;
      if (ok) {
        close_gap();
        run.push_back(line[i]);
        continue;
      }
      if (run.size() >= 2) parts.push_back(run);
      run.clear();
      sum = sum + detail::from_cgal(line[i]);
      ++count;
      gap.gap = gaps[i] < 0 ? -1 : std::max(gap.gap, gaps[i]);
      if (i > 0) gap.length += 0.5 * std::sqrt(CGAL::squared_distance(line[i - 1], line[i]));
      if (i + 1 < line.size()) gap.length += 0.5 * std::sqrt(CGAL::squared_distance(line[i], line[i + 1]));
    }
    close_gap();
    if (run.size() >= 2) parts.push_back(run);
  }
  return parts;
}

using PointKey = std::array<double, 3>;

SurfaceMesh to_surface_mesh(const C3t3& c3t3, std::map<PointKey, std::uint32_t>& index_of) {
  CGAL::Surface_mesh<detail::Point3> sm;
  CGAL::facets_in_complex_3_to_triangle_mesh(c3t3, sm);
  SurfaceMesh out;
  out.vertices.reserve(sm.number_of_vertices());
  for (auto v : sm.vertices()) {
    out.vertices.push_back(detail::from_cgal(sm.point(v)));
    index_of.emplace(out.vertices.back(), static_cast<std::uint32_t>(out.vertices.size() - 1));
  }
  out.faces.reserve(sm.number_of_faces());
  for (auto f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k < 3) t[k] = static_cast<std::uint32_t>(v.idx());
      ++k;
    }
    if (k == 3) out.faces.push_back(t);
  }
  return out;
}

/// Which protected segments (complex edges between consecutive balls) are
/// edges of the output mesh; the represented ones chained into polylines,
/// the others grouped into uncovered stretches.
void check_features(const C3t3& c3t3, const SurfaceMesh& mesh, const std::map<PointKey, std::uint32_t>& index_of,
                    const BallSizing& sizing, ImplicitMeshingResult& result) {
  std::unordered_set<std::uint64_t> mesh_edges;
  for (const Triangle& t : mesh.faces)
    for (int k = 0; k < 3; ++k) mesh_edges.insert(detail::edge_key(t[k], t[(k + 1) % 3]));
  detail::VertexAdjacency adjacency(mesh.vertices.size());
  std::vector<std::pair<Vec3, Vec3>> missing;
  for (auto e = c3t3.edges_in_complex_begin(); e != c3t3.edges_in_complex_end(); ++e) {
    ++result.protected_segments;
    const Vec3 a = detail::from_cgal(e->first->vertex(e->second)->point().point());
    const Vec3 b = detail::from_cgal(e->first->vertex(e->third)->point().point());
    const auto ia = index_of.find(a), ib = index_of.find(b);
    if (ia != index_of.end() && ib != index_of.end() && mesh_edges.count(detail::edge_key(ia->second, ib->second))) {
      ++result.represented_segments;
      adjacency[ia->second].push_back(ib->second);
      adjacency[ib->second].push_back(ia->second);
    } else {
      missing.emplace_back(a, b);
    }
  }
  result.feature_edges = detail::chain_edges(mesh.vertices, adjacency);

  // Group missing segments that share end points into stretches.
  std::map<PointKey, std::size_t> end_of;
  detail::DisjointSets sets(missing.size());
  for (std::size_t i = 0; i < missing.size(); ++i)
    for (const Vec3& p : {missing[i].first, missing[i].second}) {
      auto [it, inserted] = end_of.emplace(p, i);
      if (!inserted) sets.unite(i, it->second);
    }
  std::map<std::size_t, UncoveredGap> stretches;
  std::map<std::size_t, Vec3> sums;
  std::map<std::size_t, int> counts;
  for (std::size_t i = 0; i < missing.size(); ++i) {
    const std::size_t root = sets.find(i);
    UncoveredGap& gap = stretches[root];
    gap.length += distance(missing[i].first, missing[i].second);
    const Vec3 mid = 0.5 * (missing[i].first + missing[i].second);
    sums[root] = sums.count(root) ? sums[root] + mid : mid;
    ++counts[root];
    gap.gap = std::max(gap.gap, sizing.gap_at(mid));
  }
  for (auto& [root, gap] : stretches) {
    gap.center = (1.0 / counts[root]) * sums[root];
    result.uncovered.push_back(gap);
  }
}

}  // namespace

void RefinementCriteria::check() const {
  if (!(angle > 0 && angle <= 30))
    throw InvalidArgument("facet angle must be in (0, 30] degrees for refinement to terminate (got " + format_number(angle) + ")");
  if (!(edge_length > 0) || !std::isfinite(edge_length))
    throw InvalidArgument("maximum edge length must be positive (got " + format_number(edge_length) + ")");
  if (!(distance > 0) || !std::isfinite(distance))
    throw InvalidArgument("maximum surface distance must be positive (got " + format_number(distance) + ")");
}

RefinementCriteria RefinementCriteria::from_spacing(double d_prime) {
  RefinementCriteria c;
  c.angle = 25.0;
  c.edge_length = 2.0 * d_prime;
  c.distance = 0.6 * d_prime;
  return c;
}

void ImplicitMeshingOptions::check() const {
  criteria.check();
  if (!(seed_spacing >= 0) || !std::isfinite(seed_spacing))
    throw InvalidArgument("data seed spacing must be non-negative (got " + format_number(seed_spacing) + ")");
  for (const Vec3& p : data_seeds)
    for (double c : p)
      if (!std::isfinite(c)) throw InvalidInput("a data seed has a non-finite coordinate");
  if (!data_seed_spacings.empty() && data_seed_spacings.size() != data_seeds.size())
    throw InvalidArgument("data seed spacings must be empty or one per seed");
  for (double s : data_seed_spacings)
    if (!(s > 0) || !std::isfinite(s)) throw InvalidArgument("data seed spacings must be positive (got " + format_number(s) + ")");
  if (thin_thickness.size() != thin_points.size()) throw InvalidArgument("thin points need one thickness each");
  for (double t : thin_thickness)
    if (!(t > 0) || !std::isfinite(t)) throw InvalidArgument("thin-part thickness must be positive (got " + format_number(t) + ")");
  if (!features.polylines.empty()) {
    if (!(features.ball_radius > 0) || !std::isfinite(features.ball_radius))
      throw InvalidArgument("protecting-ball radius must be positive (got " + format_number(features.ball_radius) + ")");
    if (!(features.gap_margin >= 1) || !std::isfinite(features.gap_margin))
      throw InvalidArgument("gap margin must be at least 1 (got " + format_number(features.gap_margin) + ")");
    if (features.max_ball_radius != 0 && !(features.max_ball_radius >= features.ball_radius))
      throw InvalidArgument("maximum ball radius must be at least the ball radius");
  }
}

double meshing_domain_radius(const ImplicitSurface& surface) { return 1.5 * surface.bounding_radius(); }

double estimate_facet_count(double area, const RefinementCriteria& criteria) {
  // Equilateral facets of edge l/2 .. l; take the geometric middle.
  const double edge = criteria.edge_length / std::sqrt(2.0);
  return area / (std::sqrt(3.0) / 4.0 * edge * edge);
}

namespace {

/// Thrown when the feature protection ran past its query budget.
struct ProtectionStopped {};

/// Whether random points of the meshing ball find both signs of the
/// function (at least three of each among up to 4,000).
bool both_signs_in_ball(const ImplicitSurface& surface, double domain_radius, std::uint64_t seed) {
  std::mt19937_64 generator(seed);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  int negative = 0, positive = 0;
  for (int i = 0; i < 4000 && (negative < 3 || positive < 3); ++i) {
    const Vec3 d{coordinate(generator), coordinate(generator), coordinate(generator)};
    if (norm(d) > 1) continue;
    (surface.value(surface.bounding_center() + domain_radius * d) < 0 ? negative : positive) += 1;
  }
  return negative >= 3 && positive >= 3;
}

/// Protecting balls on the domain's feature curves (7.3.2), by Mesh_3's
/// edge protection with the ball sizing; counts go into `result`. Throws
/// ProtectionStopped when the sizing queries pass the budget.
/// CGAL's own end condition of the protection
/// (Protect_edges_sizing_field::non_adjacent_but_intersect over the
/// triangulation's edges): two protecting balls that are not neighbours on
/// one polyline and whose spheres still meet.
bool non_adjacent_balls_intersect(const C3t3& c3t3) {
  const Tr& tr = c3t3.triangulation();
  const auto sphere = tr.geom_traits().construct_sphere_3_object();
  const auto do_intersect = tr.geom_traits().do_intersect_3_object();
  const auto point = tr.geom_traits().construct_point_3_object();
  const auto weight = tr.geom_traits().compute_weight_3_object();
  for (auto e = tr.finite_edges_begin(); e != tr.finite_edges_end(); ++e) {
    const auto a = e->first->vertex(e->second);
    const auto b = e->first->vertex(e->third);
    if (c3t3.in_dimension(a) > 1 || c3t3.in_dimension(b) > 1 || c3t3.is_in_complex(a, b)) continue;
    const auto& wa = tr.point(a);
    const auto& wb = tr.point(b);
    if (do_intersect(sphere(point(wa), weight(wa)), sphere(point(wb), weight(wb)))) return true;
  }
  return false;
}

void protect_features(C3t3& c3t3, Domain& domain, const BallSizing& sizing, const ImplicitMeshingOptions& options,
                      std::size_t max_vertices, CGAL::Mesh_error_code& error, const Progress& progress,
                      ImplicitMeshingResult& result) {
  report_progress(progress, "protecting balls", 0.0);
  // Balls that must shrink below this are kept (CGAL's "special balls")
  // instead of shrinking forever where two extracted polylines cross.
  const double minimal_radius = 0.05 * options.features.ball_radius;
  std::atomic<bool> stop{false};
  BallSizing::QueryBudget budget;
  budget.stop = &stop;
  budget.limit = options.protection_query_limit;
  budget.progress = &progress;
  BallSizing budgeted_sizing = sizing;
  budgeted_sizing.budget = &budget;
  CGAL::Mesh_3::Protect_edges_sizing_field<C3t3, Domain, BallSizing> protect(c3t3, domain, budgeted_sizing, minimal_radius,
                                                                              max_vertices, &error, &stop);
  // CGAL writes "features protection has reached maximal number of loops.
  // It might result in a crash." to std::cerr when its 29 rounds of ball
  // shrinking end with balls of two polylines still intersecting (polylines
  // a spacing apart); at its smallest ball size it accepts them silently.
  // Nothing crashes here (a failing refinement is retried without the close
  // features). The library leaves the process's streams alone (the CLI
  // filters that line, apps/sharpmesh/cgal_messages.h) and measures both
  // cases itself, for the report.
  protect(true);
  result.protecting_balls_intersect = !stop.load() && non_adjacent_balls_intersect(c3t3);
  result.protection_queries = budget.count.load();
  if (stop.load()) throw ProtectionStopped{};
  for (auto v = c3t3.triangulation().finite_vertices_begin(); v != c3t3.triangulation().finite_vertices_end(); ++v) {
    if (c3t3.in_dimension(v) > 1) continue;
    ++result.protecting_balls;
    const double r = std::sqrt(c3t3.triangulation().point(v).weight());
    if (r > 1.01 * options.features.ball_radius) ++result.enlarged_balls;
    const double gap = sizing.gap_at(detail::from_cgal(c3t3.triangulation().point(v).point()));
    result.max_gap = std::max(result.max_gap, gap);
  }
  report_progress(progress, "protecting balls", 1.0);
}

/// One refinement; `runaway_spot` is where a run-away refinement piled its
/// vertices, when the check on them stopped it; `stalled` the polyline
/// points whose gap only the sign-change search found (coverable_parts).
ImplicitMeshingResult refine_implicit_surface(const ImplicitSurface& surface, const ImplicitMeshingOptions& options,
                                              const Progress& progress, std::optional<Vec3>& runaway_spot,
                                              bool rescue_stalled, std::vector<Vec3>& stalled) {
  const double radius = surface.bounding_radius();
  if (!(radius > 0)) throw InvalidInput("implicit surface has an empty bounding sphere");
  const double domain_radius = meshing_domain_radius(surface);
  const double sphere_area = 4 * M_PI * radius * radius;
  if (options.max_facets > 0 && estimate_facet_count(sphere_area, options.criteria) > 1e3 * options.max_facets)
    throw InvalidArgument("the meshing criteria are far too fine for the surface size (edge length " +
                          format_number(options.criteria.edge_length) + " on a surface of radius " + format_number(radius) + ")");

  const detail::Point3 center = detail::to_cgal(surface.bounding_center());
  // CGAL's initial points are intersections of random segments in the
  // domain ball with the surface, drawn until enough are found: when the
  // function has one sign throughout the ball, that loop never ends (a flat
  // open cloud's Poisson function). They are drawn only when random points
  // of the ball find both signs. A function restricted to a thin band around
  // open data (blade 50k) is negative in too small a volume for that test;
  // its data seeds then start the refinement, and only when there are none
  // either is the function refused (after the seeds, below).
  const bool both_signs = both_signs_in_ball(surface, domain_radius, options.seed);
  std::function<double(const detail::Point3&)> function = [&surface](const detail::Point3& p) {
    return surface.value(detail::from_cgal(p));
  };
  CGAL::Random rng(options.seed);
  namespace params = CGAL::parameters;
  Domain domain(CGAL::Labeled_mesh_domain_3<Kernel>::create_implicit_mesh_domain(
      function, Kernel::Sphere_3(center, domain_radius * domain_radius), params::relative_error_bound = 1e-6,
      params::p_rng = &rng));
  BallSizing sizing;
  sizing.surface = &surface;
  sizing.protection = options.features;
  sizing.max_radius = options.features.max_ball_radius > 0 ? options.features.max_ball_radius : 3 * options.features.ball_radius;
  ImplicitMeshingResult result;
  stalled.clear();
  const auto polylines = coverable_parts(feature_polylines(options.features.polylines, 0.01 * options.features.ball_radius), surface, sizing, result.uncovered, rescue_stalled, stalled);
  domain.add_features(polylines.begin(), polylines.end());

  // The surface Delaunay ball radius bounds edges: radius <= l/2 gives edges <= l.
  const ThinPartSizing facet_size(options.criteria.edge_length / 2.0, options.thin_points, options.thin_thickness);
  const ThinPartSizing facet_distance(options.criteria.distance, options.thin_points, options.thin_thickness, 0.25,
                                      options.thin_min_distance);
  Criteria criteria(params::edge_size = sizing, params::facet_angle = options.criteria.angle, params::facet_size = facet_size,
                    params::facet_distance = facet_distance);
  // A facet has about half a vertex: a budget of 1.5x the facet limit in
  // vertices stops a run whose estimate was far too low.
  std::size_t max_vertices = options.max_facets > 0 ? options.max_facets * 3 / 4 + 1000 : 0;
  const std::size_t expected_budget = static_cast<std::size_t>(4 * options.expected_facets) + 20000;
  const bool budget_from_data = options.expected_facets > 0 && (max_vertices == 0 || expected_budget < max_vertices);
  if (budget_from_data) max_vertices = expected_budget;
  CGAL::Mesh_error_code error = CGAL::CGAL_MESH_3_NO_ERROR;
  C3t3 c3t3;
  if (!polylines.empty()) protect_features(c3t3, domain, sizing, options, max_vertices, error, progress, result);
  if (both_signs) insert_surface_seeds(c3t3, domain);
  if (!options.data_seeds.empty()) {
    const double spacing = options.seed_spacing > 0 ? options.seed_spacing : options.criteria.edge_length;
    std::vector<double> spacings = options.data_seed_spacings;
    spacings.resize(options.data_seeds.size(), spacing);
    result.data_seeds = insert_data_seeds(c3t3, domain, surface, options.data_seeds, spacings, progress);
  }
  if (!both_signs && result.data_seeds == 0 && result.protecting_balls == 0)
    throw NumericalFailure("the implicit function has one sign throughout its bounding sphere: there is no surface to mesh "
                           "(a flat or degenerate cloud?)");

  report_progress(progress, "refinement", 0.0);
  CGAL::Mesh_3::Mesher_3<C3t3, Criteria, Domain> mesher(c3t3, domain, criteria, CGAL::MANIFOLD, max_vertices, &error);
  // 1.5x the vertices the data suggests (half a vertex per facet), two per
  // protecting ball, and 2,000 more: the meshes of fifteen CGAL models at
  // 50k points stay below half of it; spool 50k, running away, stops at 9k
  // vertices after 4 s instead of passing 14k after 15 s.
  const std::size_t runaway_vertices =
      options.expected_facets > 0 ? static_cast<std::size_t>(0.75 * options.expected_facets) + 2 * result.protecting_balls + 2000 : 0;
  refine_stepwise(mesher, c3t3, options.criteria.edge_length, max_vertices, runaway_vertices, progress, result, runaway_spot);
  if (max_vertices > 0 && c3t3.triangulation().number_of_vertices() >= max_vertices) error = CGAL::CGAL_MESH_3_MAXIMAL_NUMBER_OF_VERTICES_REACHED;
  c3t3.clear_manifold_info();
  report_progress(progress, "refinement", 1.0);
  if (error == CGAL::CGAL_MESH_3_MAXIMAL_NUMBER_OF_VERTICES_REACHED && budget_from_data)
    throw NumericalFailure("Delaunay refinement passed 8x the facet count the data suggests (" +
                           format_number(options.expected_facets) +
                           "): the implicit surface is far larger than the sampled one (inconsistent normals, or a thin or open surface)");
  if (error == CGAL::CGAL_MESH_3_MAXIMAL_NUMBER_OF_VERTICES_REACHED)
    throw NumericalFailure("Delaunay refinement reached the vertex budget of " + format_number(max_vertices) +
                           " (raise --max-facets or delta)");

  std::map<PointKey, std::uint32_t> index_of;
  result.mesh = to_surface_mesh(c3t3, index_of);
  if (result.mesh.faces.empty()) throw NumericalFailure("Delaunay refinement produced no surface facets (is the implicit surface empty?)");
  if (!polylines.empty()) check_features(c3t3, result.mesh, index_of, sizing, result);
  std::sort(result.uncovered.begin(), result.uncovered.end(),
            [](const UncoveredGap& x, const UncoveredGap& y) { return x.length > y.length; });
  return result;
}

}  // namespace

ImplicitMeshingResult mesh_implicit_surface(const ImplicitSurface& surface, const ImplicitMeshingOptions& options,
                                            const Progress& progress) {
  options.check();
  // CGAL's Mesh_3 (5.5, CGAL issue #9102) can fail next to protected
  // curves that come close to each other or to another sheet of the
  // surface: with a refinement point "already inserted on surface", or by
  // a manifold repair that runs away. refinement_retries.cpp decides what
  // goes before the next refinement; here each one runs.
  auto refine = [&](const ImplicitMeshingOptions& attempt, bool rescue_stalled, std::vector<Vec3>& stalled) {
    detail::RefinementRun run;
    try {
      run.result = refine_implicit_surface(surface, attempt, progress, run.runaway_pile, rescue_stalled, stalled);
    } catch (const CGAL::Failure_exception& e) {
      run.status = detail::RefinementRun::Status::CgalFailure;
      run.cgal_message = !e.message().empty() ? e.message() : e.expression();
    } catch (const ProtectionStopped&) {
      run.status = detail::RefinementRun::Status::ProtectionStopped;
    }
    return run;
  };
  return detail::refine_with_retries(options, refine, progress);
}

}  // namespace sharpmesh
