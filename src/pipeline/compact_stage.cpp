// The compaction stage, beyond the thesis: the refined mesh's edges
// collapsed down to a facet budget or within a tolerance, its sharp edges
// kept (sharpmesh/compact.h; issue 37, docs/compactness.md).
#include "pipeline/stages.h"
#include "sharpmesh/compact.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::detail {

void compact(const PipelineInput& in, FitStage& stage, ReconstructResult& result) {
  const ReconstructOptions& options = in.options;
  if (!options.compaction.active() || result.mesh.faces.empty()) return;
  {
    StageTimer timer(result.stages, "decimation");
    try {
      result.decimation = decimate(result.mesh, result.meshing.feature_edges, options.compaction, in.progress);
    } catch (const InvalidInput&) {
      // A mesh the repairs left non-manifold is kept as it is, with the
      // budget reported missed: nothing the refinement made is lost.
      result.decimation.input_facets = result.decimation.output_facets = result.mesh.faces.size();
      result.decimation.budget_missed = true;
      return;
    }
  }
  StageTimer timer(result.stages, "data fit after decimation");
  stage.fit = fit_to_data(result.mesh, in.points.points, stage.normals, result.data_fit.off_data_distance);
  result.boundary_edges = count_boundary_edges(result.mesh);
}

}  // namespace sharpmesh::detail
