// Looking at results (sharpmesh/view.h): the HTML page of `sharpmesh view`
// and the PNG of `sharpmesh render`.
#include "convert.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/view.h"

namespace sharpmesh::python {
namespace {

struct SceneArgs {
  ViewScene scene;
  ViewOptions view;
};

SceneArgs scene_args(const py::object& mesh, const py::object& features, const py::object& points, const py::object& reference,
                     double distance_scale, const std::string& view, const std::string& wireframe, bool bare, const std::string& title) {
  SceneArgs a;
  a.scene.title = title;
  a.scene.mesh = to_mesh(mesh, "mesh");
  a.scene.features = to_polylines(features, "features");
  if (!points.is_none()) a.scene.points = to_points(py::cast<DoubleArray>(points), "points");
  if (!reference.is_none()) {
    const SurfaceMesh ref = to_mesh(reference, "reference");
    py::gil_scoped_release release;
    a.scene.vertex_distances = distances_to_mesh(a.scene.mesh.vertices, ref);
  }
  a.scene.reference_name = "the reference";
  a.scene.distance_scale = distance_scale;
  a.view.view = view;
  if (wireframe != "auto" && wireframe != "on" && wireframe != "off") throw InvalidArgument("wireframe must be 'auto', 'on' or 'off'");
  a.view.wireframe = wireframe == "auto" ? -1 : wireframe == "on" ? 1 : 0;
  a.view.bare = bare;
  return a;
}

}  // namespace

void bind_view(py::module_& m) {
  m.def("viewer_available", &viewer_available, "False when this build has no viewer (npm was missing at build time).");
  m.def("view",
        [](const py::object& mesh, const py::object& features, const py::object& points, const py::object& reference,
           double distance_scale, const std::string& view, const std::string& wireframe, bool bare, const std::string& title) {
          const SceneArgs a = scene_args(mesh, features, points, reference, distance_scale, view, wireframe, bare, title);
          return viewer_page(a.scene, a.view);
        },
        py::arg("mesh"), py::kw_only(), py::arg("features") = py::none(), py::arg("points") = py::none(),
        py::arg("reference") = py::none(), py::arg("distance_scale") = 0.0, py::arg("view") = "iso", py::arg("wireframe") = "auto",
        py::arg("bare") = false, py::arg("title") = "mesh",
        R"(The self-contained HTML page of `sharpmesh view` -> str (write it to a file, or show it in a notebook
with IPython.display.HTML). features: polylines drawn on the mesh; points: (n, 3) dots; reference: colour by distance
to this mesh, distance_scale at the red end (0: the largest); view: iso, front, back, left, right, top or bottom.)");
  m.def("render",
        [](const std::string& path, const py::object& mesh, const py::object& features, const py::object& points,
           const py::object& reference, double distance_scale, const std::string& view, const std::string& wireframe, bool bare,
           const std::string& title, int width, int height, const std::string& browser, double timeout) {
          const SceneArgs a = scene_args(mesh, features, points, reference, distance_scale, view, wireframe, bare, title);
          RenderOptions r;
          r.width = width;
          r.height = height;
          // As the command line: $SHARPMESH_BROWSER when no browser is given.
          r.browser = browser.empty() ? py::module_::import("os").attr("environ").attr("get")("SHARPMESH_BROWSER", "").cast<std::string>()
                                      : browser;
          r.timeout_seconds = timeout;
          py::gil_scoped_release release;
          render_png(path, a.scene, a.view, r);
        },
        py::arg("path"), py::arg("mesh"), py::kw_only(), py::arg("features") = py::none(), py::arg("points") = py::none(),
        py::arg("reference") = py::none(), py::arg("distance_scale") = 0.0, py::arg("view") = "iso", py::arg("wireframe") = "auto",
        py::arg("bare") = false, py::arg("title") = "mesh", py::arg("width") = 1600, py::arg("height") = 1200,
        py::arg("browser") = "", py::arg("timeout") = 120.0,
        "Renders the page of view() to a PNG with headless Chromium, as `sharpmesh render`.");
}

}  // namespace sharpmesh::python
