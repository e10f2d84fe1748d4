// sharpmesh reconstruct CLOUD -o MESH: the Chapter 7 pipeline.
#include <cstdio>

#include "cli.h"
#include "sharpmesh/io.h"
#include "sharpmesh/reconstruct.h"

namespace sharpmesh::cli {

Command add_reconstruct(CLI::App& app) {
  struct Options {
    std::string input, output, normals = "jet";
    bool no_features = false, ascii = false;
    ReconstructOptions reconstruct;
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("reconstruct", "Point cloud -> mesh: normals, Poisson implicit function, Delaunay refinement (thesis Ch. 7)");
  sub->add_option("CLOUD", o->input, "Input point cloud (.ply, .xyz, .pwn, .off, .las); normals are used if present")->required();
  sub->add_option("-o,--output", o->output, "Output mesh (.ply, .off, .obj)")->required();
  sub->add_option("--delta", o->reconstruct.delta,
                  "Mesh size d' = delta x average spacing (6-NN); facet angle 25 deg, edges <= 2d', distance <= 0.6d' (7.3.2)")
      ->capture_default_str();
  sub->add_flag("--no-features", o->no_features, "Plain Delaunay refinement of the Poisson implicit function (the thesis's PIF baseline)");
  sub->add_option("--normals", o->normals, "Normal estimation when the input has none: pca or jet")->check(CLI::IsMember({"pca", "jet"}))->capture_default_str();
  sub->add_option("--normal-k", o->reconstruct.normals.k, "Neighbours for normal estimation")->capture_default_str();
  sub->add_option("--orient-k", o->reconstruct.orientation.k, "Neighbours for MST normal orientation")->capture_default_str();
  sub->add_flag("--recompute-normals", o->reconstruct.recompute_normals, "Ignore the input's normals and estimate new ones");
  sub->add_option("--max-facets", o->reconstruct.max_facets, "Refuse to start when the estimated facet count is above this (0: no limit)")
      ->capture_default_str();
  sub->add_option("--seed", o->reconstruct.seed, "Seed of the refinement's initial points")->capture_default_str();
  sub->add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
  common->add_to(*sub);
  auto run = [o, common] {
    if (!o->no_features)
      throw InvalidArgument("feature-preserving reconstruction is not available in this version yet; pass --no-features for the PIF baseline");
    check_output(o->output, "mesh");
    check_output(common->report, "report");
    o->reconstruct.normals.method = o->normals == "pca" ? NormalMethod::Pca : NormalMethod::Jet;
    const auto start = std::chrono::steady_clock::now();
    std::vector<StageTiming> io_stages;
    PointSet points;
    {
      StageTimer timer(io_stages, "read");
      points = read_point_set(o->input);
    }
    ProgressPrinter printer(common->quiet);
    ReconstructResult result = reconstruct(points, o->reconstruct, printer.callback());
    {
      StageTimer timer(io_stages, "write");
      write_mesh(o->output, result.mesh, o->ascii ? PlyFormat::Ascii : PlyFormat::Binary);
    }
    std::vector<StageTiming> stages{io_stages[0]};
    stages.insert(stages.end(), result.stages.begin(), result.stages.end());
    stages.push_back(io_stages[1]);
    const double diagonal = bounding_box(points.points).diagonal();
    if (!common->quiet) {
      printer.message("reconstruct: " + std::to_string(result.input_points) + " points -> " + std::to_string(result.mesh.faces.size()) +
                      " facets, " + std::to_string(result.mesh.vertices.size()) + " vertices -> " + o->output);
      for (const StageTiming& s : stages) {
        char line[160];
        std::snprintf(line, sizeof line, "  %-12s %8.2f s  %8.1f MiB peak", s.name.c_str(), s.seconds, s.peak_rss_bytes / 1048576.0);
        printer.message(line);
      }
    }
    write_report(common->report,
                 {{"command", "reconstruct"},
                  {"input", o->input},
                  {"output", o->output},
                  {"parameters",
                   {{"features", !o->no_features}, {"delta", o->reconstruct.delta}, {"spacing_k", o->reconstruct.spacing_k},
                    {"normals", o->normals}, {"normal_k", o->reconstruct.normals.k}, {"orient_k", o->reconstruct.orientation.k},
                    {"recompute_normals", o->reconstruct.recompute_normals}, {"max_facets", o->reconstruct.max_facets},
                    {"seed", o->reconstruct.seed}}},
                  {"derived",
                   {{"average_spacing", length_json(result.average_spacing, diagonal)},
                    {"d_prime", length_json(result.d_prime, diagonal)},
                    {"facet_angle_deg", result.criteria.angle},
                    {"max_edge_length", length_json(result.criteria.edge_length, diagonal)},
                    {"max_surface_distance", length_json(result.criteria.distance, diagonal)},
                    {"estimated_facets", result.estimated_facets}}},
                  {"counts",
                   {{"input_points", result.input_points}, {"points_used", result.used_points},
                    {"normals_estimated", result.normals_estimated}, {"vertices", result.mesh.vertices.size()},
                    {"facets", result.mesh.faces.size()}}},
                  {"stages", stages_json(stages)},
                  {"seconds", seconds_since(start)}});
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
