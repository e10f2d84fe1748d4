// Evaluation of the Poisson implicit function (thesis 7.3: the oracle of the
// Delaunay refinement asks for its sign at every step).
//
// Samples a mesh with its facet normals (fixed seed), solves CGAL's Poisson
// function once with each way of locating a query in its triangulation, and
// compares in the same run:
//   - sharpmesh: walks that start from a grid of cells found before;
//   - CGAL 5.5: Poisson_reconstruction_function::operator(), a walk from the
//     last cell found.
// Timed: queries at random places in the bounding box, and the surface
// refinement (criteria of 7.3.2 for d' = delta x average spacing, no
// features). Prints both times, their ratio, the largest difference of the
// values and the facet counts (which must agree).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "sharpmesh/eval.h"
#include "sharpmesh/implicit.h"
#include "sharpmesh/io.h"
#include "sharpmesh/meshing.h"
#include "sharpmesh/pointset.h"

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Run {
  double query_seconds = 0, refinement_seconds = 0;
  std::vector<double> values;
  std::size_t facets = 0;
};

Run run(const sharpmesh::PointSet& points, bool grid, const std::vector<sharpmesh::Vec3>& queries,
        const sharpmesh::ImplicitMeshingOptions& meshing) {
  sharpmesh::PoissonOptions options;
  options.start_cell_grid = grid;
  const auto surface = sharpmesh::poisson_surface(points, options);
  Run r;
  r.values.reserve(queries.size());
  auto t0 = Clock::now();
  for (const sharpmesh::Vec3& q : queries) r.values.push_back(surface->value(q));
  r.query_seconds = seconds_since(t0);
  t0 = Clock::now();
  r.facets = sharpmesh::mesh_implicit_surface(*surface, meshing).mesh.faces.size();
  r.refinement_seconds = seconds_since(t0);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Poisson function evaluation: grid start cells versus CGAL's walk from the last cell"};
  std::string mesh_path;
  std::size_t count = 200'000, query_count = 200'000;
  std::uint64_t seed = 1;
  double delta = 3.5;
  app.add_option("mesh", mesh_path, "Mesh to sample (.off, .ply, .obj, .stl)")->required();
  app.add_option("-n,--count", count, "Samples");
  app.add_option("--queries", query_count, "Random queries in the bounding box");
  app.add_option("--seed", seed, "Sampling seed");
  app.add_option("--delta", delta, "Refinement size d' in average spacings");
  CLI11_PARSE(app, argc, argv);

  sharpmesh::SampleOptions sampling;
  sampling.count = count;
  sampling.seed = seed;
  sampling.with_normals = true;
  const sharpmesh::PointSet points = sharpmesh::sample_mesh(sharpmesh::read_mesh(mesh_path), sampling);
  const sharpmesh::BoundingBox box = sharpmesh::bounding_box(points.points);
  std::mt19937_64 generator(seed);
  std::vector<sharpmesh::Vec3> queries(query_count);
  for (sharpmesh::Vec3& q : queries)
    for (int a = 0; a < 3; ++a) q[a] = std::uniform_real_distribution<double>(box.min[a], box.max[a])(generator);
  sharpmesh::ImplicitMeshingOptions meshing;
  meshing.criteria = sharpmesh::RefinementCriteria::from_spacing(delta * sharpmesh::average_spacing(points));

  const Run cgal = run(points, false, queries, meshing);
  const Run ours = run(points, true, queries, meshing);
  double largest_difference = 0;
  for (std::size_t i = 0; i < queries.size(); ++i)
    largest_difference = std::max(largest_difference, std::abs(cgal.values[i] - ours.values[i]));
  std::printf("%s, %zu samples, delta %.1f\n", mesh_path.c_str(), count, delta);
  std::printf("%zu random queries: CGAL %.3f s, sharpmesh %.3f s, ratio %.1fx; largest value difference %.1e\n", queries.size(),
              cgal.query_seconds, ours.query_seconds, cgal.query_seconds / ours.query_seconds, largest_difference);
  std::printf("refinement: CGAL %.2f s (%zu facets), sharpmesh %.2f s (%zu facets), ratio %.1fx\n", cgal.refinement_seconds,
              cgal.facets, ours.refinement_seconds, ours.facets, cgal.refinement_seconds / ours.refinement_seconds);
  return cgal.facets == ours.facets && largest_difference < 1e-9 ? 0 : 1;
}
