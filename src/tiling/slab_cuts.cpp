// Where the slabs of a tiled reconstruction are cut (tiling/tiling.h).
#include <algorithm>

#include "tiling/tiling.h"

namespace sharpmesh::detail {

std::vector<double> slab_cuts(const std::vector<Vec3>& points, int axis, int slabs, double d_prime) {
  std::vector<double> along(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) along[i] = points[i][axis];
  std::sort(along.begin(), along.end());
  std::vector<double> cuts;
  const double low = along.front(), high = along.back();
  const double slab = (high - low) / slabs;
  auto count_near = [&](double x) {
    return std::upper_bound(along.begin(), along.end(), x + d_prime) - std::lower_bound(along.begin(), along.end(), x - d_prime);
  };
  for (int k = 1; k < slabs; ++k) {
    const double quantile = along[static_cast<std::size_t>(static_cast<double>(k) / slabs * static_cast<double>(along.size() - 1))];
    // Candidates a quarter of d' apart within a quarter of a slab: the one
    // with the fewest points near it (the first of equals).
    double best = quantile;
    auto best_count = count_near(quantile);
    const double reach = 0.25 * slab;
    const double step = std::max(0.25 * d_prime, reach / 200);
    for (double x = quantile - reach; x <= quantile + reach; x += step) {
      if (x <= low + d_prime || x >= high - d_prime) continue;
      const auto c = count_near(x);
      if (c < best_count) best = x, best_count = c;
    }
    if (cuts.empty() || best > cuts.back() + 2 * d_prime) cuts.push_back(best);
  }
  return cuts;
}


}  // namespace sharpmesh::detail
