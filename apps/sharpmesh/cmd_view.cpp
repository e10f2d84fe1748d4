// sharpmesh view MESH -o page.html and sharpmesh render MESH -o shot.png:
// the mesh, its feature polylines, the input points and the distance to a
// reference, as an offline HTML page or a PNG made by headless Chromium.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli.h"
#include "sharpmesh/eval.h"
#include "sharpmesh/io.h"
#include "sharpmesh/stereo_io.h"
#include "sharpmesh/view.h"

namespace sharpmesh::cli {
namespace {

struct SceneOptions {
  std::string mesh, features, points, reference, output;
  double distance_scale = 0;
  std::size_t max_points = 500'000;
  std::string wireframe = "auto";
  std::string model, camera, up = "z";
  ViewOptions view;
  std::vector<Camera> model_cameras;  ///< of --model, in the order of view.cameras
};

void add_scene_options(CLI::App& sub, SceneOptions& o) {
  sub.add_option("MESH", o.mesh, "Mesh to show (.off, .ply, .obj, .stl)")->required();
  sub.add_option("--features", o.features, "Feature polylines to draw on it (CGAL text format, e.g. reconstruct --sharp-edges)");
  sub.add_option("--points", o.points, "Point cloud to draw as dots (e.g. the input of reconstruct)");
  sub.add_option("--max-points", o.max_points, "Draw at most this many of the points (every n-th)")->check(CLI::PositiveNumber)->capture_default_str();
  sub.add_option("-r,--reference", o.reference, "Colour the mesh by the distance of its vertices to this reference mesh");
  sub.add_option("--distance-scale", o.distance_scale,
                 "Distance at the red end of the colour ramp, data units (0: the largest distance); give pages compared side by side the same value")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  sub.add_option("--view", o.view.view, "Initial camera: iso, front, back, left, right, top or bottom (z up)")
      ->check(CLI::IsMember({"iso", "front", "back", "left", "right", "top", "bottom"}))->capture_default_str();
  sub.add_option("--wireframe", o.wireframe, "Draw the mesh edges: auto (below 300,000 facets), on or off")
      ->check(CLI::IsMember({"auto", "on", "off"}))->capture_default_str();
  sub.add_flag("--bare", o.view.bare, "No text overlay (for figures)");
  sub.add_option("--model", o.model, "Cameras to look through: a stereo model (COLMAP folder, .out, .nvm); a button each on the page");
  sub.add_option("--camera", o.camera, "Start looking through this camera of --model (its image name)");
  sub.add_option("--up", o.up, "The world's up for the named views: x, y, z, -x, -y, -z, or cameras (the --model cameras' mean up)")
      ->check(CLI::IsMember({"x", "y", "z", "-x", "-y", "-z", "cameras"}))->capture_default_str();
}

/// The --model cameras, --camera and --up into the view options.
void load_cameras(SceneOptions& o) {
  if (o.model.empty()) {
    if (!o.camera.empty()) throw InvalidArgument("--camera needs --model (the stereo model the camera belongs to)");
    if (o.up == "cameras") throw InvalidArgument("--up cameras needs --model");
  } else {
    StereoModel model = read_stereo_model(o.model);
    canonical_order(model);
    o.model_cameras = model.cameras;
    for (const Camera& c : model.cameras) o.view.cameras.push_back(view_camera(c));
    if (!o.camera.empty()) {
      const auto it = std::find_if(model.cameras.begin(), model.cameras.end(), [&](const Camera& c) { return c.image_name == o.camera; });
      if (it == model.cameras.end()) throw InvalidArgument(o.model + ": no camera '" + o.camera + "' (cameras are named by their image)");
      o.view.camera = static_cast<int>(it - model.cameras.begin());
    }
  }
  if (o.up == "cameras") {
    o.view.up = cameras_up(o.model_cameras);
  } else {
    const double sign = o.up[0] == '-' ? -1 : 1;
    const int axis = o.up.back() - 'x';
    o.view.up = {0, 0, 0};
    o.view.up[axis] = sign;
  }
}

ViewScene load_scene(SceneOptions& o, ProgressPrinter& printer) {
  o.view.wireframe = o.wireframe == "auto" ? -1 : o.wireframe == "on" ? 1 : 0;
  load_cameras(o);
  ViewScene scene;
  scene.title = std::filesystem::path(o.mesh).filename().string();
  scene.mesh = read_mesh(o.mesh);
  if (scene.mesh.faces.empty()) throw InvalidInput(o.mesh + ": the mesh has no facets");
  if (!o.features.empty()) scene.features = read_polylines(o.features);
  if (!o.points.empty()) {
    const PointSet cloud = read_point_set(o.points);
    const std::size_t step = (cloud.size() + o.max_points - 1) / o.max_points;
    for (std::size_t i = 0; i < cloud.size(); i += std::max<std::size_t>(step, 1)) scene.points.push_back(cloud.points[i]);
  }
  if (!o.reference.empty()) {
    printer.message("view: distances to " + o.reference);
    const SurfaceMesh reference = read_mesh(o.reference);
    if (reference.faces.empty()) throw InvalidInput(o.reference + ": the reference mesh has no facets");
    scene.vertex_distances = distances_to_mesh(scene.mesh.vertices, reference);
    scene.reference_name = std::filesystem::path(o.reference).filename().string();
    scene.distance_scale = o.distance_scale;
  }
  return scene;
}

nlohmann::json scene_report(const char* command, const SceneOptions& o, const ViewScene& scene) {
  std::size_t segments = 0;
  for (const Polyline& p : scene.features) segments += p.size() > 1 ? p.size() - 1 : 0;
  return {{"command", command},
          {"input", o.mesh},
          {"output", o.output},
          {"parameters",
           {{"features", o.features}, {"points", o.points}, {"reference", o.reference}, {"view", o.view.view},
            {"model", o.model}, {"camera", o.camera}, {"up", o.up},
            {"wireframe", o.wireframe}, {"bare", o.view.bare}, {"distance_scale", o.distance_scale}}},
          {"counts",
           {{"facets", scene.mesh.faces.size()}, {"vertices", scene.mesh.vertices.size()},
            {"feature_polylines", scene.features.size()}, {"feature_segments", segments}, {"points", scene.points.size()}}}};
}

}  // namespace

Command add_view(CLI::App& app) {
  auto o = std::make_shared<SceneOptions>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("view", "Write a self-contained HTML page (opens offline) showing a mesh, its feature lines, points and errors");
  add_scene_options(*sub, *o);
  sub->add_option("-o,--output", o->output, "Output page (.html)")->required();
  common->add_to(*sub);
  auto run = [o, common] {
    check_output(o->output, "page");
    check_output(common->report, "report");
    const auto start = std::chrono::steady_clock::now();
    ProgressPrinter printer(common->quiet);
    const ViewScene scene = load_scene(*o, printer);
    write_text_file(o->output, viewer_page(scene, o->view));
    if (!common->quiet)
      printer.message("view: " + std::to_string(scene.mesh.faces.size()) + " facets, " + std::to_string(scene.features.size()) +
                      " feature polylines -> " + o->output);
    nlohmann::json report = scene_report("view", *o, scene);
    report["seconds"] = seconds_since(start);
    write_report(common->report, report);
  };
  return {sub, run, common};
}

Command add_render(CLI::App& app) {
  auto o = std::make_shared<SceneOptions>();
  auto render = std::make_shared<RenderOptions>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* sub = app.add_subcommand("render", "Render the page of `view` to a PNG without a display (headless Chromium)");
  add_scene_options(*sub, *o);
  sub->add_option("-o,--output", o->output, "Output picture (.png)")->required();
  sub->add_option("--width", render->width, "Picture width, pixels")->capture_default_str();
  sub->add_option("--height", render->height, "Picture height, pixels")->capture_default_str();
  sub->add_option("--browser", render->browser, "Browser binary (default: $SHARPMESH_BROWSER, else chromium on PATH)")
      ->envname("SHARPMESH_BROWSER");
  sub->add_option("--timeout", render->timeout_seconds, "Give up after this many seconds")->capture_default_str();
  auto photo = std::make_shared<bool>(false);
  auto images = std::make_shared<std::string>();
  sub->add_flag("--photo", *photo, "Put the --camera's photograph left of the rendering, at the same height");
  sub->add_option("--images", *images, "Folder of the model's photographs (default: as `stereo` finds them)");
  common->add_to(*sub);
  auto run = [o, render, common, photo, images, sub] {
    check_output(o->output, "picture");
    check_output(common->report, "report");
    if (std::filesystem::path(o->output).extension() != ".png") throw InvalidArgument(o->output + ": render writes .png pictures");
    render->check();
    const auto start = std::chrono::steady_clock::now();
    ProgressPrinter printer(common->quiet);
    const ViewScene scene = load_scene(*o, printer);
    if (o->view.camera >= 0) {
      // The picture takes the camera's shape unless a height is given.
      const Camera& camera = o->model_cameras[static_cast<std::size_t>(o->view.camera)];
      if (sub->count("--height") == 0) render->height = std::max(16, static_cast<int>(std::lround(render->width * double(camera.height) / camera.width)));
      if (*photo)
        render->beside = (std::filesystem::path(images->empty() ? default_image_folder(o->model) : *images) / camera.image_name).string();
    } else if (*photo) {
      throw InvalidArgument("--photo needs --camera (whose photograph to show)");
    }
    if (!common->quiet) printer.message("render: starting the headless browser");
    render_png(o->output, scene, o->view, *render);
    if (!common->quiet)
      printer.message("render: " + std::to_string(render->width) + " x " + std::to_string(render->height) + " -> " + o->output);
    nlohmann::json report = scene_report("render", *o, scene);
    report["parameters"]["width"] = render->width;
    report["parameters"]["height"] = render->height;
    report["seconds"] = seconds_since(start);
    write_report(common->report, report);
  };
  return {sub, run, common};
}

}  // namespace sharpmesh::cli
