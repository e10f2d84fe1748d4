// The data-fit stage, beyond the thesis: the mesh checked against its own
// input points, and a retry with the normals of the points it leaves out
// flipped (data_fit.cpp holds the measures).
#include <algorithm>
#include <optional>

#include "pipeline/stages.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::detail {

// Beyond the thesis (docs/design-notes.md, data-fit retry): the mesh
// checked against its own data. Where a patch of normals stays inverted
// through the sign repair (it agrees with a function that is wrong there: a
// hole whose wall the MST inverted, closed by Poisson), the input points
// lie off the mesh with normals against its facets. Their normals, and
// those within 1.5 spacings that point the same way, are flipped, Poisson
// solved and repaired again and the surface meshed again; the new mesh is
// kept when a quarter fewer points are off and against it, no more off in
// all, and none farther. Points off a rounded edge (PIF, a missed feature)
// agree with the mesh and start no retry, which distance alone would.
// The fit is measured whether or not a retry may run: the report has it.
FitStage fit_and_retry(const PipelineInput& in, ImplicitSolver& solver, const PointSet& oriented, double expected_facets,
                       ReconstructResult& result) {
  const ReconstructOptions& options = in.options;
  const double off_distance = off_data_distance(result, options);
  result.data_fit.off_data_distance = off_distance;
  DataFit fit;
  std::vector<Vec3> retry_normals;  // the normals of the mesh kept, when a retry's
  {
    StageTimer timer(result.stages, "data fit");
    fit = fit_to_data(result.mesh, in.points.points, oriented.normals, off_distance);  // oriented: the input's points
  }
  const bool may_retry = options.refit_off_data && options.repair_normal_signs && options.check_input_normals;
  const std::size_t worth_a_retry = enough_for_a_repair(oriented.size(), options.tuning);
  result.data_fit.off_data_points_before_retry = fit.off.size();
  if (may_retry && fit.off_and_against.size() >= worth_a_retry) {
    // Two flip sets: the points off and against the mesh, and all the
    // points off it within 3 spacings of those (on a curved wall part of
    // an inverted patch agrees with the wrong facets; which set is better
    // depends on the part, so both are tried).
    std::vector<std::vector<std::uint32_t>> flip_sets{fit.off_and_against};
    std::vector<std::uint32_t> region = within_reach(in.points.points, fit.off, fit.off_and_against, options.tuning.retry_reach * result.average_spacing);
    if (region.size() > fit.off_and_against.size()) flip_sets.push_back(std::move(region));
    std::vector<StageTiming> stages = result.stages;
    std::optional<ReconstructResult> best;
    DataFit best_fit;
    for (std::size_t attempt = 0; attempt < flip_sets.size(); ++attempt) {
      ReconstructResult retry = result;
      retry.stages.clear();
      const std::string prefix = "retry " + std::to_string(attempt + 1) + ": ";
      PointSet flipped = oriented;
      const std::size_t flips = flip_around(flipped, flip_sets[attempt], 1.5 * result.average_spacing);
      try {
        PoissonDiagnostics retry_diagnostics;
        std::unique_ptr<ImplicitSurface> function;
        {
          StageTimer timer(retry.stages, prefix + "poisson and sign repair");
          function = solver.solve(flipped, retry_diagnostics);
          retry.normals.sign_repaired_normals = result.normals.sign_repaired_normals + solver.repair_signs(flipped, function, retry_diagnostics);
        }
        retry.implicit.poisson_points = function->sample_count();
        retry.implicit.normal_agreement = retry_diagnostics.normal_agreement;
        retry.implicit.thin_points = 0;
        retry.repairs.flattened_vertices = retry.repairs.unflattened_vertices = 0;
        mesh_surface(in, std::move(function), flipped, expected_facets, retry, prefix);
        DataFit refit;
        {
          StageTimer timer(retry.stages, prefix + "data fit");
          refit = fit_to_data(retry.mesh, in.points.points, flipped.normals, off_distance);
        }
        stages.insert(stages.end(), retry.stages.begin(), retry.stages.end());
        // A quarter fewer inverted, no more off in all, and the farthest
        // point no farther (fewer inverted points alone can come with a
        // worse Hausdorff distance); of two such, the one with fewer points
        // off and vertices without data.
        const bool better = 4 * refit.off_and_against.size() <= 3 * fit.off_and_against.size() && refit.off.size() <= fit.off.size() &&
                            refit.max_distance <= fit.max_distance;
        if (better && (!best || refit.off.size() + refit.invented_vertices < best_fit.off.size() + best_fit.invented_vertices)) {
          retry.data_fit.off_data_flips = flips;
          best = std::move(retry);
          best_fit = std::move(refit);
          retry_normals = std::move(flipped.normals);
        }
      } catch (const NumericalFailure&) {
        stages.insert(stages.end(), retry.stages.begin(), retry.stages.end());
      }
      ++result.data_fit.data_fit_retries;
      if (best && best_fit.off.empty() && best_fit.invented_vertices == 0) break;  // nothing left to improve
    }
    if (best) {
      best->data_fit.data_fit_retries = result.data_fit.data_fit_retries;
      result = std::move(*best);
      fit = std::move(best_fit);
    }
    result.stages = std::move(stages);
  }
  FitStage stage;
  stage.fit = std::move(fit);
  stage.normals = retry_normals.empty() ? oriented.normals : std::move(retry_normals);
  return stage;
}

}  // namespace sharpmesh::detail
