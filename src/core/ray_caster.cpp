#include "core/ray_caster.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include "core/cgal_bridge.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::detail {
namespace {
using Triangle3 = Kernel::Triangle_3;
using Iterator = std::vector<Triangle3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
}  // namespace

struct RayCaster::Impl {
  std::vector<Triangle3> triangles;
  std::vector<std::uint32_t> face_of;  // triangle -> mesh face (degenerate faces are skipped)
  Tree tree;
};

RayCaster::RayCaster(const SurfaceMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->triangles.reserve(mesh.faces.size());
  for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
    const Triangle& f = mesh.faces[i];
    Triangle3 t(to_cgal(mesh.vertices[f[0]]), to_cgal(mesh.vertices[f[1]]), to_cgal(mesh.vertices[f[2]]));
    if (t.is_degenerate()) continue;
    impl_->triangles.push_back(t);
    impl_->face_of.push_back(static_cast<std::uint32_t>(i));
  }
  if (impl_->triangles.empty()) throw InvalidInput("the mesh has no non-degenerate triangle");
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
}

RayCaster::~RayCaster() = default;

bool RayCaster::first_hit(const Vec3& origin, const Vec3& direction, RayHit& hit) const {
  const Kernel::Ray_3 ray(to_cgal(origin), Kernel::Vector_3(direction[0], direction[1], direction[2]));
  const auto result = impl_->tree.first_intersection(ray);
  if (!result) return false;
  const Kernel::Point_3* p = boost::get<Kernel::Point_3>(&result->first);
  if (!p) return false;  // a segment: the ray runs inside a triangle's plane
  hit.distance = distance(from_cgal(*p), origin);
  hit.face = impl_->face_of[static_cast<std::size_t>(result->second - impl_->triangles.cbegin())];
  return true;
}

bool RayCaster::occluded(const Vec3& from, const Vec3& to, double relative_gap) const {
  const Vec3 end = to + relative_gap * (from - to);
  return impl_->tree.do_intersect(Kernel::Segment_3(to_cgal(from), to_cgal(end)));
}

void RayCaster::crossed_faces(const Vec3& from, const Vec3& to, std::vector<std::uint32_t>& faces) const {
  std::vector<Iterator> hits;
  impl_->tree.all_intersected_primitives(Kernel::Segment_3(to_cgal(from), to_cgal(to)), std::back_inserter(hits));
  for (Iterator it : hits) faces.push_back(impl_->face_of[static_cast<std::size_t>(it - impl_->triangles.cbegin())]);
}

}  // namespace sharpmesh::detail
