// Reading and writing point sets, meshes and polylines. Readers validate
// everything and throw InvalidInput naming the file and the line or element;
// writers write to a temporary file in the destination folder, then rename.
#pragma once

#include <string>
#include <vector>

#include "sharpmesh/features.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

/// Reads a point set from .ply (ASCII or binary, float or double, optional
/// normals nx/ny/nz and colours red/green/blue), .xyz/.pwn (3 or 6 columns,
/// '#' comments and blank lines allowed), .off (vertices; faces ignored) or
/// .las/.laz (LAS 1.0-1.4, LAZ point formats 0-3; scale and offset applied;
/// sharpmesh/las.h reads their classes and returns).
PointSet read_point_set(const std::string& path);

/// Reads a triangle mesh from .off, .ply, .obj or .stl (ASCII or binary).
/// Polygons are split into triangles by a fan.
SurfaceMesh read_mesh(const std::string& path);

/// Reads polylines in CGAL's text format: one polyline per line, `n x1 y1 z1 ... xn yn zn`.
std::vector<Polyline> read_polylines(const std::string& path);

enum class PlyFormat { Binary, Ascii };

/// Writes a point set as .ply (binary little endian by default) or .xyz
/// (positions and, if present, normals).
void write_point_set(const std::string& path, const PointSet& points, PlyFormat format = PlyFormat::Binary);

/// Writes a mesh as .ply, .off or .obj.
void write_mesh(const std::string& path, const SurfaceMesh& mesh, PlyFormat format = PlyFormat::Binary);

/// Writes polylines in CGAL's text format.
void write_polylines(const std::string& path, const std::vector<Polyline>& polylines);

/// Writes classified points as PLY: position, class (0 smooth, 1 edge,
/// 2 corner), edge direction dx/dy/dz, eigenvalue ratios l0_l1 and l1_l2, and a
/// colour by class (grey, red, blue) so viewers show the result directly.
void write_feature_points(const std::string& path, const std::vector<Vec3>& points, const std::vector<PointFeature>& features,
                          PlyFormat format = PlyFormat::Binary);

/// Writes a text file atomically (reports, JSON).
void write_text_file(const std::string& path, const std::string& text);

/// True when the extension of `path` names a point-set (resp. mesh) format this library writes.
bool is_point_set_output(const std::string& path);
bool is_mesh_output(const std::string& path);

/// Throws InvalidArgument when `path` cannot be written: missing or read-only
/// folder. Lets tools fail before a long computation rather than after it.
void check_writable(const std::string& path);

}  // namespace sharpmesh
