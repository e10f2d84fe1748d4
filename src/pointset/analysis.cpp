// Point-set checks and average spacing (thesis App. A.3, 7.3.2).

#include <cmath>

#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"
#include "core/parallel.h"

namespace sharpmesh {

void check_point_set(const PointSet& points, std::size_t min_points, const char* what) {
  if (points.size() < min_points)
    throw InvalidInput(std::string(what) + " needs at least " + format_number(min_points) + " points, the set has " +
                       format_number(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points.points[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw InvalidInput("point " + format_number(i) + " has a non-finite coordinate (NaN or infinity)");
  }
  const double diagonal = bounding_box(points.points).diagonal();
  if (!(diagonal > 0) || !std::isfinite(diagonal))
    throw InvalidInput(std::string(what) + ": all points are at the same location (or the extent overflows)");
}

double average_spacing(const PointSet& points, int k, const Progress& progress) {
  if (k < 1) throw InvalidArgument("average spacing: k must be at least 1 (got " + format_number(k) + ")");
  check_point_set(points, static_cast<std::size_t>(k) + 1, "average spacing");
  // The thesis's avg is the mean distance to the k nearest *other* points.
  // CGAL 5.5's compute_average_spacing counts the point itself among the k
  // (its result is k/(k+1) of this), so the kd-tree is queried directly.
  report_progress(progress, "average spacing", 0.0);
  const double spacing = detail::average_spacing(points.points, detail::KnnIndex(points.points), k);
  report_progress(progress, "average spacing", 1.0);
  return spacing;
}

namespace detail {

std::vector<double> local_spacings(const std::vector<Vec3>& points, const KnnIndex& index, int k) {
  std::vector<double> mean(points.size());
  detail::parallel_chunks(points.size(), 2048, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    for (std::size_t i = begin; i != end; ++i) {
      index.nearest(points[i], k + 1, ids, d2);
      double sum = 0;
      int count = 0;
      for (std::size_t j = 0; j < ids.size() && count < k; ++j) {
        if (ids[j] == i) continue;
        sum += std::sqrt(d2[j]);
        ++count;
      }
      mean[i] = count > 0 ? sum / count : 0.0;
    }
  });
  return mean;
}

double average_spacing(const std::vector<Vec3>& points, const KnnIndex& index, int k) {
  double total = 0;  // summed in order: independent of the thread count
  for (double m : local_spacings(points, index, k)) total += m;
  return total / static_cast<double>(points.size());
}

}  // namespace detail

}  // namespace sharpmesh
