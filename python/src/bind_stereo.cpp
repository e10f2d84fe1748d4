// Multi-view stereo (thesis Ch. 6; sharpmesh/stereo_reconstruct.h) with the
// main options of `sharpmesh stereo`: tracks, filters, the soup fill and mesh size.
#include "convert.h"
#include "sharpmesh/stereo_io.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh::python {

void bind_stereo(py::module_& m) {
  const StereoReconstructionOptions d;
  m.def("stereo",
        [](const std::string& model_path, const std::string& images, const std::string& tracks, double merge_distance,
           int outlier_k, bool outlier_global, int smooth_k, double min_cone_angle, bool cone_angle_on_fused, double canny_sigma, double canny_low, double canny_high,
           bool canny_fixed,
           int max_crossings, double grazing_angle, double ncc, bool no_photo, bool no_track_photo, double angle, double size,
           double distance, std::uint32_t seed, bool no_fill, double max_hole, const py::object& progress) {
          StereoReconstructionOptions o;
          o.tracks.merge_distance = merge_distance;
          o.tracks.outlier_k = outlier_k;
          o.tracks.outlier_relative = !outlier_global;
          o.tracks.smooth_k = smooth_k;
          o.tracks.min_cone_angle = min_cone_angle;
          o.tracks.cone_angle_on_dense_points = cone_angle_on_fused;
          o.track_photo.enabled = !no_track_photo;
          o.depth_maps.canny_sigma = canny_sigma;
          o.depth_maps.canny_low = canny_low;
          o.depth_maps.canny_high = canny_high;
          o.depth_maps.canny_adaptive = !canny_fixed;
          o.filters.max_crossings = max_crossings;
          o.filters.grazing_angle = grazing_angle;
          o.filters.ncc_threshold = ncc;
          o.filters.photo_consistency = !no_photo;
          o.meshing.angle = angle;
          o.meshing.size = size;
          o.meshing.distance = distance;
          o.meshing.seed = seed;
          o.fill.enabled = !no_fill;
          o.max_hole = max_hole;
          o.check();
          ProgressBridge bridge(progress);
          StereoReconstruction r;
          StereoModel model;
          without_gil(bridge, [&] {
            model = load_stereo_model(model_path, tracks);
            const auto grey = read_grey_images(model, images.empty() ? default_image_folder(model_path) : images, bridge.callback());
            r = reconstruct_stereo(model, grey, o, bridge.callback());
          });
          py::dict counts;
          counts["views"] = model.cameras.size();
          counts["tracks_input"] = r.tracks.input;
          counts["tracks_kept"] = model.tracks.size();
          counts["cone_filter_skipped_fused"] = r.tracks.cone_filter_skipped;
          counts["soup_triangles"] = r.soup_triangles;
          counts["soup_kept"] = r.filters.output;
          counts["facets"] = r.meshing.mesh.faces.size();
          counts["fill_added"] = r.fill.added;
          counts["holes_filled"] = r.holes.filled;
          py::dict report;
          report["counts"] = counts;
          report["half_diagonal"] = r.tracks.half_diagonal;
          report["soup_half_diagonal"] = r.meshing.half_diagonal;
          report["stages"] = stages_dict(r.stages);
          std::vector<Vec3> track_points;
          for (const Track& t : model.tracks) track_points.push_back(t.position);
          return py::make_tuple(make_mesh(r.meshing.mesh), from_points(track_points), report);
        },
        py::arg("model"), py::kw_only(), py::arg("images") = "", py::arg("tracks") = "",
        py::arg("merge_distance") = d.tracks.merge_distance, py::arg("outlier_k") = d.tracks.outlier_k,
        py::arg("outlier_global") = !d.tracks.outlier_relative,
        py::arg("smooth_k") = d.tracks.smooth_k, py::arg("min_cone_angle") = d.tracks.min_cone_angle,
        py::arg("cone_angle_on_fused") = d.tracks.cone_angle_on_dense_points,
        py::arg("canny_sigma") = d.depth_maps.canny_sigma, py::arg("canny_low") = d.depth_maps.canny_low,
        py::arg("canny_high") = d.depth_maps.canny_high, py::arg("canny_fixed") = false, py::arg("max_crossings") = d.filters.max_crossings,
        py::arg("grazing_angle") = d.filters.grazing_angle, py::arg("ncc") = d.filters.ncc_threshold,
        py::arg("no_photo") = false, py::arg("no_track_photo") = false, py::arg("angle") = d.meshing.angle,
        py::arg("size") = d.meshing.size, py::arg("distance") = d.meshing.distance, py::arg("seed") = d.meshing.seed,
        py::arg("no_fill") = !d.fill.enabled, py::arg("max_hole") = d.max_hole, py::arg("progress") = py::none(),
        R"(Calibrated images and tracks -> mesh, as `sharpmesh stereo MODEL` (thesis Ch. 6) -> (Mesh, tracks (n, 3), report).

model: a COLMAP model folder, a Bundler .out, an .nvm, or a folder of Strecha .camera files (with tracks=);
images: their folder (default: MODEL/images or next to it); tracks: a tracks PLY or COLMAP's fused.ply (with .vis).
merge_distance is a fraction of the input tracks' half diagonal (report['half_diagonal']), size, distance and max_hole of the
filtered soup's (report['soup_half_diagonal']); the other options are those of the CLI.)");
}

}  // namespace sharpmesh::python
