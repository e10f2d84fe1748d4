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
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"

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

  std::size_t enclosed_cells() const { return static_cast<std::size_t>(std::count(cells_.begin(), cells_.end(), kEmpty)); }

 private:
  std::array<std::int64_t, 3> coordinates(const Vec3& p) const {
    std::array<std::int64_t, 3> c{};
    for (int a = 0; a < 3; ++a) c[a] = static_cast<std::int64_t>(std::floor((p[a] - origin_[a]) / cell_));
    return c;
  }
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
  const BoundingBox box = bounding_box(cloud.points);
  double cells = 1;
  for (int a = 0; a < 3; ++a) cells *= (box.max[a] - box.min[a]) / cell + 6;
  // A byte per cell: at most 64 cells per point (10 million at least), so
  // that memory follows the cloud, not its extent over the spacing.
  const double limit = std::max(1e7, 64.0 * static_cast<double>(cloud.size()));
  if (cells > limit) cell *= std::cbrt(cells / limit);
  const OccupancyGrid grid(cloud.points, cell);
  if (grid.enclosed_cells() == 0) return votes;
  tbb::parallel_for(std::size_t(0), cloud.size(), [&](std::size_t i) {
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

}  // namespace sharpmesh
