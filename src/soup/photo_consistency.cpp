// Photo-consistency of a soup triangle (thesis 6.3.2): the triangle is
// sampled in 3D (a barycentric grid, dense enough for the reference view's
// pixels), which warps every view onto the reference view through the
// triangle's plane, i.e. its homography; the mean NCC against the reference
// decides.
#include <algorithm>
#include <cmath>

#include "core/grey_sampling.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {
namespace {

double projected_area(const std::array<Vec2, 3>& q) {
  return 0.5 * std::abs((q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[2][0] - q[0][0]) * (q[1][1] - q[0][1]));
}

}  // namespace

double triangle_ncc(const std::array<Vec3, 3>& triangle, const std::vector<std::uint32_t>& views,
                    const StereoModel& model, const std::vector<GreyImage>& images) {
  // Reference: the view where the projected triangle is largest.
  std::vector<std::uint32_t> usable;
  std::uint32_t reference = UINT32_MAX;
  double best_area = -1;
  for (std::uint32_t v : views) {
    if (v >= model.cameras.size() || v >= images.size()) continue;
    std::array<Vec2, 3> q;
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) inside = model.cameras[v].project(triangle[k], q[k]) && model.cameras[v].in_image(q[k]);
    if (!inside) continue;
    usable.push_back(v);
    const double area = projected_area(q);
    if (area > best_area) {
      best_area = area;
      reference = v;
    }
  }
  if (usable.size() < 2) return NAN;
  // About one sample per reference pixel: (m+1)(m+2)/2 grid points for area pixels.
  const int m = std::clamp(static_cast<int>(std::sqrt(2.0 * best_area)), 3, 24);
  std::vector<Vec3> points;
  for (int i = 0; i <= m; ++i)
    for (int j = 0; i + j <= m; ++j) {
      const double a = static_cast<double>(i) / m, b = static_cast<double>(j) / m;
      points.push_back((1 - a - b) * triangle[0] + a * triangle[1] + b * triangle[2]);
    }
  const auto patch = [&](std::uint32_t v, std::vector<double>& values) {
    values.clear();
    for (const Vec3& p : points) {
      Vec2 q;
      double value;
      if (!model.cameras[v].project(p, q) || !detail::sample_bilinear(images[v], q, value)) return false;
      values.push_back(value);
    }
    return true;
  };
  std::vector<double> ref, other;
  if (!patch(reference, ref)) return NAN;
  const double n = static_cast<double>(ref.size());
  double ref_mean = 0;
  for (double x : ref) ref_mean += x;
  ref_mean /= n;
  double ref_var = 0;
  for (double x : ref) ref_var += (x - ref_mean) * (x - ref_mean);
  if (ref_var < n * 1.0) return NAN;  // under one grey level of contrast: no texture to compare
  double sum = 0;
  int compared = 0;
  for (std::uint32_t v : usable) {
    if (v == reference || !patch(v, other)) continue;
    double mean = 0;
    for (double x : other) mean += x;
    mean /= n;
    double var = 0, cov = 0;
    for (std::size_t k = 0; k < other.size(); ++k) {
      var += (other[k] - mean) * (other[k] - mean);
      cov += (other[k] - mean) * (ref[k] - ref_mean);
    }
    sum += var > 0 ? cov / std::sqrt(var * ref_var) : 0.0;
    ++compared;
  }
  return compared > 0 ? sum / compared : NAN;
}

}  // namespace sharpmesh
