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
  double max_distance = 0;         ///< of any input point to the mesh (0 without facets)
};

DataFit fit_to_data(const SurfaceMesh& mesh, const std::vector<Vec3>& points, double off_distance);

/// Flips the normals at `ids` and at the points within `radius` of one of
/// them whose normal points the same way (within 45 degrees): the patch an
/// inverted normal belongs to. Returns the number of flips.
std::size_t flip_around(PointSet& oriented, const std::vector<std::uint32_t>& ids, double radius);

}  // namespace sharpmesh::detail
