// Delaunay refinement of a triangle soup (thesis 6.3.3): CGAL's surface
// mesher (Boissonnat & Oudot 2005) with the soup as the oracle. A query
// segment, ray or line is intersected with every soup triangle it meets
// (AABB tree) and the oracle answers the centroid of the intersection
// points, as the thesis's AABB_trianglesoup_oracle (6.4) does.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh_complex_2_in_triangulation_3.h>
#include <CGAL/Surface_mesh_default_criteria_3.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_with_circumcenter_3.h>
#include <CGAL/Robust_circumcenter_traits_3.h>
#include <CGAL/Surface_mesh_cell_base_3.h>
#include <CGAL/Surface_mesh_vertex_base_3.h>
#include <CGAL/make_surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <unordered_set>

#include "core/cgal_bridge.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

/// Adds a creation stamp to a vertex or cell base. CGAL then orders handles by
/// creation (Time_stamper) instead of by heap address: the facet iterator and
/// the mesher's refinement queue compare handles, so without the stamp the
/// mesh depended on where malloc put the cells, which differs between runs
/// when earlier stages used several threads.
template <class Base>
class WithTimeStamp : public Base {
 public:
  using Has_timestamp = CGAL::Tag_true;
  template <class Tds2>
  struct Rebind_TDS {
    using Other = WithTimeStamp<typename Base::template Rebind_TDS<Tds2>::Other>;
  };
  using Base::Base;
  std::size_t time_stamp() const { return time_stamp_; }
  void set_time_stamp(const std::size_t& stamp) { time_stamp_ = stamp; }

 private:
  std::size_t time_stamp_ = std::size_t(-1);  // -1: not stamped yet (CGAL::Time_stamper)
};

// CGAL::Surface_mesh_default_triangulation_3 with time-stamped vertices and cells.
using TrK = CGAL::Robust_circumcenter_traits_3<K>;
using Vb = WithTimeStamp<CGAL::Surface_mesh_vertex_base_3<TrK>>;
using Cb = WithTimeStamp<CGAL::Delaunay_triangulation_cell_base_with_circumcenter_3<TrK, CGAL::Surface_mesh_cell_base_3<TrK>>>;
using Tr = CGAL::Delaunay_triangulation_3<TrK, CGAL::Triangulation_data_structure_3<Vb, Cb>>;
using C2t3 = CGAL::Surface_mesh_complex_2_in_triangulation_3<Tr>;
using Criteria = CGAL::Surface_mesh_default_criteria_3<Tr>;
using Triangle3 = K::Triangle_3;
using TriangleIterator = std::vector<Triangle3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, TriangleIterator>;
using AabbTraits = CGAL::AABB_traits<K, Primitive>;
using Tree = CGAL::AABB_tree<AabbTraits>;

struct SoupData {
  std::vector<Triangle3> triangles;
  Tree tree;
  std::vector<K::Point_3> seeds;  // initial points on the soup
};

/// The SurfaceMeshTraits_3 and Surface_3 of CGAL's surface mesher.
class SoupOracle {
 public:
  using Point_3 = K::Point_3;
  using Segment_3 = K::Segment_3;
  using Ray_3 = K::Ray_3;
  using Line_3 = K::Line_3;
  using Intersection_point = Point_3;
  using Surface_3 = SoupOracle;

  explicit SoupOracle(std::shared_ptr<const SoupData> data) : data_(std::move(data)) {}
  const SoupData& data() const { return *data_; }

  /// Centroid of all intersections of a query with the soup.
  template <class Query>
  static bool centroid_of_intersections(const SoupData& data, const Query& query, Point_3& centroid) {
    std::vector<typename AabbTraits::template Intersection_and_primitive_id<Query>::Type> hits;
    data.tree.all_intersections(query, std::back_inserter(hits));
    double x = 0, y = 0, z = 0;
    int count = 0;
    for (const auto& hit : hits) {
      if (const Point_3* p = boost::get<Point_3>(&hit.first)) {
        x += p->x(), y += p->y(), z += p->z();
      } else if (const Segment_3* s = boost::get<Segment_3>(&hit.first)) {  // the query lies in a triangle's plane
        const Point_3 m = CGAL::midpoint(s->source(), s->target());
        x += m.x(), y += m.y(), z += m.z();
      } else {
        continue;
      }
      ++count;
    }
    if (count == 0) return false;
    centroid = Point_3(x / count, y / count, z / count);
    return true;
  }

  class Intersect_3 {
   public:
    template <class Query>
    CGAL::Object operator()(const Surface_3& surface, const Query& query) const {
      Point_3 p;
      if (!centroid_of_intersections(surface.data(), query, p)) return CGAL::Object();
      return CGAL::make_object(p);
    }
  };
  Intersect_3 intersect_3_object() const { return Intersect_3(); }

  class Construct_initial_points {
   public:
    template <class Out>
    Out operator()(const Surface_3& surface, Out out, int /*n*/) const {
      for (const Point_3& p : surface.data().seeds) *out++ = p;
      return out;
    }
  };
  Construct_initial_points construct_initial_points_object() const { return Construct_initial_points(); }

 private:
  std::shared_ptr<const SoupData> data_;
};

std::shared_ptr<SoupData> build_soup_data(const TriangleSoup& soup) {
  auto data = std::make_shared<SoupData>();
  for (const Triangle& f : soup.faces) {
    if (f[0] >= soup.vertices.size() || f[1] >= soup.vertices.size() || f[2] >= soup.vertices.size())
      throw InvalidArgument("a soup triangle refers to a missing vertex");
    const Triangle3 t(detail::to_cgal(soup.vertices[f[0]]), detail::to_cgal(soup.vertices[f[1]]),
                      detail::to_cgal(soup.vertices[f[2]]));
    if (!t.is_degenerate()) data->triangles.push_back(t);
  }
  if (data->triangles.empty()) throw InvalidInput("the triangle soup is empty: nothing to mesh");
  data->tree.insert(data->triangles.cbegin(), data->triangles.cend());
  data->tree.build();
  return data;
}

}  // namespace

void SoupMeshingOptions::check() const {
  if (!(angle >= 0 && angle <= 30)) throw InvalidArgument("the angle bound alpha must be in [0, 30] degrees (termination is guaranteed up to 30)");
  if (!(size > 0 && size <= 10)) throw InvalidArgument("the size bound l must be in (0, 10] half diagonals, got " + format_number(size));
  if (!(distance > 0 && distance <= 10)) throw InvalidArgument("the distance bound d must be in (0, 10] half diagonals, got " + format_number(distance));
  if (size < 1e-4 || distance < 1e-5)
    throw InvalidArgument("the size and distance bounds are too small (l >= 1e-4, d >= 1e-5 half diagonals): the mesh would have billions of facets");
  if (initial_points < 3) throw InvalidArgument("at least 3 initial points are needed");
  if (!(seed_cell >= 0.25 && seed_cell <= 1000)) throw InvalidArgument("the seed cell must be in [0.25, 1000] size bounds l, got " + format_number(seed_cell));
  if (max_vertices < 4) throw InvalidArgument("the vertex limit must be at least 4");
}

double soup_half_diagonal(const TriangleSoup& soup) {
  std::vector<Vec3> used;
  for (const Triangle& f : soup.faces)
    for (std::uint32_t v : f) used.push_back(soup.vertices[v]);
  return 0.5 * bounding_box(used).diagonal();
}

bool soup_segment_intersection(const TriangleSoup& soup, const Vec3& a, const Vec3& b, Vec3& point) {
  const auto data = build_soup_data(soup);
  K::Point_3 p;
  if (!SoupOracle::centroid_of_intersections(*data, K::Segment_3(detail::to_cgal(a), detail::to_cgal(b)), p)) return false;
  point = detail::from_cgal(p);
  return true;
}

SoupMeshingResult mesh_soup(const TriangleSoup& soup, const SoupMeshingOptions& options, const Progress& progress) {
  options.check();
  report_progress(progress, "meshing the soup", 0.0);
  const std::shared_ptr<SoupData> data = build_soup_data(soup);
  std::vector<Vec3> used;
  for (const Triangle& f : soup.faces)
    for (std::uint32_t v : f) used.push_back(soup.vertices[v]);
  const double half_diagonal = soup_half_diagonal(soup);
  if (!(half_diagonal > 0)) throw InvalidInput("the triangle soup is degenerate (all vertices at one point)");
  // Seeds: centroids of random soup triangles, so that every sizeable part of the soup is found.
  CGAL::Random random(options.seed);
  double area = 0;
  for (const Triangle3& t : data->triangles) area += std::sqrt(t.squared_area());
  for (int i = 0; i < options.initial_points; ++i) {
    const Triangle3& t = data->triangles[static_cast<std::size_t>(random.get_int(0, static_cast<int>(data->triangles.size())))];
    data->seeds.push_back(CGAL::centroid(t));
  }
  // Beyond the thesis: also one seed per occupied cell of a grid of step 4l,
  // so that no part of the soup larger than a cell is left unmeshed for want
  // of a seed (random seeds alone missed patches of far ground: 2 points of
  // completeness at 2% on a fused-points scene).
  if (options.seed_cells) {
    const double cell = options.seed_cell * options.size * half_diagonal;
    const Vec3 origin = bounding_box(used).min;
    std::unordered_set<std::uint64_t> occupied;
    for (const Triangle3& t : data->triangles) {
      const K::Point_3 c = CGAL::centroid(t);
      std::uint64_t key = 0;
      for (int k = 0; k < 3; ++k)
        key = key * 2097152u + static_cast<std::uint64_t>(std::min(2097151.0, std::floor((c[k] - origin[k]) / cell)));
      if (occupied.insert(key).second) data->seeds.push_back(c);
    }
  }
  const SoupOracle oracle(data);
  Tr tr;
  C2t3 c2t3(tr);
  const Criteria criteria(options.angle, options.size * half_diagonal, options.distance * half_diagonal);
  using Mesher = CGAL::Surface_mesher_generator<C2t3, SoupOracle, Criteria, CGAL::Non_manifold_tag>::type;
  SoupOracle::Construct_initial_points()(oracle, CGAL::inserter(tr), options.initial_points);
  // A flat soup gives coplanar seeds, whose triangulation has no 3D Voronoi
  // diagram to refine: add the corners of a far box, off the surface. They are
  // never vertices of a restricted facet once refinement ends (their balls are
  // far above the size bound), and the output skips them anyway.
  std::vector<Tr::Vertex_handle> far_corners;
  if (tr.dimension() < 3) {
    const Vec3 c = bounding_box(used).center();
    const double r = 10 * half_diagonal;
    for (int k = 0; k < 8; ++k)
      far_corners.push_back(tr.insert(K::Point_3(c[0] + (k & 1 ? r : -r), c[1] + (k & 2 ? r : -r), c[2] + (k & 4 ? r : -r))));
  }
  Mesher mesher(c2t3, oracle, oracle, criteria);
  mesher.init();
  // Expected vertices: about one per (area of a Delaunay ball of radius l).
  const double expected = std::max(1.0, area / (M_PI * std::pow(options.size * half_diagonal, 2)));
  SoupMeshingResult result;
  result.half_diagonal = half_diagonal;
  CGAL::Null_mesh_visitor visitor;
  while (!mesher.is_algorithm_done()) {
    mesher.one_step(visitor);
    if (++result.steps % 2000 == 0) {
      report_progress(progress, "meshing the soup", std::min(0.99, tr.number_of_vertices() / expected));
      if (tr.number_of_vertices() > options.max_vertices)
        throw NumericalFailure("soup meshing passed " + format_number(options.max_vertices) +
                               " vertices; raise the size and distance bounds (l, d)");
    }
  }
  report_progress(progress, "meshing the soup", 1.0);
  // Facets of the complex, each oriented like the nearest soup triangle
  // (soup triangles face the camera that made them).
  std::map<Tr::Vertex_handle, std::uint32_t> index;
  SurfaceMesh& mesh = result.mesh;
  for (auto f = c2t3.facets_begin(); f != c2t3.facets_end(); ++f) {
    const Tr::Cell_handle cell = f->first;
    const int i = f->second;
    std::array<Tr::Vertex_handle, 3> v{cell->vertex((i + 1) & 3), cell->vertex((i + 2) & 3), cell->vertex((i + 3) & 3)};
    if (std::any_of(v.begin(), v.end(), [&](Tr::Vertex_handle h) {
          return std::find(far_corners.begin(), far_corners.end(), h) != far_corners.end();
        }))
      continue;
    Triangle face;
    for (int k = 0; k < 3; ++k) {
      const auto [it, inserted] = index.emplace(v[k], static_cast<std::uint32_t>(mesh.vertices.size()));
      if (inserted) mesh.vertices.push_back(detail::from_cgal(v[k]->point()));
      face[k] = it->second;
    }
    const Vec3 a = mesh.vertices[face[0]], b = mesh.vertices[face[1]], c = mesh.vertices[face[2]];
    const Vec3 normal = cross(b - a, c - a);
    const auto closest = data->tree.closest_point_and_primitive(detail::to_cgal((1.0 / 3) * (a + b + c)));
    const K::Vector_3 soup_normal = closest.second->supporting_plane().orthogonal_vector();
    if (dot(normal, detail::from_cgal(soup_normal)) < 0) std::swap(face[1], face[2]);
    mesh.faces.push_back(face);
  }
  return result;
}

}  // namespace sharpmesh
