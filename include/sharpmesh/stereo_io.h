// Readers and writers of calibrated cameras and tracks, in the conventions of
// the tools that produce them. Every reader converts to sharpmesh's camera
// (world-to-camera R, t; COLMAP pixel convention, see stereo.h), validates the
// result and throws InvalidInput naming the file and the problem.
#pragma once

#include <string>
#include <vector>

#include "sharpmesh/stereo.h"

namespace sharpmesh {

/// COLMAP sparse model folder (cameras, images, points3D), binary `.bin`
/// files when present, else `.txt`. Quaternions are scalar first and
/// world-to-camera. SIMPLE_PINHOLE and PINHOLE are read as they are; radial
/// and OpenCV models only when their distortion parameters are all zero;
/// fisheye models are refused ("undistort with colmap image_undistorter").
/// Cameras follow the images' file order; track pixels are the POINTS2D entries.
StereoModel read_colmap_model(const std::string& folder);

/// Writes cameras.txt/images.txt/points3D.txt (or .bin) into `folder`, which
/// must exist: one PINHOLE camera per image, ids from 1 in model order.
/// Tracks without pixels are given the projections of their positions.
void write_colmap_model(const std::string& folder, const StereoModel& model, bool binary = false);

/// COLMAP's dense fusion output: `fused.ply` (positions, normals, colours)
/// and `fused.ply.vis` next to it. The view indices in `.vis` are positions
/// in the image file order of the sparse model the fusion ran on, which is
/// the order of `cameras`. Normals, when present, go to `normals`.
StereoModel read_colmap_fused(const std::string& ply_path, const std::vector<Camera>& cameras,
                              std::vector<Vec3>* normals = nullptr);
/// Writes `fused.ply` (binary, with normals when given) and `fused.ply.vis`.
void write_colmap_fused(const std::string& ply_path, const StereoModel& model, const std::vector<Vec3>& normals = {});

/// Strecha et al. 2008 camera files (`<image>.camera`: K, a `0 0 0` line,
/// R camera-to-world, centre C, width and height), one per image, in file
/// name order, with the tracks in a PLY of ours (see read_tracks_ply). Pixel
/// coordinates in K follow the top-left pixel centre at (0, 0).
StereoModel read_strecha(const std::string& camera_folder, const std::string& tracks_ply);

/// Bundler v0.3 `bundle.out` with its list file (one image path per line,
/// relative to the list file's folder). Bundler cameras look down -Z with y
/// up and measurements are relative to the image centre; image sizes are read
/// from the images. Non-zero radial distortion (k1, k2) is refused.
StereoModel read_bundler(const std::string& out_path, const std::string& list_path);

/// VisualSFM NVM v3 (first model): focal, quaternion (world-to-camera), camera
/// centre (not t), radial distortion (non-zero is refused). Image paths are
/// relative to the NVM file's folder and image sizes are read from the images.
/// Whether measurements are relative to the image centre (VisualSFM) or absolute
/// pixels (some exporters) is decided from the reprojection of the points.
StereoModel read_nvm(const std::string& nvm_path);

/// Tracks as a PLY of vertices: x y z (double), red green blue, and a list
/// property `views` of uint32 view indices; `outlier` (uchar) when `outliers`
/// is not empty. Pixels are not stored.
void write_tracks_ply(const std::string& path, const std::vector<Track>& tracks, const std::vector<bool>& outliers = {});
/// Reads such a file; `outliers` receives the labels when present.
std::vector<Track> read_tracks_ply(const std::string& path, std::vector<bool>* outliers = nullptr);

/// Reads whatever `path` names: a COLMAP model folder (or a folder holding
/// `sparse/`), a `.out` (with `list.txt` next to it), or an `.nvm` file.
StereoModel read_stereo_model(const std::string& path);

/// What `sharpmesh stereo MODEL [--tracks FILE]` reads: cameras from MODEL
/// (as read_stereo_model, or a folder of Strecha .camera files, which needs
/// `tracks_path`); tracks from MODEL, or from `tracks_path` (a tracks PLY, or
/// COLMAP's fused.ply when fused.ply.vis is next to it). Validated, then put
/// in canonical order (canonical_order), so the mesh made from it does not
/// depend on how the files happened to list cameras and tracks.
StereoModel load_stereo_model(const std::string& model_path, const std::string& tracks_path = "");

/// Sorts the cameras by image name and the tracks by position (then by their
/// views, pixels and colour), each track's views ascending with their pixels, and
/// renumbers the views: the same scene gives the same model whatever order
/// its files listed it in (text or binary COLMAP models, other exporters).
void canonical_order(StereoModel& model);

/// The images of a model: MODEL/images, MODEL/../images, MODEL/../../images,
/// else the model's own folder.
std::string default_image_folder(const std::string& model_path);

}  // namespace sharpmesh
