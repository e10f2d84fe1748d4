// Procedural, view-independent surface colour of the synthetic scene:
// multi-octave value noise in world coordinates per material, with
// Lambertian shading under a fixed sun, so that image edges and photo-
// consistency behave like those of photographs of matte surfaces.
#pragma once

#include <array>
#include <cstdint>

#include "scene/building.h"

namespace sharpmesh::scene {

using Color = std::array<double, 3>;  ///< linear RGB in [0, 255]

class Texture {
 public:
  explicit Texture(std::uint64_t seed) : seed_(seed) {}
  /// Albedo times shading at a surface point with the given outward normal.
  Color shade(const Vec3& point, const Vec3& normal, Material material) const;
  /// Colour of rays that hit nothing.
  static Color sky() { return {150, 185, 225}; }

 private:
  double noise(const Vec3& p) const;  ///< value noise in [0, 1]
  double fbm(const Vec3& p, int octaves) const;
  std::uint64_t seed_;
};

}  // namespace sharpmesh::scene
