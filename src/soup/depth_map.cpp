// Contour-respecting depth maps (thesis 6.3.2): in each image, the tracks
// near a Canny contour (ctracks) are joined by the Delaunay edges that follow
// the contour (positive affine-gap score, then the length criterion), and all
// projected tracks are triangulated by a 2D constrained Delaunay
// triangulation with those edges as constraints, then lifted to 3D.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/spatial_sort.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>
#include <tuple>

#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = K::Point_2;
constexpr std::uint32_t kNoTrack = UINT32_MAX;

// Vertex info: the track index, kNoTrack for vertices CGAL adds where two
// constraints cross (they have no 3D position; their triangles are dropped).
struct TrackInfo {
  std::uint32_t track = kNoTrack;
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<TrackInfo, K>;
using Dt = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb>>;
using CVb = CGAL::Triangulation_vertex_base_with_info_2<TrackInfo, K>;
using CFb = CGAL::Constrained_triangulation_face_base_2<K>;
using CTds = CGAL::Triangulation_data_structure_2<CVb, CFb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, CTds, CGAL::Exact_predicates_tag>;

/// Candidate contour edges: Delaunay edges between ctracks with a positive score.
struct ScoredEdge {
  std::uint32_t a, b;  // positions in the projected-track list
  double length;
};

std::vector<ScoredEdge> contour_edges(const std::vector<Vec2>& pixels, const std::vector<std::uint32_t>& ctracks,
                                      const std::vector<std::uint8_t>& contours, int width, int height,
                                      const DepthMapOptions& options) {
  std::vector<std::pair<Point2, TrackInfo>> sites;
  sites.reserve(ctracks.size());
  for (std::uint32_t c : ctracks) sites.push_back({Point2(pixels[c][0], pixels[c][1]), TrackInfo{c}});
  Dt dt;
  dt.insert(sites.begin(), sites.end());
  std::vector<ScoredEdge> edges;
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    const auto va = e->first->vertex(Dt::cw(e->second)), vb = e->first->vertex(Dt::ccw(e->second));
    const std::uint32_t a = std::min(va->info().track, vb->info().track), b = std::max(va->info().track, vb->info().track);
    const double score =
        contour_edge_score(contours, width, height, pixels[a], pixels[b], options.gap_open, options.gap_extend);
    if (score > 0) edges.push_back({a, b, std::hypot(pixels[a][0] - pixels[b][0], pixels[a][1] - pixels[b][1])});
  }
  // CGAL's edge order depends on where the heap put its faces: sort, so that
  // the result does not depend on the thread or the run.
  std::sort(edges.begin(), edges.end(), [](const ScoredEdge& x, const ScoredEdge& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  return edges;
}

/// The length criterion: of kept edges leaving a ctrack in nearly the same
/// direction, only the shortest survives, so that n aligned ctracks give the
/// n - 1 edges between consecutive ones.
std::vector<ScoredEdge> non_overlapping(std::vector<ScoredEdge> edges, const std::vector<Vec2>& pixels, double angle_degrees) {
  std::stable_sort(edges.begin(), edges.end(), [](const ScoredEdge& x, const ScoredEdge& y) { return x.length < y.length; });
  const double cos_limit = std::cos(angle_degrees * M_PI / 180.0);
  std::unordered_map<std::uint32_t, std::vector<Vec2>> directions;  // accepted unit directions leaving each ctrack
  const auto unit = [&](std::uint32_t from, std::uint32_t to) {
    const double dx = pixels[to][0] - pixels[from][0], dy = pixels[to][1] - pixels[from][1];
    const double l = std::hypot(dx, dy);
    return Vec2{dx / l, dy / l};
  };
  const auto overlaps = [&](std::uint32_t at, const Vec2& d) {
    const auto it = directions.find(at);
    if (it == directions.end()) return false;
    for (const Vec2& other : it->second)
      if (other[0] * d[0] + other[1] * d[1] > cos_limit) return true;
    return false;
  };
  std::vector<ScoredEdge> kept;
  for (const ScoredEdge& e : edges) {
    if (!(e.length > 0)) continue;
    const Vec2 ab = unit(e.a, e.b), ba = unit(e.b, e.a);
    if (overlaps(e.a, ab) || overlaps(e.b, ba)) continue;
    directions[e.a].push_back(ab);
    directions[e.b].push_back(ba);
    kept.push_back(e);
  }
  return kept;
}

}  // namespace

DepthMap build_depth_map(const StereoModel& model, std::uint32_t view, const std::vector<std::uint8_t>& contours,
                         const DepthMapOptions& options) {
  if (view >= model.cameras.size()) throw InvalidArgument("depth map of a view that does not exist");
  const Camera& camera = model.cameras[view];
  const int width = camera.width, height = camera.height;
  if (contours.size() != static_cast<std::size_t>(width) * height)
    throw InvalidInput("the contour image of view " + camera.image_name + " does not have the camera's size");
  DepthMap map;
  std::vector<Vec2> pixels;  // of map.tracks
  for (std::uint32_t t = 0; t < model.tracks.size(); ++t) {
    const Track& track = model.tracks[t];
    if (std::find(track.views.begin(), track.views.end(), view) == track.views.end()) continue;
    Vec2 pixel;
    if (!camera.project(track.position, pixel) || !camera.in_image(pixel)) continue;
    map.tracks.push_back(t);
    pixels.push_back(pixel);
  }
  if (map.tracks.size() < 3) return map;

  // ctracks: projections within contour_distance of an edge pixel.
  cv::Mat edges(height, width, CV_8UC1, const_cast<std::uint8_t*>(contours.data()));
  cv::Mat not_edges = edges == 0, distance;
  cv::distanceTransform(not_edges, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  std::vector<std::uint32_t> ctrack_positions;  // positions in map.tracks
  for (std::uint32_t i = 0; i < pixels.size(); ++i) {
    const int col = std::clamp(static_cast<int>(pixels[i][0]), 0, width - 1);
    const int row = std::clamp(static_cast<int>(pixels[i][1]), 0, height - 1);
    if (distance.at<float>(row, col) <= options.contour_distance) ctrack_positions.push_back(i);
  }
  for (std::uint32_t c : ctrack_positions) map.ctracks.push_back(map.tracks[c]);
  const std::vector<ScoredEdge> constraints =
      ctrack_positions.size() >= 2
          ? non_overlapping(contour_edges(pixels, ctrack_positions, contours, width, height, options), pixels, options.overlap_angle)
          : std::vector<ScoredEdge>{};

  // Constrained Delaunay triangulation of all projected tracks.
  std::vector<std::size_t> order(pixels.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::vector<Point2> points;
  points.reserve(pixels.size());
  for (const Vec2& p : pixels) points.emplace_back(p[0], p[1]);
  CGAL::spatial_sort(order.begin(), order.end(),
                     CGAL::Spatial_sort_traits_adapter_2<K, CGAL::Pointer_property_map<Point2>::type>(
                         CGAL::make_property_map(points)));
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handle(pixels.size());
  Cdt::Vertex_handle hint;
  for (std::size_t i : order) {
    hint = cdt.insert(points[i], hint == Cdt::Vertex_handle() ? Cdt::Face_handle() : hint->face());
    if (hint->info().track == kNoTrack) hint->info().track = static_cast<std::uint32_t>(i);  // two tracks at one pixel: the first wins
    handle[i] = hint;
  }
  for (const ScoredEdge& e : constraints) {
    if (handle[e.a] == handle[e.b]) continue;
    cdt.insert_constraint(handle[e.a], handle[e.b]);
    map.constraints.push_back({map.tracks[e.a], map.tracks[e.b]});
  }
  // Lift: each finite face becomes a triangle of tracks, oriented towards the camera.
  const Vec3 center = camera.center();
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    std::array<std::uint32_t, 3> local{f->vertex(0)->info().track, f->vertex(1)->info().track, f->vertex(2)->info().track};
    if (local[0] == kNoTrack || local[1] == kNoTrack || local[2] == kNoTrack) continue;
    Triangle t{map.tracks[local[0]], map.tracks[local[1]], map.tracks[local[2]]};
    const Vec3& p0 = model.tracks[t[0]].position;
    const Vec3 normal = cross(model.tracks[t[1]].position - p0, model.tracks[t[2]].position - p0);
    if (dot(normal, center - p0) < 0) std::swap(t[1], t[2]);
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // same triangle, same orientation
    map.triangles.push_back(t);
  }
  std::sort(map.triangles.begin(), map.triangles.end());  // independent of CGAL's face order (heap addresses)
  return map;
}

std::size_t remove_duplicate_triangles(std::vector<Triangle>& triangles) {
  struct Hash {
    std::size_t operator()(const Triangle& t) const {
      return (static_cast<std::size_t>(t[0]) * 73856093u) ^ (static_cast<std::size_t>(t[1]) * 19349663u) ^
             (static_cast<std::size_t>(t[2]) * 83492791u);
    }
  };
  std::unordered_set<Triangle, Hash> seen;
  seen.reserve(triangles.size());
  std::vector<Triangle> kept;
  kept.reserve(triangles.size());
  for (const Triangle& t : triangles) {
    Triangle key = t;
    std::sort(key.begin(), key.end());
    if (key[0] == key[1] || key[1] == key[2]) continue;
    if (seen.insert(key).second) kept.push_back(t);
  }
  const std::size_t removed = triangles.size() - kept.size();
  triangles = std::move(kept);
  return removed;
}

}  // namespace sharpmesh
