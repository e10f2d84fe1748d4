// make-scene (issue 5): renders the synthetic building from cameras on an
// arc and writes images, cameras, tracks at two levels and the ground truth.
// Tracks imitate thesis 3.2: (a) matched interest points, triangulated from
// noisy pixels by minimising the squared distance to the rays (3.2.2), with
// outliers; (b) fused depth maps (3.2.3) with depth noise growing as depth^2
// and foreground fattening at depth edges.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/triangle_distance.h"
#include "io/binary.h"
#include "scene/building.h"
#include "scene/texture.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"
#include "sharpmesh/scene.h"
#include "sharpmesh/stereo_io.h"
#include "core/ray_caster.h"
#include "core/parallel.h"

namespace sharpmesh {
namespace {

namespace fs = std::filesystem;
using scene::Color;
using scene::SceneGeometry;

// Cameras on a horizontal arc in front of the building (-y side), looking at
// its centre, y down in the image.
std::vector<Camera> arc_cameras(const SceneOptions& o, const BoundingBox& building) {
  const Vec3 target{building.center()[0], building.center()[1], 0.35 * building.max[2]};
  const double radius = 1.25 * building.diagonal(), height = 1.0 * building.max[2];
  std::vector<Camera> cameras;
  for (int i = 0; i < o.views; ++i) {
    const double t = o.views == 1 ? 0.5 : static_cast<double>(i) / (o.views - 1);
    const double azimuth = (-90.0 + (t - 0.5) * o.arc) * M_PI / 180.0;
    const Vec3 center = target + Vec3{radius * std::cos(azimuth), radius * std::sin(azimuth), height - target[2]};
    const Vec3 forward = (1.0 / distance(target, center)) * (target - center);
    Vec3 right = cross(forward, Vec3{0, 0, 1});
    right = (1.0 / norm(right)) * right;
    const Vec3 down = cross(forward, right);
    Camera c;
    char name[32];
    std::snprintf(name, sizeof name, "view_%03d.png", i);
    c.image_name = name;
    c.width = o.width;
    c.height = o.height;
    c.fx = c.fy = 0.5 * o.width / std::tan(0.5 * o.fov * M_PI / 180.0);
    c.cx = 0.5 * o.width;
    c.cy = 0.5 * o.height;
    c.rotation = {{{right[0], right[1], right[2]}, {down[0], down[1], down[2]}, {forward[0], forward[1], forward[2]}}};
    c.translation = -1.0 * (c.rotation * center);
    cameras.push_back(c);
  }
  return cameras;
}

struct Rendering {
  cv::Mat color;  // CV_8UC3, BGR
  cv::Mat depth;  // CV_32F, camera z, 0 where no surface
  cv::Mat face;   // CV_32S, face index, -1 where no surface
};

Rendering render(const Camera& cam, const SceneGeometry& g, const detail::RayCaster& caster, const scene::Texture& texture,
                 const SceneOptions& o, std::uint64_t view_seed) {
  Rendering r{cv::Mat(cam.height, cam.width, CV_8UC3), cv::Mat(cam.height, cam.width, CV_32F), cv::Mat(cam.height, cam.width, CV_32S)};
  cv::Mat linear(cam.height, cam.width, CV_64FC3);
  const Vec3 origin = cam.center();
  const int ss = o.supersample;
  detail::parallel_for(static_cast<std::size_t>(cam.height), [&](std::size_t row) {
    const int y = static_cast<int>(row);
    for (int x = 0; x < cam.width; ++x) {
      Color sum{0, 0, 0};
      for (int sy = 0; sy < ss; ++sy)
        for (int sx = 0; sx < ss; ++sx) {
          const Vec2 pixel{x + (sx + 0.5) / ss, y + (sy + 0.5) / ss};
          const Vec3 dir = cam.viewing_ray(pixel);
          detail::RayHit hit;
          Color c = scene::Texture::sky();
          if (caster.first_hit(origin, dir, hit)) c = texture.shade(origin + hit.distance * dir, g.normal[hit.face], g.material[hit.face]);
          for (int k = 0; k < 3; ++k) sum[k] += c[k];
        }
      linear.at<cv::Vec3d>(y, x) = cv::Vec3d(sum[2], sum[1], sum[0]) / double(ss * ss);
      const Vec2 centre{x + 0.5, y + 0.5};
      const Vec3 dir = cam.viewing_ray(centre);
      detail::RayHit hit;
      if (caster.first_hit(origin, dir, hit)) {
        r.depth.at<float>(y, x) = static_cast<float>(cam.depth(origin + hit.distance * dir));
        r.face.at<int>(y, x) = static_cast<int>(hit.face);
      } else {
        r.depth.at<float>(y, x) = 0;
        r.face.at<int>(y, x) = -1;
      }
    }
  });
  std::mt19937_64 rng(view_seed);
  std::normal_distribution<double> noise(0.0, o.image_noise);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const cv::Vec3d c = linear.at<cv::Vec3d>(y, x);
      cv::Vec3b& out = r.color.at<cv::Vec3b>(y, x);
      for (int k = 0; k < 3; ++k) out[k] = cv::saturate_cast<std::uint8_t>(c[k] + (o.image_noise > 0 ? noise(rng) : 0.0));
    }
  return r;
}

// Least-squares point closest to the rays (thesis 3.2.2): sum over rays of
// (I - d d^T) (x - o) = 0.
Vec3 triangulate(const std::vector<Camera>& cams, const std::vector<std::uint32_t>& views, const std::vector<Vec2>& pixels) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < views.size(); ++k) {
    const Camera& c = cams[views[k]];
    const Vec3 d = c.viewing_ray(pixels[k]), o = c.center();
    const Eigen::Vector3d dv(d[0], d[1], d[2]);
    const Eigen::Matrix3d m = Eigen::Matrix3d::Identity() - dv * dv.transpose();
    a += m;
    b += m * Eigen::Vector3d(o[0], o[1], o[2]);
  }
  const Eigen::Vector3d x = a.ldlt().solve(b);
  return {x[0], x[1], x[2]};
}

Rgb to_rgb(const Color& c) {
  return {static_cast<std::uint8_t>(std::lround(c[0])), static_cast<std::uint8_t>(std::lround(c[1])), static_cast<std::uint8_t>(std::lround(c[2]))};
}

// Level (a): visible surface samples and labelled outliers, shuffled.
void make_tracks(const SceneGeometry& g, const std::vector<Camera>& cams, const detail::RayCaster& caster, const scene::Texture& texture,
                 const SceneOptions& o, StereoModel& model, std::vector<bool>& outlier) {
  std::mt19937_64 rng(o.seed * 7919 + 1);
  std::normal_distribution<double> pixel_noise(0.0, o.noise);
  std::vector<std::pair<Track, bool>> tracks;
  SampleOptions sampling;
  sampling.count = o.samples;
  sampling.seed = o.seed;
  std::vector<std::uint32_t> faces;
  const std::vector<Vec3> samples = sample_mesh(g.mesh, sampling, faces).points;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Vec3& point = samples[i];
    const std::uint32_t face = faces[i];
    Track t;
    for (std::uint32_t v = 0; v < cams.size(); ++v) {
      Vec2 p;
      if (!cams[v].project(point, p) || !cams[v].in_image(p) || caster.occluded(cams[v].center(), point)) continue;
      t.views.push_back(v);
      t.pixels.push_back({p[0] + pixel_noise(rng), p[1] + pixel_noise(rng)});
    }
    if (t.views.size() < 2) continue;
    t.position = triangulate(cams, t.views, t.pixels);
    t.color = to_rgb(texture.shade(point, g.normal[face], g.material[face]));
    tracks.emplace_back(std::move(t), false);
  }
  const std::size_t inliers = tracks.size();
  const auto wanted = static_cast<std::size_t>(std::lround(o.outliers / (1 - o.outliers) * static_cast<double>(inliers)));
  BoundingBox region = g.building;
  for (int i = 0; i < 2; ++i) region.min[i] -= 2, region.max[i] += 2;
  region.min[2] = 0;
  region.max[2] += 1;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t attempts = 0; tracks.size() < inliers + wanted && attempts < 100 * (wanted + 1); ++attempts) {
    Vec3 p;
    for (int i = 0; i < 3; ++i) p[i] = region.min[i] + u(rng) * (region.max[i] - region.min[i]);
    std::vector<std::uint32_t> seen;
    for (std::uint32_t v = 0; v < cams.size(); ++v) {
      Vec2 px;
      if (cams[v].project(p, px) && cams[v].in_image(px)) seen.push_back(v);
    }
    if (seen.size() < 2) continue;
    std::shuffle(seen.begin(), seen.end(), rng);
    seen.resize(std::min<std::size_t>(seen.size(), 2 + static_cast<std::size_t>(u(rng) * 3)));
    std::sort(seen.begin(), seen.end());
    Track t;
    t.position = p;
    t.views = seen;
    for (std::uint32_t v : seen) {
      Vec2 px;
      cams[v].project(p, px);
      t.pixels.push_back({px[0] + pixel_noise(rng), px[1] + pixel_noise(rng)});
    }
    const auto grey = static_cast<std::uint8_t>(60 + u(rng) * 140);
    t.color = {grey, grey, grey};
    tracks.emplace_back(std::move(t), true);
  }
  std::shuffle(tracks.begin(), tracks.end(), rng);
  for (auto& [t, is_outlier] : tracks) {
    model.tracks.push_back(std::move(t));
    outlier.push_back(is_outlier);
  }
}

// Level (b): depth-map points with depth noise and foreground fattening.
void make_fused(const SceneGeometry& g, const std::vector<Camera>& cams, const std::vector<Rendering>& renders, const SceneOptions& o,
                StereoModel& fused, std::vector<Vec3>& normals) {
  fused.cameras = cams;
  // Baseline of each view: distance to its nearest other camera.
  std::vector<double> baseline(cams.size(), 1.0);
  for (std::size_t v = 0; v < cams.size(); ++v) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t u = 0; u < cams.size(); ++u)
      if (u != v) best = std::min(best, distance(cams[u].center(), cams[v].center()));
    if (std::isfinite(best)) baseline[v] = best;
  }
  std::mt19937_64 rng(o.seed * 104729 + 3);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (std::size_t v = 0; v < cams.size(); ++v) {
    const Camera& cam = cams[v];
    cv::Mat far = renders[v].depth.clone();
    far.setTo(1e9f, far == 0);
    cv::Mat fattened = far;
    if (o.fatten > 0) cv::erode(far, fattened, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * o.fatten + 1, 2 * o.fatten + 1)));
    for (int y = o.fused_step / 2; y < cam.height; y += o.fused_step)
      for (int x = o.fused_step / 2; x < cam.width; x += o.fused_step) {
        double z = far.at<float>(y, x);
        const double front = fattened.at<float>(y, x);
        if (front < 0.98 * z) z = front;  // a foreground edge within `fatten` pixels swallows this one
        if (z >= 1e8) continue;
        z += gauss(rng) * o.fused_noise * z * z / (cam.fx * baseline[v]);
        const Vec2 pixel{x + 0.5, y + 0.5};
        Track t;
        t.position = cam.unproject(pixel, z);
        t.views.push_back(static_cast<std::uint32_t>(v));
        for (std::size_t u = 0; u < cams.size(); ++u) {
          Vec2 p;
          if (u == v || !cams[u].project(t.position, p) || !cams[u].in_image(p)) continue;
          const float surface = renders[u].depth.at<float>(static_cast<int>(p[1]), static_cast<int>(p[0]));
          if (surface == 0 || cams[u].depth(t.position) <= 1.02 * surface) t.views.push_back(static_cast<std::uint32_t>(u));
        }
        const cv::Vec3b c = renders[v].color.at<cv::Vec3b>(y, x);
        t.color = {c[2], c[1], c[0]};
        const int face = renders[v].face.at<int>(y, x);
        Vec3 n = face >= 0 ? g.normal[static_cast<std::size_t>(face)] : (1.0 / z) * (cam.center() - t.position);
        if (dot(n, cam.center() - t.position) < 0) n = -1.0 * n;
        fused.tracks.push_back(std::move(t));
        normals.push_back((1.0 / norm(n)) * n);
      }
  }
}

// COLMAP's dense array format (mvs/mat.h): "width&height&channels&" then
// little-endian float32 rows.
void write_depth(const std::string& path, const cv::Mat& depth) {
  io::BinaryWriter out;
  const std::string header = std::to_string(depth.cols) + "&" + std::to_string(depth.rows) + "&1&";
  for (char ch : header) out.write<char>(ch);
  for (int y = 0; y < depth.rows; ++y)
    for (int x = 0; x < depth.cols; ++x) out.write<float>(depth.at<float>(y, x));
  write_text_file(path, out.bytes());
}

void prepare_destination(const std::string& folder) {
  std::error_code ec;
  if (!fs::exists(folder, ec)) {
    const fs::path parent = fs::absolute(folder).parent_path();
    if (!fs::is_directory(parent, ec)) throw InvalidArgument("cannot write '" + folder + "': folder '" + parent.string() + "' does not exist");
    return;
  }
  if (!fs::is_directory(folder, ec)) throw InvalidArgument("cannot write '" + folder + "': it exists and is not a folder");
  if (!fs::is_empty(folder, ec) && !fs::exists(folder + "/scene.json", ec))
    throw InvalidArgument("cannot write '" + folder + "': it exists and is not a sharpmesh scene; choose another folder");
}

}  // namespace

void SceneOptions::check() const {
  if (views < 2 || views > 1000) throw InvalidArgument("--views must be in [2, 1000]");
  if (width < 16 || height < 16 || width > 8192 || height > 8192) throw InvalidArgument("image size must be in [16, 8192] pixels");
  if (!(arc > 0 && arc <= 360)) throw InvalidArgument("--arc must be in (0, 360] degrees");
  if (!(fov > 1 && fov < 170)) throw InvalidArgument("--fov must be in (1, 170) degrees");
  if (supersample < 1 || supersample > 8) throw InvalidArgument("--supersample must be in [1, 8]");
  if (!(image_noise >= 0 && image_noise <= 50)) throw InvalidArgument("--image-noise must be in [0, 50] grey levels");
  if (samples < 100 || samples > 100'000'000) throw InvalidArgument("--samples must be in [100, 1e8]");
  if (!(noise >= 0 && noise <= 10)) throw InvalidArgument("--noise must be in [0, 10] pixels");
  if (!(outliers >= 0 && outliers <= 0.9)) throw InvalidArgument("--outliers must be in [0, 0.9]");
  if (fused_step < 1 || fused_step > 64) throw InvalidArgument("--fused-step must be in [1, 64] pixels");
  if (!(fused_noise >= 0 && fused_noise <= 10)) throw InvalidArgument("--fused-noise must be in [0, 10] pixels");
  if (fatten < 0 || fatten > 32) throw InvalidArgument("--fatten must be in [0, 32] pixels");
}

SceneSummary make_scene(const std::string& folder, const SceneOptions& o, const Progress& progress) {
  o.check();
  prepare_destination(folder);
  const auto start = std::chrono::steady_clock::now();
  const std::string temp = folder + ".partial";
  std::error_code ec;
  fs::remove_all(temp, ec);
  for (const char* sub : {"", "/images", "/sparse", "/dense", "/depth"}) fs::create_directories(temp + sub);

  const SceneGeometry g = scene::building_scene();
  const detail::RayCaster caster(g.mesh);
  const scene::Texture texture(o.seed);
  StereoModel model;
  model.cameras = arc_cameras(o, g.building);
  std::vector<Rendering> renders;
  for (std::size_t v = 0; v < model.cameras.size(); ++v) {
    report_progress(progress, "render", static_cast<double>(v) / static_cast<double>(model.cameras.size()));
    renders.push_back(render(model.cameras[v], g, caster, texture, o, o.seed * 1000003 + v));
    const std::string name = model.cameras[v].image_name;
    if (!cv::imwrite(temp + "/images/" + name, renders.back().color)) throw InvalidInput("cannot write '" + temp + "/images/" + name + "'");
    write_depth(temp + "/depth/" + name + ".depth.bin", renders.back().depth);
  }
  report_progress(progress, "tracks", 0.0);
  std::vector<bool> outlier;
  make_tracks(g, model.cameras, caster, texture, o, model, outlier);
  report_progress(progress, "fused", 0.0);
  StereoModel fused;
  std::vector<Vec3> normals;
  make_fused(g, model.cameras, renders, o, fused, normals);

  SceneSummary s;
  s.ground_truth_faces = g.mesh.faces.size();
  s.tracks = model.tracks.size();
  s.outlier_tracks = static_cast<std::size_t>(std::count(outlier.begin(), outlier.end(), true));
  s.fused_points = fused.tracks.size();
  s.building_diagonal = g.building.diagonal();
  StereoModel inliers;
  inliers.cameras = model.cameras;
  for (std::size_t i = 0; i < model.tracks.size(); ++i)
    if (!outlier[i]) inliers.tracks.push_back(model.tracks[i]);
  s.reprojection = reprojection_error(inliers);
  const detail::TriangleDistance to_surface(g.mesh);
  for (const Track& t : inliers.tracks) s.mean_track_error += std::sqrt(to_surface.squared_distance(t.position));
  if (!inliers.tracks.empty()) s.mean_track_error /= static_cast<double>(inliers.tracks.size());

  write_colmap_model(temp + "/sparse", model);
  write_tracks_ply(temp + "/tracks.ply", model.tracks, outlier);
  write_colmap_fused(temp + "/dense/fused.ply", fused, normals);
  write_mesh(temp + "/ground_truth.ply", g.mesh);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json summary = {
      {"generator", "sharpmesh make-scene"},
      {"units", "metres, z up; pixels with the top-left pixel's centre at (0.5, 0.5)"},
      {"parameters",
       {{"views", o.views}, {"width", o.width}, {"height", o.height}, {"arc_degrees", o.arc}, {"fov_degrees", o.fov}, {"seed", o.seed},
        {"supersample", o.supersample}, {"image_noise", o.image_noise}, {"samples", o.samples}, {"noise_pixels", o.noise},
        {"outliers", o.outliers}, {"fused_step", o.fused_step}, {"fused_noise_pixels", o.fused_noise}, {"fatten_pixels", o.fatten}}},
      {"counts",
       {{"cameras", model.cameras.size()}, {"tracks", s.tracks}, {"outlier_tracks", s.outlier_tracks}, {"fused_points", s.fused_points},
        {"ground_truth_faces", s.ground_truth_faces}}},
      {"reprojection_pixels", {{"mean", s.reprojection.mean}, {"rms", s.reprojection.rms}, {"max", s.reprojection.max}}},
      {"mean_track_error", s.mean_track_error},
      {"building_diagonal", s.building_diagonal},
      {"seconds", s.seconds}};
  write_text_file(temp + "/scene.json", summary.dump(2) + "\n");
  if (fs::exists(folder, ec)) fs::remove_all(folder, ec);
  fs::rename(temp, folder, ec);
  if (ec) throw InvalidInput("cannot move '" + temp + "' to '" + folder + "': " + ec.message());
  report_progress(progress, "done", 1.0);
  return s;
}

}  // namespace sharpmesh
