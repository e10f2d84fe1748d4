// sharpmesh reconstruct CLOUD -o MESH: the Chapter 7 pipeline.
#include <cstdio>

#include "cli.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"
#include "sharpmesh/reconstruct.h"

namespace sharpmesh::cli {
namespace {

nlohmann::json protection_report(const ReconstructResult& r, double diagonal) {
  const ImplicitMeshingResult& m = r.meshing;
  nlohmann::json gaps = nlohmann::json::array();
  for (const UncoveredGap& g : m.uncovered)
    gaps.push_back({{"center", g.center}, {"length", length_json(g.length, diagonal)}, {"gap", length_json(g.gap, diagonal)},
                    {"refused_by_mesher", g.refused_by_mesher}, {"too_close", g.too_close}});
  return {{"polylines", r.features.graph.polylines.size()},
          {"protecting_balls", m.protecting_balls},
          {"enlarged_balls", m.enlarged_balls},
          {"protection_rounds_exhausted", m.protection_rounds_exhausted},
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

}  // namespace

Command add_reconstruct(CLI::App& app) {
  struct Options {
    std::string input, output, normals = "auto", features_file, sharp_edges_out;
    bool no_features = false, fixed_balls = false, no_flattening = false, no_snapping = false, no_sign_repair = false, no_winding_repair = false, no_thin_vertices = false, no_anchors = false, no_data_fit_retry = false, no_intersection_repair = false, allow_invalid = false, ascii = false;
    double time_limit = 0;
    ReconstructOptions reconstruct;
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand(
      "reconstruct", "Point cloud -> mesh with sharp edges: features, normals, Poisson implicit function, protected Delaunay refinement (thesis Ch. 7)");
  sub->add_option("CLOUD", o->input, "Input point cloud (.ply, .xyz, .pwn, .off, .las); normals are used if present")->required();
  sub->add_option("-o,--output", o->output, "Output mesh (.ply, .off, .obj)")->required();
  sub->add_option("--delta", o->reconstruct.delta,
                  "Mesh size d' = delta x average spacing (6-NN); facet angle 25 deg, edges <= 2d', distance <= 0.6d' (7.3.2)")
      ->capture_default_str();
  auto* no_features = sub->add_flag("--no-features", o->no_features,
                                    "Plain Delaunay refinement of the Poisson implicit function (the thesis's PIF baseline)");
  sub->add_option("--features", o->features_file, "Protect these polylines (CGAL text format) instead of extracting features")
      ->excludes(no_features);
  sub->add_option("--sharp-edges", o->sharp_edges_out, "Write the mesh edges that represent the protected features (polylines)");
  sub->add_option("--ball-radius", o->reconstruct.ball_radius, "Protecting-ball radius, fraction of d' (7.3.2)")->capture_default_str();
  sub->add_flag("--fixed-balls", o->fixed_balls,
                "Keep every ball at --ball-radius (the thesis) instead of growing it to reach the implicit surface");
  sub->add_option("--trim", o->reconstruct.trim_distance,
                  "Remove facets farther than TRIM x d' + 2 avg from every input point, so open scans give open meshes (0: keep the closed Poisson surface)")
      ->capture_default_str();
  sub->add_option("--poisson-spacing", o->reconstruct.poisson_spacing,
                  "Solve Poisson on a grid simplification of the cloud with cells of F x d' (0: on every point)")
      ->capture_default_str();
  sub->add_option("--poisson-thinning", o->reconstruct.poisson_thinning,
                  "Leave out of Poisson the points closer than F x avg to an earlier point (0: keep all); near-coincident pairs cost most of Poisson's time")
      ->capture_default_str();
  sub->add_option("--poisson-screening", o->reconstruct.poisson_screening,
                  "Pull of Poisson's function towards the points, relative to its smoothness, with lengths in average spacings: the same surface in any unit (0: CGAL's own weight, which depends on the unit)")
      ->capture_default_str();
  sub->add_option("--poisson-screening-noisy", o->reconstruct.poisson_screening_noisy,
                  "The same on clouds the feature extraction finds noisy (denoised, or noise of 0.05 avg or more)")
      ->capture_default_str();
  sub->add_option("--seed-spacing", o->reconstruct.data_seed_spacing,
                  "Before refinement, project one input point per cell of F x d' onto the implicit surface as a mesh vertex, so parts thinner than the facets are not stepped over (0: none)")
      ->capture_default_str();
  sub->add_flag("--no-flattening", o->no_flattening,
                "Keep the facets along protected edges on the Poisson surface (the thesis) instead of moving their third vertices onto the data's face planes");
  sub->add_flag("--no-snapping", o->no_snapping,
                "Leave the mesh where the refinement put it (the thesis) instead of moving vertices (2 average spacings at most) onto the "
                "corners and data points it misses by more than 0.25 and 0.75 spacings (with features only)");
  sub->add_option("--normals", o->normals, "Normals when the input has none: auto (with features: cvcm; where the CVCM is isotropic, jet normals for the orientation, then crease-aware plane fits on clean clouds; else jet), cvcm (thesis 7.4 throughout), jet or pca")
      ->check(CLI::IsMember({"auto", "cvcm", "pca", "jet"}))
      ->capture_default_str();
  sub->add_option("--normal-k", o->reconstruct.normals.k, "Neighbours for jet/pca normal estimation")->capture_default_str();
  sub->add_option("--orient-k", o->reconstruct.orientation.k, "Neighbours for MST normal orientation")->capture_default_str();
  sub->add_flag("--recompute-normals", o->reconstruct.recompute_normals, "Ignore the input's normals and estimate new ones");
  sub->add_flag("--no-sign-repair", o->no_sign_repair,
                "Keep the normals the Poisson function contradicts (by default they are flipped and Poisson solved again, up to 3 times)");
  sub->add_flag("--no-orientation-anchors", o->no_anchors,
                "Grow the normal orientation's MST from one seed per component, not from the signs the cloud's occupancy and sheet parity "
                "decide (automatic normals with features only)");
  sub->add_flag("--no-thin-vertices", o->no_thin_vertices,
                "Solve Poisson on the samples' own triangulation only, without vertices half-way across parts and gaps 1-6 avg thick "
                "(without them the function is flat inside a thin plate and its zero set wanders)");
  sub->add_flag("--no-winding-repair", o->no_winding_repair,
                "Keep the estimated normals of regions whose outer side the rest of the cloud encloses, by its generalized winding number "
                "(by default they are flipped before Poisson; automatic normals with features only)");
  sub->add_flag("--no-data-fit-retry", o->no_data_fit_retry,
                "Keep the first mesh even when input points lie off it (farther than 1.5 average spacings or the surface-distance criterion) "
                "with normals against it (by default their normals and those around them are flipped, Poisson solved and meshed again, and "
                "the new mesh is kept when it leaves a quarter fewer such points, no more off in all and none farther)");
  sub->add_option("--max-facets", o->reconstruct.max_facets, "Refuse to start when the estimated facet count is above this (0: no limit)")
      ->capture_default_str();
  sub->add_option("--protection-budget", o->reconstruct.protection_budget,
                  "Ball-size queries CGAL's protection of the feature polylines may make per polyline point; past them the "
                  "surface is meshed without it and the report says so (0: no limit)")
      ->capture_default_str();
  sub->add_option("--time-limit", o->time_limit,
                  "Seconds the whole reconstruction may take; past them it stops with exit status 1 and writes nothing (0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sub->add_option("--seed", o->reconstruct.seed, "Seed of the refinement's initial points")->capture_default_str();
  sub->add_flag("--no-intersection-repair", o->no_intersection_repair,
                "Leave facets that cross others as the refinement made them (by default they are cut out with a ring of "
                "neighbours and the holes filled)");
  sub->add_flag("--allow-invalid", o->allow_invalid,
                "Write the mesh even if facets still cross others after the repair (by default nothing is written and "
                "the exit status is 1)");
  sub->add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
  add_feature_options(*sub, o->reconstruct.features);
  common->add_to(*sub);
  auto run = [o, common] {
    check_output(o->output, "mesh");
    check_output(o->sharp_edges_out, "sharp edges");
    check_output(common->report, "report");
    ReconstructOptions& options = o->reconstruct;
    options.feature_mode = o->no_features ? FeatureMode::None : o->features_file.empty() ? FeatureMode::Extract : FeatureMode::Given;
    options.adapt_balls_to_gap = !o->fixed_balls;
    options.repair_normal_signs = !o->no_sign_repair;
    options.refit_off_data = !o->no_data_fit_retry;
    options.repair_enclosed_normals = !o->no_winding_repair;
    options.thin_part_vertices = !o->no_thin_vertices;
    options.anchor_orientation = !o->no_anchors;
    options.flatten_features = !o->no_flattening;
    options.snap_vertices = !o->no_snapping;
    options.repair_self_intersections = !o->no_intersection_repair;
    if (o->normals == "auto") {
      options.normal_source = NormalSource::Automatic;
    } else if (o->normals == "cvcm") {
      options.normal_source = NormalSource::Cvcm;
    } else {
      options.normal_source = NormalSource::Estimated;
      options.normals.method = o->normals == "pca" ? NormalMethod::Pca : NormalMethod::Jet;
    }
    if (options.normal_source == NormalSource::Cvcm && options.feature_mode != FeatureMode::Extract)
      throw InvalidArgument("--normals cvcm needs feature extraction (drop --no-features / --features)");
    const auto start = std::chrono::steady_clock::now();
    std::vector<StageTiming> io_stages;
    PointSet points;
    {
      StageTimer timer(io_stages, "read");
      points = read_point_set(o->input);
      if (options.feature_mode == FeatureMode::Given) options.given_features = read_polylines(o->features_file);
    }
    ProgressPrinter printer(common->quiet);
    // The user's time limit is the only clock: the library decides by counts.
    const Progress printed = printer.callback();
    const double limit = o->time_limit;
    bool timed_out = false;
    const Progress progress = [&](const std::string& stage, double fraction) {
      if (limit > 0 && seconds_since(start) > limit) return !(timed_out = true);
      return printed(stage, fraction);
    };
    ReconstructResult result;
    try {
      result = reconstruct(points, options, progress);
    } catch (const Cancelled&) {
      if (!timed_out) throw;
      throw Error(o->input + ": the reconstruction ran past --time-limit " + format_number(limit) + " s; nothing written");
    }
    const bool crossing = options.repair_self_intersections ? result.intersection_repair.remaining_pairs > 0
                                                             : !self_intersecting_faces(result.mesh).empty();
    if (crossing && !o->allow_invalid)
      throw Error(o->input + ": the mesh has facets that cross others" +
                  (options.repair_self_intersections ? " after " + std::to_string(result.intersection_repair.rounds) + " repair rounds" : std::string()) +
                  "; nothing written (--allow-invalid writes it anyway)");
    {
      StageTimer timer(io_stages, "write");
      write_mesh(o->output, result.mesh, o->ascii ? PlyFormat::Ascii : PlyFormat::Binary);
      if (!o->sharp_edges_out.empty()) write_polylines(o->sharp_edges_out, result.meshing.feature_edges);
    }
    std::vector<StageTiming> stages{io_stages[0]};
    stages.insert(stages.end(), result.stages.begin(), result.stages.end());
    stages.push_back(io_stages[1]);
    const double diagonal = bounding_box(points.points).diagonal();
    const ImplicitMeshingResult& m = result.meshing;
    if (!common->quiet) {
      printer.message("reconstruct: " + std::to_string(result.input_points) + " points -> " + std::to_string(result.mesh.faces.size()) +
                      " facets, " + std::to_string(result.mesh.vertices.size()) + " vertices -> " + o->output);
      if (result.trimmed_facets > 0)
        printer.message("  open surface: " + std::to_string(result.trimmed_facets) + " facets far from the data removed, " +
                        std::to_string(result.clipped_facets) + " cut along the data's edge, " +
                        std::to_string(result.boundary_edges) + " boundary edges");
      if (result.intersection_repair.intersecting_pairs > 0)
        printer.message("  self-intersections: " + std::to_string(result.intersection_repair.intersecting_pairs) + " crossing facet pairs, " +
                        std::to_string(result.intersection_repair.removed_facets) + " facets cut out, " +
                        std::to_string(result.intersection_repair.added_facets) + " filled in, " +
                        std::to_string(result.intersection_repair.remaining_pairs) + " pairs left");
      if (result.dataless_facets > 0)
        printer.message("  " + std::to_string(result.dataless_facets) + " facets of components away from the data removed");
      if (options.feature_mode != FeatureMode::None) {
        char line[200];
        std::snprintf(line, sizeof line, "  features: %zu polylines, %zu balls (%zu grown), %zu/%zu segments are mesh edges, %zu uncovered gaps",
                      result.features.graph.polylines.size(), m.protecting_balls, m.enlarged_balls, m.represented_segments,
                      m.protected_segments, m.uncovered.size());
        printer.message(line);
      }
      for (const StageTiming& s : stages) {
        char line[160];
        std::snprintf(line, sizeof line, "  %-26s %8.2f s  %8.1f MiB peak", s.name.c_str(), s.seconds, s.peak_rss_bytes / 1048576.0);
        printer.message(line);
      }
    }
    nlohmann::json report = {
        {"command", "reconstruct"},
        {"input", o->input},
        {"output", o->output},
        {"parameters",
         {{"features", o->no_features ? "none" : o->features_file.empty() ? "extract" : o->features_file},
          {"delta", options.delta}, {"spacing_k", options.spacing_k}, {"ball_radius", options.ball_radius},
          {"adapt_balls_to_gap", options.adapt_balls_to_gap},
          {"trim", options.trim_distance}, {"poisson_spacing", options.poisson_spacing}, {"poisson_thinning", options.poisson_thinning}, {"poisson_screening", options.poisson_screening}, {"poisson_screening_noisy", options.poisson_screening_noisy}, {"seed_spacing", options.data_seed_spacing}, {"flattening", options.flatten_features}, {"snapping", options.snap_vertices}, {"normals", o->normals}, {"normal_k", options.normals.k},
          {"orient_k", options.orientation.k}, {"recompute_normals", options.recompute_normals}, {"sign_repair", options.repair_normal_signs}, {"winding_repair", options.repair_enclosed_normals}, {"thin_vertices", options.thin_part_vertices}, {"orientation_anchors", options.anchor_orientation}, {"data_fit_retry", options.refit_off_data},
          {"max_facets", options.max_facets}, {"protection_budget", options.protection_budget}, {"time_limit_s", o->time_limit}, {"seed", options.seed}}},
        {"derived",
         {{"average_spacing", length_json(result.average_spacing, diagonal)},
          {"d_prime", length_json(result.d_prime, diagonal)},
          {"facet_angle_deg", result.criteria.angle},
          {"max_edge_length", length_json(result.criteria.edge_length, diagonal)},
          {"max_surface_distance", length_json(result.criteria.distance, diagonal)},
          {"ball_radius", length_json(options.ball_radius * result.d_prime, diagonal)},
          {"estimated_facets", result.estimated_facets}}},
        {"counts",
         {{"input_points", result.input_points}, {"duplicate_points", result.duplicate_points}, {"points_used", result.used_points}, {"poisson_points", result.poisson_points}, {"normal_agreement", result.normal_agreement},
          {"normals_estimated", result.normals_estimated}, {"normal_source", result.normal_source}, {"input_normal_agreement", result.input_normal_agreement}, {"isotropic_cvcm_normals", result.isotropic_cvcm_normals}, {"patch_flipped_normals", result.patch_flipped_normals}, {"enclosed_flipped_normals", result.enclosed_flipped_normals}, {"sharpened_normals", result.sharpened_normals}, {"sign_repaired_normals", result.sign_repaired_normals},
          {"vertices", result.mesh.vertices.size()}, {"facets", result.mesh.faces.size()},
          {"anchored_normals", result.anchored_normals}, {"thin_part_vertices", result.thin_part_vertices}, {"restricted_to_data", result.restricted}, {"data_seeds", m.data_seeds}, {"thin_points", result.thin_points}, {"flattened_vertices", result.flattened_vertices}, {"unflattened_vertices", result.unflattened_vertices}, {"poisson_screening", result.poisson_screening}, {"snapped_corners", result.snapped_corners}, {"snapped_to_data", result.snapped_to_data}, {"snapped_off_data", result.snapped_off_data}, {"unsnapped_vertices", result.unsnapped_vertices}, {"trimmed_facets", result.trimmed_facets}, {"dataless_facets", result.dataless_facets}, {"clipped_facets", result.clipped_facets}, {"boundary_edges", result.boundary_edges}}},
        {"stages", stages_json(stages)},
        {"seconds", seconds_since(start)}};
    const double spacing = result.average_spacing > 0 ? result.average_spacing : 1.0;
    report["data_fit"] = {{"off_distance", length_json(result.off_data_distance, diagonal)},
                          {"off_distance_avg_spacings", result.off_data_distance / spacing},
                          {"points_off_mesh", result.off_data_points},
                          {"points_off_against_mesh", result.off_data_against},
                          {"vertices_off_data", result.invented_vertices},
                          {"retries", result.data_fit_retries},
                          {"max_distance", length_json(result.max_data_distance, diagonal)},
                          {"max_distance_avg_spacings", result.max_data_distance / spacing},
                          {"points_off_first_mesh", result.off_data_points_before_retry},
                          {"retry_flipped_normals", result.off_data_flips}};
    // Points off a rounded edge agree with the mesh (PIF rounds every edge): only those against it are worth a warning.
    if (result.off_data_against > 0 && !common->quiet)
      std::fprintf(stderr, "reconstruct: warning: %zu input points lie more than %.2f average spacings from the mesh with normals against it (farthest point %.2f): the surface may have closed a hole or a slot there\n",
                   result.off_data_against, result.off_data_distance / spacing, result.max_data_distance / spacing);
    if (options.feature_mode != FeatureMode::None) report["protection"] = protection_report(result, diagonal);
    report["self_intersections"] = {{"repair", options.repair_self_intersections},
                                    {"found_pairs", result.intersection_repair.intersecting_pairs},
                                    {"remaining_pairs", result.intersection_repair.remaining_pairs},
                                    {"removed_facets", result.intersection_repair.removed_facets},
                                    {"added_facets", result.intersection_repair.added_facets},
                                    {"written_invalid", crossing}};
    report["refinement"] = {{"steps", result.meshing.refinement_steps}, {"stalled", result.meshing.refinement_stalled}, {"runaway", result.meshing.refinement_runaway}};
    if (result.meshing.refinement_runaway && !common->quiet)
      std::fprintf(stderr, "reconstruct: warning: refinement was still adding vertices long after the expected count and was ended; check the mesh's topology\n");
    if (result.meshing.protection_stopped && !common->quiet)
      std::fprintf(stderr, "reconstruct: warning: the protection of the feature polylines ran past its budget of %g queries per polyline point "
                           "and was stopped; the mesh was made without it (raise --protection-budget)\n", options.protection_budget);
    if (result.meshing.refinement_stalled && !common->quiet)
      std::fprintf(stderr, "reconstruct: warning: refinement stopped adding vertices and was ended early; check the mesh's topology\n");
    if (!common->quiet && result.normal_source == "input (re-oriented)")
      std::fprintf(stderr, "reconstruct: note: the input's normal signs are inconsistent (%.0f%% agree with a consistent orientation); re-oriented by MST\n",
                   100 * result.input_normal_agreement);
    if (!common->quiet && result.normal_source.find("input normals unusable") != std::string::npos)
      std::fprintf(stderr, "reconstruct: note: fewer than half of the input's normals are non-zero; normals estimated instead\n");
    if (options.feature_mode == FeatureMode::Extract) report["features"] = feature_report(result.features, options.features, diagonal);
    write_report(common->report, report);
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
