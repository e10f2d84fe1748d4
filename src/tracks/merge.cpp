// Track merging (thesis 6.3.1): tracks are taken one by one in input order;
// a track whose nearest kept track is closer than t1 is merged into it (union
// of the camera lists). The thesis finds that track in an incremental 3D
// Delaunay triangulation; a hash grid of cell t1 answers the same question
// (every kept track within t1 lies in the 27 cells around the query) without
// the triangulation's walks between far-apart tracks, and gives the same
// merges (tests/unit/stereo_reconstruct_test.cpp checks it against the rule).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {
namespace {

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };  // unsigned: wrapping is defined
    return static_cast<std::size_t>((u(k.x) * 73856093u) ^ (u(k.y) * 19349663u) ^ (u(k.z) * 83492791u));
  }
};

}  // namespace

std::size_t merge_tracks(std::vector<Track>& tracks, double distance) {
  if (tracks.empty() || !(distance > 0)) return 0;
  const double d2 = distance * distance;
  std::unordered_map<CellKey, std::vector<std::uint32_t>, CellHash> kept_in_cell;
  // Cells at least t1 wide (the 27-cell search needs no more), and at most
  // 2^40 of them along the box so that their indices fit.
  std::vector<Vec3> positions;
  positions.reserve(tracks.size());
  for (const Track& t : tracks) positions.push_back(t.position);
  const BoundingBox box = bounding_box(positions);
  const double cell = std::max(distance, box.diagonal() * 0x1p-40);
  auto cell_of = [&](const Vec3& p) {
    CellKey k;
    k.x = static_cast<std::int64_t>(std::floor((p[0] - box.min[0]) / cell));
    k.y = static_cast<std::int64_t>(std::floor((p[1] - box.min[1]) / cell));
    k.z = static_cast<std::int64_t>(std::floor((p[2] - box.min[2]) / cell));
    return k;
  };
  std::vector<std::uint32_t> absorbed_into(tracks.size(), UINT32_MAX);  // index of the kept track
  std::vector<std::uint32_t> members(tracks.size(), 1);
  std::size_t merged = 0;
  for (std::uint32_t i = 0; i < tracks.size(); ++i) {
    const Vec3& p = tracks[i].position;
    const CellKey c = cell_of(p);
    std::uint32_t nearest = UINT32_MAX;
    double nearest_d2 = d2;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto found = kept_in_cell.find(CellKey{c.x + dx, c.y + dy, c.z + dz});
          if (found == kept_in_cell.end()) continue;
          for (std::uint32_t k : found->second) {
            const Vec3 d = tracks[k].position - p;
            const double dd = dot(d, d);
            if (dd < nearest_d2 || (dd == nearest_d2 && nearest != UINT32_MAX && k < nearest)) {
              nearest_d2 = dd;
              nearest = k;
            }
          }
        }
    if (nearest != UINT32_MAX) {
      absorbed_into[i] = nearest;
      ++merged;
    } else {
      kept_in_cell[c].push_back(i);
    }
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
