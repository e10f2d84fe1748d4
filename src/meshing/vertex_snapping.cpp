// Vertex snapping, beyond the thesis: the gap of thesis 7.5 (Fig. 7.18)
// where the protecting balls cannot close it. Around an acute corner the
// balls of the edges meeting there must not intersect each other, so they
// stay smaller than the Poisson surface's rounding (couplingdown 50k: a
// spike corner 1.5 spacings off the implicit surface, its ball 0.9
// spacings), and the corner's vertex is not in the surface mesh; on the top
// of a wall 1.3 spacings thick the function itself is eroded (its top edge
// 1.5 spacings below the data). Mesh vertices are moved onto the corners
// and the data points that the mesh misses, and off-data vertices (bridges
// over slots, dents into walls thinner than the sampling) onto the data.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include <CGAL/intersections.h>
#include <CGAL/squared_distance_3.h>

#include "core/triangle_distance.h"
#include "core/cgal_bridge.h"
#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {
namespace {

// A move may not leave a facet with an angle below this (degrees) unless it
// had one already: the refinement's facets have 25 degrees and more.
constexpr double kMinAngle = 10;
// Tangent planes a vertex away from the data is measured against.
constexpr int kPlanes = 8;

struct Target {
  Vec3 position;
  double offset;
};

// Moves of single vertices that keep every facet on its side and no angle
// below kMinAngle (unless the facet had one already).
class VertexMover {
 public:
  explicit VertexMover(SurfaceMesh& mesh) : mesh_(mesh), faces_of_(mesh.vertices.size()), moved_(mesh.vertices.size(), 0) {
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        faces_of_[mesh.faces[f][k]].push_back(f);
        longest_edge_ = std::max(longest_edge_, norm(mesh.vertices[mesh.faces[f][k]] - mesh.vertices[mesh.faces[f][(k + 1) % 3]]));
      }
  }
  /// `accept` (may be empty) has the last word on a move that passes the facet checks.
  bool try_move(std::uint32_t v, const Vec3& to, const std::function<bool(std::uint32_t, const Vec3&)>& accept = {}) {
    if (moved_[v] || faces_of_[v].empty()) return false;
    for (std::uint32_t f : faces_of_[v]) {
      const Triangle& t = mesh_.faces[f];
      if (!(dot(normal(t, v, mesh_.vertices[v]), normal(t, v, to)) > 0)) return false;
      const double angle_after = min_angle(t, v, to);
      if (angle_after < kMinAngle && angle_after < min_angle(t, v, mesh_.vertices[v])) return false;
    }
    if (accept && !accept(v, to)) return false;
    mesh_.vertices[v] = to;
    moved_[v] = 1;
    return true;
  }

 private:
  Vec3 at(const Triangle& t, int k, std::uint32_t v, const Vec3& p) const { return t[k] == v ? p : mesh_.vertices[t[k]]; }
  Vec3 normal(const Triangle& t, std::uint32_t v, const Vec3& p) const {
    return cross(at(t, 1, v, p) - at(t, 0, v, p), at(t, 2, v, p) - at(t, 0, v, p));
  }
  // Smallest angle of facet t with vertex v at p, in degrees.
  double min_angle(const Triangle& t, std::uint32_t v, const Vec3& p) const {
    double smallest = 180;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = at(t, (k + 1) % 3, v, p) - at(t, k, v, p), b = at(t, (k + 2) % 3, v, p) - at(t, k, v, p);
      const double n = norm(a) * norm(b);
      smallest = std::min(smallest, n > 0 ? std::acos(std::clamp(dot(a, b) / n, -1.0, 1.0)) * 180 / M_PI : 0.0);
    }
    return smallest;
  }


 public:
  const SurfaceMesh& mesh() const { return mesh_; }
  const std::vector<std::uint32_t>& faces_of(std::uint32_t v) const { return faces_of_[v]; }
  /// Distance from q to the facets of v, with v at p.
  double distance_to_ring(std::uint32_t v, const Vec3& p, const Vec3& q) const {
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t f : faces_of_[v]) {
      const Triangle& t = mesh_.faces[f];
      const detail::Kernel::Triangle_3 triangle(detail::to_cgal(at(t, 0, v, p)), detail::to_cgal(at(t, 1, v, p)), detail::to_cgal(at(t, 2, v, p)));
      if (!triangle.is_degenerate()) {
        best = std::min(best, std::sqrt(CGAL::squared_distance(detail::to_cgal(q), triangle)));
        continue;
      }
      for (int k = 0; k < 3; ++k) best = std::min(best, norm(q - at(t, k, v, p)));
    }
    return best;
  }

  /// Whether v's facets, with v at p, meet no other facet except at shared
  /// vertices and edges. `original` indexes the vertices before any move;
  /// none moves farther than `max_move`, so a facet that meets them had its
  /// vertices within reach + longest edge + 3 max_move of v (the edge may
  /// have grown by 2 max_move, the vertex moved by one).
  bool keeps_facets_apart(std::uint32_t v, const Vec3& p, const detail::KnnIndex& original, double max_move) const {
    const Vec3 from = mesh_.vertices[v];
    double reach = 0;
    for (std::uint32_t f : faces_of_[v])
      for (std::uint32_t w : mesh_.faces[f]) reach = std::max({reach, norm(mesh_.vertices[w] - from), norm(mesh_.vertices[w] - p)});
    std::vector<std::uint32_t> near, more;
    const double radius = reach + longest_edge_ + 3 * max_move;
    original.within(from, radius, near);
    original.within(p, radius, more);
    near.insert(near.end(), more.begin(), more.end());
    std::vector<std::uint32_t> faces;
    for (std::uint32_t w : near) faces.insert(faces.end(), faces_of_[w].begin(), faces_of_[w].end());
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    for (std::uint32_t f : faces_of_[v])
      for (std::uint32_t g : faces)
        if (g != f && facets_meet(f, g, v, p)) return false;
    return true;
  }

  /// Whether facets f and g (v at p) meet beyond their shared vertices and
  /// edge, as Polygon_mesh_processing::self_intersections decides it (CGAL
  /// 5.5 tests whole meshes only, and orienting a patch of facets as a soup
  /// splits its pinched vertices, whose facets then seem to intersect).
  bool facets_meet(std::uint32_t f, std::uint32_t g, std::uint32_t v, const Vec3& p) const {
    const Triangle& s = mesh_.faces[f];
    const Triangle& t = mesh_.faces[g];
    auto point = [&](std::uint32_t w) { return detail::to_cgal(w == v ? p : mesh_.vertices[w]); };
    int shared = 0, si[3], ti[3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (s[i] == t[j]) si[shared] = i, ti[shared] = j, ++shared;
    using K = detail::Kernel;
    if (shared == 0) {
      const K::Triangle_3 a(point(s[0]), point(s[1]), point(s[2])), b(point(t[0]), point(t[1]), point(t[2]));
      return CGAL::do_intersect(a, b) || (!a.is_degenerate() && !b.is_degenerate() && nearly_touch(a, b, -1, -1));
    }
    if (shared == 1) {  // each one's opposite edge against the other
      const K::Triangle_3 a(point(s[0]), point(s[1]), point(s[2])), b(point(t[0]), point(t[1]), point(t[2]));
      if (a.is_degenerate() || b.is_degenerate()) return false;
      const K::Segment_3 a_edge(point(s[(si[0] + 1) % 3]), point(s[(si[0] + 2) % 3])), b_edge(point(t[(ti[0] + 1) % 3]), point(t[(ti[0] + 2) % 3]));
      return CGAL::do_intersect(a_edge, b) || CGAL::do_intersect(b_edge, a) || nearly_touch(a, b, si[0], ti[0]);
    }
    if (shared == 2) {  // folded onto each other
      const K::Point_3 e0 = point(s[si[0]]), e1 = point(s[si[1]]), a = point(s[3 - si[0] - si[1]]), b = point(t[3 - ti[0] - ti[1]]);
      return CGAL::coplanar(e0, e1, a, b) && CGAL::coplanar_orientation(e0, e1, a, b) == CGAL::POSITIVE;
    }
    return false;
  }

  /// Whether a vertex of one facet (other than the shared ones, `skip_a` of
  /// a and `skip_b` of b, -1 for none) lies within a millionth of the
  /// longest edge of the other facet: exactly apart, but touching for every
  /// tool that tests with a tolerance once written (a scan's points on one
  /// plane snap a facet flat onto a vertex already on that plane).
  bool nearly_touch(const detail::Kernel::Triangle_3& a, const detail::Kernel::Triangle_3& b, int skip_a, int skip_b) const {
    const double tolerance = 1e-6 * longest_edge_;
    const double tolerance2 = tolerance * tolerance;
    for (int k = 0; k < 3; ++k) {
      if (k != skip_a && CGAL::to_double(CGAL::squared_distance(a.vertex(k), b)) < tolerance2) return true;
      if (k != skip_b && CGAL::to_double(CGAL::squared_distance(b.vertex(k), a)) < tolerance2) return true;
    }
    return false;
  }

  /// Integral over v's facets (v at p) of the distance to the nearest data
  /// point beyond `free`, capped at `cap`: the mesh area away from the data.
  double area_off_data(std::uint32_t v, const Vec3& p, const detail::KnnIndex& data, double free, double cap) const {
    constexpr int kSteps = 6;  // 21 samples per facet
    std::vector<std::uint32_t> ids;
    std::vector<double> d2;
    double integral = 0;
    for (std::uint32_t f : faces_of_[v]) {
      const Triangle& t = mesh_.faces[f];
      const Vec3 a = at(t, 0, v, p), b = at(t, 1, v, p), c = at(t, 2, v, p);
      double sum = 0;
      int count = 0;
      for (int i = 0; i < kSteps; ++i)
        for (int j = 0; i + j < kSteps; ++j, ++count) {
          data.nearest(a + ((i + 1.0 / 3) / kSteps) * (b - a) + ((j + 1.0 / 3) / kSteps) * (c - a), 1, ids, d2);
          sum += ids.empty() ? cap - free : std::clamp(std::sqrt(d2[0]) - free, 0.0, cap - free);
        }
      integral += 0.5 * norm(cross(b - a, c - a)) * sum / count;
    }
    return integral;
  }

 private:
  SurfaceMesh& mesh_;
  std::vector<std::vector<std::uint32_t>> faces_of_;
  std::vector<char> moved_;
  double longest_edge_ = 0;  // before any move
};

// Worst first, each target takes the nearest of its four nearest vertices
// (positions before any move) that can move onto it.
std::size_t snap_vertices(VertexMover& mover, const detail::KnnIndex& original_vertices, std::vector<Target> targets, double max_move,
                          const std::function<bool(std::uint32_t, const Vec3&)>& accept = {}) {
  std::stable_sort(targets.begin(), targets.end(), [](const Target& a, const Target& b) { return a.offset > b.offset; });
  std::vector<std::uint32_t> ids;
  std::vector<double> d2;
  std::size_t count = 0;
  for (const Target& target : targets) {
    original_vertices.nearest(target.position, 4, ids, d2);
    for (std::size_t k = 0; k < ids.size() && std::sqrt(d2[k]) <= max_move; ++k)
      if (mover.try_move(ids[k], target.position, accept)) {
        ++count;
        break;
      }
  }
  return count;
}

// The corners and the supported off points farther than their `present`
// distance from the mesh as it is now.
void find_targets(const SurfaceMesh& mesh, const std::vector<Vec3>& corners, const std::vector<Vec3>& points, const SnappingOptions& o,
                  std::vector<Target>& corner_targets, std::vector<Target>& data_targets) {
  corner_targets.clear();
  data_targets.clear();
  const detail::TriangleDistance surface(mesh);
  const std::vector<double> corner_offsets = surface.distances(corners);
  for (std::size_t c = 0; c < corners.size(); ++c)
    if (corner_offsets[c] > o.corner_present && corner_offsets[c] <= o.max_move) corner_targets.push_back({corners[c], corner_offsets[c]});
  if (!o.points_are_targets) return;
  const std::vector<double> offsets = surface.distances(points);
  std::vector<Vec3> off_points;
  std::vector<double> off_offsets;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (offsets[i] > 0.5 * o.data_present) off_points.push_back(points[i]), off_offsets.push_back(offsets[i]);
  if (off_points.empty()) return;
  // An off point needs off neighbours: a lone outlier pulls no vertex.
  const detail::KnnIndex off_index(off_points);
  std::vector<std::uint32_t> ids;
  for (std::size_t k = 0; k < off_points.size(); ++k) {
    if (off_offsets[k] <= o.data_present || off_offsets[k] > o.max_move) continue;
    off_index.within(off_points[k], o.support_radius, ids);
    if (ids.size() >= o.min_support + 1) data_targets.push_back({off_points[k], off_offsets[k]});
  }
}

// Each vertex farther than data_present from the tangent disks (radius one
// spacing) of its kPlanes nearest points moves onto the nearest disk, worst
// first, if `accept` agrees. One disk is not enough: a vertex on a face
// next to a wall can be nearest to a point of the wall; and a plane must
// end: a slot's wall, extended, passes through its floor's corner.
std::size_t snap_off_data_vertices(VertexMover& mover, const detail::KnnIndex& data, const std::vector<Vec3>& points,
                                   const std::vector<Vec3>& normals,
                                   const SnappingOptions& o, const std::function<bool(std::uint32_t, const Vec3&)>& accept) {
  struct Move {
    std::uint32_t vertex;
    Vec3 to;
    double offset;
  };
  std::vector<Move> moves;
  std::vector<std::uint32_t> ids;
  std::vector<double> d2;
  const std::vector<Vec3>& vertices = mover.mesh().vertices;
  const double radius = o.average_spacing > 0 ? o.average_spacing : o.data_present;
  for (std::uint32_t v = 0; v < vertices.size(); ++v) {
    if (mover.faces_of(v).empty()) continue;
    data.nearest(vertices[v], kPlanes, ids, d2);
    if (ids.empty() || std::sqrt(d2[0]) <= o.data_present) continue;
    double offset = std::numeric_limits<double>::infinity();
    Vec3 foot{};
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const double length = norm(normals[ids[k]]);
      if (!(length > 0)) continue;
      const Vec3 n = (1 / length) * normals[ids[k]];
      const Vec3 from_point = vertices[v] - points[ids[k]];
      const Vec3 along = from_point - dot(from_point, n) * n;
      const double reach = norm(along), beyond = std::max(0.0, reach - radius);
      const double off = std::hypot(dot(from_point, n), beyond);
      if (off < offset) offset = off, foot = points[ids[k]] + (beyond > 0 ? radius / reach : 1.0) * along;
    }
    if (offset > o.data_present && offset <= o.max_move) moves.push_back({v, foot, offset});
  }
  std::stable_sort(moves.begin(), moves.end(), [](const Move& a, const Move& b) { return a.offset > b.offset; });
  std::size_t count = 0;
  for (const Move& move : moves) count += mover.try_move(move.vertex, move.to, accept);
  return count;
}

}  // namespace

std::size_t undo_intersecting_moves(SurfaceMesh& mesh, const std::vector<Vec3>& before) {
  if (before.size() != mesh.vertices.size()) throw InvalidArgument("undo_intersecting_moves: vertex counts differ");
  std::size_t undone = 0;
  auto restore = [&](std::uint32_t v) {
    if (mesh.vertices[v] == before[v]) return false;
    mesh.vertices[v] = before[v];
    ++undone;
    return true;
  };
  for (int round = 0;; ++round) {
    bool restored = false;
    for (const auto& [a, b] : self_intersecting_faces(mesh))
      for (std::uint32_t f : {a, b})
        for (std::uint32_t v : mesh.faces[f]) restored = restore(v) || restored;
    if (!restored) break;
    if (round == 7) {
      for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) restore(v);
      break;
    }
  }
  return undone;
}

SnappingStats snap_to_corners_and_data(SurfaceMesh& mesh, const std::vector<Vec3>& corners, const std::vector<Vec3>& points,
                                       const SnappingOptions& o) {
  for (double d : {o.max_move, o.corner_present, o.data_present, o.support_radius, o.average_spacing})
    if (!(d >= 0) || !std::isfinite(d)) throw InvalidArgument("snapping: distances must be finite and non-negative");
  if (!o.point_normals.empty() && o.point_normals.size() != points.size())
    throw InvalidArgument("snapping: " + std::to_string(o.point_normals.size()) + " normals for " + std::to_string(points.size()) + " points");
  SnappingStats stats;
  if (mesh.faces.empty() || !(o.max_move > 0)) return stats;
  const std::vector<Vec3> before = mesh.vertices;
  const detail::KnnIndex original_vertices(before);
  VertexMover mover(mesh);
  // A corner move must not take v's facets farther from the data around them.
  std::unique_ptr<detail::KnnIndex> data;
  const bool vertices_to_planes = !o.point_normals.empty();
  if (!points.empty() && (!corners.empty() || vertices_to_planes)) data = std::make_unique<detail::KnnIndex>(points);
  std::vector<std::uint32_t> near, near_target;
  auto fits_data_no_worse = [&](std::uint32_t v, const Vec3& to) {
    if (!data) return true;
    const Vec3 from = mover.mesh().vertices[v];
    double reach = 0;  // of v's facets from v, before and after
    for (std::uint32_t f : mover.faces_of(v))
      for (std::uint32_t w : mover.mesh().faces[f])
        if (w != v) reach = std::max({reach, norm(mover.mesh().vertices[w] - from), norm(mover.mesh().vertices[w] - to)});
    data->within(from, reach + o.support_radius, near);
    data->within(to, reach + o.support_radius, near_target);
    near.insert(near.end(), near_target.begin(), near_target.end());
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    double change = 0;
    for (std::uint32_t i : near)
      change += std::min(mover.distance_to_ring(v, to, points[i]), o.max_move) - std::min(mover.distance_to_ring(v, from, points[i]), o.max_move);
    // And no farther from the data where there is none: the mesh area off
    // the data, in points (one per spacing squared), counts the same way.
    if (o.average_spacing > 0)
      change += (mover.area_off_data(v, to, *data, o.data_present, o.max_move) - mover.area_off_data(v, from, *data, o.data_present, o.max_move)) /
                (o.average_spacing * o.average_spacing);
    return change <= 0;
  };
  // Moves are refused at once when they make facets intersect (undoing them
  // afterwards would also undo the moves of their neighbours).
  auto apart = [&](std::uint32_t v, const Vec3& to) { return mover.keeps_facets_apart(v, to, original_vertices, o.max_move); };
  auto fits_and_apart = [&](std::uint32_t v, const Vec3& to) { return fits_data_no_worse(v, to) && apart(v, to); };
  // Three passes: on a thin wall a point's nearest vertices can all go to
  // worse points first, and the mesh they leave is measured again.
  std::vector<Target> corner_targets, data_targets;
  for (int pass = 0; pass < 3; ++pass) {
    find_targets(mesh, corners, points, o, corner_targets, data_targets);
    const std::size_t corners_moved = snap_vertices(mover, original_vertices, std::move(corner_targets), o.max_move, fits_and_apart);
    const std::size_t data_moved = snap_vertices(mover, original_vertices, std::move(data_targets), o.max_move, apart);
    const std::size_t vertices_moved = vertices_to_planes ? snap_off_data_vertices(mover, *data, points, o.point_normals, o, fits_and_apart) : 0;
    stats.corners += corners_moved;
    stats.data_points += data_moved;
    stats.off_data_vertices += vertices_moved;
    if (corners_moved + data_moved + vertices_moved == 0) break;
  }
  if (stats.corners + stats.data_points + stats.off_data_vertices == 0) return stats;
  stats.undone = undo_intersecting_moves(mesh, before);
  return stats;
}

}  // namespace sharpmesh
