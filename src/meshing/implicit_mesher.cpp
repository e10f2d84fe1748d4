// Delaunay refinement of an implicit surface (Boissonnat & Oudot 2005; thesis
// 6.2.1, 7.3.1) with CGAL's Mesh_3: facet criteria only, the surface facets of
// the complex are the output.
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/facets_in_complex_3_to_triangle_mesh.h>
#include <CGAL/make_mesh_3.h>

#include <cmath>

#include "pointset/cgal_bridge.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {
namespace {

using detail::Kernel;
using Domain = CGAL::Labeled_mesh_domain_3<Kernel>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

}  // namespace

void RefinementCriteria::check() const {
  if (!(angle > 0 && angle <= 30))
    throw InvalidArgument("facet angle must be in (0, 30] degrees for refinement to terminate (got " + std::to_string(angle) + ")");
  if (!(edge_length > 0) || !std::isfinite(edge_length))
    throw InvalidArgument("maximum edge length must be positive (got " + std::to_string(edge_length) + ")");
  if (!(distance > 0) || !std::isfinite(distance))
    throw InvalidArgument("maximum surface distance must be positive (got " + std::to_string(distance) + ")");
}

RefinementCriteria RefinementCriteria::from_spacing(double d_prime) {
  RefinementCriteria c;
  c.angle = 25.0;
  c.edge_length = 2.0 * d_prime;
  c.distance = 0.6 * d_prime;
  return c;
}

void ImplicitMeshingOptions::check() const { criteria.check(); }

double estimate_facet_count(double area, const RefinementCriteria& criteria) {
  // Equilateral facets of edge l/2 .. l; take the geometric middle.
  const double edge = criteria.edge_length / std::sqrt(2.0);
  return area / (std::sqrt(3.0) / 4.0 * edge * edge);
}

SurfaceMesh mesh_implicit_surface(const ImplicitSurface& surface, const ImplicitMeshingOptions& options, const Progress& progress) {
  options.check();
  const double radius = surface.bounding_radius();
  if (!(radius > 0)) throw InvalidInput("implicit surface has an empty bounding sphere");
  // The surface lies well inside the function's bounding sphere; mesh within 1.5x of it.
  const double domain_radius = 1.5 * radius;
  const double sphere_area = 4 * M_PI * radius * radius;
  if (options.max_facets > 0 && estimate_facet_count(sphere_area, options.criteria) > 1e3 * options.max_facets)
    throw InvalidArgument("the meshing criteria are far too fine for the surface size (edge length " +
                          std::to_string(options.criteria.edge_length) + " on a surface of radius " + std::to_string(radius) + ")");

  const detail::Point3 center = detail::to_cgal(surface.bounding_center());
  std::function<double(const detail::Point3&)> function = [&surface](const detail::Point3& p) {
    return surface.value(detail::from_cgal(p));
  };
  CGAL::Random rng(options.seed);
  namespace params = CGAL::parameters;
  Domain domain = Domain::create_implicit_mesh_domain(
      function, Kernel::Sphere_3(center, domain_radius * domain_radius),
      params::relative_error_bound = 1e-6, params::p_rng = &rng);
  // The surface Delaunay ball radius bounds edges: radius <= l/2 gives edges <= l.
  Criteria criteria(params::facet_angle = options.criteria.angle, params::facet_size = options.criteria.edge_length / 2.0,
                    params::facet_distance = options.criteria.distance);
  report_progress(progress, "refinement", 0.0);
  C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(), params::no_exude(), params::manifold());
  report_progress(progress, "refinement", 1.0);

  CGAL::Surface_mesh<detail::Point3> sm;
  CGAL::facets_in_complex_3_to_triangle_mesh(c3t3, sm);
  SurfaceMesh out;
  out.vertices.reserve(sm.number_of_vertices());
  for (auto v : sm.vertices()) out.vertices.push_back(detail::from_cgal(sm.point(v)));
  out.faces.reserve(sm.number_of_faces());
  for (auto f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k < 3) t[k] = static_cast<std::uint32_t>(v.idx());
      ++k;
    }
    if (k == 3) out.faces.push_back(t);
  }
  if (out.faces.empty()) throw NumericalFailure("Delaunay refinement produced no surface facets (is the implicit surface empty?)");
  return out;
}

}  // namespace sharpmesh
