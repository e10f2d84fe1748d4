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
};

/// Poisson surface reconstruction (Kazhdan et al. 2006) by CGAL's
/// Poisson_reconstruction_function. Needs oriented normals.
struct PoissonOptions {
  void check() const {}
};
std::unique_ptr<ImplicitSurface> poisson_surface(const PointSet& oriented_points, const PoissonOptions& options = {},
                                                 const Progress& progress = {});

}  // namespace sharpmesh
