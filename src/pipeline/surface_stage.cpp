// The surface meshing stage: Delaunay refinement of the implicit function
// with protecting balls on the feature polylines (7.3.2), the flattening
// next to them and the open-surface trim.
#include <algorithm>
#include <cmath>

#include "pipeline/stages.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh::detail {
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
      ++result.implicit.thin_points;
    }
    meshing.expected_facets *= 1 + facet_ratio / static_cast<double>(oriented.size());
    meshing.thin_min_distance = result.average_spacing;
  }
  PointSet grid{oriented.points, {}, {}};
  grid_simplify(grid, spacing);
  meshing.data_seeds.insert(meshing.data_seeds.end(), grid.points.begin(), grid.points.end());
  meshing.data_seed_spacings.resize(meshing.data_seeds.size(), spacing);
}

}  // namespace

/// Distance beyond which an input point is off the mesh, or a mesh
/// component off the data: the refinement may leave the implicit surface by
/// its surface-distance criterion (0.6 d') and no more, plus the noise.
double off_data_distance(const ReconstructResult& r, const ReconstructOptions& options) {
  const double noise = options.feature_mode == FeatureMode::Extract ? r.features.noise_estimate : 0.0;
  const ReconstructTuning& tuning = options.tuning;
  return std::max(tuning.off_data_min * r.average_spacing, r.criteria.distance) + tuning.noise_deviations * noise;
}

void mesh_surface(const PipelineInput& in, std::unique_ptr<ImplicitSurface> function, const PointSet& normals,
                  double expected_facets, ReconstructResult& out, const std::string& retry_prefix) {
  const ReconstructOptions& options = in.options;
  const double trim_distance = options.trim_distance * out.d_prime + 2 * out.average_spacing;
  // Open inputs: cut the implicit function at twice the trim distance where
  // its zero set leaves the data, so Poisson's closing sheet is never
  // refined; the trim removes the cut.
  if (options.trim_distance > 0) {
    StageTimer timer(out.stages, retry_prefix + "restriction");
    const double domain_radius = meshing_domain_radius(*function);
    Restriction restriction = restrict_to_points(std::move(function), in.points.points, 2 * trim_distance, domain_radius);
    function = std::move(restriction.surface);
    out.implicit.restricted = restriction.applied;
  }
  ImplicitMeshingOptions meshing;
  meshing.criteria = out.criteria;
  meshing.max_facets = options.max_facets;
  meshing.expected_facets = expected_facets;
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
  // When most of the cloud reads as edge points, the offset radius R exceeds
  // the parts' thickness (7.2.1 assumes R below the reach): a bar thinner
  // than the convolution radius reads as an edge on all of its faces, and
  // its polylines trace across it. Those over thin parts are not trusted.
  const FeatureResult& features = out.features;
  meshing.features.drop_on_thin_parts = !features.points.empty() && 2 * features.edge_points > features.points.size();
  if (options.data_seed_spacing > 0) {
    StageTimer timer(out.stages, retry_prefix + "seeds");
    add_data_seeds(normals, options.data_seed_spacing * out.d_prime, out, meshing);
  }
  {
    StageTimer timer(out.stages, retry_prefix + "refinement");
    out.meshing = mesh_implicit_surface(*function, meshing, in.progress);
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
    const ReconstructTuning& tuning = options.tuning;
    flattening.radius = std::min(options.ball_radius * out.d_prime, tuning.flatten_radius * out.average_spacing);
    flattening.max_move = std::min(tuning.flatten_max_move * out.d_prime, tuning.flatten_max_move_spacings * out.average_spacing);
    flattening.max_residual = tuning.flatten_max_residual * out.d_prime;
    const std::vector<Vec3> before = out.mesh.vertices;
    out.repairs.flattened_vertices =
        flatten_next_to_features(out.mesh, out.meshing.feature_edges, normals.points, normals.normals, flattening);
    // A move can still push a facet through a neighbour: such moves go back.
    if (out.repairs.flattened_vertices > 0) {
      const std::size_t restored = undo_intersecting_moves(out.mesh, before);
      out.repairs.flattened_vertices -= std::min(out.repairs.flattened_vertices, restored);
      out.repairs.unflattened_vertices += restored;
    }
  }
  // Closed or open, a component whose vertices mostly lie off the data is
  // the implicit function's, not the data's (a bubble in a gap between
  // nested solids).
  out.repairs.dataless_facets = remove_components_off_points(out.mesh, in.points.points, off_data_distance(out, options));
  // A gap one or two spacings wide whose openings the implicit function
  // bridged leaves its air as a cavity of its own: filled, as the bridge
  // fills the rest (issue 36); a separate solid goes only below what the
  // pipeline resolves. With noise, a space narrower than the noise
  // allowance is not resolved either.
  {
    const double noise = options.feature_mode == FeatureMode::Extract ? out.features.noise_estimate : 0.0;
    const ReconstructTuning& tuning = options.tuning;
    const double allowance = tuning.noise_deviations * noise;
    out.repairs.thin_shell_facets =
        remove_thin_shell_components(out.mesh, std::max(tuning.thin_solid_max * out.average_spacing, allowance),
                                     std::max(tuning.thin_cavity_max * out.average_spacing, allowance));
  }
  if (options.trim_distance > 0) {
    StageTimer timer(out.stages, retry_prefix + "trim");
    out.repairs.trimmed_facets =
        trim_far_from_points(out.mesh, in.points.points, trim_distance);
    if (out.mesh.faces.empty()) throw NumericalFailure("reconstruction: no facet of the mesh lies near the input points");
    if (options.clip_boundary)
      out.repairs.clipped_facets = clip_boundary_to_points(out.mesh, in.points.points, out.average_spacing);
    out.boundary_edges = count_boundary_edges(out.mesh);
  }
}

}  // namespace sharpmesh::detail
