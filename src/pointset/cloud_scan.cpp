// scan_point_cloud: count, box, attributes and average spacing of a cloud
// read as a stream (include/sharpmesh/cloud_scan.h).
#include "sharpmesh/cloud_scan.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/point_stream.h"

namespace sharpmesh {
namespace {

std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

void report(const Progress& progress, const char* stage, double fraction) {
  report_progress(progress, stage, std::clamp(fraction, 0.0, 1.0));
}

double fraction_of(std::uint64_t done, const std::optional<std::uint64_t>& total) {
  return total && *total > 0 ? static_cast<double>(done) / static_cast<double>(*total) : 0.0;
}

/// Mean spacing over the points of blocks of 3 x 3 x 3 cells drawn by a
/// hash of their place, measured at the points of each block's centre cell:
/// their k nearest neighbours lie within a cell, so inside the block.
double sampled_spacing(const std::string& path, const CloudScan& scan, double cell, double rate, int k, const Progress& progress,
                       std::uint64_t& measured) {
  const auto threshold = static_cast<std::uint64_t>(std::min(1.0, rate) * 18446744073709551615.0);
  std::vector<Vec3> kept;
  std::vector<std::uint32_t> centre;
  PointStream stream(path);
  PointSet block;
  std::uint64_t read = 0;
  while (stream.next(block)) {
    for (const Vec3& p : block.points) {
      std::int64_t c[3], b[3];
      for (int a = 0; a < 3; ++a) {
        c[a] = static_cast<std::int64_t>(std::floor((p[a] - scan.box.min[a]) / cell));
        b[a] = c[a] / 3;
      }
      const std::uint64_t key = mix(mix(mix(static_cast<std::uint64_t>(b[0])) ^ static_cast<std::uint64_t>(b[1])) ^ static_cast<std::uint64_t>(b[2]));
      if (key > threshold) continue;
      if (c[0] - 3 * b[0] == 1 && c[1] - 3 * b[1] == 1 && c[2] - 3 * b[2] == 1) centre.push_back(static_cast<std::uint32_t>(kept.size()));
      kept.push_back(p);
    }
    read += block.size();
    report(progress, "average spacing (sampled blocks)", static_cast<double>(read) / static_cast<double>(scan.points));
  }
  measured = centre.size();
  if (centre.empty() || kept.size() <= static_cast<std::size_t>(k)) return -1;
  const detail::KnnIndex index(kept);
  std::vector<Vec3> queries;
  queries.reserve(centre.size());
  for (std::uint32_t i : centre) queries.push_back(kept[i]);
  // The queries are points of the index: local_spacings skips a neighbour
  // equal to the query by its index only, so the query's own copy is
  // skipped here by distance.
  double total = 0;
  std::vector<std::uint32_t> ids;
  std::vector<double> d2;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    index.nearest(queries[q], k + 1, ids, d2);
    double sum = 0;
    int count = 0;
    bool skipped_self = false;
    for (std::size_t j = 0; j < ids.size() && count < k; ++j) {
      if (!skipped_self && ids[j] == centre[q]) {
        skipped_self = true;
        continue;
      }
      sum += std::sqrt(d2[j]);
      ++count;
    }
    total += count > 0 ? sum / count : 0.0;
  }
  return total / static_cast<double>(queries.size());
}

}  // namespace

CloudScan scan_point_cloud(const std::string& path, const CloudScanOptions& options, const Progress& progress) {
  if (options.k < 1) throw InvalidArgument("cloud scan: k must be at least 1 (got " + format_number(options.k) + ")");
  CloudScan scan;
  const auto start = std::chrono::steady_clock::now();
  PointStream stream(path);
  const std::optional<std::uint64_t> declared = stream.declared_count();
  PointSet block, whole;
  std::vector<std::uint8_t> classes;
  bool keep_whole = options.spacing;
  // A uniform sample of the points (reservoir sampling, fixed seed): its
  // spacing gives the sampled blocks their size.
  constexpr std::size_t kReservoir = 100'000;
  std::vector<Vec3> reservoir;
  std::mt19937_64 random(1);
  bool first = true;
  while (stream.next(block, &classes)) {
    if (first) {
      scan.normals = block.has_normals();
      scan.colors = block.has_colors();
      first = false;
    }
    for (const Vec3& p : block.points) {
      for (int a = 0; a < 3; ++a) {
        scan.box.min[a] = scan.points == 0 ? p[a] : std::min(scan.box.min[a], p[a]);
        scan.box.max[a] = scan.points == 0 ? p[a] : std::max(scan.box.max[a], p[a]);
      }
      if (reservoir.size() < kReservoir) {
        reservoir.push_back(p);
      } else {
        const std::uint64_t slot = std::uniform_int_distribution<std::uint64_t>(0, scan.points)(random);
        if (slot < kReservoir) reservoir[slot] = p;
      }
      ++scan.points;
    }
    for (std::uint8_t c : classes) ++scan.classes[c];
    if (keep_whole) {
      whole.points.insert(whole.points.end(), block.points.begin(), block.points.end());
      if (whole.size() > options.exact_spacing_limit) {
        keep_whole = false;
        whole = PointSet{};
      }
    }
    report(progress, "reading", fraction_of(scan.points, declared));
  }
  scan.read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!options.spacing || scan.points <= static_cast<std::uint64_t>(options.k)) return scan;
  if (keep_whole) {
    scan.average_spacing = detail::average_spacing(whole.points, detail::KnnIndex(whole.points), options.k);
    scan.spacing_points = scan.points;
    return scan;
  }
  // Spacing on a surface falls as n^-1/2: the sample's spacing scaled down
  // estimates the cloud's (an overestimate for curves, an underestimate by a
  // few times for volumes), and a cell of 12 of them leaves the centre cell's
  // points a margin of many spacings either way.
  const double sample_spacing = detail::average_spacing(reservoir, detail::KnnIndex(reservoir), options.k);
  const double estimate = sample_spacing * std::sqrt(static_cast<double>(reservoir.size()) / static_cast<double>(scan.points));
  const double cell = std::max(12 * estimate, 1e-9 * std::max(scan.box.diagonal(), 1e-300));
  const double rate = static_cast<double>(options.sampled_spacing_points) / static_cast<double>(scan.points);
  scan.spacing_exact = false;
  scan.passes = 2;
  scan.average_spacing = sampled_spacing(path, scan, cell, rate, options.k, progress, scan.spacing_points);
  return scan;
}

}  // namespace sharpmesh
