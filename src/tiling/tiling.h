// The pieces of the tiled reconstruction (sharpmesh/tiled.h): where the
// slabs are cut, each tile's mesh clipped to its slab, and the seams made
// identical on both sides so that the tiles weld into one mesh.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh::detail {

/// `slabs - 1` cut positions along `axis`, in increasing order: near the
/// quantiles that give the slabs equal point counts, moved within a quarter
/// of a slab to where the fewest points lie within `d_prime` of the plane,
/// so that a cut crosses the surface rather than running along a face.
std::vector<double> slab_cuts(const std::vector<Vec3>& points, int axis, int slabs, double d_prime);

/// The part of `mesh` with low <= p[axis] <= high (either bound may be
/// infinite): facets across a bound are cut along it, with one new vertex
/// per cut edge, exactly on the plane. Vertices within `snap` of a bound are
/// moved onto it first, so that no sliver thinner than `snap` is made.
SurfaceMesh clip_to_slab(const SurfaceMesh& mesh, int axis, double low, double high, double snap);

/// A chain of boundary edges lying on a cut plane, in the direction the
/// mesh's facets give their boundary half-edges.
struct SeamChain {
  std::vector<std::uint32_t> vertices;
  bool closed = false;
};
/// The boundary of `mesh` lying on the plane p[axis] = plane.
std::vector<SeamChain> chains_on_plane(const SurfaceMesh& mesh, int axis, double plane);

struct SeamStitch {
  bool stitched = false;
  std::string failure;           ///< why not, when not
  std::size_t chains = 0;        ///< chains matched across the seam
  std::size_t inserted = 0;      ///< vertices added to the other side's boundary edges
  double max_move = 0;           ///< farthest a vertex of `above` moved onto `below`'s chain
};
/// Makes the boundaries of `below` (the slab under the plane) and `above`
/// on the plane the same chains of the same vertices: each of above's seam
/// vertices becomes below's nearest chain vertex when within `merge` (one
/// each, no facet turned over), or else moves to the nearest point of
/// below's matching chain (within `tolerance`), and each side's boundary
/// edges are split at the other side's remaining vertices. Unchanged, with
/// the reason, when the chains do not match one to one in order.
SeamStitch stitch_seam(SurfaceMesh& below, SurfaceMesh& above, int axis, double plane, double tolerance, double merge);

/// One mesh of the parts, the vertices that coincide exactly on the cut
/// planes merged.
SurfaceMesh weld_parts(const std::vector<SurfaceMesh>& parts, int axis, const std::vector<double>& cuts);

}  // namespace sharpmesh::detail
