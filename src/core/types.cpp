#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sharpmesh/progress.h"
#include "sharpmesh/types.h"
#include "sharpmesh/errors.h"

namespace sharpmesh {

double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
double distance(const Vec3& a, const Vec3& b) { return std::sqrt(squared_distance(a, b)); }

double BoundingBox::diagonal() const { return distance(min, max); }
Vec3 BoundingBox::center() const { return 0.5 * (min + max); }

BoundingBox bounding_box(const std::vector<Vec3>& points) {
  BoundingBox box;
  if (points.empty()) return box;
  box.min = box.max = points.front();
  for (const Vec3& p : points)
    for (int i = 0; i < 3; ++i) {
      box.min[i] = std::min(box.min[i], p[i]);
      box.max[i] = std::max(box.max[i], p[i]);
    }
  return box;
}

BoundingBox robust_bounding_box(const std::vector<Vec3>& points, double fraction) {
  BoundingBox box;
  if (points.empty()) return box;
  const std::size_t last = points.size() - 1;
  const auto low = static_cast<std::size_t>(std::floor(fraction * static_cast<double>(last)));
  const std::size_t high = last - low;
  std::vector<double> values(points.size());
  for (int axis = 0; axis < 3; ++axis) {
    for (std::size_t i = 0; i < points.size(); ++i) values[i] = points[i][axis];
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(low), values.end());
    box.min[axis] = values[low];
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(high), values.end());
    box.max[axis] = values[high];
  }
  return box;
}

void PointSet::keep_if(const std::vector<bool>& keep) {
  if (keep.size() != points.size()) throw std::logic_error("PointSet::keep_if: flag count differs from point count");
  std::size_t out = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!keep[i]) continue;
    points[out] = points[i];
    if (has_normals()) normals[out] = normals[i];
    if (has_colors()) colors[out] = colors[i];
    ++out;
  }
  points.resize(out);
  if (has_normals()) normals.resize(out);
  if (has_colors()) colors.resize(out);
}

void report_progress(const Progress& progress, const std::string& stage, double fraction) {
  if (progress && !progress(stage, std::clamp(fraction, 0.0, 1.0))) throw Cancelled();
}

}  // namespace sharpmesh
