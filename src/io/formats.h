// Internal entry points of each file format, dispatched by extension in io.cpp.
#pragma once

#include <string>
#include <vector>

#include "sharpmesh/io.h"
#include "sharpmesh/types.h"

namespace sharpmesh::io {

struct PlyContents {
  PointSet points;
  std::vector<Triangle> faces;
};
PlyContents read_ply(const std::string& path);
void write_ply_points(const std::string& path, const PointSet& points, PlyFormat format);
void write_ply_mesh(const std::string& path, const SurfaceMesh& mesh, PlyFormat format);

void write_ply_feature_points(const std::string& path, const std::vector<Vec3>& points, const std::vector<PointFeature>& features,
                              PlyFormat format);

PointSet read_xyz(const std::string& path);
void write_xyz(const std::string& path, const PointSet& points);

SurfaceMesh read_off(const std::string& path, bool require_faces, PointSet* normals_and_colors = nullptr);
void write_off(const std::string& path, const SurfaceMesh& mesh);

SurfaceMesh read_obj(const std::string& path);
void write_obj(const std::string& path, const SurfaceMesh& mesh);

SurfaceMesh read_stl(const std::string& path);

PointSet read_las(const std::string& path);

std::vector<Polyline> read_polylines_text(const std::string& path);
void write_polylines_text(const std::string& path, const std::vector<Polyline>& polylines);

/// Lower-case extension without the dot ("" if none).
std::string extension(const std::string& path);
/// Reads a whole file; InvalidInput naming the file when it cannot.
std::string read_file(const std::string& path);
/// Throws InvalidInput for a non-finite coordinate: "<path>: <where>: non-finite coordinate".
void check_finite(const Vec3& p, const std::string& path, const std::string& where);

}  // namespace sharpmesh::io
