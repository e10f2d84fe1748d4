// Tiled reconstruction (issue 38): the cloud cut into slabs along its longest
// axis, each slab meshed by the Chapter 7 pipeline with a margin of its
// neighbours' points, clipped to its slab, and the seams made identical on
// both sides so that the slabs weld into one mesh. Memory holds one slab's
// pipeline at a time.
#pragma once

#include <string>
#include <vector>

#include "sharpmesh/reconstruct.h"

namespace sharpmesh {

struct TilingOptions {
  int tiles = 2;  ///< slabs (>= 1; 1: the whole cloud in one run)
  /// Points of the neighbouring slabs each slab also meshes, on each side,
  /// in d': the neighbourhoods of the features, normals and Poisson reach
  /// over the cut, so the surfaces of two slabs agree there.
  double margin = 6;
  /// Vertices closer than this to a cut move onto it before the clip, so
  /// that no sliver thinner is made [d'].
  double snap = 0.02;
  /// A seam vertex of one side this close to one of the other side's
  /// becomes it, where no facet turns over; the others are inserted into the
  /// other side's edges (0: every vertex of both sides kept) [d'].
  double seam_merge = 0.3;
  /// The seam's two sides may lie this far apart before they are refused [d'].
  double seam_tolerance = 0.5;
  void check() const;
};

struct TileResult {
  double low = 0, high = 0;       ///< the slab along the axis (infinite at the ends)
  std::size_t points = 0;         ///< meshed, margins included
  std::size_t facets = 0;         ///< kept in the slab
  double seconds = 0;
  std::size_t peak_rss_bytes = 0; ///< of the process during the tile
};

struct SeamResult {
  double position = 0;            ///< the cut along the axis
  bool stitched = false;
  std::string failure;            ///< why not, when not
  std::size_t chains = 0;         ///< closed or open curves where the surface crosses the cut
  std::size_t inserted_vertices = 0;
  double max_move = 0;            ///< farthest a seam vertex moved to meet the other side [d']
};

struct TiledResult {
  ReconstructResult merged;       ///< the welded mesh; counts and stages summed over the tiles
  int axis = 0;                   ///< 0 x, 1 y, 2 z
  std::vector<TileResult> tiles;
  std::vector<SeamResult> seams;  ///< the cuts kept, all welded
  /// Cuts removed because their two sides could not be welded; their slabs
  /// were meshed again as one (a warning names each).
  std::size_t merged_seams = 0;
};

/// Meshes `input` in `tiling.tiles` slabs with the options of reconstruct();
/// the average spacing (hence d') is the whole cloud's. Throws as
/// reconstruct() does. A seam that cannot be welded is removed and its two
/// slabs are meshed again as one, so the mesh is never open at a cut.
TiledResult reconstruct_tiled(const PointSet& input, const ReconstructOptions& options, const TilingOptions& tiling,
                              const Progress& progress = {});

}  // namespace sharpmesh
