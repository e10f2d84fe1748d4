// Section 7.2 end to end, timed as the thesis's Table 7.1: (1) detection,
// (2) clustering, (3) polylines and junctions.
#include <Eigen/Eigenvalues>


#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>


#include "core/plane_fit.h"
#include "core/recentering.h"
#include "features/feature_graph_builder.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"
#include "core/parallel.h"

namespace sharpmesh {

void FeatureOptions::check() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw InvalidArgument(std::string(name) + " must be positive (got " + format_number(v) + ")");
  };
  positive(offset_radius, "offset radius R");
  if (offset_radius > 10) throw InvalidArgument("offset radius R is a fraction of the bounding-sphere radius: " + format_number(offset_radius) + " is too large");
  if (!(max_offset_radius == -1 || (max_offset_radius >= 0 && std::isfinite(max_offset_radius))))
    throw InvalidArgument("largest offset radius must be -1 (automatic), 0 (none) or a number of average spacings");
  if (!(convolution_radius >= 0) || convolution_radius > 100) throw InvalidArgument("convolution radius must be a fraction of R in [0, 100] (0: automatic)");
  positive(t1, "t1");
  positive(t2, "t2");
  if (cluster_k < 1) throw InvalidArgument("cluster k must be at least 1");
  if (!(cluster_angle > 0 && cluster_angle < 90)) throw InvalidArgument("cluster angle must be in (0, 90) degrees");
  if (successor_k < 1) throw InvalidArgument("successor k must be at least 1");
  positive(junction_factor, "junction factor");
  if (denoise_k < -1 || denoise_k > 10000) throw InvalidArgument("denoise k must be -1 (automatic), 0 (off) or a neighbour count up to 10000");
}

namespace {

// Median plane-fit residual over 24 neighbours, in average spacings, above
// which a cloud counts as rough (clean CAD samples: below 0.05; 0.3% noise: 0.3).
constexpr double kRoughnessRatio = 0.25;
// ...and at most this many times the residual over 8 neighbours. Noise is
// there at every scale (uniform noise of 0.1-1% of the diagonal on fandisk,
// couplingdown, anchor at 50k: 1.2-2.1x), while curvature's residual grows
// with the neighbourhood's area (clean cheese.off, whose holes are a few
// spacings wide: 5.9x; knot1 5.6x; the kitten scan 3.6x).
constexpr double kNoiseScaleRatio = 3;
constexpr int kMaxDenoisePasses = 3;
// r_junc at most 8 average spacings (beyond the thesis): two segments of
// the polylines, whose points lie at least 4 spacings apart (the r_p floor).
// A wider radius joins ends across features that do not meet; a cap of 5
// spacings loses the corners of coarsely sampled cubes (docs/corpus.md).
constexpr double kMaxJunctionRadius = 8;

// RMS distance of the points `ids` to their least-squares plane.
double plane_residual(const std::vector<Vec3>& points, const std::vector<std::uint32_t>& ids) {
  return std::sqrt(detail::scatter_eigenvalues(points, ids)(0) / static_cast<double>(ids.size()));
}

// RMS distance of the points `ids` to two parallel sheets when they form
// two (both faces of a plate thinner than the neighbourhood), else to one
// plane. The sheets: the points split by the side of their plane, then each
// point to the nearer of the two sides' planes, four rounds. Two sheets are
// taken when each holds 6 points or more, their planes lie within 15 degrees
// of parallel, one above the other (their centres closer sideways than
// apart: the faces of a shallow crease lie side by side) and farther apart
// than 8 times their residual. Noise splits a neighbourhood into two slabs
// whose centres lie a few residuals apart (uniform noise: 3.5): noisy
// fandisk, anchor and couplingdown read the same noise as with one plane,
// and clean fandisk the same crease residual.
double sheets_residual(const std::vector<Vec3>& points, const std::vector<std::uint32_t>& ids) {
  const auto at = [&](std::uint32_t i) { return Eigen::Vector3d(points[i][0], points[i][1], points[i][2]); };
  std::vector<Eigen::Vector3d> all;
  for (std::uint32_t i : ids) all.push_back(at(i));
  detail::Plane plane;
  double one = 0;
  if (!detail::fit_plane(all, plane, one)) return one;
  std::vector<char> side(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) side[i] = (all[i] - plane.point).dot(plane.normal) >= 0;
  detail::Plane sheet[2];
  double rms[2] = {0, 0};
  std::vector<Eigen::Vector3d> part[2];
  for (int round = 0; round < 4; ++round) {
    for (int s = 0; s < 2; ++s) part[s].clear();
    for (std::size_t i = 0; i < all.size(); ++i) part[side[i] ? 1 : 0].push_back(all[i]);
    for (int s = 0; s < 2; ++s)
      if (!detail::fit_plane(part[s], sheet[s], rms[s])) return one;
    for (std::size_t i = 0; i < all.size(); ++i)
      side[i] = std::abs((all[i] - sheet[1].point).dot(sheet[1].normal)) < std::abs((all[i] - sheet[0].point).dot(sheet[0].normal));
  }
  constexpr double kParallelCos = 0.9659;  // 15 degrees
  const double residual = std::sqrt((rms[0] * rms[0] * part[0].size() + rms[1] * rms[1] * part[1].size()) / all.size());
  const Eigen::Vector3d between = sheet[1].point - sheet[0].point;
  const double apart = std::abs(between.dot(sheet[0].normal));
  const double sideways = (between - between.dot(sheet[0].normal) * sheet[0].normal).norm();
  if (std::abs(sheet[0].normal.dot(sheet[1].normal)) >= kParallelCos && apart > 8 * residual && sideways < apart) return residual;
  return one;
}

// Noise level: median, over a fixed subset of points, of the RMS distance of
// the neighbours within `radius` to their least-squares plane (or to two
// sheets, `sheets`, see sheets_residual). On clean CAD samples it is tiny
// (curvature only); with noise it tracks the noise's standard deviation
// across the surface.
double estimate_noise(const std::vector<Vec3>& points, const detail::KnnIndex& index, double radius, int k = 0,
                      bool sheets = false) {
  const std::size_t samples = std::min<std::size_t>(points.size(), 2000);
  std::vector<double> residual(samples, 0.0);
  const std::size_t stride = points.size() / samples;
  detail::parallel_for(samples, [&](std::size_t s) {
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    if (k > 0) index.nearest(points[s * stride], k, ids, d2);
    else index.within(points[s * stride], radius, ids);
    if (ids.size() >= 6) residual[s] = sheets && ids.size() >= 24 ? sheets_residual(points, ids) : plane_residual(points, ids);
  });
  std::nth_element(residual.begin(), residual.begin() + samples / 2, residual.end());
  return residual[samples / 2];
}

// Noise level that creases and thin material cannot inflate: the median,
// over a fixed subset of points, of the smallest residual among the
// 16-point planes of each point's 12 nearest points (the neighbourhood
// shifting of estimate_shifted_normals_at). Some shifted plane lies on the
// point's own face unless the face is narrower than about two spacings; on
// pure noise the minimum is about 0.7 of the centred residual.
double estimate_shifted_noise(const std::vector<Vec3>& points, const detail::KnnIndex& index) {
  constexpr int kPlanePoints = 16, kCandidates = 12;
  const std::size_t samples = std::min<std::size_t>(points.size(), 2000);
  if (points.size() < static_cast<std::size_t>(kPlanePoints)) return std::numeric_limits<double>::infinity();
  std::vector<double> residual(samples, 0.0);
  const std::size_t stride = points.size() / samples;
  detail::parallel_for(samples, [&](std::size_t s) {
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    index.nearest(points[s * stride], kCandidates, ids, d2);
    std::vector<std::uint32_t> plane;
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t j : ids) {
      index.nearest(points[j], kPlanePoints, plane, d2);
      best = std::min(best, plane_residual(points, plane));
    }
    residual[s] = best;
  });
  std::nth_element(residual.begin(), residual.begin() + samples / 2, residual.end());
  return residual[samples / 2];
}

// Noise level, spacing, r, and Algorithm 1 on the convolved VCM.
// The noise is the residual over R / 3, to two sheets where a neighbourhood
// holds both faces of a plate (sheets_residual: one plane reads a plate 1.6
// spacings thick as 0.65 spacings of noise, which costs it its polylines
// and its orientation anchors). Where it reads the cloud as noisy
// it is capped at twice the shifted estimate: where bars, ribs or flanges
// are narrower than R / 3 every centred neighbourhood spans several faces
// (a cube frame whose bars are 5 spacings wide read as 1.9 spacings of
// noise, its convolution radius crossed the bars and every point became an
// edge point), while on noisy clouds the cap stays above the centred
// residual (1.4x on fandisk and anchor at 0.5% noise). A clean reading
// keeps the centred value, whose few hundredths of a spacing of crease
// residual the clean-cloud tolerances are set on.
void classify_cloud(const std::vector<Vec3>& points, const detail::KnnIndex& index, const FeatureOptions& options,
                    FeatureResult& result, const Progress& progress) {
  result.average_spacing = detail::average_spacing(points, index, 6);
  const double centred = estimate_noise(points, index, result.offset_radius / 3, 0, true);
  result.noise_estimate = centred < kCleanNoiseRatio * result.average_spacing
                              ? centred
                              : std::min(centred, 2 * estimate_shifted_noise(points, index));
  // r = R/10 (7.2.1). The automatic mode widens it so that the convolution
  // averages over enough cells: at least 2.5 average spacings (a sparser
  // cloud than the thesis's 200k fandisk otherwise convolves single, noisy
  // cells) and 4 noise deviations (r "should be chosen depending on the
  // noise level", 7.2.1).
  result.convolution_radius = options.convolution_radius > 0
                                  ? options.convolution_radius * result.offset_radius
                                  : std::max({result.offset_radius / 10, 2.5 * result.average_spacing, 4.0 * result.noise_estimate});
  const std::vector<Matrix3> vcm = voronoi_covariance(points, result.offset_radius, progress);
  const std::vector<Matrix3> cvcm = convolve_covariance(points, vcm, result.convolution_radius, progress);
  result.points = classify_points(cvcm, options.t1, options.t2);
}

// Upper quartile of lambda0/lambda1: on a clean sample, face points, far above t1.
double face_anisotropy(const std::vector<PointFeature>& features) {
  std::vector<double> anisotropy(features.size());
  for (std::size_t i = 0; i < anisotropy.size(); ++i) anisotropy[i] = features[i].ratio01;
  std::nth_element(anisotropy.begin(), anisotropy.begin() + 3 * anisotropy.size() / 4, anisotropy.end());
  return anisotropy[3 * anisotropy.size() / 4];
}

FeatureResult extract_features_centred(const PointSet& input, const FeatureOptions& options, const Progress& progress);

}  // namespace

FeatureResult extract_features(const PointSet& input, const FeatureOptions& options, const Progress& progress) {
  options.check();
  check_point_set(input, 10, "feature extraction");
  const detail::Recentering frame(input.points);
  PointSet local = input;
  frame.to_local(local.points);
  FeatureResult result = extract_features_centred(local, options, progress);
  frame.to_world(result);
  return result;
}

namespace {

/// The sharpening's tolerances (sharpen.cpp) from the cloud's spacing,
/// noise and convolution radius.
detail::SharpeningOptions sharpening_options(const FeatureResult& result, const FeatureOptions& options) {
  detail::SharpeningOptions sharpening;
  sharpening.radius = 3 * result.convolution_radius;
  sharpening.min_angle_deg = options.min_dihedral_angle;
  // Two planes fit a sharp edge up to the noise and the curvature sagitta.
  sharpening.max_residual = std::max(0.05 * sharpening.radius, 1.5 * result.noise_estimate);
  // The nearest sample to a point of a real edge lies within 0.6 average
  // spacings half of the time, within 1.1 nine times in ten; the virtual
  // corner of a chamfer w wide lies w/2 off the data. A fit closer than
  // 0.6 is taken; farther, the plane fallback is tried first; beyond 1.1,
  // neither is taken.
  const double avg = result.average_spacing, noise = result.noise_estimate;
  sharpening.close_to_data = 0.6 * avg + 2 * noise;
  sharpening.max_data_offset = 1.1 * avg + 2 * noise;
  // RANSAC planes within 5 spacings (a narrow face there has a few dozen
  // points), inliers within 0.15 spacings (the sagitta of a cylinder of
  // radius 80 spacings) or the noise, each face reaching the edge within
  // 1.5 spacings. The fallback fits positions, not normals, so a curved
  // face splits into planes a few degrees apart: it asks for 30 degrees
  // (fandisk's 22-degree creases on curved faces otherwise come out).
  sharpening.plane_tolerance = 0.15 * avg + 2 * noise;
  sharpening.plane_radius = 5 * avg;
  sharpening.face_reach = 1.5 * avg + 2 * noise;
  sharpening.plane_min_angle_deg = 30;
  // A corner point is taken only by a RANSAC pair at least 45 degrees apart
  // (30 let the adjacent plane strips of holes 8 spacings wide through:
  // anchor 50k lost its hole rims) within r of it (a point farther from
  // every edge than the band of edge points is no edge's).
  sharpening.corner_min_angle_deg = 45;
  sharpening.corner_shift = result.convolution_radius;
  return sharpening;
}

/// Polylines traced through each cluster (7.2.3), those off the data
/// dropped, and the rest joined at junctions into `result.graph`.
void trace_feature_graph(const std::vector<detail::EdgeCluster>& clusters, const std::vector<Vec3>& edge_points,
                         const std::vector<Vec3>& edge_directions, const detail::KnnIndex& input_index,
                         const FeatureOptions& options, const Progress& progress, FeatureResult& result) {
  StageTimer timer(result.stages, "polylines");
  report_progress(progress, "polylines", 0.0);
  const double step = 4 * result.average_spacing;  // r_p floor: the thinned band is denser than the cloud
  // A sharpened point lies within 0.15 spacings of its edge on clean data:
  // a line takes the members within 1.5 spacings (plus the noise) of it,
  // so parallel edges three spacings apart are traced apart. 1 or 2
  // spacings did worse on the 50k corpus (oblong lost a rounded loop's
  // rim at 1; pinion, spool and couplingdown moved by 0.2-0.6 U either way).
  const double lateral = 1.5 * result.average_spacing + 2 * result.noise_estimate;
  // Junctions: end lines pass within 1 spacing of their meeting point
  // (or within 25 degrees of it, seen from the end).
  const double junction_lateral = result.average_spacing + 2 * result.noise_estimate;
  std::vector<std::vector<detail::TracedPolyline>> per_cluster(clusters.size());
  detail::parallel_for(clusters.size(), [&](std::size_t c) {
    per_cluster[c] = detail::trace_polylines(clusters[c], edge_points, edge_directions, options.successor_k, step, lateral,
                                             options.min_cluster_size);
  });
  std::vector<detail::TracedPolyline> traced;
  for (auto& lines : per_cluster)
    for (auto& line : lines) traced.push_back(std::move(line));
  // A polyline shorter than two successor steps is a stray cluster, not an edge.
  traced.erase(std::remove_if(traced.begin(), traced.end(), [&](const auto& t) { return t.length() < 2 * step; }), traced.end());
  // A junction lies on the surface: within 2 spacings (or 3 noise
  // deviations) of a data point.
  std::vector<std::uint32_t> ids;
  std::vector<double> d2;
  auto distance_to_data = [&](const Vec3& p) {
    input_index.nearest(p, 1, ids, d2);
    return std::sqrt(d2[0]);
  };
  // A polyline that runs off the data (its median vertex farther than 1.1
  // spacings from every point, the sharpening's own bound) is a chord, not
  // an edge: on holes a few spacings across the plane fits cut inside the
  // rim (anchor 50k: four rims 1.7 spacings off; their protecting balls
  // shrank to a third of their size and 64% of the protected segments were
  // not mesh edges).
  const double max_offset = 1.1 * result.average_spacing + 2 * result.noise_estimate;
  const std::size_t traced_count = traced.size();
  traced.erase(std::remove_if(traced.begin(), traced.end(),
                              [&](const detail::TracedPolyline& t) {
                                std::vector<double> offsets;
                                for (const Vec3& v : t.vertices) offsets.push_back(distance_to_data(v));
                                std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
                                return offsets[offsets.size() / 2] > max_offset;
                              }),
               traced.end());
  result.off_data_polylines = traced_count - traced.size();
  result.graph = detail::connect_polylines(std::move(traced), options.junction_factor, distance_to_data,
                                           std::max(2 * result.average_spacing, 3 * result.noise_estimate),
                                           kMaxJunctionRadius * result.average_spacing + 3 * result.noise_estimate,
                                           junction_lateral);
  report_progress(progress, "polylines", 1.0);
}

FeatureResult extract_features_centred(const PointSet& input, const FeatureOptions& options, const Progress& progress) {
  FeatureResult result;
  const BoundingBox box = bounding_box(input.points);
  const Vec3 center = box.center();
  double sphere_radius = 0;
  for (const Vec3& p : input.points) sphere_radius = std::max(sphere_radius, distance(p, center));
  result.offset_radius = options.offset_radius * sphere_radius;
  const auto bound_offset_radius = [&](const detail::KnnIndex& index) {
    if (options.max_offset_radius == 0) return;
    const double spacing = detail::average_spacing(input.points, index, 6);
    const double bound = offset_radius_bound(options, options.max_offset_radius < 0 && looks_airborne(input, spacing));
    if (bound > 0) result.offset_radius = std::min(result.offset_radius, bound * spacing);
  };

  std::vector<Vec3> edge_points, edge_directions;
  std::vector<std::uint32_t> edge_ids;
  PointSet smoothed;
  const PointSet* cloud = &input;
  std::unique_ptr<detail::KnnIndex> input_index;  // also checks the junctions against the data
  {
    StageTimer timer(result.stages, "detection");
    input_index = std::make_unique<detail::KnnIndex>(input.points);
    bound_offset_radius(*input_index);
    std::unique_ptr<detail::KnnIndex> smoothed_index;
    const detail::KnnIndex* index = input_index.get();
    if (options.denoise_k <= 0) classify_cloud(input.points, *index, options, result, progress);
    // Beyond the thesis: under noise comparable to the sampling spacing the
    // Voronoi cells turn into cones (Fig. 7.2 right), the anisotropy of the
    // faces collapses and no t1 separates edges from faces. Two symptoms
    // together identify it: half of the points or more are rough at the
    // sampling scale (plane residual over 24 neighbours, and not mostly by
    // curvature: see kNoiseScaleRatio), and the upper
    // quartile of lambda0/lambda1 (mostly face points) falls below 2 t1.
    // Such clouds are jet-smoothed (App. A.6) over a neighbourhood a few
    // noise deviations wide and classified again;
    // the rounding left at the creases is undone by the sharpening below.
    result.denoise_k = options.denoise_k;
    if (options.denoise_k < 0) {
      const double roughness = estimate_noise(input.points, *index, 0, 24) / result.average_spacing;
      const bool noisy = roughness > kRoughnessRatio &&
                         roughness < kNoiseScaleRatio * estimate_noise(input.points, *index, 0, 8) / result.average_spacing &&
                         face_anisotropy(result.points) < 2 * options.t1;
      const double ratio = result.noise_estimate / result.average_spacing;
      result.denoise_k = noisy ? static_cast<int>(std::clamp(100 * ratio * ratio, 24.0, 300.0)) : 0;
    }
    // Up to three passes, while the faces' anisotropy stays below 2 t1
    // (each pass divides the noise by about sqrt(k / 5)).
    for (int pass = 0; pass < (options.denoise_k < 0 ? kMaxDenoisePasses : 1) && result.denoise_k > 0; ++pass) {
      if (pass > 0 && face_anisotropy(result.points) >= 2 * options.t1) break;
      report_progress(progress, "denoising", 0.0);
      if (pass == 0) smoothed = input;
      JetSmoothingOptions jet;
      jet.k = std::min<int>(result.denoise_k, static_cast<int>(input.size()) - 1);
      jet_smooth(smoothed, jet);
      cloud = &smoothed;
      smoothed_index = std::make_unique<detail::KnnIndex>(smoothed.points);
      index = smoothed_index.get();
      classify_cloud(smoothed.points, *index, options, result, progress);
      result.denoise_passes = pass + 1;
    }
    const std::vector<Vec3>& points = cloud->points;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const PointFeature& f = result.points[i];
      if (f.type == PointClass::Edge) {
        edge_ids.push_back(static_cast<std::uint32_t>(i));
        edge_points.push_back(points[i]);
        edge_directions.push_back(f.direction);
      }
      result.corner_points += f.type == PointClass::Corner;
    }
    result.edge_points = edge_points.size();
    // Corner points join the edge points here; the sharpening below keeps
    // only those it can put on the line of two faces.
    if (options.fit_corner_points)
      for (std::size_t i = 0; i < points.size(); ++i)
        if (result.points[i].type == PointClass::Corner) {
          edge_ids.push_back(static_cast<std::uint32_t>(i));
          edge_points.push_back(points[i]);
          edge_directions.push_back(result.points[i].direction);
        }
    const detail::SharpeningOptions sharpening = sharpening_options(result, options);
    detail::sharpen_edge_points(*cloud, result.points, *index, sharpening, edge_ids, edge_points, edge_directions);
    for (std::uint32_t id : edge_ids) result.fitted_corner_points += result.points[id].type == PointClass::Corner;
    result.unsharpened_edge_points = result.edge_points - (edge_ids.size() - result.fitted_corner_points);
  }
  std::vector<detail::EdgeCluster> clusters;
  {
    StageTimer timer(result.stages, "clustering");
    report_progress(progress, "clustering", 0.0);
    clusters = detail::cluster_edge_points(edge_points, edge_directions, options.cluster_k, options.cluster_angle,
                                           options.min_cluster_size, 4 * result.average_spacing, result.pruned_clusters);
    result.clusters = clusters.size();
    report_progress(progress, "clustering", 1.0);
  }
  trace_feature_graph(clusters, edge_points, edge_directions, *input_index, options, progress, result);
  return result;
}

}  // namespace
}  // namespace sharpmesh
