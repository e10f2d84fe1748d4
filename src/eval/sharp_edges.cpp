// Sharp edges of a reference mesh: the ground truth of feature evaluation.
#include <cmath>

#include "eval/mesh_graph.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"

namespace sharpmesh {

std::vector<Polyline> sharp_edges(const SurfaceMesh& mesh, double angle_deg) {
  if (!(angle_deg > 0 && angle_deg < 180)) throw InvalidArgument("sharp angle must be in (0, 180) degrees (got " + std::to_string(angle_deg) + ")");
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
  std::vector<std::vector<std::uint32_t>> adjacency(mesh.vertices.size());
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
  // Chain edges into polylines between vertices whose sharp degree is not 2.
  std::vector<Polyline> polylines;
  std::unordered_map<std::uint64_t, bool> used;
  auto walk = [&](std::uint32_t start, std::uint32_t next) {
    Polyline line{mesh.vertices[start]};
    std::uint32_t previous = start, current = next;
    used[detail::edge_key(previous, current)] = true;
    while (true) {
      line.push_back(mesh.vertices[current]);
      if (adjacency[current].size() != 2 || current == start) break;
      const std::uint32_t following = adjacency[current][0] == previous ? adjacency[current][1] : adjacency[current][0];
      if (used[detail::edge_key(current, following)]) break;
      used[detail::edge_key(current, following)] = true;
      previous = current;
      current = following;
    }
    polylines.push_back(std::move(line));
  };
  for (std::uint32_t v = 0; v < adjacency.size(); ++v)
    if (!adjacency[v].empty() && adjacency[v].size() != 2)
      for (std::uint32_t w : adjacency[v])
        if (!used[detail::edge_key(v, w)]) walk(v, w);
  for (std::uint32_t v = 0; v < adjacency.size(); ++v)  // remaining: closed loops
    for (std::uint32_t w : adjacency[v])
      if (!used[detail::edge_key(v, w)]) walk(v, w);
  return polylines;
}

}  // namespace sharpmesh
