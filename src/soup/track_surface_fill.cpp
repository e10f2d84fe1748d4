// Beyond the thesis (its limitation in 6.6): the filtered soup leaves holes
// where tracks exist but their triangles were removed (far ground seen at
// grazing angles, parts seen by two or three views), and where tracks are
// sparse. The soup is completed with a Poisson surface of the tracks:
// normals by jet fitting, oriented towards the cameras that saw each track,
// meshed by the Chapter 7 pipeline without features, cut to the
// neighbourhood of the soup's tracks or to the gaps they surround (and,
// with a positive gap, to where the soup is empty), and cleared of every
// facet a line of sight crosses.
#include <algorithm>
#include <cmath>

#include "core/triangle_distance.h"
#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"
#include "sharpmesh/reconstruct.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {

void SoupFillOptions::check() const {
  if (!(gap >= 0 && gap <= 100)) throw InvalidArgument("the fill gap must be in [0, 100] size bounds l, got " + format_number(gap));
  if (!(support > 0 && support <= 100))
    throw InvalidArgument("the fill support must be in (0, 100] average track spacings, got " + format_number(support));
  if (!(bridge >= 0 && bridge <= 100))
    throw InvalidArgument("the fill's bridging reach must be in [0, 100] local track spacings, got " + format_number(bridge));
  if (max_crossings < 0) throw InvalidArgument("the fill's line-of-sight threshold must be >= 0");
  if (!(resolution > 0 && resolution <= 100)) throw InvalidArgument("the fill resolution must be in (0, 100] size bounds l, got " + format_number(resolution));
}

namespace {

/// The tracks, one per cell of `cell`, with jet normals turned towards the
/// mean centre of their views.
PointSet oriented_tracks(const StereoModel& model, const std::vector<bool>& keep, double cell) {
  PointSet points;
  for (std::size_t t = 0; t < model.tracks.size(); ++t) {
    if (!keep[t]) continue;
    const Track& track = model.tracks[t];
    Vec3 mean{0, 0, 0};
    for (std::uint32_t v : track.views) mean = mean + model.cameras[v].center();
    points.points.push_back(track.position);
    points.normals.push_back((1.0 / static_cast<double>(track.views.size())) * mean - track.position);
  }
  grid_simplify(points, cell);  // the normals slot carries the direction to the cameras meanwhile
  const std::vector<Vec3> towards = points.normals;
  points.normals.clear();
  if (points.size() < 50) return points;
  estimate_normals(points);
  for (std::size_t i = 0; i < points.size(); ++i)
    if (dot(points.normals[i], towards[i]) < 0) points.normals[i] = -1.0 * points.normals[i];
  return points;
}

}  // namespace

SoupFillStats fill_soup_from_tracks(TriangleSoup& soup, const StereoModel& model, const SoupFillOptions& options,
                                    double size, double sight_margin, const std::vector<bool>& occluded_tracks,
                                    const Progress& progress) {
  options.check();
  SoupFillStats stats;
  if (!options.enabled) {
    stats.skipped = "disabled";
    return stats;
  }
  if (soup.faces.empty() || model.tracks.size() < 50) {
    stats.skipped = "fewer than 50 tracks";
    return stats;
  }
  PointSet all;
  for (const Track& t : model.tracks) all.points.push_back(t.position);
  const double spacing = average_spacing(all);
  // The tracks the filtered soup still uses: outliers and tracks whose
  // triangles all failed a filter do not count as support.
  std::vector<Vec3> in_soup;
  {
    std::vector<char> used(soup.vertices.size(), 0);
    for (const Triangle& f : soup.faces)
      for (std::uint32_t v : f) used[v] = 1;
    for (std::size_t v = 0; v < used.size(); ++v)
      if (used[v]) in_soup.push_back(soup.vertices[v]);
  }
  if (in_soup.size() < 8) {
    stats.skipped = "fewer than 8 tracks in the soup";
    return stats;
  }
  // How far from the soup's tracks a kept facet can lie: support, or the
  // bridging reach where they are sparsest (99th percentile).
  std::vector<double> local = detail::local_spacings(in_soup, detail::KnnIndex(in_soup), 6);
  const auto q99 = local.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(local.size() - 1));
  std::nth_element(local.begin(), q99, local.end());
  const double reach = std::max(options.support * spacing, options.bridge * *q99);
  std::vector<bool> keep(model.tracks.size(), true);
  for (std::size_t t = 0; t < occluded_tracks.size() && t < keep.size(); ++t) keep[t] = !occluded_tracks[t];
  // The tracks' surface at d' = resolution x l; it only serves as the
  // oracle's second answer, so tracks closer than l / 2 are merged first
  // (merged within d'/4 at d' = l, the fill took 50% longer for the same
  // accuracy and completeness).
  const double d_prime = std::max(options.resolution * size, spacing);
  PointSet tracks = oriented_tracks(model, keep, std::max(0.5 * size, 0.25 * spacing));
  stats.tracks = tracks.size();
  if (tracks.size() < 50) {
    stats.skipped = "fewer than 50 visible tracks";
    return stats;
  }
  ReconstructOptions surface;
  surface.feature_mode = FeatureMode::None;
  surface.check_input_normals = false;  // oriented by the cameras, which MST cannot improve
  // Tracks seen from cameras around a scene are not a scan from above: a
  // street scene's tracks can be one layer and wide, yet its walls are seen.
  surface.walls.mode = WallMode::Off;
  surface.delta = std::clamp(d_prime / average_spacing(tracks), 1.0, 16.0);
  // A first, loose cut that keeps Poisson from meshing open space; the
  // finer one follows below. No boundary clip at one spacing: it would open
  // again the gaps among sparse tracks that the fill is meant to close.
  surface.trim_distance = std::max(0.1, reach / d_prime);
  surface.clip_boundary = false;
  // Its facets only feed the soup mesher, which meshes the soup anew.
  surface.repair_self_intersections = false;
  SurfaceMesh fill;
  try {
    fill = reconstruct(tracks, surface, progress).mesh;
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {  // no surface through these tracks (flat, degenerate, Poisson failed): the soup alone
    stats.skipped = std::string("the tracks' surface failed: ") + e.what();
    return stats;
  }
  stats.surface_facets = fill.faces.size();
  if (fill.faces.empty()) return stats;

  // Keep the facets away from the soup (gap > 0) and near its tracks or in the gaps they surround.
  if (options.gap > 0) {
    const detail::TriangleDistance to_soup(soup);
    std::vector<Vec3> centroids;
    for (const Triangle& f : fill.faces)
      centroids.push_back((1.0 / 3) * (fill.vertices[f[0]] + fill.vertices[f[1]] + fill.vertices[f[2]]));
    const std::vector<double> soup_distance = to_soup.distances(centroids);
    std::vector<Triangle> candidates;
    for (std::size_t f = 0; f < fill.faces.size(); ++f) {
      if (soup_distance[f] < options.gap * size) {
        ++stats.removed_near_soup;
        continue;
      }
      candidates.push_back(fill.faces[f]);
    }
    fill.faces = candidates;
  }
  stats.removed_far = trim_unless_bridging(fill, in_soup, options.support * spacing, options.bridge);

  // Visibility (6.3.2): no line of sight may cross an invented facet.
  TriangleSoup sight;
  sight.vertices = soup.vertices;
  const auto offset = static_cast<std::uint32_t>(sight.vertices.size());
  sight.vertices.insert(sight.vertices.end(), fill.vertices.begin(), fill.vertices.end());
  for (const Triangle& f : fill.faces) sight.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  const SightCrossings crossings = count_sight_crossings(sight, model, sight_margin * spacing, progress);
  std::vector<std::uint32_t> index(fill.vertices.size(), UINT32_MAX);
  for (std::size_t f = 0; f < fill.faces.size(); ++f) {
    if (crossings.per_face[f] > static_cast<std::uint32_t>(options.max_crossings)) {
      ++stats.removed_visibility;
      continue;
    }
    Triangle added;
    for (int k = 0; k < 3; ++k) {
      std::uint32_t& i = index[fill.faces[f][k]];
      if (i == UINT32_MAX) {
        i = static_cast<std::uint32_t>(soup.vertices.size());
        soup.vertices.push_back(fill.vertices[fill.faces[f][k]]);
      }
      added[k] = i;
    }
    soup.faces.push_back(added);
    ++stats.added;
  }
  return stats;
}

}  // namespace sharpmesh
