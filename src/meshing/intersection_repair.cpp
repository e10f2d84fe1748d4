// Self-intersection repair: the facets that cross others are cut out with a
// ring of their neighbours and the holes left are closed by the hole filler
// (Liepa's triangulate, refine and fair, CGAL's Polygon Mesh Processing), the
// remedy CGAL itself offers in PMP::experimental::remove_self_intersections.
// A patch that still crosses the surface widens the cut on the next round.
#include <algorithm>
#include <cmath>

#include "core/mesh_graph.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/meshing.h"

namespace sharpmesh {
namespace {

// Faces within `rings` vertex rings of the marked ones, marked too.
void grow(const SurfaceMesh& mesh, std::vector<char>& marked, int rings) {
  std::vector<std::vector<std::uint32_t>> faces_of(mesh.vertices.size());
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
    for (std::uint32_t v : mesh.faces[f]) faces_of[v].push_back(f);
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> touched(mesh.vertices.size(), 0);
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
      if (marked[f])
        for (std::uint32_t v : mesh.faces[f]) touched[v] = 1;
    for (std::uint32_t v = 0; v < touched.size(); ++v)
      if (touched[v])
        for (std::uint32_t f : faces_of[v]) marked[f] = 1;
  }
}

// Length of the cut's rim: the edges with one marked and one unmarked or no other face.
double rim_length(const SurfaceMesh& mesh, const std::vector<char>& marked) {
  double length = 0;
  for (const detail::EdgeIncidence& e : detail::edge_incidences(mesh)) {
    std::size_t inside = 0;
    for (std::uint32_t f : e.faces) inside += marked[f];
    if (inside > 0 && inside < e.faces.size() + (e.faces.size() == 1)) {
      const Vec3 &a = mesh.vertices[e.a], &b = mesh.vertices[e.b];
      length += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
  }
  return length;
}

}  // namespace

void IntersectionRepairOptions::check() const {
  if (max_rounds < 0) throw InvalidArgument("self-intersection repair: the number of rounds must be >= 0");
  if (rings < 0) throw InvalidArgument("self-intersection repair: the ring count must be >= 0");
}

IntersectionRepairStats repair_self_intersections(SurfaceMesh& mesh, const IntersectionRepairOptions& options,
                                                  const Progress& progress) {
  options.check();
  IntersectionRepairStats stats;
  auto pairs = self_intersecting_faces(mesh);
  stats.intersecting_pairs = pairs.size();
  for (int round = 0; round < options.max_rounds && !pairs.empty(); ++round) {
    report_progress(progress, "repairing self-intersections", static_cast<double>(round) / options.max_rounds);
    std::vector<char> marked(mesh.faces.size(), 0);
    for (const auto& [a, b] : pairs) marked[a] = marked[b] = 1;
    grow(mesh, marked, options.rings + round);
    // Every hole the cut opens is at most as long as its whole rim; the
    // mesh's own borders (an open scan's) are far longer and stay open.
    HoleFillingOptions filling;
    filling.max_perimeter = rim_length(mesh, marked);
    std::vector<Triangle> kept;
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
      if (!marked[f]) kept.push_back(mesh.faces[f]);
    if (kept.empty()) break;
    stats.removed_facets += mesh.faces.size() - kept.size();
    SurfaceMesh cut = mesh;
    detail::set_faces_and_compact(cut, std::move(kept));
    const HoleFillingStats filled = fill_holes(cut, filling);
    stats.added_facets += filled.added_facets;
    mesh = std::move(cut);
    pairs = self_intersecting_faces(mesh);
    ++stats.rounds;
  }
  report_progress(progress, "repairing self-intersections", 1.0);
  stats.remaining_pairs = pairs.size();
  return stats;
}

}  // namespace sharpmesh
