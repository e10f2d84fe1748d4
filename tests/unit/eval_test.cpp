// Sampling, sharp edges, topology checks and distances on analytic meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "fixtures.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"

using namespace sharpmesh;

TEST(Sample, PointsLieOnTheCubeAndNoiseStaysWithinItsAmplitude) {
  const SurfaceMesh cube = test::cube_mesh(0.5);
  SampleOptions options;
  options.count = 20000;
  options.seed = 5;
  const PointSet clean = sample_mesh(cube, options);
  ASSERT_EQ(clean.size(), 20000u);
  std::size_t per_face[6] = {0, 0, 0, 0, 0, 0};
  for (const Vec3& p : clean.points) {
    const double m = std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
    EXPECT_NEAR(m, 0.5, 1e-12);
    for (int k = 0; k < 3; ++k)
      if (std::abs(std::abs(p[k]) - 0.5) < 1e-12) { ++per_face[2 * k + (p[k] > 0)]; break; }
  }
  for (std::size_t n : per_face) EXPECT_NEAR(n / 20000.0, 1.0 / 6, 0.015);  // uniform per area
  options.noise = 0.01;
  const PointSet noisy = sample_mesh(cube, options);
  const double amplitude = 0.01 * std::sqrt(3.0);
  for (const Vec3& p : noisy.points) EXPECT_LE(std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}), 0.5 + amplitude);
  EXPECT_EQ(sample_mesh(cube, options).points, noisy.points);  // same seed, same points
}

namespace {
// Distance from `p` to the nearest of `points` (brute force: test sizes only).
double nearest_distance(const Vec3& p, const std::vector<Vec3>& points) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& q : points) best = std::min(best, distance(p, q));
  return best;
}
// Neighbours of each point within `radius`, sorted.
std::vector<std::size_t> sorted_neighbour_counts(const std::vector<Vec3>& points, double radius) {
  std::vector<std::size_t> counts(points.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j)
      if (distance(points[i], points[j]) < radius) ++counts[i], ++counts[j];
  std::sort(counts.begin(), counts.end());
  return counts;
}
}  // namespace

TEST(Sample, MissingPatchesLeaveEmptyBallsOfTheirRadius) {
  const SurfaceMesh sphere = test::sphere_mesh(4);
  SampleOptions options;
  options.count = 4000;
  options.seed = 3;
  const PointSet full = sample_mesh(sphere, options);
  options.missing_patches = 3;
  options.missing_radius = 0.1;
  const PointSet holed = sample_mesh(sphere, options);
  ASSERT_EQ(holed.size(), 4000u);  // the holes cost draws, never the count
  options.missing_patches = 0;
  options.seed = 11;
  const PointSet probes = sample_mesh(sphere, options);
  double widest_full = 0, widest_holed = 0;
  for (const Vec3& p : probes.points) {
    widest_full = std::max(widest_full, nearest_distance(p, full.points));
    widest_holed = std::max(widest_holed, nearest_distance(p, holed.points));
  }
  const double radius = 0.1 * 2 * std::sqrt(3.0);  // of the diagonal of the sphere's box
  EXPECT_LT(widest_full, 0.4 * radius);
  EXPECT_GT(widest_holed, 0.8 * radius);  // a probe near a hole's centre is a radius from any sample
}

TEST(Sample, DensityRatioSpreadsTheLocalDensityByAboutThatRatio) {
  const SurfaceMesh sphere = test::sphere_mesh(4);
  SampleOptions options;
  options.count = 4000;
  options.seed = 2;
  const double radius = 0.3;
  auto spread = [&](const PointSet& s) {
    const std::vector<std::size_t> n = sorted_neighbour_counts(s.points, radius);
    return double(n[n.size() * 95 / 100]) / double(std::max<std::size_t>(1, n[n.size() * 5 / 100]));
  };
  const double uniform = spread(sample_mesh(sphere, options));
  options.density_ratio = 5;
  const PointSet graded = sample_mesh(sphere, options);
  ASSERT_EQ(graded.size(), 4000u);
  EXPECT_LT(uniform, 1.8);
  EXPECT_GT(spread(graded), 3.0) << "uniform spread " << uniform;
  options.density_ratio = 0.5;
  EXPECT_THROW(options.check(), InvalidArgument);
  options.density_ratio = 1;
  options.missing_radius = 0;
  EXPECT_THROW(options.check(), InvalidArgument);
}

TEST(SharpEdges, CubeHasTwelveEdgesSphereNone) {
  const std::vector<Polyline> edges = sharp_edges(test::cube_mesh(0.5));
  EXPECT_EQ(edges.size(), 12u);
  double length = 0;
  for (const Polyline& p : edges) {
    ASSERT_EQ(p.size(), 2u);
    length += distance(p[0], p[1]);
  }
  EXPECT_NEAR(length, 12.0, 1e-12);
  EXPECT_TRUE(sharp_edges(test::sphere_mesh(3)).empty());
  // A cylinder: two closed circles (64 segments each), nothing along the side.
  const std::vector<Polyline> circles = sharp_edges(test::cylinder_mesh(1.0, 2.0, 64));
  ASSERT_EQ(circles.size(), 2u);
  for (const Polyline& c : circles) {
    EXPECT_EQ(c.size(), 65u);
    EXPECT_EQ(c.front(), c.back());
  }
}

TEST(Topology, ClosedManifoldCubeAndItsDefects) {
  const SurfaceMesh cube = test::cube_mesh();
  TopologyReport t = check_topology(cube);
  EXPECT_TRUE(t.closed());
  EXPECT_TRUE(t.manifold());
  EXPECT_FALSE(t.self_intersecting);
  EXPECT_EQ(t.components, 1u);

  SurfaceMesh open = cube;
  open.faces.pop_back();
  t = check_topology(open);
  EXPECT_FALSE(t.closed());
  EXPECT_EQ(t.boundary_edges, 3u);

  // Two cubes sharing one corner vertex: a non-manifold vertex.
  SurfaceMesh two = cube;
  const SurfaceMesh other = test::cube_mesh();
  const auto offset = static_cast<std::uint32_t>(two.vertices.size());
  for (Vec3 v : other.vertices) two.vertices.push_back(v + Vec3{1, 1, 1});
  for (Triangle f : other.faces) {
    for (auto& i : f) i = (i == 0) ? 7 : i + offset;  // corner 0 of the second cube is corner 7 of the first
    two.faces.push_back(f);
  }
  t = check_topology(two);
  EXPECT_EQ(t.non_manifold_vertices, 1u);
  EXPECT_FALSE(t.manifold());

  // Two interpenetrating cubes intersect each other.
  SurfaceMesh crossing = cube;
  for (Vec3 v : other.vertices) crossing.vertices.push_back(v + Vec3{0.3, 0.2, 0.1});
  for (Triangle f : other.faces) crossing.faces.push_back({f[0] + 8, f[1] + 8, f[2] + 8});
  EXPECT_TRUE(check_topology(crossing).self_intersecting);
  EXPECT_TRUE(self_intersecting_faces(cube).empty());
  const auto pairs = self_intersecting_faces(crossing);
  ASSERT_FALSE(pairs.empty());
  for (const auto& [a, b] : pairs) {  // always one face of each cube
    EXPECT_LT(a, 12u);
    EXPECT_GE(b, 12u);
  }

  // Flipping one face breaks consistent orientation.
  SurfaceMesh flipped = cube;
  std::swap(flipped.faces[0][1], flipped.faces[0][2]);
  EXPECT_FALSE(check_topology(flipped, false).orientable);
}

TEST(Distances, IdenticalMeshesAreAtZeroAndAScaledCubeAtItsOffset) {
  const SurfaceMesh cube = test::cube_mesh(0.5);
  DistanceOptions options;
  options.samples = 20000;
  DistanceReport d = compare_meshes(cube, cube, options);
  EXPECT_NEAR(d.hausdorff, 0.0, 1e-12);
  EXPECT_EQ(d.sharp_edge_count, 12u);
  EXPECT_NEAR(d.sharp_edge_length, 12.0, 1e-9);
  const SurfaceMesh bigger = test::cube_mesh(0.51);
  d = compare_meshes(bigger, cube, options);
  // Faces are 0.01 apart, the corners sqrt(3) * 0.01; the small cube's edges
  // lie inside the big one, 0.01 from its nearest faces.
  EXPECT_NEAR(d.mean, 0.01, 1e-3);
  EXPECT_NEAR(d.hausdorff, std::sqrt(3.0) * 0.01, 1e-9);
  EXPECT_NEAR(d.sharp_max, 0.01, 1e-9);
  EXPECT_NEAR(d.diagonal, std::sqrt(3.0), 1e-12);
}

TEST(Distances, RejectsEmptyMeshes) {
  EXPECT_THROW(compare_meshes(SurfaceMesh{}, test::cube_mesh()), InvalidInput);
}

TEST(Distances, PointsToPolylinesUpToHalfTheStep) {
  const std::vector<Polyline> lines = {{{0, 0, 0}, {1, 0, 0}}, {{0, 5, 0}, {0, 5, 1}}};
  const std::vector<Vec3> points = {{0.5, 0.3, 0}, {2, 0, 0}, {0, 5.4, 0.5}};
  const std::vector<double> d = distances_to_polylines(points, lines, 0.01);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_NEAR(d[0], 0.3, 0.005);
  EXPECT_NEAR(d[1], 1.0, 0.005);
  EXPECT_NEAR(d[2], 0.4, 0.005);
  EXPECT_TRUE(std::isinf(distances_to_polylines(points, {}, 0.01)[0]));
  EXPECT_THROW(distances_to_polylines(points, lines, 0.0), InvalidArgument);
}
