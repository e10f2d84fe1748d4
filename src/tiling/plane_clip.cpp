// Clipping a tile's mesh to its slab and finding its boundary on the cut
// planes (tiling/tiling.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

#include "tiling/tiling.h"

namespace sharpmesh::detail {
namespace {

/// Keeps the part of `mesh` where side * (p[axis] - plane) >= 0.
void clip_half(SurfaceMesh& mesh, int axis, double plane, double side) {
  auto f = [&](std::uint32_t v) { return side * (mesh.vertices[v][axis] - plane); };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> cut_vertex;
  auto cut = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::minmax(a, b);
    auto [at, added] = cut_vertex.try_emplace({key.first, key.second}, 0);
    if (added) {
      const Vec3& p = mesh.vertices[key.first];
      const Vec3& q = mesh.vertices[key.second];
      const double fp = side * (p[axis] - plane), fq = side * (q[axis] - plane);
      Vec3 x = p + (fp / (fp - fq)) * (q - p);
      x[axis] = plane;  // exactly on the plane: both tiles of a seam meet there
      at->second = static_cast<std::uint32_t>(mesh.vertices.size());
      mesh.vertices.push_back(x);
    }
    return at->second;
  };
  std::vector<Triangle> kept;
  kept.reserve(mesh.faces.size());
  for (const Triangle& t : mesh.faces) {
    const double d[3] = {f(t[0]), f(t[1]), f(t[2])};
    if (d[0] >= 0 && d[1] >= 0 && d[2] >= 0) {
      kept.push_back(t);
      continue;
    }
    if (d[0] <= 0 && d[1] <= 0 && d[2] <= 0) continue;
    // Sutherland-Hodgman on one triangle: the kept polygon has 3 or 4 corners.
    std::uint32_t polygon[4];
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      if (d[i] >= 0) polygon[n++] = t[i];
      if ((d[i] > 0 && d[j] < 0) || (d[i] < 0 && d[j] > 0)) polygon[n++] = cut(t[i], t[j]);
    }
    for (int k = 1; k + 1 < n; ++k) kept.push_back({polygon[0], polygon[k], polygon[k + 1]});
  }
  mesh.faces = std::move(kept);
}

}  // namespace

SurfaceMesh clip_to_slab(const SurfaceMesh& mesh, int axis, double low, double high, double snap) {
  SurfaceMesh out = mesh;
  for (Vec3& p : out.vertices) {
    if (std::isfinite(low) && std::abs(p[axis] - low) < snap) p[axis] = low;
    if (std::isfinite(high) && std::abs(p[axis] - high) < snap) p[axis] = high;
  }
  if (std::isfinite(low)) clip_half(out, axis, low, 1);
  if (std::isfinite(high)) clip_half(out, axis, high, -1);
  // Drop the vertices no facet uses any more, and facets that the cut made
  // degenerate (two corners on one vertex).
  std::vector<std::uint32_t> index(out.vertices.size(), std::numeric_limits<std::uint32_t>::max());
  SurfaceMesh compact;
  for (const Triangle& t : out.faces) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    Triangle u;
    for (int c = 0; c < 3; ++c) {
      if (index[t[c]] == std::numeric_limits<std::uint32_t>::max()) {
        index[t[c]] = static_cast<std::uint32_t>(compact.vertices.size());
        compact.vertices.push_back(out.vertices[t[c]]);
      }
      u[c] = index[t[c]];
    }
    compact.faces.push_back(u);
  }
  return compact;
}

std::vector<SeamChain> chains_on_plane(const SurfaceMesh& mesh, int axis, double plane) {
  // Half-edges whose twin is missing: the boundary.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> half_edges;
  for (const Triangle& t : mesh.faces)
    for (int c = 0; c < 3; ++c) ++half_edges[{t[c], t[(c + 1) % 3]}];
  std::unordered_map<std::uint32_t, std::uint32_t> next;  // along the boundary, on the plane
  std::unordered_map<std::uint32_t, int> incoming;
  for (const auto& [edge, count] : half_edges) {
    const auto [a, b] = edge;
    if (half_edges.count({b, a})) continue;
    if (mesh.vertices[a][axis] != plane || mesh.vertices[b][axis] != plane) continue;
    next[a] = b;
    ++incoming[b];
  }
  std::vector<SeamChain> chains;
  std::unordered_map<std::uint32_t, bool> used;
  // Open chains first: from the vertices nothing on the plane leads to.
  std::vector<std::uint32_t> starts;
  for (const auto& [a, b] : next)
    if (!incoming.count(a)) starts.push_back(a);
  std::sort(starts.begin(), starts.end());
  for (std::uint32_t s : starts) {
    SeamChain chain;
    for (std::uint32_t v = s;; ) {
      chain.vertices.push_back(v);
      used[v] = true;
      auto it = next.find(v);
      if (it == next.end() || used.count(it->second)) {
        if (it != next.end()) chain.vertices.push_back(it->second);
        break;
      }
      v = it->second;
    }
    chains.push_back(std::move(chain));
  }
  std::vector<std::uint32_t> rest;
  for (const auto& [a, b] : next)
    if (!used.count(a)) rest.push_back(a);
  std::sort(rest.begin(), rest.end());
  for (std::uint32_t s : rest) {
    if (used.count(s)) continue;
    SeamChain chain;
    chain.closed = true;
    for (std::uint32_t v = s; !used.count(v);) {
      chain.vertices.push_back(v);
      used[v] = true;
      auto it = next.find(v);
      if (it == next.end()) {
        chain.closed = false;
        break;
      }
      v = it->second;
    }
    chains.push_back(std::move(chain));
  }
  return chains;
}

}  // namespace sharpmesh::detail
