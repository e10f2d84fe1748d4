// Beyond the thesis (issue 36): sign votes made consistent patch by patch
// before the MST grows from them.
//
// The occupancy and sheet-parity votes (exterior_votes.cpp) are right for
// more than 99% of the points they decide, but a wrong one, where no other
// vote is near (a slot's wall), seeds a tree of its own and turns a whole
// face inside out. The plain tangent MST is locally right: its mistakes
// are whole regions, flipped across knife edges and acute creases. So the
// MST's normals are grouped into patches (within 25 degrees, along edges
// within 30 degrees of both tangent planes, so that the two faces of a thin
// plate stay apart), and each patch takes the sign most of its votes give
// (two thirds of at least three); a patch without such a majority gets no
// vote at all, and the anchored MST decides it from its neighbours.
#include <boost/pending/disjoint_sets.hpp>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "pointset/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh {
namespace {

constexpr double kSamePatchCos = 0.9;    // neighbours within 25 degrees share a patch
constexpr double kMaxTangentSine = 0.5;  // ... along chords within 30 degrees of both tangent planes
constexpr int kMinVotes = 3;

}  // namespace

std::vector<signed char> patch_consensus_votes(const PointSet& cloud, const std::vector<signed char>& votes, int k) {
  if (cloud.normals.size() != cloud.size() || votes.size() != cloud.size())
    throw InvalidArgument("vote consensus: needs one normal and one vote per point");
  const std::size_t n = cloud.size();
  std::vector<signed char> agreed(n, 0);
  if (n < 4) return agreed;
  const std::vector<Vec3>& p = cloud.points;
  const std::vector<Vec3>& normal = cloud.normals;
  const detail::KnnIndex index(p);
  const int neighbours = std::min<int>(k + 1, static_cast<int>(n));
  tbb::parallel_for(std::uint32_t(0), static_cast<std::uint32_t>(n), [&](std::uint32_t i) {
    if (votes[i] == 0) return;
    std::vector<std::uint32_t> near;
    std::vector<double> squared;
    index.nearest(p[i], neighbours, near, squared);
    int same = 0, other = 0;
    for (std::uint32_t j : near) {
      if (j == i || votes[j] == 0) continue;
      const double alignment = dot(normal[i], normal[j]);
      if (std::abs(alignment) < kSamePatchCos) continue;
      const Vec3 chord = p[j] - p[i];
      const double length = norm(chord);
      if (!(length > 0)) continue;
      const double steepness = std::max(std::abs(dot(chord, normal[i])), std::abs(dot(chord, normal[j]))) / length;
      if (steepness >= kMaxTangentSine) continue;
      (votes[j] * (alignment > 0 ? 1 : -1) == votes[i] ? same : other) += 1;
    }
    if (same >= kMinVotes && 3 * same >= 2 * (same + other)) agreed[i] = votes[i];
  });
  return agreed;
}

}  // namespace sharpmesh
