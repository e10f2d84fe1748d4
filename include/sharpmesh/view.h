// Looking at results: a self-contained HTML page (three.js bundled in, opens
// offline) showing a mesh with flat shading, its feature polylines, optionally
// the input points and a colouring by distance to a reference; and a PNG of
// that page rendered by headless Chromium.
#pragma once
#include <string>
#include <vector>

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

struct ViewOptions {
  std::string view = "iso";  ///< iso, front, back, left, right, top, bottom
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
  /// Browser binary; empty: $SHARPMESH_BROWSER, else chromium or chromium-browser on PATH.
  std::string browser;
  double timeout_seconds = 120;
  void check() const;
};

/// Renders the page of `scene` to a PNG file (written atomically) with a
/// headless browser. Throws InvalidArgument when no browser is found and
/// NumericalFailure when the page did not render (with the page's error).
void render_png(const std::string& png_path, const ViewScene& scene, const ViewOptions& view = {},
                const RenderOptions& render = {});

}  // namespace sharpmesh
