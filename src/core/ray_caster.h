// Ray casting against a triangle mesh (CGAL AABB tree behind a plain
// interface): first hits for rendering, occlusion tests for visibility.
// Queries are thread-safe once constructed.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh::detail {

struct RayHit {
  double distance = 0;       ///< along the (unit) direction
  std::uint32_t face = 0;    ///< index into the mesh's faces
};

class RayCaster {
 public:
  explicit RayCaster(const SurfaceMesh& mesh);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;
  /// First hit of the ray origin + s * direction (s > 0, direction of unit length); false if none.
  bool first_hit(const Vec3& origin, const Vec3& direction, RayHit& hit) const;
  /// True when the open segment from `from` to just before `to` (by `relative_gap`
  /// of its length) crosses the mesh: `to` is hidden from `from`.
  bool occluded(const Vec3& from, const Vec3& to, double relative_gap = 1e-5) const;
  /// Appends to `faces` the mesh faces that the closed segment from-to touches.
  void crossed_faces(const Vec3& from, const Vec3& to, std::vector<std::uint32_t>& faces) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sharpmesh::detail
