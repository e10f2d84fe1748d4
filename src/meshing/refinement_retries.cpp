// The retry policy around Mesh_3's refinement (refinement_retries.h).
#include "meshing/refinement_retries.h"
#include "meshing/uncovered.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

#include "sharpmesh/errors.h"

namespace sharpmesh::detail {
namespace {

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = dot(ab, ab);
  const double t = length2 > 0 ? std::clamp(dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return norm(p - (a + t * ab));
}

/// The whole of a polyline as an unprotected stretch.
UncoveredGap refused(const Polyline& line) {
  UncoveredGap gap = whole_polyline_gap(line);
  gap.refused_by_mesher = true;
  return gap;
}

}  // namespace

bool failure_point(const std::string& message, Vec3& p) {
  const std::size_t open = message.find('(');
  if (open == std::string::npos) return false;
  double w = 0;
  return std::sscanf(message.c_str() + open, "(%lf %lf %lf %lf)", &p[0], &p[1], &p[2], &w) == 4;
}

// Every polyline near p goes: cutting out only the stretch near p leaves
// two new ends there, and dropping only the nearest polyline leaves its
// neighbours, next to which the next refinement fails the same way.
bool drop_protection_near(std::vector<Polyline>& polylines, const Vec3& p, double reach, std::vector<UncoveredGap>& dropped) {
  std::vector<Polyline> kept;
  for (Polyline& line : polylines) {
    bool near = false;
    for (std::size_t i = 0; i + 1 < line.size() && !near; ++i) near = distance_to_segment(p, line[i], line[i + 1]) <= reach;
    if (near) dropped.push_back(refused(line));
    else kept.push_back(std::move(line));
  }
  const bool any = kept.size() < polylines.size();
  polylines = std::move(kept);
  return any;
}

bool runaway_spot(const SurfaceMesh& mesh, double edge_length, Vec3& spot) {
  std::map<std::array<long, 3>, std::pair<Vec3, std::size_t>> cells;
  for (const Triangle& t : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = mesh.vertices[t[k]];
      const Vec3& b = mesh.vertices[t[(k + 1) % 3]];
      if (distance(a, b) >= 0.01 * edge_length) continue;
      const std::array<long, 3> key{static_cast<long>(std::floor(a[0] / edge_length)), static_cast<long>(std::floor(a[1] / edge_length)),
                                    static_cast<long>(std::floor(a[2] / edge_length))};
      auto& cell = cells[key];
      cell.first = cell.first + a;
      ++cell.second;
    }
  std::size_t best = 0;
  for (const auto& [key, cell] : cells)
    if (cell.second > best) best = cell.second, spot = (1.0 / static_cast<double>(cell.second)) * cell.first;
  return best > 0;
}

std::vector<Vec3> pinched_vertices(const SurfaceMesh& mesh) {
  std::map<std::array<double, 3>, int> count;
  for (const Vec3& v : mesh.vertices) ++count[{v[0], v[1], v[2]}];
  std::vector<Vec3> out;
  for (const auto& [p, n] : count)
    if (n > 1) out.push_back({p[0], p[1], p[2]});
  return out;
}

ImplicitMeshingResult refine_with_retries(const ImplicitMeshingOptions& options, const RefineOnce& refine,
                                          const Progress& progress, int max_retries) {
  ImplicitMeshingOptions attempt = options;
  std::vector<UncoveredGap> dropped;
  std::size_t runaway_stopped_at = 0;
  if (options.features.drop_on_thin_parts)
    drop_protection_on_thin_parts(attempt.features.polylines, options.thin_points, options.thin_thickness,
                                  options.features.ball_radius, dropped);
  drop_close_polylines(attempt.features.polylines, options.features.min_separation, dropped);
  const double reach = 2 * (options.features.max_ball_radius > 0 ? options.features.max_ball_radius : 3 * options.features.ball_radius);
  auto drop_all = [&] {
    for (const Polyline& line : attempt.features.polylines) dropped.push_back(refused(line));
    attempt.features.polylines.clear();
  };
  std::vector<Vec3> stalled;
  bool rescue_stalled = true;
  bool protection_stopped = false;
  for (int retries = 0;; ++retries) {
    const bool last = retries >= max_retries || attempt.features.polylines.empty();
    RefinementRun run = refine(attempt, rescue_stalled, stalled);
    if (run.status == RefinementRun::Status::ProtectionStopped) {
      protection_stopped = true;
      drop_all();
      report_progress(progress, "refinement (again, without protection: it ran past its query budget)", 0.0);
      continue;
    }
    if (run.status == RefinementRun::Status::Finished) {
      ImplicitMeshingResult& result = run.result;
      Vec3 spot;
      if (run.runaway_pile) spot = *run.runaway_pile;
      if (result.refinement_runaway && !last &&
          (run.runaway_pile || runaway_spot(result.mesh, options.criteria.edge_length, spot))) {
        runaway_stopped_at = result.runaway_stopped_at;
        if (!drop_protection_near(attempt.features.polylines, spot, reach, dropped)) drop_all();
        report_progress(progress, "refinement (again, without the features it ran away next to)", 0.0);
        continue;
      }
      // A stalled manifold repair leaves non-manifold vertices: the
      // protection near them goes, and the refinement runs again.
      if (result.refinement_stalled && !last) {
        bool any = false;
        for (const Vec3& pinch : pinched_vertices(result.mesh)) any |= drop_protection_near(attempt.features.polylines, pinch, reach, dropped);
        if (any) {
          report_progress(progress, "refinement (again, without the features it stalled next to)", 0.0);
          continue;
        }
      }
      result.mesher_retries = static_cast<std::size_t>(retries);
      result.protection_stopped = protection_stopped;
      if (!result.refinement_runaway) result.runaway_stopped_at = runaway_stopped_at;
      result.uncovered.insert(result.uncovered.end(), dropped.begin(), dropped.end());
      return std::move(result);
    }
    const std::string& what = run.cgal_message;
    if (last) {
      const std::string line = what.substr(0, what.find('\n'));
      throw NumericalFailure("Delaunay refinement failed inside CGAL Mesh_3 (" + line + "); try another delta");
    }
    Vec3 where;
    if (failure_point(what, where) && drop_protection_near(attempt.features.polylines, where, reach, dropped)) {
      report_progress(progress, "refinement (again, without the features CGAL failed next to)", 0.0);
      continue;
    }
    // No spot named ("A facet is not in conflict with its refinement
    // point!"): the first suspects are the points where the function is too
    // flat for Newton's search; they go back to being unprotected, which
    // keeps the rest of the protection (dropping all of it gives PIF's
    // rounded edges).
    if (rescue_stalled && !stalled.empty()) {
      rescue_stalled = false;
      report_progress(progress, "refinement (again, without the features where the function is flat)", 0.0);
      continue;
    }
    drop_all();
    report_progress(progress, "refinement (again, without protection)", 0.0);
  }
}

}  // namespace sharpmesh::detail
