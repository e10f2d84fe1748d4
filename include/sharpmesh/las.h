// LiDAR files: ASPRS LAS 1.0-1.4 and its LASzip-compressed form LAZ, read
// chunk by chunk so memory holds one chunk of records at a time, with the
// attributes meshing needs to choose points (classification, returns).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh {

/// What the header of a LAS or LAZ file says.
struct LasInfo {
  int version_major = 1, version_minor = 2;
  int point_format = 0;               ///< point data record format (0-10)
  std::uint16_t record_length = 0;    ///< bytes per point record
  std::uint64_t point_count = 0;
  Vec3 scale{1, 1, 1}, offset{0, 0, 0};  ///< coordinate = integer * scale + offset
  BoundingBox bounds;                 ///< as the header states it
  bool compressed = false;            ///< LAZ
  std::string laszip_version;         ///< "2.4r1" (LAZ only)
  std::uint32_t chunk_size = 0;       ///< points per LAZ chunk (0xFFFFFFFF: variable)
  std::size_t chunks = 0;             ///< chunks the reader walks through
};

/// A run of consecutive points of a LAS/LAZ file with their LiDAR attributes.
struct LasPoints {
  std::vector<Vec3> positions;            ///< scale and offset applied
  std::vector<std::uint16_t> intensity;
  std::vector<std::uint8_t> return_number, number_of_returns;
  std::vector<std::uint8_t> classification;  ///< ASPRS classes (2 ground, 6 building, ...)
  std::vector<double> gps_time;           ///< empty when the format has none
  std::vector<Rgb> colors;                ///< empty when the format has none (8 high bits of each channel)
  std::size_t size() const { return positions.size(); }
};

/// Reads a LAS or LAZ file chunk by chunk (LAZ: its own chunks, LASzip 1.x-3.x
/// "pointwise chunked" compression of point formats 0-3; LAS: runs of
/// 50,000 records). Any chunk can be read on its own, so a tiled reader can
/// take a region's chunks only. Throws InvalidInput naming the file and the
/// problem for a broken, truncated or unsupported file.
class LasReader {
 public:
  explicit LasReader(const std::string& path);
  ~LasReader();
  LasReader(const LasReader&) = delete;
  LasReader& operator=(const LasReader&) = delete;

  const LasInfo& info() const;
  std::size_t chunk_count() const;
  std::uint64_t chunk_first_point(std::size_t chunk) const;
  LasPoints read_chunk(std::size_t chunk);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// True when the path names a LAS or LAZ file (by its extension, any case).
bool is_las_path(const std::string& path);

/// All the points of a LAS/LAZ file whose class is in `classes` (empty: all),
/// with their colours when the format has them.
PointSet read_las_points(const std::string& path, const std::vector<int>& classes = {});

}  // namespace sharpmesh
