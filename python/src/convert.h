// numpy <-> sharpmesh conversions, the progress callback and the GIL rules
// shared by the binding files. Arrays come in as any real dtype (converted to
// float64, C order) and go out as float64 (n, 3) / uint32 (m, 3).
#pragma once
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "sharpmesh/progress.h"
#include "sharpmesh/types.h"

namespace sharpmesh::python {

namespace py = pybind11;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using IndexArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

/// (n, 3) array -> points; ValueError naming `what` for another shape.
std::vector<Vec3> to_points(const DoubleArray& array, const char* what);
/// (m, 3) integer array -> triangles, each index checked against `vertex_count`.
std::vector<Triangle> to_faces(const IndexArray& array, std::size_t vertex_count, const char* what);
/// A sequence of (k, 3) arrays -> polylines.
std::vector<Polyline> to_polylines(const py::object& sequence, const char* what);
/// A (vertices, faces) pair (e.g. sharpmesh.Mesh) -> mesh.
SurfaceMesh to_mesh(const py::object& pair, const char* what);

py::array_t<double> from_points(const std::vector<Vec3>& points);
py::array_t<std::uint32_t> from_faces(const std::vector<Triangle>& faces);
py::list from_polylines(const std::vector<Polyline>& polylines);
py::array_t<double> from_values(const std::vector<double>& values);

/// Wraps a Python callable progress(stage, fraction) -> bool|None. The
/// library calls it from its worker thread with the GIL released: the wrapper
/// takes the GIL, turns a False return or Ctrl-C into cancellation, and keeps
/// an exception the callable raised so that `rethrow()` re-raises it.
class ProgressBridge {
 public:
  explicit ProgressBridge(py::object callable);
  Progress callback();
  /// After the computation: re-raises the callable's exception, if any.
  void rethrow();

 private:
  py::object callable_;
  std::shared_ptr<std::optional<py::error_already_set>> error_;
};

/// Runs `work` with the GIL released, the callable's exceptions re-raised.
template <class Work>
auto without_gil(ProgressBridge& bridge, Work&& work) {
  try {
    py::gil_scoped_release release;
    return work();
  } catch (...) {
    bridge.rethrow();
    throw;
  }
}

void bind_io(py::module_& m);
void bind_pointset(py::module_& m);
void bind_features(py::module_& m);
void bind_reconstruct(py::module_& m);
void bind_eval(py::module_& m);
void bind_view(py::module_& m);
void bind_stereo(py::module_& m);
void bind_compact(py::module_& m);

}  // namespace sharpmesh::python

namespace sharpmesh::python {
/// sharpmesh.Mesh / sharpmesh.PointCloud named tuples (sharpmesh/_types.py).
py::object make_mesh(const SurfaceMesh& mesh);
py::object make_point_cloud(const PointSet& set);
/// Points and optional normals (None or (n, 3)) -> point set.
PointSet to_point_set(const DoubleArray& points, const py::object& normals);
}  // namespace sharpmesh::python

#include "sharpmesh/features.h"
namespace sharpmesh::python {
py::dict stages_dict(const std::vector<StageTiming>& stages);
/// sharpmesh.Features from a FeatureResult and its report.
py::object make_features(const FeatureResult& result, const py::object& report);
/// A JSON text as Python objects.
py::object json_report(const std::string& text);
}  // namespace sharpmesh::python
