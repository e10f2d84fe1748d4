// The multi-view stereo pipeline of thesis Ch. 6 on inputs whose answer is
// known: merging and cone angles, smoothing of a noisy plane, the contour
// score, a box edge becoming a constrained edge, a wall removed by the lines
// of sight through it, the soup oracle's centroid, and a generated scene end
// to end against its ground truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>

#include "fixtures.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"
#include "sharpmesh/meshing.h"
#include "sharpmesh/scene.h"
#include "sharpmesh/stereo_io.h"
#include "sharpmesh/stereo_reconstruct.h"

using namespace sharpmesh;

namespace {

/// A camera at `center` looking down +z (world axes = camera axes), 320x240, f = 300.
Camera camera_at(const Vec3& center) {
  Camera c;
  c.image_name = "view.png";
  c.width = 320;
  c.height = 240;
  c.fx = c.fy = 300;
  c.cx = 160;
  c.cy = 120;
  c.translation = {-center[0], -center[1], -center[2]};
  return c;
}

/// Generates a scene in `folder` and reads its cameras and tracks back.
StereoModel generated_scene(const std::string& folder, int views, int width, int height, std::size_t samples) {
  SceneOptions scene;
  scene.views = views;
  scene.width = width;
  scene.height = height;
  scene.samples = samples;
  scene.seed = 4;
  make_scene(folder, scene);
  return read_stereo_model(folder);
}

Track track(const Vec3& p, std::vector<std::uint32_t> views) {
  Track t;
  t.position = p;
  t.views = std::move(views);
  return t;
}

}  // namespace

TEST(TrackPreprocessing, MergesCloseTracksWithTheUnionOfTheirViews) {
  std::vector<Track> tracks{track({0, 0, 0}, {0, 1}), track({0.001, 0, 0}, {1, 2}), track({1, 0, 0}, {0, 2})};
  EXPECT_EQ(merge_tracks(tracks, 0.01), 1u);
  ASSERT_EQ(tracks.size(), 2u);
  EXPECT_EQ(tracks[0].views, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_NEAR(tracks[0].position[0], 0.0005, 1e-12);
  EXPECT_EQ(tracks[1].position[0], 1.0);
  EXPECT_EQ(merge_tracks(tracks, 0.01), 0u);
  // A t1 far below the box's size (cells capped at 2^40 along it): only exact duplicates merge.
  std::vector<Track> twins{track({5, 5, 5}, {0}), track({5, 5, 5}, {1}), track({6, 5, 5}, {0})};
  EXPECT_EQ(merge_tracks(twins, 1e-30), 1u);
  EXPECT_EQ(twins[0].views, (std::vector<std::uint32_t>{0, 1}));
}

// The grid search gives the rule of 6.3.1 exactly: each track, in input
// order, joins its nearest kept track when that one is closer than t1 (a
// brute-force reference, with clusters across grid cells and negative coordinates).
TEST(TrackPreprocessing, MergingMatchesTheNearestKeptTrackRule) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1, 1), jitter(-0.04, 0.04);
  std::vector<Track> tracks;
  for (int i = 0; i < 1500; ++i) {
    const Vec3 centre{u(rng), u(rng), u(rng)};
    const int copies = 1 + static_cast<int>(rng() % 3);
    for (int c = 0; c < copies; ++c)
      tracks.push_back(track(centre + Vec3{jitter(rng), jitter(rng), jitter(rng)}, {static_cast<std::uint32_t>(c)}));
  }
  const double t1 = 0.05;
  std::vector<std::uint32_t> kept;  // brute force
  std::vector<std::uint32_t> owner(tracks.size());
  for (std::uint32_t i = 0; i < tracks.size(); ++i) {
    std::uint32_t best = UINT32_MAX;
    double best_d2 = t1 * t1;
    for (std::uint32_t k : kept) {
      const Vec3 d = tracks[k].position - tracks[i].position;
      if (dot(d, d) < best_d2) {
        best_d2 = dot(d, d);
        best = k;
      }
    }
    if (best == UINT32_MAX) kept.push_back(i);
    owner[i] = best == UINT32_MAX ? i : best;
  }
  std::vector<Vec3> expected;
  for (std::uint32_t k : kept) {
    Vec3 sum{0, 0, 0};
    int n = 0;
    for (std::uint32_t i = 0; i < tracks.size(); ++i)
      if (owner[i] == k) sum = sum + tracks[i].position, ++n;
    expected.push_back((1.0 / n) * sum);
  }
  std::vector<Track> merged = tracks;
  EXPECT_EQ(merge_tracks(merged, t1), tracks.size() - kept.size());
  ASSERT_EQ(merged.size(), kept.size());
  EXPECT_GT(tracks.size() - kept.size(), 500u);
  for (std::size_t k = 0; k < kept.size(); ++k)
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(merged[k].position[a], expected[k][a], 1e-12);
}

TEST(TrackPreprocessing, ConeAngleIsTheWidestAngleBetweenLinesOfSight) {
  EXPECT_NEAR(cone_angle({0, 0, 0}, {{1, 0, 0}, {0, 2, 0}}), M_PI / 2, 1e-12);
  EXPECT_NEAR(cone_angle({0, 0, 0}, {{1, 0, 0}, {1, 0.1, 0}, {1, 0.05, 0}}), std::atan(0.1), 1e-12);
  EXPECT_EQ(cone_angle({0, 0, 0}, {{1, 0, 0}}), 0.0);
}

TEST(TrackPreprocessing, GaussianJetSmoothingFlattensANoisyPlane) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> noise(0, 0.01);
  std::vector<Vec3> points;
  for (int i = 0; i < 4000; ++i) points.push_back({u(rng), u(rng), noise(rng)});
  const auto rms_z = [](const std::vector<Vec3>& p) {
    double s = 0;
    for (const Vec3& q : p) s += q[2] * q[2];
    return std::sqrt(s / p.size());
  };
  const double before = rms_z(points);
  jet_smooth_gaussian(points, 85);
  EXPECT_LT(rms_z(points), 0.3 * before);
  EXPECT_THROW(jet_smooth_gaussian(points, 3), InvalidArgument);
}

// The unit of t1 is the bulk's extent: a far cluster under 1% of the tracks
// (a real model's stray points) moves neither it nor what merges, and is counted.
TEST(TrackPreprocessing, AFarClusterMovesNeitherTheScaleNorTheMerging) {
  StereoModel model;
  model.cameras = {camera_at({0, 0, -10}), camera_at({5, 0, -10})};
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0, 10);
  for (int i = 0; i < 2000; ++i) model.tracks.push_back(track({unit(random), unit(random), 0.1 * unit(random)}, {0, 1}));
  StereoModel with_far = model;
  for (int i = 0; i < 15; ++i) with_far.tracks.push_back(track({-80 - 0.1 * unit(random), unit(random), 0}, {0, 1}));
  TrackPreprocessOptions options;
  options.smooth_k = 0;
  options.outlier_sigmas = 1e9;
  const TrackPreprocessStats bulk = preprocess_tracks(model, options);
  const TrackPreprocessStats far = preprocess_tracks(with_far, options);
  EXPECT_GT(far.raw_half_diagonal, 3 * bulk.raw_half_diagonal);
  EXPECT_LT(far.half_diagonal, 1.1 * bulk.half_diagonal);
  EXPECT_EQ(bulk.far_tracks, 0u);
  EXPECT_EQ(far.far_tracks, 15u);
  EXPECT_LE(far.merged, bulk.merged + 15);
}

TEST(TrackPreprocessing, SingleViewTracksAreRemovedAndNothingLeftIsAnError) {
  StereoModel model;
  model.cameras = {camera_at({0, 0, 0}), camera_at({1, 0, 0})};
  for (int i = 0; i < 50; ++i) model.tracks.push_back(track({0.01 * i, 0, 5}, {0}));
  model.tracks.push_back(track({0, 1, 5}, {0, 1}));
  const TrackPreprocessStats stats = preprocess_tracks(model, {});
  EXPECT_EQ(stats.removed_cone, 50u);
  EXPECT_EQ(model.tracks.size(), 1u);
  StereoModel all = model;  // t2 = 0: the cone criterion is off, single views included
  for (int i = 0; i < 50; ++i) all.tracks.push_back(track({0.01 * i, 0, 5}, {0}));
  TrackPreprocessOptions no_cone;
  no_cone.min_cone_angle = 0;
  EXPECT_EQ(preprocess_tracks(all, no_cone).removed_cone, 0u);
  EXPECT_EQ(all.tracks.size(), 51u);
  // Fused depth-map points skip t2 by default (their views did not triangulate them).
  StereoModel dense = all;
  dense.dense_points = true;
  const TrackPreprocessStats dense_stats = preprocess_tracks(dense, {});
  EXPECT_TRUE(dense_stats.cone_filter_skipped);
  EXPECT_EQ(dense_stats.removed_cone, 0u);
  EXPECT_EQ(dense.tracks.size(), 51u);
  dense = all;
  dense.dense_points = true;
  TrackPreprocessOptions on_dense;
  on_dense.cone_angle_on_dense_points = true;
  EXPECT_EQ(preprocess_tracks(dense, on_dense).removed_cone, 50u);
  StereoModel empty = model;
  for (Track& t : empty.tracks) t.views = {0};
  std::vector<GreyImage> images(2, GreyImage{320, 240, std::vector<std::uint8_t>(320 * 240, 100)});
  EXPECT_THROW(reconstruct_stereo(empty, images, {}), InvalidInput);
}

TEST(DepthMaps, AffineGapPenalty) {
  const int w = 40, h = 10;
  std::vector<std::uint8_t> contours(w * h, 0);
  for (int x = 0; x < w; ++x) contours[5 * w + x] = 255;  // a horizontal contour on row 5
  // Along the contour: every pixel matches.
  EXPECT_DOUBLE_EQ(contour_edge_score(contours, w, h, {2.5, 5.5}, {12.5, 5.5}, 0.5, 2), 11);
  // Far from it: one gap over the 11 pixels, o + 10 e.
  EXPECT_DOUBLE_EQ(contour_edge_score(contours, w, h, {2.5, 0.5}, {12.5, 0.5}, 0.5, 2), -(0.5 + 10 * 2));
  // Two gaps of 2 cost less than one gap of 4 (the affine penalty favours short gaps).
  std::vector<std::uint8_t> broken = contours, holed = contours;
  for (int x : {5, 6, 20, 21}) broken[5 * w + x] = 0;
  for (int x : {5, 6, 7, 8}) holed[5 * w + x] = 0;
  EXPECT_GT(contour_edge_score(broken, w, h, {0.5, 5.5}, {30.5, 5.5}, 0.5, 2),
            contour_edge_score(holed, w, h, {0.5, 5.5}, {30.5, 5.5}, 0.5, 2));
}

TEST(DepthMaps, ABoxEdgeBecomesAConstrainedEdge) {
  // A camera at the origin sees the plane z = 5 whose image has a vertical
  // step edge at x = 160; tracks on the plane, some of them on the edge.
  StereoModel model;
  model.cameras = {camera_at({0, 0, 0})};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> px(5, 315), py(5, 235);
  const auto on_plane = [](double x, double y) { return Vec3{(x - 160) * 5 / 300, (y - 120) * 5 / 300, 5}; };
  while (model.tracks.size() < 400) {
    const double x = px(rng);
    if (std::abs(x - 160) > 3) model.tracks.push_back(track(on_plane(x, py(rng)), {0}));  // ctracks are the edge's own
  }
  std::vector<std::uint32_t> edge_tracks;
  for (double y = 10; y < 235; y += 15) {
    edge_tracks.push_back(static_cast<std::uint32_t>(model.tracks.size()));
    model.tracks.push_back(track(on_plane(160.0, y), {0}));
  }
  std::vector<std::uint8_t> grey(320 * 240);
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) grey[y * 320 + x] = x < 160 ? 40 : 200;
  const DepthMapOptions options;
  const std::vector<std::uint8_t> contours = detect_contours(grey, 320, 240, options);
  const DepthMap map = build_depth_map(model, 0, contours, options);
  EXPECT_EQ(map.tracks.size(), model.tracks.size());
  // Every pair of consecutive edge tracks is a constraint...
  for (std::size_t i = 0; i + 1 < edge_tracks.size(); ++i) {
    const std::array<std::uint32_t, 2> a{edge_tracks[i], edge_tracks[i + 1]}, b{edge_tracks[i + 1], edge_tracks[i]};
    EXPECT_TRUE(std::find(map.constraints.begin(), map.constraints.end(), a) != map.constraints.end() ||
                std::find(map.constraints.begin(), map.constraints.end(), b) != map.constraints.end())
        << "edge tracks " << i << " and " << i + 1 << " are not joined";
  }
  // ...and so no triangle crosses the edge along the chain.
  ASSERT_FALSE(map.triangles.empty());
  const double y_first = model.tracks[edge_tracks.front()].position[1], y_last = model.tracks[edge_tracks.back()].position[1];
  for (const Triangle& t : map.triangles) {
    bool left = false, right = false, beyond_chain = false;
    for (std::uint32_t v : t) {
      beyond_chain |= model.tracks[v].position[1] < y_first || model.tracks[v].position[1] > y_last;
      left |= model.tracks[v].position[0] < -1e-9;
      right |= model.tracks[v].position[0] > 1e-9;
    }
    EXPECT_FALSE(left && right && !beyond_chain) << "a triangle crosses the contour";
  }
}

TEST(SoupFilters, ATrackSeenThroughAWallRemovesTheWall) {
  // Camera 0 at the origin; a wall triangle at z = 5; six tracks at z = 10
  // behind it, seen by camera 0 through it.
  StereoModel model;
  model.cameras = {camera_at({0, 0, 0}), camera_at({0.5, 0, 0})};
  model.tracks = {track({-1, -1, 5}, {0, 1}), track({1, -1, 5}, {0, 1}), track({0, 1, 5}, {0, 1})};
  for (int i = 0; i < 6; ++i) model.tracks.push_back(track({0.2 * (i % 3) - 0.2, 0.2 * (i / 3) - 0.2, 10}, {0}));
  TriangleSoup soup;
  for (const Track& t : model.tracks) soup.vertices.push_back(t.position);
  soup.faces = {{0, 1, 2}};
  const SightCrossings crossings = count_sight_crossings(soup, model, 0.0);
  EXPECT_EQ(crossings.per_face[0], 6u);
  // Six lines of sight through it, above t3 = 5: the wall goes.
  SoupFilterOptions options;
  TriangleSoup kept = soup;
  const SoupFilterStats stats = filter_soup(kept, model, {}, options);
  EXPECT_EQ(stats.removed_visibility, 1u);
  EXPECT_TRUE(kept.faces.empty());
  options.max_crossings = 6;
  kept = soup;
  EXPECT_EQ(filter_soup(kept, model, {}, options).output, 1u);
}

TEST(SoupMeshing, TheOracleAnswersTheCentroidOfAllIntersections) {
  TriangleSoup soup;
  soup.vertices = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, {-1, -1, 1}, {1, -1, 1}, {0, 1, 1}};
  soup.faces = {{0, 1, 2}, {3, 4, 5}};
  Vec3 p;
  ASSERT_TRUE(soup_segment_intersection(soup, {0, 0, -1}, {0, 0, 2}, p));
  EXPECT_NEAR(p[2], 0.5, 1e-12);
  ASSERT_TRUE(soup_segment_intersection(soup, {0, 0, -1}, {0, 0, 0.5}, p));
  EXPECT_NEAR(p[2], 0.0, 1e-12);
  EXPECT_FALSE(soup_segment_intersection(soup, {5, 5, -1}, {5, 5, 2}, p));
}

TEST(SoupMeshing, AFlatSoupGivesAFlatMeshCoveringIt) {
  TriangleSoup soup;
  const int n = 20;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) soup.vertices.push_back({static_cast<double>(i) / n, static_cast<double>(j) / n, 0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto v = static_cast<std::uint32_t>(j * (n + 1) + i);
      soup.faces.push_back({v, v + 1, v + n + 2});
      soup.faces.push_back({v, v + n + 2, v + n + 1});
    }
  SoupMeshingOptions options;
  options.size = 0.05;
  options.distance = 0.01;
  const SoupMeshingResult result = mesh_soup(soup, options);
  ASSERT_GT(result.mesh.faces.size(), 100u);
  double area = 0;
  for (const Vec3& v : result.mesh.vertices) {
    EXPECT_NEAR(v[2], 0.0, 1e-9);
    EXPECT_GE(v[0], -1e-9);
    EXPECT_LE(v[0], 1 + 1e-9);
  }
  for (const Triangle& f : result.mesh.faces) {
    const Vec3 normal = cross(result.mesh.vertices[f[1]] - result.mesh.vertices[f[0]], result.mesh.vertices[f[2]] - result.mesh.vertices[f[0]]);
    area += 0.5 * norm(normal);
    EXPECT_GT(normal[2], 0) << "facets are oriented like the soup";
  }
  EXPECT_GT(area, 0.8);
  EXPECT_LT(area, 1.0 + 1e-9);
  options.size = 1e-6;
  EXPECT_THROW(mesh_soup(soup, options), InvalidArgument);
  EXPECT_THROW(mesh_soup(TriangleSoup{}, {}), InvalidInput);
}

TEST(Contours, AdaptiveThresholdsKeepTheContoursOfADimImage) {
  // Blocks of random grey levels, and the same image at 15% contrast.
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> level(0, 255);
  const int w = 240, h = 160, block = 20;
  std::vector<int> levels((w / block) * (h / block));
  for (int& l : levels) l = level(rng);
  std::vector<std::uint8_t> bright(w * h), dim(w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int l = levels[(y / block) * (w / block) + x / block];
      bright[y * w + x] = static_cast<std::uint8_t>(l);
      dim[y * w + x] = static_cast<std::uint8_t>(20 + 0.15 * l);
    }
  const auto edge_pixels = [&](const std::vector<std::uint8_t>& grey, bool adaptive) {
    DepthMapOptions options;
    options.canny_adaptive = adaptive;
    const std::vector<std::uint8_t> edges = detect_contours(grey, w, h, options);
    return std::count_if(edges.begin(), edges.end(), [](std::uint8_t e) { return e != 0; });
  };
  const auto bright_fixed = edge_pixels(bright, false), dim_fixed = edge_pixels(dim, false);
  const auto bright_adaptive = edge_pixels(bright, true), dim_adaptive = edge_pixels(dim, true);
  ASSERT_GT(bright_fixed, 1000);
  EXPECT_LT(dim_fixed, bright_fixed / 2) << "fixed thresholds lose the weaker contours of a dim image";
  EXPECT_GT(dim_adaptive, 0.8 * bright_adaptive) << "scaled thresholds keep them";
  EXPECT_LT(dim_adaptive, 1.25 * bright_adaptive);
}

TEST(SoupMeshing, EveryPatchOfTheSoupIsMeshedNotOnlyWhereRandomSeedsFall) {
  // A 10 x 10 square of 7,200 triangles and four 1 x 1 squares of 32 each,
  // off to the side: random seeds (one soup triangle each) rarely fall on the
  // small squares; the grid seeds always do.
  TriangleSoup soup;
  const auto add_square = [&soup](double x, double y, double z, double side, int n) {
    const auto base = static_cast<std::uint32_t>(soup.vertices.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) soup.vertices.push_back({x + side * i / n, y + side * j / n, z});
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto v = base + static_cast<std::uint32_t>(j * (n + 1) + i);
        soup.faces.push_back({v, v + 1, v + static_cast<std::uint32_t>(n) + 2});
        soup.faces.push_back({v, v + static_cast<std::uint32_t>(n) + 2, v + static_cast<std::uint32_t>(n) + 1});
      }
  };
  add_square(0, 0, 0, 10, 60);
  for (int k = 1; k <= 4; ++k) add_square(14, 2.5 * k - 2, 0.5, 1, 4);
  SoupMeshingOptions options;
  options.initial_points = 100;
  options.size = 0.01;
  options.distance = 0.002;
  const auto facets_on_small_squares = [](const SurfaceMesh& mesh) {
    std::array<int, 4> count{};
    for (const Triangle& f : mesh.faces) {
      const Vec3 c = (1.0 / 3) * (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]);
      if (c[0] < 13.5) continue;
      EXPECT_NEAR(c[2], 0.5, 0.01);
      const int k = static_cast<int>(std::floor((c[1] + 2) / 2.5));
      if (k >= 1 && k <= 4) ++count[static_cast<std::size_t>(k - 1)];
    }
    return count;
  };
  const std::array<int, 4> with_grid = facets_on_small_squares(mesh_soup(soup, options).mesh);
  for (int k = 0; k < 4; ++k) EXPECT_GT(with_grid[static_cast<std::size_t>(k)], 4) << "small square " << k + 1 << " was not meshed";
  options.seed_cells = false;  // the thesis's random seeds alone
  const std::array<int, 4> random_only = facets_on_small_squares(mesh_soup(soup, options).mesh);
  EXPECT_TRUE(std::count(random_only.begin(), random_only.end(), 0) > 0) << "random seeds found every small square: the test proves nothing";
}

TEST(SoupFill, AHoleOfTheSoupIsFilledFromTheTracksSurface) {
  // Tracks on a gently curved sheet z = 10 + 0.3 sin(x) cos(y), seen by
  // three cameras at z = 0; the soup over them has a hole of radius 0.45 at
  // the centre. The fill puts the tracks' surface there (within 3 spacings
  // of the soup's tracks, and where they surround it).
  StereoModel model;
  model.cameras = {camera_at({0, 0, 0}), camera_at({0.5, 0, 0}), camera_at({0, 0.5, 0})};
  const int n = 61;
  auto height = [](double x, double y) { return 10 + 0.3 * std::sin(x) * std::cos(y); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -3 + 0.1 * i, y = -3 + 0.1 * j;
      model.tracks.push_back(track({x, y, height(x, y)}, {0, 1, 2}));
    }
  TriangleSoup soup;
  for (const Track& t : model.tracks) soup.vertices.push_back(t.position);
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const auto v = static_cast<std::uint32_t>(j * n + i);
      const double x = -3 + 0.1 * (i + 0.5), y = -3 + 0.1 * (j + 0.5);
      if (x * x + y * y < 0.45 * 0.45) continue;
      soup.faces.push_back({v, v + 1, static_cast<std::uint32_t>(v + n + 1)});
      soup.faces.push_back({v, static_cast<std::uint32_t>(v + n + 1), static_cast<std::uint32_t>(v + n)});
    }
  Vec3 hit;
  ASSERT_FALSE(soup_segment_intersection(soup, {0.2, 0.1, 5}, {0.2, 0.1, 15}, hit));
  SoupFillOptions options;
  TriangleSoup disabled = soup;
  options.enabled = false;
  EXPECT_EQ(fill_soup_from_tracks(disabled, model, options, 0.1, 1.0).added, 0u);
  EXPECT_EQ(disabled.faces.size(), soup.faces.size());
  options.enabled = true;
  TriangleSoup filled = soup;
  const SoupFillStats stats = fill_soup_from_tracks(filled, model, options, 0.1, 1.0);
  EXPECT_TRUE(stats.skipped.empty()) << stats.skipped;
  EXPECT_GT(stats.added, 0u);
  ASSERT_TRUE(soup_segment_intersection(filled, {0.2, 0.1, 5}, {0.2, 0.1, 15}, hit));
  EXPECT_NEAR(hit[2], height(0.2, 0.1), 0.05);
  // With a gap of 2 l, nothing is added within 0.2 of the soup.
  options.gap = 2;
  TriangleSoup away = soup;
  const SoupFillStats gapped = fill_soup_from_tracks(away, model, options, 0.1, 1.0);
  EXPECT_GT(gapped.removed_near_soup, 0u);
  EXPECT_LT(gapped.added, stats.added);
  EXPECT_FALSE(soup_segment_intersection(away, {0.4, 0, 5}, {0.4, 0, 15}, hit)) << "0.05 inside the hole's rim";
  options.support = -1;
  EXPECT_THROW(fill_soup_from_tracks(away, model, options, 0.1, 1.0), InvalidArgument);
}

TEST(SoupFill, AGapAmongTheTracksIsBridgedButTheirEdgeIsNotExtended) {
  // The sheet of the test above, with tracks every 0.1 but none within 0.28
  // of the centre (far ground has such gaps between sparse tracks), and the
  // soup over the tracks. With a support of one spacing, the tracks'
  // surface (facets about 0.2 long) closes the gap only by bridging; it does
  // not reach past the tracks' outer edge (|x|, |y| = 3).
  StereoModel model;
  model.cameras = {camera_at({0, 0, 0}), camera_at({0.5, 0, 0}), camera_at({0, 0.5, 0})};
  const int n = 61;
  auto height = [](double x, double y) { return 10 + 0.3 * std::sin(x) * std::cos(y); };
  std::vector<std::uint32_t> index(n * n, UINT32_MAX);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -3 + 0.1 * i, y = -3 + 0.1 * j;
      if (x * x + y * y < 0.28 * 0.28) continue;
      index[static_cast<std::size_t>(j * n + i)] = static_cast<std::uint32_t>(model.tracks.size());
      model.tracks.push_back(track({x, y, height(x, y)}, {0, 1, 2}));
    }
  TriangleSoup soup;
  for (const Track& t : model.tracks) soup.vertices.push_back(t.position);
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const std::array<std::uint32_t, 4> v{index[static_cast<std::size_t>(j * n + i)], index[static_cast<std::size_t>(j * n + i + 1)],
                                           index[static_cast<std::size_t>((j + 1) * n + i + 1)], index[static_cast<std::size_t>((j + 1) * n + i)]};
      if (std::count(v.begin(), v.end(), UINT32_MAX) > 0) continue;
      soup.faces.push_back({v[0], v[1], v[2]});
      soup.faces.push_back({v[0], v[2], v[3]});
    }
  Vec3 hit;
  ASSERT_FALSE(soup_segment_intersection(soup, {0.02, 0.01, 5}, {0.02, 0.01, 15}, hit));
  SoupFillOptions options;
  options.support = 1;
  TriangleSoup filled = soup;
  const SoupFillStats stats = fill_soup_from_tracks(filled, model, options, 0.05, 1.0);
  EXPECT_TRUE(stats.skipped.empty()) << stats.skipped;
  ASSERT_TRUE(soup_segment_intersection(filled, {0.02, 0.01, 5}, {0.02, 0.01, 15}, hit)) << "the gap is bridged";
  EXPECT_NEAR(hit[2], height(0.02, 0.01), 0.05);
  double farthest = 0;
  for (std::size_t f = soup.faces.size(); f < filled.faces.size(); ++f)
    for (std::uint32_t v : filled.faces[f]) farthest = std::max({farthest, std::abs(filled.vertices[v][0]), std::abs(filled.vertices[v][1])});
  EXPECT_LT(farthest, 3.35) << "the fill stops within a facet of the tracks' edge";
  options.bridge = 0;
  TriangleSoup unbridged = soup;
  fill_soup_from_tracks(unbridged, model, options, 0.05, 1.0);
  EXPECT_FALSE(soup_segment_intersection(unbridged, {0.02, 0.01, 5}, {0.02, 0.01, 15}, hit)) << "without bridging, the gap stays";
  options.bridge = -1;
  EXPECT_THROW(fill_soup_from_tracks(unbridged, model, options, 0.05, 1.0), InvalidArgument);
}

TEST(SoupFill, FacetsThatLinesOfSightCrossAreNotAdded) {
  // Two sheets of tracks: a half sheet at z = 10 and a full one at z = 14
  // behind it, all seen by the three cameras. Where the lines of sight to
  // the far sheet cross the near one, the near one's surface is not added
  // (6.3.2's visibility constraint on the fill); the far sheet's is.
  StereoModel model;
  model.cameras = {camera_at({0, 0, 0}), camera_at({0.5, 0, 0}), camera_at({0, 0.5, 0})};
  const int n = 61;
  std::vector<std::uint32_t> far_id(n * n), near_id(n * n, UINT32_MAX);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -3 + 0.1 * i, y = -3 + 0.1 * j, wobble = 0.01 * ((i * 7 + j * 3) % 5);
      far_id[static_cast<std::size_t>(j * n + i)] = static_cast<std::uint32_t>(model.tracks.size());
      model.tracks.push_back(track({x, y, 14 + wobble}, {0, 1, 2}));
      if (x >= 0) continue;
      near_id[static_cast<std::size_t>(j * n + i)] = static_cast<std::uint32_t>(model.tracks.size());
      model.tracks.push_back(track({x, y, 10 + wobble}, {0, 1, 2}));
    }
  TriangleSoup soup;  // a soup over both sheets: their tracks support the fill
  for (const Track& t : model.tracks) soup.vertices.push_back(t.position);
  for (const auto* id : {&far_id, &near_id})
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        auto at = [&](int di, int dj) { return (*id)[static_cast<std::size_t>((j + dj) * n + i + di)]; };
        if (at(0, 0) == UINT32_MAX || at(1, 1) == UINT32_MAX || at(1, 0) == UINT32_MAX || at(0, 1) == UINT32_MAX) continue;
        soup.faces.push_back({at(0, 0), at(1, 0), at(1, 1)});
        soup.faces.push_back({at(0, 0), at(1, 1), at(0, 1)});
      }
  const std::size_t soup_faces = soup.faces.size();
  ASSERT_GT(soup_faces, 100u);
  const SoupFillStats stats = fill_soup_from_tracks(soup, model, {}, 0.1, 1.0);
  EXPECT_TRUE(stats.skipped.empty()) << stats.skipped;
  EXPECT_GT(stats.removed_visibility, 0u);
  ASSERT_GT(stats.added, 100u);
  // Lines of sight to the far sheet cross the near one where x > -2.1 and
  // |y| < 2.1 (the far sheet seen through it, scaled by 10/14).
  std::size_t near = 0, far = 0;
  for (std::size_t f = soup_faces; f < soup.faces.size(); ++f) {
    const Vec3& v = soup.vertices[soup.faces[f][0]];
    near += v[2] < 10.5 && v[0] > -1.9 && v[0] < -0.4 && std::abs(v[1]) < 1.9;  // away from its rim, where Poisson bends to the far sheet
    far += v[2] > 12;
  }
  EXPECT_LT(near, stats.added / 50) << "the near sheet, seen through, is not added";
  EXPECT_GT(far, stats.added / 2);
}

TEST(HoleFilling, ShortHolesAreClosedAndLongOnesKept) {
  SurfaceMesh sphere = test::sphere_mesh(3);
  ASSERT_EQ(count_boundary_edges(sphere), 0u);
  // Two holes: one facet removed at the north pole, a band of facets elsewhere.
  std::vector<Triangle> kept;
  std::size_t removed = 0;
  for (const Triangle& f : sphere.faces) {
    const Vec3 c = (1.0 / 3) * (sphere.vertices[f[0]] + sphere.vertices[f[1]] + sphere.vertices[f[2]]);
    if ((c[2] > 0.97) || (c[0] > 0.6 && std::abs(c[2]) < 0.3)) {
      ++removed;
      continue;
    }
    kept.push_back(f);
  }
  ASSERT_GT(removed, 4u);
  SurfaceMesh holed{sphere.vertices, kept};
  ASSERT_GT(count_boundary_edges(holed), 0u);

  SurfaceMesh none = holed;
  HoleFillingOptions options;
  options.max_perimeter = 1e-3;
  const HoleFillingStats small = fill_holes(none, options);
  EXPECT_EQ(small.holes, 2u);
  EXPECT_EQ(small.filled, 0u);
  EXPECT_EQ(none.faces.size(), holed.faces.size());

  options.max_perimeter = 10;
  const HoleFillingStats all = fill_holes(holed, options);
  EXPECT_EQ(all.holes, 2u);
  EXPECT_EQ(all.filled, 2u);
  EXPECT_EQ(all.failed, 0u);
  EXPECT_EQ(count_boundary_edges(holed), 0u) << "filled holes leave no border";
  for (const Vec3& v : holed.vertices) EXPECT_NEAR(norm(v), 1.0, 0.08) << "the faired patches follow the sphere";

  options.max_perimeter = -1;
  EXPECT_THROW(fill_holes(holed, options), InvalidArgument);
}

TEST(StereoReconstruction, AGeneratedSceneIsReconstructedAccuratelyAndCompletely) {
  test::TempDir dir;
  StereoModel model = generated_scene(dir.path("scene"), 6, 320, 240, 12000);
  const std::vector<GreyImage> images = read_grey_images(model, dir.path("scene/images"));
  const StereoReconstruction r = reconstruct_stereo(model, images, {});
  EXPECT_GT(r.tracks.removed_distance + r.removed_track_photo, 0u) << "the scene's outliers are filtered";
  EXPECT_GT(r.contour_edges, 0u);
  ASSERT_GT(r.meshing.mesh.faces.size(), 1000u);
  const SurfaceMesh truth = read_mesh(dir.path("scene/ground_truth.ply"));
  StereoEvalOptions eval;
  eval.samples = 20000;
  const StereoEvaluation e = evaluate_stereo(r.meshing.mesh, truth, model.cameras, eval);
  const std::size_t one_percent = 4;  // thresholds 0.05%, 0.1%, 0.2%, 0.5%, 1%, ...
  ASSERT_DOUBLE_EQ(eval.thresholds[one_percent], 0.01);
  // Bounds with a margin below what the pipeline reaches on generated scenes
  // (docs/stereo.md): one soup triangle from the roof to the far ground,
  // hidden behind the building, passes every filter of 6.3.2, and the fill
  // spreads next to it, so accuracy at 1% stays short of 0.95 on this scene.
  EXPECT_GT(e.accuracy[one_percent], 0.935);
  EXPECT_GT(e.completeness[one_percent], 0.92);
  // One manifold, consistently oriented surface (make_manifold).
  const TopologyReport topology = check_topology(r.meshing.mesh, false);
  EXPECT_EQ(topology.non_manifold_edges, 0u);
  EXPECT_EQ(topology.non_manifold_vertices, 0u);
  EXPECT_TRUE(topology.orientable);
}

TEST(StereoReconstruction, ImagesOfTheWrongSizeAreRefusedByName) {
  test::TempDir dir;
  StereoModel model = generated_scene(dir.path("scene"), 3, 64, 48, 500);
  model.cameras[1].width = 80;
  const std::string message = test::error_of([&] { read_grey_images(model, dir.path("scene/images")); });
  EXPECT_NE(message.find("view_001.png"), std::string::npos) << message;
  EXPECT_NE(message.find("64x48"), std::string::npos) << message;
  StereoModel broken = read_stereo_model(dir.path("scene"));
  broken.tracks[0].views.push_back(17);
  EXPECT_THROW(broken.validate("model"), InvalidInput);
}

// Three sheets on one edge and a facet facing the wrong way: afterwards no
// edge has more than two facets, neighbours agree on their orientation, and
// the facets and positions are those of before.
TEST(ManifoldRepair, SheetsMeetingAtAnEdgeAreSeparatedAndNeighboursAgree) {
  SurfaceMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}, {1.5, 1, 0}};
  // Three fins on edge 0-1; a fourth facet next to the first, wound the other way.
  mesh.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {2, 1, 5}};
  const SurfaceMesh before = mesh;
  const ManifoldRepairStats stats = make_manifold(mesh);
  EXPECT_EQ(stats.non_manifold_edges, 1u);
  EXPECT_GT(stats.duplicated_vertices, 0u);
  ASSERT_EQ(mesh.faces.size(), before.faces.size());
  const TopologyReport topology = check_topology(mesh, false);
  EXPECT_EQ(topology.non_manifold_edges, 0u);
  EXPECT_EQ(topology.non_manifold_vertices, 0u);
  EXPECT_TRUE(topology.orientable);
  // Every directed edge at most once: neighbours are wound consistently.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const Triangle& f : mesh.faces)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(++directed[std::make_pair(f[k], f[(k + 1) % 3])], 1);
  // The same triangles in space, some reversed.
  for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
    std::vector<Vec3> a, b;
    for (int k = 0; k < 3; ++k) a.push_back(before.vertices[before.faces[i][k]]), b.push_back(mesh.vertices[mesh.faces[i][k]]);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);
  }
  SurfaceMesh clean = mesh;
  const ManifoldRepairStats again = make_manifold(clean);
  EXPECT_EQ(again.non_manifold_edges, 0u);
  EXPECT_EQ(again.duplicated_vertices, 0u);
  EXPECT_EQ(again.flipped_facets, 0u);
}
