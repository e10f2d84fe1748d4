// Projection onto an implicit surface by Newton steps along the gradient, to
// measure how far a sharp-feature polyline lies from the smooth implicit
// surface (the gap of thesis 7.5, Fig. 7.18).
#include <cmath>
#include <limits>

#include "sharpmesh/implicit.h"

namespace sharpmesh {

Vec3 implicit_gradient(const ImplicitSurface& surface, const Vec3& p, double h) {
  Vec3 g{0, 0, 0};
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 a = p, b = p;
    a[axis] += h;
    b[axis] -= h;
    g[axis] = (surface.value(a) - surface.value(b)) / (2 * h);
  }
  return g;
}

bool project_onto_surface(const ImplicitSurface& surface, const Vec3& p, double max_step, double max_distance, double h,
                          Vec3& projection) {
  Vec3 x = p;
  double fx = surface.value(x);
  // The point nearest to the zero set by the first-order estimate |f| / |g|:
  // CGAL's Poisson function is piecewise linear, and next to a tetrahedron's
  // face Newton can bounce between two cells without the sign changing
  // (a cube edge of CGAL's cube-meshed at 50k points: f = 5e-6 after 40
  // steps, and the stretch was left unprotected).
  Vec3 best = x;
  double best_estimate = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < 40; ++iteration) {
    const Vec3 g = implicit_gradient(surface, x, h);
    const double gg = dot(g, g);
    if (!(gg > 0) || !std::isfinite(gg)) break;
    if (std::abs(fx) / std::sqrt(gg) < best_estimate) best_estimate = std::abs(fx) / std::sqrt(gg), best = x;
    Vec3 step = (-fx / gg) * g;
    const double length = norm(step);
    if (length > max_step) step = (max_step / length) * step;
    Vec3 next = x + step;
    double fnext = surface.value(next);
    // A sign change brackets the root: finish by bisection on the segment.
    if ((fx < 0) != (fnext < 0)) {
      Vec3 lo = x, hi = next;
      double flo = fx;
      for (int b = 0; b < 30 && distance(lo, hi) > 1e-3 * h; ++b) {
        const Vec3 mid = 0.5 * (lo + hi);
        const double fmid = surface.value(mid);
        if ((fmid < 0) == (flo < 0)) {
          lo = mid;
          flo = fmid;
        } else {
          hi = mid;
        }
      }
      projection = 0.5 * (lo + hi);
      return distance(projection, p) <= max_distance;
    }
    x = next;
    fx = fnext;
    if (distance(x, p) > max_distance) return false;
    if (length < 1e-3 * h) {
      projection = x;
      return true;
    }
  }
  if (!(best_estimate <= 1e-2 * max_step)) return false;
  projection = best;
  return distance(projection, p) <= max_distance;
}

}  // namespace sharpmesh
