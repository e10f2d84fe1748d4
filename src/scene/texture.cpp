#include "scene/texture.h"

#include <algorithm>
#include <cmath>

namespace sharpmesh::scene {
namespace {

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double smooth(double t) { return t * t * (3 - 2 * t); }

}  // namespace

double Texture::noise(const Vec3& p) const {
  const double fx = std::floor(p[0]), fy = std::floor(p[1]), fz = std::floor(p[2]);
  const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy), iz = static_cast<std::int64_t>(fz);
  const double tx = smooth(p[0] - fx), ty = smooth(p[1] - fy), tz = smooth(p[2] - fz);
  auto lattice = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const std::uint64_t h = mix(seed_ ^ mix(static_cast<std::uint64_t>(x) ^ mix(static_cast<std::uint64_t>(y) ^ mix(static_cast<std::uint64_t>(z)))));
    return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
  };
  double value = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
    const double w = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty) * (dz ? tz : 1 - tz);
    value += w * lattice(ix + dx, iy + dy, iz + dz);
  }
  return value;
}

double Texture::fbm(const Vec3& p, int octaves) const {
  double sum = 0, amplitude = 0.5, total = 0, frequency = 1;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * noise(frequency * p + Vec3{17.0 * i, 31.0 * i, 47.0 * i});
    total += amplitude;
    amplitude *= 0.5;
    frequency *= 2;
  }
  return sum / total;
}

Color Texture::shade(const Vec3& p, const Vec3& n, Material material) const {
  Color base;
  double detail;
  switch (material) {
    case Material::Ground:
      base = {120, 125, 95};
      detail = fbm(6.0 * p, 4);
      break;
    case Material::Wall:
      base = {215, 195, 160};
      detail = fbm(4.0 * p, 4);
      break;
    case Material::Roof: {
      base = {170, 80, 60};
      const double tiles = 0.5 + 0.5 * std::sin(p[2] * 2 * M_PI / 0.25);  // rows of tiles up the slope
      detail = 0.6 * fbm(8.0 * p, 3) + 0.4 * tiles;
      break;
    }
    case Material::Stone:
    default:
      base = {150, 150, 155};
      detail = fbm(7.0 * p, 4);
      break;
  }
  const Vec3 sun{-0.45, -0.75, 0.85};
  const double lambert = std::max(0.0, dot(n, (1.0 / norm(sun)) * sun));
  const double light = 0.35 + 0.65 * lambert;
  const double albedo = 0.45 + 0.9 * detail;  // strong texture for matching
  Color c;
  for (int i = 0; i < 3; ++i) c[i] = std::clamp(base[i] * albedo * light, 0.0, 255.0);
  return c;
}

}  // namespace sharpmesh::scene
