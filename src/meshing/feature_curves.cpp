// Polylines made fit for CGAL's feature protection (thesis 7.3.2 protects
// curves that meet only at junctions). Extracted polylines meet at their
// ends, but the ends of a loop can miss each other by a rounding error,
// which CGAL 5.5 takes for two corners and then walks the curve for ever; given polylines (CAD exports)
// often run through each other's corners as closed face outlines.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/fold_backs.h"
#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {
namespace {

/// Each point within `tolerance` of an earlier one (in `points`' order)
/// takes the coordinates of the earliest one within reach.
std::map<Vec3, Vec3> weld(const std::vector<Vec3>& points, double tolerance) {
  std::map<Vec3, Vec3> welded;
  if (points.empty()) return welded;
  const detail::KnnIndex index(points);
  std::vector<std::uint32_t> near;
  for (const Vec3& p : points) {
    if (welded.count(p)) continue;
    index.within(p, tolerance, near);
    Vec3 to = p;
    std::uint32_t first = static_cast<std::uint32_t>(points.size());
    for (std::uint32_t i : near)
      if (i < first && welded.count(points[i])) first = i, to = welded[points[i]];
    welded[p] = to;
  }
  return welded;
}

// CGAL's protection fails on overlapping curves: each one once, in either direction.
bool contains(const std::vector<Polyline>& lines, const Polyline& line) {
  const Polyline reversed(line.rbegin(), line.rend());
  return std::find(lines.begin(), lines.end(), line) != lines.end() || std::find(lines.begin(), lines.end(), reversed) != lines.end();
}

}  // namespace

std::vector<Polyline> curves_for_protection(const std::vector<Polyline>& polylines, double tolerance) {
  if (!(tolerance >= 0) || !std::isfinite(tolerance)) throw InvalidArgument("curves_for_protection: tolerance must be finite and non-negative");
  // Ends first, so that a loop's far end and a junction weld onto them.
  std::vector<Vec3> order;
  for (const Polyline& line : polylines)
    if (!line.empty()) order.push_back(line.front()), order.push_back(line.back());
  const std::size_t end_count = order.size();
  for (const Polyline& line : polylines)
    for (const Vec3& p : line) {
      for (double c : p)
        if (!std::isfinite(c)) throw InvalidInput("a feature polyline has a non-finite coordinate");
      order.push_back(p);
    }
  const std::map<Vec3, Vec3> weld_to = weld(order, tolerance);
  std::set<Vec3> ends;
  for (std::size_t i = 0; i < end_count; ++i) ends.insert(weld_to.at(order[i]));
  std::vector<Polyline> welded;
  for (const Polyline& line : polylines) {
    Polyline points;
    for (const Vec3& p : line) {
      const Vec3 q = weld_to.at(p);
      if (points.empty() || points.back() != q) points.push_back(q);
    }
    detail::remove_fold_backs(points, ends);  // given polylines can fold back too
    if (points.size() >= 2 && !contains(welded, points)) welded.push_back(std::move(points));
  }
  // Corners: open ends, and points where other than two segments meet.
  std::map<Vec3, int> degree;
  for (const Polyline& line : welded)
    for (std::size_t i = 0; i + 1 < line.size(); ++i) ++degree[line[i]], ++degree[line[i + 1]];
  for (const Polyline& line : welded)
    if (line.front() != line.back()) degree[line.front()] = degree[line.back()] = -1;
  auto is_corner = [&](const Vec3& p) { return degree[p] != 2; };

  std::vector<Polyline> pieces;
  for (Polyline line : welded) {
    if (line.front() == line.back()) {  // a loop: start it at a corner, if it has one
      const auto corner = std::find_if(line.begin(), line.end() - 1, is_corner);
      if (corner == line.end() - 1) {
        if (line.size() >= 4) pieces.push_back(std::move(line));
        continue;
      }
      Polyline rotated(corner, line.end() - 1);
      rotated.insert(rotated.end(), line.begin(), corner + 1);
      line = std::move(rotated);
    }
    Polyline piece{line.front()};
    for (std::size_t i = 1; i < line.size(); ++i) {
      piece.push_back(line[i]);
      if (i + 1 == line.size() || is_corner(line[i])) {
        if (piece.size() >= 2 && !(piece.size() < 4 && piece.front() == piece.back())) pieces.push_back(piece);
        piece = {line[i]};
      }
    }
  }
  std::vector<Polyline> out;
  for (Polyline& piece : pieces)
    if (!contains(out, piece)) out.push_back(std::move(piece));
  return out;
}

}  // namespace sharpmesh
