// Thin shells: an implicit function sampled too coarsely for a gap about one
// or two spacings wide (a slot, a small through-hole) bridges the gap's
// openings and leaves the air inside as a closed shell of its own, a cavity
// and a second component where the part has one. Such a shell is filled, as
// the bridge already fills the rest of the gap. A thin solid of its own is
// removed only below the thickness the pipeline resolves (two spacings,
// issue 36); a cavity that thin inside the material is the air of a
// bridged gap, since the data of a closed void is what a scan cannot see.

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "core/mesh_graph.h"
#include "core/ray_caster.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {

namespace {

/// Whether the closed component `faces` of `mesh` encloses a space thinner
/// than `max_solid` (a solid: positive signed volume) or `max_cavity` (a
/// cavity, facing inwards) from nine tenths of its area: the ray from a
/// facet's centroid into the enclosed side meets the component again within
/// it. Rays from the shell's rim run lengthwise, hence the fraction.
bool encloses_thin_space(const SurfaceMesh& mesh, const std::vector<std::uint32_t>& faces, double max_solid, double max_cavity) {
  // The shell with its own vertices only: a mesh may hold many small
  // components, and each is cast against alone.
  SurfaceMesh shell;
  std::unordered_map<std::uint32_t, std::uint32_t> local;
  for (std::uint32_t f : faces) {
    Triangle t = mesh.faces[f];
    for (std::uint32_t& v : t) {
      const auto [it, added] = local.try_emplace(v, static_cast<std::uint32_t>(shell.vertices.size()));
      if (added) shell.vertices.push_back(mesh.vertices[v]);
      v = it->second;
    }
    shell.faces.push_back(t);
  }
  // The enclosed side: against the normals when the signed volume is
  // positive (a solid), along them when negative (a cavity).
  double volume = 0;
  for (const Triangle& t : shell.faces)
    volume += dot(shell.vertices[t[0]], cross(shell.vertices[t[1]], shell.vertices[t[2]]));
  const double inward = volume >= 0 ? -1.0 : 1.0;
  const double max_thickness = volume >= 0 ? max_solid : max_cavity;
  const detail::RayCaster caster(shell);
  double area = 0, thick_area = 0;
  for (const Triangle& t : shell.faces) {
    const Vec3& a = shell.vertices[t[0]];
    const Vec3& b = shell.vertices[t[1]];
    const Vec3& c = shell.vertices[t[2]];
    const Vec3 n = cross(b - a, c - a);
    const double length = norm(n);
    if (!(length > 0)) continue;
    area += 0.5 * length;
    const Vec3 direction = (inward / length) * n;
    const Vec3 centroid = (1.0 / 3.0) * (a + b + c);
    // Leaves the facet itself behind: a millionth of the thickness tested.
    detail::RayHit hit;
    const bool met = caster.first_hit(centroid + (1e-6 * max_thickness) * direction, direction, hit);
    if (!met || hit.distance > max_thickness) thick_area += 0.5 * length;
  }
  return area > 0 && thick_area <= 0.1 * area;
}

}  // namespace

std::size_t remove_thin_shell_components(SurfaceMesh& mesh, double max_solid, double max_cavity) {
  if (!(max_solid >= 0 && max_cavity >= 0) || !std::isfinite(max_solid) || !std::isfinite(max_cavity))
    throw InvalidArgument("thin shell removal: the thicknesses must be non-negative");
  if (mesh.faces.empty() || (max_solid == 0 && max_cavity == 0)) return 0;
  detail::DisjointSets sets(mesh.vertices.size());
  for (const Triangle& t : mesh.faces)
    for (int k = 1; k < 3; ++k) sets.unite(t[0], t[k]);
  std::vector<std::uint32_t> component_of_root(mesh.vertices.size(), UINT32_MAX);
  std::vector<std::vector<std::uint32_t>> faces_of;  // by component
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const std::size_t root = sets.find(mesh.faces[f][0]);
    if (component_of_root[root] == UINT32_MAX) {
      component_of_root[root] = static_cast<std::uint32_t>(faces_of.size());
      faces_of.emplace_back();
    }
    faces_of[component_of_root[root]].push_back(f);
  }
  if (faces_of.size() < 2) return 0;
  const auto largest = static_cast<std::uint32_t>(
      std::max_element(faces_of.begin(), faces_of.end(), [](const auto& a, const auto& b) { return a.size() < b.size(); }) -
      faces_of.begin());
  // Only closed components enclose a space; an open one is a sheet of data.
  const auto edges = detail::edge_incidences(mesh);
  std::vector<char> open(faces_of.size(), 0);
  for (const auto& e : edges)
    if (e.faces.size() != 2) open[component_of_root[sets.find(mesh.faces[e.faces.front()][0])]] = 1;
  std::vector<char> removed(faces_of.size(), 0);
  for (std::uint32_t c = 0; c < faces_of.size(); ++c)
    removed[c] = c != largest && !open[c] && encloses_thin_space(mesh, faces_of[c], max_solid, max_cavity);
  std::vector<Triangle> faces;
  for (std::uint32_t c = 0; c < faces_of.size(); ++c)
    if (!removed[c])
      for (std::uint32_t f : faces_of[c]) faces.push_back(mesh.faces[f]);
  const std::size_t count = mesh.faces.size() - faces.size();
  if (count > 0) detail::set_faces_and_compact(mesh, std::move(faces));
  return count;
}

}  // namespace sharpmesh
