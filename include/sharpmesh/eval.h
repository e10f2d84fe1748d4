// Evaluation tools (thesis 7.5, 8.2): sampling of reference meshes, sharp
// edges of a reference, distances between meshes, topology checks.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "sharpmesh/progress.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

/// Points uniformly distributed over the area of a mesh, with optional
/// uniform noise of amplitude `noise` times the bounding-box diagonal (each
/// coordinate offset uniformly in [-a, a], the thesis's noise model, 7.5).
/// Scanners do not sample uniformly: `density_ratio` makes the density grow
/// linearly across the part, along a direction drawn from the seed, from 1
/// to that ratio; `missing_patches` balls of `missing_radius` times the
/// diagonal, centred on the surface, get no sample (occlusions, dark spots).
struct SampleOptions {
  std::size_t count = 100'000;
  double noise = 0.0;  ///< fraction of the bounding-box diagonal
  std::uint64_t seed = 0;
  bool with_normals = false;  ///< store the facet normal of each sample
  double density_ratio = 1.0;         ///< densest / sparsest sampling density, >= 1
  std::size_t missing_patches = 0;    ///< balls left without samples
  double missing_radius = 0.05;       ///< their radius, fraction of the bounding-box diagonal
  void check() const;
};
PointSet sample_mesh(const SurfaceMesh& mesh, const SampleOptions& options);
/// The same samples, with the index of the face each one lies on.
PointSet sample_mesh(const SurfaceMesh& mesh, const SampleOptions& options, std::vector<std::uint32_t>& faces);

/// Edges whose two incident facets make an angle above `angle_deg` (0: flat),
/// chained into polylines that run between vertices of sharp degree != 2
/// (closed loops are returned with front() == back()).
std::vector<Polyline> sharp_edges(const SurfaceMesh& mesh, double angle_deg = 30.0);

/// Combinatorial and geometric checks of a triangle mesh.
struct TopologyReport {
  std::size_t vertices = 0, faces = 0;
  std::size_t boundary_edges = 0;
  std::size_t non_manifold_edges = 0;
  std::size_t non_manifold_vertices = 0;
  std::size_t degenerate_faces = 0;
  std::size_t components = 0;
  bool orientable = true;
  bool self_intersecting = false;
  bool closed() const { return boundary_edges == 0 && faces > 0; }
  bool manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0 && orientable; }
};
TopologyReport check_topology(const SurfaceMesh& mesh, bool test_self_intersections = true);

/// The pairs of faces (indices into mesh.faces, smaller first, sorted) that intersect other
/// than along a shared edge or vertex; degenerate faces are left out.
std::vector<std::pair<std::uint32_t, std::uint32_t>> self_intersecting_faces(const SurfaceMesh& mesh);

/// Distances from `mesh` to `reference`, both ways, from uniform samples of
/// each surface (plus their vertices). All distances in the data's units;
/// `diagonal` is the reference's bounding-box diagonal.
struct DistanceOptions {
  std::size_t samples = 200'000;  ///< per surface
  std::uint64_t seed = 0;
  double sharp_angle = 30.0;      ///< degrees, for sharp-edge fidelity
  void check() const;
};
struct DistanceReport {
  double diagonal = 0;
  double hausdorff = 0;          ///< max of the two one-sided maxima
  double mesh_to_reference_max = 0, reference_to_mesh_max = 0;
  double mesh_to_reference_mean = 0, reference_to_mesh_mean = 0;
  double mean = 0, rms = 0;      ///< over samples of both sides
  std::size_t sharp_edge_count = 0;
  double sharp_edge_length = 0;
  double sharp_mean = 0, sharp_max = 0;  ///< reference sharp edges -> mesh
};
DistanceReport compare_meshes(const SurfaceMesh& mesh, const SurfaceMesh& reference,
                              const DistanceOptions& options = {}, const Progress& progress = {});

double surface_area(const SurfaceMesh& mesh);

/// Distance from each point to the nearest point of the mesh (parallel).
std::vector<double> distances_to_mesh(const std::vector<Vec3>& points, const SurfaceMesh& mesh);

}  // namespace sharpmesh

namespace sharpmesh {

/// Feature-extraction benchmark (thesis 8.2): the reference's sharp edges
/// are the ground truth. Recall = fraction of ground-truth length within
/// `tolerance` of the extracted polylines; precision = fraction of extracted
/// length within `tolerance` of the ground truth; corner recall = fraction
/// of ground-truth corners (3 or more sharp edges) with an extracted
/// junction of degree >= 3 within `tolerance`.
struct FeatureEvalOptions {
  double sharp_angle = 30.0;  ///< degrees from flat
  double tolerance = 0.005;   ///< fraction of the reference's bounding-box diagonal
  void check() const;
};
struct FeatureEvaluation {
  double diagonal = 0, tolerance = 0;  ///< data units
  double truth_length = 0, extracted_length = 0;
  double recall = 0, precision = 0;
  double truth_to_extracted_mean = 0, truth_to_extracted_max = 0;
  double extracted_to_truth_mean = 0, extracted_to_truth_max = 0;
  std::size_t truth_corners = 0, recalled_corners = 0;
};
/// Distance from each point to the nearest of the polylines, exact up to
/// `step`/2 (the polylines are resampled every `step`).
std::vector<double> distances_to_polylines(const std::vector<Vec3>& points, const std::vector<Polyline>& polylines,
                                           double step);
/// Points where `min_degree` or more open polylines end (corners of a feature graph).
std::vector<Vec3> polyline_corners(const std::vector<Polyline>& polylines, int min_degree = 3);

FeatureEvaluation evaluate_features(const std::vector<Polyline>& extracted, const std::vector<Vec3>& extracted_corners,
                                    const SurfaceMesh& reference, const FeatureEvalOptions& options = {});

}  // namespace sharpmesh

#include "sharpmesh/stereo.h"

namespace sharpmesh {

/// Multi-view stereo evaluation in the manner of Strecha et al. 2008 and the
/// thesis's Fig. 6.8: cumulative error distributions of
///  - accuracy: distance from samples of the result to the reference surface;
///  - completeness: distance from samples of the reference surface that some
///    camera sees (ray-cast visibility) to the result.
/// Thresholds are fractions of the scene size: the bounding-box diagonal of
/// the visible reference samples.
struct StereoEvalOptions {
  std::size_t samples = 200'000;  ///< per surface
  std::uint64_t seed = 0;
  std::vector<double> thresholds = {0.0005, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05};  ///< fractions of the scene size
  void check() const;
};
struct StereoEvaluation {
  double scene_size = 0;                ///< data units
  std::vector<double> thresholds;       ///< data units, increasing
  std::vector<double> accuracy;         ///< fraction of result samples within each threshold
  std::vector<double> completeness;     ///< fraction of visible reference samples within each threshold
  double accuracy_median = 0, completeness_median = 0;  ///< distances, data units
  std::size_t result_samples = 0, visible_reference_samples = 0;
  /// The visible reference samples and their distances to the result (data
  /// units): where the result is incomplete.
  std::vector<Vec3> visible_reference;
  std::vector<double> completeness_distances;
};
StereoEvaluation evaluate_stereo(const SurfaceMesh& mesh, const SurfaceMesh& reference, const std::vector<Camera>& cameras,
                                 const StereoEvalOptions& options = {}, const Progress& progress = {});

}  // namespace sharpmesh
