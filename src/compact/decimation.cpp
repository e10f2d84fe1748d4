// Feature-preserving edge collapse (sharpmesh/compact.h). CGAL's
// Surface_mesh_simplification orders the collapses by Garland and
// Heckbert's plane quadrics; the placement below adds the rule that keeps
// sharp edges sharp (as in feature-preserving QEM, e.g. Hoppe's
// "discontinuity curves", SIGGRAPH 1996): a vertex on a curve moves only
// onto the next vertex of its curve, a vertex off the curves may join one
// only at its vertex, and a corner (curve end, junction, kink) never moves.
#include "sharpmesh/compact.h"

#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Polyhedral_envelope_filter.h>
#include <CGAL/Surface_mesh_simplification/Edge_collapse_visitor_base.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numeric>

#include "compact/facet_grid.h"
#include "core/cgal_bridge.h"
#include "sharpmesh/errors.h"

namespace sharpmesh {

void DecimationOptions::check() const {
  if (!(tolerance >= 0 && tolerance < 1))
    throw InvalidArgument("tolerance is a fraction of the diagonal in [0, 1) (got " + format_number(tolerance) + ")");
  if (!(sharp_angle >= 0 && sharp_angle < 180))
    throw InvalidArgument("sharp angle is in degrees in [0, 180) (got " + format_number(sharp_angle) + ")");
}

namespace {

using detail::Kernel;
using detail::Point3;
using detail::Vector3;
using Mesh = CGAL::Surface_mesh<Point3>;
using VertexIndex = Mesh::Vertex_index;
using EdgeIndex = Mesh::Edge_index;
namespace SMS = CGAL::Surface_mesh_simplification;
using Quadrics = SMS::GarlandHeckbert_plane_policies<Mesh, Kernel>;
using Profile = SMS::Edge_profile<Mesh>;

Mesh to_surface_mesh(const SurfaceMesh& input) {
  std::vector<Point3> points = detail::to_cgal(input.vertices);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(input.faces.size());
  for (const Triangle& t : input.faces) polygons.push_back({t[0], t[1], t[2]});
  if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(polygons))
    throw InvalidInput("decimation needs an oriented, edge- and vertex-manifold mesh");
  Mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  return mesh;
}

SurfaceMesh from_surface_mesh(Mesh& mesh) {
  mesh.collect_garbage();
  SurfaceMesh out;
  out.vertices.reserve(mesh.number_of_vertices());
  for (VertexIndex v : mesh.vertices()) out.vertices.push_back(detail::from_cgal(mesh.point(v)));
  out.faces.reserve(mesh.number_of_faces());
  for (Mesh::Face_index f : mesh.faces()) {
    Triangle t{};
    int i = 0;
    for (VertexIndex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) t[i++] = static_cast<std::uint32_t>(v.idx());
    out.faces.push_back(t);
  }
  return out;
}

/// The curves that stay: per edge whether it is sharp, per vertex whether it
/// lies on a curve and whether it is a corner.
struct Curves {
  Mesh::Property_map<EdgeIndex, bool> edge;
  Mesh::Property_map<VertexIndex, bool> on_curve;
  Mesh::Property_map<VertexIndex, bool> corner;
};

/// A curve that turns by more than this at a vertex keeps the vertex as a
/// corner [degrees]: the corner of a square outline, the vertices of a hole
/// only a few facets round, which sliding would cut off.
constexpr double kKinkAngle = 40;

/// Marks the given polylines' edges, the border and the edges sharper than
/// `sharp_angle`; then the vertices on them, and as corners those with other
/// than two curve edges or whose two curve edges turn by more than kKinkAngle.
Curves mark_curves(Mesh& mesh, const std::vector<Polyline>& polylines, double sharp_angle, DecimationResult& result) {
  Curves curves{mesh.add_property_map<EdgeIndex, bool>("e:curve", false).first,
                mesh.add_property_map<VertexIndex, bool>("v:on_curve", false).first,
                mesh.add_property_map<VertexIndex, bool>("v:corner", false).first};
  std::map<Vec3, VertexIndex> by_position;
  for (VertexIndex v : mesh.vertices()) by_position.emplace(detail::from_cgal(mesh.point(v)), v);
  for (const Polyline& line : polylines)
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const auto a = by_position.find(line[i]), b = by_position.find(line[i + 1]);
      if (a == by_position.end() || b == by_position.end()) continue;
      const auto [h, found] = CGAL::halfedge(a->second, b->second, mesh);
      if (found) curves.edge[mesh.edge(h)] = true;
    }
  const double cos_sharp = std::cos(sharp_angle * M_PI / 180);
  auto face_normal = [&](Mesh::Face_index f) { return CGAL::Polygon_mesh_processing::compute_face_normal(f, mesh); };
  for (EdgeIndex e : mesh.edges()) {
    const Mesh::Halfedge_index h = mesh.halfedge(e);
    if (mesh.is_border(e)) {
      curves.edge[e] = true;
    } else if (sharp_angle > 0 && face_normal(mesh.face(h)) * face_normal(mesh.face(mesh.opposite(h))) < cos_sharp) {
      curves.edge[e] = true;
    }
  }
  for (VertexIndex v : mesh.vertices()) {
    std::vector<Vector3> directions;
    for (Mesh::Halfedge_index h : CGAL::halfedges_around_target(v, mesh))
      if (curves.edge[mesh.edge(h)]) directions.push_back(mesh.point(mesh.source(h)) - mesh.point(v));
    if (directions.empty()) continue;
    curves.on_curve[v] = true;
    bool corner = directions.size() != 2;
    if (!corner) {
      // A kink: the curve's two edges are not about opposite.
      const double c = directions[0] * directions[1] /
                       std::sqrt(directions[0].squared_length() * directions[1].squared_length());
      corner = c > -std::cos(kKinkAngle * M_PI / 180);
    }
    curves.corner[v] = corner;
    result.corner_vertices += corner;
  }
  for (EdgeIndex e : mesh.edges()) result.feature_edges += curves.edge[e];
  return curves;
}

/// Placement: Garland-Heckbert's optimum off the curves; otherwise the rule
/// of the file's header, with the cheaper end (by the same quadrics) when an
/// edge of a curve collapses.
class CurvePlacement {
 public:
  CurvePlacement(const Quadrics& quadrics, const Curves& curves) : quadrics_(quadrics), curves_(curves) {}

  boost::optional<Point3> operator()(const Profile& profile) const {
    const VertexIndex v0 = profile.v0(), v1 = profile.v1();
    const bool c0 = curves_.on_curve[v0], c1 = curves_.on_curve[v1];
    if (!c0 && !c1) return free_placement(profile);
    if (c0 && !c1) return profile.p0();
    if (c1 && !c0) return profile.p1();
    // Both on curves: only along a curve, and never moving a corner.
    if (!curves_.edge[profile.surface_mesh().edge(profile.v0_v1())]) return boost::none;
    const bool k0 = curves_.corner[v0], k1 = curves_.corner[v1];
    if (k0 && k1) return boost::none;
    if (k0) return profile.p0();
    if (k1) return profile.p1();
    const auto cost0 = quadrics_.get_cost()(profile, boost::optional<Point3>(profile.p0()));
    const auto cost1 = quadrics_.get_cost()(profile, boost::optional<Point3>(profile.p1()));
    return *cost0 <= *cost1 ? profile.p0() : profile.p1();
  }

 private:
  /// Garland-Heckbert's optimum, unless it lies farther from the edge's
  /// midpoint than the edge is long: a nearly singular quadric (a flat or
  /// a cylindrical patch) puts its optimum anywhere along the flat
  /// directions. Then the cheapest of the ends and the midpoint, Garland
  /// and Heckbert's own fallback.
  boost::optional<Point3> free_placement(const Profile& profile) const {
    const boost::optional<Point3> optimum = quadrics_.get_placement()(profile);
    const Point3 middle = CGAL::midpoint(profile.p0(), profile.p1());
    if (optimum && CGAL::squared_distance(*optimum, middle) <= CGAL::squared_distance(profile.p0(), profile.p1())) return optimum;
    boost::optional<Point3> best;
    double best_cost = 0;
    for (const Point3& candidate : {profile.p0(), profile.p1(), middle}) {
      const auto cost = quadrics_.get_cost()(profile, boost::optional<Point3>(candidate));
      if (cost && (!best || *cost < best_cost)) best = candidate, best_cost = *cost;
    }
    return best;
  }

  const Quadrics& quadrics_;
  const Curves& curves_;
};

/// What the collapses change, shared by the copies CGAL makes of the visitor.
struct CollapseState {
  Curves curves;
  std::size_t facets = 0;
  std::size_t collapsed = 0;
  // The edge being collapsed, recorded before CGAL removes it.
  bool on_curve = false, corner = false, left = false, right = false;
  std::size_t removed_facets = 0;
  /// Per input vertex, the vertex it was collapsed into (itself while it
  /// stands): a union-find whose roots are the output's vertices.
  std::vector<std::uint32_t> merged_into;
  /// The facets by place, kept up to date through the collapses.
  detail::FacetGrid* grid = nullptr;
  std::uint32_t root(std::uint32_t v) {
    while (merged_into[v] != v) v = merged_into[v] = merged_into[merged_into[v]];
    return v;
  }
};

/// Keeps the curve flags on the vertex and the edges that survive a
/// collapse, and counts the facets left.
class CurveKeeper : public SMS::Edge_collapse_visitor_base<Mesh> {
 public:
  CurveKeeper(CollapseState& state, const Progress& progress, std::size_t target)
      : state_(&state), progress_(&progress), start_(state.facets), target_(target) {}

  void OnCollapsing(const Profile& profile, const boost::optional<Point3>&) const {
    const Mesh& mesh = profile.surface_mesh();
    const Curves& c = state_->curves;
    state_->on_curve = c.on_curve[profile.v0()] || c.on_curve[profile.v1()];
    state_->corner = c.corner[profile.v0()] || c.corner[profile.v1()];
    // Of each facet the edge bounds, the two other edges become one.
    state_->left = profile.left_face_exists() && (c.edge[mesh.edge(profile.vL_v0())] || c.edge[mesh.edge(profile.v1_vL())]);
    state_->right = profile.right_face_exists() && (c.edge[mesh.edge(profile.v0_vR())] || c.edge[mesh.edge(profile.vR_v1())]);
    state_->removed_facets = static_cast<std::size_t>(profile.left_face_exists()) + profile.right_face_exists();
    // The facets around the edge change or go: out of the grid while their
    // corners are where the grid put them.
    for (VertexIndex v : {profile.v0(), profile.v1()})
      for (Mesh::Face_index f : CGAL::faces_around_target(mesh.halfedge(v), mesh))
        if (f != Mesh::null_face()) state_->grid->erase(f);
  }

  void OnCollapsed(const Profile& profile, VertexIndex kept) const {
    const Mesh& mesh = profile.surface_mesh();
    const VertexIndex removed = kept == profile.v0() ? profile.v1() : profile.v0();
    state_->merged_into[removed.idx()] = static_cast<std::uint32_t>(kept.idx());
    Curves& c = state_->curves;
    c.on_curve[kept] = state_->on_curve;
    c.corner[kept] = state_->corner;
    if (profile.left_face_exists() && state_->left) mark(mesh, kept, profile.vL());
    if (profile.right_face_exists() && state_->right) mark(mesh, kept, profile.vR());
    for (Mesh::Face_index f : CGAL::faces_around_target(mesh.halfedge(kept), mesh))
      if (f != Mesh::null_face()) state_->grid->insert(f);
    state_->facets -= state_->removed_facets;
    ++state_->collapsed;
    // Towards the budget; with a tolerance alone, the share of facets gone
    // (its end is unknown until no collapse passes).
    if (state_->collapsed % 512 == 0 && start_ > target_)
      report_progress(*progress_, "decimation", static_cast<double>(start_ - state_->facets) / static_cast<double>(start_ - target_));
  }

 private:
  void mark(const Mesh& mesh, VertexIndex a, VertexIndex b) const {
    const auto [h, found] = CGAL::halfedge(a, b, mesh);
    if (found) state_->curves.edge[mesh.edge(h)] = true;
  }

  CollapseState* state_;
  const Progress* progress_;
  std::size_t start_, target_;
};

/// Stops when the facet count reaches the budget.
/// Stops when the facet count reaches the budget, or past `cost_limit`:
/// a round after crossings stops at the quadric error the first round
/// reached, so that the frozen regions' share of the budget is not taken
/// from the rest of the surface (which would then bend into chords across
/// curved faces). `highest` gets the largest error the round went to.
struct FacetBudget {
  const std::size_t& facets;
  std::size_t target;
  double cost_limit;
  double* highest;
  bool operator()(const double& cost, const Profile&, std::size_t, std::size_t) const {
    if ((target > 0 && facets <= target) || cost > cost_limit) return true;
    *highest = std::max(*highest, cost);
    return false;
  }
};

/// The filters: CGAL's bounded normal change; no new facet across another
/// (facet_grid.h); CGAL's polyhedral envelope of the input mesh.
class CollapseFilter {
 public:
  CollapseFilter(bool bounded_normal_change, double tolerance, detail::FacetGrid& grid)
      : normal_change_(bounded_normal_change), grid_(&grid) {
    if (tolerance > 0) envelope_ = std::make_shared<SMS::Polyhedral_envelope_filter<Kernel>>(tolerance);
  }
  boost::optional<Point3> operator()(const Profile& profile, boost::optional<Point3> placement) const {
    if (placement && normal_change_) placement = SMS::Bounded_normal_change_filter<>()(profile, placement);
    if (placement && crosses(profile, *placement)) placement = boost::none;
    if (placement && envelope_) placement = (*envelope_)(profile, placement);
    return placement;
  }

 private:
  /// Whether a facet of the star, its moving corner at `placement`, meets a
  /// facet outside the star. Profile::triangles() lists the edge's own
  /// facets first, then the star's with the moving corner second.
  bool crosses(const Profile& profile, const Point3& placement) const {
    const Mesh& mesh = profile.surface_mesh();
    const auto& triangles = profile.triangles();
    std::size_t skip = static_cast<std::size_t>(profile.left_face_exists()) + profile.right_face_exists();
    for (auto t = triangles.begin() + static_cast<std::ptrdiff_t>(std::min(skip, triangles.size())); t != triangles.end(); ++t)
      if (grid_->crosses(Kernel::Triangle_3(mesh.point(t->v0), placement, mesh.point(t->v2)), {profile.v0(), profile.v1(), t->v0, t->v2}))
        return true;
    return false;
  }

  bool normal_change_;
  detail::FacetGrid* grid_;
  std::shared_ptr<SMS::Polyhedral_envelope_filter<Kernel>> envelope_;
};

/// Mean edge length of the mesh: the grid's cell is twice it.
double mean_edge(const Mesh& mesh) {
  double sum = 0;
  for (EdgeIndex e : mesh.edges()) sum += std::sqrt(CGAL::squared_distance(mesh.point(mesh.vertex(e, 0)), mesh.point(mesh.vertex(e, 1))));
  return mesh.number_of_edges() > 0 ? sum / static_cast<double>(mesh.number_of_edges()) : 1.0;
}

/// Marks the `frozen` input vertices as corners: they keep their place, and
/// their edges collapse only into them. The CGAL mesh's vertex i is input
/// vertex i (polygon_soup_to_polygon_mesh adds the points in order).
void freeze(const std::vector<bool>& frozen, Curves& curves) {
  for (std::size_t i = 0; i < frozen.size(); ++i)
    if (frozen[i]) curves.on_curve[VertexIndex(static_cast<std::uint32_t>(i))] = curves.corner[VertexIndex(static_cast<std::uint32_t>(i))] = true;
}

/// Freezes the input vertices that were collapsed into a vertex of a
/// crossing facet: where the collapse made the crossing, the next round keeps
/// the input's facets.
std::size_t freeze_crossings(const Mesh& mesh, const std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>>& pairs,
                             CollapseState& state, std::vector<bool>& frozen) {
  std::vector<bool> crossing_vertex(frozen.size(), false);
  for (const auto& pair : pairs)
    for (Mesh::Face_index f : {pair.first, pair.second})
      for (VertexIndex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
        // With their neighbours: the crossing's whole neighbourhood stays fine.
        crossing_vertex[v.idx()] = true;
        for (VertexIndex w : CGAL::vertices_around_target(mesh.halfedge(v), mesh)) crossing_vertex[w.idx()] = true;
      }
  std::size_t added = 0;
  for (std::uint32_t i = 0; i < frozen.size(); ++i)
    if (!frozen[i] && crossing_vertex[state.root(i)]) frozen[i] = true, ++added;
  return added;
}

/// Collapses that still bring facets across others (folds around a shared
/// corner, which the grid leaves to the normal-change filter) are undone by
/// collapsing again with the vertices around the crossings frozen, up to
/// this many times.
constexpr int kFreezeRounds = 8;

}  // namespace

DecimationResult decimate(SurfaceMesh& surface, const std::vector<Polyline>& feature_curves, const DecimationOptions& options,
                          const Progress& progress) {
  options.check();
  if (!options.active()) throw InvalidArgument("decimation needs a facet budget or a tolerance (both are 0)");
  DecimationResult result;
  result.input_facets = result.output_facets = surface.faces.size();
  if (options.facets > 0 && surface.faces.size() <= options.facets) return result;
  const double tolerance = options.tolerance * bounding_box(surface.vertices).diagonal();
  std::vector<bool> frozen(surface.vertices.size(), false);
  double cost_limit = std::numeric_limits<double>::infinity();
  for (int round = 0;; ++round) {
    DecimationResult attempt = result;
    Mesh mesh = to_surface_mesh(surface);
    CollapseState state;
    state.curves = mark_curves(mesh, feature_curves, options.sharp_angle, attempt);
    freeze(frozen, state.curves);
    attempt.frozen_vertices = static_cast<std::size_t>(std::count(frozen.begin(), frozen.end(), true));
    state.merged_into.resize(mesh.number_of_vertices());
    std::iota(state.merged_into.begin(), state.merged_into.end(), 0u);
    state.facets = mesh.number_of_faces();
    detail::FacetGrid grid(mesh, 2 * mean_edge(mesh));
    state.grid = &grid;
    Quadrics quadrics(mesh);
    // Progress follows the first collapse; a second one is a repair of it.
    const Progress silent;
    double highest = 0;
    SMS::edge_collapse(mesh, FacetBudget{state.facets, options.facets, cost_limit, &highest},
                       CGAL::parameters::get_cost(quadrics)
                           .get_placement(CurvePlacement(quadrics, state.curves))
                           .filter(CollapseFilter(options.bounded_normal_change, tolerance, grid))
                           .visitor(CurveKeeper(state, round == 0 ? progress : silent, options.facets)));
    attempt.collapsed_edges = state.collapsed;
    attempt.output_facets = state.facets;
    attempt.budget_missed = options.facets > 0 && state.facets > options.facets;
    attempt.rounds = round + 1;
    std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> crossing;
    CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(crossing));
    attempt.crossing_pairs = crossing.size();
    if (round == 0) cost_limit = highest;
    if (crossing.empty() || round + 1 == kFreezeRounds || freeze_crossings(mesh, crossing, state, frozen) == 0) {
      // Cancelled up to here, the caller's mesh is as it was.
      report_progress(progress, "decimation", 1.0);
      surface = from_surface_mesh(mesh);
      return attempt;
    }
  }
}

}  // namespace sharpmesh
