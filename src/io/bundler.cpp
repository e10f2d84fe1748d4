// Bundler v0.3 (`bundle.out` + list file) and VisualSFM NVM v3.
// Bundler: P = R X + t with the camera looking down -Z and y up; a
// measurement is relative to the image centre, y up. sharpmesh's camera looks
// down +Z with y down, so R and t are flipped by diag(1, -1, -1).
// NVM: focal, quaternion (world-to-camera, scalar first), camera centre C,
// radial distortion; measurements are relative to the image centre (VisualSFM)
// or absolute (some exporters), decided from the reprojections.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/formats.h"
#include "io/image_size.h"
#include "io/token_stream.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_io.h"

namespace sharpmesh {
namespace {

std::string folder_of(const std::string& path) {
  const std::string parent = std::filesystem::path(path).parent_path().string();
  return parent.empty() ? "." : parent;
}

// Largest displacement, in pixels, that radial distortion k1 r^2 + k2 r^4
// (r in normalised coordinates) causes inside the image: at its corners.
double corner_displacement(double focal, int width, int height, double k1, double k2) {
  const double radius = 0.5 * std::hypot(width, height);
  const double rho = radius / focal;
  return radius * std::abs(k1 * rho * rho + k2 * rho * rho * rho * rho);
}

constexpr double kMaxDistortionPixels = 0.5;

void refuse_distortion(const std::string& where, double displacement) {
  if (displacement > kMaxDistortionPixels)
    throw InvalidInput(where + ": radial distortion moves the image corners by " + format_number(displacement) +
                       " px; undistort the images first (only pinhole cameras are supported)");
}

}  // namespace

StereoModel read_bundler(const std::string& out_path, const std::string& list_path) {
  const std::string list_text = io::read_file(list_path);
  std::vector<std::string> images;
  {
    io::LineCursor cursor(list_text);
    std::string_view line, token;
    while (cursor.next(line))
      if (io::next_token(line, token)) images.emplace_back(token);
  }
  const std::string text = io::read_file(out_path);
  io::TokenStream in(text, out_path);
  if (text.rfind("# Bundle file v0.3", 0) != 0) throw InvalidInput(out_path + ": not a Bundler v0.3 file (first line '# Bundle file v0.3')");
  const auto num_cameras = in.integer("camera count", 0, 1 << 24);
  const auto num_points = in.integer("point count", 0, INT64_C(1) << 32);
  if (static_cast<std::size_t>(num_cameras) != images.size())
    throw InvalidInput(out_path + ": has " + format_number(num_cameras) + " cameras but " + list_path + " lists " +
                       format_number(images.size()) + " images");
  const std::string image_folder = folder_of(list_path);
  StereoModel model;
  std::vector<std::int64_t> index_of(static_cast<std::size_t>(num_cameras), -1);  // unregistered cameras (f = 0) are dropped
  for (std::int64_t i = 0; i < num_cameras; ++i) {
    const double f = in.number("focal length"), k1 = in.number("k1"), k2 = in.number("k2");
    Mat3 r;
    for (auto& row : r)
      for (double& v : row) v = in.number("rotation");
    Vec3 t;
    for (double& v : t) v = in.number("translation");
    if (f == 0) continue;
    const std::string image = images[static_cast<std::size_t>(i)];
    const std::string where = out_path + ": camera " + std::to_string(i) + " (" + image + ")";
    const auto [width, height] = io::image_size(image_folder + "/" + image);
    refuse_distortion(where, corner_displacement(f, width, height, k1, k2));
    Camera c;
    c.image_name = image;
    c.width = width;
    c.height = height;
    c.fx = c.fy = f;
    c.cx = 0.5 * width;
    c.cy = 0.5 * height;
    for (int j = 0; j < 3; ++j) c.rotation[0][j] = r[0][j], c.rotation[1][j] = -r[1][j], c.rotation[2][j] = -r[2][j];
    c.translation = {t[0], -t[1], -t[2]};
    c.validate(where);
    index_of[static_cast<std::size_t>(i)] = static_cast<std::int64_t>(model.cameras.size());
    model.cameras.push_back(c);
  }
  model.tracks.reserve(static_cast<std::size_t>(std::min<std::int64_t>(num_points, 1 << 24)));
  for (std::int64_t i = 0; i < num_points; ++i) {
    Track track;
    for (double& v : track.position) v = in.number("point position");
    for (std::uint8_t& c : track.color) c = static_cast<std::uint8_t>(in.integer("colour", 0, 255));
    const auto n = in.integer("view count", 0, num_cameras);
    for (std::int64_t k = 0; k < n; ++k) {
      const auto camera = in.integer("camera index", 0, num_cameras - 1);
      (void)in.integer("key index", 0);
      const double x = in.number("measurement"), y = in.number("measurement");
      const std::int64_t view = index_of[static_cast<std::size_t>(camera)];
      if (view < 0) throw in.error("point " + std::to_string(i) + " is seen by camera " + std::to_string(camera) + ", which is not registered");
      const Camera& c = model.cameras[static_cast<std::size_t>(view)];
      if (std::find(track.views.begin(), track.views.end(), view) != track.views.end()) continue;
      track.views.push_back(static_cast<std::uint32_t>(view));
      track.pixels.push_back({x + c.cx, -y + c.cy});
    }
    model.tracks.push_back(std::move(track));
  }
  model.validate(out_path);
  return model;
}

StereoModel read_nvm(const std::string& nvm_path) {
  const std::string text = io::read_file(nvm_path);
  io::TokenStream in(text, nvm_path);
  const std::string_view magic = in.token("NVM_V3");
  if (magic != "NVM_V3") {
    if (magic.rfind("NVM_V3", 0) == 0) throw InvalidInput(nvm_path + ": NVM variant '" + std::string(magic) + "' is not supported (only NVM_V3)");
    throw InvalidInput(nvm_path + ": not an NVM file (it does not start with NVM_V3)");
  }
  // Optional shared calibration: "FixedK fx cx fy cy" on the first line.
  double fixed_fx = 0, fixed_fy = 0;
  const std::string_view first_rest = in.rest_of_line();
  if (!first_rest.empty()) {
    std::string_view rest = first_rest, token;
    io::next_token(rest, token);
    if (token == "FixedK") {
      double v[4];
      for (double& x : v)
        if (!io::next_token(rest, token) || !io::parse_double(token, x)) throw InvalidInput(nvm_path + ": line 1: FixedK needs fx cx fy cy");
      fixed_fx = v[0];
      fixed_fy = v[2];
    }
  }
  const std::string folder = folder_of(nvm_path);
  const auto num_cameras = in.integer("camera count", 0, 1 << 24);
  StereoModel model;
  for (std::int64_t i = 0; i < num_cameras; ++i) {
    const std::string name(in.token("image file name"));
    const double f = in.number("focal length");
    double q[4];
    for (double& v : q) v = in.number("quaternion");
    Vec3 center;
    for (double& v : center) v = in.number("camera centre");
    const double radial = in.number("radial distortion");
    (void)in.number("the trailing 0");
    const std::string where = nvm_path + ": camera " + std::to_string(i) + " (" + name + ")";
    const auto [width, height] = io::image_size(folder + "/" + name);
    Camera c;
    c.image_name = name;
    c.width = width;
    c.height = height;
    c.fx = fixed_fx > 0 ? fixed_fx : f;
    c.fy = fixed_fy > 0 ? fixed_fy : f;
    refuse_distortion(where, corner_displacement(c.fx, width, height, radial, 0));
    c.cx = 0.5 * width;
    c.cy = 0.5 * height;
    try {
      c.rotation = rotation_from_quaternion(q[0], q[1], q[2], q[3]);
    } catch (const InvalidInput& e) {
      throw InvalidInput(where + ": " + e.what());
    }
    c.translation = -1.0 * (c.rotation * center);
    c.validate(where);
    model.cameras.push_back(c);
  }
  const auto num_points = in.integer("point count", 0, INT64_C(1) << 32);
  for (std::int64_t i = 0; i < num_points; ++i) {
    Track track;
    for (double& v : track.position) v = in.number("point position");
    for (std::uint8_t& c : track.color) c = static_cast<std::uint8_t>(in.integer("colour", 0, 255));
    const auto n = in.integer("measurement count", 0, num_cameras);
    for (std::int64_t k = 0; k < n; ++k) {
      const auto view = static_cast<std::uint32_t>(in.integer("image index", 0, num_cameras - 1));
      (void)in.integer("feature index", 0);
      const double x = in.number("measurement"), y = in.number("measurement");
      if (std::find(track.views.begin(), track.views.end(), view) != track.views.end()) continue;
      track.views.push_back(view);
      track.pixels.push_back({x, y});
    }
    model.tracks.push_back(std::move(track));
  }
  // Centred or absolute measurements: the median offset between a measurement
  // and the centred projection of its point is ~0 for centred ones and ~the
  // principal point for absolute ones.
  std::vector<double> dx, dy;
  for (const Track& t : model.tracks)
    for (std::size_t k = 0; k < t.views.size(); ++k) {
      const Camera& c = model.cameras[t.views[k]];
      const Vec3 p = c.to_camera(t.position);
      if (!(p[2] > 0)) continue;
      dx.push_back(t.pixels[k][0] - c.fx * p[0] / p[2]);
      dy.push_back(t.pixels[k][1] - c.fy * p[1] / p[2]);
    }
  bool absolute = false;
  if (!dx.empty()) {
    std::nth_element(dx.begin(), dx.begin() + dx.size() / 2, dx.end());
    std::nth_element(dy.begin(), dy.begin() + dy.size() / 2, dy.end());
    const double mx = dx[dx.size() / 2], my = dy[dy.size() / 2];
    const Camera& c0 = model.cameras.front();
    absolute = std::hypot(mx, my) > 0.25 * std::hypot(c0.cx, c0.cy);
  }
  for (Track& t : model.tracks)
    for (std::size_t k = 0; k < t.views.size(); ++k) {
      const Camera& c = model.cameras[t.views[k]];
      // Absolute pixels follow the top-left pixel centre at (0, 0).
      if (absolute) t.pixels[k] = {t.pixels[k][0] + 0.5, t.pixels[k][1] + 0.5};
      else t.pixels[k] = {t.pixels[k][0] + c.cx, t.pixels[k][1] + c.cy};
    }
  model.validate(nvm_path);
  return model;
}

StereoModel read_stereo_model(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string ext = io::extension(path);
  if (ext == "nvm") return read_nvm(path);
  if (ext == "out") return read_bundler(path, folder_of(path) + "/list.txt");
  if (fs::is_directory(path, ec)) {
    if (fs::exists(path + "/cameras.bin", ec) || fs::exists(path + "/cameras.txt", ec)) return read_colmap_model(path);
    if (fs::exists(path + "/sparse/cameras.bin", ec) || fs::exists(path + "/sparse/cameras.txt", ec)) return read_colmap_model(path + "/sparse");
    if (fs::exists(path + "/sparse/0/cameras.bin", ec)) return read_colmap_model(path + "/sparse/0");
    throw InvalidInput(path + ": no COLMAP model here (cameras.txt/.bin, sparse/ or sparse/0/)");
  }
  if (!fs::exists(path, ec)) throw InvalidInput("cannot open '" + path + "': no such file or folder");
  throw InvalidInput(path + ": unknown camera format (expected a COLMAP model folder, a Bundler .out or an NVM file)");
}

}  // namespace sharpmesh
