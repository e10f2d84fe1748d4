// Implicit surfaces (thesis 7.3): a function R^3 -> R whose zero level set
// approximates the data, negative inside.
#pragma once

#include <memory>

#include "sharpmesh/progress.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

class ImplicitSurface {
 public:
  virtual ~ImplicitSurface() = default;
  /// Function value at p; negative inside, positive outside. Not thread-safe.
  virtual double value(const Vec3& p) const = 0;
  /// A sphere that encloses the surface.
  virtual Vec3 bounding_center() const = 0;
  virtual double bounding_radius() const = 0;
  /// A point with a negative value (inside).
  virtual Vec3 inside_point() const = 0;
  /// Number of samples the function was fitted to (0 when not applicable).
  virtual std::size_t sample_count() const { return 0; }
};

/// Central-difference gradient of the function at p, with step h.
Vec3 implicit_gradient(const ImplicitSurface& surface, const Vec3& p, double h);

/// Closest point of the zero level set found by Newton steps along the
/// gradient (each step at most `max_step` long), starting from p. Returns
/// false when no root is reached within `max_distance` of p; `h` is the
/// finite-difference step. Where Newton stalls, the nearest sign change
/// within `stalled_search` along 26 directions is taken instead (0: none).
/// Used to measure the gap between sharp-feature polylines and the implicit
/// surface (thesis 7.5, Fig. 7.18).
bool project_onto_surface(const ImplicitSurface& surface, const Vec3& p, double max_step, double max_distance, double h,
                          Vec3& projection, double stalled_search = 0);

/// The surface restricted to the neighbourhood of the data, where it needs
/// it: when its zero set reaches farther than `max_distance` from every point
/// of `points` within `domain_radius` of the bounding centre (a sign change
/// between two grid nodes, cells of about max_distance and at most 96 per
/// side, both that far from the data: Poisson closing an open scan), the
/// function is made positive (outside) farther than max_distance from the
/// data, so that surface is cut. Otherwise the surface is returned unchanged:
/// on a closed surface the cut would only add an offset surface inside the
/// solid. Beyond the thesis (8.2).
struct Restriction {
  std::unique_ptr<ImplicitSurface> surface;
  bool applied = false;
};
Restriction restrict_to_points(std::unique_ptr<ImplicitSurface> surface, const std::vector<Vec3>& points, double max_distance,
                               double domain_radius);

/// Poisson surface reconstruction (Kazhdan et al. 2006) by CGAL's
/// Poisson_reconstruction_function. Needs oriented normals.
struct PoissonOptions {
  /// Start each point location from a grid of cells found before (default),
  /// instead of CGAL's walk from the last cell found. Same values; false is
  /// the baseline of bench/implicit_evaluation.
  bool start_cell_grid = true;
  /// Weight of CGAL's pull of the function towards 0 at the samples (its
  /// fixed lambda = 0.1 on the diagonal), relative to the Laplacian, in units
  /// where the average spacing is 1. CGAL's Laplacian entries scale with the
  /// length unit and lambda does not, so the same cloud in millimetres and in
  /// metres gave different surfaces (couplingdown 50k: 2.15 U scaled by 100,
  /// 1.58 U as published, 1.33 U scaled by 0.01); the samples are therefore
  /// scaled so this weight holds whatever the unit. 0 leaves them unscaled.
  double screening = 12;
  /// Average spacing of the samples, for `screening`; 0 = measured here (k = 6).
  double average_spacing = 0;
  /// Extra vertices of the function's triangulation, carrying no normal
  /// (beyond the thesis, issue 36). CGAL's function is linear on Delaunay
  /// cells of the samples, and its refinement leaves a plate or a slot a few
  /// spacings thick without an inner vertex: the function is then flat
  /// between the two sheets and its zero set wanders. A vertex half-way
  /// between them gives the function its inner value (thin_part_vertices).
  std::vector<Vec3> extra_vertices;
  void check() const;
};
/// How well the solved function fits the normals.
struct PoissonDiagnostics {
  /// Share of (up to 500) samples where the function grows along the normal:
  /// 1.000 on CGAL's CAD models with good normals, 0.75 with 25% flipped.
  double normal_agreement = 0;
};
std::unique_ptr<ImplicitSurface> poisson_surface(const PointSet& oriented_points, const PoissonOptions& options = {},
                                                 const Progress& progress = {}, PoissonDiagnostics* diagnostics = nullptr);

}  // namespace sharpmesh
