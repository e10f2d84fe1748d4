// make-scene and eval-stereo: the generated cameras, images, depth maps and
// tracks agree with each other and with the ground truth; the evaluation
// gives 100% for the truth and drops where a result is incomplete.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "fixtures.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"
#include "sharpmesh/scene.h"
#include "sharpmesh/stereo_io.h"

using namespace sharpmesh;
using test::TempDir;

namespace {

SceneOptions small_scene(double noise) {
  SceneOptions o;
  o.views = 6;
  o.width = 160;
  o.height = 120;
  o.samples = 4000;
  o.noise = noise;
  o.seed = 5;
  return o;
}

// COLMAP's dense array format: "width&height&channels&" then float32 rows.
cv::Mat read_depth(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string w, h, c;
  std::getline(in, w, '&');
  std::getline(in, h, '&');
  std::getline(in, c, '&');
  cv::Mat depth(std::stoi(h), std::stoi(w), CV_32F);
  in.read(reinterpret_cast<char*>(depth.data), static_cast<std::streamsize>(depth.total() * sizeof(float)));
  return depth;
}

}  // namespace

TEST(MakeScene, LayoutAndTracksReprojectWithinTheNoise) {
  TempDir dir;
  const std::string out = dir.path("scene");
  const SceneOptions o = small_scene(0.5);
  const SceneSummary s = make_scene(out, o);
  for (const char* f : {"/images/view_000.png", "/images/view_005.png", "/sparse/cameras.txt", "/sparse/images.txt", "/sparse/points3D.txt",
                        "/tracks.ply", "/dense/fused.ply", "/dense/fused.ply.vis", "/ground_truth.ply", "/depth/view_003.png.depth.bin",
                        "/scene.json"})
    EXPECT_FALSE(test::read_bytes(out + f).empty()) << f;
  const StereoModel model = read_colmap_model(out + "/sparse");
  ASSERT_EQ(model.cameras.size(), 6u);
  ASSERT_EQ(model.tracks.size(), s.tracks);
  EXPECT_GT(s.tracks, 1000u);
  std::vector<bool> outlier;
  const std::vector<Track> labelled = read_tracks_ply(out + "/tracks.ply", &outlier);
  ASSERT_EQ(labelled.size(), s.tracks);
  const double outlier_fraction = static_cast<double>(std::count(outlier.begin(), outlier.end(), true)) / static_cast<double>(s.tracks);
  EXPECT_NEAR(outlier_fraction, o.outliers, 0.01);
  // Inliers reproject within the configured pixel noise.
  StereoModel inliers;
  inliers.cameras = model.cameras;
  for (std::size_t i = 0; i < model.tracks.size(); ++i)
    if (!outlier[i]) inliers.tracks.push_back(model.tracks[i]);
  const ReprojectionStats r = reprojection_error(inliers);
  EXPECT_LT(r.rms, std::sqrt(2.0) * o.noise);
  EXPECT_LT(r.max, 6 * o.noise);
  // The fused level reads back with COLMAP's conventions and its points lie near the surface.
  std::vector<Vec3> normals;
  const StereoModel fused = read_colmap_fused(out + "/dense/fused.ply", model.cameras, &normals);
  EXPECT_EQ(fused.tracks.size(), s.fused_points);
  EXPECT_EQ(normals.size(), s.fused_points);
  const cv::Mat image = cv::imread(out + "/images/view_002.png");
  EXPECT_EQ(image.cols, 160);
  EXPECT_EQ(image.rows, 120);
}

TEST(MakeScene, ImagesDepthAndCamerasAgreeExactly) {
  TempDir dir;
  const std::string out = dir.path("scene");
  SceneOptions o = small_scene(0.0);
  o.outliers = 0;
  make_scene(out, o);
  const StereoModel model = read_colmap_model(out + "/sparse");
  EXPECT_LT(reprojection_error(model).max, 1e-6);  // noise 0: triangulation is exact
  // The true depth at a track's pixel is the track's depth in that camera
  // (up to the surface slope across one pixel): pixel centres at (x + 0.5, y + 0.5).
  std::vector<cv::Mat> depth;
  for (const Camera& c : model.cameras) depth.push_back(read_depth(out + "/depth/" + c.image_name + ".depth.bin"));
  std::vector<double> relative;
  for (const Track& t : model.tracks)
    for (std::size_t k = 0; k < t.views.size(); ++k) {
      const Camera& c = model.cameras[t.views[k]];
      const float d = depth[t.views[k]].at<float>(static_cast<int>(t.pixels[k][1]), static_cast<int>(t.pixels[k][0]));
      relative.push_back(std::abs(d - c.depth(t.position)) / c.depth(t.position));
    }
  std::sort(relative.begin(), relative.end());
  EXPECT_LT(relative[relative.size() / 2], 0.005);
  EXPECT_LT(relative[relative.size() * 9 / 10], 0.02);
}

TEST(MakeScene, DeterministicAndRefusesForeignFolders) {
  TempDir dir;
  const SceneOptions o = small_scene(0.5);
  make_scene(dir.path("a"), o);
  make_scene(dir.path("b"), o);
  EXPECT_EQ(test::read_bytes(dir.path("a/tracks.ply")), test::read_bytes(dir.path("b/tracks.ply")));
  EXPECT_EQ(test::read_bytes(dir.path("a/images/view_001.png")), test::read_bytes(dir.path("b/images/view_001.png")));
  make_scene(dir.path("a"), o);  // a previous scene is replaced
  test::write_bytes(dir.path("notes.txt"), "mine");
  EXPECT_THROW(make_scene(dir.dir(), o), InvalidArgument);
  EXPECT_EQ(test::read_bytes(dir.path("notes.txt")), "mine");
  SceneOptions bad = o;
  bad.views = 1;
  EXPECT_THROW(make_scene(dir.path("c"), bad), InvalidArgument);
}

TEST(EvalStereo, TruthIsPerfectAndMissingPartsLowerCompleteness) {
  TempDir dir;
  const std::string out = dir.path("scene");
  make_scene(out, small_scene(0.5));
  const SurfaceMesh truth = read_mesh(out + "/ground_truth.ply");
  const StereoModel model = read_colmap_model(out + "/sparse");
  StereoEvalOptions options;
  options.samples = 20000;
  const StereoEvaluation self = evaluate_stereo(truth, truth, model.cameras, options);
  EXPECT_DOUBLE_EQ(self.accuracy.front(), 1.0);
  EXPECT_DOUBLE_EQ(self.completeness.front(), 1.0);
  // Without the ground (its first two faces) every result sample is still on
  // the truth, but the visible ground is missing.
  SurfaceMesh building = truth;
  building.faces.erase(building.faces.begin(), building.faces.begin() + 2);
  const StereoEvaluation partial = evaluate_stereo(building, truth, model.cameras, options);
  EXPECT_DOUBLE_EQ(partial.accuracy.front(), 1.0);
  EXPECT_LT(partial.completeness.back(), 0.8);
  // Swapped roles: the truth has much more than the building reference, so
  // its accuracy drops while it covers all of the reference.
  const StereoEvaluation swapped = evaluate_stereo(truth, building, model.cameras, options);
  EXPECT_DOUBLE_EQ(swapped.completeness.front(), 1.0);
  EXPECT_LT(swapped.accuracy.back(), 0.8);
}

TEST(Colmap, ReadsTracksTriangulatedByColmapOnAGeneratedScene) {
  // tests/data/colmap/triangulated: COLMAP 3.8's SIFT + point_triangulator on
  // `make-scene --views 8 --width 320 --height 240` (seed 1), binary model.
  const StereoModel colmap = read_colmap_model(std::string(SHARPMESH_TEST_DATA) + "/colmap/triangulated");
  TempDir dir;
  SceneOptions o;
  o.views = 8;
  o.width = 320;
  o.height = 240;
  o.samples = 200;
  make_scene(dir.path("scene"), o);
  const StereoModel ours = read_colmap_model(dir.path("scene/sparse"));
  ASSERT_EQ(colmap.cameras.size(), ours.cameras.size());
  for (const Camera& c : colmap.cameras) {  // COLMAP kept the poses it was given
    const auto same = std::find_if(ours.cameras.begin(), ours.cameras.end(), [&](const Camera& k) { return k.image_name == c.image_name; });
    ASSERT_NE(same, ours.cameras.end());
    EXPECT_LT(distance(same->center(), c.center()), 1e-6);
    EXPECT_NEAR(same->fx, c.fx, 1e-6);
  }
  EXPECT_GT(colmap.tracks.size(), 300u);
  EXPECT_LT(reprojection_error(colmap).rms, 1.0);
  // COLMAP's tracks lie on the ground truth: its matches of our images are right.
  const SurfaceMesh truth = read_mesh(dir.path("scene/ground_truth.ply"));
  std::vector<Vec3> positions;
  for (const Track& t : colmap.tracks) positions.push_back(t.position);
  std::vector<double> d = distances_to_mesh(positions, truth);
  std::sort(d.begin(), d.end());
  EXPECT_LT(d[d.size() / 2], 0.002 * bounding_box(truth.vertices).diagonal());
}
