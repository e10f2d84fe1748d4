// sharpmesh stereo MODEL -o MESH: the Chapter 6 pipeline, calibrated images
// and tracks -> filtered triangle soup -> Delaunay refinement mesh.
#include <cstdio>
#include <filesystem>

#include "cli.h"
#include "option_flags.h"
#include "sharpmesh/io.h"
#include "sharpmesh/report.h"
#include "sharpmesh/stereo_io.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh::cli {
namespace {

/// The soup with only the vertices its triangles use.
SurfaceMesh compact(const TriangleSoup& soup) {
  SurfaceMesh out;
  std::vector<std::uint32_t> index(soup.vertices.size(), UINT32_MAX);
  for (const Triangle& f : soup.faces) {
    Triangle g;
    for (int k = 0; k < 3; ++k) {
      if (index[f[k]] == UINT32_MAX) {
        index[f[k]] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(soup.vertices[f[k]]);
      }
      g[k] = index[f[k]];
    }
    out.faces.push_back(g);
  }
  return out;
}

}  // namespace

Command add_stereo(CLI::App& app) {
  struct Options {
    std::string model, images, tracks, output, soup_out, tracks_out;
    bool ascii = false;
    StereoReconstructionOptions stereo;
  };
  auto o = std::make_shared<Options>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand(
      "stereo", "Calibrated images + tracks -> mesh: filtered tracks, contour-respecting depth maps, filtered triangle soup, "
                "Delaunay refinement (thesis Ch. 6)");
  sub->add_option("MODEL", o->model,
                  "Cameras and tracks: a COLMAP model folder (or a folder with sparse/, e.g. from make-scene), a Bundler .out, "
                  "an NVM file, or a folder of Strecha .camera files (with --tracks)")
      ->required();
  sub->add_option("-o,--output", o->output, "Output mesh (.ply, .off, .obj)")->required();
  sub->add_option("--images", o->images, "Image folder (default: MODEL/images, MODEL/../images, or the model's folder)");
  sub->add_option("--tracks", o->tracks, "Tracks instead of the model's: a tracks PLY (x y z, views) or COLMAP's fused.ply (+ .vis)");
  sub->add_option("--soup", o->soup_out, "Write the filtered triangle soup (PLY/OFF/OBJ)");
  sub->add_option("--tracks-out", o->tracks_out, "Write the pre-processed tracks (PLY with their views)");
  add_option_fields(*sub, o->stereo, stereo_option_fields(), {"threads"});
  sub->add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
  common->add_to(*sub);
  auto run = [o, common] {
    check_output(o->output, "mesh");
    check_output(o->soup_out, "soup");
    check_output(o->tracks_out, "tracks");
    check_output(common->report, "report");
    o->stereo.threads = common->threads;
    o->stereo.check();
    const auto start = std::chrono::steady_clock::now();
    std::vector<StageTiming> io_stages;
    ProgressPrinter printer(common->quiet);
    StereoModel model;
    std::vector<GreyImage> images;
    const std::string image_folder = o->images.empty() ? default_image_folder(o->model) : o->images;
    {
      StageTimer timer(io_stages, "read");
      model = load_stereo_model(o->model, o->tracks);
      images = read_grey_images(model, image_folder, printer.callback());
    }
    StereoReconstruction result = reconstruct_stereo(model, images, o->stereo, printer.callback());
    {
      StageTimer timer(io_stages, "write");
      write_mesh(o->output, result.meshing.mesh, o->ascii ? PlyFormat::Ascii : PlyFormat::Binary);
      if (!o->soup_out.empty()) write_mesh(o->soup_out, compact(result.soup), o->ascii ? PlyFormat::Ascii : PlyFormat::Binary);
      if (!o->tracks_out.empty()) write_tracks_ply(o->tracks_out, model.tracks);
    }
    std::vector<StageTiming> stages{io_stages[0]};
    stages.insert(stages.end(), result.stages.begin(), result.stages.end());
    stages.push_back(io_stages[1]);
    const TrackPreprocessStats& ts = result.tracks;
    const SoupFilterStats& fs = result.filters;
    if (!common->quiet) {
      char line[400];
      std::snprintf(line, sizeof line, "stereo: %zu views, %zu tracks -> %zu kept (%zu merged, %zu by distance, %zu by cone angle, %zu by photo-consistency)",
                    model.cameras.size(), ts.input, model.tracks.size(), ts.merged, ts.removed_distance, ts.removed_cone,
                    result.removed_track_photo);
      printer.message(line);
      std::snprintf(line, sizeof line, "  scale: half diagonal %s of the tracks' 1-99%% extent (%s with all of them; %zu tracks far outside it)",
                    format_number(ts.half_diagonal).c_str(), format_number(ts.raw_half_diagonal).c_str(), ts.far_tracks);
      printer.message(line);
      std::snprintf(line, sizeof line,
                    "  soup: %zu triangles (%zu unique), -%zu grazing, -%zu anamorphic, -%zu visibility, -%zu triangles of %zu occluded tracks, -%zu photo (%zu tested) -> %zu",
                    result.soup_triangles, result.soup_unique, fs.removed_grazing, fs.removed_anamorphic, fs.removed_visibility,
                    fs.removed_occluded, fs.occluded_tracks,
                    fs.removed_photo, fs.photo_tested, fs.output);
      printer.message(line);
      if (o->stereo.fill.enabled) {
        const SoupFillStats& fl = result.fill;
        if (fl.skipped.empty())
          std::snprintf(line, sizeof line, "  fill: tracks' surface of %zu facets from %zu tracks, -%zu near the soup, -%zu beyond the soup's tracks, -%zu visibility -> %zu added",
                        fl.surface_facets, fl.tracks, fl.removed_near_soup, fl.removed_far, fl.removed_visibility, fl.added);
        else
          std::snprintf(line, sizeof line, "  fill: none (%s)", fl.skipped.c_str());
        printer.message(line);
      }
      if (o->stereo.max_hole > 0) {
        std::snprintf(line, sizeof line, "  holes: %zu boundary cycles, %zu filled with %zu facets (%zu not faired, %zu failed)",
                      result.holes.holes, result.holes.filled, result.holes.added_facets, result.holes.unfaired, result.holes.failed);
        printer.message(line);
      }
      if (o->stereo.manifold) {
        std::snprintf(line, sizeof line, "  manifold: %zu edges had more than two facets; %zu vertices duplicated, %zu facets flipped",
                      result.manifold.non_manifold_edges, result.manifold.duplicated_vertices, result.manifold.flipped_facets);
        printer.message(line);
      }
      printer.message("  mesh: " + std::to_string(result.meshing.mesh.faces.size()) + " facets, " +
                      std::to_string(result.meshing.mesh.vertices.size()) + " vertices -> " + o->output);
      for (const StageTiming& s : stages) {
        std::snprintf(line, sizeof line, "  %-26s %8.2f s  %8.1f MiB peak", s.name.c_str(), s.seconds, s.peak_rss_bytes / 1048576.0);
        printer.message(line);
      }
    }
    nlohmann::json report = nlohmann::json::parse(stereo_report_json(result, o->stereo, model));
    report["command"] = "stereo";
    report["model"] = o->model;
    report["images"] = image_folder;
    report["tracks_input"] = o->tracks.empty() ? o->model : o->tracks;
    report["output"] = o->output;
    report["stages"] = stages_json(stages);
    report["seconds"] = seconds_since(start);
    write_report(common->report, report);
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
