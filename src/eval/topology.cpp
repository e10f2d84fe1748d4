// Combinatorial checks (closed, manifold, consistently oriented, components)
// by hand on the indexed mesh; self-intersections by CGAL's PMP.
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <set>

#include "core/mesh_graph.h"
#include "core/cgal_bridge.h"
#include "sharpmesh/eval.h"

namespace sharpmesh {
namespace {

/// The mesh as a CGAL Surface_mesh whose face k is the k-th non-degenerate
/// triangle; `face_of[k]` is its index in mesh.faces.
CGAL::Surface_mesh<detail::Point3> to_surface_mesh(const SurfaceMesh& mesh, std::vector<std::uint32_t>& face_of) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::vector<detail::Point3> points = detail::to_cgal(mesh.vertices);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(mesh.faces.size());
  face_of.clear();
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle& t = mesh.faces[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    polygons.push_back({t[0], t[1], t[2]});
    face_of.push_back(f);
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) PMP::orient_polygon_soup(points, polygons);
  CGAL::Surface_mesh<detail::Point3> sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  return sm;
}

bool has_self_intersections(const SurfaceMesh& mesh) {
  std::vector<std::uint32_t> face_of;
  return CGAL::Polygon_mesh_processing::does_self_intersect<CGAL::Parallel_if_available_tag>(to_surface_mesh(mesh, face_of));
}

}  // namespace

TopologyReport check_topology(const SurfaceMesh& mesh, bool test_self_intersections) {
  TopologyReport report;
  report.vertices = mesh.vertices.size();
  report.faces = mesh.faces.size();
  for (const Triangle& f : mesh.faces) {
    for (std::uint32_t v : f)
      if (v >= mesh.vertices.size()) throw InvalidInput("mesh face refers to a missing vertex");
    const Vec3 n = cross(mesh.vertices[f[1]] - mesh.vertices[f[0]], mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2] || !(norm(n) > 0)) ++report.degenerate_faces;
  }
  const auto edges = detail::edge_incidences(mesh);
  // Corners (face, vertex) around a vertex are joined across its manifold
  // edges; more than one group of corners at a vertex = a non-manifold vertex.
  detail::DisjointSets corners(mesh.faces.size() * 3), vertices(mesh.vertices.size());
  auto corner = [&](std::uint32_t f, std::uint32_t v) {
    const Triangle& t = mesh.faces[f];
    return 3 * static_cast<std::size_t>(f) + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
  };
  for (const auto& e : edges) {
    vertices.unite(e.a, e.b);
    if (e.faces.size() == 1) ++report.boundary_edges;
    if (e.faces.size() > 2) ++report.non_manifold_edges;
    if (e.faces.size() == 2) {
      if (e.forward[0] == e.forward[1]) report.orientable = false;
      corners.unite(corner(e.faces[0], e.a), corner(e.faces[1], e.a));
      corners.unite(corner(e.faces[0], e.b), corner(e.faces[1], e.b));
    }
  }
  std::vector<std::size_t> group(mesh.vertices.size(), SIZE_MAX);
  std::vector<bool> counted(mesh.vertices.size(), false), used(mesh.vertices.size(), false);
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.faces[f][k];
      used[v] = true;
      const std::size_t g = corners.find(3 * static_cast<std::size_t>(f) + k);
      if (group[v] == SIZE_MAX) group[v] = g;
      else if (group[v] != g && !counted[v]) {
        counted[v] = true;
        ++report.non_manifold_vertices;
      }
    }
  std::set<std::size_t> roots;
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v)
    if (used[v]) roots.insert(vertices.find(v));
  report.components = roots.size();
  if (test_self_intersections && !mesh.faces.empty()) report.self_intersecting = has_self_intersections(mesh);
  return report;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> self_intersecting_faces(const SurfaceMesh& mesh) {
  std::vector<std::uint32_t> face_of;
  const CGAL::Surface_mesh<detail::Point3> sm = to_surface_mesh(mesh, face_of);
  using Face = CGAL::Surface_mesh<detail::Point3>::Face_index;
  std::vector<std::pair<Face, Face>> pairs;
  // Orienting a non-manifold soup can duplicate vertices but keeps faces in
  // order; with the same face count, face k is face_of[k].
  if (sm.number_of_faces() != face_of.size()) return {};
  CGAL::Polygon_mesh_processing::self_intersections<CGAL::Parallel_if_available_tag>(sm, std::back_inserter(pairs));
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  out.reserve(pairs.size());
  for (const auto& [a, b] : pairs) out.push_back(std::minmax(face_of[a.idx()], face_of[b.idx()]));
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace sharpmesh
