// Compaction (sharpmesh/compact.h): a mesh's edges collapsed with its sharp
// edges kept, the options of `sharpmesh decimate` as DecimationOptions or
// keywords.
#include "options.h"
#include "sharpmesh/compact.h"
#include "sharpmesh/report.h"

namespace sharpmesh::python {

void bind_compact(py::module_& m) {
  bind_option_class(m, "DecimationOptions", decimation_option_fields(),
                    "Options of decimate(), those of `sharpmesh decimate` and of reconstruct()'s compaction.");
  m.def("decimate",
        [](const py::object& mesh, const py::object& curves, const py::object& options, const py::object& progress,
           const py::kwargs& keywords) {
          SurfaceMesh surface = to_mesh(mesh, "mesh");
          const DecimationOptions o = options_from<DecimationOptions>(options, keywords, decimation_option_fields());
          const std::vector<Polyline> given = to_polylines(curves, "curves");
          ProgressBridge bridge(progress);
          const DecimationResult r = without_gil(bridge, [&] { return decimate(surface, given, o, bridge.callback()); });
          return py::make_tuple(make_mesh(surface), json_report(decimation_report_json(r)));
        },
        py::arg("mesh"), py::kw_only(), py::arg("curves") = py::none(), py::arg("options") = py::none(),
        py::arg("progress") = py::none(),
        ("A lighter mesh, as `sharpmesh decimate` -> (Mesh, report). Edges collapse in the order of Garland-Heckbert "
         "quadrics; the given curves (polylines through the mesh's vertices, e.g. Reconstruction.sharp_edges), the "
         "border and the edges sharper than sharp_angle stay, and corners never move. Crossing facets are not repaired "
         "here (the command does). options: a DecimationOptions; keywords override it:\n" +
         keyword_help(decimation_option_fields()))
            .c_str());
}

}  // namespace sharpmesh::python
