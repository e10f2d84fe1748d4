// sharpmesh stereo MODEL -o MESH: the Chapter 6 pipeline, calibrated images
// and tracks -> filtered triangle soup -> Delaunay refinement mesh.
#include <cstdio>
#include <filesystem>

#include "cli.h"
#include "sharpmesh/io.h"
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
    bool ascii = false, no_photo = false, keep_occluded = false, no_track_photo = false;
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
  auto& t = o->stereo.tracks;
  sub->add_option("--merge-distance", t.merge_distance, "t1: merge tracks closer than this, fraction of the half diagonal (6.3.1)")->capture_default_str();
  sub->add_option("--outlier-k", t.outlier_k, "k of the distance-to-neighbours 3-sigma filter (6.3.1)")->capture_default_str();
  sub->add_flag("!--outlier-global", t.outlier_relative,
               "Compare each track's d_k with the whole cloud's (the thesis); default: with its k neighbours' (median), so "
               "regions that are only sparser, e.g. far from the cameras, are kept");
  sub->add_option("--min-cone-angle", t.min_cone_angle, "t2: remove tracks whose cameras span a cone narrower than this, radians (6.3.1); 0: off, tracks seen in one image kept")->capture_default_str();
  sub->add_flag("--cone-angle-on-fused", t.cone_angle_on_dense_points,
                "Apply t2 to fused depth-map points too (COLMAP fused.ply + .vis); default: they skip it, their views are the depth "
                "maps that agree on a point, not the views that triangulated it");
  sub->add_option("--smooth-k", t.smooth_k, "k of the Gaussian jet smoothing, 0: off (6.3.1)")->capture_default_str();
  sub->add_option("--track-ncc", o->stereo.track_photo.min_ncc,
                  "Beyond the thesis: remove tracks whose 7x7 windows in their views agree less (mean pairwise NCC) or have no texture")
      ->capture_default_str();
  sub->add_flag("--no-track-photo", o->no_track_photo, "Keep every track whatever its image windows look like (the thesis)");
  auto& d = o->stereo.depth_maps;
  sub->add_option("--canny-sigma", d.canny_sigma, "Gaussian blur before Canny, pixels (6.3.2)")->capture_default_str();
  sub->add_option("--canny-low", d.canny_low, "Canny hysteresis low threshold (gradient magnitude, 8-bit scale; scaled by the image contrast unless --canny-fixed)")->capture_default_str();
  sub->add_option("--canny-high", d.canny_high, "Canny hysteresis high threshold")->capture_default_str();
  sub->add_flag("!--canny-fixed", d.canny_adaptive,
                "Use the Canny thresholds as given, not scaled by each image's contrast (the thesis; default: scaled by the "
                "99th-percentile gradient magnitude over 100)");
  sub->add_option("--contour-distance", d.contour_distance, "A track is a ctrack when it projects this close to a contour, pixels")->capture_default_str();
  sub->add_option("--gap-open", d.gap_open, "o: gap opening penalty of the contour-edge score (6.3.2)")->capture_default_str();
  sub->add_option("--gap-extend", d.gap_extend, "e: gap extension penalty (6.3.2)")->capture_default_str();
  auto& f = o->stereo.filters;
  sub->add_option("--max-crossings", f.max_crossings, "t3: remove soup triangles crossed by more lines of sight (6.3.2)")->capture_default_str();
  sub->add_option("--sight-margin", f.sight_margin, "Lines of sight stop this far before their track, average track spacings")->capture_default_str();
  sub->add_option("--grazing-angle", f.grazing_angle, "Lines of sight farther than this from a triangle's normal are grazing, degrees (6.3.2)")->capture_default_str();
  sub->add_option("--big-radius", f.big_radius, "Triangles with a larger circumradius are big, average track spacings")->capture_default_str();
  sub->add_option("--max-radius-edge", f.max_radius_edge, "Big triangles with a larger radius-edge ratio are removed")->capture_default_str();
  sub->add_option("--ncc", f.ncc_threshold, "Big regular triangles with a lower mean NCC are removed (6.3.2)")->capture_default_str();
  sub->add_flag("--no-photo", o->no_photo, "Skip the photo-consistency filter");
  sub->add_flag("--keep-occluded-tracks", o->keep_occluded,
                "Keep the triangles of tracks hidden behind the soup from most of their views (the thesis does)");
  auto& fill = o->stereo.fill;
  sub->add_flag("!--no-fill", fill.enabled,
                "Mesh the filtered soup alone (the thesis); default: where the soup is empty, fill it with the tracks' Poisson surface (beyond the thesis, 6.6)");
  sub->add_option("--fill-gap", fill.gap, "Fill only farther than this from every soup triangle, size bounds l")->capture_default_str();
  sub->add_option("--fill-support", fill.support, "Fill only this close to a track of the filtered soup, average track spacings")->capture_default_str();
  sub->add_option("--fill-bridge", fill.bridge,
                  "Farther, fill where the soup's tracks within this many local track spacings surround the facet (gaps among sparse tracks); 0: off")
      ->capture_default_str();
  sub->add_option("--fill-resolution", fill.resolution, "Protecting-ball spacing d' of the tracks' surface, size bounds l")->capture_default_str();
  sub->add_option("--fill-crossings", fill.max_crossings, "Remove fill facets crossed by more lines of sight")->capture_default_str();
  auto& m = o->stereo.meshing;
  sub->add_option("--angle", m.angle, "alpha: minimum facet angle, degrees (6.2.1)")->capture_default_str();
  sub->add_option("--size", m.size, "l: maximum surface Delaunay ball radius, fraction of the soup's half diagonal (6.5)")->capture_default_str();
  sub->add_option("--distance", m.distance, "d: maximum facet-to-surface distance, fraction of the soup's half diagonal (6.5)")->capture_default_str();
  sub->add_option("--max-vertices", m.max_vertices, "Stop with an error past this many mesh vertices")->capture_default_str();
  sub->add_option("--seed", m.seed, "Seed of the refinement's initial points")->capture_default_str();
  sub->add_option("--seed-cell", m.seed_cell, "Also one initial point per occupied cell of a grid of this step, size bounds l")->capture_default_str();
  sub->add_option("--initial-points", m.initial_points, "Initial points of the refinement (centroids of random soup triangles)")->capture_default_str();
  sub->add_option("--max-hole", o->stereo.max_hole,
                  "Fill the mesh's holes whose boundary is shorter than this, fraction of the soup's half diagonal; 0: off (beyond the thesis, its remedy of 6.6)")
      ->capture_default_str();
  sub->add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
  common->add_to(*sub);
  auto run = [o, common] {
    check_output(o->output, "mesh");
    check_output(o->soup_out, "soup");
    check_output(o->tracks_out, "tracks");
    check_output(common->report, "report");
    o->stereo.filters.photo_consistency = !o->no_photo;
    o->stereo.track_photo.enabled = !o->no_track_photo;
    o->stereo.filters.remove_occluded_tracks = !o->keep_occluded;
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
    const double half_diagonal = result.tracks.half_diagonal;
    const TrackPreprocessStats& ts = result.tracks;
    const SoupFilterStats& fs = result.filters;
    if (!common->quiet) {
      char line[400];
      std::snprintf(line, sizeof line, "stereo: %zu views, %zu tracks -> %zu kept (%zu merged, %zu by distance, %zu by cone angle, %zu by photo-consistency)",
                    model.cameras.size(), ts.input, model.tracks.size(), ts.merged, ts.removed_distance, ts.removed_cone,
                    result.removed_track_photo);
      printer.message(line);
      std::snprintf(line, sizeof line,
                    "  soup: %zu triangles (%zu unique), -%zu grazing, -%zu anamorphic, -%zu visibility, -%zu of %zu occluded tracks, -%zu photo (%zu tested) -> %zu",
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
      printer.message("  mesh: " + std::to_string(result.meshing.mesh.faces.size()) + " facets, " +
                      std::to_string(result.meshing.mesh.vertices.size()) + " vertices -> " + o->output);
      for (const StageTiming& s : stages) {
        std::snprintf(line, sizeof line, "  %-26s %8.2f s  %8.1f MiB peak", s.name.c_str(), s.seconds, s.peak_rss_bytes / 1048576.0);
        printer.message(line);
      }
    }
    const auto& so = o->stereo;
    nlohmann::json report = {
        {"command", "stereo"},
        {"model", o->model},
        {"images", image_folder},
        {"tracks_input", o->tracks.empty() ? o->model : o->tracks},
        {"output", o->output},
        {"units", "lengths in data units; merge distance as a fraction of the input tracks' half diagonal, size, distance and max_hole of "
                  "the filtered soup's (derived.soup_half_diagonal)"},
        {"parameters",
         {{"merge_distance", so.tracks.merge_distance}, {"outlier_k", so.tracks.outlier_k},
          {"outlier_sigmas", so.tracks.outlier_sigmas}, {"outlier_relative", so.tracks.outlier_relative}, {"min_cone_angle_rad", so.tracks.min_cone_angle},
          {"cone_angle_on_fused", so.tracks.cone_angle_on_dense_points},
          {"smooth_k", so.tracks.smooth_k}, {"track_photo", so.track_photo.enabled},
          {"track_ncc", so.track_photo.min_ncc}, {"track_window", 2 * so.track_photo.half_window + 1}, {"canny_sigma", so.depth_maps.canny_sigma},
          {"canny_low", so.depth_maps.canny_low}, {"canny_high", so.depth_maps.canny_high},
          {"canny_adaptive", so.depth_maps.canny_adaptive},
          {"contour_distance_px", so.depth_maps.contour_distance}, {"gap_open", so.depth_maps.gap_open},
          {"gap_extend", so.depth_maps.gap_extend}, {"overlap_angle_deg", so.depth_maps.overlap_angle},
          {"max_crossings", so.filters.max_crossings}, {"sight_margin_spacings", so.filters.sight_margin},
          {"grazing_angle_deg", so.filters.grazing_angle}, {"big_radius_spacings", so.filters.big_radius},
          {"max_radius_edge", so.filters.max_radius_edge}, {"ncc_threshold", so.filters.ncc_threshold},
          {"photo_consistency", so.filters.photo_consistency},
          {"remove_occluded_tracks", so.filters.remove_occluded_tracks}, {"angle_deg", so.meshing.angle},
          {"size", so.meshing.size}, {"distance", so.meshing.distance}, {"seed", so.meshing.seed},
          {"fill", so.fill.enabled}, {"fill_gap_l", so.fill.gap}, {"fill_support_spacings", so.fill.support}, {"fill_bridge_local_spacings", so.fill.bridge},
          {"fill_max_crossings", so.fill.max_crossings}, {"max_hole", so.max_hole}}},
        {"derived", {{"half_diagonal", half_diagonal}, {"soup_half_diagonal", result.meshing.half_diagonal}}},
        {"counts",
         {{"views", model.cameras.size()},
          {"tracks", {{"input", ts.input}, {"merged", ts.merged}, {"removed_distance", ts.removed_distance},
                      {"removed_cone_angle", ts.removed_cone}, {"cone_filter_skipped_fused", ts.cone_filter_skipped},
                      {"removed_photo", result.removed_track_photo}, {"kept", model.tracks.size()}}},
          {"depth_maps", {{"contour_tracks", result.contour_tracks}, {"contour_edges", result.contour_edges}}},
          {"soup", {{"lifted", result.soup_triangles}, {"unique", result.soup_unique},
                    {"removed_visibility", fs.removed_visibility}, {"removed_grazing", fs.removed_grazing},
                    {"occluded_tracks", fs.occluded_tracks}, {"removed_occluded", fs.removed_occluded},
                    {"removed_anamorphic", fs.removed_anamorphic}, {"photo_tested", fs.photo_tested},
                    {"removed_photo", fs.removed_photo}, {"kept", fs.output}}},
          {"fill", {{"tracks", result.fill.tracks}, {"surface_facets", result.fill.surface_facets},
                    {"removed_near_soup", result.fill.removed_near_soup}, {"removed_far", result.fill.removed_far},
                    {"removed_visibility", result.fill.removed_visibility}, {"added", result.fill.added},
                    {"skipped", result.fill.skipped}}},
          {"mesh", {{"vertices", result.meshing.mesh.vertices.size()}, {"facets", result.meshing.mesh.faces.size()},
                    {"refinement_steps", result.meshing.steps}}},
          {"holes", {{"boundary_cycles", result.holes.holes}, {"filled", result.holes.filled},
                     {"added_facets", result.holes.added_facets}, {"unfaired", result.holes.unfaired},
                     {"failed", result.holes.failed}}}}},
        {"stages", stages_json(stages)},
        {"seconds", seconds_since(start)}};
    write_report(common->report, report);
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
