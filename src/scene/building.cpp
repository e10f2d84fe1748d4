#include "scene/building.h"

#include <cmath>

namespace sharpmesh::scene {
namespace {

class Builder {
 public:
  explicit Builder(SceneGeometry& g) : g_(g) {}

  // Convex polygon, vertices counter-clockwise seen from outside.
  void polygon(const std::vector<Vec3>& v, Material m) {
    const auto base = static_cast<std::uint32_t>(g_.mesh.vertices.size());
    g_.mesh.vertices.insert(g_.mesh.vertices.end(), v.begin(), v.end());
    const Vec3 n = cross(v[1] - v[0], v[2] - v[0]);
    for (std::uint32_t i = 1; i + 1 < v.size(); ++i) {
      g_.mesh.faces.push_back({base, base + i, base + i + 1});
      g_.material.push_back(m);
      g_.normal.push_back((1.0 / norm(n)) * n);
    }
  }

  // Axis-aligned box; the bottom is left out when it rests on the ground.
  void box(Vec3 lo, Vec3 hi, Material m) {
    const double x0 = lo[0], y0 = lo[1], z0 = lo[2], x1 = hi[0], y1 = hi[1], z1 = hi[2];
    polygon({{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}, m);  // top
    polygon({{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}}, m);  // -y
    polygon({{x1, y1, z0}, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}}, m);  // +y
    polygon({{x0, y1, z0}, {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}}, m);  // -x
    polygon({{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}}, m);  // +x
    if (z0 > 0) polygon({{x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0}, {x0, y0, z0}}, m);
  }

 private:
  SceneGeometry& g_;
};

}  // namespace

SceneGeometry building_scene() {
  SceneGeometry g;
  Builder b(g);
  b.polygon({{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}}, Material::Ground);
  const std::size_t first_building_vertex = g.mesh.vertices.size();
  b.box({-3, -2, 0}, {3, 2, 3}, Material::Wall);  // body
  // Pitched roof with 0.3 m eaves, ridge along x at y = 0.
  const double ex = 3.3, ey = 2.3, eave = 3.0, ridge = 4.5;
  b.polygon({{-ex, -ey, eave}, {ex, -ey, eave}, {ex, 0, ridge}, {-ex, 0, ridge}}, Material::Roof);
  b.polygon({{ex, ey, eave}, {-ex, ey, eave}, {-ex, 0, ridge}, {ex, 0, ridge}}, Material::Roof);
  b.polygon({{ex, -ey, eave}, {ex, ey, eave}, {ex, 0, ridge}}, Material::Wall);     // gables
  b.polygon({{-ex, ey, eave}, {-ex, -ey, eave}, {-ex, 0, ridge}}, Material::Wall);
  b.polygon({{-ex, ey, eave}, {ex, ey, eave}, {ex, -ey, eave}, {-ex, -ey, eave}}, Material::Roof);  // eave underside
  // Three steps in front of the door (-y side), nested boxes.
  b.box({-1.0, -3.05, 0}, {1.0, -2, 0.2}, Material::Stone);
  b.box({-1.0, -2.70, 0}, {1.0, -2, 0.4}, Material::Stone);
  b.box({-1.0, -2.35, 0}, {1.0, -2, 0.6}, Material::Stone);
  // Canopy slab on two pillars.
  b.box({-1.6, -3.4, 2.2}, {1.6, -2, 2.4}, Material::Stone);
  b.box({-1.475, -3.325, 0}, {-1.225, -3.075, 2.2}, Material::Stone);
  b.box({1.225, -3.325, 0}, {1.475, -3.075, 2.2}, Material::Stone);
  g.building = bounding_box(std::vector<Vec3>(g.mesh.vertices.begin() + static_cast<std::ptrdiff_t>(first_building_vertex),
                                              g.mesh.vertices.end()));
  return g;
}

}  // namespace sharpmesh::scene
