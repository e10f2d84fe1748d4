// A manifold, consistently oriented mesh from a facet complex that may have
// edges with more than two facets (meshing.h, make_manifold): the stereo
// pipeline's soup meshing leaves them where layers of the soup meet.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>

#include <algorithm>
#include <boost/pending/disjoint_sets.hpp>
#include <map>
#include <utility>
#include <vector>

#include "core/cgal_bridge.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {

ManifoldRepairStats make_manifold(SurfaceMesh& mesh) {
  ManifoldRepairStats stats;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> facets_at_edge;
  for (const Triangle& f : mesh.faces)
    for (int k = 0; k < 3; ++k) ++facets_at_edge[std::minmax(f[k], f[(k + 1) % 3])];
  for (const auto& [edge, count] : facets_at_edge) stats.non_manifold_edges += count > 2;

  std::vector<detail::Kernel::Point_3> points;
  points.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) points.push_back(detail::to_cgal(v));
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(mesh.faces.size());
  for (const Triangle& f : mesh.faces) polygons.push_back({f[0], f[1], f[2]});
  CGAL::Polygon_mesh_processing::orient_polygon_soup(points, polygons);
  stats.duplicated_vertices = points.size() - mesh.vertices.size();

  // Which facets came out reversed, and the parts they form.
  const std::size_t n = polygons.size();
  std::vector<bool> reversed(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Triangle& before = mesh.faces[i];
    const auto& after = polygons[i];
    // Compare through the original vertex of each corner (duplicates keep their position).
    const auto position = [&](std::size_t v) { return detail::from_cgal(points[v]); };
    const std::size_t at = static_cast<std::size_t>(std::find_if(after.begin(), after.end(), [&](std::size_t v) {
                                                        return position(v) == mesh.vertices[before[0]];
                                                      }) - after.begin());
    reversed[i] = at < 3 && position(after[(at + 1) % 3]) != mesh.vertices[before[1]];
  }
  std::vector<std::size_t> rank(n), parent(n);
  boost::disjoint_sets<std::size_t*, std::size_t*> parts(rank.data(), parent.data());
  for (std::size_t i = 0; i < n; ++i) parts.make_set(i);
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> first_facet;
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const auto [it, inserted] = first_facet.emplace(std::minmax(polygons[i][k], polygons[i][(k + 1) % 3]), i);
      if (!inserted) parts.union_set(i, it->second);
    }
  // Each part keeps the orientation most of its facets had before.
  std::map<std::size_t, std::ptrdiff_t> vote;
  for (std::size_t i = 0; i < n; ++i) vote[parts.find_set(i)] += reversed[i] ? 1 : -1;
  for (std::size_t i = 0; i < n; ++i) {
    if (vote[parts.find_set(i)] > 0) {
      std::reverse(polygons[i].begin(), polygons[i].end());
      reversed[i] = !reversed[i];
    }
    stats.flipped_facets += reversed[i];
  }

  mesh.vertices.resize(points.size());
  for (std::size_t v = 0; v < points.size(); ++v) mesh.vertices[v] = detail::from_cgal(points[v]);
  for (std::size_t i = 0; i < n; ++i)
    mesh.faces[i] = {static_cast<std::uint32_t>(polygons[i][0]), static_cast<std::uint32_t>(polygons[i][1]),
                     static_cast<std::uint32_t>(polygons[i][2])};
  return stats;
}

}  // namespace sharpmesh
