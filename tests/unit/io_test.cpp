// Readers and writers: round trips, hand-written files of each format and
// variant, and malformed files that must give a clear InvalidInput.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "fixtures.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/io.h"

using namespace sharpmesh;
using test::TempDir;
using test::error_of;
using test::write_bytes;

namespace {

std::string bytes_of(const void* p, std::size_t n) { return std::string(static_cast<const char*>(p), n); }

template <class T>
std::string big_endian(T value) {
  std::string s = bytes_of(&value, sizeof value);
  return std::string(s.rbegin(), s.rend());
}

PointSet small_cloud() {
  PointSet ps;
  ps.points = {{0, 0, 0}, {1, 2, 3}, {-1.5, 1e-9, 12345.678901234}};
  ps.normals = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
  ps.colors = {{255, 0, 0}, {0, 128, 0}, {1, 2, 3}};
  return ps;
}

}  // namespace

TEST(Io, PlyBinaryAndAsciiRoundTripKeepPointsNormalsColours) {
  TempDir dir;
  const PointSet ps = small_cloud();
  for (PlyFormat format : {PlyFormat::Binary, PlyFormat::Ascii}) {
    const std::string path = dir.path(format == PlyFormat::Binary ? "b.ply" : "a.ply");
    write_point_set(path, ps, format);
    const PointSet back = read_point_set(path);
    ASSERT_EQ(back.size(), 3u);
    EXPECT_EQ(back.points, ps.points);  // positions are written as doubles: exact
    ASSERT_TRUE(back.has_normals());
    ASSERT_TRUE(back.has_colors());
    EXPECT_EQ(back.colors, ps.colors);
    for (std::size_t i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(back.normals[i][k], ps.normals[i][k], 1e-7);
  }
}

TEST(Io, PlyBigEndianFloatWithExtraElementsIsRead) {
  TempDir dir;
  std::string data =
      "ply\nformat binary_big_endian 1.0\ncomment hand written\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar quality\nelement camera 1\nproperty int id\nend_header\n";
  for (float v : {1.5f, -2.0f, 3.25f}) data += big_endian(v);
  data += char(7);
  for (float v : {4.0f, 5.0f, 6.0f}) data += big_endian(v);
  data += char(9);
  data += big_endian<std::int32_t>(42);
  write_bytes(dir.path("be.ply"), data);
  const PointSet ps = read_point_set(dir.path("be.ply"));
  ASSERT_EQ(ps.size(), 2u);
  EXPECT_EQ(ps.points[0], (Vec3{1.5, -2.0, 3.25}));
  EXPECT_EQ(ps.points[1], (Vec3{4, 5, 6}));
  EXPECT_FALSE(ps.has_normals());
}

TEST(Io, PlyMeshWithQuadsIsTriangulated) {
  TempDir dir;
  write_bytes(dir.path("quad.ply"),
              "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  const SurfaceMesh m = read_mesh(dir.path("quad.ply"));
  ASSERT_EQ(m.faces.size(), 2u);
  EXPECT_EQ(m.faces[1], (Triangle{0, 2, 3}));
}

TEST(Io, TruncatedBinaryPlyIsRefusedWithItsName) {
  TempDir dir;
  PointSet ps = small_cloud();
  write_point_set(dir.path("full.ply"), ps);
  std::string bytes;
  {
    std::FILE* f = std::fopen(dir.path("full.ply").c_str(), "rb");
    char buffer[4096];
    std::size_t n = std::fread(buffer, 1, sizeof buffer, f);
    std::fclose(f);
    bytes.assign(buffer, n - 10);
  }
  write_bytes(dir.path("cut.ply"), bytes);
  const std::string message = error_of([&] { read_point_set(dir.path("cut.ply")); });
  EXPECT_NE(message.find("cut.ply"), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
}

TEST(Io, HugeElementCountIsRefusedWithoutAllocating) {
  TempDir dir;
  write_bytes(dir.path("huge.ply"),
              "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\n"
              "property float z\nend_header\n0123456789ab");
  const std::string message = error_of([&] { read_point_set(dir.path("huge.ply")); });
  EXPECT_NE(message.find("1000000000000"), std::string::npos) << message;
  write_bytes(dir.path("huge.off"), "OFF\n1000000000000 0 0\n0 0 0\n");
  EXPECT_NE(error_of([&] { read_point_set(dir.path("huge.off")); }).find("huge.off"), std::string::npos);
}

TEST(Io, NanCoordinateNamesFileAndLine) {
  TempDir dir;
  write_bytes(dir.path("nan.xyz"), "0 0 0\n1 1 1\nnan 2 2\n");
  const std::string message = error_of([&] { read_point_set(dir.path("nan.xyz")); });
  EXPECT_NE(message.find("nan.xyz: line 3"), std::string::npos) << message;
  write_bytes(dir.path("inf.ply"), "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\ninf 0 0\n");
  EXPECT_NE(error_of([&] { read_point_set(dir.path("inf.ply")); }).find("vertex 0"), std::string::npos);
}

TEST(Io, XyzAcceptsCommentsBlankLinesAndNormals) {
  TempDir dir;
  write_bytes(dir.path("p.xyz"), "# a comment\n\n0 0 0 0 0 1\r\n  1 2 3   0 1 0 # trailing\n\n");
  const PointSet ps = read_point_set(dir.path("p.xyz"));
  ASSERT_EQ(ps.size(), 2u);
  ASSERT_TRUE(ps.has_normals());
  EXPECT_EQ(ps.points[1], (Vec3{1, 2, 3}));
  EXPECT_EQ(ps.normals[1], (Vec3{0, 1, 0}));
  write_bytes(dir.path("bad.xyz"), "0 0 0\n1 2\n");
  EXPECT_NE(error_of([&] { read_point_set(dir.path("bad.xyz")); }).find("bad.xyz: line 2: expected 3 or 6 numbers"), std::string::npos);
  write_bytes(dir.path("word.xyz"), "0 0 zero\n");
  EXPECT_NE(error_of([&] { read_point_set(dir.path("word.xyz")); }).find("'zero' is not a number"), std::string::npos);
}

TEST(Io, OffObjStlReadTheSameCube) {
  TempDir dir;
  const SurfaceMesh cube = test::cube_mesh();
  write_mesh(dir.path("c.off"), cube);
  write_mesh(dir.path("c.obj"), cube);
  write_mesh(dir.path("c.ply"), cube);
  for (const char* name : {"c.off", "c.obj", "c.ply"}) {
    const SurfaceMesh m = read_mesh(dir.path(name));
    EXPECT_EQ(m.vertices, cube.vertices) << name;
    EXPECT_EQ(m.faces, cube.faces) << name;
  }
  // Binary STL: a soup, welded back into 8 vertices.
  std::string stl(80, ' ');
  const std::uint32_t count = 12;
  stl += bytes_of(&count, 4);
  for (const Triangle& f : cube.faces) {
    stl += std::string(12, '\0');
    for (std::uint32_t v : f)
      for (int k = 0; k < 3; ++k) {
        const float c = static_cast<float>(cube.vertices[v][k]);
        stl += bytes_of(&c, 4);
      }
    stl += std::string(2, '\0');
  }
  write_bytes(dir.path("c.stl"), stl);
  const SurfaceMesh from_stl = read_mesh(dir.path("c.stl"));
  EXPECT_EQ(from_stl.vertices.size(), 8u);
  EXPECT_EQ(from_stl.faces.size(), 12u);
  write_bytes(dir.path("a.stl"), "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
  EXPECT_EQ(read_mesh(dir.path("a.stl")).faces.size(), 1u);
}

TEST(Io, ObjNegativeIndicesAndBadReferences) {
  TempDir dir;
  write_bytes(dir.path("n.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf -3//1 -2//1 -1//1\n");
  const SurfaceMesh m = read_mesh(dir.path("n.obj"));
  ASSERT_EQ(m.faces.size(), 1u);
  EXPECT_EQ(m.faces[0], (Triangle{0, 1, 2}));
  write_bytes(dir.path("bad.obj"), "v 0 0 0\nf 1 2 3\n");
  EXPECT_NE(error_of([&] { read_mesh(dir.path("bad.obj")); }).find("bad.obj: line 2"), std::string::npos);
}

TEST(Io, OffFaceIndexOutOfRange) {
  TempDir dir;
  write_bytes(dir.path("bad.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  const std::string message = error_of([&] { read_mesh(dir.path("bad.off")); });
  EXPECT_NE(message.find("bad.off: line 6"), std::string::npos) << message;
  EXPECT_NE(message.find("out of range"), std::string::npos) << message;
}

namespace {

// A LAS file as LiDAR software writes it: 227/375-byte header, no VLR.
std::string las_file(int minor, int format, const std::vector<std::array<std::int32_t, 3>>& xyz, bool rgb) {
  const std::uint16_t header_size = minor >= 4 ? 375 : 227;
  const std::uint16_t record = format == 2 ? 26 : format == 6 ? 30 : 20;
  std::string h(header_size, '\0');
  std::memcpy(&h[0], "LASF", 4);
  h[24] = 1;
  h[25] = static_cast<char>(minor);
  std::memcpy(&h[94], &header_size, 2);
  const std::uint32_t offset = header_size;
  std::memcpy(&h[96], &offset, 4);
  h[104] = static_cast<char>(format);
  std::memcpy(&h[105], &record, 2);
  const std::uint32_t n = static_cast<std::uint32_t>(xyz.size());
  std::memcpy(&h[107], &n, 4);
  const double scale[3] = {0.01, 0.01, 0.001}, shift[3] = {1000, 2000, 0};
  std::memcpy(&h[131], scale, 24);
  std::memcpy(&h[155], shift, 24);
  if (minor >= 4) {
    const std::uint64_t n64 = n;
    std::memcpy(&h[247], &n64, 8);
  }
  for (const auto& p : xyz) {
    std::string r(record, '\0');
    std::memcpy(&r[0], p.data(), 12);
    if (rgb) {
      const std::uint16_t c[3] = {65535, 32768, 0};
      std::memcpy(&r[20], c, 6);
    }
    h += r;
  }
  return h;
}

}  // namespace

TEST(Io, LasAppliesScaleAndOffset) {
  TempDir dir;
  write_bytes(dir.path("a.las"), las_file(2, 2, {{100, 200, 300}, {-5, 0, 7}}, true));
  const PointSet ps = read_point_set(dir.path("a.las"));
  ASSERT_EQ(ps.size(), 2u);
  EXPECT_NEAR(ps.points[0][0], 1001.0, 1e-9);
  EXPECT_NEAR(ps.points[0][1], 2002.0, 1e-9);
  EXPECT_NEAR(ps.points[0][2], 0.3, 1e-12);
  EXPECT_NEAR(ps.points[1][0], 999.95, 1e-9);
  ASSERT_TRUE(ps.has_colors());
  EXPECT_EQ(ps.colors[0], (Rgb{255, 128, 0}));
  write_bytes(dir.path("b.las"), las_file(4, 6, {{1, 2, 3}}, false));
  EXPECT_EQ(read_point_set(dir.path("b.las")).size(), 1u);
  std::string cut = las_file(2, 0, {{1, 2, 3}, {4, 5, 6}}, false);
  cut.resize(cut.size() - 5);
  write_bytes(dir.path("cut.las"), cut);
  EXPECT_NE(error_of([&] { read_point_set(dir.path("cut.las")); }).find("truncated"), std::string::npos);
  // Compressed records (format bit 7) without LASzip's VLR: refused by name.
  std::string compressed = las_file(2, 0, {{1, 2, 3}}, false);
  compressed[104] = static_cast<char>(compressed[104] | 0x80);
  write_bytes(dir.path("c.laz"), compressed);
  const std::string message = error_of([&] { read_point_set(dir.path("c.laz")); });
  EXPECT_NE(message.find("c.laz"), std::string::npos) << message;
  EXPECT_NE(message.find("LASzip"), std::string::npos) << message;
}

TEST(Io, PolylinesRoundTrip) {
  TempDir dir;
  const std::vector<Polyline> lines = {{{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 0}}};
  write_polylines(dir.path("p.polylines.txt"), lines);
  EXPECT_EQ(read_polylines(dir.path("p.polylines.txt")), lines);
  write_bytes(dir.path("bad.txt"), "3 0 0 0 1 1 1\n");
  EXPECT_NE(error_of([&] { read_polylines(dir.path("bad.txt")); }).find("bad.txt: line 1"), std::string::npos);
}

TEST(Io, FailedWritesLeaveNothingBehind) {
  TempDir dir;
  EXPECT_THROW(write_point_set(dir.path("missing/out.ply"), small_cloud()), InvalidArgument);
  EXPECT_THROW(check_writable(dir.path("missing/out.ply")), InvalidArgument);
  EXPECT_THROW(write_point_set(dir.path("out.unknown"), small_cloud()), InvalidArgument);
  EXPECT_EQ(dir.file_count(), 0u);
  write_point_set(dir.path("out.ply"), small_cloud());
  EXPECT_EQ(dir.file_count(), 1u);  // no temporary left next to it
}

TEST(Io, MissingFileAndUnknownExtension) {
  EXPECT_NE(error_of([] { read_point_set("/nonexistent/cloud.ply"); }).find("/nonexistent/cloud.ply"), std::string::npos);
  TempDir dir;
  write_bytes(dir.path("x.abc"), "0 0 0\n");
  EXPECT_NE(error_of([&] { read_point_set(dir.path("x.abc")); }).find("unknown point-set format"), std::string::npos);
}
