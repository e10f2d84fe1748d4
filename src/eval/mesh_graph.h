// Edge-to-face incidence of an indexed triangle mesh, shared by the sharp-edge
// extraction and the topology checks.
#pragma once

#include <algorithm>
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
