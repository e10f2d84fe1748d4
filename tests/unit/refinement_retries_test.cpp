// The mesher's retry policy (src/meshing/refinement_retries.h), driven by a
// fake refinement that reports each kind of failure where the test says:
// no CGAL run has to happen to fail for these to be checked.
#include <gtest/gtest.h>

#include <vector>

#include "meshing/refinement_retries.h"
#include "sharpmesh/errors.h"

namespace sharpmesh {
namespace {

using detail::RefinementRun;

// Two polylines 5 units apart; balls of 0.1 reach 0.6 from a failure spot.
ImplicitMeshingOptions two_polylines() {
  ImplicitMeshingOptions options;
  options.criteria = RefinementCriteria::from_spacing(0.1);
  options.features.ball_radius = 0.1;
  options.features.polylines = {{{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}}, {{0, 5, 0}, {0.5, 5, 0}, {1, 5, 0}}};
  return options;
}

RefinementRun finished() {
  RefinementRun run;
  run.result.mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  run.result.mesh.faces = {{0, 1, 2}};
  return run;
}

RefinementRun cgal_failure(const std::string& message) {
  RefinementRun run;
  run.status = RefinementRun::Status::CgalFailure;
  run.cgal_message = message;
  return run;
}

// Records the options of every attempt and answers from a script.
struct ScriptedMesher {
  std::vector<RefinementRun> answers;
  std::vector<ImplicitMeshingOptions> attempts;
  std::vector<bool> rescues;
  std::vector<Vec3> stalled_points;  // handed out while rescue_stalled is on
  detail::RefineOnce refine() {
    return [this](const ImplicitMeshingOptions& attempt, bool rescue_stalled, std::vector<Vec3>& stalled) {
      attempts.push_back(attempt);
      rescues.push_back(rescue_stalled);
      stalled = rescue_stalled ? stalled_points : std::vector<Vec3>{};
      const std::size_t i = std::min(attempts.size(), answers.size()) - 1;
      return answers[i];
    };
  }
};

bool has_polyline_at_y(const ImplicitMeshingOptions& options, double y) {
  for (const Polyline& line : options.features.polylines)
    if (!line.empty() && line.front()[1] == y) return true;
  return false;
}

TEST(RefinementRetries, AFirstFinishedRunIsTakenAsItIs) {
  ScriptedMesher mesher;
  mesher.answers = {finished()};
  const ImplicitMeshingResult r = detail::refine_with_retries(two_polylines(), mesher.refine(), {});
  EXPECT_EQ(mesher.attempts.size(), 1u);
  EXPECT_EQ(r.mesher_retries, 0u);
  EXPECT_TRUE(r.uncovered.empty());
  EXPECT_EQ(r.mesh.faces.size(), 1u);
}

TEST(RefinementRetries, ARunawayDropsOnlyThePolylineNextToItsPile) {
  ScriptedMesher mesher;
  RefinementRun runaway = finished();
  runaway.result.refinement_runaway = true;
  runaway.result.runaway_stopped_at = 1234;
  runaway.runaway_pile = Vec3{0.5, 0.2, 0};
  mesher.answers = {runaway, finished()};
  const ImplicitMeshingResult r = detail::refine_with_retries(two_polylines(), mesher.refine(), {});
  ASSERT_EQ(mesher.attempts.size(), 2u);
  EXPECT_FALSE(has_polyline_at_y(mesher.attempts[1], 0));
  EXPECT_TRUE(has_polyline_at_y(mesher.attempts[1], 5));
  EXPECT_EQ(r.mesher_retries, 1u);
  EXPECT_EQ(r.runaway_stopped_at, 1234u);
  ASSERT_EQ(r.uncovered.size(), 1u);
  EXPECT_TRUE(r.uncovered[0].refused_by_mesher);
  EXPECT_NEAR(r.uncovered[0].center[1], 0, 1e-12);
  EXPECT_NEAR(r.uncovered[0].length, 1, 1e-12);
}

TEST(RefinementRetries, ARunawayWithoutAKnownPileIsLocatedByItsShortEdges) {
  ScriptedMesher mesher;
  RefinementRun runaway = finished();
  runaway.result.refinement_runaway = true;
  // A fan of edges far shorter than 1% of the edge-length bound next to the second polyline.
  SurfaceMesh& mesh = runaway.result.mesh;
  const std::uint32_t centre = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.push_back({0.5, 5.1, 0});
  for (int k = 0; k < 6; ++k) mesh.vertices.push_back({0.5 + 1e-5 * k, 5.1 + 1e-5, 0});
  for (std::uint32_t k = 1; k < 6; ++k) mesh.faces.push_back({centre, centre + k, centre + k + 1});
  Vec3 spot;
  ASSERT_TRUE(detail::runaway_spot(mesh, two_polylines().criteria.edge_length, spot));
  EXPECT_NEAR(spot[1], 5.1, 1e-3);
  mesher.answers = {runaway, finished()};
  detail::refine_with_retries(two_polylines(), mesher.refine(), {});
  ASSERT_EQ(mesher.attempts.size(), 2u);
  EXPECT_TRUE(has_polyline_at_y(mesher.attempts[1], 0));
  EXPECT_FALSE(has_polyline_at_y(mesher.attempts[1], 5));
}

TEST(RefinementRetries, ACgalFailureAtAPointDropsThePolylinesThere) {
  ScriptedMesher mesher;
  Vec3 parsed;
  const std::string message = "CGAL ERROR: the point (0.25 5.05 0 0.01) is already inserted on surface.";
  ASSERT_TRUE(detail::failure_point(message, parsed));
  EXPECT_DOUBLE_EQ(parsed[1], 5.05);
  mesher.answers = {cgal_failure(message), finished()};
  const ImplicitMeshingResult r = detail::refine_with_retries(two_polylines(), mesher.refine(), {});
  ASSERT_EQ(mesher.attempts.size(), 2u);
  EXPECT_TRUE(has_polyline_at_y(mesher.attempts[1], 0));
  EXPECT_FALSE(has_polyline_at_y(mesher.attempts[1], 5));
  EXPECT_EQ(r.mesher_retries, 1u);
  EXPECT_EQ(r.uncovered.size(), 1u);
}

TEST(RefinementRetries, AFailureNowhereUnprotectsTheFlatPointsFirstThenEverything) {
  ScriptedMesher mesher;
  mesher.stalled_points = {{0.5, 0, 0}};
  const RefinementRun nowhere = cgal_failure("A facet is not in conflict with its refinement point!");
  mesher.answers = {nowhere, nowhere, finished()};
  const ImplicitMeshingResult r = detail::refine_with_retries(two_polylines(), mesher.refine(), {});
  ASSERT_EQ(mesher.attempts.size(), 3u);
  EXPECT_TRUE(mesher.rescues[0]);
  EXPECT_FALSE(mesher.rescues[1]);
  EXPECT_EQ(mesher.attempts[1].features.polylines.size(), 2u);
  EXPECT_TRUE(mesher.attempts[2].features.polylines.empty());
  EXPECT_EQ(r.mesher_retries, 2u);
  EXPECT_EQ(r.uncovered.size(), 2u);
}

TEST(RefinementRetries, AStalledRepairDropsTheProtectionAtItsPinchedVertices) {
  ScriptedMesher mesher;
  RefinementRun stalled = finished();
  stalled.result.refinement_stalled = true;
  stalled.result.mesh.vertices.push_back({1, 5.2, 0});
  stalled.result.mesh.vertices.push_back({1, 5.2, 0});  // one position, two output vertices
  ASSERT_EQ(detail::pinched_vertices(stalled.result.mesh).size(), 1u);
  mesher.answers = {stalled, finished()};
  detail::refine_with_retries(two_polylines(), mesher.refine(), {});
  ASSERT_EQ(mesher.attempts.size(), 2u);
  EXPECT_TRUE(has_polyline_at_y(mesher.attempts[1], 0));
  EXPECT_FALSE(has_polyline_at_y(mesher.attempts[1], 5));
}

TEST(RefinementRetries, AProtectionPastItsBudgetRunsAgainWithoutProtection) {
  ScriptedMesher mesher;
  RefinementRun stopped;
  stopped.status = RefinementRun::Status::ProtectionStopped;
  mesher.answers = {stopped, finished()};
  const ImplicitMeshingResult r = detail::refine_with_retries(two_polylines(), mesher.refine(), {});
  ASSERT_EQ(mesher.attempts.size(), 2u);
  EXPECT_TRUE(mesher.attempts[1].features.polylines.empty());
  EXPECT_TRUE(r.protection_stopped);
  EXPECT_EQ(r.uncovered.size(), 2u);
}

TEST(RefinementRetries, TheLastRefinementsFailureIsThrownAsANumericalFailure) {
  ScriptedMesher mesher;
  mesher.answers = {cgal_failure("A facet is not in conflict with its refinement point!\nmore")};
  try {
    detail::refine_with_retries(two_polylines(), mesher.refine(), {});
    FAIL() << "a refinement that always fails must throw";
  } catch (const NumericalFailure& e) {
    EXPECT_NE(std::string(e.what()).find("A facet is not in conflict"), std::string::npos);
    EXPECT_EQ(std::string(e.what()).find("more"), std::string::npos) << "one line of CGAL's message";
  }
  // The first failure dropped every polyline; without protection the second was the last.
  EXPECT_EQ(mesher.attempts.size(), 2u);
}

TEST(RefinementRetries, RetriesStopAtTheLimit) {
  ScriptedMesher mesher;
  RefinementRun runaway = finished();
  runaway.result.refinement_runaway = true;
  runaway.runaway_pile = Vec3{100, 100, 100};  // near no polyline: all of them go
  ImplicitMeshingOptions options = two_polylines();
  mesher.answers = {runaway};
  const ImplicitMeshingResult r = detail::refine_with_retries(options, mesher.refine(), {}, 0);
  EXPECT_EQ(mesher.attempts.size(), 1u) << "no retry allowed: the runaway mesh is the result";
  EXPECT_TRUE(r.refinement_runaway);
}

}  // namespace
}  // namespace sharpmesh
