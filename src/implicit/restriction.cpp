// An implicit surface cut away from the data (open scans, thin open models).
#include "pointset/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/implicit.h"

namespace sharpmesh {
namespace {

class RestrictedSurface final : public ImplicitSurface {
 public:
  RestrictedSurface(std::unique_ptr<ImplicitSurface> inner, const std::vector<Vec3>& points, double max_distance)
      : inner_(std::move(inner)), index_(points), max_squared_(max_distance * max_distance) {}

  double value(const Vec3& p) const override {
    // Called millions of times by the refinement: no allocation per call.
    thread_local std::vector<std::uint32_t> ids;
    thread_local std::vector<double> d2;
    index_.nearest(p, 1, ids, d2);
    if (d2.empty() || d2[0] > max_squared_) return 1.0;
    return inner_->value(p);
  }
  Vec3 bounding_center() const override { return inner_->bounding_center(); }
  double bounding_radius() const override { return inner_->bounding_radius(); }
  Vec3 inside_point() const override { return inner_->inside_point(); }

 private:
  std::unique_ptr<ImplicitSurface> inner_;
  detail::KnnIndex index_;
  double max_squared_;
};

}  // namespace

std::unique_ptr<ImplicitSurface> restrict_to_points(std::unique_ptr<ImplicitSurface> surface, const std::vector<Vec3>& points,
                                                    double max_distance) {
  if (!(max_distance > 0)) throw InvalidArgument("restriction distance must be positive");
  if (points.empty()) throw InvalidInput("cannot restrict a surface to an empty point set");
  return std::make_unique<RestrictedSurface>(std::move(surface), points, max_distance);
}

}  // namespace sharpmesh
