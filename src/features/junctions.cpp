// Junction recovery (thesis 7.2.3, Fig. 7.7): endpoints closer than r_junc
// (5 x the spacing of a polyline's last four points) meet at the barycentre
// of the closest points of their end lines. Beyond the thesis, so that every
// polyline runs between two junctions or darts (what the protecting balls of
// 7.3.2 need): two ends of one long polyline close a loop; two collinear ends
// are joined into one polyline instead of a false cusp; a polyline passing
// through a junction is split there. r_junc is capped (extract: 8 average
// spacings; the thesis's 5 segments are 20 spacings with our r_p floor of
// 4), except between two pieces of one edge: ends of different edges 3-4
// spacings apart (couplingdown's steps) were merged into one junction
// between them.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/fold_backs.h"
#include "core/mesh_graph.h"
#include "features/feature_graph_builder.h"

namespace sharpmesh::detail {
namespace {

struct End {
  std::size_t polyline;
  bool back;        ///< the last vertex (else the first)
  Vec3 position;
  Vec3 outward;     ///< edge direction pointing out of the polyline
  double r_junc;    ///< capped at max_radius
  double r_gap = 0; ///< r_junc uncapped: how far a collinear piece of the same edge may be
};

// Whether b continues a's edge: the ends face each other and b lies on a's line.
bool continues(const End& a, const End& b, double cos_collinear) {
  const Vec3 u = (1.0 / norm(a.outward)) * a.outward, offset = b.position - a.position;
  return dot(a.outward, b.outward) < cos_collinear * norm(a.outward) * norm(b.outward) && dot(offset, u) > 0 &&
         norm(offset - dot(offset, u) * u) < 0.25 * norm(offset);
}

End make_end(const TracedPolyline& line, std::size_t index, bool back, double factor) {
  const std::size_t n = line.vertices.size();
  // Average spacing of the ending four points (three segments).
  double spacing = 0;
  int segments = 0;
  for (int s = 0; s < 3 && s + 1 < static_cast<int>(n); ++s, ++segments) {
    const std::size_t a = back ? n - 1 - s : s, b = back ? n - 2 - s : s + 1;
    spacing += distance(line.vertices[a], line.vertices[b]);
  }
  spacing = segments ? spacing / segments : 0;
  Vec3 outward = back ? line.directions.back() : -1.0 * line.directions.front();
  return {index, back, back ? line.vertices.back() : line.vertices.front(), outward, factor * spacing};
}

// Least-squares meeting point of the ends' lines (pulled slightly towards
// their centroid so that parallel lines have one).
Vec3 meeting_point(const std::vector<const End*>& group) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero(), centroid = Eigen::Vector3d::Zero();
  for (const End* e : group) centroid += Eigen::Vector3d(e->position[0], e->position[1], e->position[2]);
  centroid /= static_cast<double>(group.size());
  for (const End* e : group) {
    Eigen::Vector3d u(e->outward[0], e->outward[1], e->outward[2]);
    u.normalize();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - u * u.transpose();
    A += P;
    rhs += P * Eigen::Vector3d(e->position[0], e->position[1], e->position[2]);
  }
  const double eps = 1e-3 * static_cast<double>(group.size());
  A += eps * Eigen::Matrix3d::Identity();
  rhs += eps * centroid;
  const Eigen::Vector3d p = A.ldlt().solve(rhs);
  return {p(0), p(1), p(2)};
}

// Whether ends within r of each other point at one junction: the lines of
// all of them pass within r/3 of their meeting point, which lies within r
// of every end. Grouping ends by distance alone chains the ends of two
// parallel edges a short edge apart (two corners of one small face) into
// one junction far from both corners. Beyond that, with `lateral` > 0, each
// line passes within max(lateral, tan 25 x the end's distance) of the
// meeting point: the ends of two parallel edges 3-4 spacings apart (the
// rims of a thin plate or of a low wall) lie side by side, and their lines
// meet only halfway between them, in mid-air (oblong 50k: both rims of a
// 3 mm plate snapped to one junction between them and the loops were lost;
// couplingdown 50k: two corners 4 spacings apart merged).
bool group_meets(const std::vector<const End*>& group, double r, double lateral) {
  if (group.size() < 2) return true;
  const Vec3 p = meeting_point(group);
  const double tan_max = std::tan(25.0 * M_PI / 180.0);
  for (const End* e : group) {
    const Vec3 u = (1.0 / norm(e->outward)) * e->outward;
    const Vec3 offset = p - e->position;
    const double along = dot(offset, u), off_line = norm(offset - along * u);
    if (off_line >= r / 3 || distance(p, e->position) >= r) return false;
    if (lateral > 0 && off_line > std::max(lateral, tan_max * std::abs(along))) return false;
  }
  return true;
}

// The end moves to its junction `p`. Vertices that `p` lies beyond (the
// line would turn back by more than 90 degrees there) are dropped: a
// junction placed between a polyline's first two points would make it fold
// back on itself, which CGAL's protection cannot take (core/fold_backs.h).
void set_end(TracedPolyline& line, bool back, const Vec3& p) {
  std::vector<Vec3>& v = line.vertices;
  std::vector<Vec3>& d = line.directions;
  if (back) std::reverse(v.begin(), v.end()), std::reverse(d.begin(), d.end());
  v.front() = p;
  while (v.size() >= 3 && dot(p - v[1], v[2] - v[1]) > 0) {
    v.erase(v.begin() + 1);
    if (d.size() > 1) d.erase(d.begin() + 1);
  }
  if (back) std::reverse(v.begin(), v.end()), std::reverse(d.begin(), d.end());
}

// Ends whose directions are within 30 degrees of opposite are collinear.
const double kCosCollinear = std::cos(150.0 * M_PI / 180.0);

// Two pieces of one edge (or a loop's two ends) keep the thesis's r_junc.
double pair_radius(const End& a, const End& b) {
  const bool same_edge = continues(a, b, kCosCollinear) && continues(b, a, kCosCollinear);
  return same_edge ? std::max(a.r_gap, b.r_gap) : std::max(a.r_junc, b.r_junc);
}

std::vector<End> polyline_ends(const std::vector<TracedPolyline>& lines, double factor, double max_radius) {
  std::vector<End> ends;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].vertices.size() < 2) continue;
    ends.push_back(make_end(lines[i], i, false, factor));
    ends.push_back(make_end(lines[i], i, true, factor));
  }
  for (End& e : ends) {
    e.r_gap = e.r_junc;
    if (max_radius > 0) e.r_junc = std::min(e.r_junc, max_radius);
  }
  return ends;
}

// Whether the two ends of one polyline, `d` apart, close it into a loop.
// 4 r_junc (20 segments): spool.off's rim circles (45 points, ends 0.002
// apart) stayed open at 10 r_junc, and the two touching end balls shrank the
// whole protection to 3,400 tiny balls. Shorter polylines close too when
// their ends all but touch (within two segments, a tenth of the length):
// anchor 50k's hole rims, 0.36 long with ends 0.0002-0.002 apart, stayed
// open, their 470 balls each shrank to the 5% floor and 64% of all
// protected segments were not mesh edges.
bool closes_loop(const End& a, const End& b, double d, double length) {
  const double r = pair_radius(a, b);
  const bool touching = d < std::min(0.4 * r, 0.1 * length);
  return (length >= 4 * r || touching) && dot(a.outward, b.outward) <= -0.5;
}

// Groups of ends within r_junc of each other, closest pairs first; two
// groups merge only when all their ends still meet at one point. The two
// ends of one polyline are only grouped when it closes a loop. Each group
// is listed by its root.
std::map<std::size_t, std::vector<std::size_t>> group_ends(const std::vector<End>& ends, const std::vector<TracedPolyline>& lines,
                                                           double lateral) {
  struct Pair { double d; std::size_t a, b; };
  std::vector<Pair> pairs;
  for (std::size_t a = 0; a < ends.size(); ++a)
    for (std::size_t b = a + 1; b < ends.size(); ++b) {
      const double d = distance(ends[a].position, ends[b].position);
      if (d < pair_radius(ends[a], ends[b])) pairs.push_back({d, a, b});
    }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return x.d < y.d; });
  DisjointSets groups(ends.size());
  std::map<std::size_t, std::vector<std::size_t>> group_of;
  for (std::size_t a = 0; a < ends.size(); ++a) group_of[a] = {a};
  for (const Pair& pair : pairs) {
    const std::size_t a = pair.a, b = pair.b, ga = groups.find(a), gb = groups.find(b);
    if (ga == gb) continue;
    if (ends[a].polyline == ends[b].polyline && !closes_loop(ends[a], ends[b], pair.d, lines[ends[a].polyline].length())) continue;
    std::vector<const End*> merged;
    double r = 0;
    for (std::size_t g : {ga, gb})
      for (std::size_t e : group_of[g]) {
        merged.push_back(&ends[e]);
        r = std::max(r, ends[e].r_junc);
      }
    if (merged.size() == 2) r = pair_radius(*merged[0], *merged[1]);
    const bool loop = merged.size() == 2 && merged[0]->polyline == merged[1]->polyline;
    if (!loop && !group_meets(merged, r, lateral)) continue;
    groups.unite(a, b);
    const std::size_t root = groups.find(a), other = root == ga ? gb : ga;
    std::vector<std::size_t> members_of_root = group_of[ga];
    members_of_root.insert(members_of_root.end(), group_of[gb].begin(), group_of[gb].end());
    group_of.erase(other);
    group_of[root] = std::move(members_of_root);
  }
  std::map<std::size_t, std::vector<std::size_t>> members;
  for (std::size_t a = 0; a < ends.size(); ++a) members[groups.find(a)].push_back(a);
  return members;
}

struct Node {
  Vec3 position;
  double radius;
  std::vector<std::size_t> ends;  ///< indices into the ends; SIZE_MAX for the two sides of a split polyline
};

// One node per group: a closed loop (no node), a junction the ends move to,
// or, where the end lines meet off the surface, one dart per end.
std::vector<Node> place_junctions(const std::map<std::size_t, std::vector<std::size_t>>& members, const std::vector<End>& ends,
                                  std::vector<TracedPolyline>& lines, const std::function<double(const Vec3&)>& distance_to_data,
                                  double max_offset) {
  std::vector<Node> nodes;
  for (const auto& [root, list] : members) {
    std::vector<End> group;
    double radius = 0;
    for (std::size_t a : list) {
      group.push_back(ends[a]);
      radius = std::max(radius, ends[a].r_junc);
    }
    if (group.size() == 2 && group[0].polyline == group[1].polyline) {  // a closed loop
      TracedPolyline& line = lines[group[0].polyline];
      const Vec3 mid = 0.5 * (group[0].position + group[1].position);
      line.vertices.front() = mid;
      line.vertices.back() = mid;
      line.closed = true;
      continue;
    }
    // The junction: the point nearest to all end lines (7.2.3 takes the
    // closest points of pairs of end lines; with three or more ends the
    // least-squares point uses them all at once).
    std::vector<const End*> pointers;
    for (const End& e : group) pointers.push_back(&e);
    const Vec3 p = group.size() == 1 ? group[0].position : meeting_point(pointers);
    // End lines that meet off the surface (fandisk 30k: two ends 13 spacings
    // apart met 3.6 spacings from the data, and the mesh followed) do not
    // make a junction: each end stays where it is, as a dart.
    if (group.size() > 1 && distance_to_data && distance_to_data(p) > max_offset) {
      for (std::size_t k = 0; k < group.size(); ++k) nodes.push_back({group[k].position, group[k].r_junc, {list[k]}});
      continue;
    }
    for (const End& e : group) set_end(lines[e.polyline], e.back, p);
    nodes.push_back({p, radius, list});
  }
  return nodes;
}

// A dart pointing at a junction on its own line within the uncapped r_junc
// ends there: the rest of its edge was not traced (cube-meshed 50k: 9
// spacings missing before a corner).
void attach_darts(std::vector<Node>& nodes, const std::vector<End>& ends, std::vector<TracedPolyline>& lines) {
  for (Node& dart : nodes) {
    if (dart.ends.size() != 1) continue;
    const End& e = ends[dart.ends[0]];
    Node* best = nullptr;
    double best_d = e.r_gap;
    for (Node& node : nodes) {
      if (node.ends.size() < 2) continue;
      const double d = distance(e.position, node.position);
      if (d < best_d && continues(e, {0, false, node.position, -1.0 * e.outward, 0, 0}, kCosCollinear)) {
        best_d = d;
        best = &node;
      }
    }
    if (!best) continue;
    set_end(lines[e.polyline], e.back, best->position);
    best->ends.push_back(dart.ends[0]);
    dart.ends.clear();
  }
}

// Joins the two pieces meeting at a node of degree 2 when they are collinear
// (one sharp edge detected in two clusters): no false cusp. Returns the
// pieces joined into another.
std::vector<bool> join_collinear_pieces(std::vector<Node>& nodes, std::vector<End>& ends, std::vector<TracedPolyline>& lines) {
  std::vector<bool> dead(lines.size(), false);
  for (Node& node : nodes) {
    if (node.ends.size() != 2) continue;
    const End &a = ends[node.ends[0]], &b = ends[node.ends[1]];
    if (dot(a.outward, b.outward) > kCosCollinear) continue;
    if (a.polyline == b.polyline) {
      // A loop traced in pieces, now joined at its other gaps: it closes here.
      // (It used to be left with both ends on this node and dropped as a stub:
      // spool 50k lost a rim circle traced in two pieces.)
      lines[a.polyline].closed = true;
      node.ends.clear();
      continue;
    }
    TracedPolyline& la = lines[a.polyline];
    TracedPolyline lb = lines[b.polyline];
    // Which end meets the node is read from the positions: earlier joins may have reversed a piece.
    const bool a_back = distance(la.vertices.back(), node.position) <= distance(la.vertices.front(), node.position);
    const bool b_back = distance(lb.vertices.back(), node.position) <= distance(lb.vertices.front(), node.position);
    if (!a_back) {
      std::reverse(la.vertices.begin(), la.vertices.end());
      std::reverse(la.directions.begin(), la.directions.end());
    }
    if (b_back) {
      std::reverse(lb.vertices.begin(), lb.vertices.end());
      std::reverse(lb.directions.begin(), lb.directions.end());
    }
    la.vertices.insert(la.vertices.end(), lb.vertices.begin() + 1, lb.vertices.end());
    la.directions.insert(la.directions.end(), lb.directions.begin() + 1, lb.directions.end());
    const std::size_t removed = b.polyline, into = a.polyline;
    dead[removed] = true;
    node.ends.clear();  // no longer a junction
    for (End& e : ends)  // ends of the removed piece now belong to the merged polyline
      if (e.polyline == removed) e.polyline = into;
  }
  return dead;
}

// Splits the polylines that pass through a junction or dart (T-junctions):
// an interior vertex within the node's radius / 3 becomes the node.
void split_at_nodes(std::vector<Node>& nodes, std::vector<TracedPolyline>& kept) {
  for (Node& node : nodes) {
    if (node.ends.empty()) continue;
    for (std::size_t li = 0; li < kept.size(); ++li) {
      TracedPolyline& line = kept[li];
      std::size_t best = 0;
      double best_d = node.radius / 3;  // as close as the end lines of one junction (group_meets)
      for (std::size_t v = 1; v + 1 < line.vertices.size(); ++v) {
        const double d = distance(line.vertices[v], node.position);
        if (d < best_d) {
          best_d = d;
          best = v;
        }
      }
      if (best == 0 || best == line.vertices.size() - 1) continue;
      // Do not split a polyline at a vertex right next to its own end at this node.
      if (distance(line.vertices.front(), node.position) < 1e-12 || distance(line.vertices.back(), node.position) < 1e-12) continue;
      TracedPolyline tail;
      tail.vertices.assign(line.vertices.begin() + best, line.vertices.end());
      tail.directions.assign(line.directions.begin() + best, line.directions.end());
      line.vertices.resize(best + 1);
      line.directions.resize(best + 1);
      line.vertices.back() = node.position;
      tail.vertices.front() = node.position;
      if (line.closed) {  // a split loop becomes one open polyline from the node round to the node
        tail.vertices.insert(tail.vertices.end(), line.vertices.begin() + 1, line.vertices.end());
        tail.directions.insert(tail.directions.end(), line.directions.begin() + 1, line.directions.end());
        tail.closed = false;
        line = std::move(tail);
      } else {
        kept.push_back(std::move(tail));
      }
      node.ends.push_back(SIZE_MAX);
      node.ends.push_back(SIZE_MAX);
    }
  }
}

FeatureGraph make_graph(const std::vector<TracedPolyline>& kept, const std::vector<Node>& nodes) {
  FeatureGraph graph;
  for (const TracedPolyline& line : kept) {
    if (!(line.length() > 0)) continue;  // splits and closings can leave empty pieces
    graph.polylines.push_back(line.vertices);
    remove_fold_backs(graph.polylines.back());  // a zigzag left by the tracing
  }
  for (const Node& node : nodes) {
    if (node.ends.empty()) continue;
    Junction j;
    j.position = node.position;
    j.degree = static_cast<int>(node.ends.size());
    j.type = j.degree == 1 ? JunctionType::Dart : j.degree == 2 ? JunctionType::Cusp : JunctionType::Corner;
    graph.junctions.push_back(j);
  }
  return graph;
}

}  // namespace

FeatureGraph connect_polylines(std::vector<TracedPolyline> lines, double factor,
                               const std::function<double(const Vec3&)>& distance_to_data, double max_offset, double max_radius,
                               double lateral) {
  std::vector<End> ends = polyline_ends(lines, factor, max_radius);
  const auto members = group_ends(ends, lines, lateral);
  std::vector<Node> nodes = place_junctions(members, ends, lines, distance_to_data, max_offset);
  attach_darts(nodes, ends, lines);
  const std::vector<bool> dead = join_collinear_pieces(nodes, ends, lines);
  // A piece whose two ends were snapped to the same junction (grouped through
  // other ends) is a stub inside the junction's ball, not an edge.
  std::vector<TracedPolyline> kept;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (!dead[i] && lines[i].vertices.size() >= 2 && (lines[i].closed || lines[i].vertices.front() != lines[i].vertices.back()))
      kept.push_back(std::move(lines[i]));
  split_at_nodes(nodes, kept);
  return make_graph(kept, nodes);
}

}  // namespace sharpmesh::detail
