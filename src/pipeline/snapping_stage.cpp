// The snapping stage, beyond the thesis: mesh vertices onto the feature
// corners and onto the data points the mesh misses (snapping.cpp).
#include "pipeline/stages.h"
#include "sharpmesh/features.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh::detail {

// Beyond the thesis: vertices onto the corners and data points the mesh
// misses by more than the balls and the refinement could close (after the
// retry decision, which must see the misses). With extracted features
// only: the PIF baseline stays the thesis's. Onto data points only on
// clean clouds: a noisy point is no better than the mesh
// (docs/design-notes.md, snapping).
void snap_to_data(const PipelineInput& in, FitStage& stage, ReconstructResult& result) {
  const ReconstructOptions& options = in.options;
  const double noise = options.feature_mode == FeatureMode::Extract ? result.features.noise_estimate : 0.0;
  const double off_distance = result.data_fit.off_data_distance;
  if (options.snap_vertices && options.feature_mode == FeatureMode::Extract && !result.mesh.faces.empty()) {
    std::vector<Vec3> corners;
    for (const Junction& j : result.features.graph.junctions)
      if (j.degree >= 2) corners.push_back(j.position);
    const bool clean = result.features.denoise_passes == 0 && noise < kCleanNoiseRatio * result.average_spacing;
    SnappingOptions snapping;
    const ReconstructTuning& tuning = options.tuning;
    const double allowance = tuning.noise_deviations * noise;
    snapping.max_move = tuning.snap_max_move * result.average_spacing + allowance;
    snapping.corner_present = tuning.snap_corner_distance * result.average_spacing + allowance;
    snapping.data_present = tuning.snap_data_distance * result.average_spacing + allowance;
    snapping.support_radius = tuning.snap_support_radius * result.average_spacing;
    snapping.points_are_targets = clean;
    snapping.average_spacing = result.average_spacing;
    if (clean) snapping.point_normals = stage.normals;
    {
      StageTimer timer(result.stages, "snapping");
      const SnappingStats stats = snap_to_corners_and_data(result.mesh, corners, in.points.points, snapping);
      result.repairs.snapped_corners = stats.corners;
      result.repairs.snapped_to_data = stats.data_points;
      result.repairs.snapped_off_data = stats.off_data_vertices;
      result.repairs.unsnapped_vertices = stats.undone;
    }
    if (result.repairs.snapped_corners + result.repairs.snapped_to_data + result.repairs.snapped_off_data > result.repairs.unsnapped_vertices) {
      StageTimer timer(result.stages, "data fit after snapping");
      stage.fit = fit_to_data(result.mesh, in.points.points, stage.normals, off_distance);
    }
  }
}

}  // namespace sharpmesh::detail
