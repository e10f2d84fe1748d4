// Sharp feature extraction (thesis 7.2, 7.4; sharpmesh/features.h), with the
// options of `sharpmesh features`.
#include "convert.h"
#include "options.h"
#include "sharpmesh/features.h"
#include "sharpmesh/report.h"

namespace sharpmesh::python {

py::dict stages_dict(const std::vector<StageTiming>& stages) {
  py::dict d;
  for (const StageTiming& s : stages) d[py::str(s.name)] = s.seconds;
  return d;
}

py::object make_features(const FeatureResult& r, const py::object& report) {
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
  return py::module_::import("sharpmesh._types")
      .attr("Features")(from_polylines(r.graph.polylines), from_points(junctions), types, degrees, classes, from_points(directions),
                        from_points(normals), from_values(ratio01), from_values(ratio12), report);
}

py::object json_report(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

void bind_features(py::module_& m) {
  bind_option_class(m, "FeatureOptions", feature_option_fields(), "Options of extract_features() and the feature part of reconstruct() (thesis 7.2).");
  m.def("extract_features",
        [](const DoubleArray& points, const py::object& options, const py::object& progress, const py::kwargs& keywords) {
          PointSet set;
          set.points = to_points(points, "points");
          const FeatureOptions o = options_from<FeatureOptions>(options, keywords, feature_option_fields());
          o.check();
          ProgressBridge bridge(progress);
          const FeatureResult result = without_gil(bridge, [&] { return extract_features(set, o, bridge.callback()); });
          const double diagonal = bounding_box(set.points).diagonal();
          return make_features(result, json_report(feature_report_json(result, o, diagonal)));
        },
        py::arg("points"), py::kw_only(), py::arg("options") = py::none(), py::arg("progress") = py::none(),
        ("Sharp features of a point cloud, as `sharpmesh features` (thesis 7.2) -> Features, whose report is the "
         "command's --report.\n\noptions: a FeatureOptions; keywords override it (no_NAME=True turns a switch off):\n" +
         keyword_help(feature_option_fields()))
            .c_str());
}

}  // namespace sharpmesh::python
