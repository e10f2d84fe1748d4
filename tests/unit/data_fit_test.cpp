// The reconstruction's check against its own data (pipeline/data_fit.h).
#include <gtest/gtest.h>

#include "pipeline/data_fit.h"

using namespace sharpmesh;

namespace {

// The unit square at z = 0 (facet normals +z), data on its quarter [0, 0.5]^2.
struct Scene {
  SurfaceMesh square{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  PointSet data;
  Scene() {
    for (int i = 0; i <= 10; ++i)
      for (int j = 0; j <= 10; ++j) add({0.05 * i, 0.05 * j, 0}, {0, 0, 1});
  }
  std::uint32_t add(const Vec3& p, const Vec3& n) {
    data.points.push_back(p);
    data.normals.push_back(n);
    return static_cast<std::uint32_t>(data.points.size() - 1);
  }
};

}  // namespace

TEST(DataFit, PointsOffTheMeshThoseAgainstItAndVerticesWithoutData) {
  Scene s;
  const std::uint32_t agreeing = s.add({0.25, 0.25, 0.3}, {0, 0, 1});  // off, its normal along the facets'
  const std::uint32_t against = s.add({0.3, 0.3, -0.35}, {0, 0, -1});  // off, against them
  s.add({0.1, 0.1, 0.05}, {0, 0, -1});                                 // against but on the mesh
  const detail::DataFit fit = detail::fit_to_data(s.square, s.data.points, s.data.normals, 0.2);
  EXPECT_EQ(fit.off, (std::vector<std::uint32_t>{agreeing, against}));
  EXPECT_EQ(fit.off_and_against, (std::vector<std::uint32_t>{against}));
  EXPECT_NEAR(fit.max_distance, 0.35, 1e-12);
  EXPECT_EQ(fit.invented_vertices, 3u);  // the three corners away from the data's quarter
  EXPECT_TRUE(detail::fit_to_data(s.square, s.data.points, {}, 0.2).off_and_against.empty());
}

TEST(DataFit, FlipsThePatchAroundAnInvertedNormalOnly) {
  Scene s;
  const std::uint32_t a = s.add({0.3, 0.3, -0.35}, {0, 0, -1});
  const std::uint32_t b = s.add({0.33, 0.3, -0.35}, {0, 0, -1});  // near, same way: flipped with it
  const std::uint32_t c = s.add({0.36, 0.3, -0.35}, {0, 0, 1});   // near, the other way: kept
  const std::uint32_t d = s.add({0.8, 0.3, -0.35}, {0, 0, -1});   // same way, far: kept
  EXPECT_EQ(detail::within_reach(s.data.points, {b, c, d}, {a}, 0.1), (std::vector<std::uint32_t>{b, c}));
  EXPECT_EQ(detail::flip_around(s.data, {a}, 0.1), 2u);
  EXPECT_EQ(s.data.normals[a], (Vec3{0, 0, 1}));
  EXPECT_EQ(s.data.normals[b], (Vec3{0, 0, 1}));
  EXPECT_EQ(s.data.normals[c], (Vec3{0, 0, 1}));
  EXPECT_EQ(s.data.normals[d], (Vec3{0, 0, -1}));
}
