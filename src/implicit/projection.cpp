// Projection onto an implicit surface by Newton steps along the gradient, to
// measure how far a sharp-feature polyline lies from the smooth implicit
// surface (the gap of thesis 7.5, Fig. 7.18).
#include <algorithm>
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

namespace {

/// The root on the segment [lo, hi], whose ends the function's sign tells apart.
Vec3 bisect(const ImplicitSurface& surface, Vec3 lo, double flo, Vec3 hi, double h) {
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
  return 0.5 * (lo + hi);
}

/// Where Newton stalls, the nearest sign change along 26 directions (the
/// axes, face and cube diagonals) on spheres of doubling radius from
/// max_step / 2: a surface point, so an upper bound on the distance (exact
/// when the nearest surface point lies along one of the directions).
/// Stronger screening made CGAL's cube at 50k points stall Newton next to an
/// edge (the function's cells are smallest there) and left 0.085 of the edge
/// unprotected.
bool search_sign_change(const ImplicitSurface& surface, const Vec3& p, double fp, double max_step, double max_distance, double h,
                        Vec3& projection) {
  for (double radius = std::min(0.5 * max_step, max_distance);; radius = std::min(2 * radius, max_distance)) {
    double nearest = std::numeric_limits<double>::infinity();
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int k = -1; k <= 1; ++k) {
          if (i == 0 && j == 0 && k == 0) continue;
          Vec3 d{double(i), double(j), double(k)};
          d = (radius / norm(d)) * d;
          if ((surface.value(p + d) < 0) == (fp < 0)) continue;
          const Vec3 root = bisect(surface, p, fp, p + d, h);
          if (distance(root, p) < nearest) nearest = distance(root, p), projection = root;
        }
    if (nearest <= max_distance) return true;
    if (radius >= max_distance) return false;
  }
}

/// Newton steps along the gradient; false where they stall or stray beyond max_distance.
bool newton_projection(const ImplicitSurface& surface, const Vec3& p, double fp, double max_step, double max_distance, double h,
                       Vec3& projection) {
  Vec3 x = p;
  double fx = fp;
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
      projection = bisect(surface, x, fx, next, h);
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

}  // namespace

bool project_onto_surface(const ImplicitSurface& surface, const Vec3& p, double max_step, double max_distance, double h,
                          Vec3& projection, double stalled_search) {
  if (!(max_step > 0) || !(max_distance > 0)) return false;
  const double fp = surface.value(p);
  if (newton_projection(surface, p, fp, max_step, max_distance, h, projection)) return true;
  return stalled_search > 0 && search_sign_change(surface, p, fp, max_step, std::min(max_distance, stalled_search), h, projection);
}

}  // namespace sharpmesh
