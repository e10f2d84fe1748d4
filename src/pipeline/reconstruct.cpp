// The Chapter 7 pipeline: features (7.2), normals (7.4), Poisson implicit
// function, Delaunay refinement with protecting balls (7.3.2); without
// features the PIF baseline (7.3.1).
#include "sharpmesh/reconstruct.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <variant>

#include "core/parallel.h"
#include "core/recentering.h"
#include "pipeline/stages.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/option_fields.h"
#include "sharpmesh/eval.h"

namespace sharpmesh {
namespace {

/// The input recentred (core/recentering.h) without duplicated points, and
/// the options in its frame.
struct LocalInput {
  detail::Recentering frame;
  PointSet points;
  ReconstructOptions options;
  std::size_t duplicates = 0;
};
LocalInput recentre(const PointSet& input, const ReconstructOptions& options);

PointSet prepare(PointSet input, const ReconstructOptions& options, const Progress& progress, ReconstructResult& result);
bool normals_from_cvcm(const ReconstructOptions& options);
ReconstructResult reconstruct_centred(PointSet input, const ReconstructOptions& options, const Progress& progress);
ReconstructResult reconstruct_world(const PointSet& input, const ReconstructOptions& options, const Progress& progress);

}  // namespace

const char* to_string(NormalOrigin origin) {
  switch (origin) {
    case NormalOrigin::Input:
      return "input";
    case NormalOrigin::InputReoriented:
      return "input (re-oriented)";
    case NormalOrigin::Cvcm:
      return "cvcm";
    case NormalOrigin::Jet:
      return "jet";
    case NormalOrigin::Pca:
      return "pca";
  }
  return "?";
}

void ReconstructTuning::check() const {
  // Every threshold is a non-negative count, ratio or length (its field table
  // is option_fields.cpp's), so a new one is checked without a line here.
  for (const OptionField<ReconstructTuning>& field : tuning_option_fields()) {
    const FieldValue value = field.get(*this);
    const double* real = std::get_if<double>(&value);
    const std::int64_t* count = std::get_if<std::int64_t>(&value);
    if ((real && !(*real >= 0 && std::isfinite(*real))) || (count && *count < 0))
      throw InvalidArgument(field.name + " must be a non-negative number (got " + format_field_value(value) + ")");
  }
  if (!(min_normal_agreement >= 0 && min_normal_agreement <= 1))
    throw InvalidArgument("min_normal_agreement is a fraction in [0, 1] (got " + format_number(min_normal_agreement) + ")");
  if (!(input_normal_consensus >= 0.5 && input_normal_consensus <= 1))
    throw InvalidArgument("input_normal_consensus is a fraction in [0.5, 1] (got " + format_number(input_normal_consensus) + ")");
  if (repair_one_point_in == 0) throw InvalidArgument("repair_one_point_in must be at least 1");
}

void ReconstructOptions::check(std::size_t n) const {
  tuning.check();
  if (threads < 0) throw InvalidArgument("threads must be 0 (every core) or a positive count (got " + format_number(threads) + ")");
  if (!(protection_budget >= 0) || !std::isfinite(protection_budget))
    throw InvalidArgument("protection budget must be a non-negative number of queries per polyline point (got " +
                          format_number(protection_budget) + ")");
  if (!(average_spacing >= 0) || !std::isfinite(average_spacing))
    throw InvalidArgument("average spacing must be 0 (measured) or positive (got " + format_number(average_spacing) + ")");
  if (!(delta > 0) || !std::isfinite(delta))
    throw InvalidArgument("delta must be positive (got " + format_number(delta) + ")");
  if (!(ball_radius > 0 && ball_radius <= 2))
    throw InvalidArgument("ball radius is a fraction of d' in (0, 2] (got " + format_number(ball_radius) + ")");
  if (feature_mode == FeatureMode::Extract) features.check();
  if (normal_source == NormalSource::Cvcm && feature_mode != FeatureMode::Extract)
    throw InvalidArgument("normals 'cvcm' need feature extraction (the CVCM is computed there, 7.4)");
  compaction.check();
  walls.check();
  if (!(trim_distance >= 0) || !std::isfinite(trim_distance))
    throw InvalidArgument("trim distance must be >= 0 (got " + format_number(trim_distance) + ")");
  if (!(poisson_spacing >= 0 && poisson_spacing <= 4))
    throw InvalidArgument("Poisson sample spacing is a fraction of d' in [0, 4] (got " + format_number(poisson_spacing) + ")");
  if (!(poisson_thinning >= 0 && poisson_thinning <= 2))
    throw InvalidArgument("Poisson thinning distance is a fraction of the average spacing in [0, 2] (got " + format_number(poisson_thinning) + ")");
  for (double w : {poisson_screening, poisson_screening_noisy}) {
    PoissonOptions poisson;
    poisson.screening = w;
    poisson.check();
  }
  if (!(data_seed_spacing == 0 || (data_seed_spacing >= 0.5 && data_seed_spacing <= 100)))
    throw InvalidArgument("data seed spacing is 0 or a fraction of d' in [0.5, 100] (got " + format_number(data_seed_spacing) + ")");
  if (spacing_k < 1 || static_cast<std::size_t>(spacing_k) >= n)
    throw InvalidArgument("spacing k = " + format_number(spacing_k) + " needs more than k points, the set has " + format_number(n));
}

double estimated_area_from_spacing(std::size_t n, double average_spacing) {
  // For uniform samples, the mean distance to the 6 nearest neighbours is
  // about 0.77 sqrt(area / n) (measured on CGAL's fandisk, cube and sphere).
  const double per_point = average_spacing / 0.77;
  return static_cast<double>(n) * per_point * per_point;
}

ReconstructResult reconstruct(const PointSet& input, const ReconstructOptions& options, const Progress& progress) {
  return detail::run_with_threads(options.threads, [&] { return reconstruct_world(input, options, progress); });
}

NormalsResult reconstruct_normals(const PointSet& input, const ReconstructOptions& options, const Progress& progress) {
  return detail::run_with_threads(options.threads, [&] {
    LocalInput local = recentre(input, options);
    local.options.max_facets = 0;  // no facets are made: a small delta is no reason to refuse
    ReconstructResult result;
    PointSet points = prepare(std::move(local.points), local.options, progress, result);
    if (result.normals.normals_estimated) {
      StageTimer timer(result.stages, "normals");
      points = detail::oriented_normals({points, local.options, progress}, normals_from_cvcm(local.options), result);
    }
    local.frame.to_world(points.points);
    local.frame.to_world(result.features);
    return NormalsResult{std::move(points), result.normals, std::move(result.features),
                         local.frame.length_to_world(result.average_spacing), std::move(result.stages)};
  });
}

namespace {

/// Recentres the input, runs the stages and brings the results back.
ReconstructResult reconstruct_world(const PointSet& input, const ReconstructOptions& options, const Progress& progress) {
  LocalInput local = recentre(input, options);
  const detail::Recentering& frame = local.frame;
  ReconstructResult result = reconstruct_centred(std::move(local.points), local.options, progress);
  result.input_points = input.size();
  result.duplicate_points = local.duplicates;
  frame.to_world(result.mesh.vertices);
  frame.to_world(result.features);
  frame.to_world(result.meshing.feature_edges);
  for (UncoveredGap& gap : result.meshing.uncovered) {
    frame.to_world(gap.center);
    gap.length = frame.length_to_world(gap.length);
    if (gap.gap > 0) gap.gap = frame.length_to_world(gap.gap);
  }
  result.meshing.max_gap = frame.length_to_world(result.meshing.max_gap);
  // Beyond the thesis: the output is valid every time it can be (issue
  // 36's gate). Refinement near thin parts, flattening and snapping check
  // their own moves, but the Delaunay refinement of a surface whose two
  // sides lie closer than its facets' size can itself cross them. Checked
  // on the world coordinates written out: the translation's rounding decides
  // touching facets either way. The data-fit counts are the mesh's before
  // the repair, which changes a few facets.
  if (options.repair_self_intersections && !result.mesh.faces.empty()) {
    StageTimer timer(result.stages, "self-intersection check");
    result.repairs.intersection_repair = repair_self_intersections(result.mesh, {}, progress);
    if (result.repairs.intersection_repair.rounds > 0) result.boundary_edges = count_boundary_edges(result.mesh);
  }
  for (double* length : {&result.average_spacing, &result.d_prime, &result.criteria.edge_length, &result.criteria.distance})
    *length = frame.length_to_world(*length);
  result.diagonal = bounding_box(input.points).diagonal();
  result.warnings = detail::reconstruct_warnings(result, options);
  return result;
}

LocalInput recentre(const PointSet& input, const ReconstructOptions& options) {
  check_point_set(input, 10, "reconstruction");
  options.check(input.size());
  LocalInput local{detail::Recentering(input.points), input, options, 0};
  local.frame.to_local(local.points.points);
  local.duplicates = remove_duplicate_points(local.points);
  check_point_set(local.points, 10, "reconstruction (after removing duplicated points)");
  options.check(local.points.size());
  local.frame.to_local(local.options.given_features);
  local.options.average_spacing = local.frame.length_to_local(options.average_spacing);
  return local;
}

/// Estimated normals CVCM (7.4) or jet/pca, as the options ask.
bool normals_from_cvcm(const ReconstructOptions& options) {
  return options.normal_source == NormalSource::Cvcm ||
         (options.normal_source == NormalSource::Automatic && options.feature_mode == FeatureMode::Extract);
}

NormalOrigin estimated_origin(const ReconstructOptions& options) {
  return options.normals.method == NormalMethod::Jet ? NormalOrigin::Jet : NormalOrigin::Pca;
}

/// The prepare stage: the input's own normals checked, the average spacing
/// and the mesh size it gives (7.3.2), the features (7.2) and where the
/// normals will come from. Returns the checked input.
PointSet prepare(PointSet input, const ReconstructOptions& options, const Progress& progress, ReconstructResult& result) {
  using namespace detail;
  InputNormals input_normals = InputNormals::Used;
  if (input.has_normals() && !options.recompute_normals && options.check_input_normals) {
    StageTimer timer(result.stages, "normal check");
    input_normals = check_input_normals(input, options, result.normals.input_normal_agreement, progress);
    if (input_normals == InputNormals::Unusable) input.normals.clear();
  }
  result.input_points = input.size();

  {
    StageTimer timer(result.stages, "spacing");
    result.average_spacing = options.average_spacing > 0 ? options.average_spacing : average_spacing(input, options.spacing_k, progress);
  }
  if (!(result.average_spacing > 0)) throw InvalidInput("reconstruction: the average spacing is zero (duplicated points?)");
  {
    // Before everything that reads the surface: the walls give the eaves
    // their second face (features) and the mesh its walls (Poisson, trim).
    StageTimer timer(result.stages, "walls");
    result.walls = fill_vertical_walls(input, result.average_spacing, options.walls, progress);
  }
  result.d_prime = options.delta * result.average_spacing;
  result.criteria = RefinementCriteria::from_spacing(result.d_prime);
  const double area = estimated_area_from_spacing(input.size(), result.average_spacing);
  double estimate = estimate_facet_count(area, result.criteria);
  // A facet budget above what delta gives: the refinement is made finer, to
  // about 1.5 times the budget for the collapse to choose from (the facet
  // count grows as 1 / d'^2), but not finer than the data (d' >= avg).
  const double budget = static_cast<double>(options.compaction.facets);
  if (budget > 0 && estimate < 1.5 * budget && options.delta > 1) {
    result.d_prime = std::max(1.0, options.delta * std::sqrt(estimate / (1.5 * budget))) * result.average_spacing;
    result.criteria = RefinementCriteria::from_spacing(result.d_prime);
    estimate = estimate_facet_count(area, result.criteria);
  }
  result.estimated_facets = estimate;
  if (options.max_facets > 0 && estimate > static_cast<double>(options.max_facets))
    throw InvalidArgument("delta = " + format_number(result.d_prime / result.average_spacing) + " would give about " + format_number(estimate) +
                          " facets, above the limit of " + format_number(options.max_facets) + " (raise delta or --max-facets)");

  if (options.feature_mode == FeatureMode::Extract) {
    // The airborne verdict is the walls stage's, taken before the walls
    // made the cloud two layers deep there.
    FeatureOptions features = options.features;
    features.max_offset_radius = offset_radius_bound(features, result.walls.airborne);
    result.features = extract_features(input, features, progress);
    result.stages.insert(result.stages.end(), result.features.stages.begin(), result.features.stages.end());
  } else if (options.feature_mode == FeatureMode::Given) {
    result.features.graph.polylines = options.given_features;
  }

  const bool needs_normals = !input.has_normals() || options.recompute_normals;
  result.normals.normal_origin = !needs_normals ? (input_normals == InputNormals::Reoriented ? NormalOrigin::InputReoriented : NormalOrigin::Input)
                                 : normals_from_cvcm(options) ? NormalOrigin::Cvcm
                                                              : estimated_origin(options);
  result.normals.input_normals_unusable = input_normals == InputNormals::Unusable;
  result.normals.normals_estimated = needs_normals;
  result.used_points = input.size();
  return input;
}

/// The stages of stages.h in order, on a recentred input.
ReconstructResult reconstruct_centred(PointSet given, const ReconstructOptions& options, const Progress& progress) {
  using namespace detail;
  ReconstructResult result;
  const PointSet input = prepare(std::move(given), options, progress, result);
  const PipelineInput in{input, options, progress};
  const double estimate = result.estimated_facets;
  ImplicitSolver solver(in, result);
  ImplicitStage implicit =
      solve_implicit(in, solver, result.normals.normals_estimated, normals_from_cvcm(options), estimated_origin(options), result);
  mesh_surface(in, std::move(implicit.surface), implicit.oriented, estimate, result, "");
  FitStage fit = fit_and_retry(in, solver, implicit.oriented, estimate, result);
  snap_to_data(in, fit, result);
  compact(in, fit, result);
  result.data_fit.off_data_points = fit.fit.off.size();
  result.data_fit.off_data_against = fit.fit.off_and_against.size();
  result.data_fit.invented_vertices = fit.fit.invented_vertices;
  result.data_fit.max_data_distance = fit.fit.max_distance;
  return result;
}

}  // namespace
}  // namespace sharpmesh
