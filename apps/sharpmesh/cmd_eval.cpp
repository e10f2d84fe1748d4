// sharpmesh eval MESH --reference REF: distances (fractions of the reference's
// diagonal and the thesis's U = diagonal/200, Fig. 7.13), sizes, topology,
// sharp-edge fidelity.
#include <cstdio>

#include "cli.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"

namespace sharpmesh::cli {

nlohmann::json evaluation_json(const SurfaceMesh& mesh, const DistanceReport& d, const TopologyReport& t) {
  const double u = d.diagonal / 200.0;
  auto distance = [&](double value) {
    return nlohmann::json{{"value", value}, {"fraction_of_diagonal", value / d.diagonal}, {"U", value / u}};
  };
  return {{"vertices", mesh.vertices.size()},
          {"facets", mesh.faces.size()},
          {"reference_diagonal", d.diagonal},
          {"hausdorff", distance(d.hausdorff)},
          {"mesh_to_reference_max", distance(d.mesh_to_reference_max)},
          {"reference_to_mesh_max", distance(d.reference_to_mesh_max)},
          {"mesh_to_reference_mean", distance(d.mesh_to_reference_mean)},
          {"reference_to_mesh_mean", distance(d.reference_to_mesh_mean)},
          {"mean", distance(d.mean)},
          {"rms", distance(d.rms)},
          {"sharp_edges",
           {{"polylines", d.sharp_edge_count}, {"length", d.sharp_edge_length}, {"mean", distance(d.sharp_mean)}, {"max", distance(d.sharp_max)}}},
          {"topology",
           {{"closed", t.closed()}, {"manifold", t.manifold()}, {"self_intersecting", t.self_intersecting},
            {"boundary_edges", t.boundary_edges}, {"non_manifold_edges", t.non_manifold_edges},
            {"non_manifold_vertices", t.non_manifold_vertices}, {"consistently_oriented", t.orientable},
            {"degenerate_faces", t.degenerate_faces}, {"components", t.components}}}};
}

void print_evaluation(const nlohmann::json& e) {
  auto line = [&](const char* label, const nlohmann::json& d) {
    std::printf("%-26s %.6g  (%.4f%% of diagonal, %.3f U)\n", label, d["value"].get<double>(),
                100 * d["fraction_of_diagonal"].get<double>(), d["U"].get<double>());
  };
  std::printf("%-26s %zu vertices, %zu facets\n", "size", e["vertices"].get<std::size_t>(), e["facets"].get<std::size_t>());
  line("hausdorff", e["hausdorff"]);
  line("mean distance", e["mean"]);
  line("rms distance", e["rms"]);
  line("sharp-edge mean distance", e["sharp_edges"]["mean"]);
  line("sharp-edge max distance", e["sharp_edges"]["max"]);
  const auto& t = e["topology"];
  std::printf("%-26s closed=%s manifold=%s self-intersecting=%s components=%zu\n", "topology", t["closed"].get<bool>() ? "yes" : "no",
              t["manifold"].get<bool>() ? "yes" : "no", t["self_intersecting"].get<bool>() ? "yes" : "no",
              t["components"].get<std::size_t>());
  std::printf("%-26s U = 1/200 of the reference's bounding-box diagonal (thesis Fig. 7.13)\n", "units");
}

Command add_eval(CLI::App& app) {
  struct Options {
    std::string input, reference;
    DistanceOptions distance;
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("eval", "Compare a mesh with a reference: Hausdorff, mean and RMS distance, sharp-edge fidelity, topology");
  sub->add_option("MESH", o->input, "Mesh to evaluate (.off, .ply, .obj, .stl)")->required();
  sub->add_option("-r,--reference", o->reference, "Reference mesh (ground truth)")->required();
  sub->add_option("--samples", o->distance.samples, "Samples per surface for the distances")->check(CLI::PositiveNumber)->capture_default_str();
  sub->add_option("--seed", o->distance.seed, "Sampling seed")->capture_default_str();
  sub->add_option("--sharp-angle", o->distance.sharp_angle, "Sharp-edge threshold of the reference, degrees from flat")
      ->check(CLI::Range(0.0, 180.0))->capture_default_str();
  common->add_to(*sub, false);
  sub->add_option("--json,--report", common->report, "Write the evaluation as JSON");
  auto run = [o, common] {
    check_output(common->report, "report");
    const auto start = std::chrono::steady_clock::now();
    const SurfaceMesh mesh = read_mesh(o->input);
    const SurfaceMesh reference = read_mesh(o->reference);
    ProgressPrinter printer(common->quiet);
    const DistanceReport distances = compare_meshes(mesh, reference, o->distance, printer.callback());
    const TopologyReport topology = check_topology(mesh);
    nlohmann::json e = evaluation_json(mesh, distances, topology);
    if (!common->quiet) print_evaluation(e);
    write_report(common->report, {{"command", "eval"},
                                  {"input", o->input},
                                  {"reference", o->reference},
                                  {"parameters", {{"samples", o->distance.samples}, {"seed", o->distance.seed}, {"sharp_angle", o->distance.sharp_angle}}},
                                  {"evaluation", e},
                                  {"seconds", seconds_since(start)}});
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
