// Analytic test fixtures: meshes with known geometry, temporary folders.
#pragma once

#include <string>

#include "sharpmesh/errors.h"
#include "sharpmesh/types.h"

namespace sharpmesh::test {

/// `count` points sampled on the mesh (fixed seed), each with its facet's normal.
PointSet sample_with_normals(const SurfaceMesh& mesh, std::size_t count, std::uint64_t seed);

/// Axis-aligned cube [-h, h]^3 made of 12 outward-oriented triangles.
SurfaceMesh cube_mesh(double half_size = 0.5);
/// The cube [-1, 1]^3 with its edge at x = y = 1 cut by the plane
/// x + y = 2 - c: a chamfer face c sqrt(2) wide between two 135-degree edges.
SurfaceMesh chamfered_cube_mesh(double c);
/// The prism z in [-1, 1] over the hexagon (-1,-1) (1,-1) (1,1) (0,1) (0,1+h)
/// (-1,1+h): a step h high, a concave and a convex 90-degree edge h apart.
SurfaceMesh stepped_prism_mesh(double h);
/// The tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1), outward-oriented: three
/// 90-degree edges at the origin and three acute ones (54.7 degrees) around
/// the slanted face.
SurfaceMesh tetrahedron_mesh();
/// Unit sphere: an icosahedron subdivided `levels` times, projected onto the sphere.
SurfaceMesh sphere_mesh(int levels = 3, double radius = 1.0);
/// Closed cylinder of radius r, height h, around z, with `segments` sides.
SurfaceMesh cylinder_mesh(double radius, double height, int segments);
/// The cube [-h, h]^3 hollowed by the cube [-c, c]^3 (its facets facing into
/// the cavity), with a ball of radius r (`levels` subdivisions) in the middle.
SurfaceMesh hollow_box_mesh(double half_size, double cavity_half_size, double ball_radius, int ball_levels);
/// A fresh empty folder, removed with its content when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  const std::string& dir() const { return dir_; }
  std::size_t file_count() const;

 private:
  std::string dir_;
};
/// Path of a file of CGAL's sample data, or "" when the data is not fetched.
std::string data_file(const std::string& relative);
void write_bytes(const std::string& path, const std::string& bytes);
/// The whole file ("" when it cannot be read).
std::string read_bytes(const std::string& path);
/// The message of the InvalidInput that `f` throws, or "no error".
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace sharpmesh::test
