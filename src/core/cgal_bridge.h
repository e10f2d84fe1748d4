// Conversions between the library's plain types and CGAL's kernel types, and
// an adapter from our Progress callback to CGAL's std::function<bool(double)>.
// Include only from .cpp files that already use CGAL.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/property_map.h>

#include <vector>

#include "sharpmesh/errors.h"
#include "sharpmesh/progress.h"
#include "sharpmesh/types.h"

namespace sharpmesh::detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using Vector3 = Kernel::Vector_3;

inline Point3 to_cgal(const Vec3& p) { return {p[0], p[1], p[2]}; }
inline Vector3 to_cgal_vector(const Vec3& v) { return {v[0], v[1], v[2]}; }
inline Vec3 from_cgal(const Point3& p) { return {p.x(), p.y(), p.z()}; }
inline Vec3 from_cgal(const Vector3& v) { return {v.x(), v.y(), v.z()}; }

inline std::vector<Point3> to_cgal(const std::vector<Vec3>& points) {
  std::vector<Point3> out;
  out.reserve(points.size());
  for (const Vec3& p : points) out.push_back(to_cgal(p));
  return out;
}

/// A readable property map from a point index to its CGAL position, so that
/// CGAL algorithms can reorder indices while our arrays stay in place.
struct IndexedPointMap {
  using key_type = std::uint32_t;
  using value_type = Point3;
  using reference = const Point3&;
  using category = boost::readable_property_map_tag;
  const std::vector<Point3>* points = nullptr;
  friend reference get(const IndexedPointMap& map, key_type i) { return (*map.points)[i]; }
};

// Note: CGAL 5.5's point-set functions keep a dangling reference to their
// `callback` parameter when run in parallel (Callback_wrapper binds the
// temporary that choose_parameter returns), so no callback is passed to them;
// progress is reported around each call instead.

}  // namespace sharpmesh::detail
