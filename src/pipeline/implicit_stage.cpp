// The implicit stage: Poisson's function (CGAL, implicit/poisson.cpp) on
// the oriented points, its sign checked against their normals and repaired.
#include <algorithm>
#include <cmath>

#include "pipeline/stages.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/features.h"

namespace sharpmesh::detail {
namespace {

/// Vertices half-way across thin material and narrow gaps, for the Poisson
/// function (PoissonOptions::extra_vertices): the midpoint between each
/// point and the point facing it one to six spacings away, one per cell of a
/// spacing (a plate's two faces give one midpoint sheet; a vertex on each
/// side of it or in open space only makes CGAL's solve slower).
std::vector<Vec3> thin_part_vertices(const PointSet& oriented, double spacing) {
  std::vector<std::uint32_t> facing;
  const std::vector<double> thickness = local_thickness(oriented, spacing, 6 * spacing, &facing);
  PointSet vertices;
  for (std::size_t i = 0; i < oriented.size(); ++i)
    if (std::isfinite(thickness[i]))
      vertices.points.push_back(0.5 * (oriented.points[i] + oriented.points[facing[i]]));
  if (!vertices.empty()) grid_simplify(vertices, spacing);
  return vertices.points;
}

/// The points whose normal the implicit function contradicts: it does not
/// grow along the normal over +-h.
/// Evaluated in Morton order, so that each point location starts next to the
/// last one (about three times faster than input order, even with the
/// Poisson function's start-cell grid).
std::vector<std::uint32_t> disagreeing_normals(const ImplicitSurface& surface, const PointSet& oriented, double h) {
  const BoundingBox box = bounding_box(oriented.points);
  const double extent = std::max({box.max[0] - box.min[0], box.max[1] - box.min[1], box.max[2] - box.min[2], 1e-300});
  auto morton = [&](const Vec3& p) {
    std::uint64_t code = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const auto cell = static_cast<std::uint64_t>(std::clamp((p[axis] - box.min[axis]) / extent, 0.0, 1.0) * 1023.0);
      for (int bit = 0; bit < 10; ++bit) code |= ((cell >> bit) & 1u) << (3 * bit + axis);
    }
    return code;
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(oriented.size());
  for (std::size_t i = 0; i < oriented.size(); ++i) order[i] = {morton(oriented.points[i]), static_cast<std::uint32_t>(i)};
  std::sort(order.begin(), order.end());
  std::vector<std::uint32_t> ids;
  for (const auto& [code, i] : order) {
    const Vec3& p = oriented.points[i];
    const Vec3& n = oriented.normals[i];
    if (!(surface.value(p + h * n) > surface.value(p - h * n))) ids.push_back(i);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace

std::unique_ptr<ImplicitSurface> ImplicitSolver::solve(const PointSet& oriented, PoissonDiagnostics& diagnostics) {
  const ReconstructOptions& options = in_.options;
  // Optional: solve on a grid simplification, faster for a larger mean
  // error. By default near-coincident points are thinned out first: CGAL's
  // refinement adds a Steiner point for each short Delaunay edge, and the
  // pair's second point carries no information (docs/design-notes.md,
  // Poisson's input thinning).
  const bool thin = options.poisson_thinning > 0, grid = options.poisson_spacing > 0;
  PoissonOptions poisson;
  const bool noisy = options.feature_mode == FeatureMode::Extract &&
                     (result_.features.denoise_passes > 0 || !(result_.features.noise_estimate < kCleanNoiseRatio * result_.average_spacing));
  poisson.screening = result_.implicit.poisson_screening = noisy ? options.poisson_screening_noisy : options.poisson_screening;
  poisson.average_spacing = result_.average_spacing;
  if (options.thin_part_vertices && !thin_vertices_) thin_vertices_ = thin_part_vertices(oriented, result_.average_spacing);
  if (thin_vertices_) poisson.extra_vertices = *thin_vertices_;
  result_.implicit.thin_part_vertices = poisson.extra_vertices.size();
  if (!thin && !grid) return poisson_surface(oriented, poisson, in_.progress, &diagnostics);
  PointSet samples{oriented.points, oriented.normals, {}};
  if (grid) grid_simplify(samples, options.poisson_spacing * result_.d_prime);
  if (thin) thin_close_points(samples, options.poisson_thinning * result_.average_spacing);
  return poisson_surface(samples, poisson, in_.progress, &diagnostics);
}

/// Beyond the thesis: the orientation checked and repaired with the implicit
/// function's sign (docs/design-notes.md, sign repair). The MST can invert a
/// small patch where faces a few spacings wide meet at creases (a
/// counterbore); Poisson then bends the surface into the hole. The function
/// still follows the majority around such a patch, so the normals it
/// contradicts (at +-h = 0.5 avg) are flipped and Poisson solved again,
/// while each round lowers their number (at most 3 rounds). A rightly
/// oriented cloud pays only the check. Returns the number of flips kept.
std::size_t enough_for_a_repair(std::size_t points, const ReconstructTuning& tuning) {
  return std::max<std::size_t>(tuning.repair_min_points, points / tuning.repair_one_point_in);  // check() refuses 0
}

std::size_t ImplicitSolver::repair_signs(PointSet& oriented, std::unique_ptr<ImplicitSurface>& surface,
                                         PoissonDiagnostics& diagnostics) {
  const double h = 0.5 * result_.average_spacing;
  std::vector<std::uint32_t> wrong = disagreeing_normals(*surface, oriented, h);
  const std::size_t worth_a_solve = enough_for_a_repair(oriented.size(), in_.options.tuning);
  std::size_t flipped = 0;
  for (int round = 0; round < 3 && wrong.size() >= worth_a_solve; ++round) {
    PointSet repaired = oriented;
    for (std::uint32_t i : wrong) repaired.normals[i] = -1.0 * repaired.normals[i];
    PoissonDiagnostics retry_diagnostics;
    std::unique_ptr<ImplicitSurface> retry;
    try {
      retry = solve(repaired, retry_diagnostics);
    } catch (const NumericalFailure&) {
      break;
    }
    std::vector<std::uint32_t> still = disagreeing_normals(*retry, repaired, h);
    if (still.size() >= wrong.size()) break;
    flipped += wrong.size();
    oriented = std::move(repaired);
    surface = std::move(retry);
    diagnostics = retry_diagnostics;
    wrong = std::move(still);
  }
  return flipped;
}

ImplicitStage solve_implicit(const PipelineInput& in, ImplicitSolver& solver, bool needs_normals, bool cvcm,
                             NormalOrigin estimated, ReconstructResult& result) {
  const ReconstructOptions& options = in.options;
  ImplicitStage stage;
  auto normals = [&](bool from_cvcm, const char* name) {
    StageTimer timer(result.stages, name);
    return oriented_normals(in, from_cvcm, result);
  };
  auto solve = [&](const PointSet& oriented, PoissonDiagnostics& diagnostics, const char* name) {
    StageTimer timer(result.stages, name);
    return solver.solve(oriented, diagnostics);
  };
  // With automatic normals, CVCM normals whose Poisson function disagrees
  // with them (needle-like spikes, where the covariance's main axis runs
  // along the spike: CGAL's star.off) are replaced by jet normals; the
  // function that agrees better with its own normals is kept.
  const bool may_fall_back = needs_normals && cvcm && options.normal_source == NormalSource::Automatic;
  try {
    stage.oriented = needs_normals ? normals(cvcm, "normals") : in.points;
    stage.surface = solve(stage.oriented, stage.diagnostics, "poisson");
  } catch (const NumericalFailure&) {
    if (!may_fall_back) throw;
  }
  if (may_fall_back && stage.diagnostics.normal_agreement < options.tuning.min_normal_agreement) {
    PoissonDiagnostics fallback;
    try {
      PointSet jet = normals(false, "normals (fallback)");
      auto retry = solve(jet, fallback, "poisson (fallback)");
      if (!stage.surface || fallback.normal_agreement > stage.diagnostics.normal_agreement) {
        stage.surface = std::move(retry);
        stage.oriented = std::move(jet);
        stage.diagnostics = fallback;
        result.normals.normal_origin = estimated;
        result.normals.cvcm_fallback = true;
      }
    } catch (const NumericalFailure&) {
      if (!stage.surface) throw;
    }
  }
  if (options.repair_normal_signs && options.check_input_normals) {
    StageTimer timer(result.stages, "sign repair");
    result.normals.sign_repaired_normals = solver.repair_signs(stage.oriented, stage.surface, stage.diagnostics);
  }
  result.implicit.poisson_points = stage.surface->sample_count();
  result.implicit.normal_agreement = stage.diagnostics.normal_agreement;
  return stage;
}

}  // namespace sharpmesh::detail
