// The Chapter 7 pipeline (sharpmesh/reconstruct.h): the options of
// `sharpmesh reconstruct` as ReconstructOptions or keywords, its report as
// the command's --report.
#include "options.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/reconstruct.h"
#include "sharpmesh/report.h"

namespace sharpmesh::python {

void bind_reconstruct(py::module_& m) {
  bind_option_class(m, "ReconstructOptions", reconstruct_option_fields(),
                    "Options of reconstruct(), those of `sharpmesh reconstruct` (thesis Ch. 7).");
  m.def("reconstruct",
        [](const DoubleArray& points, const py::object& point_normals, const py::object& options, bool no_features,
           const py::object& features, const py::object& progress, const py::kwargs& keywords) {
          const PointSet set = to_point_set(points, point_normals);
          ReconstructOptions o = options_from<ReconstructOptions>(options, keywords, reconstruct_option_fields());
          if (no_features && !features.is_none()) throw InvalidArgument("give either no_features or features, not both");
          o.feature_mode = no_features ? FeatureMode::None : features.is_none() ? FeatureMode::Extract : FeatureMode::Given;
          o.given_features = to_polylines(features, "features");
          ProgressBridge bridge(progress);
          const ReconstructResult r = without_gil(bridge, [&] { return reconstruct(set, o, bridge.callback()); });
          const py::object report = json_report(reconstruct_report_json(r, o));
          const py::object extracted =
              o.feature_mode == FeatureMode::Extract ? make_features(r.features, report["features"]) : py::object(py::none());
          return py::module_::import("sharpmesh._types")
              .attr("Reconstruction")(make_mesh(r.mesh), from_polylines(r.meshing.feature_edges), extracted, report);
        },
        py::arg("points"), py::arg("point_normals") = py::none(), py::kw_only(), py::arg("options") = py::none(),
        py::arg("no_features") = false, py::arg("features") = py::none(), py::arg("progress") = py::none(),
        ("Point cloud -> mesh with sharp edges, as `sharpmesh reconstruct` (thesis Ch. 7) -> Reconstruction, whose "
         "report is the command's --report (warnings under report['warnings']).\n\n"
         "no_features: the PIF baseline; features: protect these polylines instead of extracting them; options: a "
         "ReconstructOptions; keywords override it (no_NAME=True turns a switch off):\n" +
         keyword_help(reconstruct_option_fields()))
            .c_str());
  m.def("reconstruct_normals",
        [](const DoubleArray& points, const py::object& point_normals, const py::object& options, bool no_features,
           const py::object& progress, const py::kwargs& keywords) {
          const PointSet set = to_point_set(points, point_normals);
          ReconstructOptions o = options_from<ReconstructOptions>(options, keywords, reconstruct_option_fields());
          o.feature_mode = no_features ? FeatureMode::None : FeatureMode::Extract;
          ProgressBridge bridge(progress);
          const NormalsResult r = without_gil(bridge, [&] { return reconstruct_normals(set, o, bridge.callback()); });
          return py::module_::import("sharpmesh._types")
              .attr("OrientedNormals")(make_point_cloud(r.points), json_report(normals_report_json(r, o)));
        },
        py::arg("points"), py::arg("point_normals") = py::none(), py::kw_only(), py::arg("options") = py::none(),
        py::arg("no_features") = false, py::arg("progress") = py::none(),
        "The oriented normals reconstruct() starts Poisson from, without the rest of the pipeline (its prepare and "
         "normals stages: CVCM normals of 7.4 or jet/pca, the anchored tangent MST of A.8, the orientation repairs) "
         "-> OrientedNormals(cloud, report). Given normals are checked and kept as reconstruct() keeps them. "
         "Options and keywords as reconstruct()'s.");
}

}  // namespace sharpmesh::python
