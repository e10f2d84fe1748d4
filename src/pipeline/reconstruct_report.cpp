// The report of the Chapter 7 pipeline (sharpmesh/report.h).
#include "core/field_json.h"
#include "sharpmesh/report.h"

namespace sharpmesh {
namespace detail {

nlohmann::json feature_report(const FeatureResult& result, const FeatureOptions& options, double diagonal);
nlohmann::json decimation_report(const DecimationResult& result);

namespace {

const char* feature_mode_name(FeatureMode mode) {
  return mode == FeatureMode::Extract ? "extract" : mode == FeatureMode::Given ? "given" : "none";
}

nlohmann::json protection_report(const ReconstructResult& r, const ReconstructOptions& o) {
  const ImplicitMeshingResult& m = r.meshing;
  const double diagonal = r.diagonal;
  nlohmann::json gaps = nlohmann::json::array();
  for (const UncoveredGap& g : m.uncovered)
    gaps.push_back({{"center", g.center}, {"length", length_json(g.length, diagonal)}, {"gap", g.gap >= 0 ? length_json(g.gap, diagonal) : nlohmann::json()},
                    {"refused_by_mesher", g.refused_by_mesher}, {"too_close", g.too_close}, {"on_thin_part", g.on_thin_part}});
  const std::size_t polylines = o.feature_mode == FeatureMode::Given ? o.given_features.size() : r.features.graph.polylines.size();
  return {{"polylines", polylines},
          {"protecting_balls", m.protecting_balls},
          {"enlarged_balls", m.enlarged_balls},
          {"protecting_balls_intersect", m.protecting_balls_intersect},
          {"protection_stopped", m.protection_stopped},
          {"protection_queries", m.protection_queries},
          {"max_gap", length_json(m.max_gap, diagonal)},
          {"protected_segments", m.protected_segments},
          {"represented_segments", m.represented_segments},
          {"represented_fraction", m.protected_segments ? double(m.represented_segments) / m.protected_segments : 1.0},
          {"uncovered_gaps", gaps.size()},
          {"uncovered", gaps},
          {"feature_edge_polylines", m.feature_edges.size()},
          {"mesher_retries", m.mesher_retries},
          {"runaway_stopped_at_vertices", m.runaway_stopped_at}};
}

/// "jet (cvcm fallback)", "pca (input normals unusable)": the origin with
/// the reason it is not the expected one.
std::string normal_source_text(const NormalsStats& n) {
  std::string text = to_string(n.normal_origin);
  if (n.cvcm_fallback) text += " (cvcm fallback)";
  if (n.input_normals_unusable) text += " (input normals unusable)";
  return text;
}

nlohmann::json normals_counts(const NormalsStats& n) {
  return {{"normals_estimated", n.normals_estimated},
          {"normal_source", normal_source_text(n)},
          {"input_normal_agreement", n.input_normal_agreement},
          {"isotropic_cvcm_normals", n.isotropic_cvcm_normals},
          {"anchored_normals", n.anchored_normals},
          {"patch_flipped_normals", n.patch_flipped_normals},
          {"enclosed_flipped_normals", n.enclosed_flipped_normals},
          {"sharpened_normals", n.sharpened_normals},
          {"sign_repaired_normals", n.sign_repaired_normals}};
}

nlohmann::json counts_report(const ReconstructResult& r) {
  nlohmann::json counts = normals_counts(r.normals);
  counts.update(nlohmann::json{{"input_points", r.input_points},
          {"duplicate_points", r.duplicate_points},
          {"points_used", r.used_points},
          {"poisson_points", r.implicit.poisson_points},
          {"normal_agreement", r.implicit.normal_agreement},
          {"vertices", r.mesh.vertices.size()},
          {"facets", r.mesh.faces.size()},
          {"thin_part_vertices", r.implicit.thin_part_vertices},
          {"restricted_to_data", r.implicit.restricted},
          {"data_seeds", r.meshing.data_seeds},
          {"thin_points", r.implicit.thin_points},
          {"flattened_vertices", r.repairs.flattened_vertices},
          {"unflattened_vertices", r.repairs.unflattened_vertices},
          {"poisson_screening", r.implicit.poisson_screening},
          {"snapped_corners", r.repairs.snapped_corners},
          {"snapped_to_data", r.repairs.snapped_to_data},
          {"snapped_off_data", r.repairs.snapped_off_data},
          {"unsnapped_vertices", r.repairs.unsnapped_vertices},
          {"trimmed_facets", r.repairs.trimmed_facets},
          {"dataless_facets", r.repairs.dataless_facets},
          {"thin_shell_facets", r.repairs.thin_shell_facets},
          {"clipped_facets", r.repairs.clipped_facets},
          {"boundary_edges", r.boundary_edges}});
  return counts;
}

nlohmann::json data_fit_report(const ReconstructResult& r) {
  const double spacing = r.average_spacing > 0 ? r.average_spacing : 1.0;
  return {{"off_distance", length_json(r.data_fit.off_data_distance, r.diagonal)},
          {"off_distance_avg_spacings", r.data_fit.off_data_distance / spacing},
          {"points_off_mesh", r.data_fit.off_data_points},
          {"points_off_against_mesh", r.data_fit.off_data_against},
          {"vertices_off_data", r.data_fit.invented_vertices},
          {"retries", r.data_fit.data_fit_retries},
          {"max_distance", length_json(r.data_fit.max_data_distance, r.diagonal)},
          {"max_distance_avg_spacings", r.data_fit.max_data_distance / spacing},
          {"points_off_first_mesh", r.data_fit.off_data_points_before_retry},
          {"retry_flipped_normals", r.data_fit.off_data_flips}};
}

}  // namespace

nlohmann::json reconstruct_report(const ReconstructResult& r, const ReconstructOptions& o) {
  const double diagonal = r.diagonal;
  nlohmann::json parameters = options_json(o, reconstruct_option_fields());
  parameters["feature_mode"] = feature_mode_name(o.feature_mode);
  nlohmann::json warnings = nlohmann::json::array();
  for (const Warning& w : r.warnings) warnings.push_back({{"code", w.code}, {"message", w.message}});
  nlohmann::json report = {
      {"parameters", parameters},
      {"derived",
       {{"diagonal", diagonal},
        {"average_spacing", length_json(r.average_spacing, diagonal)},
        {"d_prime", length_json(r.d_prime, diagonal)},
        {"facet_angle_deg", r.criteria.angle},
        {"max_edge_length", length_json(r.criteria.edge_length, diagonal)},
        {"max_surface_distance", length_json(r.criteria.distance, diagonal)},
        {"ball_radius", length_json(o.ball_radius * r.d_prime, diagonal)},
        {"estimated_facets", r.estimated_facets}}},
      {"counts", counts_report(r)},
      {"walls", {{"airborne", r.walls.airborne}, {"filled", r.walls.filled}, {"upper_points", r.walls.upper_points},
                 {"added_points", r.walls.added_points}}},
      {"data_fit", data_fit_report(r)},
      {"self_intersections",
       {{"repair", o.repair_self_intersections},
        {"found_pairs", r.repairs.intersection_repair.intersecting_pairs},
        {"remaining_pairs", r.repairs.intersection_repair.remaining_pairs},
        {"removed_facets", r.repairs.intersection_repair.removed_facets},
        {"added_facets", r.repairs.intersection_repair.added_facets},
        {"rounds", r.repairs.intersection_repair.rounds}}},
      {"refinement",
       {{"steps", r.meshing.refinement_steps}, {"stalled", r.meshing.refinement_stalled}, {"runaway", r.meshing.refinement_runaway}}},
      {"warnings", warnings},
      {"stages", stages_json(r.stages)}};
  if (r.decimation.input_facets > 0)
    report["decimation"] = decimation_report(r.decimation);
  if (o.feature_mode != FeatureMode::None) report["protection"] = protection_report(r, o);
  if (o.feature_mode == FeatureMode::Extract) report["features"] = feature_report(r.features, o.features, diagonal);
  return report;
}

}  // namespace detail

std::string reconstruct_report_json(const ReconstructResult& result, const ReconstructOptions& options) {
  return detail::reconstruct_report(result, options).dump();
}

std::string normals_report_json(const NormalsResult& result, const ReconstructOptions& options) {
  nlohmann::json counts = detail::normals_counts(result.normals);
  counts["points_used"] = result.points.size();
  const double diagonal = bounding_box(result.points.points).diagonal();
  nlohmann::json report = {{"parameters", detail::options_json(options, reconstruct_option_fields())},
                           {"derived", {{"diagonal", diagonal}, {"average_spacing", detail::length_json(result.average_spacing, diagonal)}}},
                           {"counts", counts},
                           {"stages", detail::stages_json(result.stages)}};
  if (options.feature_mode == FeatureMode::Extract) report["features"] = detail::feature_report(result.features, options.features, diagonal);
  return report.dump();
}

}  // namespace sharpmesh
