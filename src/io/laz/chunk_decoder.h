// LASzip's container (Isenburg 2013, section 4): the "laszip encoded" VLR
// naming the items of a record, the chunk table, and the decoding of one
// chunk: its first record raw, the others through the item decoders.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sharpmesh::io::laz {

struct Item {
  std::uint16_t type = 0, size = 0, version = 0;
};

/// The LASzip VLR (user "laszip encoded", record 22204).
struct LaszipVlr {
  std::uint16_t compressor = 0;  ///< 1 pointwise, 2 pointwise chunked, 3 layered chunked
  std::uint16_t coder = 0;       ///< 0 arithmetic
  int version_major = 0, version_minor = 0, revision = 0;
  std::uint32_t chunk_size = 0;  ///< 0xFFFFFFFF: each chunk's count is in the table
  std::vector<Item> items;
  std::size_t record_length() const;
};

/// Parses the VLR's payload; throws InvalidInput naming `path` when it is
/// malformed or describes a compression this decoder does not implement.
LaszipVlr parse_laszip_vlr(const std::uint8_t* data, std::size_t size, const std::string& path);

/// Decodes the chunk table that follows `chunks` (its own header, already
/// read): the byte size of each chunk, and each one's point count when
/// chunk sizes vary. Throws InvalidInput naming `path` when it is corrupt.
void decode_chunk_table(const std::uint8_t* data, std::size_t size, std::uint32_t chunks, bool variable_counts,
                        std::vector<std::uint64_t>& bytes, std::vector<std::uint64_t>& counts, const std::string& path);

/// Decodes chunks of point records (fresh models at each chunk start).
class ChunkDecoder {
 public:
  explicit ChunkDecoder(const LaszipVlr& vlr);
  ~ChunkDecoder();
  /// Writes `count` records of vlr.record_length() bytes to `records`;
  /// false when the chunk's bytes end before its points do.
  bool decode(const std::uint8_t* bytes, std::size_t size, std::size_t count, std::uint8_t* records);

 private:
  struct Items;
  std::unique_ptr<Items> items_;
  std::size_t record_length_;
};

}  // namespace sharpmesh::io::laz
