// The synthetic scene of `make-scene` (issue 5): a ground plane and a
// building with sharp details (steps, a canopy slab on pillars, a pitched
// roof with eaves), in metres with z up. Faces carry a material for texturing.
#pragma once

#include <cstdint>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh::scene {

enum class Material : std::uint8_t { Ground, Wall, Roof, Stone };

struct SceneGeometry {
  SurfaceMesh mesh;                  ///< outward-facing triangles (not a single closed solid)
  std::vector<Material> material;    ///< one per face
  std::vector<Vec3> normal;          ///< one unit normal per face
  BoundingBox building;              ///< bounds of everything but the ground
};

SceneGeometry building_scene();

}  // namespace sharpmesh::scene
