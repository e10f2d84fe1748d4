// Track pre-processing of thesis 6.3.1: merging, the distance-to-neighbours
// 3-sigma rule and the cone-angle filter, then Gaussian jet smoothing.
#include <algorithm>
#include <cmath>

#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {

namespace {
/// The tracks' extent runs from the 1% to the 99% quantile of each coordinate.
constexpr double kExtentQuantile = 0.01;
}  // namespace

void TrackPreprocessOptions::check() const {
  if (!(merge_distance >= 0 && merge_distance < 1))
    throw InvalidArgument("the merge distance t1 must be in [0, 1) (fraction of the half diagonal), got " + format_number(merge_distance));
  if (outlier_k < 1) throw InvalidArgument("the outlier filter's k must be >= 1, got " + format_number(outlier_k));
  if (!(outlier_sigmas > 0)) throw InvalidArgument("the outlier filter's sigma multiple must be positive");
  if (!(min_cone_angle >= 0 && min_cone_angle < M_PI))
    throw InvalidArgument("the minimum cone angle t2 must be in [0, pi) radians, got " + format_number(min_cone_angle));
  if (smooth_k != 0 && smooth_k < 6) throw InvalidArgument("the smoothing k must be 0 (off) or >= 6, got " + format_number(smooth_k));
}

double cone_angle(const Vec3& apex, const std::vector<Vec3>& centers) {
  std::vector<Vec3> directions;
  for (const Vec3& c : centers) {
    const Vec3 d = c - apex;
    const double length = norm(d);
    if (length > 0) directions.push_back((1.0 / length) * d);
  }
  double min_cos = 1.0;
  for (std::size_t i = 0; i < directions.size(); ++i)
    for (std::size_t j = i + 1; j < directions.size(); ++j) min_cos = std::min(min_cos, dot(directions[i], directions[j]));
  return std::acos(std::clamp(min_cos, -1.0, 1.0));
}

TrackPreprocessStats preprocess_tracks(StereoModel& model, const TrackPreprocessOptions& options, const Progress& progress) {
  options.check();
  TrackPreprocessStats stats;
  stats.input = model.tracks.size();
  if (model.tracks.empty()) throw InvalidInput("the model has no tracks");
  std::vector<Vec3> positions;
  positions.reserve(model.tracks.size());
  for (const Track& t : model.tracks) positions.push_back(t.position);
  stats.raw_half_diagonal = 0.5 * bounding_box(positions).diagonal();
  if (!(stats.raw_half_diagonal > 0)) throw InvalidInput("all tracks are at one position");
  // The scene's scale from the bulk of the tracks: a far cluster of a few
  // outliers doubles a real model's raw box, and t1 with it.
  const BoundingBox bulk = robust_bounding_box(positions, kExtentQuantile);
  stats.half_diagonal = 0.5 * bulk.diagonal();
  if (!(stats.half_diagonal > 0)) stats.half_diagonal = stats.raw_half_diagonal;
  for (const Vec3& p : positions) {
    double outside = 0;
    for (int axis = 0; axis < 3; ++axis) outside = std::max({outside, bulk.min[axis] - p[axis], p[axis] - bulk.max[axis]});
    if (outside > stats.half_diagonal) ++stats.far_tracks;
  }

  report_progress(progress, "merging tracks", 0.0);
  stats.merged = merge_tracks(model.tracks, options.merge_distance * stats.half_diagonal);

  // Cone angle first: it is per track and also drops single-view tracks.
  stats.cone_filter_skipped = model.dense_points && !options.cone_angle_on_dense_points && options.min_cone_angle > 0;
  const double min_cone_angle = stats.cone_filter_skipped ? 0.0 : options.min_cone_angle;
  std::vector<Vec3> centers_of_view(model.cameras.size());
  for (std::size_t v = 0; v < model.cameras.size(); ++v) centers_of_view[v] = model.cameras[v].center();
  {
    std::vector<Track> kept;
    kept.reserve(model.tracks.size());
    std::vector<Vec3> centers;
    for (Track& t : model.tracks) {
      centers.clear();
      for (std::uint32_t v : t.views) centers.push_back(centers_of_view[v]);
      if (min_cone_angle == 0 || (t.views.size() >= 2 && cone_angle(t.position, centers) >= min_cone_angle))
        kept.push_back(std::move(t));
      else
        ++stats.removed_cone;
    }
    model.tracks = std::move(kept);
  }

  // The 3-sigma rule on the average squared distance to the k nearest neighbours
  // (relative to the neighbours' own by default, beyond the thesis).
  if (model.tracks.size() > static_cast<std::size_t>(options.outlier_k)) {
    std::vector<Vec3> points;
    points.reserve(model.tracks.size());
    for (const Track& t : model.tracks) points.push_back(t.position);
    SigmaOutlierOptions sigma;
    sigma.k = options.outlier_k;
    sigma.sigmas = options.outlier_sigmas;
    sigma.relative = options.outlier_relative;
    const std::vector<bool> outlier = sigma_outliers(points, sigma, progress);
    std::vector<Track> kept;
    kept.reserve(model.tracks.size());
    for (std::size_t i = 0; i < model.tracks.size(); ++i) {
      if (outlier[i])
        ++stats.removed_distance;
      else
        kept.push_back(std::move(model.tracks[i]));
    }
    model.tracks = std::move(kept);
  }

  if (options.smooth_k > 0 && model.tracks.size() > static_cast<std::size_t>(options.smooth_k)) {
    std::vector<Vec3> points;
    points.reserve(model.tracks.size());
    for (const Track& t : model.tracks) points.push_back(t.position);
    jet_smooth_gaussian(points, options.smooth_k, progress);
    for (std::size_t i = 0; i < points.size(); ++i) {
      model.tracks[i].position = points[i];
      model.tracks[i].pixels.clear();  // the recorded pixels no longer match
    }
  }
  stats.output = model.tracks.size();
  return stats;
}

}  // namespace sharpmesh
