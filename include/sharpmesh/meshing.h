// Delaunay refinement surface meshing (Boissonnat & Oudot 2005; thesis 6.2.1, 7.3).
#pragma once

#include <cstdint>

#include "sharpmesh/implicit.h"
#include "sharpmesh/progress.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

/// Facet criteria of Section 6.2.1. A facet is bad when an angle is below
/// `angle`, when an edge is longer than `edge_length`, or when its centre is
/// farther than `distance` from the centre of its surface Delaunay ball.
/// The edge-length bound is enforced through the radius of the surface
/// Delaunay ball (radius <= edge_length / 2 bounds every edge by edge_length).
struct RefinementCriteria {
  double angle = 25.0;        ///< degrees, 7.3.2
  double edge_length = 0.0;   ///< l = 2 d', 7.3.2
  double distance = 0.0;      ///< d = 0.6 d', 7.3.2
  void check() const;
  /// The thesis's criteria for a protecting-ball spacing d' (7.3.2).
  static RefinementCriteria from_spacing(double d_prime);
};

struct ImplicitMeshingOptions {
  RefinementCriteria criteria;
  /// Refuse to start when the estimated facet count is above this (0: no limit).
  std::size_t max_facets = 5'000'000;
  std::uint32_t seed = 0;
  void check() const;
};

/// Meshes the zero level set of `surface` inside its bounding sphere. The
/// result is the boundary of the meshed volume: closed and, with the manifold
/// option of CGAL's Mesh_3, manifold.
SurfaceMesh mesh_implicit_surface(const ImplicitSurface& surface, const ImplicitMeshingOptions& options,
                                  const Progress& progress = {});

/// Rough facet count of a mesh with the given criteria on a surface of the
/// given area (equilateral facets of edge `edge_length`, halved to account
/// for curvature-driven refinement being rare on CAD data).
double estimate_facet_count(double area, const RefinementCriteria& criteria);

}  // namespace sharpmesh
