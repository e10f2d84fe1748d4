// Sharp feature extraction from point clouds (thesis 7.2, 7.4): Voronoi
// covariance measure by the clamped approximation, classification
// (Algorithm 1), clustering (Algorithm 2), polyline and junction recovery.
#pragma once

#include <cstdint>
#include <vector>

#include "sharpmesh/progress.h"
#include "sharpmesh/timing.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

using Matrix3 = std::array<double, 9>;  ///< row-major symmetric 3x3

/// Parameters of Section 7.2 with the thesis's defaults.
struct FeatureOptions {
  /// Offset radius R as a fraction of the bounding-sphere radius (7.2.1: 0.1).
  double offset_radius = 0.1;
  /// Beyond the thesis: R at most this many average spacings. A scene's
  /// bounding sphere says nothing of the size of its buildings: 0.1 of it is
  /// 7 m on a 100 m city tile, 700 m on a 10 km one, and another value on
  /// every slab of a tiled run. -1 = automatic: kSceneOffsetRadius on clouds
  /// that look airborne (looks_airborne, sharpmesh/pointset.h), no bound on
  /// objects; 0 = no bound.
  double max_offset_radius = -1;
  /// Convolution radius r as a fraction of R (7.2.1: 0.1). 0 = automatic:
  /// r = R/10, enlarged where the estimated noise level needs it.
  double convolution_radius = 0.0;
  double t1 = 50.0;  ///< smooth if lambda0/lambda1 > t1 (Algorithm 1; fandisk value)
  double t2 = 6.0;   ///< edge if lambda1/lambda2 >= t2, else corner
  int cluster_k = 20;         ///< rho_k of close pairs (7.2.2)
  double cluster_angle = 15;  ///< theta, degrees (7.2.2)
  std::size_t min_cluster_size = 7;  ///< clusters of 6 points or fewer are pruned (7.2.2)
  int successor_k = 5;        ///< r_p = rho_5(p) (7.2.3)
  double junction_factor = 5; ///< r_junc = 5 x spacing of a polyline's last four points (7.2.3)
  /// Beyond the thesis: an edge point must see two surface patches at least
  /// this angle apart (degrees) to be kept; it is moved onto their intersection.
  double min_dihedral_angle = 15;
  /// Beyond the thesis: jet smoothing (App. A.6) over k neighbours before the
  /// VCM, for clouds whose noise is several times their spacing. -1 =
  /// automatic (when the estimated noise exceeds half the average spacing),
  /// 0 = never.
  int denoise_k = -1;
  /// Beyond the thesis: corner points (Algorithm 1) next to a sharp edge are
  /// fitted like edge points, by RANSAC planes; those within r of the line
  /// of two faces at least 45 degrees apart become edge points on it. Faces
  /// narrower than r (a wall three spacings high) leave no edge points, and
  /// polylines otherwise stop r short of every corner.
  bool fit_corner_points = true;
  void check() const;
};

enum class PointClass : std::uint8_t { Smooth = 0, Edge = 1, Corner = 2 };

/// Per-point result of Algorithm 1.
struct PointFeature {
  PointClass type = PointClass::Smooth;
  Vec3 direction{0, 0, 0};  ///< e2: eigenvector of the smallest eigenvalue (edge direction)
  Vec3 normal{0, 0, 0};     ///< e0: eigenvector of the largest eigenvalue (unoriented normal)
  double ratio01 = 0;       ///< lambda0 / lambda1
  double ratio12 = 0;       ///< lambda1 / lambda2
};

enum class JunctionType : std::uint8_t { Dart = 0, Cusp = 1, Corner = 2 };

struct Junction {
  Vec3 position{0, 0, 0};
  JunctionType type = JunctionType::Dart;
  int degree = 0;  ///< number of polyline ends meeting here
};

/// The sharp-feature graph: polylines that run between junctions or darts
/// (closed loops have front() == back()).
struct FeatureGraph {
  std::vector<Polyline> polylines;
  std::vector<Junction> junctions;
};

/// The automatic bound on R for airborne clouds, in average spacings: on the
/// generated districts of bench/city (docs/city.md) eaves are found best with
/// R about 24 spacings (7 m at 11 points per square metre), and worse at half
/// or three times that.
inline constexpr double kSceneOffsetRadius = 24;

/// The bound on R that `options` ask for on a cloud whose airborne verdict
/// is `airborne` [average spacings; 0: none].
inline double offset_radius_bound(const FeatureOptions& options, bool airborne) {
  return options.max_offset_radius >= 0 ? options.max_offset_radius : airborne ? kSceneOffsetRadius : 0.0;
}

/// Noise estimate, as a fraction of the average spacing, below which a cloud
/// is clean: CAD samples measure 0.001-0.021; 0.2% and 0.5% uniform noise on
/// fandisk 50k, 0.24 and 0.13 (after denoising).
inline constexpr double kCleanNoiseRatio = 0.05;

struct FeatureResult {
  FeatureGraph graph;
  std::vector<PointFeature> points;  ///< one per input point
  double offset_radius = 0;          ///< R, data units
  double convolution_radius = 0;     ///< r, data units
  double noise_estimate = 0;         ///< estimated noise level, data units
  double average_spacing = 0;        ///< mean distance to the 6 nearest neighbours (after denoising)
  int denoise_k = 0;                 ///< jet-smoothing neighbours used before the VCM (0: none)
  int denoise_passes = 0;            ///< jet-smoothing passes run
  std::size_t edge_points = 0, corner_points = 0;
  std::size_t fitted_corner_points = 0;    ///< corner points that became edge points (fit_corner_points)
  std::size_t unsharpened_edge_points = 0;  ///< edge points dropped: no two patches around them
  std::size_t clusters = 0, pruned_clusters = 0;
  std::size_t off_data_polylines = 0;  ///< traced polylines dropped: their median vertex lies off the data
  std::vector<StageTiming> stages;   ///< detection, clustering, polylines and junctions (Table 7.1)
};

/// Voronoi covariance measure of each point by the clamped approximation
/// (7.4): Voronoi vertices beyond R are projected onto the sphere B(p, R),
/// the cell is cut into tetrahedra from p and their covariances summed.
std::vector<Matrix3> voronoi_covariance(const std::vector<Vec3>& points, double offset_radius,
                                        const Progress& progress = {});

/// Convolved VCM (7.2.1): sum of the VCMs of the points within r of each point.
std::vector<Matrix3> convolve_covariance(const std::vector<Vec3>& points, const std::vector<Matrix3>& vcm,
                                         double convolution_radius, const Progress& progress = {});

/// Algorithm 1 on convolved covariances.
std::vector<PointFeature> classify_points(const std::vector<Matrix3>& cvcm, double t1, double t2);

/// The whole of Section 7.2.
FeatureResult extract_features(const PointSet& points, const FeatureOptions& options = {},
                               const Progress& progress = {});

}  // namespace sharpmesh
