// Georeferenced clouds (UTM metres near 5e6, ECEF near 6e6) leave few bits of
// a double for the geometry: a 1e12 offset rounds coordinates to 1e-4 and
// stalls Delaunay refinement. The pipelines therefore work in coordinates
// centred on the bounding box and move their outputs back.
#pragma once

#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh::detail {

class Recentering {
 public:
  explicit Recentering(const std::vector<Vec3>& points) : offset_(bounding_box(points).center()) {}

  void to_local(std::vector<Vec3>& points) const {
    for (Vec3& p : points) p = p - offset_;
  }
  void to_world(std::vector<Vec3>& points) const {
    for (Vec3& p : points) p = p + offset_;
  }
  void to_world(Vec3& p) const { p = p + offset_; }
  void to_local(std::vector<Polyline>& polylines) const {
    for (Polyline& polyline : polylines) to_local(polyline);
  }
  void to_world(std::vector<Polyline>& polylines) const {
    for (Polyline& polyline : polylines) to_world(polyline);
  }

 private:
  Vec3 offset_;
};

}  // namespace sharpmesh::detail
