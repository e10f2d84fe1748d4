// Edge-to-face incidence of an indexed triangle mesh, shared by the sharp-edge
// extraction and the topology checks.
#pragma once

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh::detail {

struct EdgeIncidence {
  std::uint32_t a, b;                 ///< a < b
  std::vector<std::uint32_t> faces;   ///< incident faces
  std::vector<bool> forward;          ///< face traverses a -> b
};

inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

inline std::vector<EdgeIncidence> edge_incidences(const SurfaceMesh& mesh) {
  std::unordered_map<std::uint64_t, std::uint32_t> index;
  index.reserve(mesh.faces.size() * 2);
  std::vector<EdgeIncidence> edges;
  edges.reserve(mesh.faces.size() * 3 / 2 + 1);
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = mesh.faces[f][k], v = mesh.faces[f][(k + 1) % 3];
      if (u == v) continue;
      auto [it, inserted] = index.try_emplace(edge_key(u, v), static_cast<std::uint32_t>(edges.size()));
      if (inserted) edges.push_back({std::min(u, v), std::max(u, v), {}, {}});
      EdgeIncidence& e = edges[it->second];
      e.faces.push_back(f);
      e.forward.push_back(u < v);
    }
  }
  return edges;
}

using VertexAdjacency = std::vector<std::vector<std::uint32_t>>;

/// Chains the edges of a graph on mesh vertices into polylines that run
/// between vertices whose degree is not 2; what remains are closed loops
/// (front() == back()).
inline std::vector<Polyline> chain_edges(const std::vector<Vec3>& vertices, const VertexAdjacency& adjacency) {
  std::vector<Polyline> polylines;
  std::unordered_map<std::uint64_t, bool> used;
  auto walk = [&](std::uint32_t start, std::uint32_t next) {
    Polyline line{vertices[start]};
    std::uint32_t previous = start, current = next;
    used[edge_key(previous, current)] = true;
    while (true) {
      line.push_back(vertices[current]);
      if (adjacency[current].size() != 2 || current == start) break;
      const std::uint32_t following = adjacency[current][0] == previous ? adjacency[current][1] : adjacency[current][0];
      if (used[edge_key(current, following)]) break;
      used[edge_key(current, following)] = true;
      previous = current;
      current = following;
    }
    polylines.push_back(std::move(line));
  };
  for (std::uint32_t v = 0; v < adjacency.size(); ++v)
    if (!adjacency[v].empty() && adjacency[v].size() != 2)
      for (std::uint32_t w : adjacency[v])
        if (!used[edge_key(v, w)]) walk(v, w);
  for (std::uint32_t v = 0; v < adjacency.size(); ++v)  // remaining: closed loops
    for (std::uint32_t w : adjacency[v])
      if (!used[edge_key(v, w)]) walk(v, w);
  return polylines;
}

/// Replaces mesh.faces by `faces` (indices into mesh.vertices) and drops
/// the vertices no face uses, keeping the order of first use.
inline void set_faces_and_compact(SurfaceMesh& mesh, std::vector<Triangle> faces) {
  std::vector<std::uint32_t> remap(mesh.vertices.size(), UINT32_MAX);
  std::vector<Vec3> vertices;
  for (Triangle& t : faces)
    for (std::uint32_t& v : t) {
      if (remap[v] == UINT32_MAX) {
        remap[v] = static_cast<std::uint32_t>(vertices.size());
        vertices.push_back(mesh.vertices[v]);
      }
      v = remap[v];
    }
  mesh.vertices = std::move(vertices);
  mesh.faces = std::move(faces);
}

/// Union-find with path halving.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) {
    for (std::size_t i = 0; i < n; ++i) parent_[i] = i;
  }
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace sharpmesh::detail
