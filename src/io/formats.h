// Internal entry points of each file format, dispatched by extension in io.cpp.
#pragma once

#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
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

/// Where PointStream takes its blocks from (one per file format).
class PointBlockSource {
 public:
  virtual ~PointBlockSource() = default;
  /// Replaces `block` with up to `max_points` next points; false when none are left.
  virtual bool next(PointSet& block, std::size_t max_points, std::vector<std::uint8_t>* classes) = 0;
  virtual std::optional<std::uint64_t> declared_count() const { return std::nullopt; }
  virtual bool streams() const { return true; }
};
/// Binary or ASCII PLY vertices; a file whose vertex records hold lists, or
/// whose vertex element follows another with lists, is read whole.
std::unique_ptr<PointBlockSource> open_ply_points(const std::string& path);
std::unique_ptr<PointBlockSource> open_xyz_points(const std::string& path);
/// Blocks of a point set read whole (formats without a streaming reader).
std::unique_ptr<PointBlockSource> points_in_memory(PointSet points);

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
/// Opens a file to read; InvalidInput naming it when it cannot (as read_file).
std::ifstream open_file(const std::string& path);
/// The whole lines of a text file from `offset` on, a few megabytes at a
/// time; the file's last line may lack its newline.
class LineBlocks {
 public:
  LineBlocks(const std::string& path, std::uint64_t offset);
  /// The next run of whole lines, valid until the next call; false at the end.
  bool next(std::string_view& text);

 private:
  std::string path_;
  std::ifstream in_;
  std::string buffer_;
  std::size_t used_ = 0;
  bool at_end_ = false;
};
/// Throws InvalidInput for a non-finite coordinate: "<path>: <where>: non-finite coordinate".
void check_finite(const Vec3& p, const std::string& path, const std::string& where);

}  // namespace sharpmesh::io
