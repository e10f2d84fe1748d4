// Hole filling, the remedy the thesis proposes for its own limitation (6.6):
// every boundary cycle of the mesh shorter than a bound is closed by a patch
// with the topology of a disc, triangulated, refined to the density of its
// rim and faired (CGAL's Polygon Mesh Processing, after Liepa 2003). Long
// cycles, the true border of an open scene, are left alone.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <map>
#include <tuple>

#include "core/cgal_bridge.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using detail::Kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Halfedge = Mesh::Halfedge_index;

struct Cycle {
  Halfedge start;
  double perimeter = 0;
  std::size_t edges = 0;
};

Cycle measure(const Mesh& mesh, Halfedge start) {
  Cycle cycle{start};
  Halfedge h = start;
  do {
    cycle.perimeter += std::sqrt(CGAL::squared_distance(mesh.point(mesh.source(h)), mesh.point(mesh.target(h))));
    ++cycle.edges;
    h = mesh.next(h);
  } while (h != start && cycle.edges <= mesh.number_of_halfedges());
  return cycle;
}

}  // namespace

void HoleFillingOptions::check() const {
  if (!(max_perimeter >= 0) || !std::isfinite(max_perimeter))
    throw InvalidArgument("the largest hole perimeter to fill must be >= 0 (got " + format_number(max_perimeter) + ")");
  if (max_edges < 3) throw InvalidArgument("a hole has at least 3 edges: max_edges must be >= 3");
}

HoleFillingStats fill_holes(SurfaceMesh& surface, const HoleFillingOptions& options, const Progress& progress) {
  options.check();
  HoleFillingStats stats;
  if (surface.faces.empty()) return stats;
  report_progress(progress, "filling holes", 0.0);
  std::vector<Point> points;
  points.reserve(surface.vertices.size());
  for (const Vec3& v : surface.vertices) points.push_back(detail::to_cgal(v));
  std::vector<std::array<std::size_t, 3>> polygons;
  polygons.reserve(surface.faces.size());
  for (const Triangle& f : surface.faces) polygons.push_back({f[0], f[1], f[2]});
  PMP::repair_polygon_soup(points, polygons);
  // Duplicates the vertices where the surface is not a manifold, so that
  // every boundary cycle is a simple loop; merged again below.
  PMP::orient_polygon_soup(points, polygons);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);

  std::vector<Halfedge> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  stats.holes = borders.size();
  std::vector<Cycle> cycles;
  for (Halfedge h : borders) cycles.push_back(measure(mesh, h));
  for (std::size_t c = 0; c < cycles.size(); ++c) {
    report_progress(progress, "filling holes", static_cast<double>(c) / static_cast<double>(cycles.size()));
    const Cycle& cycle = cycles[c];
    if (cycle.perimeter > options.max_perimeter || cycle.edges > options.max_edges) continue;
    std::vector<Mesh::Face_index> faces;
    std::vector<Mesh::Vertex_index> vertices;
    const bool faired = std::get<0>(PMP::triangulate_refine_and_fair_hole(mesh, cycle.start, std::back_inserter(faces),
                                                                            std::back_inserter(vertices)));
    if (faces.empty()) {
      ++stats.failed;
      continue;
    }
    ++stats.filled;
    stats.unfaired += !faired;
    stats.added_facets += faces.size();
  }
  report_progress(progress, "filling holes", 1.0);
  if (stats.filled == 0) return stats;

  // Back to an indexed mesh, merging the vertices split above unless asked to keep the manifold.
  SurfaceMesh filled;
  std::map<Point, std::uint32_t> index_of;
  std::vector<std::uint32_t> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), 0);
  for (Mesh::Vertex_index v : mesh.vertices()) {
    if (!options.merge_split_vertices) {
      index[v] = static_cast<std::uint32_t>(filled.vertices.size());
      filled.vertices.push_back(detail::from_cgal(mesh.point(v)));
      continue;
    }
    const auto [it, inserted] = index_of.emplace(mesh.point(v), static_cast<std::uint32_t>(filled.vertices.size()));
    if (inserted) filled.vertices.push_back(detail::from_cgal(mesh.point(v)));
    index[v] = it->second;
  }
  for (Mesh::Face_index f : mesh.faces()) {
    Triangle t{};
    int k = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k == 3) break;
      t[k++] = index[v];
    }
    if (k == 3 && t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) filled.faces.push_back(t);
  }
  surface = std::move(filled);
  return stats;
}

}  // namespace sharpmesh
