// Beyond the thesis (App. A.8): regions of normals whose outer side the rest
// of the cloud encloses, found with the cloud's generalized winding number
// (winding_number.h) and flipped.
//
// The MST and the crease votes (patch_orientation.cpp) decide signs locally.
// A small bore whose wall is all crease points (radius under 3 spacings)
// can be inverted as a whole: along each rim the jet normals turn the short way and the MST
// follows. Nothing local tells it from a pin; the rest of the surface does.
// With consistent normals the winding number is about 0 just outside the
// cloud and 1 just inside; at the points of an inverted bore the values two
// spacings along and against the normal are swapped, near 1 and 0, because
// the bore's own flipped contribution pushes both out of place.
//
// Points whose outer side reads above 0.4 are grouped (kNN neighbours with
// normals on the same side); each group is flipped when flipping it brings
// the winding numbers at the offset points around it (both sides, the group
// and everything within twice the offset) closer to 0 outside and 1 inside:
// the summed error at least halves, and the distance of each value to the
// nearest of 0 and 1 (which needs no labels) drops too. The second test
// keeps two faces closer than the offset (a slit) as they are: there the
// outer offset point lies inside the facing wall, and a flip makes it worse.
//
// The halving rule is strict on purpose: a laxer ratio also flips right
// normals on surfaces of higher genus, where the winding number is not near
// 0 or 1 everywhere outside the sheets.
#include <algorithm>
#include <cmath>

#include <boost/pending/disjoint_sets.hpp>

#include "core/knn.h"
#include "pointset/winding_number.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"
#include "core/parallel.h"

namespace sharpmesh {
namespace {

constexpr double kOffsetSpacings = 2;     // offset points this far along and against each normal
constexpr double kSofteningSpacings = 0.5;
constexpr double kEnclosed = 0.4;         // a point's outer side reads above this: suspect
constexpr std::size_t kMinGroup = 10;     // smaller groups are not worth a verdict
constexpr int kAreaNeighbours = 6;        // a point's area: pi r^2 / 6, r the distance to its 6th neighbour
constexpr int kRounds = 3;
constexpr double kMaxPairs = 4e7;         // direct sums per group, beyond which the offset points are subsampled

/// Distance of a winding number to the nearest of 0 and 1.
double off_indicator(double w) { return w < 0 ? -w : w > 1 ? w - 1 : std::min(w, 1 - w); }

}  // namespace

std::size_t repair_enclosed_normals(PointSet& points, double spacing, int k) {
  check_point_set(points, 4, "winding orientation");
  if (!points.has_normals()) throw InvalidArgument("winding orientation: the points have no normals");
  if (!(spacing > 0) || !std::isfinite(spacing)) throw InvalidArgument("winding orientation: the spacing must be positive");
  if (k < 1) throw InvalidArgument("winding orientation: k must be at least 1");
  const std::size_t n = points.size();
  const std::vector<Vec3>& p = points.points;
  std::vector<Vec3>& normal = points.normals;
  const detail::KnnIndex index(p);
  const int count = std::max(k, kAreaNeighbours) + 1;
  std::vector<std::vector<std::uint32_t>> neighbours(n);
  std::vector<double> area(n);
  detail::parallel_for(n, [&](std::uint32_t i) {
    std::vector<double> squared;
    index.nearest(p[i], count, neighbours[i], squared);
    const std::size_t last = std::min<std::size_t>(kAreaNeighbours, squared.size() - 1);
    area[i] = M_PI * squared[last] / kAreaNeighbours;
    neighbours[i].resize(std::min<std::size_t>(neighbours[i].size(), static_cast<std::size_t>(k) + 1));
  });
  const double offset = kOffsetSpacings * spacing, softening = kSofteningSpacings * spacing;

  std::size_t flipped = 0;
  for (int round = 0; round < kRounds; ++round) {
    const detail::WindingNumber winding(p, normal, area, softening);
    std::vector<double> outer(n);
    detail::parallel_for(n,
                      [&](std::uint32_t i) { outer[i] = winding.at(p[i] + offset * normal[i]); });
    // Groups of suspects with normals on the same side.
    boost::disjoint_sets_with_storage<> sets(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      if (!(outer[i] > kEnclosed)) continue;
      for (std::uint32_t j : neighbours[i])
        if (j != i && outer[j] > kEnclosed && dot(normal[i], normal[j]) > 0) sets.union_set(i, j);
    }
    std::vector<std::vector<std::uint32_t>> groups;
    {
      std::vector<std::int64_t> group_of(n, -1);
      for (std::uint32_t i = 0; i < n; ++i) {
        if (!(outer[i] > kEnclosed)) continue;
        const std::size_t root = sets.find_set(i);
        if (group_of[root] < 0) group_of[root] = static_cast<std::int64_t>(groups.size()), groups.emplace_back();
        groups[static_cast<std::size_t>(group_of[root])].push_back(i);
      }
    }
    groups.erase(std::remove_if(groups.begin(), groups.end(), [](const auto& g) { return g.size() < kMinGroup; }), groups.end());
    if (groups.empty()) break;

    std::vector<char> flip(groups.size(), 0);
    detail::parallel_for(groups.size(), [&](std::size_t g) {
      const std::vector<std::uint32_t>& group = groups[g];  // in increasing order
      std::vector<std::uint32_t> around, found;
      for (std::uint32_t i : group) {
        index.within(p[i], 2 * offset, found);
        around.insert(around.end(), found.begin(), found.end());
      }
      std::sort(around.begin(), around.end());
      around.erase(std::unique(around.begin(), around.end()), around.end());
      const std::size_t stride =
          std::max<std::size_t>(1, static_cast<std::size_t>(2.0 * around.size() * group.size() / kMaxPairs) + 1);
      double labelled_as_is = 0, labelled_flipped = 0, unlabelled_as_is = 0, unlabelled_flipped = 0;
      for (std::size_t r = 0; r < around.size(); r += stride) {
        const std::uint32_t j = around[r];
        const Vec3 out = p[j] + offset * normal[j], in = p[j] - offset * normal[j];
        const double w_out = outer[j], w_in = winding.at(in);
        const double own_out = detail::winding_number_of(p, normal, area, group, out, softening);
        const double own_in = detail::winding_number_of(p, normal, area, group, in, softening);
        const double flipped_out = w_out - 2 * own_out, flipped_in = w_in - 2 * own_in;
        labelled_as_is += std::abs(w_out) + std::abs(w_in - 1);
        // A flipped member's outer side is its former inner side.
        labelled_flipped += std::binary_search(group.begin(), group.end(), j) ? std::abs(flipped_out - 1) + std::abs(flipped_in)
                                      : std::abs(flipped_out) + std::abs(flipped_in - 1);
        unlabelled_as_is += off_indicator(w_out) + off_indicator(w_in);
        unlabelled_flipped += off_indicator(flipped_out) + off_indicator(flipped_in);
      }
      flip[g] = labelled_flipped < 0.5 * labelled_as_is && unlabelled_flipped < unlabelled_as_is;
    });
    std::size_t this_round = 0;
    for (std::size_t g = 0; g < groups.size(); ++g) {
      if (!flip[g]) continue;
      for (std::uint32_t i : groups[g]) normal[i] = -1.0 * normal[i];
      this_round += groups[g].size();
    }
    flipped += this_round;
    if (this_round == 0) break;
  }
  return flipped;
}

}  // namespace sharpmesh
