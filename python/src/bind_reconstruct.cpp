// The Chapter 7 pipeline (sharpmesh/reconstruct.h) with the options of
// `sharpmesh reconstruct`.
#include "convert.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/reconstruct.h"

namespace sharpmesh::python {
namespace {

py::dict reconstruct_report(const ReconstructResult& r, const ReconstructOptions& o) {
  py::dict counts, derived, protection, report;
  counts["input_points"] = r.input_points;
  counts["duplicate_points"] = r.duplicate_points;
  counts["points_used"] = r.used_points;
  counts["poisson_points"] = r.poisson_points;
  counts["normal_agreement"] = r.normal_agreement;
  counts["normals_estimated"] = r.normals_estimated;
  counts["normal_source"] = r.normal_source;
  counts["input_normal_agreement"] = r.input_normal_agreement;
  counts["isotropic_cvcm_normals"] = r.isotropic_cvcm_normals;
  counts["patch_flipped_normals"] = r.patch_flipped_normals;
  counts["enclosed_flipped_normals"] = r.enclosed_flipped_normals;
  counts["sharpened_normals"] = r.sharpened_normals;
  counts["sign_repaired_normals"] = r.sign_repaired_normals;
  counts["vertices"] = r.mesh.vertices.size();
  counts["facets"] = r.mesh.faces.size();
  counts["trimmed_facets"] = r.trimmed_facets;
  counts["dataless_facets"] = r.dataless_facets;
  counts["clipped_facets"] = r.clipped_facets;
  counts["data_seeds"] = r.meshing.data_seeds;
  counts["thin_points"] = r.thin_points;
  counts["anchored_normals"] = r.anchored_normals;
  counts["thin_part_vertices"] = r.thin_part_vertices;
  counts["flattened_vertices"] = r.flattened_vertices;
  counts["poisson_screening"] = r.poisson_screening;
  counts["snapped_corners"] = r.snapped_corners;
  counts["snapped_to_data"] = r.snapped_to_data;
  counts["unsnapped_vertices"] = r.unsnapped_vertices;
  counts["restricted_to_data"] = r.restricted;
  counts["boundary_edges"] = r.boundary_edges;
  py::dict fit;
  fit["off_distance"] = r.off_data_distance;
  fit["points_off_mesh"] = r.off_data_points;
  fit["points_off_against_mesh"] = r.off_data_against;
  fit["vertices_off_data"] = r.invented_vertices;
  fit["retries"] = r.data_fit_retries;
  fit["max_distance"] = r.max_data_distance;
  fit["points_off_first_mesh"] = r.off_data_points_before_retry;
  fit["retry_flipped_normals"] = r.off_data_flips;
  report["data_fit"] = fit;
  py::dict crossings;
  crossings["found_pairs"] = r.intersection_repair.intersecting_pairs;
  crossings["remaining_pairs"] = r.intersection_repair.remaining_pairs;
  crossings["removed_facets"] = r.intersection_repair.removed_facets;
  crossings["added_facets"] = r.intersection_repair.added_facets;
  report["self_intersections"] = crossings;
  derived["average_spacing"] = r.average_spacing;
  derived["d_prime"] = r.d_prime;
  derived["facet_angle_deg"] = r.criteria.angle;
  derived["max_edge_length"] = r.criteria.edge_length;
  derived["max_surface_distance"] = r.criteria.distance;
  derived["estimated_facets"] = r.estimated_facets;
  report["counts"] = counts;
  report["derived"] = derived;
  if (o.feature_mode != FeatureMode::None) {
    const ImplicitMeshingResult& m = r.meshing;
    protection["polylines"] = o.feature_mode == FeatureMode::Given ? o.given_features.size() : r.features.graph.polylines.size();
    protection["protecting_balls"] = m.protecting_balls;
    protection["enlarged_balls"] = m.enlarged_balls;
    protection["protection_rounds_exhausted"] = m.protection_rounds_exhausted;
    protection["protection_stopped"] = m.protection_stopped;
    protection["protection_queries"] = m.protection_queries;
    protection["protected_segments"] = m.protected_segments;
    protection["represented_segments"] = m.represented_segments;
    protection["uncovered_gaps"] = m.uncovered.size();
    protection["max_gap"] = m.max_gap;
    report["protection"] = protection;
  }
  report["stages"] = stages_dict(r.stages);
  return report;
}

}  // namespace

void bind_reconstruct(py::module_& m) {
  const ReconstructOptions d;
  const FeatureOptions f;
  m.def("reconstruct",
        [](const DoubleArray& points, const py::object& point_normals, double delta, bool no_features, const py::object& features,
           double ball_radius, bool fixed_balls, double trim, double poisson_spacing, double poisson_thinning, double poisson_screening, double poisson_screening_noisy, double seed_spacing, bool no_flattening, bool no_snapping, const std::string& normals, int normal_k, int orient_k,
           bool recompute_normals, bool no_sign_repair, bool no_winding_repair, bool no_data_fit_retry, std::size_t max_facets, std::uint32_t seed, double offset_radius, double convolution_radius,
           double t1, double t2, int cluster_k, double cluster_angle, int successor_k, double junction_factor, int denoise_k, bool fit_corner_points,
           const py::object& progress) {
          const PointSet set = to_point_set(points, point_normals);
          ReconstructOptions o;
          o.delta = delta;
          o.feature_mode = no_features ? FeatureMode::None : features.is_none() ? FeatureMode::Extract : FeatureMode::Given;
          if (no_features && !features.is_none()) throw InvalidArgument("give either no_features or features, not both");
          o.given_features = to_polylines(features, "features");
          o.ball_radius = ball_radius;
          o.adapt_balls_to_gap = !fixed_balls;
          o.trim_distance = trim;
          o.poisson_spacing = poisson_spacing;
          o.poisson_thinning = poisson_thinning;
          o.poisson_screening = poisson_screening;
          o.poisson_screening_noisy = poisson_screening_noisy;
          o.data_seed_spacing = seed_spacing;
          o.flatten_features = !no_flattening;
          o.snap_vertices = !no_snapping;
          if (normals == "auto") {
            o.normal_source = NormalSource::Automatic;
          } else if (normals == "cvcm") {
            o.normal_source = NormalSource::Cvcm;
          } else if (normals == "jet" || normals == "pca") {
            o.normal_source = NormalSource::Estimated;
            o.normals.method = normals == "pca" ? NormalMethod::Pca : NormalMethod::Jet;
          } else {
            throw InvalidArgument("normals must be 'auto', 'cvcm', 'jet' or 'pca'");
          }
          if (o.normal_source == NormalSource::Cvcm && o.feature_mode != FeatureMode::Extract)
            throw InvalidArgument("normals='cvcm' needs feature extraction (drop no_features / features)");
          o.normals.k = normal_k;
          o.orientation.k = orient_k;
          o.recompute_normals = recompute_normals;
          o.repair_normal_signs = !no_sign_repair;
          o.refit_off_data = !no_data_fit_retry;
          o.repair_enclosed_normals = !no_winding_repair;
          o.max_facets = max_facets;
          o.seed = seed;
          o.features = feature_options(offset_radius, convolution_radius, t1, t2, cluster_k, cluster_angle, successor_k,
                                       junction_factor, denoise_k, fit_corner_points);
          ProgressBridge bridge(progress);
          const ReconstructResult r = without_gil(bridge, [&] { return reconstruct(set, o, bridge.callback()); });
          const py::object extracted = o.feature_mode == FeatureMode::Extract ? make_features(r.features) : py::object(py::none());
          return py::module_::import("sharpmesh._types")
              .attr("Reconstruction")(make_mesh(r.mesh), from_polylines(r.meshing.feature_edges), extracted, reconstruct_report(r, o));
        },
        py::arg("points"), py::arg("point_normals") = py::none(), py::kw_only(), py::arg("delta") = d.delta,
        py::arg("no_features") = false, py::arg("features") = py::none(), py::arg("ball_radius") = d.ball_radius,
        py::arg("fixed_balls") = false, py::arg("trim") = d.trim_distance,
        py::arg("poisson_spacing") = d.poisson_spacing, py::arg("poisson_thinning") = d.poisson_thinning,
        py::arg("poisson_screening") = d.poisson_screening, py::arg("poisson_screening_noisy") = d.poisson_screening_noisy, py::arg("seed_spacing") = d.data_seed_spacing,
        py::arg("no_flattening") = false, py::arg("no_snapping") = false, py::arg("normals") = "auto",
        py::arg("normal_k") = d.normals.k, py::arg("orient_k") = d.orientation.k, py::arg("recompute_normals") = false,
        py::arg("no_sign_repair") = false, py::arg("no_winding_repair") = false, py::arg("no_data_fit_retry") = false,
        py::arg("max_facets") = d.max_facets, py::arg("seed") = d.seed, py::arg("offset_radius") = f.offset_radius,
        py::arg("convolution_radius") = f.convolution_radius, py::arg("t1") = f.t1, py::arg("t2") = f.t2,
        py::arg("cluster_k") = f.cluster_k, py::arg("cluster_angle") = f.cluster_angle, py::arg("successor_k") = f.successor_k,
        py::arg("junction_factor") = f.junction_factor, py::arg("denoise_k") = f.denoise_k, py::arg("fit_corner_points") = f.fit_corner_points, py::arg("progress") = py::none(),
        R"(Point cloud -> mesh with sharp edges, as `sharpmesh reconstruct` (thesis Ch. 7) -> Reconstruction.

delta: mesh size d' = delta x average spacing (7.3.2); no_features: the PIF baseline; features: protect these polylines
instead of extracting them; ball_radius: fraction of d'; fixed_balls: do not grow balls to reach the implicit surface;
trim: remove facets farther than trim x d' + 2 avg from the data (0: keep the closed surface); poisson_spacing: solve Poisson on a grid simplification with
cells of poisson_spacing x d' (0: every point); poisson_thinning: leave out of Poisson the points closer than
poisson_thinning x avg to an earlier one (0: none); poisson_screening: pull of the Poisson function towards the points
relative to its smoothness, lengths in average spacings, the same in any unit (0: CGAL's own, unit-dependent); poisson_screening_noisy: the same on clouds found noisy; seed_spacing: before refinement, one input point per cell of
seed_spacing x d' projected onto the implicit surface as a vertex (0: none); no_flattening: keep the facets along protected
edges on the Poisson surface; no_snapping: leave the vertices where the refinement put them (by default up to 2 avg
onto the corners and data points the mesh misses; report counts snapped_*); normals (when
point_normals is None or recompute_normals): 'auto', 'cvcm', 'jet' or 'pca', over normal_k neighbours, oriented over
orient_k; no_sign_repair: keep the normals the Poisson function contradicts (by default flipped and
Poisson solved again, up to 3 times); no_winding_repair: keep the regions whose outer side the rest of the cloud
encloses by its winding number (by default flipped before Poisson); no_data_fit_retry: keep the first mesh even when input points lie off it (by
default their normals are flipped and the surface solved and meshed again; report['data_fit']); max_facets: refuse larger estimates (0: no limit); the feature options are those of extract_features().)");
}

}  // namespace sharpmesh::python
