// Normal estimation by PCA or jet fitting (App. A.7) and MST orientation
// (Hoppe et al. 1992; App. A.8).
#include <CGAL/Eigen_svd.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/mst_orient_normals.h>
#include <CGAL/pca_estimate_normals.h>


#include <limits>
#include <tuple>

#include "core/plane_fit.h"
#include "core/cgal_bridge.h"
#include "core/knn.h"
#include "sharpmesh/pointset.h"
#include "core/parallel.h"

namespace sharpmesh {
namespace {

using Record = std::tuple<detail::Point3, detail::Vector3, std::uint32_t>;
using PointMap = CGAL::Nth_of_tuple_property_map<0, Record>;
using NormalMap = CGAL::Nth_of_tuple_property_map<1, Record>;

std::vector<Record> make_records(const PointSet& points) {
  std::vector<Record> records;
  records.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    records.emplace_back(detail::to_cgal(points.points[i]),
                         points.has_normals() ? detail::to_cgal_vector(points.normals[i]) : detail::Vector3(0, 0, 0),
                         static_cast<std::uint32_t>(i));
  return records;
}

void check_k(int k, int minimum, std::size_t n, const char* what) {
  if (k < minimum)
    throw InvalidArgument(std::string(what) + ": k must be at least " + format_number(minimum) + " (got " + format_number(k) + ")");
  if (static_cast<std::size_t>(k) >= n)
    throw InvalidArgument(std::string(what) + ": k = " + format_number(k) + " needs more than k points, the set has " + format_number(n));
}

/// Checks shared by the estimates at given points; zero normals where there
/// were none. False when there is nothing to estimate.
bool prepare_normals_at(PointSet& points, const std::vector<std::uint32_t>& indices) {
  if (points.normals.size() != points.size()) points.normals.assign(points.size(), Vec3{0, 0, 0});
  if (indices.empty()) return false;
  for (std::uint32_t i : indices)
    if (i >= points.size()) throw InvalidArgument("normal estimation: point index out of range");
  return true;
}

}  // namespace

void NormalEstimationOptions::check(std::size_t n) const {
  check_k(k, method == NormalMethod::Jet ? 6 : 3, n, "normal estimation");
}

void NormalOrientationOptions::check(std::size_t n) const { check_k(k, 2, n, "normal orientation"); }

void estimate_normals(PointSet& points, const NormalEstimationOptions& options, const Progress& progress) {
  check_point_set(points, 4, "normal estimation");
  options.check(points.size());
  std::vector<Record> records = make_records(points);
  report_progress(progress, "normal estimation", 0.0);
  const auto np = CGAL::parameters::point_map(PointMap()).normal_map(NormalMap());
  if (options.method == NormalMethod::Jet)
    CGAL::jet_estimate_normals<CGAL::Parallel_if_available_tag>(records, static_cast<unsigned>(options.k), np);
  else
    CGAL::pca_estimate_normals<CGAL::Parallel_if_available_tag>(records, static_cast<unsigned>(options.k), np);
  report_progress(progress, "normal estimation", 1.0);
  points.normals.resize(points.size());
  for (const Record& r : records) {
    Vec3 n = detail::from_cgal(std::get<1>(r));
    const double length = norm(n);
    points.normals[std::get<2>(r)] = length > 0 && std::isfinite(length) ? (1.0 / length) * n : Vec3{0, 0, 0};
  }
}

void estimate_normals_at(PointSet& points, const std::vector<std::uint32_t>& indices, const NormalEstimationOptions& options) {
  check_point_set(points, 4, "normal estimation");
  options.check(points.size());
  if (!prepare_normals_at(points, indices)) return;
  using Monge = CGAL::Monge_via_jet_fitting<detail::Kernel, CGAL::Simple_cartesian<double>, CGAL::Eigen_svd>;
  const detail::KnnIndex index(points.points);
  detail::parallel_chunks(indices.size(), 256, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    std::vector<detail::Point3> local;
    std::vector<Eigen::Vector3d> plane_points;
    for (std::size_t m = begin; m != end; ++m) {
      const std::uint32_t i = indices[m];
      index.nearest(points.points[i], options.k + 1, ids, d2);
      Vec3 n{0, 0, 0};
      if (options.method == NormalMethod::Jet) {
        local.clear();
        for (std::uint32_t j : ids) local.push_back(detail::to_cgal(points.points[j]));
        Monge fit;
        n = detail::from_cgal(fit(local.begin(), local.end(), 2, 1).normal_direction());
      } else {
        plane_points.clear();
        for (std::uint32_t j : ids) plane_points.emplace_back(points.points[j][0], points.points[j][1], points.points[j][2]);
        detail::Plane plane;
        double rms = 0;
        if (detail::fit_plane(plane_points, plane, rms)) n = {plane.normal(0), plane.normal(1), plane.normal(2)};
      }
      const double length = norm(n);
      points.normals[i] = length > 0 && std::isfinite(length) ? (1.0 / length) * n : Vec3{0, 0, 0};
    }
  });
}

void ShiftedNormalOptions::check(std::size_t n) const {
  check_k(k, 6, n, "shifted normal estimation");
  check_k(candidates, 1, n, "shifted normal estimation (candidates)");
}

void estimate_shifted_normals_at(PointSet& points, const std::vector<std::uint32_t>& indices, const ShiftedNormalOptions& options) {
  check_point_set(points, 4, "normal estimation");
  options.check(points.size());
  if (!prepare_normals_at(points, indices)) return;
  const detail::KnnIndex index(points.points);
  const std::size_t kc = static_cast<std::size_t>(options.candidates);
  // The candidates of every point, then one plane per candidate (each fitted once).
  std::vector<std::uint32_t> candidates(indices.size() * kc);
  detail::parallel_chunks(indices.size(), 256, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    for (std::size_t m = begin; m != end; ++m) {
      index.nearest(points.points[indices[m]], options.candidates, ids, d2);
      std::copy(ids.begin(), ids.end(), candidates.begin() + static_cast<std::ptrdiff_t>(m * kc));
    }
  });
  std::vector<char> needed(points.size(), 0);
  for (std::uint32_t j : candidates) needed[j] = 1;
  std::vector<std::uint32_t> fitted;
  for (std::size_t j = 0; j < needed.size(); ++j)
    if (needed[j]) fitted.push_back(static_cast<std::uint32_t>(j));
  std::vector<detail::Plane> planes(points.size());
  std::vector<double> residual(points.size(), std::numeric_limits<double>::infinity());
  detail::parallel_chunks(fitted.size(), 256, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    std::vector<Eigen::Vector3d> local;
    for (std::size_t m = begin; m != end; ++m) {
      const std::uint32_t j = fitted[m];
      index.nearest(points.points[j], options.k, ids, d2);
      local.clear();
      for (std::uint32_t q : ids) local.emplace_back(points.points[q][0], points.points[q][1], points.points[q][2]);
      double rms = 0;
      if (detail::fit_plane(local, planes[j], rms)) residual[j] = rms;
    }
  });
  detail::parallel_for(indices.size(), [&](std::size_t m) {
    const Vec3& p = points.points[indices[m]];
    const Eigen::Vector3d x(p[0], p[1], p[2]);
    double best = std::numeric_limits<double>::infinity();
    Vec3 normal{0, 0, 0};
    for (std::size_t c = 0; c < kc; ++c) {  // nearest first: ties go to the nearest candidate
      const std::uint32_t j = candidates[m * kc + c];
      if (!std::isfinite(residual[j])) continue;
      const double score = residual[j] + std::abs(planes[j].normal.dot(x - planes[j].point));
      if (score < best) best = score, normal = {planes[j].normal(0), planes[j].normal(1), planes[j].normal(2)};
    }
    Vec3& n = points.normals[indices[m]];
    n = dot(normal, n) < 0 ? -1.0 * normal : normal;
  });
}

std::size_t orient_normals_mst(PointSet& points, const NormalOrientationOptions& options, const Progress& progress) {
  check_point_set(points, 4, "normal orientation");
  options.check(points.size());
  if (!points.has_normals()) throw InvalidArgument("normal orientation: the points have no normals to orient");
  std::vector<Record> records = make_records(points);
  report_progress(progress, "normal orientation", 0.0);
  const auto first_unoriented = CGAL::mst_orient_normals(records, static_cast<unsigned>(options.k),
                                                         CGAL::parameters::point_map(PointMap()).normal_map(NormalMap()));
  report_progress(progress, "normal orientation", 1.0);
  std::vector<bool> keep(points.size(), true);
  for (auto it = records.begin(); it != records.end(); ++it) {
    points.normals[std::get<2>(*it)] = detail::from_cgal(std::get<1>(*it));
    if (it >= first_unoriented) keep[std::get<2>(*it)] = false;
  }
  const std::size_t unoriented = static_cast<std::size_t>(records.end() - first_unoriented);
  if (options.remove_unoriented && unoriented > 0) points.keep_if(keep);
  return unoriented;
}

}  // namespace sharpmesh
