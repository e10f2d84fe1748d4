// Strecha et al. 2008 (EPFL dense multi-view benchmark) camera files:
//   K (3 lines), a distortion line "0 0 0", R (3 lines, camera-to-world),
//   C (camera centre), "width height".
// Projection: m = K R^T (M - C). K's pixel origin is the centre of the
// top-left pixel, so 0.5 is added to the principal point.
#include <cmath>
#include <algorithm>
#include <filesystem>

#include "io/formats.h"
#include "io/token_stream.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_io.h"

namespace sharpmesh {
namespace {

Camera read_strecha_camera(const std::string& path, const std::string& image_name) {
  const std::string text = io::read_file(path);
  io::TokenStream in(text, path);
  double k[3][3], distortion[3], r[3][3], c[3], size[2];
  for (auto& row : k)
    for (double& v : row) v = in.number("K");
  for (double& v : distortion) v = in.number("the distortion line");
  for (auto& row : r)
    for (double& v : row) v = in.number("R");
  for (double& v : c) v = in.number("the camera centre");
  for (double& v : size) {
    v = in.number("width and height");
    if (!(v >= 1 && v <= (1 << 20)) || v != std::floor(v))
      throw InvalidInput(path + ": image size " + format_number(v) + " is not a pixel count in [1, 2^20]");
  }
  if (distortion[0] != 0 || distortion[1] != 0 || distortion[2] != 0)
    throw InvalidInput(path + ": non-zero distortion; undistort the images first");
  if (k[1][0] != 0 || k[2][0] != 0 || k[2][1] != 0 || k[2][2] != 1) throw InvalidInput(path + ": K is not upper triangular with K[2][2] = 1");
  if (std::abs(k[0][1]) > 1e-6 * std::abs(k[0][0])) throw InvalidInput(path + ": K has a skew term, which pinhole cameras here do not model");
  Camera cam;
  cam.image_name = image_name;
  cam.fx = k[0][0];
  cam.fy = k[1][1];
  cam.cx = k[0][2] + 0.5;
  cam.cy = k[1][2] + 0.5;
  cam.width = static_cast<int>(size[0]);
  cam.height = static_cast<int>(size[1]);
  Mat3 camera_to_world;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) camera_to_world[i][j] = r[i][j];
  cam.rotation = transpose(camera_to_world);
  cam.translation = -1.0 * (cam.rotation * Vec3{c[0], c[1], c[2]});
  cam.validate(path);
  return cam;
}

}  // namespace

StereoModel read_strecha(const std::string& camera_folder, const std::string& tracks_ply) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(camera_folder, ec)) throw InvalidInput("cannot open '" + camera_folder + "': not a folder");
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(camera_folder, ec))
    if (entry.path().extension() == ".camera") files.push_back(entry.path().filename().string());
  if (files.empty()) throw InvalidInput(camera_folder + ": no .camera files");
  std::sort(files.begin(), files.end());
  StereoModel model;
  for (const std::string& name : files)
    model.cameras.push_back(read_strecha_camera(camera_folder + "/" + name, name.substr(0, name.size() - 7)));
  model.tracks = read_tracks_ply(tracks_ply);
  model.validate(tracks_ply);
  return model;
}

}  // namespace sharpmesh
