// Reading a point cloud a block at a time, so that memory holds one block
// whatever the file's size (issue 38: clouds larger than memory).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh {

namespace io {
class PointBlockSource;
}

/// The points of a file in order, `block_points` at a time. Binary and ASCII
/// PLY (vertex records without list properties), XYZ/PWN and LAS/LAZ stream;
/// OFF and PLY files laid out otherwise are read whole and handed out in
/// blocks. Errors are the readers' own (InvalidInput naming the file and the
/// place), raised when the block that holds the fault is read.
class PointStream {
 public:
  explicit PointStream(const std::string& path, std::size_t block_points = std::size_t(1) << 20);
  ~PointStream();
  PointStream(const PointStream&) = delete;
  PointStream& operator=(const PointStream&) = delete;

  /// Replaces `block` with the next points (normals and colours when the file
  /// has them); false, with `block` empty, when none are left. LAS/LAZ:
  /// `classes` (when given) receives each point's ASPRS class; other formats
  /// leave it empty.
  bool next(PointSet& block, std::vector<std::uint8_t>* classes = nullptr);
  /// The point count the header declares (PLY, LAS/LAZ); none for XYZ.
  std::optional<std::uint64_t> declared_count() const;
  /// True when the file is read block by block, false when it was read whole.
  bool streams() const;

 private:
  std::unique_ptr<io::PointBlockSource> source_;
  std::size_t block_points_;
};

}  // namespace sharpmesh
