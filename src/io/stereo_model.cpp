// The stereo model of `sharpmesh stereo MODEL [--tracks FILE]` (stereo_io.h):
// cameras from any supported model, tracks from it or from a separate file.
#include <algorithm>
#include <filesystem>
#include <numeric>
#include <tuple>

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
  canonical_order(model);
  return model;
}

void canonical_order(StereoModel& model) {
  std::vector<std::uint32_t> order(model.cameras.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return model.cameras[a].image_name < model.cameras[b].image_name; });
  std::vector<std::uint32_t> new_index(order.size());
  std::vector<Camera> cameras;
  cameras.reserve(order.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) {
    new_index[order[i]] = i;
    cameras.push_back(std::move(model.cameras[order[i]]));
  }
  model.cameras = std::move(cameras);

  for (Track& t : model.tracks) {
    std::vector<std::size_t> by_view(t.views.size());
    std::iota(by_view.begin(), by_view.end(), std::size_t{0});
    for (std::uint32_t& v : t.views) v = new_index[v];
    std::sort(by_view.begin(), by_view.end(), [&](std::size_t a, std::size_t b) { return t.views[a] < t.views[b]; });
    std::vector<std::uint32_t> views;
    std::vector<Vec2> pixels;
    for (std::size_t k : by_view) {
      views.push_back(t.views[k]);
      if (!t.pixels.empty()) pixels.push_back(t.pixels[k]);
    }
    t.views = std::move(views);
    t.pixels = std::move(pixels);
  }
  std::sort(model.tracks.begin(), model.tracks.end(), [](const Track& a, const Track& b) {
    return std::tie(a.position, a.views, a.pixels, a.color) < std::tie(b.position, b.views, b.pixels, b.color);
  });
}

std::string default_image_folder(const std::string& model_path) {
  std::error_code ec;
  const fs::path p(model_path);
  for (const fs::path& candidate : {p / "images", p.parent_path() / "images", p.parent_path().parent_path() / "images"})
    if (!candidate.empty() && fs::is_directory(candidate, ec)) return candidate.string();
  return fs::is_directory(p, ec) ? p.string() : p.parent_path().string();
}

}  // namespace sharpmesh
