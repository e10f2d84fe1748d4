// Evaluation (thesis 7.5, 8.2; sharpmesh/eval.h): sampling, sharp edges,
// distances between meshes, the feature benchmark, topology checks.
#include "convert.h"
#include "sharpmesh/eval.h"

namespace sharpmesh::python {
namespace {

py::dict topology_dict(const TopologyReport& t) {
  py::dict d;
  d["vertices"] = t.vertices;
  d["faces"] = t.faces;
  d["boundary_edges"] = t.boundary_edges;
  d["non_manifold_edges"] = t.non_manifold_edges;
  d["non_manifold_vertices"] = t.non_manifold_vertices;
  d["degenerate_faces"] = t.degenerate_faces;
  d["components"] = t.components;
  d["orientable"] = t.orientable;
  d["self_intersecting"] = t.self_intersecting;
  d["closed"] = t.closed();
  d["manifold"] = t.manifold();
  return d;
}

}  // namespace

void bind_eval(py::module_& m) {
  m.def("sample",
        [](const py::object& mesh, std::size_t count, double noise, std::uint64_t seed, bool normals, double density_ratio,
           std::size_t missing_patches, double missing_radius) {
          const SurfaceMesh surface = to_mesh(mesh, "mesh");
          SampleOptions o;
          o.count = count;
          o.noise = noise;
          o.seed = seed;
          o.with_normals = normals;
          o.density_ratio = density_ratio;
          o.missing_patches = missing_patches;
          o.missing_radius = missing_radius;
          o.check();
          PointSet set;
          {
            py::gil_scoped_release release;
            set = sample_mesh(surface, o);
          }
          return make_point_cloud(set);
        },
        py::arg("mesh"), py::kw_only(), py::arg("count") = 100000, py::arg("noise") = 0.0, py::arg("seed") = 0,
        py::arg("normals") = false, py::arg("density_ratio") = SampleOptions{}.density_ratio,
        py::arg("missing_patches") = SampleOptions{}.missing_patches, py::arg("missing_radius") = SampleOptions{}.missing_radius,
        "Samples of a mesh, as `sharpmesh sample` -> PointCloud. noise: uniform, fraction of the diagonal (7.5); density_ratio: "
        "densest / sparsest density along a seeded direction; missing_patches balls of missing_radius x diagonal without samples.");
  m.def("sharp_edges",
        [](const py::object& mesh, double sharp_angle) { return from_polylines(sharp_edges(to_mesh(mesh, "mesh"), sharp_angle)); },
        py::arg("mesh"), py::arg("sharp_angle") = 30.0,
        "Edges whose facets make an angle above sharp_angle degrees from flat, chained into polylines.");
  m.def("evaluate",
        [](const py::object& mesh, const py::object& reference, std::size_t samples, std::uint64_t seed, double sharp_angle,
           const py::object& progress) {
          const SurfaceMesh a = to_mesh(mesh, "mesh"), b = to_mesh(reference, "reference");
          DistanceOptions o;
          o.samples = samples;
          o.seed = seed;
          o.sharp_angle = sharp_angle;
          o.check();
          ProgressBridge bridge(progress);
          const DistanceReport r = without_gil(bridge, [&] { return compare_meshes(a, b, o, bridge.callback()); });
          const TopologyReport t = without_gil(bridge, [&] { return check_topology(a); });
          py::dict d;
          d["diagonal"] = r.diagonal;
          d["hausdorff"] = r.hausdorff;
          d["mesh_to_reference_max"] = r.mesh_to_reference_max;
          d["reference_to_mesh_max"] = r.reference_to_mesh_max;
          d["mesh_to_reference_mean"] = r.mesh_to_reference_mean;
          d["reference_to_mesh_mean"] = r.reference_to_mesh_mean;
          d["mean"] = r.mean;
          d["rms"] = r.rms;
          d["sharp_edge_length"] = r.sharp_edge_length;
          d["sharp_mean"] = r.sharp_mean;
          d["sharp_max"] = r.sharp_max;
          d["facets"] = a.faces.size();
          d["vertices"] = a.vertices.size();
          d["topology"] = topology_dict(t);
          return d;
        },
        py::arg("mesh"), py::arg("reference"), py::kw_only(), py::arg("samples") = 200000, py::arg("seed") = 0,
        py::arg("sharp_angle") = 30.0, py::arg("progress") = py::none(),
        "Distances between a mesh and a reference, as `sharpmesh eval` -> dict (data units; 'diagonal' is the reference's).");
  m.def("eval_features",
        [](const py::object& polylines, const py::object& reference, double sharp_angle, double tolerance) {
          const std::vector<Polyline> lines = to_polylines(polylines, "polylines");
          const SurfaceMesh ref = to_mesh(reference, "reference");
          FeatureEvalOptions o;
          o.sharp_angle = sharp_angle;
          o.tolerance = tolerance;
          o.check();
          FeatureEvaluation e;
          {
            py::gil_scoped_release release;
            e = evaluate_features(lines, polyline_corners(lines), ref, o);
          }
          py::dict d;
          d["diagonal"] = e.diagonal;
          d["tolerance"] = e.tolerance;
          d["truth_length"] = e.truth_length;
          d["extracted_length"] = e.extracted_length;
          d["recall"] = e.recall;
          d["precision"] = e.precision;
          d["truth_to_extracted_mean"] = e.truth_to_extracted_mean;
          d["truth_to_extracted_max"] = e.truth_to_extracted_max;
          d["extracted_to_truth_mean"] = e.extracted_to_truth_mean;
          d["extracted_to_truth_max"] = e.extracted_to_truth_max;
          d["truth_corners"] = e.truth_corners;
          d["recalled_corners"] = e.recalled_corners;
          return d;
        },
        py::arg("polylines"), py::arg("reference"), py::kw_only(), py::arg("sharp_angle") = 30.0, py::arg("tolerance") = 0.005,
        "Feature benchmark, as `sharpmesh eval-features` -> dict. tolerance: fraction of the reference's diagonal.");
  m.def("check_topology",
        [](const py::object& mesh, bool self_intersections) {
          const SurfaceMesh a = to_mesh(mesh, "mesh");
          TopologyReport t;
          {
            py::gil_scoped_release release;
            t = check_topology(a, self_intersections);
          }
          return topology_dict(t);
        },
        py::arg("mesh"), py::arg("self_intersections") = true,
        "Closed, manifold, orientable, self-intersecting; boundary and non-manifold counts -> dict.");
  m.def("distances_to_mesh",
        [](const DoubleArray& points, const py::object& mesh) {
          const std::vector<Vec3> p = to_points(points, "points");
          const SurfaceMesh a = to_mesh(mesh, "mesh");
          std::vector<double> d;
          {
            py::gil_scoped_release release;
            d = distances_to_mesh(p, a);
          }
          return from_values(d);
        },
        py::arg("points"), py::arg("mesh"), "Distance from each point to the nearest point of the mesh -> (n,) array.");
}

}  // namespace sharpmesh::python
