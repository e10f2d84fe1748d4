// Reading and writing point clouds, meshes and polylines (sharpmesh/io.h).
#include "convert.h"
#include "sharpmesh/io.h"
#include "sharpmesh/las.h"

namespace sharpmesh::python {
namespace {

py::object point_cloud(const PointSet& set) {
  py::object normals = py::none(), colors = py::none();
  if (set.has_normals()) normals = from_points(set.normals);
  if (set.has_colors()) {
    py::array_t<std::uint8_t> c({static_cast<py::ssize_t>(set.colors.size()), py::ssize_t(3)});
    std::memcpy(c.mutable_data(), set.colors.data(), set.colors.size() * sizeof(Rgb));
    colors = c;
  }
  return py::module_::import("sharpmesh._types").attr("PointCloud")(from_points(set.points), normals, colors);
}

}  // namespace

py::object make_mesh(const SurfaceMesh& mesh) {
  return py::module_::import("sharpmesh._types").attr("Mesh")(from_points(mesh.vertices), from_faces(mesh.faces));
}

py::object make_point_cloud(const PointSet& set) { return point_cloud(set); }

PointSet to_point_set(const DoubleArray& points, const py::object& normals) {
  PointSet set;
  set.points = to_points(points, "points");
  if (!normals.is_none()) {
    set.normals = to_points(py::cast<DoubleArray>(normals), "point_normals");
    if (set.normals.size() != set.points.size()) throw py::value_error("point_normals must have one row per point");
  }
  return set;
}

void bind_io(py::module_& m) {
  m.def("read_points", [](const std::string& path, const std::vector<int>& classes) {
        PointSet set;
        {
          py::gil_scoped_release release;
          set = classes.empty() ? read_point_set(path) : read_las_points(path, classes);
        }
        return point_cloud(set);
      },
      py::arg("path"), py::kw_only(), py::arg("classes") = std::vector<int>{},
      "Reads a point cloud (.ply, .xyz, .pwn, .off, .las, .laz) -> PointCloud(points, normals, colors); absent attributes are None. "
      "classes: for LAS/LAZ, keep the points of these ASPRS classes only (e.g. [2, 6]: ground and buildings).");
  m.def("write_points", [](const std::string& path, const DoubleArray& points, const py::object& point_normals, bool ascii) {
        const PointSet set = to_point_set(points, point_normals);
        py::gil_scoped_release release;
        write_point_set(path, set, ascii ? PlyFormat::Ascii : PlyFormat::Binary);
      },
      py::arg("path"), py::arg("points"), py::arg("point_normals") = py::none(), py::arg("ascii") = false,
      "Writes points (and normals) as .ply (binary unless ascii) or .xyz, atomically.");
  m.def("read_mesh", [](const std::string& path) {
        SurfaceMesh mesh;
        {
          py::gil_scoped_release release;
          mesh = read_mesh(path);
        }
        return make_mesh(mesh);
      },
      py::arg("path"), "Reads a triangle mesh (.off, .ply, .obj, .stl) -> Mesh(vertices, faces).");
  m.def("write_mesh", [](const std::string& path, const DoubleArray& vertices, const IndexArray& faces, bool ascii) {
        SurfaceMesh mesh;
        mesh.vertices = to_points(vertices, "vertices");
        mesh.faces = to_faces(faces, mesh.vertices.size(), "faces");
        py::gil_scoped_release release;
        write_mesh(path, mesh, ascii ? PlyFormat::Ascii : PlyFormat::Binary);
      },
      py::arg("path"), py::arg("vertices"), py::arg("faces"), py::arg("ascii") = false,
      "Writes a mesh as .ply (binary unless ascii), .off or .obj, atomically.");
  m.def("read_polylines", [](const std::string& path) { return from_polylines(read_polylines(path)); }, py::arg("path"),
        "Reads polylines in CGAL's text format -> list of (k, 3) arrays.");
  m.def("write_polylines", [](const std::string& path, const py::object& polylines) {
        write_polylines(path, to_polylines(polylines, "polylines"));
      },
      py::arg("path"), py::arg("polylines"), "Writes a list of (k, 3) arrays in CGAL's text format, atomically.");
}

}  // namespace sharpmesh::python
