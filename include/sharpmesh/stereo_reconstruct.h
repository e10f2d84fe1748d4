// Surface reconstruction from multi-view stereo (thesis Ch. 6): tracks are
// merged, filtered and smoothed (6.3.1), lifted from contour-respecting
// depth maps into a triangle soup that is filtered by visibility, shape and
// photo-consistency (6.3.2), and the soup is meshed by Delaunay refinement
// with the soup as the oracle (6.3.3). Plain C++; CGAL and OpenCV stay in
// src/tracks, src/soup and src/meshing.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sharpmesh/meshing.h"
#include "sharpmesh/progress.h"
#include "sharpmesh/stereo.h"
#include "sharpmesh/timing.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

/// Grey images of the model's views, row-major 8-bit, in view order.
struct GreyImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;
};

// ---- 6.3.1 Merging, filtering and smoothing -------------------------------

struct TrackPreprocessOptions {
  /// t1: tracks closer than this are merged, fraction of the half diagonal beta.
  double merge_distance = 0.001;
  int outlier_k = 150;            ///< k of the distance-to-neighbours filter
  double outlier_sigmas = 3.0;    ///< the 3-sigma rule
  /// Beyond the thesis: score each track's d_k relative to its neighbours'
  /// (SigmaOutlierOptions::relative). The thesis's global rule removes every
  /// track of a region that is only sparser, e.g. ground far from the cameras.
  bool outlier_relative = true;
  double min_cone_angle = 0.08;   ///< t2, radians
  /// t2 measures how wide a baseline triangulated a track (6.3.1). Fused
  /// depth-map points (StereoModel::dense_points) were triangulated by their
  /// depth maps' own source views, which their view lists do not name, so by
  /// default they skip it (beyond the thesis, whose tracks are all matches).
  bool cone_angle_on_dense_points = false;
  int smooth_k = 85;              ///< k of the jet smoothing; 0 disables smoothing
  void check() const;
};

struct TrackPreprocessStats {
  std::size_t input = 0;
  std::size_t merged = 0;            ///< tracks absorbed into a neighbour
  std::size_t removed_distance = 0;  ///< 3-sigma rule
  std::size_t removed_cone = 0;      ///< cone angle below t2 (includes single-view tracks)
  bool cone_filter_skipped = false;  ///< dense points, see cone_angle_on_dense_points
  std::size_t output = 0;
  /// beta: half the diagonal of the input tracks' 1-99% extent per axis
  /// (robust_bounding_box), the unit of t1; far outliers cannot stretch it.
  double half_diagonal = 0;
  double raw_half_diagonal = 0;      ///< of the input tracks' full bounding box
  /// Input tracks farther than beta outside the 1-99% box: far outliers.
  std::size_t far_tracks = 0;
};

/// Merges tracks within t1 of an earlier kept track (union of the views,
/// position and colour averaged), in input order through an incremental
/// Delaunay triangulation's nearest-vertex query. Pixels are dropped (the
/// merged track is seen at its projections). Returns the number merged.
std::size_t merge_tracks(std::vector<Track>& tracks, double distance);

/// Aperture, radians, of the smallest cone with apex `apex` that contains the
/// given camera centres, approximated by the largest angle between two
/// lines of sight (exact for two or coplanar lines of sight, and at most 13%
/// below the aperture otherwise). 0 for fewer than two centres.
double cone_angle(const Vec3& apex, const std::vector<Vec3>& centers);

/// Jet smoothing with Gaussian weights (6.3.1): a weighted PCA plane over the
/// k nearest neighbours, a weighted quadric fit in it, projection of the
/// point onto the quadric. The Gaussian's width is the mean distance to the
/// k neighbours. Parallel; positions only.
void jet_smooth_gaussian(std::vector<Vec3>& points, int k, const Progress& progress = {});

/// Beyond the thesis: a track must be matchable. Small fronto-parallel
/// windows around its projections must show texture (standard deviation of
/// at least `min_texture` grey levels) and agree (mean pairwise NCC).
struct TrackPhotoOptions {
  bool enabled = true;
  int half_window = 3;      ///< 7x7 windows
  double min_ncc = 0.0;     ///< below this mean pairwise NCC the track goes (0: uncorrelated)
  double min_texture = 2.0; ///< grey levels
  void check() const;
};
/// Mean pairwise NCC of a track's windows; -1 when its windows have no
/// texture, NaN when fewer than two windows fit in the images.
double track_ncc(const Track& track, const StereoModel& model, const std::vector<GreyImage>& images, int half_window,
                 double min_texture);
/// Removes tracks failing the test; returns the number removed.
std::size_t filter_tracks_photo(StereoModel& model, const std::vector<GreyImage>& images, const TrackPhotoOptions& options,
                                const Progress& progress = {});

/// The whole of 6.3.1 on a model's tracks.
TrackPreprocessStats preprocess_tracks(StereoModel& model, const TrackPreprocessOptions& options,
                                       const Progress& progress = {});

// ---- 6.3.2 Triangle soup extraction ---------------------------------------

struct DepthMapOptions {
  double canny_sigma = 2.0;       ///< Gaussian blur before Canny, pixels
  double canny_low = 20.0;        ///< hysteresis thresholds on the Sobel gradient
  double canny_high = 60.0;       ///<   magnitude of the blurred image (8-bit scale)
  /// Beyond the thesis: scale both thresholds by the image's contrast (its
  /// 99th-percentile gradient magnitude over 100, that of the generated
  /// scenes), so that a darker or flatter image keeps its contours (at 30%
  /// contrast, the fixed thresholds find no contour at all).
  bool canny_adaptive = true;
  double contour_distance = 1.5;  ///< a ctrack projects this close to an edge pixel, pixels
  double gap_open = 0.5;          ///< o of the affine gap penalty
  double gap_extend = 2.0;        ///< e of the affine gap penalty
  /// Two kept contour edges at one ctrack closer than this angle overlap; the
  /// longer one is dropped (the length criterion), degrees.
  double overlap_angle = 20.0;
  void check() const;
};

/// One image's contour-respecting depth map, in track indices.
struct DepthMap {
  std::vector<std::uint32_t> tracks;                       ///< tracks projected in the image
  std::vector<std::uint32_t> ctracks;                      ///< of those, near a contour
  std::vector<std::array<std::uint32_t, 2>> constraints;   ///< kept contour edges
  std::vector<Triangle> triangles;                         ///< oriented towards the camera
};

/// Edge pixels of one grey image (Canny with the options' blur and thresholds);
/// 255 on edges, 0 elsewhere, row-major, width x height.
std::vector<std::uint8_t> detect_contours(const std::vector<std::uint8_t>& grey, int width, int height,
                                          const DepthMapOptions& options);

/// Builds the depth map of view `view` (6.3.2) from a contour image as made
/// by detect_contours.
DepthMap build_depth_map(const StereoModel& model, std::uint32_t view, const std::vector<std::uint8_t>& contours,
                         const DepthMapOptions& options);

/// Score of the segment a-b (pixels) over a contour image, by the affine gap
/// penalty: +1 per pixel on (or next to) a contour, -(o + (L-1) e) per gap of L pixels.
double contour_edge_score(const std::vector<std::uint8_t>& contours, int width, int height, const Vec2& a,
                          const Vec2& b, double gap_open, double gap_extend);

/// A triangle soup over the tracks: vertices are track positions (same indices).
using TriangleSoup = SurfaceMesh;

/// Keeps one copy of triangles with the same vertices (in any order) and
/// drops degenerate ones; returns the number removed.
std::size_t remove_duplicate_triangles(std::vector<Triangle>& triangles);

// ---- 6.3.2 Soup filtering -------------------------------------------------

struct SoupFilterOptions {
  int max_crossings = 5;          ///< t3: more lines of sight through a triangle remove it
  /// Lines of sight stop this far before their track, in average track
  /// spacings, so that the noise left after smoothing does not count.
  double sight_margin = 1.0;
  /// Degrees between line of sight and triangle normal. The thesis uses 60;
  /// 80 keeps ground and side walls seen obliquely from street level (measured
  /// in docs/stereo.md) while still removing edge-on bridging triangles.
  double grazing_angle = 80.0;
  double big_radius = 3.0;        ///< a triangle is big past this circumradius, average track spacings
  double max_radius_edge = 2.0;   ///< big triangles above this radius-edge ratio are anamorphic
  double ncc_threshold = 0.7;     ///< big regular triangles below this mean NCC are removed
  bool photo_consistency = true;
  /// Beyond the thesis: remove the triangles of tracks hidden behind kept
  /// triangles from more than half of their views (outliers behind surfaces).
  bool remove_occluded_tracks = true;
  void check() const;
};

struct SoupFilterStats {
  std::size_t input = 0;
  std::size_t removed_visibility = 0;
  std::size_t occluded_tracks = 0;    ///< tracks hidden from most of their views
  /// Per track: hidden behind the kept triangles from most of its views
  /// (computed whether or not their triangles are removed).
  std::vector<bool> occluded;
  std::size_t removed_occluded = 0;   ///< triangles of those tracks
  std::size_t removed_grazing = 0;
  std::size_t removed_anamorphic = 0;
  std::size_t removed_photo = 0;
  std::size_t photo_tested = 0;
  std::size_t output = 0;
};


/// Lines of sight (camera centre to track, for every view of every track,
/// stopped `margin` before the track) crossing soup triangles; triangles
/// incident to the track do not count.
struct SightCrossings {
  std::vector<std::uint32_t> per_face;  ///< number of lines of sight through each triangle
  /// For each track, (view, triangle) of each crossing of its lines of sight.
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> per_track;
};
SightCrossings count_sight_crossings(const TriangleSoup& soup, const StereoModel& model, double margin,
                                     const Progress& progress = {});

/// Mean NCC between the reference view (largest projected area) and the other
/// views that see all three vertices, sampled on the 3D triangle (the same as
/// warping through the triangle's homography). NaN when fewer than two views
/// see it or the reference patch has no texture.
double triangle_ncc(const std::array<Vec3, 3>& triangle, const std::vector<std::uint32_t>& views,
                    const StereoModel& model, const std::vector<GreyImage>& images);

/// Removes triangles by the filters of 6.3.2: grazing lines of sight and
/// anamorphic big triangles, then visibility (and occluded tracks) among the
/// survivors, then photo-consistency of big regular ones (when images are
/// given). A triangle removed by one filter is counted under that one only.
SoupFilterStats filter_soup(TriangleSoup& soup, const StereoModel& model, const std::vector<GreyImage>& images,
                            const SoupFilterOptions& options, const Progress& progress = {});

// ---- 6.3.3 Meshing --------------------------------------------------------

/// Criteria (alpha, l, d) of 6.2.1 in units of the half diagonal of the
/// soup's bounding box, so that one soup gives several resolutions.
struct SoupMeshingOptions {
  double angle = 20.0;      ///< alpha, degrees (6.5)
  double size = 0.01;       ///< l: bound on the surface Delaunay ball radius (6.5: 0.01 and 0.035)
  double distance = 0.002;  ///< d (6.5: 0.002 and 0.01)
  int initial_points = 1000;  ///< centroids of random soup triangles
  bool seed_cells = true;     ///< also one seed per occupied cell of a grid of step seed_cell x l
  double seed_cell = 4.0;
  std::size_t max_vertices = 2'000'000;  ///< stop with an error past this many vertices
  std::uint32_t seed = 0;
  void check() const;
};

struct SoupMeshingResult {
  SurfaceMesh mesh;
  std::size_t steps = 0;
  double half_diagonal = 0;  ///< of the soup's bounding box: the unit of l and d
};

/// Boissonnat-Oudot Delaunay refinement whose oracle intersects a query
/// segment, ray or line with the soup through an AABB tree and answers the
/// centroid of all intersection points (the thesis's AABB_trianglesoup_oracle, 6.4).
SoupMeshingResult mesh_soup(const TriangleSoup& soup, const SoupMeshingOptions& options, const Progress& progress = {});

/// The oracle alone: centroid of the intersections of segment a-b with the
/// soup; false when there is none.
bool soup_segment_intersection(const TriangleSoup& soup, const Vec3& a, const Vec3& b, Vec3& point);

// ---- Beyond the thesis (6.6): the soup filled where it is empty ----------

/// The filtered soup leaves holes where tracks exist but their triangles were
/// removed (far ground seen at grazing angles, parts seen by few views).
/// There, a Poisson surface of the tracks, with normals towards their
/// cameras, is meshed, cut to the neighbourhood of the tracks, and cleared
/// of every facet a line of sight crosses (the visibility constraint of
/// 6.3.2); its facets join the soup before meshing, so the mesher's oracle
/// also answers where the soup has nothing. Tracks hidden behind the soup
/// from most of their views are left out of the surface. Measured in
/// docs/stereo.md: keeping the facets next to the soup too (gap 0) closes
/// the rim the refinement loses around each hole of the soup.
struct SoupFillOptions {
  bool enabled = true;
  /// Fill only farther than this from every soup triangle, in units of the
  /// mesher's size bound l (0: everywhere the tracks' surface is visibility-consistent).
  double gap = 0.0;
  /// Facets farther than this from every track of the filtered soup are
  /// dropped (all three corners and the centroid), average track spacings
  /// (farther, Poisson's sheets in open space, which no line of sight can
  /// refute, cost accuracy: docs/stereo.md), unless `bridge` keeps them.
  double support = 2.0;
  /// Beyond `support`, a facet stays where the soup's tracks within this
  /// many local track spacings surround it in its plane
  /// (trim_unless_bridging): gaps among sparse tracks (far ground) are
  /// filled, the tracks' outer edge is not extended. 0: no bridging.
  double bridge = 3.0;
  /// A facet crossed by more lines of sight than this is removed (t3 of 6.3.2).
  int max_crossings = 1;
  /// Protecting-ball spacing d' of the tracks' surface (7.3.2), in units of
  /// l: its facets are about 2 d' long. At 1 the surface overshoots the
  /// tracks' edge less than at 2 and deviates less where it overlaps the
  /// soup, for a little more time (docs/stereo.md).
  double resolution = 1.0;
  void check() const;
};

struct SoupFillStats {
  std::size_t tracks = 0;             ///< tracks the surface was fitted to (after merging those closer than l/2)
  std::size_t surface_facets = 0;     ///< facets of the tracks' meshed surface
  std::size_t removed_near_soup = 0;  ///< where the soup already is
  std::size_t removed_far = 0;        ///< farther than `support` from the soup's tracks, and not bridging a gap among them
  std::size_t removed_visibility = 0;
  std::size_t added = 0;              ///< facets added to the soup
  std::string skipped;                ///< why no fill was attempted (empty: it ran)
};

/// Adds to `soup` the facets of the tracks' surface where it is empty (see
/// SoupFillOptions). `size` is the mesher's l in scene units, `sight_margin`
/// as SoupFilterOptions::sight_margin; `occluded_tracks` (empty: none) as
/// SoupFilterStats::occluded, left out of the surface.
SoupFillStats fill_soup_from_tracks(TriangleSoup& soup, const StereoModel& model, const SoupFillOptions& options,
                                    double size, double sight_margin, const std::vector<bool>& occluded_tracks = {},
                                    const Progress& progress = {});

/// Half the bounding-box diagonal of the vertices the soup's triangles use:
/// the unit of the mesher's l and d.
double soup_half_diagonal(const TriangleSoup& soup);

// ---- The pipeline ---------------------------------------------------------

struct StereoReconstructionOptions {
  TrackPreprocessOptions tracks;
  TrackPhotoOptions track_photo;
  DepthMapOptions depth_maps;
  SoupFilterOptions filters;
  SoupFillOptions fill;
  SoupMeshingOptions meshing;
  /// Beyond the thesis (its remedy in 6.6): holes of the mesh whose boundary
  /// is shorter than this are filled, fraction of the half diagonal; 0: off.
  double max_hole = 0.0;
  /// Beyond the thesis: the mesh made a combinatorial manifold, consistently
  /// oriented (make_manifold), so that every edge has at most two facets.
  bool manifold = true;
  /// Worker threads of this call's parallel loops (0: every core). The
  /// limit holds for this call only, not for the process.
  int threads = 0;
  void check() const;
};

struct StereoReconstruction {
  TrackPreprocessStats tracks;
  std::size_t removed_track_photo = 0;  ///< tracks that failed the photo-consistency test
  std::size_t soup_triangles = 0;      ///< lifted, before deduplication
  std::size_t soup_unique = 0;         ///< after keeping one copy
  std::size_t contour_tracks = 0;      ///< ctracks over all images
  std::size_t contour_edges = 0;       ///< constrained edges over all images
  SoupFilterStats filters;
  TriangleSoup soup;                   ///< filtered soup (and its fill)
  SoupFillStats fill;
  SoupMeshingResult meshing;
  HoleFillingStats holes;
  ManifoldRepairStats manifold;
  /// Wall time and memory of: tracks (6.3.1), depth maps, soup filters, meshing.
  std::vector<StageTiming> stages;
};

/// Runs 6.3.1 to 6.3.3 on a model (modified: its tracks are pre-processed)
/// and its images, given in view order.
StereoReconstruction reconstruct_stereo(StereoModel& model, const std::vector<GreyImage>& images,
                                        const StereoReconstructionOptions& options, const Progress& progress = {});

/// Reads the model's images from `folder` as grey, checking that each has the
/// camera's size. Throws InvalidInput naming the file otherwise.
std::vector<GreyImage> read_grey_images(const StereoModel& model, const std::string& folder,
                                        const Progress& progress = {});

}  // namespace sharpmesh
