// Beyond the thesis (issue 36): sign votes kept only where the same sheet
// confirms them, before the MST grows from them.
//
// The occupancy and sheet-parity votes (exterior_votes.cpp) are right for
// nearly all the points they decide, but a wrong one where no other vote is
// near (a slot's wall) seeds a tree of its own and turns a whole face
// inside out. A vote stays when, among its k nearest neighbours on the same
// sheet (normal lines within 25 degrees, along chords within 30 degrees of
// both tangent planes, so the far face of a thin plate does not count), at
// least three have votes and two thirds of those give the same sign once
// carried across by the sign of the normals' dot product. A wider consensus
// (every smooth patch of the plain MST taking its majority) decided nothing
// on thin plates whose two faces one patch joined, and gave a whole face of
// a ribbed part the wrong sign.

#include <cmath>
#include <cstdint>
#include <algorithm>
#include <vector>

#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"
#include "core/parallel.h"

namespace sharpmesh {
namespace {

constexpr double kSameSheetCos = 0.9;     // normal lines within 25 degrees
constexpr double kMaxTangentSine = 0.5;  // ... along chords within 30 degrees of both tangent planes
constexpr int kMinVotes = 3;

}  // namespace

std::vector<signed char> neighbour_confirmed_votes(const PointSet& cloud, const std::vector<signed char>& votes, int k) {
  if (cloud.normals.size() != cloud.size() || votes.size() != cloud.size())
    throw InvalidArgument("vote consensus: needs one normal and one vote per point");
  const std::size_t n = cloud.size();
  std::vector<signed char> agreed(n, 0);
  if (n < 4) return agreed;
  const std::vector<Vec3>& p = cloud.points;
  const std::vector<Vec3>& normal = cloud.normals;
  const detail::KnnIndex index(p);
  const int neighbours = std::min<int>(k + 1, static_cast<int>(n));
  detail::parallel_for(n, [&](std::uint32_t i) {
    if (votes[i] == 0) return;
    std::vector<std::uint32_t> near;
    std::vector<double> squared;
    index.nearest(p[i], neighbours, near, squared);
    int same = 0, other = 0;
    for (std::uint32_t j : near) {
      if (j == i || votes[j] == 0) continue;
      const double alignment = dot(normal[i], normal[j]);
      if (std::abs(alignment) < kSameSheetCos) continue;
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
