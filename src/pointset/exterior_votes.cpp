// Outside and inside from the cloud's occupancy (beyond the thesis, App. A.8;
// issue 36): the MST carries a normal's sign from point to point, and where
// a surface folds back on itself at an acute knife edge (a conical roof's
// rim, a blade) it carries it the wrong way round, since the two faces'
// normals there differ by less than 90 degrees once one is flipped. The
// sign is a global fact, though: the outside of a closed surface is the
// space connected to infinity. Cells of a grid that hold a point (dilated
// by one cell, so the sampling's gaps close) wall off the inside; a flood
// fill from the grid's border marks the outside. A point whose normal line
// reaches the outside on one side and an enclosed empty cell on the other
// has its sign decided; elsewhere (thin material, open clouds whose inside
// the fill reaches, noise bands) it stays undecided.
//
// Thin material has no enclosed empty cell, so the sheet parity decides it
// (sheet_parity_votes): along a normal line, the points near the line group
// into the sheets it crosses, counted until the line reaches the outside; the
// side that meets the outside after an even number of sheets is the outer
// one (the crossing-parity rule of inside/outside tests, e.g. Jacobson et al.
// 2013, "Robust inside-outside segmentation using generalized winding
// numbers", applied to the samples instead of facets).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"
#include "core/parallel.h"

namespace sharpmesh {
namespace {

enum Cell : std::uint8_t { kEmpty = 0, kOccupied = 1, kOutside = 2 };

class OccupancyGrid {
 public:
  OccupancyGrid(const std::vector<Vec3>& points, double cell) : cell_(cell) {
    BoundingBox box = bounding_box(points);
    // Two cells of margin: the border layer is empty and connected.
    for (int a = 0; a < 3; ++a) {
      origin_[a] = box.min[a] - 2.5 * cell;
      size_[a] = static_cast<std::int64_t>(std::ceil((box.max[a] - box.min[a]) / cell)) + 6;
    }
    cells_.assign(static_cast<std::size_t>(size_[0] * size_[1] * size_[2]), kEmpty);
    for (const Vec3& p : points) {
      const auto c = coordinates(p);
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
          for (std::int64_t dz = -1; dz <= 1; ++dz) cells_[index(c[0] + dx, c[1] + dy, c[2] + dz)] = kOccupied;
    }
    flood_outside();
  }

  /// The cell holding p, or kOutside beyond the grid.
  Cell at(const Vec3& p) const {
    const auto c = coordinates(p);
    for (int a = 0; a < 3; ++a)
      if (c[a] < 0 || c[a] >= size_[a]) return kOutside;
    return static_cast<Cell>(cells_[index(c[0], c[1], c[2])]);
  }

  /// Integer cell coordinates of p (may lie beyond the grid).
  std::array<std::int64_t, 3> coordinates(const Vec3& p) const {
    std::array<std::int64_t, 3> c{};
    for (int a = 0; a < 3; ++a) c[a] = static_cast<std::int64_t>(std::floor((p[a] - origin_[a]) / cell_));
    return c;
  }
  bool contains(const std::array<std::int64_t, 3>& c) const {
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < size_[0] && c[1] < size_[1] && c[2] < size_[2];
  }
  std::size_t index(const std::array<std::int64_t, 3>& c) const { return index(c[0], c[1], c[2]); }

  std::size_t enclosed_cells() const { return static_cast<std::size_t>(std::count(cells_.begin(), cells_.end(), kEmpty)); }

 private:
  std::size_t index(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return static_cast<std::size_t>((z * size_[1] + y) * size_[0] + x);
  }

  void flood_outside() {
    std::vector<std::size_t> stack{index(0, 0, 0)};
    cells_[stack.back()] = kOutside;
    const std::int64_t sx = 1, sy = size_[0], sz = size_[0] * size_[1];
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      const std::int64_t x = static_cast<std::int64_t>(i) % size_[0];
      const std::int64_t y = (static_cast<std::int64_t>(i) / size_[0]) % size_[1];
      const std::int64_t z = static_cast<std::int64_t>(i) / sz;
      const std::array<std::pair<bool, std::int64_t>, 6> steps{{{x > 0, -sx},
                                                                {x + 1 < size_[0], sx},
                                                                {y > 0, -sy},
                                                                {y + 1 < size_[1], sy},
                                                                {z > 0, -sz},
                                                                {z + 1 < size_[2], sz}}};
      for (const auto& [inside_grid, step] : steps) {
        if (!inside_grid) continue;
        const auto j = static_cast<std::size_t>(static_cast<std::int64_t>(i) + step);
        if (cells_[j] != kEmpty) continue;
        cells_[j] = kOutside;
        stack.push_back(j);
      }
    }
  }

  double cell_;
  std::array<double, 3> origin_{};
  std::array<std::int64_t, 3> size_{};
  std::vector<std::uint8_t> cells_;
};

/// A byte per cell: at most 64 cells per point (10 million at least), so
/// that memory follows the cloud, not its extent over the spacing.
double bounded_cell(const std::vector<Vec3>& points, double cell) {
  const BoundingBox box = bounding_box(points);
  double cells = 1;
  for (int a = 0; a < 3; ++a) cells *= (box.max[a] - box.min[a]) / cell + 6;
  const double limit = std::max(1e7, 64.0 * static_cast<double>(points.size()));
  return cells > limit ? cell * std::cbrt(cells / limit) : cell;
}

/// The first unoccupied cell along the ray p + t d, t in (0, reach], or
/// kOccupied when every one is.
Cell first_free(const OccupancyGrid& grid, const Vec3& p, const Vec3& d, double step, double reach) {
  for (double t = step; t <= reach; t += step) {
    const Cell c = grid.at(p + t * d);
    if (c != kOccupied) return c;
  }
  return kOccupied;
}

}  // namespace

std::vector<signed char> exterior_side_votes(const PointSet& cloud, double cell, double reach) {
  if (cloud.normals.size() != cloud.size()) throw InvalidArgument("exterior votes: needs one normal per point");
  if (!(cell > 0) || !std::isfinite(cell) || !(reach >= cell) || !std::isfinite(reach))
    throw InvalidArgument("exterior votes: the cell size must be positive and the reach at least one cell");
  std::vector<signed char> votes(cloud.size(), 0);
  if (cloud.empty()) return votes;
  const OccupancyGrid grid(cloud.points, bounded_cell(cloud.points, cell));
  if (grid.enclosed_cells() == 0) return votes;
  detail::parallel_for(cloud.size(), [&](std::size_t i) {
    const double length = norm(cloud.normals[i]);
    if (!(length > 0)) return;
    const Vec3 n = (1.0 / length) * cloud.normals[i];
    const Cell ahead = first_free(grid, cloud.points[i], n, 0.5 * cell, reach);
    const Cell behind = first_free(grid, cloud.points[i], -1.0 * n, 0.5 * cell, reach);
    if (ahead == kOutside && behind == kEmpty) votes[i] = 1;
    if (ahead == kEmpty && behind == kOutside) votes[i] = -1;
  });
  return votes;
}

namespace {

/// The points of each occupied grid cell (a hash map: the grid has up to 64
/// cells per point, most of them empty).
class CellPoints {
 public:
  CellPoints(const std::vector<Vec3>& points, const OccupancyGrid& grid) : points_(points) {
    std::vector<std::pair<std::size_t, std::uint32_t>> keyed(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) keyed[i] = {grid.index(grid.coordinates(points[i])), static_cast<std::uint32_t>(i)};
    std::sort(keyed.begin(), keyed.end());
    ids_.resize(keyed.size());
    for (std::size_t i = 0; i < keyed.size(); ++i) {
      ids_[i] = keyed[i].second;
      if (i == 0 || keyed[i].first != keyed[i - 1].first) ranges_[keyed[i].first] = {static_cast<std::uint32_t>(i), 0};
      ++ranges_[keyed[i].first].second;
    }
  }

  template <class F>
  void for_each_in(std::size_t cell, F&& f) const {
    const auto it = ranges_.find(cell);
    if (it == ranges_.end()) return;
    for (std::uint32_t k = it->second.first; k < it->second.first + it->second.second; ++k) f(ids_[k], points_[ids_[k]]);
  }

 private:
  const std::vector<Vec3>& points_;
  std::vector<std::uint32_t> ids_;
  std::unordered_map<std::size_t, std::pair<std::uint32_t, std::uint32_t>> ranges_;
};

struct SheetCount {
  int sheets = 0;       ///< sheets crossed beyond the point's own
  bool clear = false;   ///< reached the outside, every sheet crossed cleanly
};

/// Walks the ray p + t d (t > 0) in half-cell steps until it enters the
/// outside, gathering the points within `radius` of the line whose offset t
/// falls in each step (only occupied cells hold any: the occupancy is
/// dilated by a cell and the radius is below one), then groups the offsets
/// into sheets split by gaps wider than `gap`. The first group holds the
/// point itself. A group longer than `max_extent` is a sheet the line grazes
/// (or the point's own face turning at a crease): the count is not clear.
SheetCount count_sheets(const OccupancyGrid& grid, const CellPoints& cells, const Vec3& p, const Vec3& d, double cell,
                        double radius, double gap, double max_extent, std::vector<double>& offsets) {
  constexpr std::size_t kMaxGathered = 4096;
  offsets.assign(1, 0.0);
  const double step = 0.5 * cell;
  SheetCount count;
  for (double t = 0;; t += step) {
    const Vec3 x = p + t * d;
    const auto c = grid.coordinates(x);
    if (!grid.contains(c)) break;
    const Cell state = grid.at(x);
    if (state == kOutside) break;
    if (state != kOccupied) continue;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const std::array<std::int64_t, 3> n{c[0] + dx, c[1] + dy, c[2] + dz};
          if (!grid.contains(n)) continue;
          cells.for_each_in(grid.index(n), [&](std::uint32_t, const Vec3& q) {
            const Vec3 v = q - p;
            const double along = dot(v, d);
            if (along <= 0 || along < t - 0.5 * step || along >= t + 0.5 * step) return;
            const Vec3 off = v - along * d;
            if (dot(off, off) < radius * radius) offsets.push_back(along);
          });
        }
    if (offsets.size() > kMaxGathered) return count;
  }
  std::sort(offsets.begin(), offsets.end());
  double start = offsets.front();
  for (std::size_t k = 1; k <= offsets.size(); ++k) {
    if (k < offsets.size() && offsets[k] - offsets[k - 1] <= gap) continue;
    if (offsets[k - 1] - start > max_extent) return count;
    if (k < offsets.size()) {
      ++count.sheets;
      start = offsets[k];
    }
  }
  count.clear = true;
  return count;
}

}  // namespace

std::vector<signed char> sheet_parity_votes(const PointSet& cloud, double spacing, double noise) {
  if (cloud.normals.size() != cloud.size()) throw InvalidArgument("sheet parity votes: needs one normal per point");
  if (!(spacing > 0) || !std::isfinite(spacing) || !(noise >= 0) || !std::isfinite(noise))
    throw InvalidArgument("sheet parity votes: the spacing must be positive and the noise non-negative");
  std::vector<signed char> votes(cloud.size(), 0);
  if (cloud.empty()) return votes;
  // Cells of 1.5 spacings: a line of radius 0.95 cells misses a sheet of a
  // uniform sample about once in 70 crossings (Poisson process, 0.59 points
  // per squared spacing); one cell of dilation keeps every point within the
  // radius of the line in an occupied cell.
  const double cell = bounded_cell(cloud.points, 1.5 * spacing);
  const OccupancyGrid grid(cloud.points, cell);
  const CellPoints cells(cloud.points, grid);
  const double radius = 0.95 * cell;
  // Two sheets two spacings apart stay apart; noise blurs each sheet by its
  // deviation on both sides.
  const double gap = spacing + 3 * noise;
  // A sheet crossed at up to about 45 degrees spans twice the radius.
  const double max_extent = 2 * radius + 6 * noise;
  detail::parallel_chunks(cloud.size(), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<double> offsets;
    for (std::size_t i = begin; i != end; ++i) {
      const double length = norm(cloud.normals[i]);
      if (!(length > 0)) continue;
      const Vec3 n = (1.0 / length) * cloud.normals[i];
      const SheetCount ahead = count_sheets(grid, cells, cloud.points[i], n, cell, radius, gap, max_extent, offsets);
      if (!ahead.clear) continue;
      const SheetCount behind = count_sheets(grid, cells, cloud.points[i], -1.0 * n, cell, radius, gap, max_extent, offsets);
      // Both sides must tell the same story: one reaches the outside
      // after an even count, the other after an odd one.
      if (!behind.clear || (ahead.sheets + behind.sheets) % 2 == 0) continue;
      votes[i] = ahead.sheets % 2 == 0 ? 1 : -1;
    }
  });
  return votes;
}

}  // namespace sharpmesh
