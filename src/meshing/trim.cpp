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
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (keep[f]) faces.push_back(mesh.faces[f]);
  const std::size_t removed = mesh.faces.size() - faces.size();
  if (removed > 0) detail::set_faces_and_compact(mesh, std::move(faces));
  return removed;
}

std::size_t count_boundary_edges(const SurfaceMesh& mesh) {
  std::size_t count = 0;
  for (const auto& e : detail::edge_incidences(mesh)) count += e.faces.size() == 1;
  return count;
}

}  // namespace sharpmesh
