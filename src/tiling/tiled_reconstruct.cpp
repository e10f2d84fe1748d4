// reconstruct_tiled (sharpmesh/tiled.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include "sharpmesh/errors.h"
#include "sharpmesh/meshing.h"
#include "sharpmesh/pointset.h"
#include "sharpmesh/tiled.h"
#include "sharpmesh/timing.h"
#include "tiling/tiling.h"

namespace sharpmesh {

void TilingOptions::check() const {
  if (tiles < 1 || tiles > 4096) throw InvalidArgument("tiles must be in [1, 4096] (got " + format_number(tiles) + ")");
  if (!(margin >= 1) || !std::isfinite(margin)) throw InvalidArgument("tile margin must be at least 1 d' (got " + format_number(margin) + ")");
  if (!(snap >= 0 && snap < 0.5)) throw InvalidArgument("seam snap distance must be in [0, 0.5) d' (got " + format_number(snap) + ")");
  if (!(seam_merge >= 0 && seam_merge < 1)) throw InvalidArgument("seam merge distance must be in [0, 1) d' (got " + format_number(seam_merge) + ")");
  if (!(seam_tolerance > 0) || !std::isfinite(seam_tolerance))
    throw InvalidArgument("seam tolerance must be positive (got " + format_number(seam_tolerance) + ")");
}

TiledResult reconstruct_tiled(const PointSet& input, const ReconstructOptions& options, const TilingOptions& tiling,
                              const Progress& progress) {
  tiling.check();
  options.check(input.size());
  if (options.compaction.facets > 0 || options.compaction.tolerance > 0)
    throw InvalidArgument("a facet budget or a tolerance is not available with tiles yet: run `decimate` on the tiled mesh");
  check_point_set(input, 10, "tiled reconstruction");
  TiledResult out;
  ReconstructOptions tile_options = options;
  {
    StageTimer timer(out.merged.stages, "spacing");
    tile_options.average_spacing = options.average_spacing > 0 ? options.average_spacing : average_spacing(input, options.spacing_k, progress);
  }
  // Normals of the whole cloud, oriented once: a slab's own orientation
  // sees a cloud open at its cuts, where the occupancy and sheet-parity
  // anchors (and the winding repair) take the inside for the outside, and
  // Poisson then puts a second sheet inside the part. The slabs use them as
  // given.
  // Walls of the whole cloud, decided once: a slab's own airborne test
  // could decide otherwise than its neighbour's.
  PointSet walled;
  {
    StageTimer timer(out.merged.stages, "walls");
    const WallMode mode = options.walls.mode;
    const bool airborne = looks_airborne(input, tile_options.average_spacing);
    // R's bound too: every slab takes the whole cloud's.
    tile_options.features.max_offset_radius = offset_radius_bound(options.features, airborne);
    if (mode == WallMode::On || (mode == WallMode::Automatic && airborne)) {
      walled = input;
      out.merged.walls = fill_vertical_walls(walled, tile_options.average_spacing, options.walls, progress);
    }
    tile_options.walls.mode = WallMode::Off;
  }
  const PointSet& source = walled.empty() ? input : walled;
  PointSet oriented;
  if (!source.has_normals() || options.recompute_normals) {
    NormalsResult normals = reconstruct_normals(source, tile_options, progress);
    for (StageTiming s : normals.stages) {
      s.name = "whole cloud: " + s.name;
      out.merged.stages.push_back(s);
    }
    out.merged.normals = normals.normals;
    oriented = std::move(normals.points);
  }
  const PointSet& cloud = oriented.empty() ? source : oriented;
  tile_options.recompute_normals = false;
  tile_options.check_input_normals = false;
  const double d_prime = options.delta * tile_options.average_spacing;
  const BoundingBox box = bounding_box(input.points);
  for (int a = 1; a < 3; ++a)
    if (box.max[a] - box.min[a] > box.max[out.axis] - box.min[out.axis]) out.axis = a;
  const int axis = out.axis;
  std::vector<double> cuts = detail::slab_cuts(cloud.points, axis, tiling.tiles, d_prime);
  const double margin = tiling.margin * d_prime;
  const double infinity = std::numeric_limits<double>::infinity();
  // One slab: its points with the margins, the pipeline, the clip. Kept by
  // its bounds, so that merging two slabs re-meshes only the merged one.
  struct Slab {
    TileResult tile;
    SurfaceMesh part;
    std::vector<Polyline> feature_edges;
  };
  std::map<std::pair<double, double>, Slab> slabs;
  auto mesh_slab = [&](double low, double high, const std::string& stage) -> const Slab& {
    auto [at, added] = slabs.try_emplace({low, high});
    if (!added) return at->second;
    Slab& slab = at->second;
    slab.tile.low = low;
    slab.tile.high = high;
    const auto start = std::chrono::steady_clock::now();
    PointSet points;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const double x = cloud.points[i][axis];
      if (x < low - margin || x > high + margin) continue;
      points.points.push_back(cloud.points[i]);
      if (cloud.has_normals()) points.normals.push_back(cloud.normals[i]);
      if (cloud.has_colors()) points.colors.push_back(cloud.colors[i]);
    }
    slab.tile.points = points.size();
    Progress tile_progress;
    if (progress)
      tile_progress = [&](const std::string& name, double fraction) { return progress(stage + ": " + name, fraction); };
    ReconstructResult result = reconstruct(points, tile_options, tile_progress);
    slab.part = detail::clip_to_slab(result.mesh, axis, low, high, tiling.snap * d_prime);
    slab.tile.facets = slab.part.faces.size();
    slab.tile.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    slab.tile.peak_rss_bytes = peak_rss_bytes();
    for (StageTiming s : result.stages) {
      s.name = stage + ": " + s.name;
      out.merged.stages.push_back(s);
    }
    // The mesh edges along the features, each segment in the slab of its
    // midpoint (one slab keeps a segment across a cut).
    for (const Polyline& line : result.meshing.feature_edges) {
      Polyline piece;
      for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        const double middle = 0.5 * (line[i][axis] + line[i + 1][axis]);
        if (middle >= low && middle < high) {
          if (piece.empty()) piece.push_back(line[i]);
          piece.push_back(line[i + 1]);
        } else if (!piece.empty()) {
          slab.feature_edges.push_back(std::move(piece));
          piece.clear();
        }
      }
      if (!piece.empty()) slab.feature_edges.push_back(std::move(piece));
    }
    out.merged.warnings.insert(out.merged.warnings.end(), result.warnings.begin(), result.warnings.end());
    return slab;
  };
  // A seam that cannot be welded (the two sides see the surface cross the
  // cut differently: a thin part one slab meshes and the other misses) is
  // removed, and its two slabs are meshed again as one: the mesh is never
  // left open at a cut. At worst the whole cloud is one slab.
  std::vector<SurfaceMesh> parts;
  for (int round = 0;; ++round) {
    parts.clear();
    out.tiles.clear();
    out.seams.clear();
    // A slab the pipeline refuses on its own (all its points on one plane:
    // a stretch of flat ground in a scan) is meshed with its neighbour.
    bool refused = false;
    for (std::size_t k = 0; k <= cuts.size() && !refused; ++k) {
      const double low = k == 0 ? -infinity : cuts[k - 1], high = k == cuts.size() ? infinity : cuts[k];
      try {
        const Slab& slab = mesh_slab(low, high, "slab " + std::to_string(k + 1) + " of " + std::to_string(cuts.size() + 1));
        out.tiles.push_back(slab.tile);
        parts.push_back(slab.part);
      } catch (const Error& e) {
        if (cuts.empty() || dynamic_cast<const Cancelled*>(&e) || dynamic_cast<const InvalidArgument*>(&e)) throw;
        slabs.erase({low, high});
        const std::size_t dropped = k < cuts.size() ? k : k - 1;
        out.merged.warnings.push_back({"slab_merged", "the slab from " + format_number(low) + " to " + format_number(high) + " along " +
                                                          "xyz"[axis] + " could not be meshed alone (" + e.what() + "): it was meshed with its neighbour"});
        ++out.merged_seams;
        cuts.erase(cuts.begin() + static_cast<std::ptrdiff_t>(dropped));
        refused = true;
      }
    }
    if (refused) continue;
    std::vector<std::size_t> failed;
    for (std::size_t k = 0; k < cuts.size(); ++k) {
      const detail::SeamStitch stitch = detail::stitch_seam(parts[k], parts[k + 1], axis, cuts[k], tiling.seam_tolerance * d_prime,
                                                            tiling.seam_merge * d_prime);
      out.seams.push_back({cuts[k], stitch.stitched, stitch.failure, stitch.chains, stitch.inserted, stitch.max_move / d_prime});
      if (!stitch.stitched) failed.push_back(k);
    }
    if (failed.empty()) break;
    for (auto k = failed.rbegin(); k != failed.rend(); ++k) {
      out.merged.warnings.push_back({"seam_merged", "the cut at " + format_number(cuts[*k]) + " along " + "xyz"[axis] +
                                                        " could not be welded (" + out.seams[*k].failure + "): its two slabs were meshed as one"});
      ++out.merged_seams;
      cuts.erase(cuts.begin() + static_cast<std::ptrdiff_t>(*k));
    }
  }
  for (const TileResult& tile : out.tiles)
    for (const Polyline& line : slabs.at({tile.low, tile.high}).feature_edges) out.merged.meshing.feature_edges.push_back(line);
  // The slabs' own polylines overlap in the margins: the merged result
  // names the feature curves by the mesh edges along them.
  out.merged.features.graph.polylines = out.merged.meshing.feature_edges;
  out.merged.mesh = detail::weld_parts(parts, axis, cuts);
  out.merged.average_spacing = tile_options.average_spacing;
  out.merged.d_prime = d_prime;
  out.merged.diagonal = box.diagonal();
  out.merged.input_points = input.size();
  out.merged.used_points = input.size();
  // Each slab repaired its own crossings; the seams' new facets may add
  // some (a thin part cut by a cut): the welded mesh gets the same repair.
  if (options.repair_self_intersections) {
    StageTimer timer(out.merged.stages, "self-intersection check (welded)");
    out.merged.repairs.intersection_repair = repair_self_intersections(out.merged.mesh, {}, progress);
  }
  out.merged.boundary_edges = count_boundary_edges(out.merged.mesh);
  return out;
}

}  // namespace sharpmesh
