// Track merging (thesis 6.3.1): tracks are inserted one by one into a 3D
// Delaunay triangulation; a track whose nearest kept track is closer than t1
// is merged into it (union of the camera lists).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>

#include "pointset/cgal_bridge.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {
namespace {
using detail::Kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
}  // namespace

std::size_t merge_tracks(std::vector<Track>& tracks, double distance) {
  if (tracks.empty() || !(distance > 0)) return 0;
  const double d2 = distance * distance;
  Delaunay dt;
  std::vector<std::uint32_t> absorbed_into(tracks.size(), UINT32_MAX);  // index of the kept track
  std::vector<std::uint32_t> members(tracks.size(), 1);
  Delaunay::Vertex_handle hint;
  std::size_t merged = 0;
  for (std::uint32_t i = 0; i < tracks.size(); ++i) {
    const auto p = detail::to_cgal(tracks[i].position);
    if (dt.number_of_vertices() > 0) {
      const Delaunay::Vertex_handle nearest = dt.nearest_vertex(p, hint == Delaunay::Vertex_handle() ? Delaunay::Cell_handle() : hint->cell());
      if (CGAL::squared_distance(nearest->point(), p) < d2) {
        absorbed_into[i] = nearest->info();
        ++merged;
        hint = nearest;
        continue;
      }
    }
    hint = dt.insert(p, hint == Delaunay::Vertex_handle() ? Delaunay::Cell_handle() : hint->cell());
    hint->info() = i;
  }
  if (merged == 0) return 0;
  // Fold the absorbed tracks into their keepers: views united, position and
  // colour averaged over the members.
  std::vector<std::array<double, 6>> sums(tracks.size(), std::array<double, 6>{});
  for (std::uint32_t i = 0; i < tracks.size(); ++i) {
    const std::uint32_t k = absorbed_into[i] == UINT32_MAX ? i : absorbed_into[i];
    for (int c = 0; c < 3; ++c) {
      sums[k][c] += tracks[i].position[c];
      sums[k][3 + c] += tracks[i].color[c];
    }
    if (k != i) {
      ++members[k];
      tracks[k].views.insert(tracks[k].views.end(), tracks[i].views.begin(), tracks[i].views.end());
    }
  }
  std::vector<Track> kept;
  kept.reserve(tracks.size() - merged);
  for (std::uint32_t i = 0; i < tracks.size(); ++i) {
    if (absorbed_into[i] != UINT32_MAX) continue;
    Track t = std::move(tracks[i]);
    if (members[i] > 1) {
      for (int c = 0; c < 3; ++c) {
        t.position[c] = sums[i][c] / members[i];
        t.color[c] = static_cast<std::uint8_t>(std::lround(sums[i][3 + c] / members[i]));
      }
      std::sort(t.views.begin(), t.views.end());
      t.views.erase(std::unique(t.views.begin(), t.views.end()), t.views.end());
      t.pixels.clear();
    }
    kept.push_back(std::move(t));
  }
  tracks = std::move(kept);
  return merged;
}

}  // namespace sharpmesh
