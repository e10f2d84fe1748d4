// Poisson implicit function (Kazhdan et al. 2006) through CGAL's
// Poisson_reconstruction_function (thesis 7.3, 7.4).
#include "implicit/poisson_refinement_order.h"  // before CGAL's Poisson

#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Poisson_reconstruction_function.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>
#include <tuple>
#include <type_traits>

#include "core/cgal_bridge.h"
#include "sharpmesh/implicit.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh {
namespace {

using detail::Kernel;
using PointWithNormal = std::pair<detail::Point3, detail::Vector3>;
using Function = CGAL::Poisson_reconstruction_function<Kernel>;
using Triangulation = Function::Triangulation;
static_assert(std::is_same_v<Triangulation, detail::PoissonTriangulation>,
              "the deterministic refinement queue (poisson_refinement_order.h) must match CGAL's Poisson triangulation");
using Cell = Triangulation::Cell;
using Cell_handle = Triangulation::Cell_handle;
/// The weight Poisson_reconstruction_function::compute_implicit_function adds
/// to the diagonal at the input vertices (its `lambda`, fixed in CGAL 5.5).
constexpr double kCgalPoissonLambda = 0.1;

/// Evaluates CGAL's Poisson function (its operator()'s piecewise-linear
/// interpolation and formula, so the same value whenever the walk ends in the
/// same cell) with a better start for the point location.
/// CGAL walks from the last cell it found; Mesh_3 asks at far-apart places
/// (circumcentres of new cells, then the dual edges of new facets), and on
/// fandisk 200k those walks took most of the refinement stage. Two grids of
/// start cells (a fine one, and one 8 times coarser for a fine slot's first
/// query), each slot filled by the first query that falls in it, bound every
/// walk to about one grid step. Safe to call from several threads.
class StartCellGrid {
 public:
  void build(const Triangulation& tr) {
    CGAL::Bbox_3 box;
    for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) box += v->point().bbox();
    // About 16 vertices per fine step along the surface (N / 16 = g^2), at most 128^3 slots (16 MiB).
    const double n = static_cast<double>(tr.number_of_vertices());
    const int fine = std::clamp(static_cast<int>(std::sqrt(n / 16)), 8, 128);
    levels_[0].resize(box, fine);
    levels_[1].resize(box, fine / 8);
  }

  double value(const Triangulation& tr, const detail::Point3& p) const {
    std::atomic<Cell*>& fine = levels_[0].slot(p);
    std::atomic<Cell*>& coarse = levels_[1].slot(p);
    Cell* const fine_start = fine.load(std::memory_order_relaxed);
    Cell* const grid_start = fine_start ? fine_start : coarse.load(std::memory_order_relaxed);
    Cell* const last = last_.load(std::memory_order_relaxed);
    // The nearer of the grid's start and the last cell found (consecutive
    // queries along a segment or a grid are close).
    Cell* start = grid_start ? grid_start : last;
    if (grid_start && last && squared_distance_to_cell(tr, p, last) < squared_distance_to_cell(tr, p, grid_start)) start = last;
    const Cell_handle cell = start ? tr.locate(p, handle(start)) : tr.locate(p);
    if (!fine_start) {
      fine.store(cell.operator->(), std::memory_order_relaxed);
      if (!grid_start) coarse.store(cell.operator->(), std::memory_order_relaxed);
    }
    last_.store(cell.operator->(), std::memory_order_relaxed);
    if (tr.is_infinite(cell)) return cell->vertex((cell->index(tr.infinite_vertex()) + 1) & 3)->f();
    // As CGAL's barycentric_coordinates (Poisson_reconstruction_function.h).
    const detail::Point3& pd = cell->vertex(3)->point();
    const detail::Vector3 va = cell->vertex(0)->point() - pd, vb = cell->vertex(1)->point() - pd, vc = cell->vertex(2)->point() - pd;
    double i[9];
    CGAL::internal::invert(va.x(), va.y(), va.z(), vb.x(), vb.y(), vb.z(), vc.x(), vc.y(), vc.z(), i[0], i[1], i[2], i[3], i[4],
                           i[5], i[6], i[7], i[8]);
    const detail::Vector3 vp = p - pd;
    const double a = i[0] * vp.x() + i[3] * vp.y() + i[6] * vp.z();
    const double b = i[1] * vp.x() + i[4] * vp.y() + i[7] * vp.z();
    const double c = i[2] * vp.x() + i[5] * vp.y() + i[8] * vp.z();
    const double d = 1 - (a + b + c);
    return a * cell->vertex(0)->f() + b * cell->vertex(1)->f() + c * cell->vertex(2)->f() + d * cell->vertex(3)->f();
  }

 private:
  /// A uniform grid over the triangulation's bounding box, one start cell per slot.
  struct Level {
    void resize(const CGAL::Bbox_3& box, int slots_per_axis) {
      size = slots_per_axis;
      for (int a = 0; a < 3; ++a) {
        low[a] = box.min(a);
        scale[a] = size / std::max(box.max(a) - box.min(a), 1e-300);
      }
      cells = std::vector<std::atomic<Cell*>>(static_cast<std::size_t>(size) * size * size);
    }
    std::atomic<Cell*>& slot(const detail::Point3& p) {
      std::size_t at = 0;
      for (int a = 0; a < 3; ++a) {
        const double t = (p[a] - low[a]) * scale[a];
        const int k = t > 0 ? static_cast<int>(std::min(t, size - 0.5)) : 0;  // NaN and outside points clamp to the border
        at = at * static_cast<std::size_t>(size) + static_cast<std::size_t>(k);
      }
      return cells[at];
    }
    int size = 1;
    double low[3] = {0, 0, 0}, scale[3] = {1, 1, 1};
    std::vector<std::atomic<Cell*>> cells = std::vector<std::atomic<Cell*>>(1);
  };

  static Cell_handle handle(Cell* cell) { return Triangulation::Triangulation_data_structure::Cell_range::s_iterator_to(*cell); }
  static double squared_distance_to_cell(const Triangulation& tr, const detail::Point3& p, Cell* cell) {
    const int v = tr.is_infinite(cell->vertex(0)) ? 1 : 0;
    return CGAL::squared_distance(p, cell->vertex(v)->point());
  }

  mutable Level levels_[2];
  mutable std::atomic<Cell*> last_{nullptr};
};

class PoissonSurface final : public ImplicitSurface {
 public:
  /// The function is solved on the samples scaled by `scale` (see
  /// PoissonOptions::screening) and evaluated at scale * p.
  PoissonSurface(std::vector<PointWithNormal> samples, double scale, bool start_cell_grid, const std::vector<Vec3>& extra_vertices)
      : start_cell_grid_(start_cell_grid),
        scale_(scale),
        samples_(std::move(samples)),
        scaled_(scaled_points(samples_, scale)),
        function_(scaled_.begin(), scaled_.end(), CGAL::First_of_pair_property_map<PointWithNormal>(),
                  CGAL::Second_of_pair_property_map<PointWithNormal>()) {
    scaled_ = {};  // CGAL keeps its own copy in the triangulation
    // As Steiner vertices, the kind CGAL's own refinement adds: unknowns of
    // the solve with no normal and no pull towards 0. The function exposes
    // its triangulation read-only; inserting before the solve is what its
    // refinement does itself.
    auto& triangulation = const_cast<Triangulation&>(function_.tr());
    Cell_handle hint;
    for (const Vec3& v : extra_vertices) {
      const Triangulation::Point_with_normal p(detail::to_cgal(scale * v));
      hint = triangulation.insert(p, Triangulation::STEINER, hint, CGAL::Poisson_visitor())->cell();
    }
  }

  bool solve() {
    // CGAL's default runs conjugate gradients to machine precision (387
    // iterations on fandisk 200k); a relative residual of 1e-6 takes 189
    // and moves the function by 1e-7 where it is 0.035 (half the solve time).
    using Matrix = CGAL::Eigen_sparse_symmetric_matrix<double>::EigenType;
    CGAL::Eigen_solver_traits<Eigen::ConjugateGradient<Matrix>> solver;
    solver.solver().setTolerance(1e-6);
    if (!function_.compute_implicit_function(solver)) return false;
    if (start_cell_grid_) start_cells_.build(function_.tr());
    return true;
  }
  const std::vector<PointWithNormal>& samples() const { return samples_; }
  double value(const Vec3& p) const override {
    const detail::Point3 q = detail::to_cgal(scale_ * p);
    return sign_ * (start_cell_grid_ ? start_cells_.value(function_.tr(), q) : function_(q));
  }
  /// CGAL orients the function by an inner point it finds itself; on an open
  /// scene (a street seen from one side) that point can lie outside and the
  /// whole function comes out inverted against consistent normals. Flipped
  /// here, with an inner point taken behind a sample; false (and unchanged)
  /// when no such point is found.
  bool flip() {
    sign_ = -sign_;
    const double h = 1e-3 * bounding_radius();
    const std::size_t stride = std::max<std::size_t>(1, samples_.size() / 500);
    for (std::size_t i = 0; i < samples_.size(); i += stride) {
      const Vec3 n = detail::from_cgal(samples_[i].second);
      const Vec3 q = detail::from_cgal(samples_[i].first) - (h / norm(n)) * n;
      if (value(q) < 0) {
        inside_ = q;
        has_inside_ = true;
        return true;
      }
    }
    sign_ = -sign_;
    return false;
  }
  Vec3 bounding_center() const override { return (1 / scale_) * detail::from_cgal(function_.bounding_sphere().center()); }
  double bounding_radius() const override { return std::sqrt(function_.bounding_sphere().squared_radius()) / scale_; }
  Vec3 inside_point() const override { return has_inside_ ? inside_ : (1 / scale_) * detail::from_cgal(function_.get_inner_point()); }
  std::size_t sample_count() const override { return samples_.size(); }

 private:
  static std::vector<PointWithNormal> scaled_points(const std::vector<PointWithNormal>& samples, double scale) {
    std::vector<PointWithNormal> scaled;
    scaled.reserve(samples.size());
    for (const PointWithNormal& s : samples)
      scaled.emplace_back(detail::Point3(scale * s.first.x(), scale * s.first.y(), scale * s.first.z()), s.second);
    return scaled;
  }

  bool start_cell_grid_;
  double scale_;
  std::vector<PointWithNormal> samples_;
  std::vector<PointWithNormal> scaled_;
  Function function_;
  StartCellGrid start_cells_;
  double sign_ = 1;
  Vec3 inside_{0, 0, 0};
  bool has_inside_ = false;
};

/// True when no four samples span a volume (exact predicates).
bool all_coplanar(const std::vector<PointWithNormal>& samples) {
  const detail::Point3& a = samples[0].first;
  std::size_t i = 1;
  while (i < samples.size() && samples[i].first == a) ++i;
  if (i == samples.size()) return true;
  const detail::Point3& b = samples[i].first;
  while (i < samples.size() && CGAL::collinear(a, b, samples[i].first)) ++i;
  if (i == samples.size()) return true;
  const detail::Point3& c = samples[i].first;
  for (; i < samples.size(); ++i)
    if (CGAL::orientation(a, b, c, samples[i].first) != CGAL::COPLANAR) return false;
  return true;
}

/// Share of (up to 500, evenly spread) samples where the function grows along
/// the oriented normal, as it must when it is negative inside.
double normal_agreement(const PoissonSurface& surface) {
  const auto& samples = surface.samples();
  const double h = 1e-3 * surface.bounding_radius();
  const std::size_t stride = std::max<std::size_t>(1, samples.size() / 500);
  std::size_t tested = 0, agree = 0;
  for (std::size_t i = 0; i < samples.size(); i += stride) {
    const Vec3 p = detail::from_cgal(samples[i].first);
    Vec3 n = detail::from_cgal(samples[i].second);
    n = (1.0 / norm(n)) * n;
    ++tested;
    agree += surface.value(p + h * n) > surface.value(p - h * n);
  }
  return static_cast<double>(agree) / static_cast<double>(tested);
}

/// Moves each sample by up to `amount` in each coordinate (fixed seed).
std::vector<PointWithNormal> jittered(std::vector<PointWithNormal> samples, double amount) {
  std::mt19937_64 generator(1);
  std::uniform_real_distribution<double> offset(-amount, amount);
  for (PointWithNormal& s : samples) {
    const double dx = offset(generator), dy = offset(generator), dz = offset(generator);
    s.first = detail::Point3(s.first.x() + dx, s.first.y() + dy, s.first.z() + dz);
  }
  return samples;
}

}  // namespace

void PoissonOptions::check() const {
  if (!(screening >= 0 && screening <= 1e6))
    throw InvalidArgument("Poisson screening weight must be in [0, 1e6] (got " + format_number(screening) + ")");
  if (!(average_spacing >= 0 && std::isfinite(average_spacing)))
    throw InvalidArgument("Poisson average spacing must be finite and non-negative (got " + format_number(average_spacing) + ")");
}

std::unique_ptr<ImplicitSurface> poisson_surface(const PointSet& points, const PoissonOptions& options, const Progress& progress,
                                                 PoissonDiagnostics* diagnostics) {
  options.check();
  check_point_set(points, 4, "Poisson reconstruction");
  if (!points.has_normals()) throw InvalidArgument("Poisson reconstruction needs oriented normals");
  std::vector<PointWithNormal> samples;
  samples.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& n = points.normals[i];
    if (!(norm(n) > 0)) continue;  // a zero normal carries no orientation
    samples.emplace_back(detail::to_cgal(points.points[i]), detail::to_cgal_vector(n));
  }
  if (samples.size() < 4) throw InvalidInput("Poisson reconstruction: fewer than 4 points have a usable normal");
  if (all_coplanar(samples))  // CGAL's Poisson needs a 3D Delaunay triangulation
    throw InvalidInput("Poisson reconstruction: all points lie on one plane (or line); a surface cannot be reconstructed from a flat cloud");
  report_progress(progress, "poisson", 0.0);
  double scale = 1;
  if (options.screening > 0) {
    const double spacing = options.average_spacing > 0 ? options.average_spacing : average_spacing(points);
    // Clamped: a spacing of 0 (or nearly, all points doubled) must not blow
    // the coordinates up; recentred clouds have diagonals in [2^-20, 2^20].
    if (spacing > 0) scale = std::clamp(kCgalPoissonLambda / (options.screening * spacing), 1e-9, 1e9);
  }
  auto surface = std::make_unique<PoissonSurface>(samples, scale, options.start_cell_grid, options.extra_vertices);
  if (!surface->solve()) throw NumericalFailure("Poisson reconstruction: the linear solver failed");
  // Samples on an exact sphere (1,000 points of a Fibonacci sphere fail,
  // 1,500 do not) make CGAL's Delaunay refinement of the Poisson domain
  // degenerate, and the function comes out with no consistent sign. Detected
  // by its gradient disagreeing with the normals at over a quarter of the
  // samples; solved again on samples moved by 1e-4, then 1e-3, of the
  // bounding radius (1e-5 is not enough), keeping the most consistent
  // function. Partly inconsistent normals also lower the agreement; jitter
  // does not help them.
  // A function that disagrees with nearly all normals (the negated one then
  // agrees with at least 95%) is inverted as a whole (see flip), not
  // inconsistent.
  auto agreement_of = [](PoissonSurface& f) {
    const double a = normal_agreement(f);
    return a <= 0.05 && f.flip() ? normal_agreement(f) : a;
  };
  double agreement = agreement_of(*surface);
  for (double jitter : {1e-4, 1e-3}) {
    if (agreement >= 0.75) break;
    auto retry = std::make_unique<PoissonSurface>(jittered(samples, jitter * surface->bounding_radius()), scale, options.start_cell_grid,
                                                  options.extra_vertices);
    if (!retry->solve()) continue;
    const double retry_agreement = agreement_of(*retry);
    if (retry_agreement > agreement) std::tie(surface, agreement) = std::make_pair(std::move(retry), retry_agreement);
  }
  if (diagnostics) diagnostics->normal_agreement = agreement;
  if (agreement < 0.5)
    throw NumericalFailure("Poisson reconstruction: the implicit function disagrees with most normals (grows along " +
                           format_number(std::round(1000 * agreement) / 10) + "% of them; inconsistent normals, or a degenerate point set)");
  report_progress(progress, "poisson", 1.0);
  return surface;
}

}  // namespace sharpmesh
