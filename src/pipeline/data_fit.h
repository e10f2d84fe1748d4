// Beyond the thesis: the reconstructed mesh checked against its own input
// points, and the normals of the points it leaves out flipped for a retry.
#pragma once

#include <cstdint>
#include <vector>

#include "sharpmesh/types.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh::detail {

struct DataFit {
  std::vector<std::uint32_t> off;  ///< input points farther than the given distance from the mesh
  /// Those of `off` whose normal points against the mesh's closest facet:
  /// inverted normals. Points off a rounded edge (a missed feature, or PIF)
  /// agree with it (normal . facet normal 0.3-0.9 on CGAL's cube and joint
  /// by PIF, 50k points); those of couplingdown's inverted hole wall mostly
  /// do not (median -0.49).
  std::vector<std::uint32_t> off_and_against;
  double max_distance = 0;         ///< of any input point to the mesh (0 without facets)
  /// Mesh vertices farther than the given distance from every input point:
  /// surface without data (a cap Poisson puts over a hole).
  std::size_t invented_vertices = 0;
};

/// `normals` may be empty (then off_and_against stays empty).
DataFit fit_to_data(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const std::vector<Vec3>& normals,
                    double off_distance);

/// Those of `ids` within `reach` of one of `near` (indices into `points`).
std::vector<std::uint32_t> within_reach(const std::vector<Vec3>& points, const std::vector<std::uint32_t>& ids,
                                        const std::vector<std::uint32_t>& near, double reach);

/// Flips the normals at `ids` and at the points within `radius` of one of
/// them whose normal points the same way (within 45 degrees): the patch an
/// inverted normal belongs to. Returns the number of flips.
std::size_t flip_around(PointSet& oriented, const std::vector<std::uint32_t>& ids, double radius);

}  // namespace sharpmesh::detail
