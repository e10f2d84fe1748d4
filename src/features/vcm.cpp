// Voronoi covariance measure, clamped approximation (thesis 7.4; Merigot et
// al. 2009), and its convolution (7.2.1).
//
// The Voronoi cell of p is bounded by the faces dual to its Delaunay edges
// (p, q); each face is the polygon of the circumcentres of the cells around
// the edge. Vertices farther than R from p are clamped onto the sphere
// B(p, R); the clamped cell is star-shaped from p, so the tetrahedra
// (p, c0, ci, ci+1) tile it and their covariances (closed form, Alliez et al.
// 2007) add up. Dummy points far around the data bound every data cell
// without cutting any ball B(p, R).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>


#include <algorithm>
#include <cmath>

#include "core/cgal_bridge.h"
#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/features.h"
#include "core/parallel.h"

namespace sharpmesh {
namespace {

using detail::Kernel;
using detail::Point3;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Kernel>;
using Cb = CGAL::Triangulation_cell_base_with_info_3<std::uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;

constexpr std::uint32_t kDummy = 0xFFFFFFFFu;

// Adds t * (a a^T + b b^T + c c^T + s s^T), s = a + b + c: the covariance of
// the tetrahedron (0, a, b, c) about its apex 0 is |det| / 120 times this sum.
void add_tetrahedron(Matrix3& m, const Vec3& a, const Vec3& b, const Vec3& c) {
  const double volume6 = std::abs(dot(a, cross(b, c)));
  if (!(volume6 > 0)) return;
  const double w = volume6 / 120.0;
  const Vec3 s = a + b + c;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      const double v = w * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
      m[3 * i + j] += v;
      if (i != j) m[3 * j + i] += v;
    }
}

}  // namespace

std::vector<Matrix3> voronoi_covariance(const std::vector<Vec3>& points, double R, const Progress& progress) {
  if (!(R > 0) || !std::isfinite(R)) throw InvalidArgument("offset radius R must be positive (got " + format_number(R) + ")");
  if (points.size() < 4) throw InvalidInput("the Voronoi covariance needs at least 4 points");
  report_progress(progress, "voronoi covariance", 0.0);
  const BoundingBox box = bounding_box(points);
  const double margin = 3.0 * R + box.diagonal();
  std::vector<std::pair<Point3, std::uint32_t>> input;
  input.reserve(points.size() + 27);
  for (std::uint32_t i = 0; i < points.size(); ++i) input.emplace_back(detail::to_cgal(points[i]), i);
  // 26 dummy points on a box at distance > 2R of every data point: their
  // bisectors stay farther than R from any data point.
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) {
          const Vec3 c = box.center();
          input.emplace_back(Point3(c[0] + x * margin, c[1] + y * margin, c[2] + z * margin), kDummy);
        }
  Delaunay dt(input.begin(), input.end());
  report_progress(progress, "voronoi covariance", 0.3);

  // Circumcentres, indexed through the cell info; vertex handles by point index.
  std::vector<Vec3> centers;
  centers.reserve(dt.number_of_finite_cells());
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    c->info() = static_cast<std::uint32_t>(centers.size());
    centers.push_back(detail::from_cgal(CGAL::circumcenter(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(), c->vertex(3)->point())));
  }
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c)
    if (dt.is_infinite(c)) c->info() = kDummy;
  std::vector<Delaunay::Vertex_handle> vertex_of(points.size());
  std::size_t merged = 0;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
    if (v->info() != kDummy) vertex_of[v->info()] = v;
  for (const auto& v : vertex_of) merged += (v == Delaunay::Vertex_handle());

  std::vector<Matrix3> vcm(points.size(), Matrix3{});
  // Duplicated input points share one Delaunay vertex: they share its VCM.
  std::vector<std::uint32_t> representative(points.size());
  if (merged > 0) {
    const detail::KnnIndex index(points);
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    for (std::uint32_t i = 0; i < points.size(); ++i) {
      representative[i] = i;
      if (vertex_of[i] != Delaunay::Vertex_handle()) continue;
      index.nearest(points[i], 8, ids, d2);
      for (std::uint32_t j : ids)
        if (vertex_of[j] != Delaunay::Vertex_handle() && points[j] == points[i]) representative[i] = j;
    }
  }

  const double R2 = R * R;
  detail::parallel_chunks(points.size(), 512, [&](std::size_t begin, std::size_t end) {
    std::vector<Delaunay::Edge> edges;
    std::vector<Delaunay::Cell_handle> cells;
    std::vector<Delaunay::Vertex_handle> seen;
    std::vector<Vec3> polygon;
    for (std::size_t i = begin; i != end; ++i) {
      const auto v = vertex_of[i];
      if (v == Delaunay::Vertex_handle()) continue;
      const Vec3 p = detail::from_cgal(v->point());
      // The Delaunay edges (v, w), one per neighbour w, from the incident
      // cells (the thread-safe traversal: the plain one marks cells).
      edges.clear();
      cells.clear();
      seen.clear();
      dt.incident_cells_threadsafe(v, std::back_inserter(cells));
      for (const auto& c : cells) {
        const int iv = c->index(v);
        for (int j = 0; j < 4; ++j) {
          const auto w = c->vertex(j);
          if (j == iv || dt.is_infinite(w) || std::find(seen.begin(), seen.end(), w) != seen.end()) continue;
          seen.push_back(w);
          edges.emplace_back(c, iv, j);
        }
      }
      Matrix3& m = vcm[i];
      for (const Delaunay::Edge& e : edges) {
        polygon.clear();
        bool bounded = true;
        auto circulator = dt.incident_cells(e), done = circulator;
        do {
          const std::uint32_t c = circulator->info();
          if (c == kDummy) { bounded = false; break; }
          Vec3 q = centers[c] - p;
          const double d2 = dot(q, q);
          if (!std::isfinite(d2)) { bounded = false; break; }
          if (d2 > R2) q = (R / std::sqrt(d2)) * q;  // clamp onto the sphere B(p, R)
          polygon.push_back(q);
        } while (++circulator != done);
        if (!bounded || polygon.size() < 3) continue;
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k) add_tetrahedron(m, polygon[0], polygon[k], polygon[k + 1]);
      }
    }
  });
  if (merged > 0)
    for (std::size_t i = 0; i < points.size(); ++i)
      if (representative[i] != i) vcm[i] = vcm[representative[i]];
  report_progress(progress, "voronoi covariance", 1.0);
  return vcm;
}

std::vector<Matrix3> convolve_covariance(const std::vector<Vec3>& points, const std::vector<Matrix3>& vcm, double r,
                                         const Progress& progress) {
  if (!(r >= 0) || !std::isfinite(r)) throw InvalidArgument("convolution radius r must be non-negative (got " + format_number(r) + ")");
  report_progress(progress, "convolution", 0.0);
  const detail::KnnIndex index(points);
  std::vector<Matrix3> out(points.size(), Matrix3{});
  detail::parallel_chunks(points.size(), 512, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> ids;
    for (std::size_t i = begin; i != end; ++i) {
      index.within(points[i], r, ids);
      std::sort(ids.begin(), ids.end());  // fixed summation order: thread-count independent
      Matrix3& m = out[i];
      for (std::uint32_t j : ids)
        for (int k = 0; k < 9; ++k) m[k] += vcm[j][k];
      if (ids.empty()) m = vcm[i];
    }
  });
  report_progress(progress, "convolution", 1.0);
  return out;
}

}  // namespace sharpmesh
