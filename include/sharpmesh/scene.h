// A deterministic calibrated scene with exact ground truth, for the stereo
// pipeline's tests and benchmarks (issue 5): a textured ground plane and a
// building with sharp details, rendered from cameras on an arc.
#pragma once

#include <cstdint>
#include <string>

#include "sharpmesh/progress.h"
#include "sharpmesh/stereo.h"

namespace sharpmesh {

struct SceneOptions {
  int views = 8;                  ///< cameras, evenly spread on the arc
  int width = 320, height = 240;  ///< image size in pixels
  double arc = 100;               ///< degrees of the arc of cameras around the front of the building
  double fov = 55;                ///< horizontal field of view, degrees
  std::uint64_t seed = 1;
  int supersample = 2;            ///< rays per pixel along each axis (anti-aliasing)
  double image_noise = 2.0;       ///< standard deviation of the image noise, grey levels
  // Tracks, level (a): surface samples seen by >= 2 views, triangulated from noisy pixels.
  std::size_t samples = 20000;    ///< surface samples before the visibility test
  double noise = 0.5;             ///< standard deviation of the pixel observations, pixels
  double outliers = 0.05;         ///< fraction of the tracks that are outliers (labelled)
  // Level (b), "fused": depth-map points as an MVS fusion would give them.
  int fused_step = 4;             ///< one point every `fused_step` pixels in each direction
  double fused_noise = 0.5;       ///< disparity noise, pixels (depth noise grows with depth^2)
  int fatten = 2;                 ///< foreground fattening at depth edges, pixels
  void check() const;
};

/// Counts and measures of a generated scene (also written to OUT/scene.json).
struct SceneSummary {
  std::size_t ground_truth_faces = 0;
  std::size_t tracks = 0, outlier_tracks = 0, fused_points = 0;
  ReprojectionStats reprojection;  ///< of the inlier tracks' recorded pixels
  double mean_track_error = 0;     ///< mean distance of inlier track positions to the surface
  double building_diagonal = 0;    ///< of the building's bounding box, metres
  double seconds = 0;
};

/// Writes the scene into `folder` (created; an existing scene folder is replaced):
///   images/view_NNN.png, sparse/{cameras,images,points3D}.txt (level a, COLMAP text),
///   tracks.ply (level a with `outlier` labels), dense/fused.ply + fused.ply.vis (level b),
///   ground_truth.ply, depth/view_NNN.png.depth.bin (true depth, COLMAP's array format:
///   "width&height&1&" then float32 rows; 0 where no surface), scene.json.
/// The folder appears only once complete.
SceneSummary make_scene(const std::string& folder, const SceneOptions& options, const Progress& progress = {});

}  // namespace sharpmesh
