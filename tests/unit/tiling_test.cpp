// Tiled reconstruction (sharpmesh/tiled.h, src/tiling/): the slabs' meshes
// clipped exactly on their cuts, the seams made one chain of one set of
// vertices, and the welded mesh as valid as one run's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fixtures.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/meshing.h"
#include "sharpmesh/tiled.h"
#include "tiling/tiling.h"

using namespace sharpmesh;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

SurfaceMesh moved(SurfaceMesh mesh, const Vec3& by) {
  for (Vec3& p : mesh.vertices) p = p + by;
  return mesh;
}

/// A sphere tessellated otherwise: the icosphere turned about an oblique axis.
SurfaceMesh turned_sphere(int levels) {
  SurfaceMesh mesh = test::sphere_mesh(levels);
  const double c = std::cos(0.7), s = std::sin(0.7);
  for (Vec3& p : mesh.vertices) p = Vec3{c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]};
  return mesh;
}

}  // namespace

TEST(Tiling, ClipKeepsTheSlabAndLeavesClosedChainsExactlyOnTheCuts) {
  const SurfaceMesh sphere = test::sphere_mesh(4);
  const SurfaceMesh slab = detail::clip_to_slab(sphere, 2, -0.3, 0.45, 1e-3);
  for (const Vec3& p : slab.vertices) {
    EXPECT_GE(p[2], -0.3);
    EXPECT_LE(p[2], 0.45);
  }
  for (double cut : {-0.3, 0.45}) {
    const auto chains = detail::chains_on_plane(slab, 2, cut);
    ASSERT_EQ(chains.size(), 1u) << cut;
    EXPECT_TRUE(chains[0].closed);
    for (std::uint32_t v : chains[0].vertices) EXPECT_EQ(slab.vertices[v][2], cut);
  }
  const TopologyReport t = check_topology(slab);
  EXPECT_TRUE(t.manifold());
  EXPECT_EQ(t.components, 1u);
  // The band's area: 2 pi r h on a unit sphere, up to the tessellation.
  const double area = surface_area(slab);
  EXPECT_NEAR(area, 2 * M_PI * 0.75, 0.03 * 2 * M_PI * 0.75);
}

TEST(Tiling, SeamsOfDifferentTessellationsWeldIntoOneClosedValidMesh) {
  // The two sides of each cut come from two meshes of the same sphere whose
  // vertices differ everywhere, as two slabs' meshes do.
  const SurfaceMesh a = test::sphere_mesh(4), b = turned_sphere(4);
  const std::vector<double> cuts = {-0.4, 0.1, 0.55};
  std::vector<SurfaceMesh> parts;
  for (std::size_t k = 0; k <= cuts.size(); ++k)
    parts.push_back(detail::clip_to_slab(k % 2 == 0 ? a : b, 2, k == 0 ? -kInf : cuts[k - 1], k == cuts.size() ? kInf : cuts[k], 1e-3));
  // Every vertex of both sides kept, and nearby ones merged: both weld.
  std::size_t kept_vertices = 0;
  for (double merge : {0.0, 0.04}) {
    SCOPED_TRACE("merge " + std::to_string(merge));
    std::vector<SurfaceMesh> stitched = parts;
    for (std::size_t k = 0; k < cuts.size(); ++k) {
      const detail::SeamStitch seam = detail::stitch_seam(stitched[k], stitched[k + 1], 2, cuts[k], 0.05, merge);
      ASSERT_TRUE(seam.stitched) << seam.failure;
      EXPECT_EQ(seam.chains, 1u);
      EXPECT_GT(seam.inserted, 0u);
      EXPECT_LT(seam.max_move, 0.05);
    }
    const SurfaceMesh welded = detail::weld_parts(stitched, 2, cuts);
    const TopologyReport t = check_topology(welded);
    EXPECT_TRUE(t.closed());
    EXPECT_TRUE(t.manifold());
    EXPECT_TRUE(t.orientable);
    EXPECT_FALSE(t.self_intersecting);
    EXPECT_EQ(t.components, 1u);
    if (merge == 0) kept_vertices = welded.vertices.size();
    else EXPECT_LT(welded.vertices.size(), kept_vertices);
  }
  // Two spheres at the cut do not match: refused, both left as they were.
  SurfaceMesh below = detail::clip_to_slab(a, 2, -kInf, 0.1, 1e-3);
  SurfaceMesh above = detail::clip_to_slab(moved(b, {0.5, 0, 0}), 2, 0.1, kInf, 1e-3);
  const SurfaceMesh below_before = below, above_before = above;
  const detail::SeamStitch refused = detail::stitch_seam(below, above, 2, 0.1, 0.05, 0.04);
  EXPECT_FALSE(refused.stitched);
  EXPECT_FALSE(refused.failure.empty());
  EXPECT_EQ(below.faces, below_before.faces);
  EXPECT_EQ(above.vertices, above_before.vertices);
}

TEST(Tiling, OpenSurfacesWeldOverTheOverlapOfTheirChains) {
  // Half spheres (open along x = 0) of two tessellations, in slabs along z:
  // each cut crosses the surface in an arc whose two ends are the data's edge.
  const SurfaceMesh a = detail::clip_to_slab(test::sphere_mesh(4), 0, 0, kInf, 1e-3);
  const SurfaceMesh b = detail::clip_to_slab(turned_sphere(4), 0, 0, kInf, 1e-3);
  const std::vector<double> cuts = {-0.35, 0.2};
  std::vector<SurfaceMesh> parts;
  for (std::size_t k = 0; k <= cuts.size(); ++k)
    parts.push_back(detail::clip_to_slab(k % 2 == 0 ? a : b, 2, k == 0 ? -kInf : cuts[k - 1], k == cuts.size() ? kInf : cuts[k], 1e-3));
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    ASSERT_FALSE(detail::chains_on_plane(parts[k], 2, cuts[k]).at(0).closed);
    const detail::SeamStitch seam = detail::stitch_seam(parts[k], parts[k + 1], 2, cuts[k], 0.05, 0.04);
    ASSERT_TRUE(seam.stitched) << seam.failure;
  }
  const SurfaceMesh welded = detail::weld_parts(parts, 2, cuts);
  const TopologyReport t = check_topology(welded);
  EXPECT_TRUE(t.manifold());
  EXPECT_FALSE(t.self_intersecting);
  EXPECT_EQ(t.components, 1u);
  // The only boundary left is the half sphere's own rim, on x = 0, where the
  // two sides' chains do not overlap at most an edge or two.
  EXPECT_GT(t.boundary_edges, 0u);
  const std::size_t rim = std::max(check_topology(a, false).boundary_edges, check_topology(b, false).boundary_edges);
  EXPECT_LE(t.boundary_edges, rim + 8 * cuts.size());
}

TEST(Tiling, CutsAvoidAFaceLyingAcrossTheAxis) {
  // Half of the points on the plane x = 0, where the median falls.
  std::vector<Vec3> points;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) points.push_back({0.0, i * 0.01, j * 0.01});
  for (int i = 0; i < 10000; ++i) points.push_back({-1.0 + 2.0 * (i + 0.5) / 10000, 0.5, 0.5});
  const double d_prime = 0.02;
  const std::vector<double> cuts = detail::slab_cuts(points, 0, 2, d_prime);
  ASSERT_EQ(cuts.size(), 1u);
  EXPECT_GT(std::abs(cuts[0]), d_prime);
  EXPECT_LT(std::abs(cuts[0]), 0.5);
}

TEST(Tiling, SlabsWeldIntoAClosedValidMeshAsAccurateAsOneRun) {
  const SurfaceMesh part = test::chamfered_cube_mesh(0.3);
  PointSet points = test::sample_with_normals(part, 30000, 7);
  points.normals.clear();
  ReconstructOptions options;
  options.delta = 5;
  TilingOptions tiling;
  tiling.tiles = 3;
  const TiledResult tiled = reconstruct_tiled(points, options, tiling);
  ASSERT_EQ(tiled.seams.size(), 2u);
  for (const SeamResult& seam : tiled.seams) EXPECT_TRUE(seam.stitched) << seam.failure;
  const TopologyReport t = check_topology(tiled.merged.mesh);
  EXPECT_TRUE(t.closed());
  EXPECT_TRUE(t.manifold());
  EXPECT_TRUE(t.orientable);
  EXPECT_FALSE(t.self_intersecting);
  EXPECT_EQ(t.components, 1u);
  // No vertex twice: the seams' two sides became one set of vertices.
  std::vector<Vec3> sorted = tiled.merged.mesh.vertices;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
  const ReconstructResult one = reconstruct(points, options);
  const double tiled_error = compare_meshes(tiled.merged.mesh, part).hausdorff;
  const double one_error = compare_meshes(one.mesh, part).hausdorff;
  EXPECT_LE(tiled_error, 1.2 * one_error + 0.05 * tiled.merged.d_prime);
  // The sharp edges the slabs kept, together, are the cube's (12 edges of
  // length 2, the chamfered one replaced by two shorter ones).
  double length = 0;
  for (const Polyline& line : tiled.merged.meshing.feature_edges)
    for (std::size_t i = 0; i + 1 < line.size(); ++i) length += norm(line[i + 1] - line[i]);
  EXPECT_GT(length, 0.9 * 24);
  // Tiles are the same whatever the thread count.
  options.threads = 1;
  const TiledResult single = reconstruct_tiled(points, options, tiling);
  EXPECT_EQ(single.merged.mesh.vertices, tiled.merged.mesh.vertices);
  EXPECT_EQ(single.merged.mesh.faces, tiled.merged.mesh.faces);
}

TEST(Tiling, OptionsAreChecked) {
  const PointSet points = test::sample_with_normals(test::cube_mesh(), 2000, 1);
  for (auto change : {+[](TilingOptions& t) { t.tiles = 0; }, +[](TilingOptions& t) { t.margin = 0.5; },
                      +[](TilingOptions& t) { t.snap = 0.7; }, +[](TilingOptions& t) { t.seam_tolerance = 0; },
                      +[](TilingOptions& t) { t.seam_merge = 1.5; }}) {
    TilingOptions tiling;
    change(tiling);
    EXPECT_THROW(reconstruct_tiled(points, {}, tiling), InvalidArgument);
  }
  ReconstructOptions budget;
  budget.compaction.facets = 500;
  EXPECT_THROW(reconstruct_tiled(points, budget, {}), InvalidArgument);
}

TEST(Tiling, ACutWhoseSidesCannotBeWeldedIsDroppedAndTheMeshStaysClosed) {
  // A tolerance no two meshes of a curved part meet (on a planar face the
  // two sides' chains lie on one line): every seam is refused, each refused
  // cut is dropped and its slabs meshed as one, down to the whole cloud.
  PointSet points = test::sample_with_normals(test::sphere_mesh(5), 12000, 3);
  points.normals.clear();
  ReconstructOptions options;
  options.delta = 6;
  TilingOptions tiling;
  tiling.tiles = 3;
  tiling.seam_tolerance = 1e-12;
  const TiledResult tiled = reconstruct_tiled(points, options, tiling);
  EXPECT_EQ(tiled.merged_seams, 2u);
  EXPECT_TRUE(tiled.seams.empty());
  ASSERT_EQ(tiled.tiles.size(), 1u);
  std::size_t warnings = 0;
  for (const Warning& w : tiled.merged.warnings) warnings += w.code == "seam_merged";
  EXPECT_EQ(warnings, 2u);
  const TopologyReport t = check_topology(tiled.merged.mesh);
  EXPECT_TRUE(t.closed());
  EXPECT_TRUE(t.manifold());
  EXPECT_FALSE(t.self_intersecting);
}

TEST(Tiling, ASlabThePipelineRefusesAloneIsMeshedWithItsNeighbour) {
  // A box with a long flat strip along x (a scan's stretch of ground): the
  // last slab holds strip points only, all on one plane, which Poisson refuses.
  PointSet points = test::sample_with_normals(test::cube_mesh(), 12000, 2);
  points.normals.clear();
  for (int i = 0; i < 800; ++i)
    for (int j = 0; j < 30; ++j) points.points.push_back({0.6 + 0.025 * i, -0.4 + 0.027 * j, -0.5});
  ReconstructOptions options;
  options.delta = 6;
  TilingOptions tiling;
  tiling.tiles = 3;
  const TiledResult tiled = reconstruct_tiled(points, options, tiling);
  EXPECT_GE(tiled.merged_seams, 1u);
  std::size_t refused = 0;
  for (const Warning& w : tiled.merged.warnings) refused += w.code == "slab_merged";
  EXPECT_GE(refused, 1u);
  EXPECT_EQ(tiled.tiles.size() + tiled.merged_seams, 3u);
  const TopologyReport t = check_topology(tiled.merged.mesh);
  EXPECT_TRUE(t.manifold());
  EXPECT_FALSE(t.self_intersecting);
  EXPECT_GT(tiled.merged.mesh.faces.size(), 0u);
}
