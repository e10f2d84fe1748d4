// Compaction (sharpmesh/compact.h): the decimated mesh keeps its topology,
// its sharp edges and corners, the budget and the tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <algorithm>
#include <random>

#include "fixtures.h"
#include "sharpmesh/compact.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/reconstruct.h"

namespace sharpmesh {
namespace {

/// Each facet split into four at its edges' midpoints, `levels` times: the
/// same surface with many more facets.
SurfaceMesh subdivided(SurfaceMesh mesh, int levels) {
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto found = midpoints.find(key);
      if (found != midpoints.end()) return found->second;
      mesh.vertices.push_back(0.5 * (mesh.vertices[a] + mesh.vertices[b]));
      const auto index = static_cast<std::uint32_t>(mesh.vertices.size() - 1);
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<Triangle> faces;
    for (const Triangle& t : mesh.faces) {
      const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      faces.push_back({t[0], ab, ca});
      faces.push_back({ab, t[1], bc});
      faces.push_back({ca, bc, t[2]});
      faces.push_back({ab, bc, ca});
    }
    mesh.faces = std::move(faces);
  }
  return mesh;
}

/// The cube [-1, 1]^3 subdivided, its vertices inside a face moved at random
/// within the face's plane: an irregular fine mesh of an exact cube.
SurfaceMesh fine_cube(int levels, std::uint64_t seed) {
  SurfaceMesh mesh = subdivided(test::cube_mesh(1.0), levels);
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  const double step = 2.0 / (1 << levels);
  for (Vec3& p : mesh.vertices) {
    int on_faces = 0;
    for (double c : p) on_faces += std::abs(std::abs(c) - 1) < 1e-12;
    if (on_faces != 1) continue;
    for (double& c : p)
      if (std::abs(std::abs(c) - 1) > 1e-12) c += jitter(random) * step;
  }
  return mesh;
}

/// Largest distance of a vertex to the surface of the cube [-1, 1]^3.
double farthest_from_unit_cube(const SurfaceMesh& mesh) {
  double farthest = 0;
  for (const Vec3& p : mesh.vertices) {
    const double inside = std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
    farthest = std::max(farthest, std::abs(inside - 1));
  }
  return farthest;
}

double sharp_length(const SurfaceMesh& mesh) {
  double length = 0;
  for (const Polyline& line : sharp_edges(mesh, 30))
    for (std::size_t i = 0; i + 1 < line.size(); ++i) length += distance(line[i], line[i + 1]);
  return length;
}

void expect_valid_closed(const SurfaceMesh& mesh) {
  const TopologyReport topology = check_topology(mesh);
  EXPECT_TRUE(topology.closed());
  EXPECT_TRUE(topology.manifold());
  EXPECT_FALSE(topology.self_intersecting);
  EXPECT_EQ(topology.components, 1u);
}

TEST(Decimation, AFineCubeComesBackAsTheCubeWithItsTwelveEdges) {
  for (std::uint64_t seed : {1, 2, 3}) {
    SurfaceMesh mesh = fine_cube(4, seed);
    ASSERT_EQ(mesh.faces.size(), 3072u);
    DecimationOptions options;
    options.facets = 12;
    const DecimationResult result = decimate(mesh, {}, options);
    expect_valid_closed(mesh);
    EXPECT_EQ(result.output_facets, mesh.faces.size());
    EXPECT_LE(mesh.faces.size(), 24u) << "seed " << seed;
    // Every vertex on the cube and the whole area there: the same surface.
    EXPECT_LT(farthest_from_unit_cube(mesh), 1e-9);
    EXPECT_NEAR(surface_area(mesh), 24.0, 1e-9);
    EXPECT_NEAR(sharp_length(mesh), 24.0, 1e-9);
    EXPECT_EQ(result.corner_vertices, 8u);
  }
}

TEST(Decimation, GivenCurvesAloneKeepTheEdges) {
  SurfaceMesh mesh = fine_cube(3, 4);
  // The cube's edges as polylines through the fine mesh's vertices.
  std::vector<Polyline> curves;
  for (const Polyline& line : sharp_edges(mesh, 30)) curves.push_back(line);
  ASSERT_FALSE(curves.empty());
  DecimationOptions options;
  options.facets = 12;
  options.sharp_angle = 0;  // the curves only
  decimate(mesh, curves, options);
  expect_valid_closed(mesh);
  EXPECT_LT(farthest_from_unit_cube(mesh), 1e-9);
  EXPECT_NEAR(surface_area(mesh), 24.0, 1e-9);
  EXPECT_NEAR(sharp_length(mesh), 24.0, 1e-9);
}

TEST(Decimation, LandsOnTheBudgetAndStaysCloseOnACurvedSurface) {
  SurfaceMesh fine = test::sphere_mesh(5);
  ASSERT_GT(fine.faces.size(), 20000u);
  for (std::size_t budget : {500u, 2000u, 8000u}) {
    SurfaceMesh mesh = fine;
    DecimationOptions options;
    options.facets = budget;
    const DecimationResult result = decimate(mesh, {}, options);
    expect_valid_closed(mesh);
    EXPECT_FALSE(result.budget_missed);
    EXPECT_LE(mesh.faces.size(), budget);
    EXPECT_GE(mesh.faces.size(), budget * 9 / 10);
    // A regular mesh of that many facets is about sqrt(4 pi / (F / 2)) apart,
    // and its sagitta is an eighth of its edge squared: the collapse does no
    // worse than twice that.
    const double edge = std::sqrt(8 * M_PI / double(budget));
    const DistanceReport distances = compare_meshes(mesh, fine);
    EXPECT_LT(distances.hausdorff, 2 * edge * edge / 8) << budget << " facets";
  }
}

TEST(Decimation, ToleranceBoundsTheDistanceToTheFineMesh) {
  const SurfaceMesh fine = test::sphere_mesh(4);
  const double diagonal = bounding_box(fine.vertices).diagonal();
  for (double tolerance : {0.001, 0.004}) {
    SurfaceMesh mesh = fine;
    DecimationOptions options;
    options.tolerance = tolerance;
    decimate(mesh, {}, options);
    expect_valid_closed(mesh);
    // A regular mesh of the sphere whose sagitta e^2 / 8 is the tolerance
    // has about 8 pi / e^2 facets: the collapse gets within 4x of that.
    const double edge = std::sqrt(8 * tolerance * diagonal);
    EXPECT_LT(double(mesh.faces.size()), 4 * 8 * M_PI / (edge * edge)) << "tolerance " << tolerance;
    const DistanceReport distances = compare_meshes(mesh, fine);
    EXPECT_LE(distances.hausdorff, tolerance * diagonal) << "tolerance " << tolerance;
  }
}

TEST(Decimation, TheTwoSidesOfAThinShellNeverCross) {
  // A hollow ball whose wall (0.03) is thinner than the facets of every
  // budget: collapsing one sphere on its own would cut through the other.
  SurfaceMesh shell = test::sphere_mesh(4);
  const SurfaceMesh inner = test::sphere_mesh(4, 0.97);
  const auto offset = static_cast<std::uint32_t>(shell.vertices.size());
  shell.vertices.insert(shell.vertices.end(), inner.vertices.begin(), inner.vertices.end());
  for (const Triangle& t : inner.faces) shell.faces.push_back({t[0] + offset, t[2] + offset, t[1] + offset});
  ASSERT_FALSE(check_topology(shell).self_intersecting);
  for (std::size_t budget : {100u, 400u, 2000u}) {
    SurfaceMesh mesh = shell;
    DecimationOptions options;
    options.facets = budget;
    const DecimationResult result = decimate(mesh, {}, options);
    const TopologyReport topology = check_topology(mesh);
    EXPECT_TRUE(topology.closed() && topology.manifold()) << budget;
    EXPECT_FALSE(topology.self_intersecting) << budget;
    EXPECT_EQ(topology.components, 2u) << budget;
    EXPECT_EQ(result.crossing_pairs, 0u) << budget;
    // The outer sphere's facets may sag into the wall by their sagitta
    // e^2 / 8: with 200 facets a side (e about 0.35) they fit, with 50
    // (e about 0.7) they cannot, and the collapse stops short of the budget.
    if (budget >= 400) EXPECT_LE(mesh.faces.size(), budget) << budget;
    else EXPECT_TRUE(result.budget_missed);
    EXPECT_LT(mesh.faces.size(), shell.faces.size() / 4) << budget;
  }
}

TEST(Decimation, AnOpenSheetKeepsItsBoundaryAndCorners) {
  // The cube's bottom face alone: a square sheet with a free boundary.
  SurfaceMesh cube = fine_cube(4, 5);
  SurfaceMesh sheet;
  sheet.vertices = cube.vertices;
  for (const Triangle& t : cube.faces)
    if (cube.vertices[t[0]][2] < -1 + 1e-12 && cube.vertices[t[1]][2] < -1 + 1e-12 && cube.vertices[t[2]][2] < -1 + 1e-12)
      sheet.faces.push_back(t);
  const std::size_t boundary = count_boundary_edges(sheet);
  ASSERT_GT(boundary, 0u);
  DecimationOptions options;
  options.facets = 2;
  decimate(sheet, {}, options);
  const TopologyReport topology = check_topology(sheet);
  EXPECT_TRUE(topology.manifold());
  EXPECT_FALSE(topology.self_intersecting);
  EXPECT_GT(topology.boundary_edges, 0u);
  EXPECT_NEAR(surface_area(sheet), 4.0, 1e-9);
  EXPECT_LE(sheet.faces.size(), 8u);
}

TEST(Decimation, RefusesANonManifoldMeshAndAnEmptyRequest) {
  SurfaceMesh mesh = test::cube_mesh();
  mesh.faces.push_back(mesh.faces.front());  // an edge with three facets
  DecimationOptions options;
  options.facets = 4;
  EXPECT_NE(test::error_of([&] { decimate(mesh, {}, options); }).find("manifold"), std::string::npos);
  SurfaceMesh cube = test::cube_mesh();
  EXPECT_THROW(decimate(cube, {}, DecimationOptions{}), InvalidArgument);
  options.tolerance = 2;
  EXPECT_THROW(options.check(), InvalidArgument);
}

TEST(Decimation, ReportsProgressAndACancelLeavesTheMeshAsItWas) {
  const SurfaceMesh fine = test::sphere_mesh(4);
  SurfaceMesh mesh = fine;
  DecimationOptions options;
  options.facets = 100;
  std::vector<double> fractions;
  decimate(mesh, {}, options, [&](const std::string&, double f) { return fractions.push_back(f), true; });
  ASSERT_GE(fractions.size(), 2u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_EQ(fractions.back(), 1.0);
  mesh = fine;
  EXPECT_THROW(decimate(mesh, {}, options, [](const std::string&, double f) { return f < 0.5; }), Cancelled);
  EXPECT_EQ(mesh.faces, fine.faces);
  EXPECT_EQ(mesh.vertices, fine.vertices);
}

TEST(Decimation, ReconstructLandsWithinItsBudgetClosedWithTheCubesEdges) {
  const PointSet cloud = test::sample_with_normals(test::cube_mesh(1.0), 20000, 7);
  ReconstructOptions options;
  options.compaction.facets = 200;
  const ReconstructResult result = reconstruct(PointSet{cloud.points, {}, {}}, options);
  expect_valid_closed(result.mesh);
  EXPECT_LE(result.mesh.faces.size(), 200u);
  EXPECT_EQ(result.decimation.output_facets, result.mesh.faces.size());
  EXPECT_GT(result.decimation.input_facets, 1000u);
  // The sharp edges stay within the refinement's error of the cube's.
  EXPECT_NEAR(sharp_length(result.mesh), 24.0, 0.5);
  EXPECT_LT(farthest_from_unit_cube(result.mesh), 0.02);
  // A budget above what delta gives: a finer refinement, then the budget.
  options.compaction.facets = 2 * result.decimation.input_facets;
  const ReconstructResult finer = reconstruct(PointSet{cloud.points, {}, {}}, options);
  expect_valid_closed(finer.mesh);
  EXPECT_LT(finer.d_prime, result.d_prime);
  EXPECT_LE(finer.mesh.faces.size(), options.compaction.facets);
  EXPECT_GE(finer.mesh.faces.size(), options.compaction.facets * 9 / 10);
}

}  // namespace
}  // namespace sharpmesh
