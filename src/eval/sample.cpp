// Uniform area sampling of a triangle mesh with the thesis's noise model (7.5).
#include <algorithm>
#include <cmath>
#include <random>

#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"

namespace sharpmesh {

void SampleOptions::check() const {
  if (count == 0) throw InvalidArgument("sample count must be positive");
  if (count > 2'000'000'000ull) throw InvalidArgument("sample count " + format_number(count) + " is too large");
  if (!(noise >= 0 && noise < 1)) throw InvalidArgument("noise must be in [0, 1) of the diagonal (got " + format_number(noise) + ")");
  if (!(density_ratio >= 1 && density_ratio <= 1000))
    throw InvalidArgument("density ratio must be in [1, 1000] (got " + format_number(density_ratio) + ")");
  if (!(missing_radius > 0 && missing_radius < 1))
    throw InvalidArgument("missing-patch radius must be in (0, 1) of the diagonal (got " + format_number(missing_radius) + ")");
  if (missing_patches > 10'000) throw InvalidArgument("at most 10,000 missing patches (got " + format_number(missing_patches) + ")");
}

double surface_area(const SurfaceMesh& mesh) {
  double area = 0;
  for (const Triangle& f : mesh.faces)
    area += 0.5 * norm(cross(mesh.vertices[f[1]] - mesh.vertices[f[0]], mesh.vertices[f[2]] - mesh.vertices[f[0]]));
  return area;
}

PointSet sample_mesh(const SurfaceMesh& mesh, const SampleOptions& options) {
  std::vector<std::uint32_t> faces;
  return sample_mesh(mesh, options, faces);
}

PointSet sample_mesh(const SurfaceMesh& mesh, const SampleOptions& options, std::vector<std::uint32_t>& faces) {
  options.check();
  faces.clear();
  faces.reserve(options.count);
  std::vector<double> cumulative(mesh.faces.size());
  double total = 0;
  for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
    const Triangle& f = mesh.faces[i];
    for (std::uint32_t v : f)
      if (v >= mesh.vertices.size()) throw InvalidInput("mesh face " + format_number(i) + " refers to a missing vertex");
    total += 0.5 * norm(cross(mesh.vertices[f[1]] - mesh.vertices[f[0]], mesh.vertices[f[2]] - mesh.vertices[f[0]]));
    cumulative[i] = total;
  }
  if (!(total > 0) || !std::isfinite(total)) throw InvalidInput("the mesh has zero (or non-finite) area: nothing to sample");
  const double amplitude = options.noise * bounding_box(mesh.vertices).diagonal();

  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> offset(-amplitude, amplitude);
  auto uniform_point = [&](std::mt19937_64& random, std::size_t& face) {
    const double r = unit(random) * total;
    face = std::min<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin(), cumulative.size() - 1);
    const Triangle& f = mesh.faces[face];
    // Uniform barycentric coordinates (Osada et al. 2002).
    const double r1 = std::sqrt(unit(random)), r2 = unit(random);
    return (1 - r1) * mesh.vertices[f[0]] + (r1 * (1 - r2)) * mesh.vertices[f[1]] + (r1 * r2) * mesh.vertices[f[2]];
  };
  // The density gradient's direction and the missing patches come from a
  // second generator, so that the default sampling stays the same sequence.
  std::mt19937_64 layout(options.seed ^ 0x5eed5a3b1e5ull);
  Vec3 direction{0, 0, 1};
  double low = 0, high = 1;
  if (options.density_ratio > 1) {
    std::normal_distribution<double> gauss;
    do direction = {gauss(layout), gauss(layout), gauss(layout)};
    while (!(norm(direction) > 1e-9));
    direction = (1.0 / norm(direction)) * direction;
    low = high = dot(direction, mesh.vertices[mesh.faces[0][0]]);
    for (const Triangle& f : mesh.faces)
      for (std::uint32_t v : f) low = std::min(low, dot(direction, mesh.vertices[v])), high = std::max(high, dot(direction, mesh.vertices[v]));
    if (!(high > low)) high = low + 1;
  }
  std::vector<Vec3> holes;
  const double hole_radius = options.missing_radius * bounding_box(mesh.vertices).diagonal();
  for (std::size_t i = 0; i < options.missing_patches; ++i) {
    std::size_t face = 0;
    holes.push_back(uniform_point(layout, face));
  }
  auto kept = [&](const Vec3& p) {
    for (const Vec3& h : holes)
      if (distance(p, h) < hole_radius) return false;
    if (options.density_ratio == 1) return true;
    const double t = (dot(direction, p) - low) / (high - low);
    return unit(rng) * options.density_ratio <= 1 + (options.density_ratio - 1) * t;
  };
  PointSet out;
  out.points.reserve(options.count);
  if (options.with_normals) out.normals.reserve(options.count);
  // Rejection sampling: the holes and the gradient cost draws, never the count.
  const std::size_t max_draws = 1000 * options.count + 1000;
  std::size_t draws = 0;
  for (std::size_t s = 0; s < options.count; ++s) {
    std::size_t face = 0;
    Vec3 p = uniform_point(rng, face);
    while (!kept(p)) {
      if (++draws > max_draws) throw InvalidArgument("the missing patches cover the whole mesh: nothing left to sample");
      p = uniform_point(rng, face);
    }
    const Triangle& f = mesh.faces[face];
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    if (amplitude > 0) p = p + Vec3{offset(rng), offset(rng), offset(rng)};
    out.points.push_back(p);
    faces.push_back(static_cast<std::uint32_t>(face));
    if (options.with_normals) {
      const Vec3 n = cross(b - a, c - a);
      out.normals.push_back((1.0 / norm(n)) * n);
    }
  }
  return out;
}

}  // namespace sharpmesh
