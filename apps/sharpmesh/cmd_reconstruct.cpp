// sharpmesh reconstruct CLOUD -o MESH: the Chapter 7 pipeline.
#include <cstdio>

#include "cli.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"
#include "option_flags.h"
#include "sharpmesh/reconstruct.h"
#include "sharpmesh/report.h"
#include "sharpmesh/tiled.h"

#include <cmath>

namespace sharpmesh::cli {

Command add_reconstruct(CLI::App& app) {
  struct Options {
    std::string input, output, features_file, sharp_edges_out;
    std::vector<int> classes;
    bool no_features = false, allow_invalid = false, ascii = false;
    double time_limit = 0;
    ReconstructOptions reconstruct;
    TilingOptions tiling{1};
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand(
      "reconstruct", "Point cloud -> mesh with sharp edges: features, normals, Poisson implicit function, protected Delaunay refinement (thesis Ch. 7)");
  sub->add_option("CLOUD", o->input, "Input point cloud (.ply, .xyz, .pwn, .off, .las, .laz); normals are used if present")->required();
  add_classes_option(*sub, o->classes);
  sub->add_option("-o,--output", o->output, "Output mesh (.ply, .off, .obj)")->required();
  auto* no_features = sub->add_flag("--no-features", o->no_features,
                                    "Plain Delaunay refinement of the Poisson implicit function (the thesis's PIF baseline)");
  sub->add_option("--features", o->features_file, "Protect these polylines (CGAL text format) instead of extracting features")
      ->excludes(no_features);
  sub->add_option("--sharp-edges", o->sharp_edges_out, "Write the mesh edges that represent the protected features (polylines)");
  add_option_fields(*sub, o->reconstruct, reconstruct_option_fields(), {"threads"});
  add_option_fields(*sub, o->tiling, tiling_option_fields(), {});
  sub->add_option("--time-limit", o->time_limit,
                  "Seconds the whole reconstruction may take; past them it stops with exit status 1 and writes nothing (0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  add_mesh_output_flags(*sub, o->allow_invalid, o->ascii);
  common->add_to(*sub);
  auto run = [o, common] {
    check_output(o->output, "mesh");
    check_output(o->sharp_edges_out, "sharp edges");
    check_output(common->report, "report");
    o->tiling.check();
    ReconstructOptions& options = o->reconstruct;
    options.threads = common->threads;
    options.feature_mode = o->no_features ? FeatureMode::None : o->features_file.empty() ? FeatureMode::Extract : FeatureMode::Given;
    const auto start = std::chrono::steady_clock::now();
    std::vector<StageTiming> io_stages;
    PointSet points;
    {
      StageTimer timer(io_stages, "read");
      points = read_cloud(o->input, o->classes);
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
    TiledResult tiled;
    try {
      if (o->tiling.tiles > 1) {
        tiled = reconstruct_tiled(points, options, o->tiling, progress);
        result = std::move(tiled.merged);
      } else {
        result = reconstruct(points, options, progress);
      }
    } catch (const Cancelled&) {
      if (!timed_out) throw;
      throw Error(o->input + ": the reconstruction ran past --time-limit " + format_number(limit) + " s; nothing written");
    }
    const bool crossing = options.repair_self_intersections ? result.repairs.intersection_repair.remaining_pairs > 0
                                                             : !self_intersecting_faces(result.mesh).empty();
    if (crossing && !o->allow_invalid)
      throw Error(o->input + ": the mesh has facets that cross others" +
                  (options.repair_self_intersections ? " after " + std::to_string(result.repairs.intersection_repair.rounds) + " repair rounds" : std::string()) +
                  "; nothing written (--allow-invalid writes it anyway)");
    {
      StageTimer timer(io_stages, "write");
      write_mesh(o->output, result.mesh, o->ascii ? PlyFormat::Ascii : PlyFormat::Binary);
      if (!o->sharp_edges_out.empty()) write_polylines(o->sharp_edges_out, result.meshing.feature_edges);
    }
    std::vector<StageTiming> stages{io_stages[0]};
    stages.insert(stages.end(), result.stages.begin(), result.stages.end());
    stages.push_back(io_stages[1]);
    const ImplicitMeshingResult& m = result.meshing;
    if (!common->quiet) {
      printer.message("reconstruct: " + std::to_string(result.input_points) + " points -> " + std::to_string(result.mesh.faces.size()) +
                      " facets, " + std::to_string(result.mesh.vertices.size()) + " vertices -> " + o->output);
      for (const SeamResult& seam : tiled.seams) {
        char line[300];
        std::snprintf(line, sizeof line, "  seam at %g: %s", seam.position,
                      seam.stitched ? (std::to_string(seam.chains) + " curves welded, " + std::to_string(seam.inserted_vertices) +
                                       " vertices inserted").c_str()
                                    : ("not welded (" + seam.failure + ")").c_str());
        printer.message(line);
      }
      if (result.repairs.trimmed_facets > 0)
        printer.message("  open surface: " + std::to_string(result.repairs.trimmed_facets) + " facets far from the data removed, " +
                        std::to_string(result.repairs.clipped_facets) + " cut along the data's edge, " +
                        std::to_string(result.boundary_edges) + " boundary edges");
      if (result.repairs.intersection_repair.intersecting_pairs > 0)
        printer.message("  self-intersections: " + std::to_string(result.repairs.intersection_repair.intersecting_pairs) + " crossing facet pairs, " +
                        std::to_string(result.repairs.intersection_repair.removed_facets) + " facets cut out, " +
                        std::to_string(result.repairs.intersection_repair.added_facets) + " filled in, " +
                        std::to_string(result.repairs.intersection_repair.remaining_pairs) + " pairs left");
      if (result.repairs.dataless_facets > 0)
        printer.message("  " + std::to_string(result.repairs.dataless_facets) + " facets of components away from the data removed");
      if (result.repairs.thin_shell_facets > 0)
        printer.message("  " + std::to_string(result.repairs.thin_shell_facets) + " facets of shells enclosing a space too thin for the data removed");
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
    nlohmann::json report = nlohmann::json::parse(reconstruct_report_json(result, options));
    report["command"] = "reconstruct";
    report["input"] = o->input;
    report["output"] = o->output;
    report["parameters"]["features_file"] = o->features_file;
    report["parameters"]["time_limit_s"] = o->time_limit;
    report["self_intersections"]["written_invalid"] = crossing;
    report["stages"] = stages_json(stages);
    report["seconds"] = seconds_since(start);
    if (o->tiling.tiles > 1) {
      nlohmann::json tiles = nlohmann::json::array(), seams = nlohmann::json::array();
      for (const TileResult& t : tiled.tiles)
        tiles.push_back({{"low", std::isfinite(t.low) ? nlohmann::json(t.low) : nlohmann::json(nullptr)},
                         {"high", std::isfinite(t.high) ? nlohmann::json(t.high) : nlohmann::json(nullptr)}, {"points", t.points},
                         {"facets", t.facets}, {"seconds", t.seconds}, {"peak_memory_mib", t.peak_rss_bytes / 1048576.0}});
      for (const SeamResult& seam : tiled.seams)
        seams.push_back({{"position", seam.position}, {"stitched", seam.stitched}, {"failure", seam.failure}, {"chains", seam.chains},
                         {"inserted_vertices", seam.inserted_vertices}, {"max_move_d_prime", seam.max_move}});
      report["tiling"] = {{"axis", tiled.axis}, {"tiles", tiles}, {"seams", seams}, {"merged_seams", tiled.merged_seams}};
    }
    if (!common->quiet)
      for (const Warning& w : result.warnings) std::fprintf(stderr, "reconstruct: warning: %s\n", w.message.c_str());
    write_report(common->report, report);
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
