// The Chapter 7 pipeline: features (7.2), normals (7.4), Poisson implicit
// function, Delaunay refinement with protecting balls (7.3.2); without
// features the PIF baseline (7.3.1).
#include "sharpmesh/reconstruct.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include "core/recentering.h"
#include "pipeline/data_fit.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/implicit.h"

namespace sharpmesh {
namespace {

ReconstructResult reconstruct_centred(const PointSet& input, const ReconstructOptions& options, const Progress& progress);

}  // namespace

void ReconstructOptions::check(std::size_t n) const {
  if (!(protection_budget >= 0) || !std::isfinite(protection_budget))
    throw InvalidArgument("protection budget must be a non-negative number of queries per polyline point (got " +
                          format_number(protection_budget) + ")");
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
  // Beyond the thesis: the output is valid every time it can be (issue
  // 36's gate). Refinement near thin parts, flattening and snapping check
  // their own moves, but the Delaunay refinement of a surface whose two
  // sides lie closer than its facets' size can itself cross them. Checked
  // on the world coordinates written out: the translation's rounding decides
  // touching facets either way. The data-fit counts are the mesh's before
  // the repair, which changes a few facets.
  if (options.repair_self_intersections && !result.mesh.faces.empty()) {
    StageTimer timer(result.stages, "self-intersection check");
    result.intersection_repair = repair_self_intersections(result.mesh, {}, progress);
    if (result.intersection_repair.rounds > 0) result.boundary_edges = count_boundary_edges(result.mesh);
  }
  for (double* length : {&result.average_spacing, &result.d_prime, &result.criteria.edge_length, &result.criteria.distance})
    *length = frame.length_to_world(*length);
  return result;
}

namespace {

/// Data seeds for the refinement (ImplicitMeshingOptions::data_seeds): one
/// point per cell of `spacing`, and, where the solid (or a gap) is thinner
/// than spacing / 2, every point with a spacing of twice the local
/// thickness, so both sides get vertices close enough for the restricted
/// Delaunay triangulation to separate them; there the facets are also
/// bounded by the thickness (ImplicitMeshingOptions::thin_points), and the
/// facet count expected grows by the ratio of the areas of uniform and
/// local facets. Walls thinner than the noise or than one average spacing
/// are not looked for.
void add_data_seeds(const PointSet& oriented, double spacing, ReconstructResult& result, ImplicitMeshingOptions& meshing) {
  meshing.seed_spacing = spacing;
  if (result.average_spacing < 0.5 * spacing) {
    const std::vector<double> thickness = local_thickness(oriented, result.average_spacing, 0.5 * spacing);
    const double uniform = meshing.criteria.edge_length / 2;
    double facet_ratio = 0;
    for (std::size_t i = 0; i < oriented.size(); ++i) {
      if (!std::isfinite(thickness[i])) continue;
      meshing.data_seeds.push_back(oriented.points[i]);
      meshing.data_seed_spacings.push_back(2 * thickness[i]);
      meshing.thin_points.push_back(oriented.points[i]);
      meshing.thin_thickness.push_back(thickness[i]);
      const double local = std::min(uniform, thickness[i]);
      facet_ratio += (uniform / local) * (uniform / local) - 1;
      ++result.thin_points;
    }
    meshing.expected_facets *= 1 + facet_ratio / static_cast<double>(oriented.size());
  }
  PointSet grid{oriented.points, {}, {}};
  grid_simplify(grid, spacing);
  meshing.data_seeds.insert(meshing.data_seeds.end(), grid.points.begin(), grid.points.end());
  meshing.data_seed_spacings.resize(meshing.data_seeds.size(), spacing);
}

/// Vertices half-way across thin material and narrow gaps, for the Poisson
/// function (PoissonOptions::extra_vertices): at each point whose facing
/// sheet lies between one and six spacings away, both points half the
/// thickness along its normal line (one lies between the sheets, the other
/// in open space beside them, where a vertex costs nothing), one per cell
/// of a spacing.
std::vector<Vec3> thin_part_vertices(const PointSet& oriented, double spacing) {
  const std::vector<double> thickness = local_thickness(oriented, spacing, 6 * spacing);
  PointSet vertices;
  for (std::size_t i = 0; i < oriented.size(); ++i) {
    const double length = norm(oriented.normals[i]);
    if (!std::isfinite(thickness[i]) || !(length > 0)) continue;
    const Vec3 half = (0.5 * thickness[i] / length) * oriented.normals[i];
    vertices.points.push_back(oriented.points[i] - half);
    vertices.points.push_back(oriented.points[i] + half);
  }
  if (!vertices.empty()) grid_simplify(vertices, spacing);
  return vertices.points;
}

/// CVCM normals (7.4) where the convolved VCM is anisotropic; elsewhere
/// (lambda0/lambda1 below `min_anisotropy`, 20: a fifth to a third of the
/// points of CAD models, near edges and in thin parts) a plane fit. In a wall
/// or flange thinner than the offset radius R the Voronoi cells are cut short
/// by the other side, the covariance turns isotropic and its main axis can
/// lie in the tangent plane: the MST then inverted 18% of spool.off's and 26%
/// of rotor.off's normals (50k points), Poisson closed the flanges off the
/// data and the trimmed mesh had holes.
/// Those points lie next to creases, where any centred neighbourhood
/// straddles two faces (jet normals over 18 points there: 13-18 degrees off
/// on seven CGAL models at 50k points, half of them more than 10 degrees).
/// On clean-to-moderately noisy clouds they take crease-aware normals from
/// shifted neighbourhoods instead (pointset.h): 0.8-6.3 degrees on the same
/// clouds. Their plane size grows with the noise, from 8 points when clean
/// to 30 at noise of 0.22 spacings (measured crossover with jet: small
/// planes are worse than jet from 0.1 spacings of noise, 30-point planes
/// better up to 0.25). Clouds the extraction had to denoise keep jet normals
/// (shifted planes were 3-18 degrees worse there). Here those points get
/// jet normals, which turn smoothly enough for the MST; sharpen_normals
/// replaces them after orientation. Returns the points replaced.
std::vector<std::uint32_t> cvcm_normals(PointSet& cloud, const FeatureResult& features, const NormalEstimationOptions& estimation,
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
  return isotropic;
}

/// Distance beyond which an input point is off the mesh, or a mesh
/// component off the data: the refinement may leave the implicit surface by
/// its surface-distance criterion (0.6 d', 2.1 spacings at delta 3.5) and no
/// more, plus three noise deviations.
double off_data_distance(const ReconstructResult& r, const ReconstructOptions& options) {
  const double noise = options.feature_mode == FeatureMode::Extract ? r.features.noise_estimate : 0.0;
  return std::max(1.5 * r.average_spacing, r.criteria.distance) + 3 * noise;
}

/// After orientation: the crease-aware normals at `ids` (see cvcm_normals),
/// each taking the sign of the oriented normal it replaces. They are not
/// oriented themselves: at a crease they turn by up to 90 degrees from one
/// point to the next and the MST loses the sign (17.6% of couplingdown's
/// normals inverted, against 0.2% with the smoothly turning jet normals).
/// Returns the number replaced (0 for denoised or noisier clouds).
std::size_t sharpen_normals(PointSet& oriented, const std::vector<std::uint32_t>& ids, const FeatureResult& features) {
  const int last = static_cast<int>(oriented.size()) - 1;
  const double noise = features.average_spacing > 0 ? features.noise_estimate / features.average_spacing : 1.0;
  if (features.denoise_passes > 0 || !(noise < 0.25) || ids.empty()) return 0;
  ShiftedNormalOptions options;
  options.k = std::min(last, static_cast<int>(std::lround(std::clamp(8 + 100 * noise, 8.0, 30.0))));
  options.candidates = std::min(last, std::max(18, 3 * options.k / 2));
  estimate_shifted_normals_at(oriented, ids, options);  // signed like the oriented jet normals
  return ids.size();
}

/// The points whose normal the implicit function contradicts: it does not
/// grow along the normal over +-h.
/// Evaluated in Morton order, so that each point location starts next to the
/// last one: even with the Poisson function's start-cell grid, the check on
/// fandisk 200k (nothing to repair) takes 0.37-0.49 s so and 1.1-1.2 s in
/// input order.
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

/// Beyond the thesis: the orientation checked and repaired with the implicit
/// function's sign (issue 4 item 1). The MST can invert a small patch where
/// faces a few spacings wide meet at creases (couplingdown.off, 50k points:
/// 146 normals inside a counterbore); Poisson then bends the surface into the
/// hole. The function still follows the majority around such a patch, so the
/// normals it contradicts (at +-h = 0.5 avg) are flipped and Poisson solved
/// again, while each round lowers their number (at most 3 rounds). On
/// couplingdown: 55 -> 43 -> 24 -> 0 contradicted, 146 -> 40 inverted
/// normals, Hausdorff at delta 2 3.67 -> 2.20 U
/// (with the crease-aware normals). Clean CAD samples whose
/// orientation is right (fandisk, anchor, pinion, joint) have none and pay
/// only the check (0.11-0.14 s at 50k points). Returns the number of flips kept.
std::size_t repair_normal_signs(PointSet& oriented, std::unique_ptr<ImplicitSurface>& surface, PoissonDiagnostics& diagnostics,
                                double average_spacing,
                                const std::function<std::unique_ptr<ImplicitSurface>(const PointSet&, PoissonDiagnostics&)>& solve) {
  const double h = 0.5 * average_spacing;
  std::vector<std::uint32_t> wrong = disagreeing_normals(*surface, oriented, h);
  // A few scattered wrong normals barely move the function: no new solve
  // for fewer than 10 (or 0.02% of the points).
  const std::size_t worth_a_solve = std::max<std::size_t>(10, oriented.size() / 5000);
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

/// Signs for the tangent MST to grow from (exterior_votes.cpp), so that no
/// knife edge (a conical roof's rim) inverts the face behind it: the sheet
/// parity where it decides (thin plates and bars included), else the
/// occupancy (cells of one spacing resolve thin roofs; where a random
/// sampling's gaps let the outside in, a cube at 20k points, cells of 1.5
/// spacings still wall it off); none where the two disagree. Then only the
/// votes their same-sheet neighbours confirm (vote_consensus.cpp). All zero
/// on open clouds.
std::vector<signed char> occupancy_anchors(const PointSet& cloud, double average_spacing, double noise, int k) {
  std::vector<signed char> occupancy;
  for (double cell : {average_spacing, 1.5 * average_spacing}) {
    occupancy = exterior_side_votes(cloud, cell, 6 * cell + 4 * noise);
    if (std::any_of(occupancy.begin(), occupancy.end(), [](signed char v) { return v != 0; })) break;
  }
  std::vector<signed char> votes = sheet_parity_votes(cloud, average_spacing, noise);
  for (std::size_t i = 0; i < votes.size(); ++i) {
    if (votes[i] == 0) votes[i] = occupancy[i];
    else if (occupancy[i] != 0 && occupancy[i] != votes[i]) votes[i] = 0;
  }
  return neighbour_confirmed_votes(cloud, votes, k);
}

/// Normals read from a file are checked before Poisson trusts them: files
/// in the wild carry zero normals (CGAL's blobby.xyz: all of them) or
/// normals whose lines are right but whose signs flip from face to face
/// (CGAL's cube.pwn: half of them point inwards, and the Poisson surface
/// broke up into shreds along the grooves). Usable normals are made unit;
/// when fewer than half are usable they are ignored and estimated instead.
/// Otherwise PCA normals, which turn smoothly across creases, are oriented
/// by the tangent MST (App. A.8), anchored by the occupancy as the
/// estimated normals are (a knife edge would otherwise invert a face and
/// the file's right signs look inconsistent), and compared with the file's signs: at
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
  const std::vector<signed char> anchors =
      occupancy_anchors(reference, average_spacing(reference, std::min(options.spacing_k, last), progress), 0.0,
                        std::min(options.orientation.k, last));
  orient_normals_tangent_mst(reference, std::min(options.orientation.k, last), anchors, progress);
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
    std::vector<std::uint32_t> isotropic;
    if (from_cvcm) {
      // Automatic normals replace the isotropic CVCM ones; --normals cvcm is the thesis's 7.4 throughout.
      const double min_anisotropy = options.normal_source == NormalSource::Automatic ? 20.0 : 0.0;
      isotropic = cvcm_normals(oriented, result.features, options.normals, min_anisotropy);
      result.isotropic_cvcm_normals = isotropic.size();
    } else {
      estimate_normals(oriented, options.normals, progress);
    }
    const bool automatic = options.normal_source == NormalSource::Automatic && options.feature_mode == FeatureMode::Extract;
    // Tangent-aware MST (orientation.cpp): no flips across thin walls.
    // Automatic normals: anchored by the occupancy (occupancy_anchors).
    std::vector<signed char> anchors;
    if (automatic && options.anchor_orientation) {
      anchors = occupancy_anchors(oriented, result.average_spacing, result.features.noise_estimate, options.orientation.k);
      result.anchored_normals = static_cast<std::size_t>(std::count_if(anchors.begin(), anchors.end(), [](signed char v) { return v != 0; }));
    }
    orient_normals_tangent_mst(oriented, options.orientation.k, anchors, progress);
    // The crease points' jet normals carried the MST across the creases;
    // the anisotropic CVCM normals vote on it (patch_orientation.cpp).
    if (from_cvcm && automatic)
      result.patch_flipped_normals = repair_inverted_patches(oriented, isotropic, result.average_spacing, options.orientation.k);
    // Regions the rest of the surface encloses on their outer side
    // (enclosed_orientation.cpp); not on the PIF baseline (--no-features).
    if (automatic && options.repair_enclosed_normals)
      result.enclosed_flipped_normals = repair_enclosed_normals(oriented, result.average_spacing);
    if (from_cvcm && automatic) result.sharpened_normals = sharpen_normals(oriented, isotropic, result.features);
    return oriented;
  };
  // Found once: later solves flip normal signs only (the sign repair, the
  // data-fit retries), which leaves the half-way points where they are.
  std::optional<std::vector<Vec3>> thin_vertices;
  auto solve = [&](const PointSet& oriented, PoissonDiagnostics& diagnostics, const char* stage) {
    std::optional<StageTimer> timer;
    if (stage) timer.emplace(result.stages, stage);
    // Optional: solve on a grid simplification, 4x faster on fandisk 200k at
    // cells of d'/2, for about 30% more mean error (measured in the README).
    // Keeping every edge point as well made blade's function inconsistent.
    // By default near-coincident points are thinned out first: on fandisk
    // 200k, leaving out the 19% closer than 0.4 avg to a kept point cuts
    // Poisson from 31 to 12 s (CGAL's refinement adds a Steiner point for
    // each short Delaunay edge) with the same Hausdorff and mean error.
    const bool thin = options.poisson_thinning > 0, grid = options.poisson_spacing > 0;
    PoissonOptions poisson;
    const bool noisy = options.feature_mode == FeatureMode::Extract &&
                       (result.features.denoise_passes > 0 || !(result.features.noise_estimate < kCleanNoiseRatio * result.average_spacing));
    poisson.screening = result.poisson_screening = noisy ? options.poisson_screening_noisy : options.poisson_screening;
    poisson.average_spacing = result.average_spacing;
    if (options.thin_part_vertices && !thin_vertices) thin_vertices = thin_part_vertices(oriented, result.average_spacing);
    if (thin_vertices) poisson.extra_vertices = *thin_vertices;
    result.thin_part_vertices = poisson.extra_vertices.size();
    if (!thin && !grid) return poisson_surface(oriented, poisson, progress, &diagnostics);
    PointSet samples{oriented.points, oriented.normals, {}};
    if (grid) grid_simplify(samples, options.poisson_spacing * result.d_prime);
    if (thin) thin_close_points(samples, options.poisson_thinning * result.average_spacing);
    return poisson_surface(samples, poisson, progress, &diagnostics);
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
  if (options.repair_normal_signs && options.check_input_normals) {
    StageTimer timer(result.stages, "sign repair");
    result.sign_repaired_normals = repair_normal_signs(oriented, surface, diagnostics, result.average_spacing,
                                                       [&](const PointSet& points, PoissonDiagnostics& d) { return solve(points, d, nullptr); });
  }
  result.poisson_points = surface->sample_count();
  result.normal_agreement = diagnostics.normal_agreement;
  // Stages 3-4 (and the open-surface trim) on one implicit function.
  auto build_mesh = [&](std::unique_ptr<ImplicitSurface> function, const PointSet& normals, ReconstructResult& out,
                        const std::string& retry_prefix) {
    const double trim_distance = options.trim_distance * out.d_prime + 2 * out.average_spacing;
    // Open inputs: cut the implicit function at twice the trim distance where
    // its zero set leaves the data, so Poisson's closing sheet is never
    // refined; the trim removes the cut.
    if (options.trim_distance > 0) {
      StageTimer timer(out.stages, retry_prefix + "restriction");
      const double domain_radius = meshing_domain_radius(*function);
      Restriction restriction = restrict_to_points(std::move(function), input.points, 2 * trim_distance, domain_radius);
      function = std::move(restriction.surface);
      out.restricted = restriction.applied;
    }
    ImplicitMeshingOptions meshing;
    meshing.criteria = out.criteria;
    meshing.max_facets = options.max_facets;
    meshing.expected_facets = estimate;
    meshing.seed = options.seed;
    meshing.features.polylines = out.features.graph.polylines;
    if (options.protection_budget > 0) {
      std::size_t polyline_points = 0;
      for (const Polyline& line : meshing.features.polylines) polyline_points += line.size();
      meshing.protection_query_limit = static_cast<std::size_t>(options.protection_budget * static_cast<double>(polyline_points)) + 1;
    }
    meshing.features.ball_radius = options.ball_radius * out.d_prime;
    meshing.features.adapt_to_gap = options.adapt_balls_to_gap;
    // Two polylines (or two stretches of one) closer than two spacings get balls
    // too thin to reach the surface: the shorter is left unprotected.
    meshing.features.min_separation = 2 * out.average_spacing;
    if (options.data_seed_spacing > 0) {
      StageTimer timer(out.stages, retry_prefix + "seeds");
      add_data_seeds(normals, options.data_seed_spacing * out.d_prime, out, meshing);
    }
    {
      StageTimer timer(out.stages, retry_prefix + "refinement");
      out.meshing = mesh_implicit_surface(*function, meshing, progress);
      out.mesh = std::move(out.meshing.mesh);
      out.meshing.mesh = {};
    }
    // The facets along protected edges lean with the rounded Poisson surface:
    // their third vertices go onto the face planes of the data.
    if (options.flatten_features && !out.meshing.feature_edges.empty()) {
      StageTimer timer(out.stages, retry_prefix + "flattening");
      FlatteningOptions flattening;
      // The rounding is at the data's scale, a few spacings whatever delta;
      // a plane over a larger radius would cut through curved faces.
      flattening.radius = std::min(options.ball_radius * out.d_prime, 3 * out.average_spacing);
      flattening.max_move = std::min(0.25 * out.d_prime, 2 * out.average_spacing);
      flattening.max_residual = 0.15 * out.d_prime;
      const std::vector<Vec3> before = out.mesh.vertices;
      out.flattened_vertices =
          flatten_next_to_features(out.mesh, out.meshing.feature_edges, normals.points, normals.normals, flattening);
      // A move can still push a facet through a neighbour (couplingdown 50k at
      // delta 8 and 32 self-intersected): such moves go back.
      if (out.flattened_vertices > 0) {
        const std::size_t restored = undo_intersecting_moves(out.mesh, before);
        out.flattened_vertices -= std::min(out.flattened_vertices, restored);
        out.unflattened_vertices += restored;
      }
    }
    // Closed or open, a component whose vertices mostly lie off the data is
    // the implicit function's, not the data's (a bubble in a gap between
    // nested solids).
    out.dataless_facets = remove_components_off_points(out.mesh, input.points, off_data_distance(out, options));
    if (options.trim_distance > 0) {
      StageTimer timer(out.stages, retry_prefix + "trim");
      out.trimmed_facets =
          trim_far_from_points(out.mesh, input.points, trim_distance);
      if (out.mesh.faces.empty()) throw NumericalFailure("reconstruction: no facet of the mesh lies near the input points");
      if (options.clip_boundary)
        out.clipped_facets = clip_boundary_to_points(out.mesh, input.points, out.average_spacing);
      out.boundary_edges = count_boundary_edges(out.mesh);
    }
  };
  build_mesh(std::move(surface), oriented, result, "");
  // Beyond the thesis: the mesh checked against its own data. Where a patch
  // of normals stayed inverted through the sign repair (it agrees with a
  // function that is wrong there: couplingdown 50k, sampling seed 2, a hole
  // 5 spacings wide whose wall the MST inverted, was closed by Poisson and
  // its wall points ended 2.9 spacings inside the solid), the input points
  // lie off the mesh with normals against its facets. Their normals, and
  // those within 1.5 spacings that point the same way, are flipped, Poisson
  // solved and repaired again and the surface meshed again; the new mesh is
  // kept when a quarter fewer points are off and against it, no more off
  // in all, and none farther. Points off a rounded edge (PIF, a missed feature) agree
  // with the mesh and start no retry: by distance alone, PIF on 8 of the 15
  // corpus models retried for nothing (3 -> 8 s).
  // Measured whether or not a retry may run (0.19-0.24 s on fandisk 200k).
  {
    const double noise = options.feature_mode == FeatureMode::Extract ? result.features.noise_estimate : 0.0;
    const double off_distance = off_data_distance(result, options);
    result.off_data_distance = off_distance;
    detail::DataFit fit;
    std::vector<Vec3> retry_normals;  // the normals of the mesh kept, when a retry's
    {
      StageTimer timer(result.stages, "data fit");
      fit = detail::fit_to_data(result.mesh, input.points, oriented.normals, off_distance);  // oriented: the input's points
    }
    const bool may_retry = options.refit_off_data && options.repair_normal_signs && options.check_input_normals;
    const std::size_t worth_a_retry = std::max<std::size_t>(10, oriented.size() / 5000);
    result.off_data_points_before_retry = fit.off.size();
    if (may_retry && fit.off_and_against.size() >= worth_a_retry) {
      // Two flip sets: the points off and against the mesh, and all the
      // points off it within 3 spacings of those (on a curved wall part of
      // an inverted patch agrees with the wrong facets: couplingdown seed 2,
      // 43 flips left a cap in the hole, 2.82 U; 44 reopened it, 1.76 U;
      // spool 50k at delta 3.5 is the other way round, 4.60 and 5.34 U).
      std::vector<std::vector<std::uint32_t>> flip_sets{fit.off_and_against};
      std::vector<std::uint32_t> region = detail::within_reach(input.points, fit.off, fit.off_and_against, 3 * result.average_spacing);
      if (region.size() > fit.off_and_against.size()) flip_sets.push_back(std::move(region));
      std::vector<StageTiming> stages = result.stages;
      std::optional<ReconstructResult> best;
      detail::DataFit best_fit;
      for (std::size_t attempt = 0; attempt < flip_sets.size(); ++attempt) {
        ReconstructResult retry = result;
        retry.stages.clear();
        const std::string prefix = "retry " + std::to_string(attempt + 1) + ": ";
        PointSet flipped = oriented;
        const std::size_t flips = detail::flip_around(flipped, flip_sets[attempt], 1.5 * result.average_spacing);
        try {
          PoissonDiagnostics retry_diagnostics;
          std::unique_ptr<ImplicitSurface> function;
          {
            StageTimer timer(retry.stages, prefix + "poisson and sign repair");
            function = solve(flipped, retry_diagnostics, nullptr);
            retry.sign_repaired_normals =
                result.sign_repaired_normals + repair_normal_signs(flipped, function, retry_diagnostics, result.average_spacing,
                                                      [&](const PointSet& points, PoissonDiagnostics& d) { return solve(points, d, nullptr); });
          }
          retry.poisson_points = function->sample_count();
          retry.normal_agreement = retry_diagnostics.normal_agreement;
          retry.thin_points = 0;
          retry.flattened_vertices = retry.unflattened_vertices = 0;
          build_mesh(std::move(function), flipped, retry, prefix);
          detail::DataFit refit;
          {
            StageTimer timer(retry.stages, prefix + "data fit");
            refit = detail::fit_to_data(retry.mesh, input.points, flipped.normals, off_distance);
          }
          stages.insert(stages.end(), retry.stages.begin(), retry.stages.end());
          // A quarter fewer inverted, no more off in all, and the farthest
          // point no farther (PIF on couplingdown 50k kept a retry that
          // left 3.65 -> 3.81 U); of two such, the one with fewer points
          // off and vertices without data.
          const bool better = 4 * refit.off_and_against.size() <= 3 * fit.off_and_against.size() && refit.off.size() <= fit.off.size() &&
                              refit.max_distance <= fit.max_distance;
          if (better && (!best || refit.off.size() + refit.invented_vertices < best_fit.off.size() + best_fit.invented_vertices)) {
            retry.off_data_flips = flips;
            best = std::move(retry);
            best_fit = std::move(refit);
            retry_normals = std::move(flipped.normals);
          }
        } catch (const NumericalFailure&) {
          stages.insert(stages.end(), retry.stages.begin(), retry.stages.end());
        }
        ++result.data_fit_retries;
        if (best && best_fit.off.empty() && best_fit.invented_vertices == 0) break;  // nothing left to improve
      }
      if (best) {
        best->data_fit_retries = result.data_fit_retries;
        result = std::move(*best);
        fit = std::move(best_fit);
      }
      result.stages = std::move(stages);
    }
    // Beyond the thesis: vertices onto the corners and data points the mesh
    // misses by more than the balls and the refinement could close (after the
    // retry decision, which must see the misses). With extracted features
    // only: the PIF baseline stays the thesis's. Onto data points only on
    // clean clouds: a noisy point is no better than the mesh (fandisk and
    // anchor 50k with 0.5% noise: mean distance 0.13 -> 0.19 U, 0.15 -> 0.19 U).
    if (options.snap_vertices && options.feature_mode == FeatureMode::Extract && !result.mesh.faces.empty()) {
      std::vector<Vec3> corners;
      for (const Junction& j : result.features.graph.junctions)
        if (j.degree >= 2) corners.push_back(j.position);
      const bool clean = result.features.denoise_passes == 0 && noise < kCleanNoiseRatio * result.average_spacing;
      SnappingOptions snapping;
      // The rounding left is 1-1.5 spacings; a vertex moves at most 2.
      snapping.max_move = 2 * result.average_spacing + 3 * noise;
      snapping.corner_present = 0.25 * result.average_spacing + 3 * noise;
      snapping.data_present = 0.75 * result.average_spacing + 3 * noise;
      snapping.support_radius = 1.5 * result.average_spacing;
      snapping.points_are_targets = clean;
      snapping.average_spacing = result.average_spacing;
      if (clean) snapping.point_normals = retry_normals.empty() ? oriented.normals : retry_normals;
      {
        StageTimer timer(result.stages, "snapping");
        const SnappingStats stats = snap_to_corners_and_data(result.mesh, corners, input.points, snapping);
        result.snapped_corners = stats.corners;
        result.snapped_to_data = stats.data_points;
        result.snapped_off_data = stats.off_data_vertices;
        result.unsnapped_vertices = stats.undone;
      }
      if (result.snapped_corners + result.snapped_to_data + result.snapped_off_data > result.unsnapped_vertices) {
        StageTimer timer(result.stages, "data fit after snapping");
        fit = detail::fit_to_data(result.mesh, input.points, retry_normals.empty() ? oriented.normals : retry_normals, off_distance);
      }
    }
    result.off_data_points = fit.off.size();
    result.off_data_against = fit.off_and_against.size();
    result.invented_vertices = fit.invented_vertices;
    result.max_data_distance = fit.max_distance;
  }
  return result;
}

}  // namespace
}  // namespace sharpmesh
