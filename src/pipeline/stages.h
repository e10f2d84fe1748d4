// The stages of the Chapter 7 pipeline, one file each, which reconstruct.cpp
// composes: input normals check -> normals (7.4 and the orientation
// repairs) -> implicit function (Poisson, its sign repair) -> surface
// meshing (7.3.2 with the open-surface trim) -> data fit (retries against
// the input) -> snapping -> compaction (with a facet budget or a
// tolerance). Each stage writes its counts into the ReconstructResult it is
// given.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/data_fit.h"
#include "sharpmesh/implicit.h"
#include "sharpmesh/reconstruct.h"

namespace sharpmesh::detail {

/// What every stage reads: the recentred input without duplicates, the
/// options and the progress callback.
struct PipelineInput {
  const PointSet& points;
  const ReconstructOptions& options;
  const Progress& progress;
};

// ---- input_normals.cpp -------------------------------------------------

/// How the normals a file carried were taken (check_input_normals).
enum class InputNormals { Used, Reoriented, Unusable };

/// Makes usable normals unit and re-signs inconsistent ones after the
/// oriented PCA normals; `agreement` gets the share of agreeing signs.
InputNormals check_input_normals(PointSet& cloud, const ReconstructOptions& options, double& agreement, const Progress& progress);

// ---- normals_stage.cpp -------------------------------------------------

/// Exterior signs for the tangent MST to grow from (0: no vote).
std::vector<signed char> occupancy_anchors(const PointSet& cloud, double average_spacing, double noise, int k);

/// The input with oriented normals: CVCM (7.4) or estimated, oriented by the
/// anchored tangent MST (A.8) and repaired; counts go into `result`.
PointSet oriented_normals(const PipelineInput& in, bool from_cvcm, ReconstructResult& result);

// ---- implicit_stage.cpp ------------------------------------------------

/// Poisson solves with the pipeline's screening, thinning and thin-part
/// vertices (the latter found once: later solves flip normal signs only,
/// which leaves the half-way points where they are).
class ImplicitSolver {
 public:
  ImplicitSolver(const PipelineInput& in, ReconstructResult& result) : in_(in), result_(result) {}
  std::unique_ptr<ImplicitSurface> solve(const PointSet& oriented, PoissonDiagnostics& diagnostics);
  /// The sign repair: normals the function contradicts are flipped and the
  /// function solved again. Returns the number of flips kept.
  std::size_t repair_signs(PointSet& oriented, std::unique_ptr<ImplicitSurface>& surface, PoissonDiagnostics& diagnostics);

 private:
  const PipelineInput& in_;
  ReconstructResult& result_;
  std::optional<std::vector<Vec3>> thin_vertices_;
};

/// Points a repair (the sign repair, the data-fit retry) needs before it
/// solves Poisson again (ReconstructTuning::repair_min_points, repair_one_point_in).
std::size_t enough_for_a_repair(std::size_t points, const ReconstructTuning& tuning);

/// An implicit function with the oriented points it was solved with.
struct ImplicitStage {
  std::unique_ptr<ImplicitSurface> surface;
  PoissonDiagnostics diagnostics;
  PointSet oriented;
};

/// Normals, Poisson and the sign repair, with the jet fallback for CVCM
/// normals the function disagrees with.
ImplicitStage solve_implicit(const PipelineInput& in, ImplicitSolver& solver, bool needs_normals, bool cvcm,
                             NormalOrigin estimated, ReconstructResult& result);

// ---- surface_stage.cpp -------------------------------------------------

/// Distance beyond which an input point is off the mesh, or a mesh
/// component off the data.
double off_data_distance(const ReconstructResult& r, const ReconstructOptions& options);

/// Restriction, seeds, refinement with protecting balls, flattening and the
/// open-surface trim of one implicit function into `out.mesh`. Stage names
/// carry `retry_prefix`.
void mesh_surface(const PipelineInput& in, std::unique_ptr<ImplicitSurface> function, const PointSet& normals,
                  double expected_facets, ReconstructResult& out, const std::string& retry_prefix);

// ---- data_fit_stage.cpp ------------------------------------------------

/// The mesh's fit to its input after the stage, with the normals of the
/// implicit function the mesh kept.
struct FitStage {
  DataFit fit;
  std::vector<Vec3> normals;
};

/// Checks the mesh against its input points and retries with the normals of
/// the points off and against it flipped; keeps a retry that fits better.
FitStage fit_and_retry(const PipelineInput& in, ImplicitSolver& solver, const PointSet& oriented, double expected_facets,
                       ReconstructResult& result);

// ---- snapping_stage.cpp ------------------------------------------------

/// Vertices onto the corners and data points the mesh misses, then the fit
/// measured again.
void snap_to_data(const PipelineInput& in, FitStage& stage, ReconstructResult& result);

// ---- compact_stage.cpp -------------------------------------------------

/// With a facet budget or a tolerance: the mesh's edges collapsed with its
/// sharp edges kept (sharpmesh/compact.h), then the fit measured again.
void compact(const PipelineInput& in, FitStage& stage, ReconstructResult& result);

/// The warnings of a finished reconstruction (ReconstructResult::warnings).
std::vector<Warning> reconstruct_warnings(const ReconstructResult& result, const ReconstructOptions& options);

}  // namespace sharpmesh::detail
