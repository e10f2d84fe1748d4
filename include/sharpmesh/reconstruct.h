// The point-cloud-to-mesh pipeline of Chapter 7: sharp features (7.2),
// normals (if missing; CVCM normals, 7.4), Poisson implicit function, and
// Delaunay refinement with the 7.3.2 criteria derived from one parameter
// delta, the feature polylines protected by weighted points. Without
// features it is the thesis's PIF baseline (7.3.1).
#pragma once

#include <string>
#include <vector>

#include "sharpmesh/compact.h"
#include "sharpmesh/features.h"
#include "sharpmesh/implicit.h"
#include "sharpmesh/meshing.h"
#include "sharpmesh/pointset.h"
#include "sharpmesh/progress.h"
#include "sharpmesh/timing.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

/// Where unoriented normals come from when the input has none.
/// Where the normals a reconstruction used came from.
enum class NormalOrigin { Input, InputReoriented, Cvcm, Jet, Pca };
/// "input", "input (re-oriented)", "cvcm", "jet", "pca".
const char* to_string(NormalOrigin origin);

enum class NormalSource {
  Automatic,  ///< CVCM when features are extracted, else jet fitting
  Cvcm,       ///< eigenvector of the largest eigenvalue of the convolved VCM (7.4)
  Estimated,  ///< PCA or jet fitting over k neighbours (App. A.7), see `normals`
};

/// Which sharp features to protect.
enum class FeatureMode {
  Extract,  ///< extract them from the cloud (7.2)
  Given,    ///< use `given_features`
  None,     ///< the PIF baseline (7.3.1)
};

/// The thresholds of the repairs beyond the thesis, one documented field
/// each (docs/design-notes.md gives the reasons). Lengths are in average
/// spacings (avg) or in d'; `noise` is the feature extraction's estimate,
/// allowed for `noise_deviations` times wherever a distance decides.
struct ReconstructTuning {
  /// Automatic normals: a CVCM whose largest eigenvalue is less than this
  /// many times the next is isotropic (a thin part or a needle tip inside
  /// the offset radius), and its point takes a jet normal (7.4).
  double min_cvcm_anisotropy = 20;
  /// Automatic normals: a Poisson function agreeing with fewer of its CVCM
  /// normals than this fraction is solved again from jet normals, and the
  /// function that agrees better is kept.
  double min_normal_agreement = 0.9;
  /// Input normals agreeing in sign with an MST orientation on at least this
  /// fraction of the points (or on at most 1 - it) are used as given; in
  /// between, each takes the orientation's sign.
  double input_normal_consensus = 0.9;
  /// Crease-aware normals replace jet normals only on clouds whose noise is
  /// below this [avg]: on noisier ones the plane fits are no sharper.
  double sharpen_max_noise = 0.25;
  /// Noise deviations allowed wherever a distance decides (data fit, snapping).
  double noise_deviations = 3;
  /// A point is off the mesh farther than max(this [avg], the surface
  /// distance criterion 0.6 d') + noise_deviations x noise.
  double off_data_min = 1.5;
  /// The sign repair and the data-fit retry solve Poisson again only for at
  /// least this many points, or one point in repair_one_point_in when more:
  /// a few scattered wrong normals barely move the function.
  std::size_t repair_min_points = 10;
  std::size_t repair_one_point_in = 5000;
  /// The data-fit retry's second flip set: the points off the mesh within
  /// this distance of those against it [avg].
  double retry_reach = 3;
  /// Flattening: face planes fitted within min(ball radius x d', this [avg]);
  /// the rounding is at the data's scale, whatever delta.
  double flatten_radius = 3;
  /// Flattening: a vertex moves at most min(flatten_max_move x d',
  /// flatten_max_move_spacings [avg]), onto a plane whose residual is at
  /// most flatten_max_residual x d'.
  double flatten_max_move = 0.25;
  double flatten_max_move_spacings = 2;
  double flatten_max_residual = 0.15;
  /// Snapping: a vertex moves at most this [avg] + the noise allowance
  /// (the rounding Poisson leaves is 1-1.5 spacings).
  double snap_max_move = 2;
  /// Snapping: corners and data points the mesh misses by more than these
  /// [avg] + the noise allowance take a vertex.
  double snap_corner_distance = 0.25;
  double snap_data_distance = 0.75;
  /// Snapping: a move must not take the facets farther from the points
  /// within this radius [avg].
  double snap_support_radius = 1.5;
  /// Thin shells: a closed component other than the largest goes when the
  /// space it encloses is thinner than max(this [avg], the noise allowance)
  /// over nine tenths of its area: a solid below the two spacings the
  /// pipeline resolves, a cavity (the air of a gap whose openings the
  /// implicit function bridged) up to a wider space. 0: none.
  double thin_solid_max = 1.5;
  double thin_cavity_max = 2.5;
  /// Throws InvalidArgument naming the field that is out of its range.
  void check() const;
};

struct ReconstructOptions {
  double delta = 3.5;  ///< d' = delta * avg (7.3.2; Fig. 7.10a)
  int spacing_k = 6;   ///< avg = mean distance to the 6 nearest neighbours (7.3.2)
  /// avg in the input's unit when the caller knows it (0: measured on the
  /// input). The tiles of one cloud take their whole cloud's, so that d'
  /// and every length in spacings agree across a seam (sharpmesh/tiled.h).
  double average_spacing = 0;
  FeatureMode feature_mode = FeatureMode::Extract;
  FeatureOptions features;               ///< used with FeatureMode::Extract
  WallOptions walls;                     ///< walls under roof edges of airborne scans (beyond the thesis)
  std::vector<Polyline> given_features;  ///< used with FeatureMode::Given
  double ball_radius = 2.0 / 3.0;        ///< protecting-ball radius, fraction of d' (7.3.2)
  bool adapt_balls_to_gap = true;        ///< grow balls to reach the implicit surface (beyond the thesis)
  /// Open surfaces: remove facets farther than trim_distance x d' + 2 avg
  /// from every input point (0: keep Poisson's closed surface everywhere).
  double trim_distance = 1.0;
  /// Open surfaces: after the trim, cut the facets that overhang the data at
  /// the mesh's boundary along the level set at about one spacing from it
  /// (clip_boundary_to_points). Off where the caller trims by its own rule.
  bool clip_boundary = true;
  /// Poisson is solved on a grid simplification with cells of
  /// poisson_spacing x d' (0: on every point). Beyond the thesis: the
  /// function only has to be accurate at the scale of the mesh.
  double poisson_spacing = 0;
  /// Poisson samples closer than poisson_thinning x avg to an earlier one
  /// are left out (0: none). Beyond the thesis: near-coincident pairs of a
  /// random sampling cost CGAL's Poisson most of its Steiner points.
  double poisson_thinning = 0.4;
  /// Poisson's pull of the function towards the samples, relative to its
  /// Laplacian, with lengths in average spacings (PoissonOptions::screening):
  /// the same surface whatever the cloud's unit. 0: CGAL's, unit-dependent.
  double poisson_screening = PoissonOptions{}.screening;
  /// The same on clouds the feature extraction found noisy (denoised, or a
  /// noise estimate of 0.05 avg or more): a noisy point is no better than
  /// the smooth surface (fandisk and oblong 50k with 0.5% and 1% noise: mean
  /// error lowest at 1 of 0.3 / 1 / 3 / 12, by 10-17% against 12).
  double poisson_screening_noisy = 1;
  /// Before refinement, one input point per cell of data_seed_spacing x d'
  /// is projected onto the implicit surface and inserted, and more where the
  /// solid or a gap is thinner than half that (0: none). Beyond the thesis:
  /// parts thinner than the facets (thin walls, narrow slots) are not
  /// stepped over by the refinement.
  double data_seed_spacing = 2.0;
  /// Beyond the thesis: the vertices that share a facet with a protected
  /// edge are moved onto the plane of the data's face (flatten_next_to_features).
  bool flatten_features = true;
  /// Beyond the thesis: corners (junctions of two or more polylines) and,
  /// on clean clouds, input points the mesh misses each take a mesh vertex
  /// near them (snap_to_corners_and_data; distances in `tuning`). With
  /// extracted features only: the PIF baseline stays the thesis's.
  bool snap_vertices = true;
  /// Beyond the thesis: the facets of the output that cross others are cut
  /// out with a ring of neighbours and the holes filled
  /// (repair_self_intersections); ReconstructResult::intersection_repair
  /// says whether any crossing remains.
  bool repair_self_intersections = true;
  NormalSource normal_source = NormalSource::Automatic;
  NormalEstimationOptions normals;       ///< used when the input has no normals
  NormalOrientationOptions orientation;  ///< used when the input has no normals
  bool recompute_normals = false;        ///< ignore normals present in the input
  /// Compare the input's normals with an MST orientation and re-orient them
  /// when they disagree in sign (false: their signs come from elsewhere,
  /// e.g. the cameras that saw each point, and are used as given).
  bool check_input_normals = true;
  /// Flip the normals the Poisson function contradicts and solve again
  /// (beyond the thesis; not with check_input_normals = false).
  bool repair_normal_signs = true;
  /// With automatic normals and extracted features, after the MST: flip the
  /// regions whose outer side the rest of the cloud encloses, by its
  /// generalized winding number (repair_enclosed_normals; beyond the thesis).
  bool repair_enclosed_normals = true;
  /// With automatic normals and extracted features: grow the tangent MST
  /// from the signs the occupancy and the sheet parity decide
  /// (occupancy_anchors; beyond the thesis, issue 36), not from one seed.
  bool anchor_orientation = true;
  /// Poisson vertices half-way across material and gaps 1-6 spacings thick
  /// (thin_part_vertices; beyond the thesis, issue 36).
  bool thin_part_vertices = true;
  /// After meshing, when input points lie off the mesh (tuning.off_data_min)
  /// with normals against its closest facets (enough of them:
  /// tuning.repair_min_points), flip their normals (and those around them),
  /// solve and mesh again, and keep the new mesh when it leaves a quarter
  /// fewer such points, no more points off in all and none farther (beyond
  /// the thesis; with repair_normal_signs).
  bool refit_off_data = true;
  std::size_t max_facets = 5'000'000;
  /// Beyond the thesis, whose refinement gives every region the same size
  /// d' (its 7.5): with a facet budget or a tolerance, the refined mesh's
  /// edges are collapsed, sharp edges kept (sharpmesh/compact.h). A budget
  /// above the facet count delta gives refines finer first (d' >= avg).
  DecimationOptions compaction;
  /// Ball-size queries the feature protection may make per point of the
  /// protected polylines before the surface is meshed without it
  /// (ImplicitMeshingOptions::protection_query_limit; 0: no limit). Healthy
  /// runs make a few per point (docs/design-notes.md, "Guards"): the default
  /// stops only a protection that walks a curve for ever.
  double protection_budget = 1000;
  std::uint32_t seed = 0;
  /// Worker threads of this call's parallel loops (0: every core). The
  /// limit holds for this call only, not for the process.
  int threads = 0;
  ReconstructTuning tuning;  ///< the repairs' thresholds
  void check(std::size_t n) const;
};

/// Something about a result its user should look at: a stable code
/// (`refinement_runaway`, `points_off_mesh`, ...) and a one-line message.
/// The CLI prints the messages; Python's report lists both.
struct Warning {
  std::string code;
  std::string message;
};

/// The normals stage: where the normals came from and what the orientation
/// and its repairs changed (7.4, App. A.8 and the repairs beyond them).
struct NormalsStats {
  bool normals_estimated = false;
  NormalOrigin normal_origin = NormalOrigin::Input;  ///< where the normals Poisson was solved with came from
  /// The CVCM normals gave a function that contradicts them (agreement under
  /// 0.9) and estimated ones (jet or pca) gave a better one (7.4).
  bool cvcm_fallback = false;
  /// Fewer than half of the file's normals were non-zero: they were estimated instead.
  bool input_normals_unusable = false;
  /// Share of the input's normals whose sign the tangent MST orientation of
  /// their lines keeps (between 0.1 and 0.9: inconsistent, re-oriented); 0 without input normals.
  double input_normal_agreement = 0;
  /// CVCM normals replaced by jet normals where the convolved VCM is
  /// isotropic (lambda0/lambda1 < 20: thin walls, creases, corners).
  std::size_t isotropic_cvcm_normals = 0;
  std::size_t anchored_normals = 0;  ///< normals whose sign the occupancy decided before the MST (exterior_side_votes)
  std::size_t patch_flipped_normals = 0;  ///< normals of patches the creases showed inverted after the MST (repair_inverted_patches)
  std::size_t enclosed_flipped_normals = 0;  ///< normals of regions the rest of the cloud encloses on their outer side (repair_enclosed_normals)
  std::size_t sharpened_normals = 0;  ///< isotropic-CVCM normals replaced by crease-aware ones (shifted planes)
  std::size_t sign_repaired_normals = 0;  ///< normal flips kept by the sign repair against the Poisson function
};

/// The implicit stage: the Poisson function the surface was meshed from.
struct ImplicitStats {
  std::size_t poisson_points = 0;    ///< samples the Poisson equation was solved on
  double normal_agreement = 0;       ///< of the Poisson function with its normals (PoissonDiagnostics)
  double poisson_screening = 0;      ///< the weight used (poisson_screening or poisson_screening_noisy)
  std::size_t thin_part_vertices = 0;  ///< Poisson vertices added inside thin material and gaps
  std::size_t thin_points = 0;         ///< input points where the solid or a gap is thinner than the seed spacing / 2
  bool restricted = false;           ///< the function was cut away from the data (open surfaces)
};

/// The repairs after the refinement (beyond the thesis): trim and clip of
/// open surfaces, flattening next to features, snapping onto the data, the
/// self-intersection repair.
struct RepairStats {
  std::size_t trimmed_facets = 0;    ///< removed far from the data (open surfaces)
  std::size_t dataless_facets = 0;   ///< of whole components off the data, removed (remove_components_off_points)
  std::size_t thin_shell_facets = 0;  ///< of closed components enclosing a space too thin for the data, removed (remove_thin_shell_components)
  std::size_t clipped_facets = 0;    ///< cut where the boundary overhangs the data (open surfaces)
  std::size_t flattened_vertices = 0;  ///< moved onto the face planes next to protected edges
  std::size_t unflattened_vertices = 0;  ///< moves undone because they made facets intersect
  std::size_t snapped_corners = 0;     ///< mesh vertices moved onto corners the refinement missed
  std::size_t snapped_to_data = 0;     ///< mesh vertices moved onto input points the mesh missed
  std::size_t snapped_off_data = 0;    ///< mesh vertices away from the data moved onto its tangent planes
  std::size_t unsnapped_vertices = 0;  ///< snaps undone because they made facets intersect
  IntersectionRepairStats intersection_repair;  ///< crossings found, repaired and left (remaining_pairs)
};

/// The mesh checked against its own input points, and the retries with the
/// normals of the points it leaves out flipped (beyond the thesis).
struct DataFitStats {
  /// Input points farther than off_data_distance = max(1.5 avg, the
  /// surface-distance criterion) + 3 x the noise from the output mesh: data
  /// the surface does not represent (measured with or without refit_off_data).
  std::size_t off_data_points = 0;
  std::size_t off_data_against = 0;  ///< of those, the points whose normal points against the closest facet's
  std::size_t invented_vertices = 0;  ///< mesh vertices farther than off_data_distance from every input point
  std::size_t data_fit_retries = 0;   ///< retries run (0-2)
  double off_data_distance = 0;
  std::size_t off_data_points_before_retry = 0;  ///< off the first mesh (before any retry)
  std::size_t off_data_flips = 0;    ///< normals flipped by the kept retry (0: none kept)
  double max_data_distance = 0;      ///< largest distance of an input point to the output mesh
};

/// What reconstruct() made, stage by stage.
struct ReconstructResult {
  SurfaceMesh mesh;
  double diagonal = 0;  ///< of the input's bounding box: the report gives lengths also as fractions of it
  double average_spacing = 0;
  double d_prime = 0;
  double estimated_facets = 0;
  RefinementCriteria criteria;
  std::size_t input_points = 0;
  std::size_t duplicate_points = 0;  ///< removed: same position as an earlier point
  std::size_t used_points = 0;       ///< after removing duplicated and unorientable points
  std::size_t boundary_edges = 0;    ///< of the output mesh (0: closed)
  FeatureResult features;            ///< when extracted (graph only when given)
  WallResult walls;                  ///< points added under roof edges (sharpmesh/pointset.h)
  NormalsStats normals;
  ImplicitStats implicit;
  ImplicitMeshingResult meshing;     ///< feature protection counts and gaps
  RepairStats repairs;
  DataFitStats data_fit;
  DecimationResult decimation;       ///< with a facet budget or a tolerance (input_facets 0: not run)
  std::vector<Warning> warnings;
  std::vector<StageTiming> stages;
};

/// Surface area suggested by n uniform samples of the given average spacing (k = 6).
double estimated_area_from_spacing(std::size_t n, double average_spacing);

ReconstructResult reconstruct(const PointSet& input, const ReconstructOptions& options = {},
                              const Progress& progress = {});

/// The normals reconstruct() solves Poisson with, on their own: its prepare
/// stage (the input's normals checked, the average spacing, the features of
/// 7.2) and its normals stage (CVCM normals of 7.4 or jet/pca ones, the
/// anchored tangent MST of A.8 and the orientation repairs beyond it).
/// What follows in reconstruct() may still change some: the implicit
/// stage's sign repair and its jet fallback for CVCM normals that Poisson
/// contradicts.
struct NormalsResult {
  PointSet points;  ///< the input without duplicated points, with oriented unit normals
  NormalsStats normals;
  FeatureResult features;  ///< when extracted (graph only when given)
  double average_spacing = 0;
  std::vector<StageTiming> stages;
};

NormalsResult reconstruct_normals(const PointSet& input, const ReconstructOptions& options = {},
                                  const Progress& progress = {});

}  // namespace sharpmesh
