// Plain geometric types of the public API. No CGAL here: every algorithm
// converts at its boundary (DESIGN.md, "The product").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sharpmesh {

using Vec3 = std::array<double, 3>;
using Rgb = std::array<std::uint8_t, 3>;
using Triangle = std::array<std::uint32_t, 3>;

/// An unorganised point set, optionally with one normal and one colour per point.
struct PointSet {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;  ///< empty, or one per point
  std::vector<Rgb> colors;    ///< empty, or one per point

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool has_normals() const { return !normals.empty(); }
  bool has_colors() const { return !colors.empty(); }
  /// Keeps the points whose flag is true, with their attributes, in order.
  void keep_if(const std::vector<bool>& keep);
};

/// An indexed triangle mesh (polygons are triangulated by the readers).
struct SurfaceMesh {
  std::vector<Vec3> vertices;
  std::vector<Triangle> faces;
};

/// An open or closed chain of points (closed when front() == back()).
using Polyline = std::vector<Vec3>;

struct BoundingBox {
  Vec3 min{0, 0, 0};
  Vec3 max{0, 0, 0};
  double diagonal() const;
  Vec3 center() const;
};

BoundingBox bounding_box(const std::vector<Vec3>& points);
/// The box from the `fraction` to the 1 - `fraction` quantile of each
/// coordinate: the extent of the bulk of the points, which a few far
/// outliers cannot stretch (the raw box of real tracks can be twice as large).
BoundingBox robust_bounding_box(const std::vector<Vec3>& points, double fraction);

// Small vector helpers used across the library and the tools.
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 operator*(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec3& a);
inline double squared_distance(const Vec3& a, const Vec3& b) { const Vec3 d = a - b; return dot(d, d); }
double distance(const Vec3& a, const Vec3& b);

}  // namespace sharpmesh
