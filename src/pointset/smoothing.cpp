// Jet smoothing (App. A.6; Cazals & Pouget 2003): each point is projected onto
// a quadric fitted over its k nearest neighbours.
#include <CGAL/jet_smooth_point_set.h>

#include "core/cgal_bridge.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh {

void JetSmoothingOptions::check(std::size_t n) const {
  if (k < 6) throw InvalidArgument("jet smoothing: k must be at least 6 to fit a quadric (got " + format_number(k) + ")");
  if (static_cast<std::size_t>(k) >= n)
    throw InvalidArgument("jet smoothing: k = " + format_number(k) + " needs more than k points, the set has " + format_number(n));
}

void jet_smooth(PointSet& points, const JetSmoothingOptions& options, const Progress& progress) {
  check_point_set(points, 7, "jet smoothing");
  options.check(points.size());
  std::vector<detail::Point3> cgal_points = detail::to_cgal(points.points);
  report_progress(progress, "jet smoothing", 0.0);
  CGAL::jet_smooth_point_set<CGAL::Parallel_if_available_tag>(cgal_points, static_cast<unsigned>(options.k));
  report_progress(progress, "jet smoothing", 1.0);
  for (std::size_t i = 0; i < cgal_points.size(); ++i) {
    const Vec3 p = detail::from_cgal(cgal_points[i]);
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) points.points[i] = p;  // degenerate fits keep the point
  }
}

}  // namespace sharpmesh
