// sharpmesh make-scene OUT: a calibrated synthetic scene with exact ground
// truth (images, COLMAP cameras and tracks, fused points, depth, mesh).
#include <cstdio>

#include "cli.h"
#include "sharpmesh/scene.h"

namespace sharpmesh::cli {

Command add_make_scene(CLI::App& app) {
  auto folder = std::make_shared<std::string>();
  auto o = std::make_shared<SceneOptions>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand(
      "make-scene", "Generate a calibrated multi-view scene with exact ground truth: a textured building rendered from cameras on an arc");
  sub->add_option("OUT", *folder, "Output folder (created; a previous scene there is replaced)")->required();
  sub->add_option("--views", o->views, "Number of cameras on the arc")->capture_default_str();
  sub->add_option("--width", o->width, "Image width, pixels")->capture_default_str();
  sub->add_option("--height", o->height, "Image height, pixels")->capture_default_str();
  sub->add_option("--arc", o->arc, "Angle covered by the cameras around the front of the building, degrees")->capture_default_str();
  sub->add_option("--fov", o->fov, "Horizontal field of view, degrees")->capture_default_str();
  sub->add_option("--seed", o->seed, "Random seed (texture, noise, samples)")->capture_default_str();
  sub->add_option("--supersample", o->supersample, "Rays per pixel along each axis (anti-aliasing)")->capture_default_str();
  sub->add_option("--image-noise", o->image_noise, "Image noise standard deviation, grey levels")->capture_default_str();
  sub->add_option("--samples", o->samples, "Surface samples tried for the tracks (kept when seen by >= 2 views)")->capture_default_str();
  sub->add_option("--noise", o->noise, "Standard deviation of the tracks' pixel observations, pixels")->capture_default_str();
  sub->add_option("--outliers", o->outliers, "Fraction of tracks that are outliers (labelled in tracks.ply)")->capture_default_str();
  sub->add_option("--fused-step", o->fused_step, "Fused level: one depth sample every N pixels")->capture_default_str();
  sub->add_option("--fused-noise", o->fused_noise, "Fused level: disparity noise, pixels (depth noise grows as depth^2)")->capture_default_str();
  sub->add_option("--fatten", o->fatten, "Fused level: foreground fattening at depth edges, pixels")->capture_default_str();
  common->add_to(*sub);
  auto run = [folder, o, common] {
    o->check();
    check_output(common->report, "report");
    ProgressPrinter printer(common->quiet);
    const SceneSummary s = make_scene(*folder, *o, printer.callback());
    if (!common->quiet)
      std::fprintf(stderr,
                   "make-scene: %d views %dx%d, %zu tracks (%zu outliers, reprojection rms %.2f px, mean error %.4f m), "
                   "%zu fused points -> %s (%.1f s)\n",
                   o->views, o->width, o->height, s.tracks, s.outlier_tracks, s.reprojection.rms, s.mean_track_error, s.fused_points,
                   folder->c_str(), s.seconds);
    write_report(common->report, {{"command", "make-scene"},
                                  {"output", *folder},
                                  {"counts", {{"tracks", s.tracks}, {"outlier_tracks", s.outlier_tracks}, {"fused_points", s.fused_points}}},
                                  {"reprojection_pixels", {{"mean", s.reprojection.mean}, {"rms", s.reprojection.rms}, {"max", s.reprojection.max}}},
                                  {"mean_track_error", s.mean_track_error},
                                  {"seconds", s.seconds}});
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
