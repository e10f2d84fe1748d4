// A uniform grid of a mesh's facets that follows its edge collapses: the
// facets near a new one, for the crossing test CGAL's collapse filters do not
// make (Bounded_normal_change_filter and the envelope look at the star of
// the edge only, and on a part thinner than the facets a collapse on one side
// cuts through the other). Include only from CGAL .cpp files.
#pragma once

#include <CGAL/Surface_mesh.h>
#include <CGAL/intersections.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/cgal_bridge.h"

namespace sharpmesh::detail {

class FacetGrid {
 public:
  using Mesh = CGAL::Surface_mesh<Point3>;
  using Face = Mesh::Face_index;
  using Vertex = Mesh::Vertex_index;

  /// Every facet of `mesh` in cells of side `cell`.
  FacetGrid(const Mesh& mesh, double cell) : mesh_(mesh), cell_(cell), stamp_(mesh.number_of_faces(), 0) {
    for (Face f : mesh.faces()) insert(f);
  }

  /// Call before a facet changes or goes, with its current corners.
  void erase(Face f) {
    for_cells(box(f), [&](std::int64_t key) {
      std::vector<Face>& list = cells_[key];
      for (std::size_t i = 0; i < list.size(); ++i)
        if (list[i] == f) {
          list[i] = list.back();
          list.pop_back();
          break;
        }
    });
  }

  void insert(Face f) {
    for_cells(box(f), [&](std::int64_t key) { cells_[key].push_back(f); });
  }

  /// Whether `triangle` meets a facet none of whose corners is in `skip`
  /// (the collapsing edge's ends, whose facets are being replaced, and the
  /// triangle's own corners, whose facets touch it by construction).
  bool crosses(const Kernel::Triangle_3& triangle, const std::array<Vertex, 4>& skip) {
    if (triangle.is_degenerate()) return false;
    ++query_;
    bool found = false;
    for_cells(triangle.bbox(), [&](std::int64_t key) {
      if (found) return;
      const auto cell = cells_.find(key);
      if (cell == cells_.end()) return;
      for (Face f : cell->second) {
        if (stamp_[f.idx()] == query_) continue;
        stamp_[f.idx()] = query_;
        bool touching = false;
        std::array<Point3, 3> corners;
        int i = 0;
        for (Vertex v : CGAL::vertices_around_face(mesh_.halfedge(f), mesh_)) {
          touching = touching || std::find(skip.begin(), skip.end(), v) != skip.end();
          corners[i++] = mesh_.point(v);
        }
        if (!touching && CGAL::do_intersect(triangle, Kernel::Triangle_3(corners[0], corners[1], corners[2]))) {
          found = true;
          return;
        }
      }
    });
    return found;
  }

 private:
  CGAL::Bbox_3 box(Face f) const {
    CGAL::Bbox_3 b;
    for (Vertex v : CGAL::vertices_around_face(mesh_.halfedge(f), mesh_)) b += mesh_.point(v).bbox();
    return b;
  }

  template <class Visit>
  void for_cells(const CGAL::Bbox_3& b, Visit&& visit) const {
    const auto index = [&](double x) { return static_cast<std::int64_t>(std::floor(x / cell_)); };
    for (std::int64_t i = index(b.xmin()); i <= index(b.xmax()); ++i)
      for (std::int64_t j = index(b.ymin()); j <= index(b.ymax()); ++j)
        for (std::int64_t k = index(b.zmin()); k <= index(b.zmax()); ++k)
          visit(((i & 0x1fffff) << 42) | ((j & 0x1fffff) << 21) | (k & 0x1fffff));
  }

  const Mesh& mesh_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<Face>> cells_;
  std::vector<std::uint32_t> stamp_;  ///< per facet, the last query that tested it
  std::uint32_t query_ = 0;
};

}  // namespace sharpmesh::detail
