// The LAZ reader against laz-perf (LASzip's own decoder compiled to
// WebAssembly), point by point and field by field, on the real LiDAR tiles
// of ../shared/data/lidar. tests/laz_oracle/run.sh decodes each tile with the
// oracle and runs this test with SHARPMESH_LAZ_ORACLE naming the tile and
// its oracle records; without it the test is skipped.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "sharpmesh/las.h"

using namespace sharpmesh;

namespace {

template <class T>
T get(const char* record, std::size_t offset) {
  T value;
  std::memcpy(&value, record + offset, sizeof value);
  return value;
}

}  // namespace

TEST(LazOracle, EveryFieldOfEveryPointIsLazPerfs) {
  const char* spec = std::getenv("SHARPMESH_LAZ_ORACLE");  // "TILE.laz:ORACLE.records"
  if (spec == nullptr) GTEST_SKIP() << "SHARPMESH_LAZ_ORACLE is not set (tests/laz_oracle/run.sh sets it)";
  const std::string pair(spec);
  const std::size_t colon = pair.rfind(':');
  ASSERT_NE(colon, std::string::npos) << pair;
  const std::string tile = pair.substr(0, colon), oracle_path = pair.substr(colon + 1);
  std::ifstream in(oracle_path, std::ios::binary);
  const std::string oracle((std::istreambuf_iterator<char>(in)), {});

  LasReader reader(tile);
  const LasInfo& info = reader.info();
  ASSERT_TRUE(info.compressed);
  ASSERT_LE(info.point_format, 3);
  ASSERT_EQ(oracle.size(), info.point_count * info.record_length) << "the oracle decoded another number of points";
  const bool has_time = info.point_format == 1 || info.point_format == 3;
  std::size_t index = 0, mismatches = 0;
  for (std::size_t chunk = 0; chunk < reader.chunk_count(); ++chunk) {
    ASSERT_EQ(reader.chunk_first_point(chunk), index);
    const LasPoints points = reader.read_chunk(chunk);
    for (std::size_t i = 0; i < points.size(); ++i, ++index) {
      const char* r = oracle.data() + index * info.record_length;
      bool same = true;
      for (int k = 0; k < 3; ++k) same &= points.positions[i][k] == get<std::int32_t>(r, 4 * k) * info.scale[k] + info.offset[k];
      same &= points.intensity[i] == get<std::uint16_t>(r, 12);
      same &= points.return_number[i] == (r[14] & 7) && points.number_of_returns[i] == ((r[14] >> 3) & 7);
      same &= points.classification[i] == (r[15] & 31);
      if (has_time) same &= points.gps_time[i] == get<double>(r, 20);
      if (!same && ++mismatches <= 5) ADD_FAILURE() << tile << ": point " << index << " (chunk " << chunk << ") differs from laz-perf's";
    }
  }
  EXPECT_EQ(index, info.point_count);
  EXPECT_EQ(mismatches, 0u);
}
