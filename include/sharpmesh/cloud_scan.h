// What `sharpmesh info` says of a point cloud, read as a stream so that a
// cloud larger than memory can be described (issue 38).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "sharpmesh/progress.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

struct CloudScanOptions {
  int k = 6;                 ///< neighbours for the average spacing (thesis 7.3.2)
  bool spacing = true;       ///< false: count, box and attributes only
  /// Up to this many points the spacing is the exact mean over every point;
  /// above it, the mean over the points of sampled blocks of space (see
  /// CloudScan::spacing_exact).
  std::size_t exact_spacing_limit = 4'000'000;
  /// Points the sampled blocks hold at most (their kd-tree bounds the memory).
  std::size_t sampled_spacing_points = 2'000'000;
};

struct CloudScan {
  std::uint64_t points = 0;
  BoundingBox box;
  bool normals = false, colors = false;
  std::array<std::uint64_t, 256> classes{};  ///< LAS/LAZ: points per ASPRS class
  double average_spacing = -1;  ///< -1: not measured (asked not to, or k + 1 points or fewer)
  /// True: the mean over every point. False: over `spacing_points` points
  /// whose neighbourhoods lie whole inside blocks of space drawn evenly
  /// over the cloud, so each of them has the neighbours it has in the whole
  /// cloud and only which points are averaged is sampled.
  bool spacing_exact = true;
  std::uint64_t spacing_points = 0;
  int passes = 1;  ///< reads of the file
  double read_seconds = 0;  ///< wall time of the first read (reported only)
};

/// Reads `path` block by block (PointStream): memory holds one block, plus
/// the cloud itself up to `exact_spacing_limit` points, or the sampled blocks
/// above it.
CloudScan scan_point_cloud(const std::string& path, const CloudScanOptions& options = {}, const Progress& progress = {});

}  // namespace sharpmesh
