// Polylines closer to each other than the protecting balls can shrink to
// (beyond the thesis; CGAL issue #9102 asks for the same merge). Two
// curves w apart need balls thinner than w / 2, which no longer reach the
// implicit surface when w is below about two sampling spacings: the chamfers
// of couplingdown (1.4 spacings wide) and oblong got balls at 6% of their
// size, and half of their protected segments were not mesh edges. Of two
// such curves the shorter is left to the implicit surface. A polyline that
// comes back close to itself (a trace zigzagging between two edges a
// spacing apart: oblong 50k, 900 balls at the 5% floor) is left out too.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/knn.h"
#include "meshing/uncovered.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {

UncoveredGap detail::whole_polyline_gap(const Polyline& line) {
  UncoveredGap gap;
  Vec3 sum{0, 0, 0};
  for (std::size_t i = 0; i < line.size(); ++i) {
    sum = sum + line[i];
    if (i > 0) gap.length += distance(line[i - 1], line[i]);
  }
  gap.center = (1.0 / static_cast<double>(std::max<std::size_t>(line.size(), 1))) * sum;
  gap.gap = -1;
  return gap;
}

std::size_t drop_close_polylines(std::vector<Polyline>& polylines, double min_separation, std::vector<UncoveredGap>& dropped) {
  if (!(min_separation > 0) || polylines.size() < 2) return 0;
  // Samples every min_separation / 2, each labelled with its polyline.
  const double step = 0.5 * min_separation;
  std::vector<Vec3> samples;
  std::vector<std::uint32_t> owner;
  std::vector<double> arc;  // arc length of each sample along its polyline
  std::vector<double> length(polylines.size(), 0.0);
  for (std::size_t k = 0; k < polylines.size(); ++k) {
    const Polyline& line = polylines[k];
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const double d = distance(line[i], line[i + 1]);
      const int n = std::max(1, static_cast<int>(std::ceil(d / step)));
      for (int s = 0; s < n; ++s) {
        const double t = static_cast<double>(s) / n;
        samples.push_back(line[i] + t * (line[i + 1] - line[i]));
        owner.push_back(static_cast<std::uint32_t>(k));
        arc.push_back(length[k] + t * d);
      }
      length[k] += d;
    }
    if (!line.empty()) samples.push_back(line.back()), owner.push_back(static_cast<std::uint32_t>(k)), arc.push_back(length[k]);
  }
  if (samples.empty()) return 0;
  const detail::KnnIndex index(samples);
  std::vector<std::size_t> order(polylines.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return length[a] < length[b]; });
  std::vector<bool> keep(polylines.size(), true);
  std::vector<std::uint32_t> ids;
  for (std::size_t k : order) {
    const Polyline& line = polylines[k];
    if (line.size() < 2) continue;
    // Away from its ends (where polylines meet at junctions on purpose).
    std::size_t interior = 0, close = 0;
    for (std::size_t s = 0; s < samples.size(); ++s) {
      if (owner[s] != k) continue;
      if (distance(samples[s], line.front()) < 2 * min_separation || distance(samples[s], line.back()) < 2 * min_separation) continue;
      ++interior;
      index.within(samples[s], min_separation, ids);
      // Another kept polyline, or this one farther along than 4 separations
      // (a closed loop's ends excepted, where the arc wraps around).
      close += std::any_of(ids.begin(), ids.end(), [&](std::uint32_t j) {
        if (owner[j] != k) return static_cast<bool>(keep[owner[j]]);
        const double along = std::abs(arc[j] - arc[s]);
        return along > 4 * min_separation && length[k] - along > 4 * min_separation;
      });
    }
    if (interior == 0 || 2 * close <= interior) continue;
    keep[k] = false;
    UncoveredGap gap = detail::whole_polyline_gap(line);
    gap.too_close = true;
    dropped.push_back(gap);
  }
  std::vector<Polyline> kept;
  for (std::size_t k = 0; k < polylines.size(); ++k)
    if (keep[k]) kept.push_back(std::move(polylines[k]));
  const std::size_t removed = polylines.size() - kept.size();
  polylines = std::move(kept);
  return removed;
}

}  // namespace sharpmesh
