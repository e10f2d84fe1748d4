// The point-set toolbox (thesis App. A; sharpmesh/pointset.h), with the
// options of `sharpmesh clean` in the same order: outliers, simplification,
// smoothing, normals, orientation.
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
           const std::string& orient_method, bool winding_repair, const py::object& progress) {
          PointSet set = to_point_set(points, point_normals);
          if (normals && *normals != "pca" && *normals != "jet" && *normals != "shifted")
            throw InvalidArgument("normals must be 'pca', 'jet' or 'shifted'");
          if (orient_method != "tangent" && orient_method != "cgal") throw InvalidArgument("orient_method must be 'tangent' or 'cgal'");
          CleanOptions options;
          if (outliers) options.outliers = PercentageOutlierOptions{outlier_k, *outliers};
          if (outliers_sigma) options.outliers_sigma = SigmaOutlierOptions{sigma_k, *outliers_sigma};
          options.grid_cell = grid;
          options.random_percentage = random;
          options.seed = seed;
          if (smooth != 0) options.smoothing = JetSmoothingOptions{smooth};
          if (normals) options.normals = NormalEstimationOptions{*normals == "pca" ? NormalMethod::Pca : NormalMethod::Jet, normal_k};
          if (normals && *normals == "shifted") options.crease_aware_normals = ShiftedNormalOptions{};
          if (orient) options.orientation = orient_method == "cgal" ? CleanOptions::Orientation::CgalMst : CleanOptions::Orientation::TangentMst;
          options.orient_k = orient_k;
          options.repair_enclosed = winding_repair;
          options.check();
          ProgressBridge bridge(progress);
          without_gil(bridge, [&] {
            check_point_set(set, 1, "points");
            clean_point_set(set, options, bridge.callback());
          });
          return make_point_cloud(set);
        },
        py::arg("points"), py::arg("point_normals") = py::none(), py::kw_only(), py::arg("outliers") = py::none(),
        py::arg("outlier_k") = 24, py::arg("outliers_sigma") = py::none(), py::arg("sigma_k") = 150, py::arg("grid") = py::none(),
        py::arg("random") = py::none(), py::arg("seed") = 0, py::arg("smooth") = 0, py::arg("normals") = py::none(),
        py::arg("normal_k") = 18, py::arg("orient") = false, py::arg("orient_k") = 18, py::arg("orient_method") = "tangent",
        py::arg("winding_repair") = true, py::arg("progress") = py::none(),
        R"(The point-set toolbox of `sharpmesh clean` (thesis App. A) -> PointCloud.

outliers: remove this % of points with the largest average squared kNN distance (A.4), over outlier_k neighbours;
outliers_sigma: remove points beyond mean + S standard deviations of that distance (6.3.1), over sigma_k neighbours;
grid: keep one point per cell of this size, in multiples of the average spacing (A.5); random: remove this % at random (seed);
smooth: jet smoothing over this many neighbours (A.6); normals: 'pca' or 'jet' over normal_k neighbours (A.7), or 'shifted' (jet, then
crease-aware planes from shifted neighbourhoods, signed like the jet normals);
orient: MST orientation over orient_k neighbours (A.8), orient_method 'tangent' or 'cgal'; with 'tangent', winding_repair
then flips the regions whose outer side the rest of the cloud encloses (generalized winding number).)");
}

}  // namespace sharpmesh::python
