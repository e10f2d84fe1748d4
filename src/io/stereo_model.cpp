// The stereo model of `sharpmesh stereo MODEL [--tracks FILE]` (stereo_io.h):
// cameras from any supported model, tracks from it or from a separate file.
#include <filesystem>

#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_io.h"

namespace sharpmesh {

namespace fs = std::filesystem;

namespace {

bool has_strecha_cameras(const std::string& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return false;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    if (entry.path().extension() == ".camera") return true;
  return false;
}

}  // namespace

StereoModel load_stereo_model(const std::string& model_path, const std::string& tracks_path) {
  if (has_strecha_cameras(model_path)) {
    if (tracks_path.empty()) throw InvalidArgument("Strecha cameras (" + model_path + ") need a tracks file (--tracks TRACKS.ply)");
    return read_strecha(model_path, tracks_path);
  }
  StereoModel model = read_stereo_model(model_path);
  if (!tracks_path.empty()) {
    std::error_code ec;
    if (fs::exists(tracks_path + ".vis", ec)) {
      StereoModel fused = read_colmap_fused(tracks_path, model.cameras);
      model.tracks = std::move(fused.tracks);
      model.dense_points = true;
    } else {
      model.tracks = read_tracks_ply(tracks_path);
    }
  }
  model.validate(tracks_path.empty() ? model_path : tracks_path);
  return model;
}

std::string default_image_folder(const std::string& model_path) {
  std::error_code ec;
  const fs::path p(model_path);
  for (const fs::path& candidate : {p / "images", p.parent_path() / "images", p.parent_path().parent_path() / "images"})
    if (!candidate.empty() && fs::is_directory(candidate, ec)) return candidate.string();
  return fs::is_directory(p, ec) ? p.string() : p.parent_path().string();
}

}  // namespace sharpmesh
