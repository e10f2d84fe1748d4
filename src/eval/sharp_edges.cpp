// Sharp edges of a reference mesh: the ground truth of feature evaluation.
#include <cmath>

#include "core/mesh_graph.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"

namespace sharpmesh {

std::vector<Polyline> sharp_edges(const SurfaceMesh& mesh, double angle_deg) {
  if (!(angle_deg > 0 && angle_deg < 180)) throw InvalidArgument("sharp angle must be in (0, 180) degrees (got " + format_number(angle_deg) + ")");
  const double cos_limit = std::cos(angle_deg * M_PI / 180.0);
  std::vector<Vec3> normals(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle& t = mesh.faces[f];
    const Vec3 n = cross(mesh.vertices[t[1]] - mesh.vertices[t[0]], mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const double length = norm(n);
    normals[f] = length > 0 ? (1.0 / length) * n : Vec3{0, 0, 0};
  }
  // Sharp edges: two faces whose normals differ by more than the angle
  // (orientation-aware), or more than two faces (non-manifold edge).
  detail::VertexAdjacency adjacency(mesh.vertices.size());
  for (const auto& e : detail::edge_incidences(mesh)) {
    bool sharp = e.faces.size() > 2;
    if (e.faces.size() == 2) {
      const Vec3 &n0 = normals[e.faces[0]], &n1 = normals[e.faces[1]];
      if (norm(n0) > 0 && norm(n1) > 0) {
        const double sign = e.forward[0] != e.forward[1] ? 1.0 : -1.0;  // same direction: inconsistent orientation
        sharp = sign * dot(n0, n1) < cos_limit;
      }
    }
    if (sharp) {
      adjacency[e.a].push_back(e.b);
      adjacency[e.b].push_back(e.a);
    }
  }
  return detail::chain_edges(mesh.vertices, adjacency);
}

}  // namespace sharpmesh
