// An implicit surface cut away from the data (open scans, thin open models).
#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/implicit.h"

namespace sharpmesh {
namespace {

class RestrictedSurface final : public ImplicitSurface {
 public:
  RestrictedSurface(std::unique_ptr<ImplicitSurface> inner, std::unique_ptr<const detail::KnnIndex> index, double max_distance)
      : inner_(std::move(inner)), index_(std::move(index)), max_distance_(max_distance), id_(next_id()) {}

  double value(const Vec3& p) const override { return near_data(p) ? inner_->value(p) : 1.0; }
  Vec3 bounding_center() const override { return inner_->bounding_center(); }
  double bounding_radius() const override { return inner_->bounding_radius(); }
  Vec3 inside_point() const override { return inner_->inside_point(); }
  std::size_t sample_count() const override { return inner_->sample_count(); }

 private:
  /// Within max_distance of a data point? Called millions of times by the
  /// refinement, mostly at points close to the previous one (bisection along
  /// a segment): the distance d to the data is 1-Lipschitz, so the last
  /// query q decides whenever |p - q| < |d(q) - max_distance|.
  bool near_data(const Vec3& p) const {
    struct Last {
      std::uint64_t owner = 0;  // an id, not the address: a new surface may reuse a freed one's
      Vec3 point{0, 0, 0};
      double distance = 0;
    };
    thread_local Last last;
    thread_local std::vector<std::uint32_t> ids;
    thread_local std::vector<double> d2;
    if (last.owner == id_) {
      const double moved = distance(p, last.point);
      if (last.distance + moved <= max_distance_) return true;
      if (last.distance - moved > max_distance_) return false;
    }
    index_->nearest(p, 1, ids, d2);
    if (d2.empty()) return false;
    last = {id_, p, std::sqrt(d2[0])};
    return last.distance <= max_distance_;
  }

  static std::uint64_t next_id() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
  }

  std::unique_ptr<ImplicitSurface> inner_;
  std::unique_ptr<const detail::KnnIndex> index_;
  double max_distance_;
  std::uint64_t id_;
};

/// Whether the zero set has a sign change between two grid nodes that both
/// lie farther than max_distance from the data.
bool zero_set_leaves_points(const ImplicitSurface& surface, const detail::KnnIndex& index, double max_distance,
                            double domain_radius) {
  // Grid over the cube around the meshing domain, cells of about
  // max_distance (8 to 96 per side).
  const int n = std::clamp(static_cast<int>(std::ceil(2 * domain_radius / max_distance)), 8, 96);
  const double step = 2 * domain_radius / n;
  const Vec3 origin = surface.bounding_center() - Vec3{domain_radius, domain_radius, domain_radius};
  auto node = [&](int i, int j, int k) { return origin + Vec3{i * step, j * step, k * step}; };
  const auto at = [n](int i, int j, int k) { return (static_cast<std::size_t>(i) * (n + 1) + j) * (n + 1) + k; };
  std::vector<signed char> sign(static_cast<std::size_t>(n + 1) * (n + 1) * (n + 1));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) sign[at(i, j, k)] = surface.value(node(i, j, k)) < 0 ? -1 : 1;
  std::vector<std::uint32_t> ids;
  std::vector<double> d2;
  auto far = [&](const Vec3& p) {
    index.nearest(p, 1, ids, d2);
    return d2.empty() || d2[0] > max_distance * max_distance;
  };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        const signed char s = sign[at(i, j, k)];
        const bool crosses = (i < n && sign[at(i + 1, j, k)] != s) || (j < n && sign[at(i, j + 1, k)] != s) ||
                             (k < n && sign[at(i, j, k + 1)] != s);
        if (!crosses || !far(node(i, j, k))) continue;
        // Some neighbour across the sign change must be far too.
        if ((i < n && sign[at(i + 1, j, k)] != s && far(node(i + 1, j, k))) ||
            (j < n && sign[at(i, j + 1, k)] != s && far(node(i, j + 1, k))) ||
            (k < n && sign[at(i, j, k + 1)] != s && far(node(i, j, k + 1))))
          return true;
      }
  return false;
}

}  // namespace

Restriction restrict_to_points(std::unique_ptr<ImplicitSurface> surface, const std::vector<Vec3>& points, double max_distance,
                               double domain_radius) {
  if (!(max_distance > 0)) throw InvalidArgument("restriction distance must be positive");
  if (points.empty()) throw InvalidInput("cannot restrict a surface to an empty point set");
  auto index = std::make_unique<const detail::KnnIndex>(points);
  if (!zero_set_leaves_points(*surface, *index, max_distance, domain_radius)) return {std::move(surface), false};
  return {std::make_unique<RestrictedSurface>(std::move(surface), std::move(index), max_distance), true};
}

}  // namespace sharpmesh
