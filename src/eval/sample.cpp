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
  PointSet out;
  out.points.reserve(options.count);
  if (options.with_normals) out.normals.reserve(options.count);
  for (std::size_t s = 0; s < options.count; ++s) {
    const double r = unit(rng) * total;
    const std::size_t face = std::min<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin(),
                                                   cumulative.size() - 1);
    const Triangle& f = mesh.faces[face];
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    // Uniform barycentric coordinates (Osada et al. 2002).
    const double r1 = std::sqrt(unit(rng)), r2 = unit(rng);
    Vec3 p = (1 - r1) * a + (r1 * (1 - r2)) * b + (r1 * r2) * c;
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
