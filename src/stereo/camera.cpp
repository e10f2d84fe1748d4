// Pinhole camera geometry (thesis 3.2): projection m = A [R t] M, centres,
// viewing rays, quaternions, and the reprojection check of tracks.
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "sharpmesh/errors.h"
#include "sharpmesh/stereo.h"

namespace sharpmesh {

Mat3 identity3() { return {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}; }

Mat3 transpose(const Mat3& m) {
  Mat3 t{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t[i][j] = m[j][i];
  return t;
}

Mat3 operator*(const Mat3& a, const Mat3& b) {
  Mat3 c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) c[i][j] += a[i][k] * b[k][j];
  return c;
}

Vec3 operator*(const Mat3& m, const Vec3& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

Mat3 rotation_from_quaternion(double w, double x, double y, double z) {
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  if (!(n > 1e-12) || !std::isfinite(n)) throw InvalidInput("quaternion of zero or non-finite length");
  w /= n; x /= n; y /= n; z /= n;
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

std::array<double, 4> quaternion_from_rotation(const Mat3& r) {
  // Shepperd's method: pick the largest diagonal term for stability.
  const double trace = r[0][0] + r[1][1] + r[2][2];
  std::array<double, 4> q{};
  if (trace > 0) {
    const double s = 2 * std::sqrt(1 + trace);
    q = {0.25 * s, (r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s};
  } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
    const double s = 2 * std::sqrt(1 + r[0][0] - r[1][1] - r[2][2]);
    q = {(r[2][1] - r[1][2]) / s, 0.25 * s, (r[0][1] + r[1][0]) / s, (r[0][2] + r[2][0]) / s};
  } else if (r[1][1] > r[2][2]) {
    const double s = 2 * std::sqrt(1 + r[1][1] - r[0][0] - r[2][2]);
    q = {(r[0][2] - r[2][0]) / s, (r[0][1] + r[1][0]) / s, 0.25 * s, (r[1][2] + r[2][1]) / s};
  } else {
    const double s = 2 * std::sqrt(1 + r[2][2] - r[0][0] - r[1][1]);
    q = {(r[1][0] - r[0][1]) / s, (r[0][2] + r[2][0]) / s, (r[1][2] + r[2][1]) / s, 0.25 * s};
  }
  if (q[0] < 0)
    for (double& c : q) c = -c;
  return q;
}

Vec3 Camera::center() const { return -1.0 * (transpose(rotation) * translation); }

Vec3 Camera::to_camera(const Vec3& world) const { return rotation * world + translation; }

bool Camera::project(const Vec3& world, Vec2& pixel) const {
  const Vec3 c = to_camera(world);
  if (!(c[2] > 0)) return false;
  pixel = {fx * c[0] / c[2] + cx, fy * c[1] / c[2] + cy};
  return true;
}

bool Camera::in_image(const Vec2& pixel) const {
  return pixel[0] >= 0 && pixel[1] >= 0 && pixel[0] < width && pixel[1] < height;
}

Vec3 Camera::viewing_ray(const Vec2& pixel) const {
  const Vec3 local{(pixel[0] - cx) / fx, (pixel[1] - cy) / fy, 1.0};
  const Vec3 world = transpose(rotation) * local;
  return (1.0 / norm(world)) * world;
}

Vec3 Camera::unproject(const Vec2& pixel, double depth_value) const {
  const Vec3 local{depth_value * (pixel[0] - cx) / fx, depth_value * (pixel[1] - cy) / fy, depth_value};
  return transpose(rotation) * (local - translation);
}

void Camera::validate(const std::string& where) const {
  auto fail = [&](const std::string& what) { return InvalidInput(where + ": " + what); };
  if (width <= 0 || height <= 0) throw fail("image size " + std::to_string(width) + "x" + std::to_string(height) + " is not positive");
  if (!(fx > 0) || !(fy > 0) || !std::isfinite(fx) || !std::isfinite(fy)) throw fail("focal length must be positive and finite");
  if (!std::isfinite(cx) || !std::isfinite(cy)) throw fail("principal point is not finite");
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(translation[i])) throw fail("translation is not finite");
    for (int j = 0; j < 3; ++j)
      if (!std::isfinite(rotation[i][j])) throw fail("rotation is not finite");
  }
  const Mat3 rrt = rotation * transpose(rotation);
  double error = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) error = std::max(error, std::abs(rrt[i][j] - (i == j ? 1.0 : 0.0)));
  const double det = rotation[0][0] * (rotation[1][1] * rotation[2][2] - rotation[1][2] * rotation[2][1]) -
                     rotation[0][1] * (rotation[1][0] * rotation[2][2] - rotation[1][2] * rotation[2][0]) +
                     rotation[0][2] * (rotation[1][0] * rotation[2][1] - rotation[1][1] * rotation[2][0]);
  if (error > 1e-4 || det < 0) throw fail("R is not a rotation matrix");
}

void StereoModel::validate(const std::string& where) const {
  for (std::size_t i = 0; i < cameras.size(); ++i) cameras[i].validate(where + ": camera " + std::to_string(i) + " (" + cameras[i].image_name + ")");
  std::unordered_set<std::uint32_t> seen;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const Track& t = tracks[i];
    const std::string at = where + ": track " + std::to_string(i);
    for (double c : t.position)
      if (!std::isfinite(c)) throw InvalidInput(at + ": non-finite coordinate");
    if (!t.pixels.empty() && t.pixels.size() != t.views.size()) throw InvalidInput(at + ": pixel count differs from view count");
    seen.clear();
    for (std::uint32_t v : t.views) {
      if (v >= cameras.size())
        throw InvalidInput(at + ": refers to view " + format_number(v) + " but there are " + format_number(cameras.size()) + " cameras");
      if (!seen.insert(v).second) throw InvalidInput(at + ": lists view " + format_number(v) + " twice");
    }
  }
}

ReprojectionStats reprojection_error(const StereoModel& model) {
  ReprojectionStats stats;
  double sum = 0, sum2 = 0;
  for (const Track& t : model.tracks)
    for (std::size_t k = 0; k < t.pixels.size(); ++k) {
      Vec2 p;
      double e = std::numeric_limits<double>::infinity();
      if (model.cameras[t.views[k]].project(t.position, p)) e = std::hypot(p[0] - t.pixels[k][0], p[1] - t.pixels[k][1]);
      ++stats.observations;
      sum += e;
      sum2 += e * e;
      stats.max = std::max(stats.max, e);
    }
  if (stats.observations > 0) {
    stats.mean = sum / static_cast<double>(stats.observations);
    stats.rms = std::sqrt(sum2 / static_cast<double>(stats.observations));
  }
  return stats;
}

}  // namespace sharpmesh
