// sharpmesh sample MESH -n N -o CLOUD: uniform samples of a reference mesh,
// with the thesis's uniform noise (7.5), and its sharp edges as polylines.
#include <cstdio>

#include "cli.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"

namespace sharpmesh::cli {

Command add_sample(CLI::App& app) {
  struct Options {
    std::string input, output, sharp_output;
    std::size_t count = 100000;
    double noise = 0, density_ratio = 1, missing_radius = 0.05;
    std::size_t missing_patches = 0;
    std::uint64_t seed = 0;
    double sharp_angle = 30;
    bool normals = false, ascii = false;
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("sample", "Sample points uniformly on a mesh (optionally noisy) and extract its sharp edges");
  sub->add_option("MESH", o->input, "Reference mesh (.off, .ply, .obj, .stl)")->required();
  sub->add_option("-n,--count", o->count, "Number of points")->check(CLI::PositiveNumber)->capture_default_str();
  sub->add_option("--noise", o->noise, "Uniform noise amplitude, as a fraction of the bounding-box diagonal (thesis 7.5: 0.01)")
      ->check(CLI::Range(0.0, 0.5))->capture_default_str();
  sub->add_option("--density-ratio", o->density_ratio,
                  "Non-uniform sampling: the density grows linearly across the part, along a direction drawn from the seed, up to this ratio")
      ->check(CLI::Range(1.0, 1000.0))->capture_default_str();
  sub->add_option("--missing-patches", o->missing_patches, "Balls on the surface left without samples (occlusions)")->capture_default_str();
  sub->add_option("--missing-radius", o->missing_radius, "Radius of each missing patch, fraction of the bounding-box diagonal")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  sub->add_option("--seed", o->seed, "Random seed")->capture_default_str();
  sub->add_option("-o,--output", o->output, "Output point cloud (.ply or .xyz)")->required();
  sub->add_flag("--normals", o->normals, "Store the exact facet normal of each sample");
  sub->add_option("--sharp-edges", o->sharp_output, "Write the mesh's sharp edges as polylines (CGAL text format)");
  sub->add_option("--sharp-angle", o->sharp_angle, "Angle between facet normals above which an edge is sharp, degrees (0 = flat)")
      ->check(CLI::Range(0.0, 180.0))->capture_default_str();
  sub->add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
  common->add_to(*sub);
  auto run = [o, common] {
    check_output(o->output, "points");
    check_output(o->sharp_output, "polylines");
    check_output(common->report, "report");
    const auto start = std::chrono::steady_clock::now();
    const SurfaceMesh mesh = read_mesh(o->input);
    SampleOptions options;
    options.count = o->count;
    options.noise = o->noise;
    options.seed = o->seed;
    options.density_ratio = o->density_ratio;
    options.missing_patches = o->missing_patches;
    options.missing_radius = o->missing_radius;
    options.with_normals = o->normals;
    const PointSet points = sample_mesh(mesh, options);
    std::vector<Polyline> edges;
    if (!o->sharp_output.empty()) edges = sharp_edges(mesh, o->sharp_angle);
    write_point_set(o->output, points, o->ascii ? PlyFormat::Ascii : PlyFormat::Binary);
    if (!o->sharp_output.empty()) write_polylines(o->sharp_output, edges);
    if (!common->quiet) {
      std::fprintf(stderr, "sample: %zu points on %s (noise %g of the diagonal) -> %s\n", points.size(), o->input.c_str(), o->noise,
                   o->output.c_str());
      if (!o->sharp_output.empty()) std::fprintf(stderr, "sample: %zu sharp-edge polylines -> %s\n", edges.size(), o->sharp_output.c_str());
    }
    write_report(common->report, {{"command", "sample"},
                                  {"input", o->input},
                                  {"output", o->output},
                                  {"parameters", {{"count", o->count}, {"noise", o->noise}, {"seed", o->seed}, {"sharp_angle", o->sharp_angle},
                                                  {"density_ratio", o->density_ratio}, {"missing_patches", o->missing_patches},
                                                  {"missing_radius", o->missing_radius}}},
                                  {"counts", {{"points", points.size()}, {"sharp_polylines", edges.size()}, {"mesh_faces", mesh.faces.size()}}},
                                  {"seconds", seconds_since(start)}});
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
