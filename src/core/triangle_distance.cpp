#include "core/triangle_distance.h"


#include <cmath>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include "core/cgal_bridge.h"
#include "core/parallel.h"

namespace sharpmesh::detail {
namespace {
using Triangle3 = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle3>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
}  // namespace

struct TriangleDistance::Impl {
  std::vector<Triangle3> triangles;
  Tree tree;
};

TriangleDistance::TriangleDistance(const SurfaceMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->triangles.reserve(mesh.faces.size());
  for (const Triangle& f : mesh.faces) {
    Triangle3 t(to_cgal(mesh.vertices[f[0]]), to_cgal(mesh.vertices[f[1]]), to_cgal(mesh.vertices[f[2]]));
    if (!t.is_degenerate()) impl_->triangles.push_back(t);
  }
  if (impl_->triangles.empty()) throw InvalidInput("the mesh has no non-degenerate triangle");
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

TriangleDistance::~TriangleDistance() = default;

double TriangleDistance::squared_distance(const Vec3& q) const { return impl_->tree.squared_distance(to_cgal(q)); }

Vec3 TriangleDistance::closest_point(const Vec3& q) const { return from_cgal(impl_->tree.closest_point(to_cgal(q))); }

Vec3 TriangleDistance::closest_normal(const Vec3& q) const {
  const Triangle3& t = *impl_->tree.closest_point_and_primitive(to_cgal(q)).second;
  const Vec3 n = from_cgal(CGAL::cross_product(t[1] - t[0], t[2] - t[0]));
  const double length = norm(n);
  return length > 0 ? (1.0 / length) * n : n;
}

std::vector<double> TriangleDistance::distances(const std::vector<Vec3>& queries) const {
  std::vector<double> d(queries.size());
  detail::parallel_chunks(queries.size(), 2048, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i != end; ++i) d[i] = std::sqrt(squared_distance(queries[i]));
  });
  return d;
}

}  // namespace sharpmesh::detail
