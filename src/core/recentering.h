// Georeferenced clouds (UTM metres near 5e6, ECEF near 6e6) leave few bits of
// a double for the geometry: a 1e12 offset rounds coordinates to 1e-4 and
// stalls Delaunay refinement. The pipelines therefore work in coordinates
// centred on the bounding box and move their outputs back.
//
// Extreme sizes break things too: CGAL's Poisson finds no surface below a
// diagonal of about 1e-17, and covariances (length^5) overflow above 1e60.
// Clouds whose diagonal is outside [2^-20, 2^20] are therefore also scaled by
// a power of two (exact in floating point) to a diagonal in [1, 2); clouds in
// that range, which is every real scan, are only translated.
#pragma once

#include <cmath>
#include <vector>

#include "sharpmesh/features.h"
#include "sharpmesh/types.h"

namespace sharpmesh::detail {

class Recentering {
 public:
  explicit Recentering(const std::vector<Vec3>& points) {
    const BoundingBox box = bounding_box(points);
    offset_ = box.center();
    const double diagonal = box.diagonal();
    if (std::isfinite(diagonal) && diagonal > 0 && (diagonal < 0x1p-20 || diagonal > 0x1p20))
      scale_ = std::ldexp(1.0, -std::ilogb(diagonal));
  }

  /// A length measured in local coordinates, in world units.
  double length_to_world(double length) const { return length / scale_; }
  double length_to_local(double length) const { return length * scale_; }

  void to_local(Vec3& p) const { p = scale_ * (p - offset_); }
  void to_world(Vec3& p) const { p = (1.0 / scale_) * p + offset_; }
  void to_local(std::vector<Vec3>& points) const {
    for (Vec3& p : points) to_local(p);
  }
  void to_world(std::vector<Vec3>& points) const {
    for (Vec3& p : points) to_world(p);
  }
  void to_local(std::vector<Polyline>& polylines) const {
    for (Polyline& polyline : polylines) to_local(polyline);
  }
  void to_world(std::vector<Polyline>& polylines) const {
    for (Polyline& polyline : polylines) to_world(polyline);
  }
  /// The feature graph and the radii and spacings measured in local lengths.
  void to_world(FeatureResult& features) const {
    to_world(features.graph.polylines);
    for (Junction& j : features.graph.junctions) to_world(j.position);
    for (double* length : {&features.offset_radius, &features.convolution_radius, &features.noise_estimate, &features.average_spacing})
      *length = length_to_world(*length);
  }

 private:
  Vec3 offset_{0, 0, 0};
  double scale_ = 1.0;
};

}  // namespace sharpmesh::detail
