// The generalized winding number of an oriented point cloud (beyond the
// thesis; Barill et al., "Fast winding numbers for soups and clouds", 2018):
// w(q) = sum_i a_i (p_i - q) . n_i / (4 pi |p_i - q|^3), about 1 inside a
// consistently oriented closed surface and 0 outside. Evaluated with a
// Barnes-Hut octree: far clusters act as one dipole.
#pragma once

#include <cstdint>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh::detail {

class WindingNumber {
 public:
  /// `areas`: the surface area each point stands for. `softening`: a length
  /// added in quadrature to near distances, so that a query a spacing or two
  /// from the cloud does not see single points. The vectors must outlive it.
  WindingNumber(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, const std::vector<double>& areas,
                double softening);
  double at(const Vec3& q) const;

 private:
  struct Node {
    Vec3 centre{0, 0, 0};  ///< area-weighted centroid
    Vec3 dipole{0, 0, 0};  ///< sum of a_i n_i
    double radius = 0;     ///< of the points around the centroid
    std::uint32_t begin = 0, end = 0;
    std::uint32_t first_child = 0, child_count = 0;
  };
  std::uint32_t build(std::uint32_t begin, std::uint32_t end, int depth);

  const std::vector<Vec3>& points_;
  const std::vector<Vec3>& normals_;
  const std::vector<double>& areas_;
  double softening2_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> child_lists_;
};

/// The contribution of the points `ids` alone at q (direct sum, softened).
double winding_number_of(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, const std::vector<double>& areas,
                         const std::vector<std::uint32_t>& ids, const Vec3& q, double softening);

}  // namespace sharpmesh::detail
