// Sharp feature extraction (thesis 7.2, 7.4; sharpmesh/features.h), with the
// options of `sharpmesh features`.
#include "convert.h"
#include "sharpmesh/features.h"

namespace sharpmesh::python {

py::dict stages_dict(const std::vector<StageTiming>& stages) {
  py::dict d;
  for (const StageTiming& s : stages) d[py::str(s.name)] = s.seconds;
  return d;
}

py::object make_features(const FeatureResult& r) {
  const std::size_t n = r.points.size();
  py::array_t<std::uint8_t> classes(static_cast<py::ssize_t>(n));
  std::vector<Vec3> directions(n), normals(n);
  std::vector<double> ratio01(n), ratio12(n);
  for (std::size_t i = 0; i < n; ++i) {
    classes.mutable_at(i) = static_cast<std::uint8_t>(r.points[i].type);
    directions[i] = r.points[i].direction;
    normals[i] = r.points[i].normal;
    ratio01[i] = r.points[i].ratio01;
    ratio12[i] = r.points[i].ratio12;
  }
  std::vector<Vec3> junctions;
  py::list types;
  py::array_t<std::int32_t> degrees(static_cast<py::ssize_t>(r.graph.junctions.size()));
  for (std::size_t i = 0; i < r.graph.junctions.size(); ++i) {
    const Junction& j = r.graph.junctions[i];
    junctions.push_back(j.position);
    types.append(j.type == JunctionType::Dart ? "dart" : j.type == JunctionType::Cusp ? "cusp" : "corner");
    degrees.mutable_at(i) = j.degree;
  }
  py::dict report;
  report["offset_radius"] = r.offset_radius;
  report["convolution_radius"] = r.convolution_radius;
  report["noise_estimate"] = r.noise_estimate;
  report["average_spacing"] = r.average_spacing;
  report["denoise_k"] = r.denoise_k;
  report["edge_points"] = r.edge_points;
  report["corner_points"] = r.corner_points;
  report["fitted_corner_points"] = r.fitted_corner_points;
  report["clusters"] = r.clusters;
  report["pruned_clusters"] = r.pruned_clusters;
  report["off_data_polylines"] = r.off_data_polylines;
  report["polylines"] = r.graph.polylines.size();
  report["junctions"] = r.graph.junctions.size();
  report["stages"] = stages_dict(r.stages);
  return py::module_::import("sharpmesh._types")
      .attr("Features")(from_polylines(r.graph.polylines), from_points(junctions), types, degrees, classes, from_points(directions),
                        from_points(normals), from_values(ratio01), from_values(ratio12), report);
}

FeatureOptions feature_options(double offset_radius, double convolution_radius, double t1, double t2, int cluster_k,
                               double cluster_angle, int successor_k, double junction_factor, int denoise_k,
                               bool fit_corner_points) {
  FeatureOptions o;
  o.offset_radius = offset_radius;
  o.convolution_radius = convolution_radius;
  o.t1 = t1;
  o.t2 = t2;
  o.cluster_k = cluster_k;
  o.cluster_angle = cluster_angle;
  o.successor_k = successor_k;
  o.junction_factor = junction_factor;
  o.denoise_k = denoise_k;
  o.fit_corner_points = fit_corner_points;
  o.check();
  return o;
}

void bind_features(py::module_& m) {
  const FeatureOptions d;
  m.def("extract_features",
        [](const DoubleArray& points, double offset_radius, double convolution_radius, double t1, double t2, int cluster_k,
           double cluster_angle, int successor_k, double junction_factor, int denoise_k, bool fit_corner_points, const py::object& progress) {
          PointSet set;
          set.points = to_points(points, "points");
          const FeatureOptions options = feature_options(offset_radius, convolution_radius, t1, t2, cluster_k, cluster_angle,
                                                         successor_k, junction_factor, denoise_k, fit_corner_points);
          ProgressBridge bridge(progress);
          const FeatureResult result = without_gil(bridge, [&] { return extract_features(set, options, bridge.callback()); });
          return make_features(result);
        },
        py::arg("points"), py::kw_only(), py::arg("offset_radius") = d.offset_radius, py::arg("convolution_radius") = d.convolution_radius,
        py::arg("t1") = d.t1, py::arg("t2") = d.t2, py::arg("cluster_k") = d.cluster_k, py::arg("cluster_angle") = d.cluster_angle,
        py::arg("successor_k") = d.successor_k, py::arg("junction_factor") = d.junction_factor, py::arg("denoise_k") = d.denoise_k,
        py::arg("fit_corner_points") = d.fit_corner_points,
        py::arg("progress") = py::none(),
        R"(Sharp features of a point cloud, as `sharpmesh features` (thesis 7.2) -> Features.

offset_radius: R, fraction of the bounding-sphere radius (0.1); convolution_radius: r, fraction of R (0: automatic, R/10
or more with noise); t1, t2: Algorithm 1 thresholds; cluster_k, cluster_angle (degrees): Algorithm 2; successor_k and
junction_factor: polyline and junction recovery (7.2.3); denoise_k: jet smoothing before the VCM (-1 automatic, 0 never); fit_corner_points: corner points on the line of two
faces become edge points (beyond the thesis; False: the thesis's Algorithm 1).)");
}

}  // namespace sharpmesh::python
