// Format dispatch by file extension.
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/io.h"

namespace sharpmesh {

using io::extension;

PointSet read_point_set(const std::string& path) {
  const std::string ext = extension(path);
  PointSet points;
  if (ext == "ply") {
    points = io::read_ply(path).points;
  } else if (ext == "xyz" || ext == "pwn" || ext == "txt") {
    points = io::read_xyz(path);
  } else if (ext == "off") {
    PointSet attributes;
    points.points = io::read_off(path, false, &attributes).vertices;
    points.normals = std::move(attributes.normals);
  } else if (ext == "las" || ext == "laz") {
    points = io::read_las(path);
  } else {
    throw InvalidInput(path + ": unknown point-set format '." + ext + "' (expected .ply, .xyz, .pwn, .off or .las)");
  }
  return points;
}

SurfaceMesh read_mesh(const std::string& path) {
  const std::string ext = extension(path);
  SurfaceMesh mesh;
  if (ext == "off") {
    mesh = io::read_off(path, true);
  } else if (ext == "ply") {
    io::PlyContents contents = io::read_ply(path);
    if (contents.faces.empty()) throw InvalidInput(path + ": PLY file has no faces (a mesh is expected)");
    mesh.vertices = std::move(contents.points.points);
    mesh.faces = std::move(contents.faces);
  } else if (ext == "obj") {
    mesh = io::read_obj(path);
  } else if (ext == "stl") {
    mesh = io::read_stl(path);
  } else {
    throw InvalidInput(path + ": unknown mesh format '." + ext + "' (expected .off, .ply, .obj or .stl)");
  }
  return mesh;
}

std::vector<Polyline> read_polylines(const std::string& path) { return io::read_polylines_text(path); }

bool is_point_set_output(const std::string& path) {
  const std::string ext = extension(path);
  return ext == "ply" || ext == "xyz" || ext == "pwn";
}

bool is_mesh_output(const std::string& path) {
  const std::string ext = extension(path);
  return ext == "ply" || ext == "off" || ext == "obj";
}

void write_point_set(const std::string& path, const PointSet& points, PlyFormat format) {
  const std::string ext = extension(path);
  if (ext == "ply") io::write_ply_points(path, points, format);
  else if (ext == "xyz" || ext == "pwn") io::write_xyz(path, points);
  else throw InvalidArgument(path + ": cannot write point sets as '." + ext + "' (use .ply or .xyz)");
}

void write_mesh(const std::string& path, const SurfaceMesh& mesh, PlyFormat format) {
  const std::string ext = extension(path);
  if (ext == "ply") io::write_ply_mesh(path, mesh, format);
  else if (ext == "off") io::write_off(path, mesh);
  else if (ext == "obj") io::write_obj(path, mesh);
  else throw InvalidArgument(path + ": cannot write meshes as '." + ext + "' (use .ply, .off or .obj)");
}

void write_polylines(const std::string& path, const std::vector<Polyline>& polylines) {
  io::write_polylines_text(path, polylines);
}

void write_feature_points(const std::string& path, const std::vector<Vec3>& points, const std::vector<PointFeature>& features,
                          PlyFormat format) {
  if (io::extension(path) != "ply") throw InvalidArgument(path + ": classified points are written as .ply");
  if (features.size() != points.size()) throw InvalidArgument("one classification per point is needed");
  io::write_ply_feature_points(path, points, features, format);
}

void write_text_file(const std::string& path, const std::string& text) {
  io::AtomicFile file(path);
  file.write(text);
  file.commit();
}

void check_writable(const std::string& path) {
  if (path.empty()) throw InvalidArgument("empty output path");
  const std::size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  struct stat info {};
  if (::stat(folder.c_str(), &info) != 0)
    throw InvalidArgument("cannot write '" + path + "': folder '" + folder + "' does not exist");
  if (!S_ISDIR(info.st_mode)) throw InvalidArgument("cannot write '" + path + "': '" + folder + "' is not a folder");
  if (::access(folder.c_str(), W_OK) != 0)
    throw InvalidArgument("cannot write '" + path + "': folder '" + folder + "' is not writable");
  if (::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
    throw InvalidArgument("cannot write '" + path + "': it is a directory");
}

}  // namespace sharpmesh
