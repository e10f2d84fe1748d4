#include "convert.h"

#include <cstring>

namespace sharpmesh::python {

std::vector<Vec3> to_points(const DoubleArray& array, const char* what) {
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw py::value_error(std::string(what) + " must be an (n, 3) array");
  std::vector<Vec3> points(static_cast<std::size_t>(array.shape(0)));
  if (!points.empty()) std::memcpy(points.data(), array.data(), points.size() * sizeof(Vec3));
  return points;
}

std::vector<Triangle> to_faces(const IndexArray& array, std::size_t vertex_count, const char* what) {
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw py::value_error(std::string(what) + " must be an (m, 3) integer array");
  std::vector<Triangle> faces(static_cast<std::size_t>(array.shape(0)));
  const std::int64_t* data = array.data();
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t index = data[3 * i + k];
      if (index < 0 || static_cast<std::size_t>(index) >= vertex_count)
        throw py::value_error(std::string(what) + ": face " + std::to_string(i) + " refers to vertex " + std::to_string(index) +
                              " of " + std::to_string(vertex_count));
      faces[i][k] = static_cast<std::uint32_t>(index);
    }
  return faces;
}

std::vector<Polyline> to_polylines(const py::object& sequence, const char* what) {
  std::vector<Polyline> polylines;
  if (sequence.is_none()) return polylines;
  for (const py::handle item : sequence) {
    polylines.push_back(to_points(py::cast<DoubleArray>(item), what));
    if (polylines.back().size() < 2) throw py::value_error(std::string(what) + ": a polyline needs at least 2 points");
  }
  return polylines;
}

SurfaceMesh to_mesh(const py::object& pair, const char* what) {
  const py::tuple items = py::tuple(pair);
  if (items.size() != 2) throw py::value_error(std::string(what) + " must be a (vertices, faces) pair, such as sharpmesh.Mesh");
  SurfaceMesh mesh;
  mesh.vertices = to_points(py::cast<DoubleArray>(items[0]), what);
  mesh.faces = to_faces(py::cast<IndexArray>(items[1]), mesh.vertices.size(), what);
  return mesh;
}

py::array_t<double> from_points(const std::vector<Vec3>& points) {
  py::array_t<double> array({static_cast<py::ssize_t>(points.size()), py::ssize_t(3)});
  if (!points.empty()) std::memcpy(array.mutable_data(), points.data(), points.size() * sizeof(Vec3));
  return array;
}

py::array_t<std::uint32_t> from_faces(const std::vector<Triangle>& faces) {
  py::array_t<std::uint32_t> array({static_cast<py::ssize_t>(faces.size()), py::ssize_t(3)});
  if (!faces.empty()) std::memcpy(array.mutable_data(), faces.data(), faces.size() * sizeof(Triangle));
  return array;
}

py::list from_polylines(const std::vector<Polyline>& polylines) {
  py::list list;
  for (const Polyline& p : polylines) list.append(from_points(p));
  return list;
}

py::array_t<double> from_values(const std::vector<double>& values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  if (!values.empty()) std::memcpy(array.mutable_data(), values.data(), values.size() * sizeof(double));
  return array;
}

ProgressBridge::ProgressBridge(py::object callable)
    : callable_(std::move(callable)), error_(std::make_shared<std::optional<py::error_already_set>>()) {
  if (!callable_.is_none() && !PyCallable_Check(callable_.ptr())) throw py::type_error("progress must be callable or None");
}

Progress ProgressBridge::callback() {
  // Even without a callable, Ctrl-C must stop a long computation. The
  // callable is captured as a raw pointer (this bridge owns the reference):
  // the library copies callbacks in threads that do not hold the GIL.
  PyObject* callable = callable_.is_none() ? nullptr : callable_.ptr();
  auto error = error_;
  return [callable, error](const std::string& stage, double fraction) {
    py::gil_scoped_acquire acquire;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!callable) return true;
      const py::object answer = py::reinterpret_borrow<py::object>(callable)(stage, fraction);
      if (answer.is_none()) return true;
      const int truth = PyObject_IsTrue(answer.ptr());
      if (truth < 0) throw py::error_already_set();
      return truth != 0;
    } catch (py::error_already_set& e) {
      if (!*error) error->emplace(std::move(e));
      return false;
    }
  };
}

void ProgressBridge::rethrow() {
  if (*error_) {
    py::error_already_set e = std::move(**error_);
    error_->reset();
    throw e;
  }
}

}  // namespace sharpmesh::python
