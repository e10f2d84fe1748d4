// Protection only where the part is thicker than the diameter of its
// protecting balls (beyond the thesis). On a bar, fin or flange thinner than
// that, the balls of its two rims overlap or reach the other sheet, so a
// protected curve no longer splits the surface into the two patches Mesh_3
// expects (7.3.2; CGAL issue #9102 is the same failure between close
// curves): the protection shrinks the balls until they miss the surface and
// the refinement runs away, leaving a frame of thin bars in pieces. Such
// polylines are left to the implicit surface, as the PIF baseline meshes
// them; with a smaller d' the same edges keep their balls. The surface stage
// asks for it only where the feature detection read most of the cloud as
// edges (surface_stage.cpp): elsewhere CGAL's shrinking balls cope with the
// rims of thin blades.
#include <algorithm>

#include "core/knn.h"
#include "meshing/uncovered.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {

std::size_t drop_protection_on_thin_parts(std::vector<Polyline>& polylines, const std::vector<Vec3>& thin_points,
                                          const std::vector<double>& thin_thickness, double ball_radius,
                                          std::vector<UncoveredGap>& dropped) {
  if (!(ball_radius > 0) || polylines.empty()) return 0;
  std::vector<Vec3> thinner;
  for (std::size_t i = 0; i < thin_points.size() && i < thin_thickness.size(); ++i)
    if (thin_thickness[i] < 2 * ball_radius) thinner.push_back(thin_points[i]);
  if (thinner.empty()) return 0;
  const detail::KnnIndex index(thinner);
  std::vector<std::uint32_t> nearest;
  std::vector<double> squared;
  std::size_t removed = 0;
  std::vector<Polyline> kept;
  for (Polyline& line : polylines) {
    std::vector<bool> thin(line.size());
    for (std::size_t i = 0; i < line.size(); ++i) {
      index.nearest(line[i], 1, nearest, squared);
      thin[i] = !squared.empty() && squared[0] < ball_radius * ball_radius;
    }
    // Most of its length over thin parts: a thin part's rim or a trace
    // across it. A curve that only passes by a thin part (where a bar meets
    // a block) keeps its protection whole: cut there, it would leave ends
    // that the implicit surface rounds.
    double length = 0, thin_length = 0;
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const double d = distance(line[i], line[i + 1]);
      length += d;
      thin_length += 0.5 * d * (static_cast<double>(thin[i]) + static_cast<double>(thin[i + 1]));
    }
    if (!(2 * thin_length > length)) {
      kept.push_back(std::move(line));
      continue;
    }
    UncoveredGap gap = detail::whole_polyline_gap(line);
    gap.on_thin_part = true;
    dropped.push_back(gap);
    ++removed;
  }
  polylines = std::move(kept);
  return removed;
}

}  // namespace sharpmesh
