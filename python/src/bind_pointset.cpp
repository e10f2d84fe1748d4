// The point-set toolbox (thesis App. A; sharpmesh/pointset.h), with the
// options of `sharpmesh clean` in the same order: outliers, simplification,
// smoothing, normals, orientation.
#include <cmath>

#include "convert.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh::python {

void bind_pointset(py::module_& m) {
  m.def("average_spacing", [](const DoubleArray& points, int k) {
        PointSet set;
        set.points = to_points(points, "points");
        py::gil_scoped_release release;
        return average_spacing(set, k);
      },
      py::arg("points"), py::arg("k") = 6, "Mean distance from each point to its k nearest neighbours (App. A.3; k = 6 is the thesis's avg).");
  m.def("clean",
        [](const DoubleArray& points, const py::object& point_normals, std::optional<double> outliers, int outlier_k,
           std::optional<double> outliers_sigma, int sigma_k, std::optional<double> grid, std::optional<double> random,
           std::uint64_t seed, int smooth, std::optional<std::string> normals, int normal_k, bool orient, int orient_k,
           const std::string& orient_method, const py::object& progress) {
          PointSet set = to_point_set(points, point_normals);
          if (outliers && !(*outliers >= 0 && *outliers <= 100)) throw InvalidArgument("outliers must be a percentage in [0, 100]");
          if (outliers_sigma && !(*outliers_sigma > 0)) throw InvalidArgument("outliers_sigma must be positive");
          if (grid && !(*grid > 0 && std::isfinite(*grid))) throw InvalidArgument("grid must be a positive multiple of the average spacing");
          if (random && !(*random >= 0 && *random <= 100)) throw InvalidArgument("random must be a percentage in [0, 100]");
          if (smooth != 0 && smooth < 6) throw InvalidArgument("smooth needs at least 6 neighbours to fit a quadric");
          if (normals && *normals != "pca" && *normals != "jet") throw InvalidArgument("normals must be 'pca' or 'jet'");
          if (orient_method != "tangent" && orient_method != "cgal") throw InvalidArgument("orient_method must be 'tangent' or 'cgal'");
          ProgressBridge bridge(progress);
          without_gil(bridge, [&] {
            const Progress callback = bridge.callback();
            check_point_set(set, 1, "points");
            if (outliers) remove_outliers_percentage(set, {outlier_k, *outliers}, callback);
            if (outliers_sigma) remove_outliers_sigma(set, {sigma_k, *outliers_sigma}, callback);
            if (grid) grid_simplify(set, *grid * average_spacing(set, 6, callback));
            if (random) random_simplify(set, *random, seed);
            if (smooth > 0) jet_smooth(set, {smooth}, callback);
            if (normals) estimate_normals(set, {*normals == "pca" ? NormalMethod::Pca : NormalMethod::Jet, normal_k}, callback);
            if (orient) {
              if (orient_method == "cgal") orient_normals_mst(set, {orient_k, true}, callback);
              else orient_normals_tangent_mst(set, orient_k, callback);
            }
          });
          return make_point_cloud(set);
        },
        py::arg("points"), py::arg("point_normals") = py::none(), py::kw_only(), py::arg("outliers") = py::none(),
        py::arg("outlier_k") = 24, py::arg("outliers_sigma") = py::none(), py::arg("sigma_k") = 150, py::arg("grid") = py::none(),
        py::arg("random") = py::none(), py::arg("seed") = 0, py::arg("smooth") = 0, py::arg("normals") = py::none(),
        py::arg("normal_k") = 18, py::arg("orient") = false, py::arg("orient_k") = 18, py::arg("orient_method") = "tangent",
        py::arg("progress") = py::none(),
        R"(The point-set toolbox of `sharpmesh clean` (thesis App. A) -> PointCloud.

outliers: remove this % of points with the largest average squared kNN distance (A.4), over outlier_k neighbours;
outliers_sigma: remove points beyond mean + S standard deviations of that distance (6.3.1), over sigma_k neighbours;
grid: keep one point per cell of this size, in multiples of the average spacing (A.5); random: remove this % at random (seed);
smooth: jet smoothing over this many neighbours (A.6); normals: 'pca' or 'jet' over normal_k neighbours (A.7);
orient: MST orientation over orient_k neighbours (A.8), orient_method 'tangent' or 'cgal'.)");
}

}  // namespace sharpmesh::python
