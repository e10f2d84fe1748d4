// sharpmesh info CLOUD: count, bounding box, average spacing, attributes.
#include <cstdio>

#include "cli.h"
#include "sharpmesh/io.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh::cli {

Command add_info(CLI::App& app) {
  struct Options {
    std::string input;
    int k = 6;
  };
  auto options = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("info", "Point count, bounding box, average spacing and attributes of a point cloud");
  sub->add_option("CLOUD", options->input, "Point cloud (.ply, .xyz, .pwn, .off, .las)")->required();
  sub->add_option("-k,--k", options->k, "Neighbours for the average spacing (thesis 7.3.2: 6)")->check(CLI::PositiveNumber)->capture_default_str();
  common->add_to(*sub);
  auto run = [options, common] {
    check_output(common->report, "report");
    const auto start = std::chrono::steady_clock::now();
    const PointSet points = read_point_set(options->input);
    ProgressPrinter printer(common->quiet);
    check_point_set(points, 1, options->input.c_str());
    const BoundingBox box = bounding_box(points.points);
    double spacing = -1;
    if (points.size() > static_cast<std::size_t>(options->k)) spacing = average_spacing(points, options->k, printer.callback());
    if (!common->quiet) {
      std::printf("file:            %s\n", options->input.c_str());
      std::printf("points:          %zu\n", points.size());
      std::printf("normals:         %s\n", points.has_normals() ? "yes" : "no");
      std::printf("colours:         %s\n", points.has_colors() ? "yes" : "no");
      std::printf("bounding box:    [%g %g %g] - [%g %g %g]\n", box.min[0], box.min[1], box.min[2], box.max[0], box.max[1], box.max[2]);
      std::printf("diagonal:        %g\n", box.diagonal());
      if (spacing >= 0)
        std::printf("average spacing: %g (k = %d; %.3g of the diagonal)\n", spacing, options->k, spacing / box.diagonal());
      else
        std::printf("average spacing: n/a (fewer than k + 1 = %d points)\n", options->k + 1);
    }
    nlohmann::json report = {{"command", "info"},
                             {"input", options->input},
                             {"parameters", {{"k", options->k}}},
                             {"counts", {{"points", points.size()}}},
                             {"normals", points.has_normals()},
                             {"colors", points.has_colors()},
                             {"bounding_box", {{"min", box.min}, {"max", box.max}, {"diagonal", box.diagonal()}}},
                             {"seconds", seconds_since(start)}};
    if (spacing >= 0) report["average_spacing"] = length_json(spacing, box.diagonal());
    write_report(common->report, report);
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
