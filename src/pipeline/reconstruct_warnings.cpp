// What a reconstruction's user should look at (ReconstructResult::warnings):
// decided here once, printed by the CLI, listed in Python's report.
#include <cstdio>

#include "pipeline/stages.h"

namespace sharpmesh::detail {
namespace {

std::string printed(const char* format, double a, double b = 0, double c = 0) {
  char text[400];
  std::snprintf(text, sizeof text, format, a, b, c);
  return text;
}

}  // namespace

std::vector<Warning> reconstruct_warnings(const ReconstructResult& r, const ReconstructOptions& options) {
  std::vector<Warning> out;
  const double spacing = r.average_spacing > 0 ? r.average_spacing : 1.0;
  // Points off a rounded edge agree with the mesh (PIF rounds every edge):
  // only those against it are worth a warning.
  if (r.data_fit.off_data_against > 0)
    out.push_back({"points_off_mesh",
                   printed("%.0f input points lie more than %.2f average spacings from the mesh with normals against it (farthest "
                           "point %.2f): the surface may have closed a hole or a slot there",
                           double(r.data_fit.off_data_against), r.data_fit.off_data_distance / spacing, r.data_fit.max_data_distance / spacing)});
  if (r.meshing.refinement_runaway)
    out.push_back({"refinement_runaway",
                   "refinement was still adding vertices long after the expected count and was ended; check the mesh's topology"});
  if (r.meshing.protection_stopped)
    out.push_back({"protection_stopped", printed("the protection of the feature polylines ran past its budget of %g queries per "
                                                 "polyline point and was stopped; the mesh was made without it (raise protection_budget)",
                                                 options.protection_budget)});
  if (r.meshing.refinement_stalled)
    out.push_back({"refinement_stalled", "refinement stopped adding vertices and was ended early; check the mesh's topology"});
  if (r.repairs.intersection_repair.remaining_pairs > 0)
    out.push_back({"self_intersecting", printed("%.0f pairs of facets still cross after the repair", double(r.repairs.intersection_repair.remaining_pairs))});
  if (r.decimation.budget_missed)
    out.push_back({"facet_budget_missed",
                   printed("the mesh kept %.0f facets, above the budget of %.0f: every further collapse would move a corner, leave a "
                           "sharp edge, fold a facet or break the tolerance",
                           double(r.decimation.output_facets), double(options.compaction.facets))});
  if (r.normals.normal_origin == NormalOrigin::InputReoriented)
    out.push_back({"input_normals_reoriented",
                   printed("the input's normal signs are inconsistent (%.0f%% agree with a consistent orientation); re-oriented by MST",
                           100 * r.normals.input_normal_agreement)});
  if (r.normals.input_normals_unusable)
    out.push_back({"input_normals_unusable", "fewer than half of the input's normals are non-zero; normals estimated instead"});
  return out;
}

}  // namespace sharpmesh::detail
