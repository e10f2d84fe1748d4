// LAS and LAZ files that are broken: a clear error naming the file, never a
// crash, a hang or an absurd allocation. The LAZ cases damage a real tile
// (../shared/data/lidar; skipped when absent).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "fixtures.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/las.h"

using namespace sharpmesh;
using test::TempDir;
using test::error_of;
using test::write_bytes;

namespace {

/// The smaller real tile, or "" when the shared data is not there.
std::string real_tile() {
  const std::string path = std::string(SHARPMESH_LIDAR_DIR) + "/ahn3_cropped_2.laz";
  return std::filesystem::exists(path) ? path : "";
}

template <class T>
void put(std::string& bytes, std::size_t offset, T value) {
  std::memcpy(bytes.data() + offset, &value, sizeof value);
}
template <class T>
T take(const std::string& bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

/// Reads every chunk; returns the error message, or "" when all decoded.
std::string read_everything(const std::string& path) {
  try {
    LasReader reader(path);
    for (std::size_t c = 0; c < reader.chunk_count(); ++c) reader.read_chunk(c);
    return "";
  } catch (const InvalidInput& e) {
    return e.what();
  }
}

}  // namespace

TEST(Laz, BrokenTilesGiveAClearErrorNamingTheFile) {
  const std::string tile = real_tile();
  if (tile.empty()) GTEST_SKIP() << "no shared LiDAR data";
  const std::string good = test::read_bytes(tile);
  TempDir dir;
  const auto expect_error = [&](const std::string& name, const std::string& bytes, const std::string& words) {
    const std::string path = dir.path(name);
    write_bytes(path, bytes);
    const std::string message = read_everything(path);
    EXPECT_NE(message.find(path), std::string::npos) << name << ": " << message;
    EXPECT_NE(message.find(words), std::string::npos) << name << ": " << message;
  };
  const auto point_offset = take<std::uint32_t>(good, 96);
  const auto table = static_cast<std::size_t>(take<std::int64_t>(good, point_offset));
  expect_error("half.laz", good.substr(0, good.size() / 2), "chunk table");
  expect_error("header-only.laz", good.substr(0, 300), "");
  std::string absurd = good;
  put<std::uint32_t>(absurd, 107, 4'000'000'000u);
  expect_error("absurd-count.laz", absurd, "chunk table holds");
  std::string many_chunks = good;
  put<std::uint32_t>(many_chunks, table + 4, 0x7FFFFFFFu);
  expect_error("many-chunks.laz", many_chunks, "chunk");
  std::string table_outside = good;
  put<std::int64_t>(table_outside, point_offset, static_cast<std::int64_t>(good.size()) + 100);
  expect_error("table-outside.laz", table_outside, "chunk table");
  std::string item_version = good;
  const std::size_t vlr_items = 227 + 54 + 34;  // the LASzip VLR follows the header; its item list at byte 34
  put<std::uint16_t>(item_version, vlr_items + 4, 1);
  expect_error("item-v1.laz", item_version, "version 1");
}

// Damaged chunk tables and chunk bytes decode to an error or to points, but
// never crash or hang (the sanitizer build checks the memory accesses).
TEST(Laz, DamagedBytesNeverCrash) {
  const std::string tile = real_tile();
  if (tile.empty()) GTEST_SKIP() << "no shared LiDAR data";
  const std::string good = test::read_bytes(tile);
  TempDir dir;
  const auto point_offset = take<std::uint32_t>(good, 96);
  const auto table = static_cast<std::size_t>(take<std::int64_t>(good, point_offset));
  for (const std::size_t at : {table + 8, table + 12, std::size_t{point_offset} + 8 + 28, std::size_t{point_offset} + 5000, good.size() / 2}) {
    std::string bytes = good;
    for (std::size_t k = at; k < std::min(bytes.size(), at + 16); ++k) bytes[k] = static_cast<char>(bytes[k] ^ 0x5A);
    write_bytes(dir.path("damaged.laz"), bytes);
    read_everything(dir.path("damaged.laz"));  // an InvalidInput or points; anything else fails the test
  }
}

TEST(Las, UncompressedFilesReadInChunksWithTheirAttributes) {
  // Point format 1: coordinates, intensity, returns, class, GPS time.
  std::string bytes(227 + 3 * 28, '\0');
  std::memcpy(bytes.data(), "LASF", 4);
  bytes[24] = 1;
  bytes[25] = 2;
  put<std::uint16_t>(bytes, 94, 227);
  put<std::uint32_t>(bytes, 96, 227);
  bytes[104] = 1;
  put<std::uint16_t>(bytes, 105, 28);
  put<std::uint32_t>(bytes, 107, 3);
  for (int k = 0; k < 3; ++k) put<double>(bytes, 131 + 8 * k, 0.01);
  for (int i = 0; i < 3; ++i) {
    const std::size_t r = 227 + 28 * i;
    put<std::int32_t>(bytes, r, 100 * i);
    put<std::uint16_t>(bytes, r + 12, static_cast<std::uint16_t>(7 + i));
    bytes[r + 14] = static_cast<char>(1 | (2 << 3));  // return 1 of 2
    bytes[r + 15] = static_cast<char>(i == 1 ? 6 : 2);
    put<double>(bytes, r + 20, 1000.5 + i);
  }
  TempDir dir;
  write_bytes(dir.path("three.las"), bytes);
  LasReader reader(dir.path("three.las"));
  EXPECT_FALSE(reader.info().compressed);
  ASSERT_EQ(reader.chunk_count(), 1u);
  const LasPoints points = reader.read_chunk(0);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_DOUBLE_EQ(points.positions[2][0], 2.0);
  EXPECT_EQ(points.intensity[1], 8);
  EXPECT_EQ(points.return_number[0], 1);
  EXPECT_EQ(points.number_of_returns[0], 2);
  EXPECT_EQ(points.classification[1], 6);
  EXPECT_DOUBLE_EQ(points.gps_time[2], 1002.5);
  EXPECT_TRUE(is_las_path("tiles/B.LaZ") && is_las_path("three.las"));
  EXPECT_FALSE(is_las_path("three.las.ply") || is_las_path("las"));
  EXPECT_EQ(read_las_points(dir.path("three.las"), {6}).size(), 1u);
  EXPECT_EQ(read_las_points(dir.path("three.las"), {2, 6}).size(), 3u);
  put<std::uint32_t>(bytes, 107, 4);  // one record more than the file holds
  write_bytes(dir.path("short.las"), bytes);
  const std::string message = error_of([&] { LasReader short_file(dir.path("short.las")); });
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
}
