// Walls under roof edges (fill_vertical_walls, sharpmesh/pointset.h): a
// cloud scanned from above gets its missing walls, on the footprint and
// from the ground to the eaves; a closed object gets nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "fixtures.h"
#include "sharpmesh/features.h"
#include "sharpmesh/pointset.h"

using namespace sharpmesh;

namespace {

// A gabled house on flat ground, as an airborne scanner samples it: a
// jittered grid seen from straight above, so the walls hold no point.
constexpr double kX0 = 10, kX1 = 22, kY0 = 14, kY1 = 24, kEave = 6, kRidge = 9, kStep = 0.5;

double roof_height(double x, double y) {
  if (x < kX0 || x > kX1 || y < kY0 || y > kY1) return 0;
  const double half = 0.5 * (kY1 - kY0);
  return kRidge - (kRidge - kEave) * std::abs(y - 0.5 * (kY0 + kY1)) / half;
}

PointSet house_from_above(bool with_normals) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> jitter(-0.3 * kStep, 0.3 * kStep);
  PointSet cloud;
  for (double x = 0; x <= 32; x += kStep)
    for (double y = 0; y <= 38; y += kStep) {
      const double px = x + jitter(random), py = y + jitter(random);
      cloud.points.push_back({px, py, roof_height(px, py)});
      if (with_normals) cloud.normals.push_back({0, 0, 1});
    }
  return cloud;
}

/// Horizontal distance from (x, y) to the footprint's outline.
double to_outline(double x, double y) {
  const double dx = std::max({kX0 - x, 0.0, x - kX1}), dy = std::max({kY0 - y, 0.0, y - kY1});
  if (dx > 0 || dy > 0) return std::hypot(dx, dy);
  return std::min({x - kX0, kX1 - x, y - kY0, kY1 - y});
}

}  // namespace

TEST(Walls, ACloudFromAboveGetsItsWallsOnTheFootprintFromTheGroundToTheRoof) {
  PointSet cloud = house_from_above(false);
  const std::size_t before = cloud.size();
  const double spacing = average_spacing(cloud);
  ASSERT_TRUE(looks_airborne(cloud, spacing));
  const WallResult walls = fill_vertical_walls(cloud, spacing);
  EXPECT_TRUE(walls.airborne);
  EXPECT_TRUE(walls.filled);
  ASSERT_EQ(cloud.size(), before + walls.added_points);
  ASSERT_GT(walls.added_points, 0u);
  for (std::size_t i = before; i < cloud.size(); ++i) {
    const Vec3& p = cloud.points[i];
    EXPECT_LE(to_outline(p[0], p[1]), spacing) << p[0] << " " << p[1];
    const double top = std::max(roof_height(p[0] - 0.01, p[1]), roof_height(std::clamp(p[0], kX0, kX1), std::clamp(p[1], kY0, kY1)));
    EXPECT_GE(p[2], -spacing);
    EXPECT_LE(p[2], top + spacing);
  }
  // Every part of the four walls (gables up to the roof line) has a point
  // within 1.5 spacings.
  std::size_t probes = 0, covered = 0;
  auto probe = [&](double x, double y, double z) {
    ++probes;
    for (const Vec3& p : cloud.points)
      if (std::hypot(p[0] - x, p[1] - y, p[2] - z) <= 1.5 * spacing) {
        ++covered;
        return;
      }
  };
  for (double z = 0.5; z < kEave - 0.5; z += 1) {
    for (double x = kX0 + 0.5; x < kX1; x += 1) probe(x, kY0, z), probe(x, kY1, z);
    for (double y = kY0 + 0.5; y < kY1; y += 1) probe(kX0, y, z), probe(kX1, y, z);
  }
  EXPECT_GE(covered, probes * 95 / 100) << covered << " of " << probes;
}

TEST(Walls, TheAddedPointsNormalsAreHorizontalAndFaceOutOfTheBuilding) {
  PointSet cloud = house_from_above(true);
  const std::size_t before = cloud.size();
  const WallResult walls = fill_vertical_walls(cloud, average_spacing(cloud));
  ASSERT_GT(walls.added_points, 0u);
  ASSERT_EQ(cloud.normals.size(), cloud.size());
  const double cx = 0.5 * (kX0 + kX1), cy = 0.5 * (kY0 + kY1);
  for (std::size_t i = before; i < cloud.size(); ++i) {
    const Vec3& n = cloud.normals[i];
    EXPECT_NEAR(n[2], 0, 1e-12);
    EXPECT_NEAR(std::hypot(n[0], n[1]), 1, 1e-9);
    EXPECT_GT(n[0] * (cloud.points[i][0] - cx) + n[1] * (cloud.points[i][1] - cy), 0);
  }
}

TEST(Walls, AClosedObjectIsNotAirborneAndAutomaticModeLeavesItAlone) {
  for (const SurfaceMesh& mesh : {test::sphere_mesh(3), test::cube_mesh(0.5), test::stepped_prism_mesh(0.3)}) {
    PointSet cloud = test::sample_with_normals(mesh, 20000, 3);
    const std::size_t before = cloud.size();
    const double spacing = average_spacing(cloud);
    EXPECT_FALSE(looks_airborne(cloud, spacing));
    const WallResult walls = fill_vertical_walls(cloud, spacing);
    EXPECT_FALSE(walls.filled);
    EXPECT_EQ(walls.added_points, 0u);
    EXPECT_EQ(cloud.size(), before);
  }
}

TEST(Walls, OffMeansNoPointAddedEvenFromAbove) {
  PointSet cloud = house_from_above(false);
  const std::size_t before = cloud.size();
  WallOptions off;
  off.mode = WallMode::Off;
  const WallResult walls = fill_vertical_walls(cloud, average_spacing(cloud), off);
  EXPECT_TRUE(walls.airborne);
  EXPECT_FALSE(walls.filled);
  EXPECT_EQ(cloud.size(), before);
}

TEST(Walls, BadOptionsAreRefusedByName) {
  PointSet cloud = house_from_above(false);
  WallOptions bad;
  bad.reach = 0;
  try {
    fill_vertical_walls(cloud, 0.5, bad);
    FAIL() << "a zero reach was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("wall reach"), std::string::npos) << e.what();
  }
}

TEST(Walls, AirborneCloudsBoundTheOffsetRadiusInSpacingsObjectsKeepTheThesisOne) {
  FeatureOptions automatic;
  EXPECT_EQ(offset_radius_bound(automatic, true), kSceneOffsetRadius);
  EXPECT_EQ(offset_radius_bound(automatic, false), 0.0);
  FeatureOptions none;
  none.max_offset_radius = 0;
  EXPECT_EQ(offset_radius_bound(none, true), 0.0);

  // A bound that binds: R is that many spacings.
  const PointSet scene = house_from_above(false);
  FeatureOptions bounded;
  bounded.max_offset_radius = 2;
  const FeatureResult small = extract_features(scene, bounded);
  EXPECT_NEAR(small.offset_radius, 2 * small.average_spacing, 1e-9 * small.offset_radius);
  // An object: the thesis's 0.1 of the bounding sphere, automatic or not.
  const PointSet sphere = test::sample_with_normals(test::sphere_mesh(3), 20000, 3);
  const FeatureResult thesis = extract_features(sphere);
  EXPECT_NEAR(thesis.offset_radius, 0.1, 0.005);
}
