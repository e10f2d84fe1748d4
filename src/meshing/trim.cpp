// Trimming where there is no data: Poisson's implicit function is closed by
// construction, so on open scans and open models (CGAL's blade) it invents a
// closing sheet. Facets far from every input point are removed.
#include <tbb/parallel_for.h>

#include "eval/mesh_graph.h"
#include "pointset/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {

std::size_t trim_far_from_points(SurfaceMesh& mesh, const std::vector<Vec3>& points, double max_distance) {
  if (!(max_distance > 0)) throw InvalidArgument("trim distance must be positive");
  if (points.empty() || mesh.faces.empty()) return 0;
  const detail::KnnIndex index(points);
  std::vector<char> keep(mesh.faces.size(), 1);
  tbb::parallel_for(std::size_t(0), mesh.faces.size(), [&](std::size_t f) {
    const Triangle& t = mesh.faces[f];
    const Vec3 c = (1.0 / 3.0) * (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]);
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    index.nearest(c, 1, ids, d2);
    keep[f] = !d2.empty() && d2[0] <= max_distance * max_distance;
  });
  std::vector<Triangle> faces;
  std::vector<std::uint32_t> remap(mesh.vertices.size(), UINT32_MAX);
  std::vector<Vec3> vertices;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!keep[f]) continue;
    Triangle t = mesh.faces[f];
    for (std::uint32_t& v : t) {
      if (remap[v] == UINT32_MAX) {
        remap[v] = static_cast<std::uint32_t>(vertices.size());
        vertices.push_back(mesh.vertices[v]);
      }
      v = remap[v];
    }
    faces.push_back(t);
  }
  const std::size_t removed = mesh.faces.size() - faces.size();
  if (removed > 0) {
    mesh.faces = std::move(faces);
    mesh.vertices = std::move(vertices);
  }
  return removed;
}

std::size_t count_boundary_edges(const SurfaceMesh& mesh) {
  std::size_t count = 0;
  for (const auto& e : detail::edge_incidences(mesh)) count += e.faces.size() == 1;
  return count;
}

}  // namespace sharpmesh
