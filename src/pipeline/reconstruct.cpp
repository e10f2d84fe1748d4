// The Chapter 7 pipeline: features (7.2), normals (7.4), Poisson implicit
// function, Delaunay refinement with protecting balls (7.3.2); without
// features the PIF baseline (7.3.1).
#include "sharpmesh/reconstruct.h"

#include <algorithm>
#include <cmath>

#include "core/recentering.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/implicit.h"

namespace sharpmesh {
namespace {

ReconstructResult reconstruct_centred(const PointSet& input, const ReconstructOptions& options, const Progress& progress);

}  // namespace

void ReconstructOptions::check(std::size_t n) const {
  if (!(delta > 0) || !std::isfinite(delta))
    throw InvalidArgument("delta must be positive (got " + format_number(delta) + ")");
  if (!(ball_radius > 0 && ball_radius <= 2))
    throw InvalidArgument("ball radius is a fraction of d' in (0, 2] (got " + format_number(ball_radius) + ")");
  if (feature_mode == FeatureMode::Extract) features.check();
  if (!(trim_distance >= 0) || !std::isfinite(trim_distance))
    throw InvalidArgument("trim distance must be >= 0 (got " + format_number(trim_distance) + ")");
  if (!(poisson_spacing >= 0 && poisson_spacing <= 4))
    throw InvalidArgument("Poisson sample spacing is a fraction of d' in [0, 4] (got " + format_number(poisson_spacing) + ")");
  if (!(poisson_thinning >= 0 && poisson_thinning <= 2))
    throw InvalidArgument("Poisson thinning distance is a fraction of the average spacing in [0, 2] (got " + format_number(poisson_thinning) + ")");
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
  check_point_set(input, 10, "reconstruction");
  options.check(input.size());
  const detail::Recentering frame(input.points);
  PointSet local = input;
  frame.to_local(local.points);
  const std::size_t duplicates = remove_duplicate_points(local);
  check_point_set(local, 10, "reconstruction (after removing duplicated points)");
  options.check(local.size());
  ReconstructOptions local_options = options;
  frame.to_local(local_options.given_features);
  ReconstructResult result = reconstruct_centred(local, local_options, progress);
  result.input_points = input.size();
  result.duplicate_points = duplicates;
  frame.to_world(result.mesh.vertices);
  frame.to_world(result.features);
  frame.to_world(result.meshing.feature_edges);
  for (UncoveredGap& gap : result.meshing.uncovered) {
    frame.to_world(gap.center);
    gap.length = frame.length_to_world(gap.length);
    if (gap.gap > 0) gap.gap = frame.length_to_world(gap.gap);
  }
  result.meshing.max_gap = frame.length_to_world(result.meshing.max_gap);
  for (double* length : {&result.average_spacing, &result.d_prime, &result.criteria.edge_length, &result.criteria.distance})
    *length = frame.length_to_world(*length);
  return result;
}

namespace {

/// Data seeds for the refinement (ImplicitMeshingOptions::data_seeds): one
/// point per cell of `spacing`, and, where the solid (or a gap) is thinner
/// than spacing / 2, every point with a spacing of twice the local
/// thickness, so both sides get vertices close enough for the restricted
/// Delaunay triangulation to separate them. Walls thinner than the noise or
/// than one average spacing are not looked for.
void add_data_seeds(const PointSet& oriented, double spacing, ReconstructResult& result, ImplicitMeshingOptions& meshing) {
  meshing.seed_spacing = spacing;
  if (result.average_spacing < 0.5 * spacing) {
    const std::vector<double> thickness = local_thickness(oriented, result.average_spacing, 0.5 * spacing);
    for (std::size_t i = 0; i < oriented.size(); ++i) {
      if (!std::isfinite(thickness[i])) continue;
      meshing.data_seeds.push_back(oriented.points[i]);
      meshing.data_seed_spacings.push_back(2 * thickness[i]);
      ++result.thin_points;
    }
  }
  PointSet grid{oriented.points, {}, {}};
  grid_simplify(grid, spacing);
  meshing.data_seeds.insert(meshing.data_seeds.end(), grid.points.begin(), grid.points.end());
  meshing.data_seed_spacings.resize(meshing.data_seeds.size(), spacing);
}

/// CVCM normals (7.4) where the convolved VCM is anisotropic; elsewhere
/// (lambda0/lambda1 below `min_anisotropy`, 20: a fifth to a third of the
/// points of CAD models, near edges and in thin parts) the jet normal of the
/// k nearest points (App. A.7). In a wall or flange thinner than the offset radius R
/// the Voronoi cells are cut short by the other side, the covariance turns
/// isotropic and its main axis can lie in the tangent plane: the MST then
/// inverted 18% of spool.off's and 26% of rotor.off's normals (50k points),
/// Poisson closed the flanges off the data and the trimmed mesh had holes.
/// With jet normals there: 0.2% and 0.01% (PCA normals there: 20% on spool;
/// jet normals everywhere: 0.2% and 0.03%, but twice the CVCM's angle error
/// elsewhere on rotor). Over 12 CGAL models at 50k points the mean error
/// summed drops from 1.32 to 0.82 U, and spool, rotor and couplingdown all
/// come out closed and manifold (thresholds 3 and 10 each left one open).
/// Returns the number replaced.
std::size_t cvcm_normals(PointSet& cloud, const FeatureResult& features, const NormalEstimationOptions& estimation,
                         double min_anisotropy) {
  cloud.normals.resize(cloud.size());
  std::vector<std::uint32_t> isotropic;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    cloud.normals[i] = features.points[i].normal;
    if (!(features.points[i].ratio01 >= min_anisotropy)) isotropic.push_back(static_cast<std::uint32_t>(i));
  }
  NormalEstimationOptions jet = estimation;
  jet.method = NormalMethod::Jet;
  jet.k = std::min<int>(jet.k, static_cast<int>(cloud.size()) - 1);
  estimate_normals_at(cloud, isotropic, jet);
  return isotropic.size();
}

/// Normals read from a file are checked before Poisson trusts them: files
/// in the wild carry zero normals (CGAL's blobby.xyz: all of them) or
/// normals whose lines are right but whose signs flip from face to face
/// (CGAL's cube.pwn: half of them point inwards, and the Poisson surface
/// broke up into shreds along the grooves). Usable normals are made unit;
/// when fewer than half are usable they are ignored and estimated instead.
/// Otherwise PCA normals, which turn smoothly across creases, are oriented
/// by the tangent MST (App. A.8) and compared with the file's signs: at
/// between 10% and 90% agreement the signs are inconsistent, and each input
/// normal takes the sign of the oriented PCA normal (its line is kept).
/// Consistently inward normals, near 0%, are kept as given.
enum class InputNormals { Used, Reoriented, Unusable };

InputNormals check_input_normals(PointSet& cloud, const ReconstructOptions& options, double& agreement, const Progress& progress) {
  std::size_t usable = 0;
  for (Vec3& n : cloud.normals) {
    const double length = norm(n);
    if (std::isfinite(length) && length > 0) {
      n = (1.0 / length) * n;
      ++usable;
    } else {
      n = {0, 0, 0};
    }
  }
  if (2 * usable < cloud.size()) return InputNormals::Unusable;
  const int last = static_cast<int>(cloud.size()) - 1;
  PointSet reference{cloud.points, {}, {}};
  NormalEstimationOptions pca = options.normals;
  pca.method = NormalMethod::Pca;
  pca.k = std::min(pca.k, last);
  estimate_normals(reference, pca, progress);
  orient_normals_tangent_mst(reference, std::min(options.orientation.k, last), progress);
  std::size_t agree = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) agree += dot(reference.normals[i], cloud.normals[i]) > 0;
  agreement = static_cast<double>(agree) / static_cast<double>(usable);
  if (agreement <= 0.1 || agreement >= 0.9) return InputNormals::Used;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (dot(reference.normals[i], cloud.normals[i]) < 0) cloud.normals[i] = -1.0 * cloud.normals[i];
  return InputNormals::Reoriented;
}

ReconstructResult reconstruct_centred(const PointSet& given, const ReconstructOptions& options, const Progress& progress) {
  ReconstructResult result;
  PointSet checked;
  InputNormals input_normals = InputNormals::Used;
  if (given.has_normals() && !options.recompute_normals && options.check_input_normals) {
    StageTimer timer(result.stages, "normal check");
    checked = given;
    input_normals = check_input_normals(checked, options, result.input_normal_agreement, progress);
    if (input_normals == InputNormals::Unusable) checked.normals.clear();
  }
  const PointSet& input = checked.points.empty() ? given : checked;
  result.input_points = input.size();

  {
    StageTimer timer(result.stages, "spacing");
    result.average_spacing = average_spacing(input, options.spacing_k, progress);
  }
  if (!(result.average_spacing > 0)) throw InvalidInput("reconstruction: the average spacing is zero (duplicated points?)");
  result.d_prime = options.delta * result.average_spacing;
  result.criteria = RefinementCriteria::from_spacing(result.d_prime);
  const double estimate = estimate_facet_count(estimated_area_from_spacing(input.size(), result.average_spacing), result.criteria);
  result.estimated_facets = estimate;
  if (options.max_facets > 0 && estimate > static_cast<double>(options.max_facets))
    throw InvalidArgument("delta = " + format_number(options.delta) + " would give about " + format_number(estimate) +
                          " facets, above the limit of " + format_number(options.max_facets) + " (raise delta or --max-facets)");

  if (options.feature_mode == FeatureMode::Extract) {
    result.features = extract_features(input, options.features, progress);
    result.stages.insert(result.stages.end(), result.features.stages.begin(), result.features.stages.end());
  } else if (options.feature_mode == FeatureMode::Given) {
    result.features.graph.polylines = options.given_features;
  }

  const bool cvcm = options.normal_source == NormalSource::Cvcm ||
                    (options.normal_source == NormalSource::Automatic && options.feature_mode == FeatureMode::Extract);
  const bool needs_normals = !input.has_normals() || options.recompute_normals;
  if (cvcm && needs_normals && options.feature_mode != FeatureMode::Extract)
    throw InvalidArgument("CVCM normals need feature extraction (they come from its covariance measure)");
  auto oriented_normals = [&](bool from_cvcm, const char* stage) {
    StageTimer timer(result.stages, stage);
    PointSet oriented = input;
    if (from_cvcm) {
      // Automatic normals replace the isotropic CVCM ones; --normals cvcm is the thesis's 7.4 throughout.
      const double min_anisotropy = options.normal_source == NormalSource::Automatic ? 20.0 : 0.0;
      result.isotropic_cvcm_normals = cvcm_normals(oriented, result.features, options.normals, min_anisotropy);
    } else {
      estimate_normals(oriented, options.normals, progress);
    }
    // Tangent-aware MST (orientation.cpp): no flips across thin walls.
    orient_normals_tangent_mst(oriented, options.orientation.k, progress);
    return oriented;
  };
  auto solve = [&](const PointSet& oriented, PoissonDiagnostics& diagnostics, const char* stage) {
    StageTimer timer(result.stages, stage);
    // Optional: solve on a grid simplification, 4x faster on fandisk 200k at
    // cells of d'/2, for about 30% more mean error (measured in the README).
    // Keeping every edge point as well made blade's function inconsistent.
    // By default near-coincident points are thinned out first: on fandisk
    // 200k, leaving out the 19% closer than 0.4 avg to a kept point cuts
    // Poisson from 31 to 12 s (CGAL's refinement adds a Steiner point for
    // each short Delaunay edge) with the same Hausdorff and mean error.
    const bool thin = options.poisson_thinning > 0, grid = options.poisson_spacing > 0;
    if (!thin && !grid) return poisson_surface(oriented, PoissonOptions{}, progress, &diagnostics);
    PointSet samples{oriented.points, oriented.normals, {}};
    if (grid) grid_simplify(samples, options.poisson_spacing * result.d_prime);
    if (thin) thin_close_points(samples, options.poisson_thinning * result.average_spacing);
    return poisson_surface(samples, PoissonOptions{}, progress, &diagnostics);
  };
  const std::string estimated_name = options.normals.method == NormalMethod::Jet ? "jet" : "pca";
  result.normal_source = !needs_normals ? (input_normals == InputNormals::Reoriented ? "input (re-oriented)" : "input")
                         : cvcm ? "cvcm" : estimated_name;
  if (input_normals == InputNormals::Unusable) result.normal_source += " (input normals unusable)";
  result.normals_estimated = needs_normals;
  result.used_points = input.size();

  std::unique_ptr<ImplicitSurface> surface;
  PoissonDiagnostics diagnostics;
  PointSet oriented;  // the points and normals Poisson was solved with
  // With automatic normals, CVCM normals whose Poisson function disagrees
  // with them (needle-like spikes, where the covariance's main axis runs
  // along the spike: CGAL's star.off) are replaced by jet normals; the
  // function that agrees better with its own normals is kept.
  const bool may_fall_back = needs_normals && cvcm && options.normal_source == NormalSource::Automatic;
  try {
    oriented = needs_normals ? oriented_normals(cvcm, "normals") : input;
    surface = solve(oriented, diagnostics, "poisson");
  } catch (const NumericalFailure&) {
    if (!may_fall_back) throw;
  }
  if (may_fall_back && diagnostics.normal_agreement < 0.9) {
    PoissonDiagnostics fallback;
    try {
      PointSet jet = oriented_normals(false, "normals (fallback)");
      auto retry = solve(jet, fallback, "poisson (fallback)");
      if (!surface || fallback.normal_agreement > diagnostics.normal_agreement) {
        surface = std::move(retry);
        oriented = std::move(jet);
        diagnostics = fallback;
        result.normal_source = estimated_name + " (cvcm fallback)";
      }
    } catch (const NumericalFailure&) {
      if (!surface) throw;
    }
  }
  result.poisson_points = surface->sample_count();
  result.normal_agreement = diagnostics.normal_agreement;
  const double trim_distance = options.trim_distance * result.d_prime + 2 * result.average_spacing;
  // Open inputs: cut the implicit function at twice the trim distance where
  // its zero set leaves the data, so Poisson's closing sheet is never
  // refined; the trim removes the cut.
  if (options.trim_distance > 0) {
    StageTimer timer(result.stages, "restriction");
    const double domain_radius = meshing_domain_radius(*surface);
    Restriction restriction = restrict_to_points(std::move(surface), input.points, 2 * trim_distance, domain_radius);
    surface = std::move(restriction.surface);
    result.restricted = restriction.applied;
  }
  ImplicitMeshingOptions meshing;
  meshing.criteria = result.criteria;
  meshing.max_facets = options.max_facets;
  meshing.expected_facets = estimate;
  meshing.seed = options.seed;
  meshing.features.polylines = result.features.graph.polylines;
  meshing.features.ball_radius = options.ball_radius * result.d_prime;
  meshing.features.adapt_to_gap = options.adapt_balls_to_gap;
  // Two polylines (or two stretches of one) closer than two spacings get balls
  // too thin to reach the surface: the shorter is left unprotected.
  meshing.features.min_separation = 2 * result.average_spacing;
  if (options.data_seed_spacing > 0) {
    StageTimer timer(result.stages, "seeds");
    add_data_seeds(oriented, options.data_seed_spacing * result.d_prime, result, meshing);
  }
  {
    StageTimer timer(result.stages, "refinement");
    result.meshing = mesh_implicit_surface(*surface, meshing, progress);
    result.mesh = std::move(result.meshing.mesh);
    result.meshing.mesh = {};
  }
  // The facets along protected edges lean with the rounded Poisson surface:
  // their third vertices go onto the face planes of the data.
  if (options.flatten_features && !result.meshing.feature_edges.empty()) {
    StageTimer timer(result.stages, "flattening");
    FlatteningOptions flattening;
    // The rounding is at the data's scale, a few spacings whatever delta;
    // a plane over a larger radius would cut through curved faces.
    flattening.radius = std::min(options.ball_radius * result.d_prime, 3 * result.average_spacing);
    flattening.max_move = std::min(0.25 * result.d_prime, 2 * result.average_spacing);
    flattening.max_residual = 0.15 * result.d_prime;
    const std::vector<Vec3> before = result.mesh.vertices;
    result.flattened_vertices =
        flatten_next_to_features(result.mesh, result.meshing.feature_edges, oriented.points, oriented.normals, flattening);
    // A move can still push a facet through a neighbour (couplingdown 50k at
    // delta 8 and 32 self-intersected): the moved vertices of intersecting
    // facets go back, until none intersect or none of theirs moved.
    for (int round = 0; round < 4 && result.flattened_vertices > 0; ++round) {
      std::size_t restored = 0;
      for (const auto& [a, b] : self_intersecting_faces(result.mesh))
        for (std::uint32_t f : {a, b})
          for (std::uint32_t v : result.mesh.faces[f])
            if (result.mesh.vertices[v] != before[v]) result.mesh.vertices[v] = before[v], ++restored;
      if (restored == 0) break;
      result.flattened_vertices -= std::min(result.flattened_vertices, restored);
      result.unflattened_vertices += restored;
    }
  }
  if (options.trim_distance > 0) {
    StageTimer timer(result.stages, "trim");
    result.trimmed_facets =
        trim_far_from_points(result.mesh, input.points, trim_distance);
    if (result.mesh.faces.empty()) throw NumericalFailure("reconstruction: no facet of the mesh lies near the input points");
    result.clipped_facets = clip_boundary_to_points(result.mesh, input.points, result.average_spacing);
    result.boundary_edges = count_boundary_edges(result.mesh);
  }
  return result;
}

}  // namespace
}  // namespace sharpmesh
