// Streaming reads (include/sharpmesh/point_stream.h) and the streamed cloud
// scan of `info` (include/sharpmesh/cloud_scan.h): the blocks together are
// the file as the whole-file reader reads it, in every format and layout,
// and a broken file fails as the whole-file reader fails.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "fixtures.h"
#include "sharpmesh/cloud_scan.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/io.h"
#include "sharpmesh/las.h"
#include "sharpmesh/point_stream.h"
#include "sharpmesh/pointset.h"

using namespace sharpmesh;
using test::TempDir;
using test::error_of;
using test::write_bytes;

namespace {

PointSet random_cloud(std::size_t n, bool normals, bool colors, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> u(-3, 3);
  PointSet cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.push_back({u(random), u(random), u(random)});
    if (normals) cloud.normals.push_back({u(random), u(random), 1.0});
    if (colors) cloud.colors.push_back({static_cast<std::uint8_t>(i % 256), 7, 200});
  }
  return cloud;
}

/// Every block of the stream, appended; checks each block's size.
PointSet streamed(const std::string& path, std::size_t block_points, bool* streams = nullptr) {
  PointStream stream(path, block_points);
  if (streams) *streams = stream.streams();
  PointSet all, block;
  while (stream.next(block)) {
    EXPECT_LE(block.size(), block_points);
    EXPECT_GT(block.size(), 0u);
    all.points.insert(all.points.end(), block.points.begin(), block.points.end());
    all.normals.insert(all.normals.end(), block.normals.begin(), block.normals.end());
    all.colors.insert(all.colors.end(), block.colors.begin(), block.colors.end());
  }
  EXPECT_TRUE(block.empty());
  return all;
}

void expect_same(const PointSet& a, const PointSet& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.colors, b.colors);
}

}  // namespace

TEST(PointStream, BlocksTogetherAreTheFileInEveryWrittenFormat) {
  TempDir dir;
  const PointSet cloud = random_cloud(1000, true, true, 3);
  const PointSet plain = random_cloud(777, false, false, 4);
  struct Case {
    std::string name;
    const PointSet* points;
    PlyFormat format;
  };
  for (const Case& c : {Case{"binary.ply", &cloud, PlyFormat::Binary}, Case{"ascii.ply", &cloud, PlyFormat::Ascii},
                        Case{"normals.xyz", &cloud, PlyFormat::Binary}, Case{"plain.xyz", &plain, PlyFormat::Binary},
                        Case{"plain.ply", &plain, PlyFormat::Binary}}) {
    const std::string path = dir.path(c.name);
    write_point_set(path, *c.points, c.format);
    const PointSet whole = read_point_set(path);
    for (std::size_t block : {1, 7, 1000, 5000}) {
      SCOPED_TRACE(c.name + ", blocks of " + std::to_string(block));
      bool streams = false;
      expect_same(streamed(path, block, &streams), whole);
      EXPECT_TRUE(streams);
    }
    PointStream stream(path);
    if (c.name.find(".xyz") != std::string::npos) EXPECT_FALSE(stream.declared_count().has_value());
    else EXPECT_EQ(stream.declared_count().value_or(0), c.points->size());
  }
}

TEST(PointStream, HandWrittenLayoutsStreamAsTheyRead) {
  TempDir dir;
  // ASCII PLY with comments, blank lines, CRLF ends, an element before the
  // vertices and faces after them.
  write_bytes(dir.path("layout.ply"),
              "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nelement camera 2\r\nproperty float f\r\n"
              "element vertex 3\r\nproperty float y\r\nproperty float x\r\nproperty float z\r\nproperty uchar red\r\n"
              "property uchar green\r\nproperty uchar blue\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\n"
              "end_header\r\n1\r\n\r\n2\r\n0 1 2 10 20 30\r\n# a comment line\r\n3 4 5 40 50 60\r\n6 7 8 70 80 90\r\n3 0 1 2\r\n");
  // Binary big endian, doubles, an element of fixed size before the vertices.
  std::string binary = "ply\nformat binary_big_endian 1.0\nelement extra 2\nproperty short s\nelement vertex 2\n"
                       "property double x\nproperty double y\nproperty double z\nend_header\n";
  binary += std::string(4, '\x01');
  for (double v : {1.5, -2.0, 3.25, 4.0, 5.0, -6.5}) {
    unsigned char bytes[8];
    std::memcpy(bytes, &v, 8);
    for (int i = 7; i >= 0; --i) binary += static_cast<char>(bytes[i]);
  }
  write_bytes(dir.path("big.ply"), binary);
  // XYZ without a final newline, with comments and CRLF.
  write_bytes(dir.path("last.xyz"), "# x y z\r\n0 0 0\r\n\r\n1 2 3 # a point\r\n4 5 6");
  for (const char* name : {"layout.ply", "big.ply", "last.xyz"}) {
    const PointSet whole = read_point_set(dir.path(name));
    ASSERT_FALSE(whole.empty()) << name;
    for (std::size_t block : {1, 2, 100}) {
      SCOPED_TRACE(std::string(name) + ", blocks of " + std::to_string(block));
      expect_same(streamed(dir.path(name), block), whole);
    }
  }
  EXPECT_EQ(read_point_set(dir.path("big.ply")).points[1], (Vec3{4.0, 5.0, -6.5}));
  // A vertex record with a list property cannot be cut into fixed records:
  // the file is read whole, and the blocks are still the file.
  write_bytes(dir.path("list.ply"),
              "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
              "property list uchar int tags\nend_header\n0 0 0 2 5 6\n1 1 1 0\n");
  bool streams = true;
  expect_same(streamed(dir.path("list.ply"), 1, &streams), read_point_set(dir.path("list.ply")));
  EXPECT_FALSE(streams);
}

TEST(PointStream, BrokenFilesFailAsTheWholeFileReaderFails) {
  TempDir dir;
  write_point_set(dir.path("cloud.ply"), random_cloud(100, true, false, 5), PlyFormat::Binary);
  std::string bytes = test::read_bytes(dir.path("cloud.ply"));
  write_bytes(dir.path("short.ply"), bytes.substr(0, bytes.size() - 30));
  // Refused before any block is handed out: nothing is half read.
  const std::string message = error_of([&] { PointStream stream(dir.path("short.ply")); });
  EXPECT_NE(message.find("short.ply"), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
  EXPECT_NE(error_of([&] { read_point_set(dir.path("short.ply")); }), "no error");

  std::string lines;
  for (int i = 0; i < 5000; ++i) lines += std::to_string(i) + " 1 2\n";
  lines += "5 x 6\n";
  write_bytes(dir.path("bad.xyz"), lines);
  const std::string streaming = error_of([&] { streamed(dir.path("bad.xyz"), 64); });
  EXPECT_EQ(streaming, error_of([&] { read_point_set(dir.path("bad.xyz")); }));
  EXPECT_NE(streaming.find("line 5001"), std::string::npos) << streaming;

  write_bytes(dir.path("noheader.ply"), "ply\nformat ascii 1.0\nelement vertex 1\n");
  EXPECT_NE(error_of([&] { PointStream stream(dir.path("noheader.ply")); }).find("end_header"), std::string::npos);
  EXPECT_NE(error_of([&] { PointStream stream(dir.path("missing.xyz")); }).find("missing.xyz"), std::string::npos);
}

TEST(PointStream, LazTilesStreamChunkByChunkWithTheirClasses) {
  const std::string tile = std::string(SHARPMESH_LIDAR_DIR) + "/ahn3_cropped_2.laz";
  if (!std::filesystem::exists(tile)) GTEST_SKIP() << "no shared LiDAR data";
  const PointSet whole = read_point_set(tile);
  PointStream stream(tile, 30000);
  PointSet block, all;
  std::vector<std::uint8_t> classes;
  std::size_t buildings = 0;
  while (stream.next(block, &classes)) {
    ASSERT_EQ(classes.size(), block.size());
    all.points.insert(all.points.end(), block.points.begin(), block.points.end());
    for (std::uint8_t c : classes) buildings += c == 6;
  }
  EXPECT_EQ(all.points, whole.points);
  EXPECT_EQ(buildings, read_las_points(tile, {6}).size());
}

TEST(CloudScan, ExactSpacingBelowTheLimitAndASampledOneAboveIt) {
  TempDir dir;
  // A surface: the sampled blocks' cell size assumes spacing falls as n^-1/2.
  const PointSet cloud = test::sample_with_normals(test::sphere_mesh(4, 2.0), 60000, 9);
  write_point_set(dir.path("sphere.ply"), cloud, PlyFormat::Binary);
  const double exact = average_spacing(cloud);
  const BoundingBox box = bounding_box(cloud.points);

  const CloudScan whole = scan_point_cloud(dir.path("sphere.ply"));
  EXPECT_EQ(whole.points, cloud.size());
  EXPECT_TRUE(whole.normals);
  EXPECT_EQ(whole.box.min, box.min);
  EXPECT_EQ(whole.box.max, box.max);
  EXPECT_TRUE(whole.spacing_exact);
  EXPECT_DOUBLE_EQ(whole.average_spacing, exact);

  CloudScanOptions sampled;
  sampled.exact_spacing_limit = 10000;
  sampled.sampled_spacing_points = 20000;
  const CloudScan scan = scan_point_cloud(dir.path("sphere.ply"), sampled);
  EXPECT_FALSE(scan.spacing_exact);
  EXPECT_EQ(scan.passes, 2);
  EXPECT_GT(scan.spacing_points, 200u);
  EXPECT_LT(scan.spacing_points, 20000u);
  EXPECT_NEAR(scan.average_spacing, exact, 0.05 * exact);

  CloudScanOptions none;
  none.spacing = false;
  EXPECT_LT(scan_point_cloud(dir.path("sphere.ply"), none).average_spacing, 0);
}
