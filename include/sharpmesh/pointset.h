// The point-set toolbox of the thesis's Appendix A, on CGAL's
// Point_set_processing_3, parallel where CGAL allows (TBB).
// All distances are in the data's units unless stated.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "sharpmesh/progress.h"
#include "sharpmesh/timing.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

/// Throws InvalidInput when the set has NaN/inf coordinates, fewer than
/// `min_points` points, or all points at one location.
void check_point_set(const PointSet& points, std::size_t min_points, const char* what);

/// Mean distance from each point to its k nearest neighbours (App. A.3).
/// k = 6 is the thesis's unit length `avg` (7.3.2).
double average_spacing(const PointSet& points, int k = 6, const Progress& progress = {});

/// Removes `percentage` % of the points with the largest average squared
/// distance to their k nearest neighbours (App. A.4). Returns the count removed.
struct PercentageOutlierOptions {
  int k = 24;               ///< App. A.4 example
  double percentage = 5.0;  ///< App. A.4 example
  void check(std::size_t n) const;
};
std::size_t remove_outliers_percentage(PointSet& points, const PercentageOutlierOptions& options = {},
                                       const Progress& progress = {});

/// The 3-sigma rule of Section 6.3.1: d_k(p) is the average squared distance
/// from p to its k nearest neighbours; points with d_k > mean + sigmas * stddev
/// are removed. Returns the count removed.
struct SigmaOutlierOptions {
  int k = 150;          ///< Section 6.3.1
  double sigmas = 3.0;  ///< Section 6.3.1
  /// false: the thesis's score d_k(p), compared over the whole cloud, which
  /// removes whole regions that are merely sparser (far from the cameras,
  /// seen at a slant). true (beyond the thesis): d_k(p) divided by the median
  /// d_k of p's k neighbours, so a point is an outlier when it is isolated
  /// relative to its own surroundings.
  bool relative = false;
  void check(std::size_t n) const;
};
std::size_t remove_outliers_sigma(PointSet& points, const SigmaOutlierOptions& options = {},
                                  const Progress& progress = {});
/// The same rule as flags (true: outlier), for callers that keep their own
/// records per point (the tracks of Section 6.3.1). Points must be finite.
std::vector<bool> sigma_outliers(const std::vector<Vec3>& points, const SigmaOutlierOptions& options = {},
                                 const Progress& progress = {});

/// Removes points at exactly the same position as an earlier one (merged
/// scans repeat them; they make k-neighbourhoods degenerate). Returns the count.
std::size_t remove_duplicate_points(PointSet& points);

/// Local thickness at each point (beyond the thesis): the distance to the
/// nearest point that faces it across the solid or across a gap (normals
/// parallel, either orientation, and lying within 30 degrees of the
/// normal's line), looked for between min_thickness (raised to 4x the
/// noise level measured on the points) and max_thickness; infinity where
/// there is none. Needs one (unoriented) normal per point. With `facing`,
/// also the index of that point (the point's own index where there is none).
std::vector<double> local_thickness(const PointSet& points, double min_thickness, double max_thickness,
                                    std::vector<std::uint32_t>* facing = nullptr);

/// Vertical walls under roof edges (beyond the thesis; issue 44): an
/// airborne scanner looks down, so the walls between a roof's edge and the
/// ground get few points or none, and the eave is an edge of one sampled
/// face only. Where the last point of a locally flat face (towards the
/// drop) has points at least `min_drop` lower within `reach` horizontally,
/// steeper than 1.5 in 1, a column of points one spacing apart is added
/// half a spacing beyond it towards them, from the lowest one up to it,
/// wherever the cloud has no point within 0.75 spacings: the footprint edge
/// extruded along the vertical, the usual prior of building reconstruction
/// from airborne LiDAR. Lengths in average spacings; z is up.
enum class WallMode { Automatic, On, Off };
struct WallOptions {
  /// auto: on for clouds that look airborne (looks_airborne); on; off.
  WallMode mode = WallMode::Automatic;
  double min_drop = 4;     ///< [avg]
  double reach = 1.5;      ///< [avg]
  /// Smallest over largest eigenvalue of the covariance of the upper
  /// point's 12 nearest points, at most: a face, not a tree crown.
  double max_flatness = 0.03;
  void check() const;
};
struct WallResult {
  bool airborne = false;          ///< the automatic test's verdict
  bool filled = false;            ///< walls were added (or looked for)
  std::size_t upper_points = 0;   ///< points at the top of a drop
  std::size_t added_points = 0;
};
/// A cloud looks airborne when its height range is at most 0.3 of its
/// smaller horizontal extent and fewer than 65% of its columns two spacings
/// wide hold points more than two spacings apart in height: a scan from
/// above sees one layer except under trees and at walls (half the columns
/// of the Delft tiles), a closed object two (81-100% of the columns of the
/// generated corpus's solids, flat ones included).
bool looks_airborne(const PointSet& points, double average_spacing);
/// Adds the walls (appended after the input's points; with normals, the
/// new points' face away from the upper point).
WallResult fill_vertical_walls(PointSet& points, double average_spacing, const WallOptions& options = {},
                               const Progress& progress = {});

/// Keeps one point per cell of a regular grid of the given cell size (App. A.5).
std::size_t grid_simplify(PointSet& points, double cell_size);

/// Removes every point closer than min_distance to an earlier kept point
/// (input order), so that no two points are nearer than that. Random
/// sampling is full of near-coincident pairs; each one costs CGAL's Poisson
/// (and any Delaunay refinement) extra Steiner points and carries no
/// information the pair's first point does not.
std::size_t thin_close_points(PointSet& points, double min_distance);

/// Removes `percentage` % of the points at random, reproducibly for a seed (App. A.5).
std::size_t random_simplify(PointSet& points, double percentage, std::uint64_t seed = 0);

/// Projects each point onto a jet (quadric) fitted over its k nearest neighbours (App. A.6).
struct JetSmoothingOptions {
  int k = 24;  ///< App. A.6 ("default is 24 for real-world point sets")
  void check(std::size_t n) const;
};
void jet_smooth(PointSet& points, const JetSmoothingOptions& options = {}, const Progress& progress = {});

/// Unoriented normal estimation over k nearest neighbours (App. A.7).
enum class NormalMethod { Pca, Jet };
struct NormalEstimationOptions {
  NormalMethod method = NormalMethod::Jet;
  int k = 18;  ///< App. A.8 example ("3 rings")
  void check(std::size_t n) const;
};
void estimate_normals(PointSet& points, const NormalEstimationOptions& options = {},
                      const Progress& progress = {});
/// The same estimate at the given points only (their neighbours taken from
/// the whole set); the other normals are kept (zero if there were none).
void estimate_normals_at(PointSet& points, const std::vector<std::uint32_t>& indices,
                         const NormalEstimationOptions& options = {});

/// Crease-aware normals at the given points (neighbourhood shifting, beyond
/// App. A.7): each point takes, among the least-squares planes of the
/// k-neighbourhoods of its `candidates` nearest points (itself included),
/// the one minimising RMS residual + the point's distance to the plane. Next
/// to a crease some shifted neighbourhood lies on the point's own face, where
/// a centred one straddles both. A point that already has a (non-zero) normal
/// keeps its sign: orient smoothly turning normals first (across a crease the
/// new ones turn by 90 degrees, and an MST loses their sign there). The
/// other points' normals are kept.
struct ShiftedNormalOptions {
  int k = 10;           ///< points per fitted plane (at least 6)
  int candidates = 18;  ///< nearest points whose planes compete
  void check(std::size_t n) const;
};
void estimate_shifted_normals_at(PointSet& points, const std::vector<std::uint32_t>& indices,
                                 const ShiftedNormalOptions& options = {});

/// Orients normals by propagation along a minimum spanning tree of the
/// k-nearest-neighbour graph (Hoppe et al. 1992; App. A.8). Points whose
/// normal could not be oriented are moved to the end and, if
/// `remove_unoriented`, removed. Returns the number of unoriented points.
struct NormalOrientationOptions {
  int k = 18;  ///< App. A.8 example
  bool remove_unoriented = true;
  void check(std::size_t n) const;
};
std::size_t orient_normals_mst(PointSet& points, const NormalOrientationOptions& options = {},
                               const Progress& progress = {});

/// MST orientation whose edge weights also penalise leaving the tangent
/// planes, so that a flip does not spread across thin walls. Every point is
/// oriented (each connected component of the k-nearest-neighbour graph from
/// its highest point, normal up); returns the number of components.
std::size_t orient_normals_tangent_mst(PointSet& points, int k = 18, const Progress& progress = {});
/// The same, with the signs of some points decided beforehand (`anchors`:
/// +1 keep, -1 flip, 0 undecided; one per point): the tree grows from all of
/// them at once, so each undecided point takes its sign from the anchors it
/// is best connected to; components without an anchor start from their
/// highest point as above. Returns the number of trees grown (all the
/// anchors together count as one).
std::size_t orient_normals_tangent_mst(PointSet& points, int k, const std::vector<signed char>& anchors,
                                       const Progress& progress = {});

/// Signs from the cloud's occupancy (beyond the thesis, issue 36): cells of
/// size `cell` holding a point (dilated by one cell) wall off the inside, a
/// flood fill from the border marks the outside. +1 where the normal's line
/// reaches the outside ahead of the point and an enclosed empty cell behind
/// it (within `reach`), -1 the other way round, 0 elsewhere (thin material,
/// clouds whose inside the fill reaches). The cell grows when the grid would
/// exceed 64 cells per point (10 million at least).
std::vector<signed char> exterior_side_votes(const PointSet& cloud, double cell, double reach);

/// Signs from sheet parity (beyond the thesis, issue 36), for material too
/// thin to enclose an empty cell (a plate two spacings thick): along each
/// normal line the points within about 1.4 `spacing`s of it group into the
/// sheets the line crosses before it reaches the outside (an occupancy flood
/// fill as above); +1 where the side ahead meets the outside after an even
/// count and the side behind after an odd one, -1 the other way round, 0
/// where the counts disagree, a sheet is grazed, or the cloud is open.
/// `noise`: the points' deviation from their surface (widens the gap that
/// separates two sheets).
std::vector<signed char> sheet_parity_votes(const PointSet& cloud, double spacing, double noise);

/// Sign votes (+1 keep, -1 flip, 0 undecided; one per point) kept only
/// where the same sheet confirms them (beyond the thesis, issue 36): among
/// the k nearest neighbours whose normal lines lie within 25 degrees and
/// along tangent chords, at least three vote and two thirds agree (signs
/// carried by the normals' dot product); other votes become 0. A stray
/// wrong vote no longer seeds an MST tree of its own.
std::vector<signed char> neighbour_confirmed_votes(const PointSet& cloud, const std::vector<signed char>& votes, int k = 18);

/// Beyond the thesis: after an MST orientation, flips the patches of
/// normals that the creases around them show inverted (an MST inverts a
/// whole face beyond an acute crease, whose consistent normals have a
/// negative dot product). `unreliable`: points whose normal line is
/// uncertain (crease points); they do not vote and follow their neighbours.
/// `spacing`: the average spacing. `anchored`: empty, or nonzero for the
/// points whose sign is known (the anchors an anchored MST grew from): a
/// patch holding anchored points keeps the sign most of them have, the
/// crease votes decide only the others, and anchored points never flip.
/// Returns the number of normals flipped.
std::size_t repair_inverted_patches(PointSet& points, const std::vector<std::uint32_t>& unreliable, double spacing, int k = 18,
                                    const std::vector<signed char>& anchored = {});

/// Beyond the thesis: flips the regions of normals whose outer side the rest
/// of the cloud encloses, by the cloud's generalized winding number (about 1
/// inside, 0 outside a consistently oriented closed surface): an inverted
/// bore the local rules cannot see. `spacing`: the average spacing; `k`:
/// neighbours that join a region. Returns the number of normals flipped.
std::size_t repair_enclosed_normals(PointSet& points, double spacing, int k = 10);

/// The toolbox as one pipeline, in the order of the thesis's Fig. A.2:
/// outliers, simplification, smoothing, normals, orientation. A step runs
/// when its option is set.
struct CleanOptions {
  std::optional<PercentageOutlierOptions> outliers;  ///< App. A.4
  std::optional<SigmaOutlierOptions> outliers_sigma;  ///< 6.3.1
  std::optional<double> grid_cell;                    ///< App. A.5, multiples of the average spacing
  std::optional<double> random_percentage;            ///< App. A.5
  std::uint64_t seed = 0;                             ///< of the random simplification
  std::optional<JetSmoothingOptions> smoothing;       ///< App. A.6
  std::optional<NormalEstimationOptions> normals;     ///< App. A.7
  /// After `normals` (and the orientation): crease-aware normals from shifted
  /// neighbourhoods, each signed like the normal it replaces (for clean or
  /// nearly clean clouds; see estimate_shifted_normals_at).
  std::optional<ShiftedNormalOptions> crease_aware_normals;
  enum class Orientation { None, TangentMst, CgalMst };
  Orientation orientation = Orientation::None;        ///< App. A.8
  int orient_k = 18;
  /// With the tangent MST: then flip the regions whose outer side the rest
  /// of the cloud encloses (repair_enclosed_normals; beyond the thesis).
  bool repair_enclosed = true;
  /// Throws InvalidArgument for values no cloud accepts (the k checks need the cloud).
  void check() const;
};

struct CleanStats {
  std::size_t input = 0, output = 0;
  std::size_t removed_outliers = 0, removed_outliers_sigma = 0, removed_grid = 0, removed_random = 0;
  std::size_t unoriented_removed = 0;       ///< CGAL's MST orientation
  std::size_t orientation_components = 0;   ///< tangent MST orientation
  std::size_t enclosed_flipped = 0;         ///< normals flipped by repair_enclosed_normals
  std::vector<StageTiming> stages;
};

/// Runs the steps of `options` on `points`; throws InvalidInput when no point is left.
CleanStats clean_point_set(PointSet& points, const CleanOptions& options, const Progress& progress = {});

}  // namespace sharpmesh
