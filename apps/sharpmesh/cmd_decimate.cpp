// sharpmesh decimate MESH -o OUT --facets N: a mesh made lighter by edge
// collapse with its sharp edges kept (sharpmesh/compact.h), checked for
// crossing facets like reconstruct's output.
#include <cstdio>
#include <variant>

#include "cli.h"
#include "option_flags.h"
#include "sharpmesh/compact.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"
#include "sharpmesh/meshing.h"
#include "sharpmesh/report.h"

namespace sharpmesh::cli {

Command add_decimate(CLI::App& app) {
  struct Options {
    std::string input, output, curves_file;
    bool allow_invalid = false, ascii = false;
    DecimationOptions decimation;
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand(
      "decimate", "Mesh -> lighter mesh: edges collapsed by quadric error, sharp edges and corners kept (beyond the thesis)");
  sub->add_option("MESH", o->input, "Input mesh (.ply, .off, .obj, .stl): oriented, edge- and vertex-manifold")->required();
  sub->add_option("-o,--output", o->output, "Output mesh (.ply, .off, .obj)")->required();
  sub->add_option("--feature-curves", o->curves_file,
                  "Polylines through the mesh's vertices to keep as sharp edges (CGAL text format, as reconstruct --sharp-edges "
                  "writes them)");
  add_option_fields(*sub, o->decimation, decimation_option_fields());
  add_mesh_output_flags(*sub, o->allow_invalid, o->ascii);
  common->add_to(*sub);
  auto run = [o, common] {
    check_output(o->output, "mesh");
    check_output(common->report, "report");
    o->decimation.check();
    if (!o->decimation.active()) throw InvalidArgument("decimate needs --facets or --tolerance");
    const auto start = std::chrono::steady_clock::now();
    std::vector<StageTiming> stages;
    SurfaceMesh mesh;
    std::vector<Polyline> curves;
    {
      StageTimer timer(stages, "read");
      mesh = read_mesh(o->input);
      if (!o->curves_file.empty()) curves = read_polylines(o->curves_file);
    }
    if (mesh.faces.empty()) throw InvalidInput(o->input + ": the mesh has no facets");
    ProgressPrinter printer(common->quiet);
    DecimationResult result;
    {
      StageTimer timer(stages, "decimation");
      try {
        result = decimate(mesh, curves, o->decimation, printer.callback());
      } catch (const InvalidInput& e) {
        throw InvalidInput(o->input + ": " + e.what());
      }
    }
    IntersectionRepairStats repair;
    {
      StageTimer timer(stages, "self-intersection check");
      repair = repair_self_intersections(mesh, {}, printer.callback());
    }
    if (repair.remaining_pairs > 0 && !o->allow_invalid)
      throw Error(o->input + ": the decimated mesh has facets that cross others after " + std::to_string(repair.rounds) +
                  " repair rounds; nothing written (--allow-invalid writes it anyway)");
    {
      StageTimer timer(stages, "write");
      write_mesh(o->output, mesh, o->ascii ? PlyFormat::Ascii : PlyFormat::Binary);
    }
    if (!common->quiet) {
      printer.message("decimate: " + std::to_string(result.input_facets) + " -> " + std::to_string(mesh.faces.size()) + " facets, " +
                      std::to_string(result.feature_edges) + " sharp edges and " + std::to_string(result.corner_vertices) +
                      " corners kept -> " + o->output);
      if (result.budget_missed)
        std::fprintf(stderr, "decimate: warning: the budget was not reached: every further collapse would move a corner, leave a "
                             "sharp edge, fold a facet or break the tolerance\n");
    }
    nlohmann::json counts = nlohmann::json::parse(decimation_report_json(result));
    counts["output_facets"] = mesh.faces.size();  // after the self-intersection check's repair, if it ran
    counts["boundary_edges"] = count_boundary_edges(mesh);
    nlohmann::json parameters;
    for (const OptionField<DecimationOptions>& field : decimation_option_fields())
      std::visit([&](const auto& value) { parameters[field.name] = value; }, field.get(o->decimation));
    parameters["feature_curves"] = o->curves_file;
    write_report(common->report, {{"command", "decimate"},
                                  {"input", o->input},
                                  {"output", o->output},
                                  {"parameters", parameters},
                                  {"counts", counts},
                                  {"self_intersections",
                                   {{"found_pairs", repair.intersecting_pairs},
                                    {"remaining_pairs", repair.remaining_pairs},
                                    {"written_invalid", repair.remaining_pairs > 0}}},
                                  {"stages", stages_json(stages)},
                                  {"seconds", seconds_since(start)}});
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
