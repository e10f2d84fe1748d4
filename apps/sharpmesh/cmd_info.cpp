// sharpmesh info CLOUD: count, bounding box, average spacing, attributes.
#include <cstdio>

#include "cli.h"
#include "sharpmesh/cloud_scan.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/io.h"
#include "sharpmesh/las.h"

namespace sharpmesh::cli {

Command add_info(CLI::App& app) {
  struct Options {
    std::string input;
    int k = 6;
    bool no_spacing = false;
  };
  auto options = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("info", "Point count, bounding box, average spacing and attributes of a point cloud");
  sub->add_option("CLOUD", options->input, "Point cloud (.ply, .xyz, .pwn, .off, .las, .laz)")->required();
  sub->add_flag("--no-spacing", options->no_spacing, "Skip the average spacing (a k-nearest-neighbour pass over all points)");
  sub->add_option("-k,--k", options->k, "Neighbours for the average spacing (thesis 7.3.2: 6)")->check(CLI::PositiveNumber)->capture_default_str();
  common->add_to(*sub);
  auto run = [options, common] {
    check_output(common->report, "report");
    const auto start = std::chrono::steady_clock::now();
    const bool lidar = is_las_path(options->input);
    LasInfo las;
    if (lidar) las = LasReader(options->input).info();
    ProgressPrinter printer(common->quiet);
    // Streamed: memory holds a block of points, the whole cloud only up to
    // CloudScanOptions::exact_spacing_limit points (for the exact spacing).
    CloudScanOptions scan_options;
    scan_options.k = options->k;
    scan_options.spacing = !options->no_spacing;
    const CloudScan scan = scan_point_cloud(options->input, scan_options, printer.callback());
    if (scan.points == 0) throw InvalidInput(options->input + ": the file holds no points");
    const BoundingBox& box = scan.box;
    if (!(box.diagonal() > 0) || !std::isfinite(box.diagonal()))
      throw InvalidInput(options->input + ": all points are at the same location (or the extent overflows)");
    const double spacing = scan.average_spacing;
    if (!common->quiet) {
      std::printf("file:            %s\n", options->input.c_str());
      std::printf("points:          %llu\n", static_cast<unsigned long long>(scan.points));
      std::printf("normals:         %s\n", scan.normals ? "yes" : "no");
      std::printf("colours:         %s\n", scan.colors ? "yes" : "no");
      std::printf("bounding box:    [%g %g %g] - [%g %g %g]\n", box.min[0], box.min[1], box.min[2], box.max[0], box.max[1], box.max[2]);
      std::printf("diagonal:        %g\n", box.diagonal());
      if (spacing >= 0) {
        std::printf("average spacing: %g (k = %d; %.3g of the diagonal", spacing, options->k, spacing / box.diagonal());
        if (!scan.spacing_exact)
          std::printf("; the mean over %llu points of blocks of space drawn over the cloud", static_cast<unsigned long long>(scan.spacing_points));
        std::printf(")\n");
      } else if (!options->no_spacing) {
        std::printf("average spacing: n/a (fewer than k + 1 = %d points)\n", options->k + 1);
      }
      if (lidar) {
        std::printf("LAS:             version %d.%d, point format %d, %u-byte records\n", las.version_major, las.version_minor,
                    las.point_format, unsigned(las.record_length));
        if (las.compressed)
          std::printf("LAZ:             LASzip %s, %zu chunks of %u points\n", las.laszip_version.c_str(), las.chunks, las.chunk_size);
        std::printf("scale, offset:   [%g %g %g], [%g %g %g]\n", las.scale[0], las.scale[1], las.scale[2], las.offset[0], las.offset[1],
                    las.offset[2]);
        std::printf("header box:      [%g %g %g] - [%g %g %g]\n", las.bounds.min[0], las.bounds.min[1], las.bounds.min[2], las.bounds.max[0],
                    las.bounds.max[1], las.bounds.max[2]);
        std::printf("classes:        ");
        for (int c = 0; c < 256; ++c)
          if (scan.classes[c] > 0) std::printf(" %d: %llu", c, static_cast<unsigned long long>(scan.classes[c]));
        std::printf("\n");
      }
    }
    nlohmann::json report = {{"command", "info"},
                             {"input", options->input},
                             {"parameters", {{"k", options->k}}},
                             {"counts", {{"points", scan.points}}},
                             {"normals", scan.normals},
                             {"colors", scan.colors},
                             {"bounding_box", {{"min", box.min}, {"max", box.max}, {"diagonal", box.diagonal()}}},
                             {"passes", scan.passes},
                             {"read_seconds", scan.read_seconds},
                             {"seconds", seconds_since(start)}};
    if (lidar) {
      nlohmann::json histogram = nlohmann::json::object();
      for (int c = 0; c < 256; ++c)
        if (scan.classes[c] > 0) histogram[std::to_string(c)] = scan.classes[c];
      report["las"] = {{"version", std::to_string(las.version_major) + "." + std::to_string(las.version_minor)},
                       {"point_format", las.point_format}, {"record_length", las.record_length}, {"compressed", las.compressed},
                       {"laszip_version", las.laszip_version}, {"chunk_size", las.chunk_size}, {"chunks", las.chunks},
                       {"scale", las.scale}, {"offset", las.offset},
                       {"header_bounds", {{"min", las.bounds.min}, {"max", las.bounds.max}}}, {"classes", histogram}};
    }
    if (spacing >= 0) {
      report["average_spacing"] = length_json(spacing, box.diagonal());
      report["average_spacing"]["exact"] = scan.spacing_exact;
      report["average_spacing"]["measured_points"] = scan.spacing_points;
    }
    write_report(common->report, report);
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
