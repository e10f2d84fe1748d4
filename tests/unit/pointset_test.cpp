// Point-set toolbox (App. A) on analytic fixtures.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "fixtures.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/pointset.h"

using namespace sharpmesh;

namespace {

PointSet grid(int n, double h, double noise = 0, unsigned seed = 1) {
  PointSet ps;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-noise, noise);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) ps.points.push_back({i * h, j * h, noise > 0 ? u(rng) : 0.0});
  return ps;
}

PointSet sphere_points(std::size_t n, std::uint64_t seed = 3) {
  SampleOptions options;
  options.count = n;
  options.seed = seed;
  return sample_mesh(test::sphere_mesh(4), options);
}

}  // namespace

TEST(AverageSpacing, IsTheMeanDistanceToTheKNearestOtherPoints) {
  // Brute force on a jittered grid: sort the distances to every other point.
  const PointSet ps = grid(25, 0.1, 0.03);
  for (int k : {1, 4, 6}) {
    double total = 0;
    for (const Vec3& p : ps.points) {
      std::vector<double> d;
      for (const Vec3& q : ps.points)
        if (&p != &q) d.push_back(distance(p, q));
      std::sort(d.begin(), d.end());
      for (int j = 0; j < k; ++j) total += d[j] / k;
    }
    EXPECT_NEAR(average_spacing(ps, k), total / ps.size(), 1e-12) << "k = " << k;
  }
}

TEST(AverageSpacing, RejectsBadK) {
  const PointSet ps = grid(3, 1.0);
  EXPECT_THROW(average_spacing(ps, 0), InvalidArgument);
  EXPECT_THROW(average_spacing(ps, 9), InvalidInput);  // 9 points cannot have 9 other neighbours
}

TEST(Outliers, ThreeSigmaRuleRemovesPlantedOutliersAndNothingElse) {
  PointSet ps = grid(40, 0.05, 0.002);
  const std::size_t clean = ps.size();
  for (int i = 0; i < 6; ++i) ps.points.push_back({0.3 * i, 5.0 + i, 3.0 - i});
  SigmaOutlierOptions options;
  options.k = 24;
  EXPECT_EQ(remove_outliers_sigma(ps, options), 6u);
  ASSERT_EQ(ps.size(), clean);
  for (const Vec3& p : ps.points) EXPECT_LT(std::abs(p[2]), 0.01);
}

// A dense patch, a patch 16 times sparser (as ground far from the cameras
// is, in tracks from images) and isolated points: the thesis's global rule
// removes the sparse patch wholesale, the relative rule keeps it.
TEST(Outliers, RelativeThreeSigmaRuleKeepsSparseRegionsAndRemovesIsolatedPoints) {
  PointSet ps = grid(60, 0.02, 0.0005);
  const std::size_t dense = ps.size();
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) ps.points.push_back({3.0 + 0.08 * i, 0.08 * j, 0.0});
  const std::size_t sparse = ps.size() - dense;
  for (int i = 0; i < 6; ++i) ps.points.push_back({0.3 * i, 3.0 + 0.7 * i, 1.5 - 0.4 * i});
  SigmaOutlierOptions options;
  options.k = 24;
  const std::vector<Vec3> patches(ps.points.begin(), ps.points.begin() + static_cast<std::ptrdiff_t>(dense + sparse));
  const std::vector<bool> global = sigma_outliers(patches, options);  // isolated points would inflate its sigma
  options.relative = true;
  const std::vector<bool> relative = sigma_outliers(ps.points, options);
  std::size_t global_sparse = 0, relative_sparse = 0, relative_dense = 0, relative_isolated = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (i < dense) relative_dense += relative[i];
    else if (i < dense + sparse) global_sparse += global[i], relative_sparse += relative[i];
    else relative_isolated += relative[i];
  }
  EXPECT_GT(global_sparse, sparse / 2) << "the fixture should defeat the global rule";
  EXPECT_EQ(relative_sparse, 0u);
  EXPECT_EQ(relative_dense, 0u);
  EXPECT_EQ(relative_isolated, 6u);
}

TEST(Outliers, PercentageRemovesTheMostIsolatedPoints) {
  PointSet ps = grid(20, 0.05);
  for (int i = 0; i < 4; ++i) ps.points.push_back({10.0 * (i + 1), 0, 0});
  PercentageOutlierOptions options;
  options.k = 8;
  options.percentage = 100.0 * 4 / ps.size();
  EXPECT_EQ(remove_outliers_percentage(ps, options), 4u);
  for (const Vec3& p : ps.points) EXPECT_LT(p[0], 1.0);
  EXPECT_THROW(remove_outliers_percentage(ps, {8, 120.0}), InvalidArgument);
}

TEST(Simplify, GridKeepsOnePointPerCell) {
  PointSet copy = grid(40, 0.1);
  grid_simplify(copy, 0.2001);
  EXPECT_EQ(copy.size(), 20u * 20u);
  EXPECT_THROW(grid_simplify(copy, 0.0), InvalidArgument);
  // Points at one location (a single point, or the two equal midpoints of
  // a pair of points facing each other) are one cell, not an error.
  for (std::size_t n : {1u, 2u, 5u}) {
    PointSet same{std::vector<Vec3>(n, Vec3{1, 2, 3}), std::vector<Vec3>(n, Vec3{0, 0, 1}), {}};
    EXPECT_EQ(grid_simplify(same, 0.1), n - 1);
    ASSERT_EQ(same.size(), 1u);
    EXPECT_EQ(same.normals.size(), 1u);
  }
  PointSet bad{{{0, 0, 0}, {std::nan(""), 0, 0}}, {}, {}};
  EXPECT_THROW(grid_simplify(bad, 0.1), InvalidInput);
}

TEST(Simplify, ThinningKeepsPointsApartAndTheFirstOfEachPair) {
  PointSet ps = grid(20, 1.0);  // 400 points 1 apart, then a near copy of each
  const std::size_t n = ps.size();
  for (std::size_t i = 0; i < n; ++i) ps.points.push_back(ps.points[i] + Vec3{0.2, 0.1, 0.0});
  const std::vector<Vec3> originals(ps.points.begin(), ps.points.begin() + n);
  EXPECT_EQ(thin_close_points(ps, 0.5), n);
  EXPECT_EQ(ps.points, originals);
  EXPECT_EQ(thin_close_points(ps, 0.99), 0u);
  EXPECT_EQ(thin_close_points(ps, 1.01), 200u);  // every other point of each row is within 1
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (std::size_t j = i + 1; j < ps.size(); ++j) EXPECT_GE(distance(ps.points[i], ps.points[j]), 1.01);
  EXPECT_THROW(thin_close_points(ps, 0.0), InvalidArgument);
  EXPECT_THROW(thin_close_points(ps, std::nan("")), InvalidArgument);
}

TEST(Simplify, RandomIsExactAndReproducible) {
  PointSet a = grid(20, 1.0), b = grid(20, 1.0), c = grid(20, 1.0);
  EXPECT_EQ(random_simplify(a, 25.0, 7), 100u);
  random_simplify(b, 25.0, 7);
  random_simplify(c, 25.0, 8);
  EXPECT_EQ(a.size(), 300u);
  EXPECT_EQ(a.points, b.points);
  EXPECT_NE(a.points, c.points);
}

TEST(JetSmoothing, ReducesNoiseOnAPlane) {
  PointSet ps = grid(40, 0.05, 0.01);
  auto rms_z = [](const PointSet& s) {
    double sum = 0;
    for (const Vec3& p : s.points) sum += p[2] * p[2];
    return std::sqrt(sum / s.size());
  };
  const double before = rms_z(ps);
  jet_smooth(ps, {24});
  EXPECT_LT(rms_z(ps), before / 2);
  EXPECT_THROW(jet_smooth(ps, {3}), InvalidArgument);
}

TEST(Normals, SphereNormalsAreRadialAndOrientedOutward) {
  for (NormalMethod method : {NormalMethod::Pca, NormalMethod::Jet}) {
    PointSet ps = sphere_points(5000);
    estimate_normals(ps, {method, 18});
    EXPECT_EQ(orient_normals_mst(ps, {18, true}), 0u);
    std::size_t outward = 0;
    double worst = 1;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const double c = dot(ps.normals[i], (1.0 / norm(ps.points[i])) * ps.points[i]);
      outward += c > 0;
      worst = std::min(worst, std::abs(c));
    }
    EXPECT_EQ(outward, ps.size());
    EXPECT_GT(worst, 0.95);
  }
}

// Normals at a subset of the points, neighbours from the whole set: the
// same lines as the full estimate there, and nothing changed elsewhere.
TEST(Normals, EstimatesAtGivenPointsOnly) {
  PointSet all = sphere_points(4000);
  NormalEstimationOptions jet;  // App. A.7: jet, k = 18
  estimate_normals(all, jet);
  PointSet some = sphere_points(4000);
  some.normals.assign(some.size(), Vec3{0, 0, 7});
  std::vector<std::uint32_t> indices;
  for (std::uint32_t i = 0; i < some.size(); i += 5) indices.push_back(i);
  estimate_normals_at(some, indices, jet);
  for (std::uint32_t i = 0; i < some.size(); ++i) {
    if (i % 5 != 0) {
      EXPECT_EQ(some.normals[i], (Vec3{0, 0, 7}));
      continue;
    }
    EXPECT_NEAR(std::abs(dot(some.normals[i], all.normals[i])), 1.0, 1e-6);
    const Vec3 radial = (1.0 / norm(some.points[i])) * some.points[i];
    EXPECT_GT(std::abs(dot(some.normals[i], radial)), 0.99);
  }
  indices.push_back(static_cast<std::uint32_t>(some.size()));
  EXPECT_THROW(estimate_normals_at(some, indices, jet), InvalidArgument);
}

// Next to a crease a centred neighbourhood straddles two faces; a shifted
// one (the best-fitting plane among the neighbours' neighbourhoods) lies on
// the point's own face. A cube's points within one spacing of an edge.
TEST(Normals, ShiftedNeighbourhoodsKeepTheFaceNormalNextToACrease) {
  const PointSet truth = test::sample_with_normals(test::cube_mesh(1.0), 24000, 5);  // spacing about 0.03
  std::vector<std::uint32_t> near_edges;
  for (std::uint32_t i = 0; i < truth.size(); ++i) {
    int at_face = 0;
    for (int axis = 0; axis < 3; ++axis) at_face += std::abs(truth.points[i][axis]) > 1 - 0.03;
    if (at_face >= 2) near_edges.push_back(i);
  }
  ASSERT_GT(near_edges.size(), 300u);
  auto mean_error_deg = [&](const PointSet& estimated) {
    double sum = 0;
    for (std::uint32_t i : near_edges)
      sum += std::acos(std::min(1.0, std::abs(dot(estimated.normals[i], truth.normals[i])))) * 180 / M_PI;
    return sum / static_cast<double>(near_edges.size());
  };
  PointSet jet{truth.points, {}, {}};
  estimate_normals_at(jet, near_edges, {NormalMethod::Jet, 18});
  PointSet shifted{truth.points, {}, {}};
  estimate_shifted_normals_at(shifted, near_edges, {8, 18});
  EXPECT_GT(mean_error_deg(jet), 10.0);
  EXPECT_LT(mean_error_deg(shifted), 3.0);
  for (std::uint32_t i = 0; i < shifted.size(); ++i)
    if (!std::binary_search(near_edges.begin(), near_edges.end(), i)) {
      ASSERT_EQ(shifted.normals[i], (Vec3{0, 0, 0}));
    }
  EXPECT_THROW(estimate_shifted_normals_at(shifted, near_edges, {4, 18}), InvalidArgument);
}

// The toolbox's `clean --normals shifted --orient`: jet normals oriented by
// the tangent MST, then crease-aware ones with their signs.
TEST(Clean, CreaseAwareNormalsAreOrientedAndSharpAtTheEdges) {
  const PointSet truth = test::sample_with_normals(test::cube_mesh(1.0), 24000, 5);
  PointSet cloud{truth.points, {}, {}};
  CleanOptions options;
  options.normals = NormalEstimationOptions{NormalMethod::Jet, 18};
  options.crease_aware_normals = ShiftedNormalOptions{};
  options.orientation = CleanOptions::Orientation::TangentMst;
  const CleanStats stats = clean_point_set(cloud, options);
  ASSERT_EQ(cloud.size(), truth.size());
  EXPECT_EQ(stats.stages.back().name, "crease-aware normals");
  std::size_t inward = 0, off = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double c = dot(cloud.normals[i], truth.normals[i]);
    inward += c < -0.5;  // inverted; a point on an edge may take the other face's normal (c = 0)
    off += std::abs(c) < std::cos(10 * M_PI / 180);
  }
  EXPECT_EQ(inward, 0u);
  EXPECT_LT(off, cloud.size() / 200);  // jet normals: 2,116 (8.8%) more than 10 degrees off
  CleanOptions unsigned_only;
  unsigned_only.crease_aware_normals = ShiftedNormalOptions{};
  EXPECT_THROW(unsigned_only.check(), InvalidArgument);
}

TEST(Normals, OrientationNeedsNormals) {
  PointSet ps = sphere_points(100);
  EXPECT_THROW(orient_normals_mst(ps), InvalidArgument);
}

TEST(Determinism, ResultsDoNotDependOnTheThreadCount) {
  auto run = [](int threads) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
    PointSet ps = sphere_points(3000);
    jet_smooth(ps, {24});
    estimate_normals(ps, {NormalMethod::Jet, 18});
    orient_normals_mst(ps, {18, true});
    remove_outliers_sigma(ps, {24, 3.0});
    return std::make_pair(ps, average_spacing(ps, 6));
  };
  const auto one = run(1), two = run(2);
  EXPECT_EQ(one.first.points, two.first.points);
  EXPECT_EQ(one.first.normals, two.first.normals);
  EXPECT_EQ(one.second, two.second);
}

TEST(CheckPointSet, RejectsEmptyNanAndCoincidentSets) {
  PointSet ps;
  EXPECT_THROW(check_point_set(ps, 1, "test"), InvalidInput);
  ps.points = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  EXPECT_THROW(check_point_set(ps, 1, "test"), InvalidInput);
  ps.points = {{0, 0, 0}, {1, 0, 0}, {NAN, 0, 0}};
  EXPECT_THROW(check_point_set(ps, 1, "test"), InvalidInput);
}

namespace {

// Fraction of normals pointing against the exact ones (after undoing a global flip).
double flipped_fraction(const PointSet& oriented, const PointSet& truth) {
  std::size_t against = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) against += dot(oriented.normals[i], truth.normals[i]) < 0;
  const double f = static_cast<double>(against) / static_cast<double>(truth.size());
  return std::min(f, 1 - f);
}

}  // namespace

TEST(Normals, TangentMstDoesNotFlipAcrossAThinWall) {
  // A 1 x 1 x 0.02 slab: the 18 nearest neighbours of a point reach the
  // opposite face, whose normals are parallel (weight 0 for CGAL's MST).
  SurfaceMesh slab = test::cube_mesh(0.5);
  for (Vec3& v : slab.vertices) v[2] *= 0.02;
  const PointSet truth = test::sample_with_normals(slab, 20000, 4);
  PointSet cgal = truth, ours = truth;
  estimate_normals(cgal, {});
  estimate_normals(ours, {});
  orient_normals_mst(cgal, {18, false});
  EXPECT_EQ(orient_normals_tangent_mst(ours, 18), 1u);
  const double ours_flipped = flipped_fraction(ours, truth), cgal_flipped = flipped_fraction(cgal, truth);
  EXPECT_LT(ours_flipped, 0.005);
  EXPECT_GT(cgal_flipped, ours_flipped);
  PointSet bare;
  bare.points = truth.points;
  EXPECT_THROW(orient_normals_tangent_mst(bare, 18), InvalidArgument);
}

// Sheet parity decides the sign where the material is too thin to enclose
// an empty cell (a plate 2.5 spacings thick), and inside a cavity, where
// what the occupancy calls enclosed is outside the material (a ball in a
// hollow box): every decided vote is right; an open sheet gets none. The
// consensus keeps the votes the same-sheet neighbours confirm and drops
// stray wrong ones.
TEST(Normals, SheetParityVotesDecideThinPlatesAndCavities) {
  SurfaceMesh plate = test::cube_mesh(0.5);
  for (Vec3& v : plate.vertices) v[2] *= 0.02;
  const PointSet plate_truth = test::sample_with_normals(plate, 20000, 5);
  const double spacing = average_spacing(plate_truth, 6);
  ASSERT_LT(0.02, 3 * spacing);  // thinner than three spacings
  PointSet flipped = plate_truth;
  for (std::size_t i = 0; i < flipped.size(); i += 2) flipped.normals[i] = -1.0 * flipped.normals[i];
  for (double cell : {spacing, 1.5 * spacing})
    for (signed char v : exterior_side_votes(flipped, cell, 6 * cell)) EXPECT_EQ(v, 0);  // nothing enclosed
  const std::vector<signed char> votes = sheet_parity_votes(flipped, spacing, 0.0);
  std::size_t decided = 0, wrong = 0;
  for (std::size_t i = 0; i < votes.size(); ++i) {
    if (votes[i] == 0) continue;
    ++decided;
    wrong += votes[i] != (i % 2 == 0 ? -1 : 1);
  }
  EXPECT_GT(decided, plate_truth.size() * 8 / 10);
  EXPECT_LE(wrong, decided / 1000);

  // A hollow box (walls 0.1 thick) with a ball in its cavity; the inner
  // shell's facets face into the cavity.
  const PointSet nested = test::sample_with_normals(test::hollow_box_mesh(0.5, 0.4, 0.2, 4), 40000, 6);
  PointSet nested_flipped = nested;
  for (std::size_t i = 0; i < nested.size(); i += 3) nested_flipped.normals[i] = -1.0 * nested_flipped.normals[i];
  const std::vector<signed char> nested_votes = sheet_parity_votes(nested_flipped, average_spacing(nested, 6), 0.0);
  std::size_t cavity_decided = 0, nested_wrong = 0;
  for (std::size_t i = 0; i < nested.size(); ++i) {
    if (nested_votes[i] == 0) continue;
    const double r = std::max({std::abs(nested.points[i][0]), std::abs(nested.points[i][1]), std::abs(nested.points[i][2])});
    cavity_decided += r > 0.35 && r < 0.45;
    nested_wrong += nested_votes[i] != (i % 3 == 0 ? -1 : 1);
  }
  std::size_t nested_decided = 0;
  for (signed char v : nested_votes) nested_decided += v != 0;
  EXPECT_GT(cavity_decided, 1000u);
  EXPECT_LE(nested_wrong, nested_decided / 1000);

  // Stray wrong votes among right ones: the consensus drops them.
  std::vector<signed char> noisy(plate_truth.size(), 1);
  for (std::size_t i = 0; i < noisy.size(); i += 50) noisy[i] = -1;
  const std::vector<signed char> agreed = neighbour_confirmed_votes(plate_truth, noisy);
  std::size_t kept = 0;
  for (signed char v : agreed) {
    EXPECT_NE(v, -1);
    kept += v == 1;
  }
  EXPECT_GT(kept, plate_truth.size() * 8 / 10);

  PointSet sheet;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) sheet.points.push_back({i / 100.0, j / 100.0, 0.0}), sheet.normals.push_back({0, 0, 1});
  for (signed char v : sheet_parity_votes(sheet, 0.01, 0.0)) EXPECT_EQ(v, 0);
  EXPECT_THROW(sheet_parity_votes(sheet, 0, 0), InvalidArgument);
}

// The occupancy decides signs on a closed solid and nowhere on an open sheet;
// an MST grown from those anchors orients every normal outwards (no global
// flip left to undo).
TEST(Normals, ExteriorVotesAnchorTheMstOutwards) {
  const PointSet truth = test::sample_with_normals(test::cube_mesh(0.5), 20000, 7);
  const double spacing = average_spacing(truth, 6);
  PointSet flipped = truth;
  for (std::size_t i = 0; i < flipped.size(); i += 2) flipped.normals[i] = -1.0 * flipped.normals[i];
  const std::vector<signed char> votes = exterior_side_votes(flipped, 1.5 * spacing, 9 * spacing);
  std::size_t decided = 0;
  for (std::size_t i = 0; i < votes.size(); ++i) {
    if (votes[i] == 0) continue;
    ++decided;
    EXPECT_EQ(votes[i], i % 2 == 0 ? -1 : 1) << i;
  }
  EXPECT_GT(decided, truth.size() * 8 / 10);
  // A slab tapering to a knife edge (about 11 degrees), where the plain MST
  // turns one face inside out: the anchors on its thick end orient the faces
  // outwards, with no global flip to undo; what is left inverted lies at
  // the tip, thinner than a cell.
  SurfaceMesh wedge = test::cube_mesh(0.5);
  for (Vec3& v : wedge.vertices) v[2] *= v[0] < 0 ? 0.2 : 0.002;
  const PointSet wedge_truth = test::sample_with_normals(wedge, 20000, 3);
  const double wedge_spacing = average_spacing(wedge_truth, 6);
  PointSet plain = wedge_truth, anchored = wedge_truth;
  estimate_normals(plain, {});
  estimate_normals(anchored, {});
  orient_normals_tangent_mst(plain, 18);
  const std::vector<signed char> anchors = exterior_side_votes(anchored, 1.5 * wedge_spacing, 9 * wedge_spacing);
  EXPECT_GT(std::count_if(anchors.begin(), anchors.end(), [](signed char v) { return v != 0; }), 1000);
  orient_normals_tangent_mst(anchored, 18, anchors);
  auto inwards = [&](const PointSet& oriented) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < wedge_truth.size(); ++i) count += dot(oriented.normals[i], wedge_truth.normals[i]) < 0;
    return static_cast<double>(count) / static_cast<double>(wedge_truth.size());
  };
  EXPECT_LT(inwards(anchored), 0.05);

  PointSet sheet;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) sheet.points.push_back({i / 100.0, j / 100.0, 0.0}), sheet.normals.push_back({0, 0, 1});
  for (signed char v : exterior_side_votes(sheet, 0.01, 0.06)) EXPECT_EQ(v, 0);
  EXPECT_THROW(exterior_side_votes(sheet, 0, 0.06), InvalidArgument);
  EXPECT_THROW(orient_normals_tangent_mst(sheet, 18, std::vector<signed char>(3, 0)), InvalidArgument);
}

// The slanted face of a tetrahedron inverted, as an MST leaves it when the
// crease points' normals turn the short way across its acute edges: the
// crease votes flip it back; a consistent cube and tetrahedron stay as they are.
TEST(Normals, InvertedPatchBeyondAnAcuteCreaseIsFlippedBack) {
  const PointSet truth = test::sample_with_normals(test::tetrahedron_mesh(), 20000, 3);
  const double spacing = average_spacing(truth);
  std::vector<std::uint32_t> creases;  // within 2 spacings of an edge: no reliable normal line
  for (std::uint32_t i = 0; i < truth.size(); ++i) {
    const Vec3& p = truth.points[i];
    const double planes[4] = {p[0], p[1], p[2], (1 - p[0] - p[1] - p[2]) / std::sqrt(3.0)};
    int near = 0;
    for (double d : planes) near += std::abs(d) < 2 * spacing;
    if (near >= 2) creases.push_back(i);
  }
  PointSet inverted = truth;
  std::size_t slanted = 0;
  for (std::uint32_t i = 0; i < inverted.size(); ++i)
    if (dot(truth.normals[i], Vec3{1, 1, 1}) > 1.5) inverted.normals[i] = -1.0 * inverted.normals[i], ++slanted;
  ASSERT_GT(slanted, 4000u);
  PointSet repaired = inverted;
  const std::size_t flips = repair_inverted_patches(repaired, creases, spacing);
  EXPECT_GE(flips, slanted - creases.size());
  std::vector<char> crease(truth.size(), 0);
  for (std::uint32_t i : creases) crease[i] = 1;
  std::size_t wrong = 0;  // crease points follow the majority of their neighbours, which may lie on another face
  for (std::uint32_t i = 0; i < truth.size(); ++i) wrong += !crease[i] && dot(repaired.normals[i], truth.normals[i]) < 0;
  EXPECT_EQ(wrong, 0u);
  EXPECT_LT(flipped_fraction(repaired, truth), 0.03);

  PointSet consistent = truth;
  EXPECT_EQ(repair_inverted_patches(consistent, creases, spacing), 0u);

  // Anchored points (signs known, as after an anchored MST) pin their
  // patch: anchors on the three right faces leave the slanted face to the
  // crease votes, which flip it back; anchors on the slanted face keep it.
  std::vector<signed char> right_faces(truth.size(), 0), slanted_face(truth.size(), 0);
  for (std::uint32_t i = 0; i < truth.size(); i += 50) {
    if (crease[i]) continue;
    (dot(truth.normals[i], Vec3{1, 1, 1}) > 1.5 ? slanted_face : right_faces)[i] = 1;
  }
  PointSet voted = inverted;
  repair_inverted_patches(voted, creases, spacing, 18, right_faces);
  EXPECT_LT(flipped_fraction(voted, truth), 0.03);
  PointSet pinned = inverted;
  repair_inverted_patches(pinned, creases, spacing, 18, slanted_face);
  for (std::uint32_t i = 0; i < truth.size(); ++i) {
    if (!crease[i] && dot(truth.normals[i], Vec3{1, 1, 1}) > 1.5) {
      ASSERT_LT(dot(pinned.normals[i], truth.normals[i]), 0) << i;
    }
  }
  PointSet cube = test::sample_with_normals(test::cube_mesh(1.0), 20000, 3);
  EXPECT_EQ(repair_inverted_patches(cube, {}, average_spacing(cube)), 0u);
}

// Half an octahedron inverted (its four upper faces, as an MST that crossed
// one crease wrongly leaves them): each inverted face has two inverted
// neighbours that agree with it and one that does not, so no face is
// outvoted on its own; the spanning tree over the crease votes repairs them.
TEST(Normals, InvertedHalfOfAnOctahedronIsFlippedBack) {
  SurfaceMesh octahedron;
  octahedron.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (std::uint32_t x : {0u, 1u})
    for (std::uint32_t y : {2u, 3u})
      for (std::uint32_t z : {4u, 5u}) {
        const bool outward = ((x == 0) == (y == 2)) == (z == 4);  // counter-clockwise seen from outside
        octahedron.faces.push_back(outward ? std::array<std::uint32_t, 3>{x, y, z} : std::array<std::uint32_t, 3>{x, z, y});
      }
  const PointSet truth = test::sample_with_normals(octahedron, 20000, 5);
  for (std::uint32_t i = 0; i < truth.size(); ++i) ASSERT_GT(dot(truth.normals[i], truth.points[i]), 0);  // outward
  const double spacing = average_spacing(truth);
  std::vector<std::uint32_t> creases;
  for (std::uint32_t i = 0; i < truth.size(); ++i) {
    const Vec3& p = truth.points[i];
    if (std::min({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}) < spacing) creases.push_back(i);
  }
  PointSet inverted = truth;
  for (std::uint32_t i = 0; i < inverted.size(); ++i)
    if (truth.points[i][2] > 0) inverted.normals[i] = -1.0 * inverted.normals[i];
  EXPECT_GT(repair_inverted_patches(inverted, creases, spacing), 0u);
  std::vector<char> crease(truth.size(), 0);
  for (std::uint32_t i : creases) crease[i] = 1;
  std::size_t wrong = 0;
  for (std::uint32_t i = 0; i < truth.size(); ++i) wrong += !crease[i] && dot(inverted.normals[i], truth.normals[i]) < 0;
  EXPECT_EQ(wrong, 0u);
}

namespace {

// A 2 x 2 x 1 block with a vertical bore of radius r through it, sampled
// uniformly with exact outward normals (the bore's point toward its axis).
PointSet block_with_bore(double r, std::size_t count, unsigned seed, std::vector<char>* on_bore = nullptr) {
  const double pi = 3.14159265358979323846;
  const double caps = 2 * (4 - pi * r * r), sides = 8, bore = 2 * pi * r;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  PointSet ps;
  while (ps.size() < count) {
    const double pick = u(rng) * (caps + sides + bore);
    const double a = 2 * u(rng) - 1, b = 2 * u(rng) - 1;
    bool wall = false;
    if (pick < caps) {
      if (a * a + b * b < r * r) continue;
      const double z = pick < caps / 2 ? 0.5 : -0.5;
      ps.points.push_back({a, b, z}), ps.normals.push_back({0, 0, z > 0 ? 1.0 : -1.0});
    } else if (pick < caps + sides) {
      const int side = static_cast<int>(4 * u(rng)) % 4;
      const double s = side % 2 ? 1.0 : -1.0, z = b / 2;
      if (side < 2) ps.points.push_back({s, a, z}), ps.normals.push_back({s, 0, 0});
      else ps.points.push_back({a, s, z}), ps.normals.push_back({0, s, 0});
    } else {
      const double t = 2 * pi * u(rng);
      ps.points.push_back({r * std::cos(t), r * std::sin(t), b / 2});
      ps.normals.push_back({-std::cos(t), -std::sin(t), 0});
      wall = true;
    }
    if (on_bore) on_bore->push_back(wall);
  }
  return ps;
}

}  // namespace

// A bore about 3 spacings in radius inverted as a whole (its wall is all
// crease points, whose jet normals let an MST turn it at both rims): nothing
// local tells it from a pin, the winding number of the rest of the block
// does. Consistent normals, and two blocks facing each other across a slit
// narrower than the winding test's offset, are left as they are.
TEST(Normals, InvertedBoreWallIsFlippedBackByTheWindingNumber) {
  std::vector<char> wall;
  const PointSet truth = block_with_bore(0.1, 20000, 7, &wall);
  const double spacing = average_spacing(truth);
  ASSERT_LT(0.1 / spacing, 4.0);
  PointSet inverted = truth;
  std::size_t walls = 0;
  for (std::uint32_t i = 0; i < truth.size(); ++i)
    if (wall[i]) inverted.normals[i] = -1.0 * inverted.normals[i], ++walls;
  ASSERT_GT(walls, 500u);
  const std::size_t flips = repair_enclosed_normals(inverted, spacing);
  EXPECT_GE(flips, walls * 95 / 100);
  std::size_t wrong_wall = 0, wrong_elsewhere = 0;
  for (std::uint32_t i = 0; i < truth.size(); ++i)
    (wall[i] ? wrong_wall : wrong_elsewhere) += dot(inverted.normals[i], truth.normals[i]) < 0;
  EXPECT_LE(wrong_wall, walls / 50);
  EXPECT_EQ(wrong_elsewhere, 0u);

  PointSet consistent = truth;
  EXPECT_EQ(repair_enclosed_normals(consistent, spacing), 0u);

  // Two unit cubes 0.4 spacings apart: each facing face's outer offset
  // point lies inside the other cube.
  const PointSet cube = test::sample_with_normals(test::cube_mesh(0.5), 12000, 8);
  const double cube_spacing = average_spacing(cube);
  PointSet pair;
  for (double side : {-1.0, 1.0})
    for (std::size_t i = 0; i < cube.size(); ++i) {
      pair.points.push_back(cube.points[i] + Vec3{side * (0.5 + 0.2 * cube_spacing), 0, 0});
      pair.normals.push_back(cube.normals[i]);
    }
  EXPECT_EQ(repair_enclosed_normals(pair, average_spacing(pair)), 0u);
  PointSet bare;
  bare.points = truth.points;
  EXPECT_THROW(repair_enclosed_normals(bare, spacing), InvalidArgument);
}

TEST(Clean, RunsTheStepsOfFigureA2InOrder) {
  PointSet ps = sphere_points(5000);
  for (int i = 0; i < 10; ++i)  // outliers 2 radii off the unit sphere, in 10 directions
    ps.points.push_back({3 * std::cos(0.628 * i), 3 * std::sin(0.628 * i), i % 2 ? 0.5 : -0.5});
  CleanOptions options;
  options.outliers_sigma = SigmaOutlierOptions{24, 3.0};
  options.random_percentage = 10;
  options.smoothing = JetSmoothingOptions{24};
  options.normals = NormalEstimationOptions{NormalMethod::Jet, 18};
  options.orientation = CleanOptions::Orientation::TangentMst;
  const CleanStats stats = clean_point_set(ps, options);
  EXPECT_EQ(stats.input, 5010u);
  EXPECT_EQ(stats.removed_outliers_sigma, 10u);
  EXPECT_EQ(stats.removed_random, 500u);
  EXPECT_EQ(stats.output, 4500u);
  ASSERT_EQ(ps.size(), 4500u);
  std::vector<std::string> names;
  for (const StageTiming& s : stats.stages) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"outliers-sigma", "random simplification", "smoothing", "normals", "orientation"}));
  ASSERT_TRUE(ps.has_normals());
  std::size_t outward = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) outward += dot(ps.normals[i], ps.points[i]) > 0;
  EXPECT_TRUE(outward == ps.size() || outward == 0) << "one consistent orientation";

  CleanOptions bad;
  bad.smoothing = JetSmoothingOptions{3};
  EXPECT_THROW(clean_point_set(ps, bad), InvalidArgument);
  bad = {};
  bad.grid_cell = -1.0;
  EXPECT_THROW(clean_point_set(ps, bad), InvalidArgument);
  bad = {};
  bad.outliers = PercentageOutlierOptions{24, 100.0};
  EXPECT_THROW(clean_point_set(ps, bad), InvalidInput) << "nothing left";
}

// Local thickness: two parallel sheets 0.1 apart face each other; a single
// sheet has nothing in front of it.
TEST(LocalThickness, FindsTheOppositeSheetOnly) {
  PointSet two;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (double z : {0.0, 0.1}) {
        two.points.push_back({i * 0.02, j * 0.02, z});
        two.normals.push_back({0, 0, z > 0 ? 1.0 : -1.0});
      }
  std::vector<std::uint32_t> facing;
  const std::vector<double> t = local_thickness(two, 0.01, 0.3, &facing);
  ASSERT_EQ(facing.size(), two.size());
  for (std::size_t i = 0; i < two.size(); ++i) {
    EXPECT_NEAR(t[i], 0.1, 1e-9);
    // The facing point lies on the other sheet, straight across.
    EXPECT_NEAR(two.points[facing[i]][2], 0.1 - two.points[i][2], 1e-12);
    EXPECT_NEAR(norm(two.points[facing[i]] - two.points[i]), t[i], 1e-12);
  }
  PointSet one;
  for (std::size_t i = 0; i < two.size(); i += 2) one.points.push_back(two.points[i]), one.normals.push_back(two.normals[i]);
  for (double x : local_thickness(one, 0.01, 0.3, &facing)) EXPECT_TRUE(std::isinf(x));
  for (std::size_t i = 0; i < one.size(); ++i) EXPECT_EQ(facing[i], i) << "no facing point: the point itself";
  EXPECT_THROW(local_thickness(PointSet{two.points, {}, {}}, 0.01, 0.3), InvalidArgument);
  EXPECT_THROW(local_thickness(two, 0.3, 0.1), InvalidArgument);
}

// Over a wide range (max_thickness / min_thickness = 40, a coarse mesh) the
// search runs along each normal line instead of through one large ball: the
// same thickness as the rule applied to every pair of points.
TEST(LocalThickness, SearchAlongTheNormalLineMatchesAllPairs) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // A wall 0.15 thick, a gap of 0.3 above it, and a side wall, each sheet
  // farther from the others than its 24 neighbours reach (so the noise
  // estimate, which raises min_thickness, stays 0).
  PointSet sheets;
  for (int i = 0; i < 2400; ++i) {
    const double a = unit(random), b = unit(random);
    switch (i % 4) {
      case 0: sheets.points.push_back({a, b, 0.0}), sheets.normals.push_back({0, 0, -1}); break;
      case 1: sheets.points.push_back({a, b, 0.15}), sheets.normals.push_back({0, 0, 1}); break;
      case 2: sheets.points.push_back({a, b, 0.45}), sheets.normals.push_back({0, 0, -1}); break;
      default: sheets.points.push_back({1.2, a, 0.45 * b}), sheets.normals.push_back({1, 0, 0}); break;
    }
  }
  const double min_thickness = 0.01, max_thickness = 0.6;
  const std::vector<double> fast = local_thickness(sheets, min_thickness, max_thickness);
  const double cos_parallel = std::cos(25.0 * M_PI / 180.0), cos_cone = std::cos(30.0 * M_PI / 180.0);
  std::size_t finite = 0;
  for (std::size_t i = 0; i < sheets.size(); ++i) {
    const Vec3& p = sheets.points[i];
    const Vec3& n = sheets.normals[i];
    double best = std::numeric_limits<double>::infinity();
    std::size_t facing = 0;
    for (std::size_t j = 0; j < sheets.size(); ++j) {
      const Vec3 d = sheets.points[j] - p;
      const double length = norm(d);
      if (!(length > min_thickness) || length >= best || length > max_thickness) continue;
      if (std::abs(dot(n, sheets.normals[j])) < cos_parallel || std::abs(dot(d, n)) < cos_cone * length) continue;
      best = length, facing = j;
    }
    if (std::isfinite(best)) {
      const Vec3 half = 0.5 * (p + sheets.points[facing]);
      double nearest = std::numeric_limits<double>::infinity();
      for (const Vec3& q : sheets.points) nearest = std::min(nearest, norm(q - half));
      if (nearest * nearest < 0.09 * best * best) best = std::numeric_limits<double>::infinity();
    }
    finite += std::isfinite(best);
    ASSERT_EQ(fast[i], best) << "point " << i;
  }
  EXPECT_GT(finite, 1000u);  // the wall's and the gap's points
  // Lone pairs, facing each other at up to 29 degrees off the normal and at
  // every distance of the range: the balls along the line cover the cone.
  PointSet pairs;
  std::vector<double> expected;
  for (double angle : {0.0, 10.0, 20.0, 29.0})
    for (double length = 0.012; length < max_thickness; length *= 1.13) {
      const Vec3 p{10.0 * static_cast<double>(pairs.size()), 0, 0};
      const double a = angle * M_PI / 180;
      pairs.points.push_back(p), pairs.normals.push_back({0, 0, 1});
      pairs.points.push_back(p + Vec3{length * std::sin(a), 0, -length * std::cos(a)}), pairs.normals.push_back({0, 0, -1});
      expected.push_back(length);
    }
  const std::vector<double> t = local_thickness(pairs, min_thickness, max_thickness);
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(t[2 * k], expected[k], 1e-12) << "pair " << k;
}
