// Looking at results: a self-contained HTML page (three.js bundled in, opens
// offline) showing a mesh with flat shading, its feature polylines, optionally
// the input points and a colouring by distance to a reference; and a PNG of
// that page rendered by headless Chromium.
#pragma once
#include <string>
#include <vector>

#include "sharpmesh/stereo.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

/// What the page shows. Only `mesh` is required.
struct ViewScene {
  std::string title;                 ///< shown on the page (usually the file name)
  SurfaceMesh mesh;
  std::vector<Polyline> features;    ///< drawn as thick lines in a contrasting colour
  std::vector<Vec3> points;          ///< drawn as small dots (e.g. the input cloud)
  /// Per-vertex distances to a reference (empty: no colouring).
  std::vector<double> vertex_distances;
  std::string reference_name;        ///< named in the legend of the colouring
  /// Distance mapped to the top of the colour ramp (0: the largest distance).
  /// Give the same value to pages that are compared side by side.
  double distance_scale = 0;
};

/// A camera to look through, in world coordinates: an input camera of a
/// stereo model (view_camera), so a mesh can be seen as that photo saw it.
struct ViewCamera {
  std::string name;
  Vec3 position{0, 0, 0};
  Vec3 forward{0, 0, 1};  ///< unit viewing direction
  Vec3 up{0, -1, 0};      ///< unit, the image's up
  double vertical_fov_degrees = 50;
  double aspect = 4.0 / 3.0;  ///< image width / height
};

/// A stereo camera as a ViewCamera (COLMAP's y runs down the image, so up is
/// -y of the camera). The principal point is taken at the image centre.
ViewCamera view_camera(const Camera& camera);

/// The up direction the cameras agree on (mean of their image-up vectors),
/// for scenes whose world is not z-up; z when there are no cameras.
Vec3 cameras_up(const std::vector<Camera>& cameras);

struct ViewOptions {
  std::string view = "iso";  ///< iso, front, back, left, right, top, bottom
  /// The world's up for the named views (unit length; z for CAD and LiDAR).
  Vec3 up{0, 0, 1};
  /// Cameras offered on the page (a button each; keys c/C cycle them).
  std::vector<ViewCamera> cameras;
  int camera = -1;  ///< start looking through cameras[camera] (-1: the named view)
  /// Draw every mesh edge faintly (-1: automatic, on below 300,000 facets).
  int wireframe = -1;
  bool bare = false;         ///< no text overlay (figures)
  void check() const;
};

/// False when this build has no viewer (npm was not available at build time).
bool viewer_available();

/// The HTML page (UTF-8), self-contained. Throws InvalidArgument for an empty
/// mesh, bad indices or options, or when the viewer is not available.
std::string viewer_page(const ViewScene& scene, const ViewOptions& options = {});

struct RenderOptions {
  int width = 1600, height = 1200;  ///< pixels
  /// Browser binary; empty: chromium, chromium-browser or google-chrome on
  /// PATH. The command line and Python take it from $SHARPMESH_BROWSER when
  /// not given; the library reads no setting from the environment.
  std::string browser;
  double timeout_seconds = 120;
  /// A picture (for example the photograph of the camera looked through)
  /// placed left of the rendering, scaled to its height; empty: none.
  std::string beside;
  void check() const;
};

/// Renders the page of `scene` to a PNG file (written atomically) with a
/// headless browser. Throws InvalidArgument when no browser is found and
/// NumericalFailure when the page did not render (with the page's error).
void render_png(const std::string& png_path, const ViewScene& scene, const ViewOptions& view = {},
                const RenderOptions& render = {});

}  // namespace sharpmesh
