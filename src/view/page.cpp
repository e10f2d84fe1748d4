// The HTML page of `sharpmesh view`: the template and the three.js bundle
// built from web/ (view/assets.h), with the scene as base64 typed arrays in
// a JSON block. Coordinates are shifted to the bounding-box centre before the
// conversion to float, so far-from-origin scans keep their precision.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sharpmesh/errors.h"
#include "sharpmesh/version.h"
#include "sharpmesh/view.h"
#include "view/assets.h"

namespace sharpmesh {
namespace {

const char* const kViews[] = {"iso", "front", "back", "left", "right", "top", "bottom"};

std::string base64(const void* data, std::size_t size) {
  static const char table[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const std::uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    out += {table[v >> 18], table[(v >> 12) & 63], table[(v >> 6) & 63], table[v & 63]};
  }
  if (i + 1 == size) {
    const std::uint32_t v = bytes[i] << 16;
    out += {table[v >> 18], table[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == size) {
    const std::uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8);
    out += {table[v >> 18], table[(v >> 12) & 63], table[(v >> 6) & 63], '='};
  }
  return out;
}

template <class T>
std::string base64(const std::vector<T>& values) {
  return base64(values.data(), values.size() * sizeof(T));
}

std::vector<float> shifted(const std::vector<Vec3>& points, const Vec3& center) {
  std::vector<float> out;
  out.reserve(3 * points.size());
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(p[k] - center[k]));
  return out;
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

void check_scene(const ViewScene& scene) {
  const SurfaceMesh& mesh = scene.mesh;
  if (mesh.faces.empty()) throw InvalidArgument("view: the mesh has no facets");
  for (const Vec3& v : mesh.vertices)
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      throw InvalidArgument("view: the mesh has a NaN or infinite coordinate");
  for (const Triangle& f : mesh.faces)
    for (std::uint32_t i : f)
      if (i >= mesh.vertices.size()) throw InvalidArgument("view: a facet refers to vertex " + format_number(i) + ", past the last one");
  if (!scene.vertex_distances.empty() && scene.vertex_distances.size() != mesh.vertices.size())
    throw InvalidArgument("view: " + format_number(scene.vertex_distances.size()) + " distances for " +
                          format_number(mesh.vertices.size()) + " vertices");
  if (!(scene.distance_scale >= 0 && std::isfinite(scene.distance_scale)))
    throw InvalidArgument("view: the distance scale must be a finite value >= 0");
}

}  // namespace

void ViewOptions::check() const {
  if (std::find(std::begin(kViews), std::end(kViews), view) == std::end(kViews))
    throw InvalidArgument("view: unknown view '" + view + "' (iso, front, back, left, right, top or bottom)");
  if (!(std::abs(norm(up) - 1) < 1e-6)) throw InvalidArgument("view: the up direction must be a unit vector");
  if (camera < -1 || camera >= static_cast<int>(cameras.size()))
    throw InvalidArgument("view: camera " + format_number(camera) + " of " + format_number(cameras.size()));
  for (const ViewCamera& c : cameras)
    if (!(c.vertical_fov_degrees > 0 && c.vertical_fov_degrees < 180 && c.aspect > 0))
      throw InvalidArgument("view: camera '" + c.name + "' has no usable field of view");
}

ViewCamera view_camera(const Camera& camera) {
  ViewCamera v;
  v.name = camera.image_name;
  v.position = camera.center();
  // Rows of R are the camera axes in world coordinates.
  const Mat3& r = camera.rotation;
  v.forward = {r[2][0], r[2][1], r[2][2]};
  v.up = {-r[1][0], -r[1][1], -r[1][2]};
  v.vertical_fov_degrees = 2 * std::atan(0.5 * camera.height / camera.fy) * 180 / M_PI;
  v.aspect = static_cast<double>(camera.width) / camera.height;
  return v;
}

Vec3 cameras_up(const std::vector<Camera>& cameras) {
  Vec3 sum{0, 0, 0};
  for (const Camera& c : cameras) sum = sum + view_camera(c).up;
  const double length = norm(sum);
  return length > 0 ? (1 / length) * sum : Vec3{0, 0, 1};
}

bool viewer_available() { return view_assets::kScript[0] != '\0'; }

std::string viewer_page(const ViewScene& scene, const ViewOptions& options) {
  options.check();
  check_scene(scene);
  if (!viewer_available())
    throw InvalidArgument("this sharpmesh was built without its viewer (npm was not found at build time)");
  const SurfaceMesh& mesh = scene.mesh;
  const BoundingBox box = bounding_box(mesh.vertices);
  const Vec3 center = box.center();
  const double diagonal = box.diagonal() > 0 ? box.diagonal() : 1.0;

  std::vector<std::uint32_t> indices;
  indices.reserve(3 * mesh.faces.size());
  for (const Triangle& f : mesh.faces) indices.insert(indices.end(), f.begin(), f.end());
  nlohmann::json data = {
      {"title", scene.title.empty() ? "mesh" : scene.title},
      {"view", options.view},
      {"up", options.up},
      {"camera", options.camera},
      {"diagonal", diagonal},
      {"center", center},
      {"wireframe", options.wireframe < 0 ? mesh.faces.size() < 300'000 : options.wireframe > 0},
      {"mesh",
       {{"positions", base64(shifted(mesh.vertices, center))},
        {"indices", base64(indices)},
        {"facets", mesh.faces.size()},
        {"vertices", mesh.vertices.size()}}}};
  if (!scene.features.empty()) {
    std::vector<Vec3> segments;
    for (const Polyline& line : scene.features)
      for (std::size_t i = 1; i < line.size(); ++i) {
        segments.push_back(line[i - 1]);
        segments.push_back(line[i]);
      }
    data["features"] = {{"positions", base64(shifted(segments, center))},
                        {"polylines", scene.features.size()},
                        {"segments", segments.size() / 2}};
  }
  if (!options.cameras.empty()) {
    nlohmann::json cameras = nlohmann::json::array();
    for (const ViewCamera& c : options.cameras)
      cameras.push_back({{"name", c.name}, {"position", c.position - center}, {"forward", c.forward}, {"up", c.up},
                         {"fov", c.vertical_fov_degrees}, {"aspect", c.aspect}});
    data["cameras"] = cameras;
  }
  if (!scene.points.empty())
    data["points"] = {{"positions", base64(shifted(scene.points, center))}, {"count", scene.points.size()}};
  if (!scene.vertex_distances.empty()) {
    const std::vector<double>& d = scene.vertex_distances;
    const double max = *std::max_element(d.begin(), d.end());
    double sum = 0;
    for (double v : d) sum += v;
    const double scale = scene.distance_scale > 0 ? scene.distance_scale : max > 0 ? max : 1.0;
    data["distance"] = {{"values", base64(std::vector<float>(d.begin(), d.end()))},
                        {"max", max},
                        {"mean", sum / d.size()},
                        {"scale", scale},
                        {"reference", scene.reference_name.empty() ? "the reference" : scene.reference_name}};
  }
  // "</" inside a <script> block would end it; "<\/" is the same JSON string.
  std::string json = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  replace_all(json, "</", "<\\/");
  std::string title = scene.title.empty() ? "mesh" : scene.title;
  for (const auto& [from, to] : {std::pair<const char*, const char*>{"&", "&amp;"}, {"<", "&lt;"}, {">", "&gt;"}, {"@", "&#64;"}})
    replace_all(title, from, to);

  std::string page = view_assets::kTemplate;
  replace_all(page, "@VERSION@", SHARPMESH_VERSION);
  replace_all(page, "@TITLE@", title);
  replace_all(page, "@BODY_CLASS@", options.bare ? "bare" : "");
  // Data and script last: they are large and must not be scanned for placeholders.
  const std::size_t data_at = page.find("@DATA@");
  page.replace(data_at, 6, json);
  const std::size_t script_at = page.find("@SCRIPT@", data_at + json.size());
  page.replace(script_at, 8, view_assets::kScript);
  return page;
}

}  // namespace sharpmesh
