// The point-cloud-to-mesh pipeline of Chapter 7. The PIF baseline (7.3.1):
// normals (if missing), Poisson implicit function, Delaunay refinement with
// the 7.3.2 criteria derived from one parameter delta.
#pragma once

#include <string>
#include <vector>

#include "sharpmesh/meshing.h"
#include "sharpmesh/pointset.h"
#include "sharpmesh/progress.h"
#include "sharpmesh/timing.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

struct ReconstructOptions {
  double delta = 3.5;  ///< d' = delta * avg (7.3.2; Fig. 7.10a)
  int spacing_k = 6;   ///< avg = mean distance to the 6 nearest neighbours (7.3.2)
  NormalEstimationOptions normals;       ///< used when the input has no normals
  NormalOrientationOptions orientation;  ///< used when the input has no normals
  bool recompute_normals = false;        ///< ignore normals present in the input
  std::size_t max_facets = 5'000'000;
  std::uint32_t seed = 0;
  void check(std::size_t n) const;
};

struct ReconstructResult {
  SurfaceMesh mesh;
  double average_spacing = 0;
  double d_prime = 0;
  double estimated_facets = 0;
  RefinementCriteria criteria;
  std::size_t input_points = 0;
  std::size_t used_points = 0;       ///< after removing unorientable points
  bool normals_estimated = false;
  std::vector<StageTiming> stages;
};

/// Surface area suggested by n uniform samples of the given average spacing (k = 6).
double estimated_area_from_spacing(std::size_t n, double average_spacing);

ReconstructResult reconstruct(const PointSet& input, const ReconstructOptions& options = {},
                              const Progress& progress = {});

}  // namespace sharpmesh
