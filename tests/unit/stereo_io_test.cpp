// Cameras and tracks: camera geometry, and each reader on files in the real
// tool's conventions with hand-checked values (a track projects onto its
// recorded pixel within 0.5 px), plus malformed files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "fixtures.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/io.h"
#include "sharpmesh/stereo_io.h"

using namespace sharpmesh;
using test::TempDir;
using test::error_of;
using test::write_bytes;

namespace {

const std::string kColmap = std::string(SHARPMESH_TEST_DATA) + "/colmap";

void copy_model(const std::string& from, const TempDir& to, const std::string& ext) {
  for (const char* name : {"cameras", "images", "points3D"})
    write_bytes(to.path(std::string(name) + ext), test::read_bytes(from + "/" + name + ext));
}

void write_image(const std::string& path, int width, int height) {
  cv::imwrite(path, cv::Mat(height, width, CV_8UC3, cv::Scalar(10, 20, 30)));
}

const Camera& by_name(const StereoModel& m, const std::string& name) {
  for (const Camera& c : m.cameras)
    if (c.image_name == name) return c;
  throw std::runtime_error("no camera " + name);
}

// The hand-made COLMAP model in tests/data/colmap: image 5 "front.png"
// (identity, t = (0,0,5)) sees the point (1, 0.5, 0) at (420, 290); image 2
// "side.png" (90 degrees about y, t = (0,0,4)) at (320, 323.33).
void check_hand_model(const StereoModel& m) {
  ASSERT_EQ(m.cameras.size(), 3u);
  ASSERT_EQ(m.tracks.size(), 1u);
  const Camera& front = by_name(m, "front.png");
  EXPECT_EQ(front.width, 640);
  EXPECT_DOUBLE_EQ(front.cx, 320);
  const Vec3 c = front.center();
  EXPECT_NEAR(c[2], -5, 1e-12);
  const Camera& small = by_name(m, "small.png");  // SIMPLE_RADIAL with k = 0
  EXPECT_DOUBLE_EQ(small.fx, 250);
  EXPECT_DOUBLE_EQ(small.fy, 250);
  EXPECT_DOUBLE_EQ(small.cy, 120);
  const Track& t = m.tracks[0];
  EXPECT_EQ(t.color, (Rgb{200, 100, 50}));
  ASSERT_EQ(t.views.size(), 2u);
  ASSERT_EQ(t.pixels.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    Vec2 p;
    ASSERT_TRUE(m.cameras[t.views[k]].project(t.position, p));
    EXPECT_LT(std::hypot(p[0] - t.pixels[k][0], p[1] - t.pixels[k][1]), 0.5) << m.cameras[t.views[k]].image_name;
  }
  Vec2 side;
  ASSERT_TRUE(by_name(m, "side.png").project(t.position, side));
  EXPECT_NEAR(side[0], 320, 1e-9);
  EXPECT_NEAR(side[1], 240 + 500 * 0.5 / 3, 1e-9);
  EXPECT_LT(reprojection_error(m).max, 1e-6);
}

}  // namespace

TEST(Camera, ProjectUnprojectAndRays) {
  Camera c;
  c.width = 640, c.height = 480, c.fx = 500, c.fy = 480, c.cx = 320, c.cy = 240;
  c.rotation = rotation_from_quaternion(0.9, 0.1, -0.3, 0.2);
  c.translation = {0.3, -0.2, 4};
  const Vec3 x{0.4, -0.7, 1.1};
  Vec2 p;
  ASSERT_TRUE(c.project(x, p));
  const Vec3 back = c.unproject(p, c.depth(x));
  EXPECT_LT(distance(back, x), 1e-12);
  const Vec3 ray = c.viewing_ray(p);
  const Vec3 along = c.center() + distance(x, c.center()) * ray;
  EXPECT_LT(distance(along, x), 1e-12);
  EXPECT_FALSE(c.project(c.center() - 1.0 * ray, p));  // behind the camera
  const auto q = quaternion_from_rotation(c.rotation);
  const Mat3 r = rotation_from_quaternion(q[0], q[1], q[2], q[3]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(r[i][j], c.rotation[i][j], 1e-12);
}

TEST(Colmap, ReadsHandCheckedTextModel) { check_hand_model(read_colmap_model(kColmap + "/text")); }

TEST(Colmap, ReadsBinaryModelWrittenByColmap) {
  // tests/data/colmap/binary was written by `colmap model_converter` (3.8) from the text model.
  check_hand_model(read_colmap_model(kColmap + "/binary"));
}

TEST(Colmap, TextAndBinaryRoundTrips) {
  const StereoModel original = read_colmap_model(kColmap + "/text");
  for (bool binary : {false, true}) {
    TempDir dir;
    write_colmap_model(dir.dir(), original, binary);
    const StereoModel back = read_colmap_model(dir.dir());
    ASSERT_EQ(back.cameras.size(), original.cameras.size());
    for (std::size_t i = 0; i < back.cameras.size(); ++i) {
      EXPECT_EQ(back.cameras[i].image_name, original.cameras[i].image_name);
      EXPECT_LT(distance(back.cameras[i].center(), original.cameras[i].center()), 1e-9);
    }
    ASSERT_EQ(back.tracks.size(), 1u);
    EXPECT_EQ(back.tracks[0].views, original.tracks[0].views);
    EXPECT_LT(reprojection_error(back).max, 1e-6);
  }
}

TEST(Colmap, RefusesDistortedAndFisheyeModels) {
  TempDir dir;
  copy_model(kColmap + "/text", dir, ".txt");
  write_bytes(dir.path("cameras.txt"), "3 OPENCV 640 480 500 500 320 240 0.1 0 0 0\n7 PINHOLE 320 240 250 250 160 120\n");
  EXPECT_NE(error_of([&] { read_colmap_model(dir.dir()); }).find("non-zero distortion"), std::string::npos);
  write_bytes(dir.path("cameras.txt"), "3 OPENCV_FISHEYE 640 480 500 500 320 240 0 0 0 0\n7 PINHOLE 320 240 250 250 160 120\n");
  EXPECT_NE(error_of([&] { read_colmap_model(dir.dir()); }).find("not a pinhole"), std::string::npos);
  write_bytes(dir.path("cameras.txt"), "3 FOOBAR 640 480 500\n");
  EXPECT_NE(error_of([&] { read_colmap_model(dir.dir()); }).find("unknown camera model 'FOOBAR'"), std::string::npos);
}

TEST(Colmap, RefusesTrackOnMissingImage) {
  TempDir dir;
  copy_model(kColmap + "/text", dir, ".txt");
  write_bytes(dir.path("points3D.txt"), "11 1 0.5 0 200 100 50 0.1 5 0 4 0\n");
  EXPECT_NE(error_of([&] { read_colmap_model(dir.dir()); }).find("refers to image 4, which is not in images"), std::string::npos);
  write_bytes(dir.path("points3D.txt"), "11 1 0.5 0 200 100 50 0.1 5 7\n");
  EXPECT_NE(error_of([&] { read_colmap_model(dir.dir()); }).find("refers to observation 7"), std::string::npos);
}

TEST(Colmap, RefusesTruncatedAndUnknownBinary) {
  TempDir dir;
  copy_model(kColmap + "/binary", dir, ".bin");
  const std::string images = test::read_bytes(kColmap + "/binary/images.bin");
  write_bytes(dir.path("images.bin"), images.substr(0, images.size() - 5));
  EXPECT_NE(error_of([&] { read_colmap_model(dir.dir()); }).find("truncated"), std::string::npos);
  copy_model(kColmap + "/binary", dir, ".bin");
  std::string cameras = test::read_bytes(kColmap + "/binary/cameras.bin");
  const std::int32_t bad_model = 99;
  std::memcpy(cameras.data() + 12, &bad_model, 4);  // first camera's model id
  write_bytes(dir.path("cameras.bin"), cameras);
  EXPECT_NE(error_of([&] { read_colmap_model(dir.dir()); }).find("unknown camera model id 99"), std::string::npos);
  std::string huge = test::read_bytes(kColmap + "/binary/points3D.bin");
  const std::uint64_t count = std::uint64_t(1) << 60;
  std::memcpy(huge.data(), &count, 8);
  copy_model(kColmap + "/binary", dir, ".bin");
  write_bytes(dir.path("points3D.bin"), huge);
  EXPECT_NE(error_of([&] { read_colmap_model(dir.dir()); }).find("exceeds the file size"), std::string::npos);
}

TEST(Colmap, FusedVisIndicesFollowFileOrderNotImageIds) {
  // Image ids 5, 2, 9 in file order: .vis index 1 is "side.png" (id 2).
  const StereoModel sparse = read_colmap_model(kColmap + "/text");
  TempDir dir;
  StereoModel fused;
  fused.cameras = sparse.cameras;
  Track t;
  t.position = {1, 0.5, 0};
  t.views = {1, 0};
  fused.tracks = {t};
  write_colmap_fused(dir.path("fused.ply"), fused, {{0, 0, 1}});
  std::vector<Vec3> normals;
  const StereoModel back = read_colmap_fused(dir.path("fused.ply"), sparse.cameras, &normals);
  EXPECT_TRUE(back.dense_points);
  ASSERT_EQ(back.tracks.size(), 1u);
  ASSERT_EQ(back.tracks[0].views.size(), 2u);
  EXPECT_EQ(back.cameras[back.tracks[0].views[0]].image_name, "side.png");
  EXPECT_LT(distance(back.tracks[0].position, t.position), 1e-6);
  ASSERT_EQ(normals.size(), 1u);
  // A .vis index beyond the model's images, and a .vis of another point count.
  std::string vis = test::read_bytes(dir.path("fused.ply.vis"));
  const std::uint32_t bad = 3;
  std::memcpy(vis.data() + 12, &bad, 4);
  write_bytes(dir.path("fused.ply.vis"), vis);
  EXPECT_NE(error_of([&] { read_colmap_fused(dir.path("fused.ply"), sparse.cameras); }).find("refers to image index 3"), std::string::npos);
  write_bytes(dir.path("fused.ply.vis"), vis.substr(0, 6));
  EXPECT_NE(error_of([&] { read_colmap_fused(dir.path("fused.ply"), sparse.cameras); }).find("truncated"), std::string::npos);
}

TEST(Strecha, ReadsCameraFileAndTracks) {
  TempDir dir;
  // K with the top-left pixel centre at (0,0); R camera-to-world = I; C = (0,0,-5).
  write_bytes(dir.path("0000.png.camera"), "500 0 319.5\n0 500 239.5\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 -5\n640 480\n");
  Track t;
  t.position = {1, 0.5, 0};
  t.views = {0};
  write_tracks_ply(dir.path("tracks.ply"), {t});
  const StereoModel m = read_strecha(dir.dir(), dir.path("tracks.ply"));
  ASSERT_EQ(m.cameras.size(), 1u);
  EXPECT_EQ(m.cameras[0].image_name, "0000.png");
  Vec2 p;
  ASSERT_TRUE(m.cameras[0].project(m.tracks[0].position, p));
  EXPECT_NEAR(p[0], 420, 1e-9);  // 419.5 in Strecha's pixel-centre origin
  EXPECT_NEAR(p[1], 290, 1e-9);
  write_bytes(dir.path("0000.png.camera"), "500 0 319.5\n0 500 239.5\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_NE(error_of([&] { read_strecha(dir.dir(), dir.path("tracks.ply")); }).find("unexpected end of file"), std::string::npos);
}

TEST(Bundler, ConvertsMinusZCamerasAndCentredMeasurements) {
  TempDir dir;
  write_image(dir.path("a.png"), 640, 480);
  write_bytes(dir.path("list.txt"), "a.png 0 500\n");
  // R = I, t = (0,0,-5): the camera looks down -Z. The point (1, 0.5, -10) is
  // at P = (1, 0.5, -15), p = -P/P.z * f = (33.33, 16.67) from the centre, y up,
  // so at pixel (353.33, 223.33).
  write_bytes(dir.path("bundle.out"),
              "# Bundle file v0.3\n1 1\n500 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 -5\n1 0.5 -10\n255 0 0\n1 0 17 33.333333 16.666667\n");
  const StereoModel m = read_stereo_model(dir.path("bundle.out"));
  ASSERT_EQ(m.cameras.size(), 1u);
  EXPECT_EQ(m.cameras[0].width, 640);
  Vec2 p;
  ASSERT_TRUE(m.cameras[0].project(m.tracks[0].position, p));
  EXPECT_NEAR(p[0], 320 + 500.0 / 15, 1e-9);
  EXPECT_NEAR(p[1], 240 - 250.0 / 15, 1e-9);
  EXPECT_LT(reprojection_error(m).max, 0.5);
  // Strong distortion is refused; a measurement on an unknown camera too.
  write_bytes(dir.path("bundle.out"), "# Bundle file v0.3\n1 0\n500 0.2 0\n1 0 0\n0 1 0\n0 0 1\n0 0 -5\n");
  EXPECT_NE(error_of([&] { read_stereo_model(dir.path("bundle.out")); }).find("undistort"), std::string::npos);
  write_bytes(dir.path("bundle.out"), "# Bundle file v0.3\n1 1\n500 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 -5\n1 0.5 -10\n255 0 0\n1 3 17 33 16\n");
  EXPECT_NE(error_of([&] { read_stereo_model(dir.path("bundle.out")); }).find("camera index"), std::string::npos);
  write_bytes(dir.path("list.txt"), "missing.png\n");
  EXPECT_NE(error_of([&] { read_stereo_model(dir.path("bundle.out")); }).find("missing.png"), std::string::npos);
}

TEST(Nvm, CameraCentreAndBothMeasurementConventions) {
  TempDir dir;
  write_image(dir.path("a.png"), 640, 480);
  write_image(dir.path("b.png"), 640, 480);
  // Identity rotation, centre (0,0,-5): (1, 0.5, 0) is 100 px right and 50 px
  // below the centre in a; b sits at centre (1,0,-5) and sees it at (0, 50).
  const std::string cameras = "2\na.png 500 1 0 0 0 0 0 -5 0 0\nb.png 500 1 0 0 0 1 0 -5 0 0\n";
  for (const auto& [name, measurements] :
       {std::pair<std::string, std::string>{"centred", "0 0 100 50 1 0 0 50"}, {"absolute", "0 0 419.5 289.5 1 0 319.5 289.5"}}) {
    write_bytes(dir.path("m.nvm"), "NVM_V3\n\n" + cameras + "1\n1 0.5 0 10 20 30 2 " + measurements + "\n0\n");
    const StereoModel m = read_stereo_model(dir.path("m.nvm"));
    ASSERT_EQ(m.cameras.size(), 2u) << name;
    EXPECT_NEAR(m.cameras[1].center()[0], 1, 1e-12);
    EXPECT_NEAR(m.tracks[0].pixels[0][0], 420, 1e-9) << name;
    EXPECT_NEAR(m.tracks[0].pixels[0][1], 290, 1e-9) << name;
    EXPECT_LT(reprojection_error(m).max, 0.5) << name;
  }
  write_bytes(dir.path("m.nvm"), "NVM_V3_R9T\n");
  EXPECT_NE(error_of([&] { read_stereo_model(dir.path("m.nvm")); }).find("not supported"), std::string::npos);
  write_bytes(dir.path("m.nvm"), "NVM_V3\n\n" + cameras + "1\n1 0.5 0 10 20 30 1 5 0 100 50\n");
  EXPECT_NE(error_of([&] { read_stereo_model(dir.path("m.nvm")); }).find("image index"), std::string::npos);
}

TEST(Tracks, PlyRoundTripWithLabels) {
  TempDir dir;
  std::vector<Track> tracks(3);
  tracks[0].position = {1, 2, 3};
  tracks[0].views = {0, 4, 2};
  tracks[2].views = {1};
  tracks[2].color = {1, 2, 3};
  write_tracks_ply(dir.path("t.ply"), tracks, {false, true, false});
  std::vector<bool> labels;
  const std::vector<Track> back = read_tracks_ply(dir.path("t.ply"), &labels);
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[0].views, tracks[0].views);
  EXPECT_EQ(back[2].color, tracks[2].color);
  EXPECT_EQ(labels, (std::vector<bool>{false, true, false}));
  // The same file is an ordinary point cloud for the other tools.
  EXPECT_EQ(read_point_set(dir.path("t.ply")).size(), 3u);
}

// The same scene listed in another order (cameras, tracks, each track's
// observations reversed, views renumbered) becomes the same model.
TEST(CanonicalOrder, AnyListingOfTheSameSceneBecomesTheSameModel) {
  StereoModel model = read_colmap_model(kColmap + "/text");
  ASSERT_GE(model.cameras.size(), 2u);
  StereoModel reversed = model;
  const auto n = static_cast<std::uint32_t>(model.cameras.size());
  std::reverse(reversed.cameras.begin(), reversed.cameras.end());
  std::reverse(reversed.tracks.begin(), reversed.tracks.end());
  for (Track& t : reversed.tracks) {
    for (std::uint32_t& v : t.views) v = n - 1 - v;
    std::reverse(t.views.begin(), t.views.end());
    std::reverse(t.pixels.begin(), t.pixels.end());
  }
  canonical_order(model);
  canonical_order(reversed);
  ASSERT_EQ(model.cameras.size(), reversed.cameras.size());
  for (std::size_t i = 0; i < model.cameras.size(); ++i) {
    EXPECT_EQ(model.cameras[i].image_name, reversed.cameras[i].image_name);
    EXPECT_EQ(model.cameras[i].translation, reversed.cameras[i].translation);
  }
  for (std::size_t i = 1; i < model.cameras.size(); ++i) EXPECT_LT(model.cameras[i - 1].image_name, model.cameras[i].image_name);
  ASSERT_EQ(model.tracks.size(), reversed.tracks.size());
  for (std::size_t i = 0; i < model.tracks.size(); ++i) {
    EXPECT_EQ(model.tracks[i].position, reversed.tracks[i].position);
    EXPECT_EQ(model.tracks[i].views, reversed.tracks[i].views);
    EXPECT_EQ(model.tracks[i].pixels, reversed.tracks[i].pixels);
    EXPECT_TRUE(std::is_sorted(model.tracks[i].views.begin(), model.tracks[i].views.end()));
  }
  // Each pixel still belongs to its view: the tracks project onto them.
  for (const Track& t : model.tracks)
    for (std::size_t k = 0; k < t.pixels.size(); ++k) {
      Vec2 projected;
      ASSERT_TRUE(model.cameras[t.views[k]].project(t.position, projected));
      EXPECT_NEAR(projected[0], t.pixels[k][0], 0.5);
      EXPECT_NEAR(projected[1], t.pixels[k][1], 0.5);
    }
}
