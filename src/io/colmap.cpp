// COLMAP sparse models (cameras, images, points3D; text and binary) and the
// dense fusion output (fused.ply + fused.ply.vis), in COLMAP 3.8's layout:
// quaternions scalar first and world-to-camera, pixel (0.5, 0.5) at the
// centre of the top-left pixel (the convention of sharpmesh's Camera).
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <unordered_map>

#include <sys/stat.h>

#include "io/atomic_file.h"
#include "io/binary.h"
#include "io/formats.h"
#include "io/text.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_io.h"

namespace sharpmesh {
namespace {

using io::BinaryReader;
using io::BinaryWriter;

// COLMAP's camera models (src/base/camera_models.h in 3.8): id, name,
// parameter count, and which parameters are distortion terms.
struct CameraModelInfo {
  int id;
  const char* name;
  int params;
  int first_distortion;  // index of the first distortion parameter, -1 if none
  bool fisheye;
};
constexpr CameraModelInfo kModels[] = {
    {0, "SIMPLE_PINHOLE", 3, -1, false}, {1, "PINHOLE", 4, -1, false},        {2, "SIMPLE_RADIAL", 4, 3, false},
    {3, "RADIAL", 5, 3, false},          {4, "OPENCV", 8, 4, false},          {5, "OPENCV_FISHEYE", 8, 4, true},
    {6, "FULL_OPENCV", 12, 4, false},    {7, "FOV", 5, 4, true},              {8, "SIMPLE_RADIAL_FISHEYE", 4, 3, true},
    {9, "RADIAL_FISHEYE", 5, 3, true},   {10, "THIN_PRISM_FISHEYE", 12, 4, true}};

const CameraModelInfo* model_by_name(std::string_view name) {
  for (const CameraModelInfo& m : kModels)
    if (name == m.name) return &m;
  return nullptr;
}
const CameraModelInfo* model_by_id(int id) {
  for (const CameraModelInfo& m : kModels)
    if (id == m.id) return &m;
  return nullptr;
}

// Intrinsics of one COLMAP camera, checked to be a pinhole.
struct Intrinsics {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
};

Intrinsics to_pinhole(const CameraModelInfo& model, std::uint64_t width, std::uint64_t height, const std::vector<double>& p,
                      const std::string& where) {
  if (model.fisheye)
    throw InvalidInput(where + ": camera model " + model.name +
                       " is not a pinhole; undistort the images first (colmap image_undistorter) and use its sparse model");
  if (model.first_distortion >= 0)
    for (std::size_t i = static_cast<std::size_t>(model.first_distortion); i < p.size(); ++i)
      if (p[i] != 0)
        throw InvalidInput(where + ": camera model " + model.name +
                           " has non-zero distortion; undistort the images first (colmap image_undistorter) and use its sparse model");
  if (width == 0 || height == 0 || width > (1u << 20) || height > (1u << 20))
    throw InvalidInput(where + ": image size " + format_number(width) + "x" + format_number(height) + " is invalid");
  Intrinsics k;
  k.width = static_cast<int>(width);
  k.height = static_cast<int>(height);
  const bool one_focal = model.id == 0 || model.id == 2 || model.id == 3;
  k.fx = p[0];
  k.fy = one_focal ? p[0] : p[1];
  k.cx = one_focal ? p[1] : p[2];
  k.cy = one_focal ? p[2] : p[3];
  return k;
}

struct RawImage {
  std::uint32_t id = 0;
  std::uint32_t camera_id = 0;
  std::array<double, 4> q{};
  Vec3 t{};
  std::string name;
  std::vector<Vec2> points2d;
};

struct RawPoint {
  Vec3 position{};
  Rgb color{};
  std::vector<std::pair<std::uint32_t, std::uint32_t>> track;  // (image id, point2D index)
};

StereoModel assemble(const std::string& folder, const std::map<std::uint32_t, Intrinsics>& cameras, const std::vector<RawImage>& images,
                     const std::vector<RawPoint>& points) {
  StereoModel model;
  std::unordered_map<std::uint32_t, std::uint32_t> index_of_image;
  for (const RawImage& image : images) {
    const std::string where = folder + ": image " + std::to_string(image.id) + " (" + image.name + ")";
    const auto k = cameras.find(image.camera_id);
    if (k == cameras.end()) throw InvalidInput(where + ": refers to camera " + format_number(image.camera_id) + ", which is not in cameras");
    if (!index_of_image.emplace(image.id, static_cast<std::uint32_t>(model.cameras.size())).second)
      throw InvalidInput(where + ": image id used twice");
    Camera c;
    c.image_name = image.name;
    c.width = k->second.width;
    c.height = k->second.height;
    c.fx = k->second.fx;
    c.fy = k->second.fy;
    c.cx = k->second.cx;
    c.cy = k->second.cy;
    try {
      c.rotation = rotation_from_quaternion(image.q[0], image.q[1], image.q[2], image.q[3]);
    } catch (const InvalidInput& e) {
      throw InvalidInput(where + ": " + e.what());
    }
    c.translation = image.t;
    c.validate(where);
    model.cameras.push_back(std::move(c));
  }
  model.tracks.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const RawPoint& p = points[i];
    Track t;
    t.position = p.position;
    t.color = p.color;
    for (const auto& [image_id, point2d] : p.track) {
      const auto it = index_of_image.find(image_id);
      if (it == index_of_image.end())
        throw InvalidInput(folder + ": point " + format_number(i) + " refers to image " + format_number(image_id) + ", which is not in images");
      const RawImage& image = images[it->second];
      if (point2d >= image.points2d.size())
        throw InvalidInput(folder + ": point " + format_number(i) + " refers to observation " + format_number(point2d) + " of image " +
                           format_number(image_id) + ", which has " + format_number(image.points2d.size()));
      if (std::find(t.views.begin(), t.views.end(), it->second) != t.views.end()) continue;  // one observation per view
      t.views.push_back(it->second);
      t.pixels.push_back(image.points2d[point2d]);
    }
    model.tracks.push_back(std::move(t));
  }
  model.validate(folder);
  return model;
}

// ---- text -------------------------------------------------------------------

std::vector<double> parse_numbers(std::string_view line, const std::string& where) {
  std::vector<double> values;
  std::string_view token;
  while (io::next_token(line, token)) {
    double v;
    if (!io::parse_double(token, v)) throw InvalidInput(where + ": '" + std::string(token) + "' is not a number");
    values.push_back(v);
  }
  return values;
}

bool is_data_line(std::string_view line) {
  std::size_t i = 0;
  while (i < line.size() && io::is_space(line[i])) ++i;
  return i < line.size() && line[i] != '#';
}

std::uint32_t as_id(double v, const std::string& where) {
  if (!(v >= 0) || v > 4294967295.0 || v != std::floor(v)) throw InvalidInput(where + ": invalid id");
  return static_cast<std::uint32_t>(v);
}

std::map<std::uint32_t, Intrinsics> read_cameras_text(const std::string& path) {
  const std::string text = io::read_file(path);
  io::LineCursor cursor(text);
  std::string_view line;
  std::map<std::uint32_t, Intrinsics> cameras;
  while (cursor.next(line)) {
    if (!is_data_line(line)) continue;
    const std::string where = path + ": line " + std::to_string(cursor.line_number());
    std::string_view rest = line, id_token, model_token;
    io::next_token(rest, id_token);
    if (!io::next_token(rest, model_token)) throw InvalidInput(where + ": expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]");
    std::int64_t id;
    if (!io::parse_integer(id_token, id) || id < 0 || id > 4294967295LL) throw InvalidInput(where + ": invalid camera id");
    const CameraModelInfo* model = model_by_name(model_token);
    if (!model) throw InvalidInput(where + ": unknown camera model '" + std::string(model_token) + "'");
    const std::vector<double> values = parse_numbers(rest, where);
    if (values.size() != static_cast<std::size_t>(model->params) + 2)
      throw InvalidInput(where + ": " + model->name + " needs WIDTH HEIGHT and " + format_number(model->params) + " parameters");
    for (double size : {values[0], values[1]})
      if (!(size >= 0 && size <= 2147483647.0) || size != std::floor(size))
        throw InvalidInput(where + ": invalid image size (expected WIDTH and HEIGHT in pixels)");
    const std::vector<double> params(values.begin() + 2, values.end());
    cameras[static_cast<std::uint32_t>(id)] =
        to_pinhole(*model, static_cast<std::uint64_t>(values[0]), static_cast<std::uint64_t>(values[1]), params, where);
  }
  return cameras;
}

std::vector<RawImage> read_images_text(const std::string& path) {
  const std::string text = io::read_file(path);
  io::LineCursor cursor(text);
  std::string_view line;
  std::vector<RawImage> images;
  while (cursor.next(line)) {
    if (!is_data_line(line)) continue;
    const std::string where = path + ": line " + std::to_string(cursor.line_number());
    std::string_view rest = line, token;
    std::vector<double> v;
    for (int i = 0; i < 9; ++i) {
      double x;
      if (!io::next_token(rest, token) || !io::parse_double(token, x))
        throw InvalidInput(where + ": expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
      v.push_back(x);
    }
    std::string_view name;
    if (!io::next_token(rest, name)) throw InvalidInput(where + ": missing image name");
    RawImage image;
    image.id = as_id(v[0], where);
    image.q = {v[1], v[2], v[3], v[4]};
    image.t = {v[5], v[6], v[7]};
    image.camera_id = as_id(v[8], where);
    image.name = std::string(name);
    // The next line holds the observations, possibly empty: it is never skipped.
    std::string_view points_line;
    if (cursor.next(points_line)) {
      const std::vector<double> p = parse_numbers(points_line, path + ": line " + std::to_string(cursor.line_number()));
      if (p.size() % 3 != 0) throw InvalidInput(path + ": line " + format_number(cursor.line_number()) + ": POINTS2D must be triples X Y POINT3D_ID");
      for (std::size_t i = 0; i < p.size(); i += 3) image.points2d.push_back({p[i], p[i + 1]});
    }
    images.push_back(std::move(image));
  }
  return images;
}

std::vector<RawPoint> read_points_text(const std::string& path) {
  const std::string text = io::read_file(path);
  io::LineCursor cursor(text);
  std::string_view line;
  std::vector<RawPoint> points;
  while (cursor.next(line)) {
    if (!is_data_line(line)) continue;
    const std::string where = path + ": line " + std::to_string(cursor.line_number());
    const std::vector<double> v = parse_numbers(line, where);
    if (v.size() < 8 || (v.size() - 8) % 2 != 0)
      throw InvalidInput(where + ": expected POINT3D_ID X Y Z R G B ERROR and (IMAGE_ID POINT2D_IDX) pairs");
    RawPoint p;
    p.position = {v[1], v[2], v[3]};
    io::check_finite(p.position, path, "line " + std::to_string(cursor.line_number()));
    for (int c = 0; c < 3; ++c) p.color[c] = static_cast<std::uint8_t>(std::clamp(v[4 + c], 0.0, 255.0));
    for (std::size_t i = 8; i < v.size(); i += 2) p.track.emplace_back(as_id(v[i], where), as_id(v[i + 1], where));
    points.push_back(std::move(p));
  }
  return points;
}

// ---- binary (COLMAP's ReadCamerasBinary, ReadImagesBinary, ReadPoints3DBinary) ----

std::map<std::uint32_t, Intrinsics> read_cameras_binary(const std::string& path) {
  const std::string data = io::read_file(path);
  BinaryReader in(data, path);
  const auto count = in.read<std::uint64_t>("the camera count");
  in.expect(count, 24, "camera");
  std::map<std::uint32_t, Intrinsics> cameras;
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::string where = path + ": camera " + std::to_string(i);
    const auto id = in.read<std::uint32_t>("a camera id");
    const auto model_id = in.read<std::int32_t>("a camera model");
    const CameraModelInfo* model = model_by_id(model_id);
    if (!model) throw InvalidInput(where + ": unknown camera model id " + format_number(model_id));
    const auto width = in.read<std::uint64_t>("a width");
    const auto height = in.read<std::uint64_t>("a height");
    std::vector<double> params(static_cast<std::size_t>(model->params));
    for (double& p : params) p = in.read<double>("camera parameters");
    cameras[id] = to_pinhole(*model, width, height, params, where);
  }
  return cameras;
}

std::vector<RawImage> read_images_binary(const std::string& path) {
  const std::string data = io::read_file(path);
  BinaryReader in(data, path);
  const auto count = in.read<std::uint64_t>("the image count");
  in.expect(count, 4 + 7 * 8 + 4 + 1 + 8, "image");
  std::vector<RawImage> images(static_cast<std::size_t>(count));
  for (RawImage& image : images) {
    image.id = in.read<std::uint32_t>("an image id");
    for (double& q : image.q) q = in.read<double>("a quaternion");
    for (double& t : image.t) t = in.read<double>("a translation");
    image.camera_id = in.read<std::uint32_t>("a camera id");
    image.name = in.read_string("an image name");
    const auto n = in.read<std::uint64_t>("the observation count");
    in.expect(n, 24, "observation");
    image.points2d.resize(static_cast<std::size_t>(n));
    for (Vec2& p : image.points2d) {
      p[0] = in.read<double>("an observation");
      p[1] = in.read<double>("an observation");
      (void)in.read<std::uint64_t>("an observation's point id");
    }
  }
  return images;
}

std::vector<RawPoint> read_points_binary(const std::string& path) {
  const std::string data = io::read_file(path);
  BinaryReader in(data, path);
  const auto count = in.read<std::uint64_t>("the point count");
  in.expect(count, 8 + 24 + 3 + 8 + 8, "point");
  std::vector<RawPoint> points(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < points.size(); ++i) {
    RawPoint& p = points[i];
    (void)in.read<std::uint64_t>("a point id");
    for (double& c : p.position) c = in.read<double>("a point position");
    io::check_finite(p.position, path, "point " + std::to_string(i));
    for (std::uint8_t& c : p.color) c = in.read<std::uint8_t>("a colour");
    (void)in.read<double>("a reprojection error");
    const auto n = in.read<std::uint64_t>("a track length");
    in.expect(n, 8, "track element");
    p.track.resize(static_cast<std::size_t>(n));
    for (auto& [image, point2d] : p.track) {
      image = in.read<std::uint32_t>("a track's image id");
      point2d = in.read<std::uint32_t>("a track's observation index");
    }
  }
  return points;
}

bool exists(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0;
}

// ---- writers ----------------------------------------------------------------

struct Observation {
  Vec2 pixel;
  std::int64_t point;
};

// COLMAP's ERROR column: the mean reprojection error of a track, pixels.
double mean_reprojection_error(const StereoModel& model, const Track& t) {
  if (t.pixels.empty()) return 0;
  double sum = 0;
  for (std::size_t k = 0; k < t.views.size(); ++k) {
    Vec2 p;
    if (model.cameras[t.views[k]].project(t.position, p)) sum += std::hypot(p[0] - t.pixels[k][0], p[1] - t.pixels[k][1]);
  }
  return sum / static_cast<double>(t.views.size());
}

// For each view, the observations it makes, and for each track the index of
// its observation in each of its views (COLMAP's POINT2D_IDX).
void collect_observations(const StereoModel& model, std::vector<std::vector<Observation>>& per_view,
                          std::vector<std::vector<std::uint32_t>>& index) {
  per_view.assign(model.cameras.size(), {});
  index.assign(model.tracks.size(), {});
  for (std::size_t i = 0; i < model.tracks.size(); ++i) {
    const Track& t = model.tracks[i];
    for (std::size_t k = 0; k < t.views.size(); ++k) {
      Vec2 pixel{0, 0};
      if (!t.pixels.empty()) pixel = t.pixels[k];
      else model.cameras[t.views[k]].project(t.position, pixel);
      index[i].push_back(static_cast<std::uint32_t>(per_view[t.views[k]].size()));
      per_view[t.views[k]].push_back({pixel, static_cast<std::int64_t>(i + 1)});
    }
  }
}

void write_text(const std::string& folder, const StereoModel& model) {
  std::vector<std::vector<Observation>> per_view;
  std::vector<std::vector<std::uint32_t>> index;
  collect_observations(model, per_view, index);
  std::ostringstream cameras, images, points;
  cameras.precision(17);
  images.precision(17);
  points.precision(17);
  cameras << "# Camera list with one line of data per camera:\n#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n# Number of cameras: "
          << model.cameras.size() << "\n";
  images << "# Image list with two lines of data per image:\n#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
            "#   POINTS2D[] as (X, Y, POINT3D_ID)\n# Number of images: "
         << model.cameras.size() << "\n";
  for (std::size_t i = 0; i < model.cameras.size(); ++i) {
    const Camera& c = model.cameras[i];
    cameras << i + 1 << " PINHOLE " << c.width << ' ' << c.height << ' ' << c.fx << ' ' << c.fy << ' ' << c.cx << ' ' << c.cy << '\n';
    const auto q = quaternion_from_rotation(c.rotation);
    images << i + 1 << ' ' << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << q[3] << ' ' << c.translation[0] << ' ' << c.translation[1]
           << ' ' << c.translation[2] << ' ' << i + 1 << ' ' << c.image_name << '\n';
    bool first = true;
    for (const Observation& o : per_view[i]) {
      images << (first ? "" : " ") << o.pixel[0] << ' ' << o.pixel[1] << ' ' << o.point;
      first = false;
    }
    images << '\n';
  }
  points << "# 3D point list with one line of data per point:\n"
            "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n# Number of points: "
         << model.tracks.size() << "\n";
  for (std::size_t i = 0; i < model.tracks.size(); ++i) {
    const Track& t = model.tracks[i];
    points << i + 1 << ' ' << t.position[0] << ' ' << t.position[1] << ' ' << t.position[2] << ' ' << int(t.color[0]) << ' '
           << int(t.color[1]) << ' ' << int(t.color[2]) << ' ' << mean_reprojection_error(model, t);
    for (std::size_t k = 0; k < t.views.size(); ++k) points << ' ' << t.views[k] + 1 << ' ' << index[i][k];
    points << '\n';
  }
  write_text_file(folder + "/cameras.txt", cameras.str());
  write_text_file(folder + "/images.txt", images.str());
  write_text_file(folder + "/points3D.txt", points.str());
}

void write_binary(const std::string& folder, const StereoModel& model) {
  std::vector<std::vector<Observation>> per_view;
  std::vector<std::vector<std::uint32_t>> index;
  collect_observations(model, per_view, index);
  BinaryWriter cameras, images, points;
  cameras.write<std::uint64_t>(model.cameras.size());
  images.write<std::uint64_t>(model.cameras.size());
  for (std::size_t i = 0; i < model.cameras.size(); ++i) {
    const Camera& c = model.cameras[i];
    cameras.write<std::uint32_t>(static_cast<std::uint32_t>(i + 1));
    cameras.write<std::int32_t>(1);  // PINHOLE
    cameras.write<std::uint64_t>(static_cast<std::uint64_t>(c.width));
    cameras.write<std::uint64_t>(static_cast<std::uint64_t>(c.height));
    for (double p : {c.fx, c.fy, c.cx, c.cy}) cameras.write<double>(p);
    images.write<std::uint32_t>(static_cast<std::uint32_t>(i + 1));
    for (double q : quaternion_from_rotation(c.rotation)) images.write<double>(q);
    for (double t : c.translation) images.write<double>(t);
    images.write<std::uint32_t>(static_cast<std::uint32_t>(i + 1));
    images.write_string(c.image_name);
    images.write<std::uint64_t>(per_view[i].size());
    for (const Observation& o : per_view[i]) {
      images.write<double>(o.pixel[0]);
      images.write<double>(o.pixel[1]);
      images.write<std::uint64_t>(static_cast<std::uint64_t>(o.point));
    }
  }
  points.write<std::uint64_t>(model.tracks.size());
  for (std::size_t i = 0; i < model.tracks.size(); ++i) {
    const Track& t = model.tracks[i];
    points.write<std::uint64_t>(i + 1);
    for (double c : t.position) points.write<double>(c);
    for (std::uint8_t c : t.color) points.write<std::uint8_t>(c);
    points.write<double>(mean_reprojection_error(model, t));
    points.write<std::uint64_t>(t.views.size());
    for (std::size_t k = 0; k < t.views.size(); ++k) {
      points.write<std::uint32_t>(t.views[k] + 1);
      points.write<std::uint32_t>(index[i][k]);
    }
  }
  write_text_file(folder + "/cameras.bin", cameras.bytes());
  write_text_file(folder + "/images.bin", images.bytes());
  write_text_file(folder + "/points3D.bin", points.bytes());
}

}  // namespace

StereoModel read_colmap_model(const std::string& folder) {
  const bool binary = exists(folder + "/cameras.bin");
  if (!binary && !exists(folder + "/cameras.txt"))
    throw InvalidInput(folder + ": not a COLMAP model (no cameras.bin or cameras.txt)");
  if (binary)
    return assemble(folder, read_cameras_binary(folder + "/cameras.bin"), read_images_binary(folder + "/images.bin"),
                    read_points_binary(folder + "/points3D.bin"));
  return assemble(folder, read_cameras_text(folder + "/cameras.txt"), read_images_text(folder + "/images.txt"),
                  read_points_text(folder + "/points3D.txt"));
}

void write_colmap_model(const std::string& folder, const StereoModel& model, bool binary) {
  model.validate("model to write to " + folder);
  if (binary) write_binary(folder, model);
  else write_text(folder, model);
}

StereoModel read_colmap_fused(const std::string& ply_path, const std::vector<Camera>& cameras, std::vector<Vec3>* normals) {
  const io::PlyContents ply = io::read_ply(ply_path);
  const std::string vis_path = ply_path + ".vis";
  const std::string data = io::read_file(vis_path);
  BinaryReader in(data, vis_path);
  const auto count = in.read<std::uint64_t>("the point count");
  if (count != ply.points.size())
    throw InvalidInput(vis_path + ": lists " + format_number(count) + " points but " + ply_path + " has " + format_number(ply.points.size()));
  StereoModel model;
  model.cameras = cameras;
  model.dense_points = true;
  model.tracks.resize(ply.points.size());
  for (std::size_t i = 0; i < ply.points.size(); ++i) {
    Track& t = model.tracks[i];
    t.position = ply.points.points[i];
    if (ply.points.has_colors()) t.color = ply.points.colors[i];
    const auto n = in.read<std::uint32_t>("a visibility count");
    in.expect(n, 4, "view index");
    for (std::uint32_t k = 0; k < n; ++k) {
      const auto view = in.read<std::uint32_t>("a view index");
      if (view >= cameras.size())
        throw InvalidInput(vis_path + ": point " + format_number(i) + " refers to image index " + format_number(view) + " but the model has " +
                           format_number(cameras.size()) + " images");
      if (std::find(t.views.begin(), t.views.end(), view) == t.views.end()) t.views.push_back(view);
    }
  }
  if (!in.at_end()) throw InvalidInput(vis_path + ": unexpected data after the last point");
  if (normals) *normals = ply.points.normals;
  model.validate(ply_path);
  return model;
}

void write_colmap_fused(const std::string& ply_path, const StereoModel& model, const std::vector<Vec3>& normals) {
  // COLMAP's own layout (mvs/fusion): float x y z nx ny nz, uchar red green blue.
  if (!normals.empty() && normals.size() != model.tracks.size()) throw std::logic_error("write_colmap_fused: one normal per point expected");
  std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(model.tracks.size()) +
                       "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                       "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  BinaryWriter body, vis;
  vis.write<std::uint64_t>(model.tracks.size());
  for (std::size_t i = 0; i < model.tracks.size(); ++i) {
    const Track& t = model.tracks[i];
    for (double c : t.position) body.write<float>(static_cast<float>(c));
    for (int k = 0; k < 3; ++k) body.write<float>(normals.empty() ? 0.0f : static_cast<float>(normals[i][k]));
    for (std::uint8_t c : t.color) body.write<std::uint8_t>(c);
    vis.write<std::uint32_t>(static_cast<std::uint32_t>(t.views.size()));
    for (std::uint32_t v : t.views) vis.write<std::uint32_t>(v);
  }
  write_text_file(ply_path, header + body.bytes());
  write_text_file(ply_path + ".vis", vis.bytes());
}

}  // namespace sharpmesh
