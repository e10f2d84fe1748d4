// The PIF pipeline (7.3.1) end to end on analytic and real models.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "fixtures.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"
#include "sharpmesh/reconstruct.h"

using namespace sharpmesh;

namespace {

PointSet sample(const SurfaceMesh& mesh, std::size_t n, double noise = 0, std::uint64_t seed = 11) {
  SampleOptions options;
  options.count = n;
  options.noise = noise;
  options.seed = seed;
  return sample_mesh(mesh, options);
}

/// The cloud of `sharpmesh sample MESH -n N --seed S`.
PointSet cli_sample(const SurfaceMesh& mesh, std::size_t n, std::uint64_t seed) { return sample(mesh, n, 0, seed); }

/// Manifold, free of self-intersections, closed (or open, for open inputs),
/// and within a Hausdorff distance of the reference (fraction of its diagonal).
void expect_valid_and_close(const SurfaceMesh& result, const SurfaceMesh& reference, double max_hausdorff_fraction,
                            bool closed = true) {
  const TopologyReport t = check_topology(result);
  EXPECT_EQ(t.closed(), closed);
  EXPECT_TRUE(t.manifold());
  EXPECT_FALSE(t.self_intersecting);
  DistanceOptions options;
  options.samples = 50000;
  const DistanceReport d = compare_meshes(result, reference, options);
  EXPECT_LT(d.hausdorff / d.diagonal, max_hausdorff_fraction);
}

}  // namespace

TEST(Reconstruct, SphereGivesAClosedManifoldMeshCloseToTheSphere) {
  const SurfaceMesh sphere = test::sphere_mesh(5);
  ReconstructOptions options;
  const ReconstructResult r = reconstruct(sample(sphere, 20000), options);
  EXPECT_TRUE(r.normals.normals_estimated);
  EXPECT_GT(r.mesh.faces.size(), 500u);
  // Closed: the zero set stays near the data, so the function is not cut
  // (a cut would add an offset sphere inside, meshed and then trimmed).
  EXPECT_FALSE(r.implicit.restricted);
  EXPECT_EQ(r.repairs.trimmed_facets, 0u);
  expect_valid_and_close(r.mesh, sphere, 0.005);
  // The facet estimate that guards --max-facets is within a factor 2 of the truth.
  EXPECT_GT(r.estimated_facets, 0.5 * r.mesh.faces.size());
  EXPECT_LT(r.estimated_facets, 2.0 * r.mesh.faces.size());
}

namespace {

// Dihedral angle (degrees, 180 = flat) at each mesh edge whose end points
// are consecutive vertices of a feature polyline.
std::vector<double> feature_dihedral_angles(const SurfaceMesh& mesh, const std::vector<Polyline>& features) {
  std::map<std::array<double, 3>, std::uint32_t> index_of;
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) index_of[mesh.vertices[v]] = v;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> faces_of;
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      std::uint32_t a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
      faces_of[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  auto normal = [&](std::uint32_t f) {
    const Triangle& t = mesh.faces[f];
    const Vec3 n = cross(mesh.vertices[t[1]] - mesh.vertices[t[0]], mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    return (1.0 / norm(n)) * n;
  };
  std::vector<double> angles;
  for (const Polyline& line : features)
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const std::uint32_t a = index_of.at(line[i]), b = index_of.at(line[i + 1]);
      const auto& faces = faces_of.at({std::min(a, b), std::max(a, b)});
      if (faces.size() != 2) {
        angles.push_back(-1);
        continue;
      }
      angles.push_back(180.0 - std::acos(std::clamp(dot(normal(faces[0]), normal(faces[1])), -1.0, 1.0)) * 180.0 / M_PI);
    }
  return angles;
}

}  // namespace

// Chapter 7 end to end on a cube: the 12 edges come out as chains of mesh
// edges with right dihedral angles, meeting at 8 corner vertices.
TEST(FeaturePreservingReconstruction, CubeKeepsTwelveSharpEdgesAndEightCorners) {
  const SurfaceMesh cube = test::cube_mesh(1.0);
  ReconstructOptions options;
  options.delta = 6;
  const ReconstructResult r = reconstruct(sample(cube, 30000), options);
  EXPECT_EQ(r.normals.normal_origin, NormalOrigin::Cvcm);
  ASSERT_EQ(r.features.graph.polylines.size(), 12u);
  EXPECT_EQ(r.meshing.represented_segments, r.meshing.protected_segments);
  EXPECT_TRUE(r.meshing.uncovered.empty());
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_GT(r.repairs.flattened_vertices, 0u);
  // Every input point is on the mesh: no data-fit retry.
  EXPECT_EQ(r.data_fit.off_data_points, 0u);
  EXPECT_EQ(r.data_fit.off_data_points_before_retry, 0u);
  EXPECT_LT(r.data_fit.max_data_distance, r.average_spacing);
  expect_valid_and_close(r.mesh, cube, 0.005);
  // The feature edges of the mesh: all 12 cube edges, nothing else.
  FeatureEvalOptions eval;
  eval.tolerance = 0.005;
  const FeatureEvaluation e = evaluate_features(r.meshing.feature_edges, polyline_corners(r.meshing.feature_edges), cube, eval);
  EXPECT_GT(e.recall, 0.99);
  EXPECT_GT(e.precision, 0.99);
  EXPECT_EQ(e.recalled_corners, 8u);
  EXPECT_EQ(polyline_corners(r.meshing.feature_edges).size(), 8u);
  const std::vector<double> angles = feature_dihedral_angles(r.mesh, r.meshing.feature_edges);
  ASSERT_FALSE(angles.empty());
  for (double angle : angles) EXPECT_NEAR(angle, 90.0, 5.0);
  // Without features the same delta rounds the edges: the feature mesh is much closer.
  options.feature_mode = FeatureMode::None;
  const ReconstructResult pif = reconstruct(sample(cube, 30000), options);
  DistanceOptions d;
  d.samples = 50000;
  EXPECT_LT(2 * compare_meshes(r.mesh, cube, d).hausdorff, compare_meshes(pif.mesh, cube, d).hausdorff);
}

// A tetrahedron's acute edges: the MST inverted its slanted face, and Poisson
// then closed the surface away from the data (an open, trimmed mesh 2 U off
// at 50k points). With the crease votes it is closed and close.
TEST(FeaturePreservingReconstruction, TetrahedronWithAcuteEdgesGivesAClosedMesh) {
  const SurfaceMesh tetrahedron = test::tetrahedron_mesh();
  const ReconstructResult r = reconstruct(sample(tetrahedron, 30000), {});
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_FALSE(r.implicit.restricted);
  expect_valid_and_close(r.mesh, tetrahedron, 0.012);
}

// Given polylines are protected as they are; a polyline far off the surface
// is reported as an uncovered gap, not meshed into a spike.
TEST(FeaturePreservingReconstruction, GivenPolylinesAndUncoveredGaps) {
  const SurfaceMesh cube = test::cube_mesh(1.0);
  ReconstructOptions options;
  options.delta = 6;
  options.feature_mode = FeatureMode::Given;
  options.given_features = {{{-1, -1, -1}, {1, -1, -1}}, {{-0.5, 0, 3}, {0.5, 0, 3}}};
  const ReconstructResult r = reconstruct(sample(cube, 30000), options);
  ASSERT_EQ(r.meshing.uncovered.size(), 1u);
  EXPECT_NEAR(r.meshing.uncovered[0].center[2], 3.0, 1e-6);
  EXPECT_NEAR(r.meshing.uncovered[0].length, 1.0, 1e-6);
  const double gap = r.meshing.uncovered[0].gap;  // -1: no surface found near it
  EXPECT_TRUE(gap < 0 || gap > 1.5) << gap;
  // The one given cube edge is a chain of mesh edges; the other edges are
  // rounded as in PIF.
  ASSERT_EQ(r.meshing.feature_edges.size(), 1u);
  EXPECT_NEAR(distance(r.meshing.feature_edges[0].front(), r.meshing.feature_edges[0].back()), 2.0, 1e-9);
  EXPECT_EQ(r.meshing.represented_segments, r.meshing.protected_segments);
  expect_valid_and_close(r.mesh, cube, 0.05);
}

// Given polylines as CAD exports them: the cube's top and bottom outlines as
// loops through its corners, their ends 4e-16 apart, and its vertical
// edges, their ends 4e-16 off the loops' corners, are protected as its 12
// edges. CGAL's curves may meet only at their ends (even with exact ends,
// 185 of 1,419 protected segments became mesh edges and 2 corners of 8
// were kept), and CGAL 5.5 takes ends a rounding error apart for two
// corners (couplingdown 50k, sampling seed 7, hung walking such a loop).
TEST(FeaturePreservingReconstruction, PolylineEndsARoundingErrorApartAreJoined) {
  const SurfaceMesh cube = test::cube_mesh(1.0);
  ReconstructOptions options;
  options.delta = 6;
  options.feature_mode = FeatureMode::Given;
  const double e = 4e-16;
  for (double z : {-1.0, 1.0}) options.given_features.push_back({{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}, {-1, -1, z + e}});
  for (double x : {-1.0, 1.0})
    for (double y : {-1.0, 1.0}) options.given_features.push_back({{x, y, -1 + e}, {x, y, 0}, {x + e, y, 1}});
  SampleOptions sampling;  // with the facets' normals: sharp at the edges, as CVCM normals are
  sampling.count = 30000;
  sampling.seed = 11;
  sampling.with_normals = true;
  const ReconstructResult r = reconstruct(sample_mesh(cube, sampling), options);
  EXPECT_TRUE(r.meshing.uncovered.empty());
  EXPECT_EQ(r.meshing.represented_segments, r.meshing.protected_segments);
  EXPECT_EQ(polyline_corners(r.meshing.feature_edges).size(), 8u);
  FeatureEvalOptions eval;
  eval.tolerance = 0.005;
  EXPECT_GT(evaluate_features(r.meshing.feature_edges, polyline_corners(r.meshing.feature_edges), cube, eval).recall, 0.99);
  expect_valid_and_close(r.mesh, cube, 0.005);
}

// Open surfaces: a square sheet gives an open mesh that stays on the sheet
// instead of Poisson's closing surface.
TEST(FeaturePreservingReconstruction, OpenSheetIsTrimmedToTheData) {
  PointSet sheet;
  for (int i = 0; i <= 100; ++i)
    for (int j = 0; j <= 100; ++j) sheet.points.push_back({i / 100.0 + 0.002 * (j % 3), j / 100.0, 0.05 * std::sin(3.0 * i / 100.0)});
  ReconstructOptions options;
  options.feature_mode = FeatureMode::None;
  const ReconstructResult r = reconstruct(sheet, options);
  EXPECT_TRUE(r.implicit.restricted);  // Poisson's closing sheet leaves the data
  EXPECT_GT(r.repairs.trimmed_facets, 0u);
  EXPECT_GT(r.boundary_edges, 0u);
  for (const Vec3& v : r.mesh.vertices) EXPECT_LT(std::abs(v[2] - 0.05 * std::sin(3.0 * v[0])), 0.03);
  // The boundary is cut along the data's edge, not left overhanging it by
  // the trim distance (about 5 spacings).
  EXPECT_GT(r.repairs.clipped_facets, 0u);
  const double margin = 1.5 * r.average_spacing;
  for (const Vec3& v : r.mesh.vertices) {
    EXPECT_GT(v[0], -margin);
    EXPECT_LT(v[0], 1.004 + margin);
    EXPECT_GT(v[1], -margin);
    EXPECT_LT(v[1], 1 + margin);
  }
  EXPECT_TRUE(check_topology(r.mesh).manifold());
}

// 30k points: PIF rounds the sharp edges, whose error dominates; the 200k
// claim (< 1% of the diagonal) is the CLI test cli.fandisk-200k.
TEST(CgalModels, FandiskThirtyThousandPointsWithinTwoPercentOfTheDiagonal) {
  const std::string path = test::data_file("meshes/fandisk.off");
  if (path.empty()) GTEST_SKIP() << "CGAL data not fetched (scripts/fetch-data)";
  const SurfaceMesh fandisk = read_mesh(path);
  ReconstructOptions pif;
  pif.feature_mode = FeatureMode::None;
  const ReconstructResult r = reconstruct(sample(fandisk, 30000), pif);
  expect_valid_and_close(r.mesh, fandisk, 0.02);
}

// The feature pipeline on the same sparse cloud: closed, manifold, and
// closer to the model than PIF at the same delta, along its sharp edges too.
// Most protected segments are mesh edges: 85% with fitted corner points and
// the capped r_junc (853 of 999; the rest lie off the implicit surface
// around junctions and are reported as gaps), 97% with the thesis's
// polylines (but 5,400 facets at 3.0-3.4 U instead of 6,000 at 1.5-1.9 U
// over two CLI samples).
TEST(CgalModels, FandiskThirtyThousandPointsCloserThanPif) {
  const std::string path = test::data_file("meshes/fandisk.off");
  if (path.empty()) GTEST_SKIP() << "CGAL data not fetched (scripts/fetch-data)";
  const SurfaceMesh fandisk = read_mesh(path);
  const PointSet cloud = sample(fandisk, 30000);
  const ReconstructResult r = reconstruct(cloud, ReconstructOptions{});
  EXPECT_GT(r.meshing.represented_segments, 0.8 * r.meshing.protected_segments);
  expect_valid_and_close(r.mesh, fandisk, 0.015);
  ReconstructOptions pif;
  pif.feature_mode = FeatureMode::None;
  DistanceOptions d;
  d.samples = 50000;
  const DistanceReport ours = compare_meshes(r.mesh, fandisk, d), theirs = compare_meshes(reconstruct(cloud, pif).mesh, fandisk, d);
  EXPECT_LT(ours.hausdorff, theirs.hausdorff);
  EXPECT_LT(ours.sharp_mean, 0.5 * theirs.sharp_mean);
  // The fitted corner points against the thesis's polylines, both without
  // snapping (which moves more vertices for the thesis's polylines and
  // evens them out: 1.89 and 1.88 U with it, 1.89 and 2.17 U without).
  ReconstructOptions fitted, thesis;
  fitted.snap_vertices = thesis.snap_vertices = false;
  thesis.features.fit_corner_points = false;
  EXPECT_LT(compare_meshes(reconstruct(cloud, fitted).mesh, fandisk, d).hausdorff,
            compare_meshes(reconstruct(cloud, thesis).mesh, fandisk, d).hausdorff);
}

// CGAL's couplingdown at 50k points: chamfers 1.4 spacings wide, a thin
// wall, rims that come close to each other. Their polylines can make CGAL's
// Mesh_3 fail ("already inserted on surface") or run away in its manifold
// repair; those polylines are dropped and reported (the policy is tested by
// injection in refinement_retries_test.cpp), and the result is closed,
// manifold and close to the model, with most polylines kept. A runaway, if
// one happens, is stopped before the facet count the data suggests. With
// the thesis's polylines (corner points left out) and with the default's.
TEST(CgalModels, CouplingdownMeshesDespiteCloseFeatures) {
  const std::string path = test::data_file("meshes/couplingdown.off");
  if (path.empty()) GTEST_SKIP() << "CGAL data not fetched (scripts/fetch-data)";
  const SurfaceMesh part = read_mesh(path);
  ReconstructOptions options;
  options.features.fit_corner_points = false;
  const ReconstructResult r = reconstruct(sample(part, 50000), options);
  EXPECT_FALSE(r.meshing.refinement_runaway);
  EXPECT_LT(static_cast<double>(r.meshing.runaway_stopped_at), r.estimated_facets);
  EXPECT_GT(r.features.graph.polylines.size(), 10u);
  std::size_t refused = 0;
  for (const UncoveredGap& gap : r.meshing.uncovered) refused += gap.refused_by_mesher;
  EXPECT_LE(refused, r.features.graph.polylines.size() / 2);
  expect_valid_and_close(r.mesh, part, 0.02);
}

TEST(CgalModels, CouplingdownDefaultPipelineGivesAValidMesh) {
  const std::string path = test::data_file("meshes/couplingdown.off");
  if (path.empty()) GTEST_SKIP() << "CGAL data not fetched (scripts/fetch-data)";
  const SurfaceMesh part = read_mesh(path);
  const ReconstructResult r = reconstruct(cli_sample(part, 50000, 1), ReconstructOptions{});
  EXPECT_GT(r.features.fitted_corner_points, 0u);
  EXPECT_FALSE(r.meshing.refinement_stalled);
  EXPECT_FALSE(r.meshing.refinement_runaway);
  expect_valid_and_close(r.mesh, part, 0.02);
}

// PIF rounds the cube's edges: the points along them lie off the mesh, but
// their normals agree with its facets, so no data-fit retry runs (by
// distance alone PIF retried for nothing on 8 of the 15 corpus models).
TEST(Reconstruct, PointsOffARoundedEdgeStartNoDataFitRetry) {
  const SurfaceMesh cube = test::cube_mesh(1.0);
  ReconstructOptions pif;
  pif.feature_mode = FeatureMode::None;
  const ReconstructResult r = reconstruct(sample(cube, 50000), pif);
  EXPECT_GT(r.data_fit.off_data_points, 0u);
  EXPECT_EQ(r.data_fit.off_data_against, 0u);
  EXPECT_EQ(r.data_fit.data_fit_retries, 0u);
}

// couplingdown sampled with seed 2 (50k points): the MST inverts the wall of
// a hole 5 spacings wide (about 130 normals), the sign repair cannot undo it
// (the Poisson function agrees with them: it closes the hole) and the mesh
// ended 3.17 U (diagonal / 200, `sharpmesh eval`) off, its wall points up to 2.9 spacings
// inside the solid. The data-fit check finds them; the retry with their
// normals flipped opens the hole (1.76 U, no point off). Here without the
// winding-number repair, which finds that wall before Poisson (next test),
// with the MST grown from one seed (the occupancy anchors orient that wall
// right from the start) and without the Poisson vertices in thin parts
// (with them 14 points stay off the first mesh, none against it, and no
// retry starts).
TEST(CgalModels, PointsOffTheMeshGetTheirNormalsFlippedAndARetry) {
  const std::string path = test::data_file("meshes/couplingdown.off");
  if (path.empty()) GTEST_SKIP() << "CGAL data not fetched (scripts/fetch-data)";
  const SurfaceMesh part = read_mesh(path);
  ReconstructOptions options;
  options.delta = 1.5;
  options.repair_enclosed_normals = false;
  options.anchor_orientation = false;
  options.thin_part_vertices = false;
  const ReconstructResult r = reconstruct(cli_sample(part, 50000, 2), options);
  EXPECT_EQ(r.normals.enclosed_flipped_normals, 0u);
  EXPECT_GE(r.data_fit.off_data_points_before_retry, 10u);
  EXPECT_GE(r.data_fit.data_fit_retries, 1u);
  EXPECT_GT(r.data_fit.off_data_flips, 0u);
  EXPECT_LE(4 * r.data_fit.off_data_points, 3 * r.data_fit.off_data_points_before_retry);
  expect_valid_and_close(r.mesh, part, 0.011);  // 2.2 U; 3.17 U without the retry
}

// The same cloud (MST from one seed) with the winding-number repair: the
// wall is flipped back before Poisson and the first mesh already fits the
// data. With the default anchors as well, nothing is left off the mesh.
TEST(CgalModels, TheWindingRepairFlipsTheInvertedHoleWallBeforePoisson) {
  const std::string path = test::data_file("meshes/couplingdown.off");
  if (path.empty()) GTEST_SKIP() << "CGAL data not fetched (scripts/fetch-data)";
  const SurfaceMesh part = read_mesh(path);
  ReconstructOptions options;
  options.delta = 1.5;
  options.anchor_orientation = false;
  const ReconstructResult repaired = reconstruct(cli_sample(part, 50000, 2), options);
  EXPECT_GT(repaired.normals.enclosed_flipped_normals, 0u);  // which normals: Normals.InvertedBoreWallIsFlippedBackByTheWindingNumber
  EXPECT_LT(repaired.data_fit.off_data_points_before_retry, 10u);
  EXPECT_EQ(repaired.data_fit.data_fit_retries, 0u);
  expect_valid_and_close(repaired.mesh, part, 1.5 / 200);
  options.anchor_orientation = true;
  const ReconstructResult anchored = reconstruct(cli_sample(part, 50000, 2), options);
  EXPECT_LT(anchored.data_fit.off_data_points_before_retry, 10u);
  expect_valid_and_close(anchored.mesh, part, 1.5 / 200);
}

// couplingdown 50k (sampling seed 1) at delta 1.5: its two spike corners
// (three faces, the top one a wedge of 70 degrees) and the top of a wall 1.3
// spacings thick are rounded by Poisson beyond what their protecting balls
// reach; the mesh vertices nearest to the corners and to the data points it
// misses are moved onto them. Measured 1.37 U (diagonal / 200); 1.75 U
// without snapping. CGAL's "might result in a crash" warning about its ball
// shrinking goes to the report, not to stderr.
TEST(CgalModels, CouplingdownCornersAndThinWallTopsAreSnappedOnto) {
  const std::string path = test::data_file("meshes/couplingdown.off");
  if (path.empty()) GTEST_SKIP() << "CGAL data not fetched (scripts/fetch-data)";
  const SurfaceMesh part = read_mesh(path);
  ReconstructOptions options;
  options.delta = 1.5;
  testing::internal::CaptureStderr();
  const ReconstructResult r = reconstruct(cli_sample(part, 50000, 1), options);
  const std::string messages = testing::internal::GetCapturedStderr();
  EXPECT_EQ(messages.find("features protection"), std::string::npos) << messages;
  EXPECT_GE(r.repairs.snapped_corners, 2u);
  EXPECT_GE(r.repairs.snapped_to_data, 5u);
  EXPECT_LT(r.repairs.unsnapped_vertices, r.repairs.snapped_corners + r.repairs.snapped_to_data);
  expect_valid_and_close(r.mesh, part, 1.5 / 200);
}

// CGAL's blade at 50k points: a thin open plate. Poisson closes it; the
// function is restricted to a band around the data, negative in too small a
// volume for random points of the domain to find, and the data seeds start
// the refinement (refusing the function as one-signed gave no mesh at all).
// The result is open, manifold and within 1 U (diagonal / 200) both ways.
// The plate is about two spacings thick: its two faces are meshed apart
// (thin_part_vertices, the facets bounded by the thickness), and the mesh
// stays open where the reference is.
TEST(CgalModels, BladeOpenPlateGivesAnOpenMeshCloseToIt) {
  const std::string path = test::data_file("meshes/blade.off");
  if (path.empty()) GTEST_SKIP() << "CGAL data not fetched (scripts/fetch-data)";
  const SurfaceMesh blade = read_mesh(path);
  const ReconstructResult r = reconstruct(sample(blade, 50000), ReconstructOptions{});
  EXPECT_GT(r.boundary_edges, 0u);
  EXPECT_GT(r.implicit.thin_part_vertices, 0u);
  expect_valid_and_close(r.mesh, blade, 1.0 / 200, /*closed=*/false);
}

// CGAL's spool at 50k points: in its flanges the convolved VCM is isotropic
// and its main axis no normal; those points take jet normals, and the
// closed model comes out closed (with CVCM normals throughout the MST
// inverted 18% of them and the trimmed mesh had 600 boundary edges).
TEST(CgalModels, SpoolFlangesKeepTheSurfaceClosed) {
  const std::string path = test::data_file("meshes/spool.off");
  if (path.empty()) GTEST_SKIP() << "CGAL data not fetched (scripts/fetch-data)";
  const SurfaceMesh spool = read_mesh(path);
  const ReconstructResult r = reconstruct(sample(spool, 50000), ReconstructOptions{});
  EXPECT_GT(r.normals.isotropic_cvcm_normals, 0u);
  EXPECT_EQ(r.boundary_edges, 0u);
  expect_valid_and_close(r.mesh, spool, 0.03);
}

// CGAL's star (a cube with six pyramidal spikes): at the needle-like tips
// the CVCM's main axis runs along the spike, and the CVCM normals gave a
// Poisson function that disagreed with them (refused). Automatic normals
// stay CVCM normals overall and take jet normals where the CVCM is
// isotropic, and the function agrees with them.
TEST(CgalModels, SpikyStarKeepsCvcmNormalsAndTakesJetOnesWhereTheCvcmIsIsotropic) {
  const std::string path = test::data_file("meshes/star.off");
  if (path.empty()) GTEST_SKIP() << "CGAL data not fetched (scripts/fetch-data)";
  const SurfaceMesh star = read_mesh(path);
  ReconstructOptions options;
  options.delta = 7;
  // Sample-dependent: with CVCM normals throughout, 30k points (seed 11) and
  // 40k (seed 1) gave CGAL a function inverted against them.
  const PointSet cloud = sample(star, 30000);
  const ReconstructResult r = reconstruct(cloud, options);
  // Automatic normals: the isotropic CVCM at the tips is replaced by jet
  // normals there, and the function agrees with its normals.
  EXPECT_EQ(r.normals.normal_origin, NormalOrigin::Cvcm);
  EXPECT_GT(r.normals.isotropic_cvcm_normals, 0u);
  EXPECT_GT(r.implicit.normal_agreement, 0.9);
  expect_valid_and_close(r.mesh, star, 0.04);  // the spike tips are cut (reported as uncovered gaps)
  // Explicit CVCM normals (7.4 throughout) are not replaced. CGAL's Poisson
  // used to come out inverted as a whole on them (agreement near 0, once
  // taken for inconsistent normals); it is flipped back now.
  options.normal_source = NormalSource::Cvcm;
  const ReconstructResult c = reconstruct(cloud, options);
  EXPECT_EQ(c.normals.normal_origin, NormalOrigin::Cvcm);
  EXPECT_EQ(c.normals.isotropic_cvcm_normals, 0u);
  EXPECT_GT(c.implicit.normal_agreement, 0.9);
  expect_valid_and_close(c.mesh, star, 0.04);
}

// Issue 36: a plate about 2.5 average spacings thick comes out closed, in
// one piece and without self-intersections at the default delta, whose
// facets are twice its thickness: the Poisson function gets vertices
// between the two faces and the facets near them are bounded by the
// thickness.
TEST(Reconstruct, PlateThinnerThanTheFacetsStaysClosed) {
  SurfaceMesh plate = test::cube_mesh(0.5);
  for (Vec3& v : plate.vertices) v[2] *= 0.02;
  const PointSet cloud = sample(plate, 20000);
  ReconstructOptions options;
  const ReconstructResult r = reconstruct(cloud, options);
  EXPECT_LT(0.02, 3 * r.average_spacing);
  EXPECT_GT(r.implicit.thin_part_vertices, 0u);
  EXPECT_GT(r.implicit.thin_points, cloud.size() / 2);
  EXPECT_EQ(check_topology(r.mesh, false).components, 1u);
  expect_valid_and_close(r.mesh, plate, 0.015);  // about two spacings, at the rim
}

// Normals read from a file are checked: consistent ones are used as given;
// per-face sign flips (CGAL's cube.pwn) are re-oriented; all-zero ones
// (CGAL's blobby.xyz) are replaced by estimated normals.
TEST(LargeClouds, InputNormalsAreCheckedBeforePoissonUsesThem) {
  const SurfaceMesh cube = test::cube_mesh(1.0);
  const PointSet consistent = test::sample_with_normals(cube, 30000, 11);
  ASSERT_TRUE(consistent.has_normals());
  ReconstructOptions options;  // the whole Chapter 7 pipeline, as in CubeKeepsTwelveSharpEdgesAndEightCorners
  options.delta = 6;
  const ReconstructResult kept = reconstruct(consistent, options);
  EXPECT_EQ(kept.normals.normal_origin, NormalOrigin::Input);
  EXPECT_GT(kept.normals.input_normal_agreement, 0.99);
  expect_valid_and_close(kept.mesh, cube, 0.005);

  PointSet flipped = consistent;  // the +x, +y and +z faces point inwards
  for (Vec3& n : flipped.normals)
    if (n[0] + n[1] + n[2] > 0.5) n = -1.0 * n;
  const ReconstructResult reoriented = reconstruct(flipped, options);
  EXPECT_EQ(reoriented.normals.normal_origin, NormalOrigin::InputReoriented);
  EXPECT_GT(reoriented.normals.input_normal_agreement, 0.3);
  EXPECT_LT(reoriented.normals.input_normal_agreement, 0.7);
  expect_valid_and_close(reoriented.mesh, cube, 0.005);

  // A slab tapering to a knife edge (about 11 degrees): an MST of PCA
  // normals grown from one seed inverts one face, so right normals would
  // look half wrong; the occupancy anchors keep the comparison honest.
  SurfaceMesh wedge = test::cube_mesh(0.5);
  for (Vec3& v : wedge.vertices) v[2] *= v[0] < 0 ? 0.2 : 0.002;
  ReconstructOptions pif = options;
  pif.feature_mode = FeatureMode::None;
  const ReconstructResult knife = reconstruct(test::sample_with_normals(wedge, 20000, 3), pif);
  EXPECT_EQ(knife.normals.normal_origin, NormalOrigin::Input);
  EXPECT_GT(knife.normals.input_normal_agreement, 0.9);

  PointSet zero = consistent;
  for (Vec3& n : zero.normals) n = {0, 0, 0};
  const ReconstructResult estimated = reconstruct(zero, options);
  EXPECT_TRUE(estimated.normals.normals_estimated);
  EXPECT_TRUE(estimated.normals.input_normals_unusable);
  expect_valid_and_close(estimated.mesh, cube, 0.005);
}

// Normals the orientation got wrong (the MST leaves small inverted groups
// where faces a few spacings wide meet, e.g. in a counterbore of CGAL's
// couplingdown): the Poisson function follows the majority around them, and
// the normals it contradicts are flipped and Poisson solved again. Here 2.5%
// of a sphere's normals, scattered, are inverted: the repair flips those and
// no others. (A large inverted patch, 90 points in one cap, is followed by the
// function instead and stays: Poisson dents the cap; not repaired.)
TEST(Reconstruct, SignRepairFlipsTheNormalsThePoissonFunctionContradicts) {
  const SurfaceMesh sphere = test::sphere_mesh(5);
  PointSet cloud = test::sample_with_normals(sphere, 20000, 11);
  std::size_t inverted = 0;
  for (std::size_t i = 0; i < cloud.size(); i += 40) cloud.normals[i] = -1.0 * cloud.normals[i], ++inverted;
  ReconstructOptions options;
  options.feature_mode = FeatureMode::None;
  const ReconstructResult repaired = reconstruct(cloud, options);
  EXPECT_EQ(repaired.normals.normal_origin, NormalOrigin::Input);  // 97.5% agree with the MST: used as given
  EXPECT_GE(repaired.normals.sign_repaired_normals, inverted - inverted / 50);
  EXPECT_LE(repaired.normals.sign_repaired_normals, inverted + inverted / 50);
  expect_valid_and_close(repaired.mesh, sphere, 0.005);
  options.repair_normal_signs = false;
  EXPECT_EQ(reconstruct(cloud, options).normals.sign_repaired_normals, 0u);
}

// The Poisson function is pulled towards the points with the full weight on
// clean clouds and a twelfth of it on the ones the feature extraction finds
// noisy (a noisy point is no better than the smooth surface); the weight
// used is reported. Given or no features: no noise estimate, full weight.
TEST(Reconstruct, NoisyCloudsTakeTheWeakerPoissonScreening) {
  const SurfaceMesh cube = test::cube_mesh(0.5);
  ReconstructOptions options;
  options.delta = 4;
  const ReconstructResult clean = reconstruct(sample(cube, 20000), options);
  EXPECT_DOUBLE_EQ(clean.implicit.poisson_screening, options.poisson_screening);
  const ReconstructResult noisy = reconstruct(sample(cube, 20000, 0.01), options);
  EXPECT_DOUBLE_EQ(noisy.implicit.poisson_screening, options.poisson_screening_noisy);
  EXPECT_LT(options.poisson_screening_noisy, options.poisson_screening);
  ReconstructOptions pif = options;
  pif.feature_mode = FeatureMode::None;
  EXPECT_DOUBLE_EQ(reconstruct(sample(cube, 20000, 0.01), pif).implicit.poisson_screening, options.poisson_screening);
  ReconstructOptions bad = options;
  bad.poisson_screening_noisy = -1;
  EXPECT_THROW(reconstruct(sample(cube, 2000), bad), InvalidArgument);
}

TEST(Reconstruct, RejectsBadDeltaAndExplodingFacetCounts) {
  const PointSet points = sample(test::sphere_mesh(3), 2000);
  ReconstructOptions options;
  options.delta = 0;
  EXPECT_THROW(reconstruct(points, options), InvalidArgument);
  options.delta = -1;
  EXPECT_THROW(reconstruct(points, options), InvalidArgument);
  options.delta = 1e-4;
  try {
    reconstruct(points, options);
    FAIL() << "a tiny delta must be refused";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("max-facets"), std::string::npos) << e.what();
  }
}

// The thread limit is the call's own (a task arena): the loops inside see
// one thread, and the mesh does not depend on how many threads ran it.
TEST(Reconstruct, OneThreadGivesTheSameMeshAsEveryCore) {
  const PointSet points = sample(test::chamfered_cube_mesh(0.3), 20000);
  ReconstructOptions options;
  options.delta = 6;
  const ReconstructResult every_core = reconstruct(points, options);
  options.threads = 1;
  int most_threads_seen = 0;
  const Progress progress = [&](const std::string&, double) {
    most_threads_seen = std::max(most_threads_seen, tbb::this_task_arena::max_concurrency());
    return true;
  };
  const ReconstructResult one_thread = reconstruct(points, options, progress);
  EXPECT_EQ(most_threads_seen, 1);
  ASSERT_FALSE(one_thread.mesh.faces.empty());
  EXPECT_EQ(one_thread.mesh.vertices, every_core.mesh.vertices);
  EXPECT_EQ(one_thread.mesh.faces, every_core.mesh.faces);
  options.threads = -1;
  EXPECT_THROW(reconstruct(points, options), InvalidArgument);
}

// A hollow box whose walls are about three spacings thick, with a ball in
// its cavity: the cavity's walls face into the cavity and the ball out of
// itself. From the cavity's face, the wall's occupied band reaches the
// outside beyond the outer face, which must not decide its sign.
TEST(Reconstruct, NormalsStageOrientsAThinWalledCavityInwards) {
  const PointSet exact = test::sample_with_normals(test::hollow_box_mesh(0.5, 0.45, 0.25, 4), 40000, 7);
  PointSet bare = exact;
  bare.normals.clear();
  const NormalsResult r = reconstruct_normals(bare);
  const double wall = 0.05 / average_spacing(exact, 6);
  ASSERT_GT(wall, 2.0);
  ASSERT_LT(wall, 4.0);
  std::size_t against = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) against += dot(r.points.normals[i], exact.normals[i]) < 0;
  EXPECT_LT(against, exact.size() / 200) << "walls " << wall << " spacings thick";
}

// The normals stage on its own gives the normals reconstruct() starts from:
// oriented outwards on a closed part away from the origin (the stage runs
// recentred and returns the input's own coordinates), and given consistent
// normals kept as they are.
TEST(Reconstruct, NormalsStageAloneOrientsAClosedPartOutwards) {
  PointSet exact = test::sample_with_normals(test::chamfered_cube_mesh(0.3), 20000, 5);
  for (Vec3& p : exact.points) p = p + Vec3{100, -50, 20};
  PointSet bare = exact;
  bare.normals.clear();
  const NormalsResult r = reconstruct_normals(bare);
  EXPECT_EQ(r.normals.normal_origin, NormalOrigin::Cvcm);
  EXPECT_FALSE(r.features.graph.polylines.empty());
  ASSERT_EQ(r.points.size(), exact.size());
  ASSERT_EQ(r.points.normals.size(), exact.size());
  std::size_t outward = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    EXPECT_LT(norm(r.points.points[i] - exact.points[i]), 1e-9) << i;
    EXPECT_NEAR(norm(r.points.normals[i]), 1.0, 1e-9);
    outward += dot(r.points.normals[i], exact.normals[i]) > 0 ? 1 : 0;
  }
  EXPECT_GT(outward, exact.size() * 995 / 1000);
  ReconstructOptions tiny_facets;
  tiny_facets.delta = 1e-4;  // refused by reconstruct() (max_facets), not by the normals alone
  EXPECT_EQ(reconstruct_normals(bare, tiny_facets).points.size(), exact.size());
  const NormalsResult given = reconstruct_normals(exact);
  EXPECT_EQ(given.normals.normal_origin, NormalOrigin::Input);
  EXPECT_FALSE(given.normals.normals_estimated);
  for (std::size_t i = 0; i < exact.size(); ++i) EXPECT_GT(dot(given.points.normals[i], exact.normals[i]), 0.999) << i;
}

// The repairs' thresholds are options like the others: one reaches its
// stage (no CVCM is isotropic below an anisotropy of 0, every one is below
// an unreachable anisotropy), and values out of range are refused by name.
TEST(Reconstruct, TuningFieldsReachTheirStageAndAreChecked) {
  const PointSet cloud = sample(test::chamfered_cube_mesh(0.3), 10000);
  ReconstructOptions none;
  none.tuning.min_cvcm_anisotropy = 0;
  const NormalsResult kept = reconstruct_normals(cloud, none);
  EXPECT_EQ(kept.normals.normal_origin, NormalOrigin::Cvcm);
  EXPECT_EQ(kept.normals.isotropic_cvcm_normals, 0u);
  ReconstructOptions all;
  all.tuning.min_cvcm_anisotropy = 1e300;
  EXPECT_EQ(reconstruct_normals(cloud, all).normals.isotropic_cvcm_normals, kept.points.size());
  ReconstructOptions bad;
  bad.tuning.snap_max_move = -1;
  EXPECT_THROW(bad.check(cloud.size()), InvalidArgument);
  bad = {};
  bad.tuning.input_normal_consensus = 0.2;
  EXPECT_THROW(bad.check(cloud.size()), InvalidArgument);
  bad = {};
  bad.tuning.repair_one_point_in = 0;
  EXPECT_THROW(bad.check(cloud.size()), InvalidArgument);
}

TEST(Reconstruct, RejectsTooFewPoints) {
  PointSet points;
  points.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_THROW(reconstruct(points), InvalidInput);
}
