// PointStream: a point cloud read a block at a time (include/sharpmesh/point_stream.h).
#include "sharpmesh/point_stream.h"

#include <algorithm>

#include "io/formats.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/io.h"
#include "sharpmesh/las.h"

namespace sharpmesh {
namespace io {
namespace {

/// A point set already in memory, handed out in blocks.
class InMemorySource final : public PointBlockSource {
 public:
  explicit InMemorySource(PointSet points) : points_(std::move(points)) {}
  bool next(PointSet& block, std::size_t max_points, std::vector<std::uint8_t>* classes) override {
    if (classes) classes->clear();
    block = PointSet{};
    const std::size_t end = std::min(points_.size(), done_ + max_points);
    auto take = [&](const auto& from, auto& to) {
      if (!from.empty()) to.assign(from.begin() + static_cast<std::ptrdiff_t>(done_), from.begin() + static_cast<std::ptrdiff_t>(end));
    };
    take(points_.points, block.points);
    take(points_.normals, block.normals);
    take(points_.colors, block.colors);
    done_ = end;
    return !block.empty();
  }
  std::optional<std::uint64_t> declared_count() const override { return points_.size(); }
  bool streams() const override { return false; }

 private:
  PointSet points_;
  std::size_t done_ = 0;
};

/// LAS/LAZ chunk by chunk (LasReader), cut into blocks of the asked size.
class LasSource final : public PointBlockSource {
 public:
  explicit LasSource(const std::string& path) : reader_(path) {}
  bool next(PointSet& block, std::size_t max_points, std::vector<std::uint8_t>* classes) override {
    block = PointSet{};
    if (classes) classes->clear();
    while (block.size() < max_points) {
      if (at_ == chunk_.size()) {
        if (next_chunk_ == reader_.chunk_count()) break;
        chunk_ = reader_.read_chunk(next_chunk_++);
        at_ = 0;
        continue;
      }
      const std::size_t end = std::min(chunk_.size(), at_ + (max_points - block.size()));
      const auto from = static_cast<std::ptrdiff_t>(at_), to = static_cast<std::ptrdiff_t>(end);
      block.points.insert(block.points.end(), chunk_.positions.begin() + from, chunk_.positions.begin() + to);
      if (!chunk_.colors.empty()) block.colors.insert(block.colors.end(), chunk_.colors.begin() + from, chunk_.colors.begin() + to);
      if (classes) classes->insert(classes->end(), chunk_.classification.begin() + from, chunk_.classification.begin() + to);
      at_ = end;
    }
    return !block.empty();
  }
  std::optional<std::uint64_t> declared_count() const override { return reader_.info().point_count; }

 private:
  LasReader reader_;
  LasPoints chunk_;
  std::size_t next_chunk_ = 0, at_ = 0;
};

}  // namespace

std::unique_ptr<PointBlockSource> points_in_memory(PointSet points) { return std::make_unique<InMemorySource>(std::move(points)); }

}  // namespace io

PointStream::PointStream(const std::string& path, std::size_t block_points) : block_points_(std::max<std::size_t>(1, block_points)) {
  const std::string ext = io::extension(path);
  if (ext == "ply") source_ = io::open_ply_points(path);
  else if (ext == "xyz" || ext == "pwn" || ext == "txt") source_ = io::open_xyz_points(path);
  else if (ext == "las" || ext == "laz") source_ = std::make_unique<io::LasSource>(path);
  else source_ = io::points_in_memory(read_point_set(path));  // OFF; read_point_set names an unknown format
}

PointStream::~PointStream() = default;

bool PointStream::next(PointSet& block, std::vector<std::uint8_t>* classes) { return source_->next(block, block_points_, classes); }

std::optional<std::uint64_t> PointStream::declared_count() const { return source_->declared_count(); }

bool PointStream::streams() const { return source_->streams(); }

}  // namespace sharpmesh
