// Delaunay refinement surface meshing (Boissonnat & Oudot 2005; thesis 6.2.1, 7.3).
#pragma once

#include <cstdint>
#include <vector>

#include "sharpmesh/implicit.h"
#include "sharpmesh/progress.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

/// Facet criteria of Section 6.2.1. A facet is bad when an angle is below
/// `angle`, when an edge is longer than `edge_length`, or when its centre is
/// farther than `distance` from the centre of its surface Delaunay ball.
/// The edge-length bound is enforced through the radius of the surface
/// Delaunay ball (radius <= edge_length / 2 bounds every edge by edge_length).
struct RefinementCriteria {
  double angle = 25.0;        ///< degrees, 7.3.2
  double edge_length = 0.0;   ///< l = 2 d', 7.3.2
  double distance = 0.0;      ///< d = 0.6 d', 7.3.2
  void check() const;
  /// The thesis's criteria for a protecting-ball spacing d' (7.3.2).
  static RefinementCriteria from_spacing(double d_prime);
};

/// Protecting balls on sharp-feature polylines (7.3.2). Balls are placed by
/// CGAL's Mesh_3 protection, which keeps consecutive balls overlapping and
/// shrinks balls where non-consecutive ones would intersect; the centre
/// spacing follows the radius.
struct FeatureProtection {
  /// Polylines to keep as chains of mesh edges; closed when front() == back().
  /// Polylines meeting at a shared end point make a corner there.
  std::vector<Polyline> polylines;
  double ball_radius = 0.0;  ///< data units; the thesis's 2/3 d' (7.3.2)
  /// Beyond the thesis (its future work, 8.2): grow a ball to reach the
  /// implicit surface where the polyline lies off it (the gap of Fig. 7.18):
  /// radius = max(ball_radius, gap_margin x gap), up to max_ball_radius.
  bool adapt_to_gap = true;
  double gap_margin = 1.5;
  double max_ball_radius = 0.0;  ///< data units; 0: 3 x ball_radius
  /// Polylines closer than this to a longer one are not protected
  /// (drop_close_polylines); data units, 0: all are.
  double min_separation = 0.0;
  /// Leave to the implicit surface the polylines that run mostly over parts
  /// thinner than the balls' diameter (drop_protection_on_thin_parts).
  bool drop_on_thin_parts = false;
};

/// A stretch of a protected polyline that the output mesh does not follow
/// (its balls miss the implicit surface).
struct UncoveredGap {
  Vec3 center{0, 0, 0};  ///< midpoint of the stretch
  double length = 0;     ///< length of the stretch
  double gap = 0;        ///< largest polyline-to-surface distance on it (-1: not found; null in the report)
  /// Left out because CGAL's Mesh_3 failed next to it (close or tangled
  /// features; CGAL issue #9102), and the refinement was run again without it.
  bool refused_by_mesher = false;
  /// Left out because it runs closer than FeatureProtection::min_separation
  /// to a longer polyline (balls that thin miss the surface).
  bool too_close = false;
  /// Left out because the part under it is thinner than the diameter of its
  /// protecting balls (drop_protection_on_thin_parts).
  bool on_thin_part = false;
};

/// Removes, shortest first, each polyline whose interior (away from its
/// ends) lies for more than half within `min_separation` of another kept
/// polyline; each removed one is reported. Returns the number removed.
std::size_t drop_close_polylines(std::vector<Polyline>& polylines, double min_separation, std::vector<UncoveredGap>& dropped);

/// Removes every polyline that runs, for more than half of its length,
/// within `ball_radius` of a thin point (ImplicitMeshingOptions::thin_points)
/// whose thickness is below the balls' diameter; each one removed is
/// reported. Returns the number removed.
std::size_t drop_protection_on_thin_parts(std::vector<Polyline>& polylines, const std::vector<Vec3>& thin_points,
                                          const std::vector<double>& thin_thickness, double ball_radius,
                                          std::vector<UncoveredGap>& dropped);

/// The polylines as CGAL's feature protection needs them (its curves may
/// meet only at their ends): points within `tolerance` of each other become
/// one point, and every polyline is cut where it passes through the end of
/// another or shares a point with another (a closed loop through corners
/// becomes open pieces between them). Loops whose ends miss each other by
/// less than `tolerance` are closed; consecutive repeats, pieces of one
/// point and repeated pieces are dropped. Throws InvalidInput on a
/// non-finite coordinate.
std::vector<Polyline> curves_for_protection(const std::vector<Polyline>& polylines, double tolerance);

struct ImplicitMeshingOptions {
  RefinementCriteria criteria;
  FeatureProtection features;
  /// Refuse to start when the estimated facet count is above this (0: no limit).
  std::size_t max_facets = 5'000'000;
  /// Facets the data suggests (0: unknown). Refinement stops with an error
  /// past 8x this many facets: the implicit surface is then far larger than
  /// the data (inconsistent normals, an open or thin surface).
  double expected_facets = 0;
  /// Beyond the thesis: points near the surface (e.g. the input points
  /// thinned to one per `seed_spacing`), each projected onto the surface and
  /// inserted before refinement where no vertex lies within seed_spacing / 2,
  /// so every part of the data starts with a vertex. Without them a coarse
  /// refinement steps over parts thinner than its facets (a thin wall whose
  /// two sides one Voronoi edge crosses shows no sign change).
  std::vector<Vec3> data_seeds;
  double seed_spacing = 0;  ///< data units; 0: the maximum edge length
  /// One spacing per data seed (empty: seed_spacing for all); seeds are
  /// inserted densest first.
  std::vector<double> data_seed_spacings;
  /// Beyond the thesis (issue 36; the local-feature-size sizing the thesis
  /// names as future work, 8.2): points of thin material or narrow gaps and
  /// their local thickness (data units, one per point). Within twice its
  /// thickness of such a point the surface Delaunay balls are bounded by
  /// that thickness instead of the uniform facet size, so the restricted
  /// Delaunay triangulation keeps the two sheets apart, and the facet
  /// distance by a quarter of it, but not below `thin_min_distance`.
  std::vector<Vec3> thin_points;
  std::vector<double> thin_thickness;
  /// Data units; the implicit surface is no more accurate than the sampling
  /// spacing, and a tighter bound only chases its ripples (and, past an open
  /// boundary, the closing sheet the trim then has to cut).
  double thin_min_distance = 0;
  std::uint32_t seed = 0;
  /// Ball-size queries CGAL's feature protection may make (0: no limit).
  /// Past them it is stopped and the surface meshed without protection,
  /// every polyline reported as uncovered: a safety net for a curve that
  /// CGAL walks for ever (loop ends that miss each other by a rounding
  /// error did, before they were welded). A count, not a time, so that the
  /// mesh does not depend on the machine.
  std::size_t protection_query_limit = 0;
  void check() const;
};

struct ImplicitMeshingResult {
  SurfaceMesh mesh;
  /// Mesh edges that represent protected polylines, chained into polylines.
  std::vector<Polyline> feature_edges;
  std::size_t protecting_balls = 0;      ///< corner and edge balls
  std::size_t enlarged_balls = 0;        ///< balls grown to reach the surface
  /// After CGAL's protection, two balls that are not neighbours on one
  /// polyline still intersect (polylines closer than two of its smallest
  /// balls, or its 29 rounds of shrinking ran out): there the refinement
  /// may not keep the polylines apart (7.3.2's guarantee needs disjoint
  /// balls).
  bool protecting_balls_intersect = false;
  /// The protection ran past protection_query_limit and was stopped; the
  /// mesh was made without protection.
  bool protection_stopped = false;
  std::size_t protection_queries = 0;    ///< ball-size queries of the last protection run
  std::size_t protected_segments = 0;    ///< segments between consecutive balls
  std::size_t represented_segments = 0;  ///< of those, edges of the output mesh
  double max_gap = 0;                    ///< largest polyline-to-surface distance measured at a ball
  std::vector<UncoveredGap> uncovered;
  std::size_t data_seeds = 0;         ///< data seeds inserted before refinement
  std::size_t refinement_steps = 0;   ///< Mesher_3 steps
  bool refinement_stalled = false;    ///< stopped after many steps without a new vertex
  bool refinement_runaway = false;    ///< stopped: piling new vertices onto one spot, or far past the expected count
  std::size_t mesher_retries = 0;     ///< refinements run again after a CGAL failure next to a feature
  std::size_t runaway_stopped_at = 0; ///< vertices of the last refinement stopped as running away (0: none was)
};

/// Meshes the zero level set of `surface` inside its bounding sphere by
/// Delaunay refinement (6.2.1), with the polylines of `options.features`
/// protected by weighted points (7.3.2). The result is the boundary of the
/// meshed volume: closed and, with the manifold option of CGAL's Mesh_3,
/// manifold.
/// Radius, around the surface's bounding centre, of the ball the refinement
/// meshes in: the surface lies well inside its bounding sphere.
double meshing_domain_radius(const ImplicitSurface& surface);

ImplicitMeshingResult mesh_implicit_surface(const ImplicitSurface& surface, const ImplicitMeshingOptions& options,
                                            const Progress& progress = {});

/// Open surfaces (beyond the thesis): removes the facets whose centroid is
/// farther than `max_distance` from every point of `points` (where Poisson
/// closed a hole or an open sheet with invented surface), then the vertices
/// no facet uses. Returns the number of facets removed.
std::size_t trim_far_from_points(SurfaceMesh& mesh, const std::vector<Vec3>& points, double max_distance);

/// Removes the connected components (facets sharing vertices) whose median
/// vertex lies farther than `max_distance` from every point of `points`:
/// bubbles of an implicit function that carry no data (a sphere in a cavity
/// leaves Poisson a second zero set in the gap). A component on the data
/// keeps every facet. Returns the number of facets removed.
std::size_t remove_components_off_points(SurfaceMesh& mesh, const std::vector<Vec3>& points, double max_distance);

/// Removes the closed connected components, other than the largest, that
/// enclose a space thinner than `max_solid` (solids, by their signed
/// volume) or `max_cavity` (cavities, facing inwards): the ray from nine
/// tenths of the area into the enclosed side meets the component within it.
/// Such a cavity is the air of a gap too narrow for the data, left as a
/// shell of its own where the implicit function bridged the gap's openings.
/// A threshold of 0 removes nothing of its kind. Returns the number of
/// facets removed.
std::size_t remove_thin_shell_components(SurfaceMesh& mesh, double max_solid, double max_cavity);

/// Gaps inside the data are kept, its outer edge is not extended: removes
/// the facets with no corner and no centroid within `max_distance` of the
/// points, unless the points within `bridge` local spacings of the centroid
/// surround it (those within 30 degrees of the facet's plane leave no
/// angular gap of half a turn around it). The local spacing there is the
/// median, over the 8 points nearest to it, of their mean distance to their
/// 6 nearest (robust to isolated outliers). bridge = 0: no bridging.
/// Returns the number of facets removed.
std::size_t trim_unless_bridging(SurfaceMesh& mesh, const std::vector<Vec3>& points, double max_distance, double bridge);

/// Hole filling (the remedy of thesis 6.6): boundary cycles up to this
/// perimeter are closed by a triangulated, refined and faired disc patch.
struct HoleFillingOptions {
  double max_perimeter = 0;      ///< data units; 0 fills nothing
  std::size_t max_edges = 2000;  ///< longer cycles are left open (the patch search is cubic at worst)
  /// The filling separates the sheets meeting at non-manifold edges and
  /// vertices (duplicating vertices); true joins them again by position
  /// afterwards, false keeps the mesh a manifold.
  bool merge_split_vertices = true;
  void check() const;
};

struct HoleFillingStats {
  std::size_t holes = 0;         ///< boundary cycles found
  std::size_t filled = 0;        ///< of those, closed
  std::size_t unfaired = 0;      ///< closed, but the fairing failed (the patch is only refined)
  std::size_t failed = 0;        ///< short enough, but no patch was found
  std::size_t added_facets = 0;
};

/// Fills the holes of `mesh` (any orientation, non-manifold vertices
/// allowed) whose perimeter is at most options.max_perimeter.
HoleFillingStats fill_holes(SurfaceMesh& mesh, const HoleFillingOptions& options, const Progress& progress = {});

/// What make_manifold found and changed.
struct ManifoldRepairStats {
  std::size_t non_manifold_edges = 0;   ///< edges with more than two facets, before
  std::size_t duplicated_vertices = 0;  ///< copies made to separate the sheets meeting there
  std::size_t flipped_facets = 0;       ///< to agree with their neighbours
};

/// Makes a triangle mesh a combinatorial manifold, consistently oriented:
/// CGAL's orient_polygon_soup separates the sheets that meet at a
/// non-manifold edge or vertex (duplicating its vertices) and flips facets
/// until neighbours agree; each connected part then keeps the orientation
/// most of its facets had. Facets and positions are kept.
ManifoldRepairStats make_manifold(SurfaceMesh& mesh);

/// Self-intersection repair: the facets that cross others, with `rings`
/// rings of neighbours (one more each round), are cut out and the holes
/// closed by fill_holes, until no pair crosses or `max_rounds` are done.
struct IntersectionRepairOptions {
  int max_rounds = 3;
  int rings = 1;
  void check() const;
};

struct IntersectionRepairStats {
  std::size_t intersecting_pairs = 0;  ///< crossing facet pairs before the repair
  std::size_t remaining_pairs = 0;     ///< after it (0: the mesh no longer self-intersects)
  std::size_t removed_facets = 0;
  std::size_t added_facets = 0;
  int rounds = 0;
};

/// Repairs the self-intersections of `mesh` in place (see IntersectionRepairOptions).
IntersectionRepairStats repair_self_intersections(SurfaceMesh& mesh, const IntersectionRepairOptions& options = {},
                                                  const Progress& progress = {});

/// Flattening of the facets along protected edges (beyond the thesis).
struct FlatteningOptions {
  double radius = 0;           ///< data units: input points within this of a vertex fit its face plane
  double max_move = 0;         ///< data units: vertices farther than this from the plane stay
  double max_residual = 0;     ///< data units: planes whose RMS residual is above this are not used
  double max_angle_deg = 20;   ///< points whose normal is farther than this from the mesh's are on another face
};

/// Moves each vertex that shares a facet with a feature vertex (a vertex of
/// `feature_edges`, which are polylines through mesh vertices) onto the
/// plane fitted to the input points near it whose unoriented normals agree
/// with the mesh's vertex normal: the face it lies on. The Poisson surface
/// is rounded next to sharp edges, so without this these facets lean.
/// Returns the number of vertices moved.
std::size_t flatten_next_to_features(SurfaceMesh& mesh, const std::vector<Polyline>& feature_edges,
                                     const std::vector<Vec3>& points, const std::vector<Vec3>& normals,
                                     const FlatteningOptions& options);

/// After vertex moves (flattening, snapping): the moved vertices (those
/// that differ from `before`) of intersecting facets go back, until no
/// facets intersect or none of theirs moved; if eight rounds still leave an
/// intersection, every move goes back. Returns the number of vertices put back.
std::size_t undo_intersecting_moves(SurfaceMesh& mesh, const std::vector<Vec3>& before);

/// Snapping (beyond the thesis): mesh vertices moved onto the corners and
/// data points the mesh misses. Distances in data units.
struct SnappingOptions {
  double max_move = 0;        ///< a vertex moves at most this far, onto a target at most this far off the mesh
  double corner_present = 0;  ///< a corner this close to the mesh is in it
  double data_present = 0;    ///< an input point this close to the mesh is on it
  double support_radius = 0;  ///< an off point needs `min_support` other points off by data_present / 2 within this (no outlier pulls)
  std::size_t min_support = 2;
  /// The input points are targets too (clean clouds); either way they judge
  /// the corner moves: one that takes the vertex's facets farther from the
  /// points within support_radius of them (distances capped at max_move) is
  /// refused, as from a flat face down to a junction misplaced below it.
  bool points_are_targets = true;
  /// With a spacing, a corner move must also not add mesh area away from the
  /// points (farther than data_present, one point per spacing squared): a
  /// junction misplaced into a wall draws a spike that no point is near
  /// (seen on CGAL's couplingdown, one and a half to two spacings off).
  /// 0: not checked.
  double average_spacing = 0;
  /// With a normal per input point: a vertex farther than data_present from
  /// the tangent disks (one spacing wide) of its eight nearest points moves
  /// onto the nearest disk, judged like a corner move (a bridge over an
  /// undersampled slot, a dent into a thin wall: couplingdown 50k, 1.1-1.3
  /// spacings off).
  std::vector<Vec3> point_normals;
};

struct SnappingStats {
  std::size_t corners = 0;      ///< vertices moved onto corners
  std::size_t data_points = 0;  ///< vertices moved onto input points the mesh missed
  std::size_t off_data_vertices = 0;  ///< vertices away from the data moved onto its tangent planes
  std::size_t undone = 0;       ///< moves undone because they made facets intersect
};

/// At acute corners and on the tops of walls thinner than two spacings the
/// Poisson surface is rounded by more than the protecting balls there can
/// reach, so the mesh misses the corner and the data by 1.5 spacings.
/// Each corner (first) and each input point (then) farther than its
/// `present` distance from the mesh, worst first, takes the nearest vertex
/// not moved yet, within max_move, and with normals each vertex away from
/// the data moves onto it (see point_normals), unless a facet of the vertex
/// would turn over, fall below 10 degrees or meet another facet; any
/// intersection left is undone (all moves when eight rounds of undoing
/// leave one).
SnappingStats snap_to_corners_and_data(SurfaceMesh& mesh, const std::vector<Vec3>& corners, const std::vector<Vec3>& points,
                                       const SnappingOptions& options);

/// Open surfaces (beyond the thesis): cuts the facets between the boundary
/// and the data (those with a vertex beyond the clip distance, connected to
/// the boundary through such facets) along the level set where the distance
/// to the nearest point of `points` equals the clip distance:
/// max(min_distance, 2 x the median vertex-to-data distance, which grows
/// with noise). Closed meshes are unchanged. Returns the number of facets
/// cut or removed.
std::size_t clip_boundary_to_points(SurfaceMesh& mesh, const std::vector<Vec3>& points, double min_distance);

/// Number of mesh edges with exactly one incident facet.
std::size_t count_boundary_edges(const SurfaceMesh& mesh);

/// Rough facet count of a mesh with the given criteria on a surface of the
/// given area (equilateral facets of edge `edge_length`, halved to account
/// for curvature-driven refinement being rare on CAD data).
double estimate_facet_count(double area, const RefinementCriteria& criteria);

}  // namespace sharpmesh
