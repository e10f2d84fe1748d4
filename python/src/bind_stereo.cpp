// Multi-view stereo (thesis Ch. 6; sharpmesh/stereo_reconstruct.h) with the
// options of `sharpmesh stereo` as StereoOptions or keywords, its report as
// the command's --report.
#include "options.h"
#include "sharpmesh/report.h"
#include "sharpmesh/stereo_io.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh::python {

void bind_stereo(py::module_& m) {
  bind_option_class(m, "StereoOptions", stereo_option_fields(), "Options of stereo(), those of `sharpmesh stereo` (thesis Ch. 6).");
  m.def("stereo",
        [](const std::string& model_path, const std::string& images, const std::string& tracks, const py::object& options,
           const py::object& progress, const py::kwargs& keywords) {
          const StereoReconstructionOptions o = options_from<StereoReconstructionOptions>(options, keywords, stereo_option_fields());
          o.check();
          ProgressBridge bridge(progress);
          StereoReconstruction r;
          StereoModel model;
          without_gil(bridge, [&] {
            model = load_stereo_model(model_path, tracks);
            const auto grey = read_grey_images(model, images.empty() ? default_image_folder(model_path) : images, bridge.callback());
            r = reconstruct_stereo(model, grey, o, bridge.callback());
          });
          std::vector<Vec3> track_points;
          for (const Track& t : model.tracks) track_points.push_back(t.position);
          return py::make_tuple(make_mesh(r.meshing.mesh), from_points(track_points), json_report(stereo_report_json(r, o, model)));
        },
        py::arg("model"), py::kw_only(), py::arg("images") = "", py::arg("tracks") = "", py::arg("options") = py::none(),
        py::arg("progress") = py::none(),
        ("Calibrated images and tracks -> mesh, as `sharpmesh stereo MODEL` (thesis Ch. 6) -> (Mesh, tracks (n, 3), report), "
         "the report being the command's --report.\n\n"
         "model: a COLMAP model folder, a Bundler .out, an .nvm, or a folder of Strecha .camera files (with tracks=); images: "
         "their folder (default: MODEL/images or next to it); tracks: a tracks PLY or COLMAP's fused.ply (with .vis); options: "
         "a StereoOptions; keywords override it (no_NAME=True turns a switch off):\n" +
         keyword_help(stereo_option_fields()))
            .c_str());
}

}  // namespace sharpmesh::python
