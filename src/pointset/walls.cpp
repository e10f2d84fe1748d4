// Vertical walls under roof edges for clouds scanned from above (beyond the
// thesis; sharpmesh/pointset.h explains the rule). Horizontal neighbourhoods
// come from a grid of columns over x and y; the vertical is z, as in every
// airborne survey's projected coordinates.
#include <algorithm>
#include <cmath>
#include <mutex>
#include <unordered_map>

#include "core/knn.h"
#include "core/parallel.h"
#include "core/plane_fit.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh {
namespace {

/// Points bucketed by column (x, y cells of one size).
class ColumnGrid {
 public:
  ColumnGrid(const std::vector<Vec3>& points, double cell) : points_(points), cell_(cell) {
    for (std::uint32_t i = 0; i < points.size(); ++i) cells_[key(cell_of(points[i][0]), cell_of(points[i][1]))].push_back(i);
  }
  /// Calls f(index) for every point within `radius` of p horizontally (radius <= cell).
  template <class F>
  void within(const Vec3& p, double radius, F&& f) const {
    const std::int64_t cx = cell_of(p[0]), cy = cell_of(p[1]);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (std::uint32_t j : it->second) {
          const double hx = points_[j][0] - p[0], hy = points_[j][1] - p[1];
          if (hx * hx + hy * hy <= radius * radius) f(j);
        }
      }
  }

 private:
  std::int64_t cell_of(double v) const { return static_cast<std::int64_t>(std::floor(v / cell_)); }
  static std::uint64_t key(std::int64_t x, std::int64_t y) {
    return (static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL) ^ static_cast<std::uint64_t>(y);
  }
  const std::vector<Vec3>& points_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

/// Smallest over largest eigenvalue of the points' covariance: near 0 on a
/// face (and on a face's last row), a sizeable fraction in a tree crown,
/// whose returns come from a volume.
double flatness(const std::vector<Vec3>& points, const std::vector<std::uint32_t>& ids) {
  const Eigen::Vector3d eigenvalues = detail::scatter_eigenvalues(points, ids);
  return eigenvalues(2) > 0 ? eigenvalues(0) / eigenvalues(2) : 1.0;
}

}  // namespace

void WallOptions::check() const {
  if (!(min_drop > 0) || !std::isfinite(min_drop)) throw InvalidArgument("wall drop must be a positive number of average spacings");
  if (!(reach > 0) || reach > 100) throw InvalidArgument("wall reach must be in (0, 100] average spacings");
  if (!(max_flatness > 0) || max_flatness > 1) throw InvalidArgument("wall flatness must be in (0, 1]");
}

bool looks_airborne(const PointSet& points, double average_spacing) {
  if (points.size() < 100 || !(average_spacing > 0)) return false;
  const BoundingBox box = bounding_box(points.points);
  const double width = std::min(box.max[0] - box.min[0], box.max[1] - box.min[1]);
  if (!(box.max[2] - box.min[2] <= 0.3 * width)) return false;
  // Columns two spacings wide: their lowest and highest points.
  const double cell = 2 * average_spacing;
  std::unordered_map<std::uint64_t, std::pair<double, double>> columns;
  for (const Vec3& p : points.points) {
    const auto c = [&](double v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v / cell))); };
    const auto [it, added] = columns.try_emplace((c(p[0]) * 0x9E3779B97F4A7C15ULL) ^ c(p[1]), p[2], p[2]);
    if (!added) it->second = {std::min(it->second.first, p[2]), std::max(it->second.second, p[2])};
  }
  std::size_t deep = 0;
  for (const auto& column : columns) deep += column.second.second - column.second.first > cell;
  return deep * 100 < columns.size() * 65;
}

WallResult fill_vertical_walls(PointSet& points, double average_spacing, const WallOptions& options, const Progress& progress) {
  options.check();
  WallResult result;
  result.airborne = looks_airborne(points, average_spacing);
  if (options.mode == WallMode::Off || (options.mode == WallMode::Automatic && !result.airborne)) return result;
  result.filled = true;
  report_progress(progress, "walls", 0.0);
  const double s = average_spacing, reach = options.reach * s, drop = options.min_drop * s;
  const std::vector<Vec3> in = points.points;  // the index keeps reading them while points are added
  const ColumnGrid grid(in, reach);
  const detail::KnnIndex index(in);
  // Each upper point's column: its foot (x, y), bottom and top heights, and
  // the horizontal direction towards the lower side.
  struct Column {
    std::size_t upper = 0;  // the input point that starts it
    double x = 0, y = 0, bottom = 0, top = 0, nx = 0, ny = 0;
  };
  // Few points start a wall: each chunk keeps its own, sorted by point afterwards.
  std::vector<Column> columns;
  std::mutex columns_mutex;
  detail::parallel_chunks(in.size(), 1024, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    std::vector<Column> found;
    for (std::size_t i = begin; i < end; ++i) {
      const Vec3& p = in[i];
      // The lower side: the points at least `drop` below p within reach;
      // its direction is their mean offset, its nearest one sets the slope.
      double mx = 0, my = 0, bottom = p[2], nearest_lower = INFINITY;
      std::size_t lower = 0;
      grid.within(p, reach, [&](std::uint32_t j) {
        if (in[j][2] > p[2] - drop) return;
        const double rx = in[j][0] - p[0], ry = in[j][1] - p[1];
        mx += rx;
        my += ry;
        ++lower;
        bottom = std::min(bottom, in[j][2]);
        nearest_lower = std::min(nearest_lower, std::hypot(rx, ry));
      });
      const double length = std::hypot(mx, my);
      if (lower == 0 || !(length > 0) || p[2] - bottom < 1.5 * nearest_lower) continue;
      const double ux = mx / length, uy = my / length;
      // Only the upper face's last point towards the drop starts a wall:
      // none of its level lies farther that way.
      bool inner = false;
      grid.within(p, reach, [&](std::uint32_t j) {
        const double rx = in[j][0] - p[0], ry = in[j][1] - p[1], along = rx * ux + ry * uy;
        inner = inner || (along > 0.5 * s && std::abs(rx * uy - ry * ux) < 0.5 * s && in[j][2] > p[2] - 0.5 * drop);
      });
      if (inner) continue;
      index.nearest(p, 12, ids, d2);
      if (flatness(in, ids) > options.max_flatness) continue;
      // Half a spacing beyond the upper point: its face's last sample lies
      // on average half a spacing short of the edge.
      const double step = std::min(0.5 * nearest_lower, 0.5 * s);
      found.push_back({i, p[0] + ux * step, p[1] + uy * step, bottom, p[2], ux, uy});
    }
    const std::lock_guard<std::mutex> lock(columns_mutex);
    columns.insert(columns.end(), found.begin(), found.end());
  });
  std::sort(columns.begin(), columns.end(), [](const Column& a, const Column& b) { return a.upper < b.upper; });
  // New points one spacing apart up each column, kept where the cloud and
  // the points added so far leave a gap of 0.75 spacings (in input order,
  // so the result does not depend on the threads).
  std::unordered_map<std::uint64_t, char> taken;
  const double cell = 0.5 * s;
  auto cell_key = [&](const Vec3& v) {
    const auto c = [&](double x) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(x / cell))); };
    return (c(v[0]) * 0x9E3779B97F4A7C15ULL) ^ (c(v[1]) * 0xC2B2AE3D27D4EB4FULL) ^ c(v[2]);
  };
  std::vector<std::uint32_t> ids;
  std::vector<double> d2;
  const bool normals = points.has_normals(), colors = points.has_colors();
  result.upper_points = columns.size();
  for (const Column& c : columns) {
    for (double z = c.bottom + 0.5 * s; z < c.top - 0.5 * s; z += s) {
      const Vec3 v{c.x, c.y, z};
      const std::uint64_t k = cell_key(v);
      if (taken.count(k)) continue;
      index.nearest(v, 1, ids, d2);
      if (!d2.empty() && d2[0] < 0.5625 * s * s) continue;
      taken[k] = 1;
      points.points.push_back(v);
      if (normals) points.normals.push_back({c.nx, c.ny, 0});
      if (colors) {
        const Rgb colour = points.colors[c.upper];
        points.colors.push_back(colour);
      }
      ++result.added_points;
    }
  }
  report_progress(progress, "walls", 1.0);
  return result;
}

}  // namespace sharpmesh
