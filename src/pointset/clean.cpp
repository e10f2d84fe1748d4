// The point-set toolbox as one pipeline, in the order of the thesis's
// Fig. A.2: outliers, simplification, smoothing, normals, orientation.
#include <cmath>

#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh {

void CleanOptions::check() const {
  if (outliers && !(outliers->percentage >= 0 && outliers->percentage <= 100))
    throw InvalidArgument("the outlier percentage must be in [0, 100]");
  if (outliers_sigma && !(outliers_sigma->sigmas > 0)) throw InvalidArgument("the outlier sigmas must be positive");
  if (grid_cell && !(*grid_cell > 0 && std::isfinite(*grid_cell)))
    throw InvalidArgument("the grid cell must be a positive multiple of the average spacing");
  if (random_percentage && !(*random_percentage >= 0 && *random_percentage <= 100))
    throw InvalidArgument("the random simplification percentage must be in [0, 100]");
  if (smoothing && smoothing->k < 6) throw InvalidArgument("jet smoothing needs at least 6 neighbours to fit a quadric");
  if (crease_aware_normals && !normals) throw InvalidArgument("crease-aware normals are signed like estimated ones: estimate normals too");
}

CleanStats clean_point_set(PointSet& points, const CleanOptions& options, const Progress& progress) {
  options.check();
  CleanStats stats;
  stats.input = points.size();
  if (options.outliers) {
    StageTimer stage(stats.stages, "outliers");
    stats.removed_outliers = remove_outliers_percentage(points, *options.outliers, progress);
  }
  if (options.outliers_sigma) {
    StageTimer stage(stats.stages, "outliers-sigma");
    stats.removed_outliers_sigma = remove_outliers_sigma(points, *options.outliers_sigma, progress);
  }
  if (options.grid_cell) {
    StageTimer stage(stats.stages, "grid simplification");
    stats.removed_grid = grid_simplify(points, *options.grid_cell * average_spacing(points, 6, progress));
  }
  if (options.random_percentage) {
    StageTimer stage(stats.stages, "random simplification");
    stats.removed_random = random_simplify(points, *options.random_percentage, options.seed);
  }
  if (options.smoothing) {
    StageTimer stage(stats.stages, "smoothing");
    jet_smooth(points, *options.smoothing, progress);
  }
  if (options.normals) {
    StageTimer stage(stats.stages, "normals");
    estimate_normals(points, *options.normals, progress);
  }
  if (options.orientation != CleanOptions::Orientation::None) {
    StageTimer stage(stats.stages, "orientation");
    if (options.orientation == CleanOptions::Orientation::CgalMst)
      stats.unoriented_removed = orient_normals_mst(points, {options.orient_k, true}, progress);
    else
      stats.orientation_components = orient_normals_tangent_mst(points, options.orient_k, progress);
    if (options.orientation == CleanOptions::Orientation::TangentMst && options.repair_enclosed && points.size() >= 4)
      stats.enclosed_flipped = repair_enclosed_normals(points, average_spacing(points));
  }
  // After the orientation: crease-aware normals turn by 90 degrees across a
  // crease, and the MST would lose their sign there.
  if (options.crease_aware_normals) {
    StageTimer stage(stats.stages, "crease-aware normals");
    std::vector<std::uint32_t> all(points.size());
    for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    estimate_shifted_normals_at(points, all, *options.crease_aware_normals);  // signed like the estimated normals
  }
  if (points.empty()) throw InvalidInput("no point is left after cleaning");
  stats.output = points.size();
  return stats;
}

}  // namespace sharpmesh
