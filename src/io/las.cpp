// ASPRS LAS 1.0-1.4 and LAZ (las.h). The header and VLRs are parsed here;
// LAZ chunks are decoded by io/laz. Files are read chunk by chunk through a
// stream, so memory holds the header and one chunk of records.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "io/formats.h"
#include "io/laz/chunk_decoder.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/las.h"

namespace sharpmesh {
namespace {

template <class T>
T get(const std::uint8_t* data, std::size_t offset) {
  T value;
  std::memcpy(&value, data + offset, sizeof(T));
  return value;
}

/// Points per chunk of an uncompressed file.
constexpr std::uint64_t kLasChunk = 50'000;
constexpr std::uint32_t kVariableChunks = 0xFFFFFFFFu;
// Arithmetic coding spends at least a fraction of a bit on every symbol, and
// every LAZ point decodes several symbols of models that never give one
// symbol more than 1 - 2^-10 of the interval: far fewer than this many
// points fit in a byte. A chunk claiming more is corrupt, and is refused
// before its records are allocated.
constexpr std::uint64_t kMaxPointsPerByte = 4096;
// The smallest record of each point format (LAS 1.4 R15, table 7 onwards).
constexpr int kMinRecordLength[11] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};

}  // namespace

struct LasReader::Impl {
  std::string path;
  std::ifstream in;
  std::uint64_t file_size = 0;
  LasInfo info;
  std::uint32_t point_offset = 0;
  // LAZ: where each chunk starts, its compressed size and its point count.
  std::unique_ptr<io::laz::ChunkDecoder> decoder;
  std::vector<std::uint64_t> chunk_start, chunk_bytes, chunk_points;
  std::vector<std::uint8_t> buffer, records;

  std::vector<std::uint8_t> read_at(std::uint64_t offset, std::uint64_t size, const char* what) {
    if (offset > file_size || size > file_size - offset)
      throw InvalidInput(path + ": " + what + " lies beyond the end of the file (truncated?)");
    std::vector<std::uint8_t> bytes(size);
    in.seekg(static_cast<std::streamoff>(offset));
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
      throw InvalidInput(path + ": cannot read " + what);
    return bytes;
  }

  void read_header();
  void read_laz_chunks(const std::vector<std::uint8_t>& laszip_vlr);
  void to_points(const std::uint8_t* records, std::size_t count, LasPoints& out) const;
};

void LasReader::Impl::read_header() {
  in.seekg(0, std::ios::end);
  file_size = static_cast<std::uint64_t>(in.tellg());
  if (file_size < 227) throw InvalidInput(path + ": not a LAS file (" + std::to_string(file_size) + " bytes, shorter than a LAS header)");
  const std::vector<std::uint8_t> head = read_at(0, 227, "the header");
  if (std::memcmp(head.data(), "LASF", 4) != 0) throw InvalidInput(path + ": not a LAS file (no 'LASF' signature)");
  info.version_major = head[24];
  info.version_minor = head[25];
  if (info.version_major != 1 || info.version_minor > 4)
    throw InvalidInput(path + ": LAS version " + format_number(info.version_major) + "." + format_number(info.version_minor) +
                       " is not supported (1.0-1.4)");
  const auto header_size = get<std::uint16_t>(head.data(), 94);
  point_offset = get<std::uint32_t>(head.data(), 96);
  const auto vlr_count = get<std::uint32_t>(head.data(), 100);
  const std::uint8_t format_byte = head[104];
  info.record_length = get<std::uint16_t>(head.data(), 105);
  info.point_count = get<std::uint32_t>(head.data(), 107);
  // Bit 7 marks LASzip-compressed records (bit 6 was used by early writers).
  info.compressed = (format_byte & 0xC0) != 0;
  info.point_format = format_byte & 0x3F;
  if (info.point_format > 10) throw InvalidInput(path + ": unknown LAS point data record format " + format_number(info.point_format));
  if (info.version_minor >= 4 && header_size >= 375) {
    const std::vector<std::uint8_t> extended = read_at(0, 375, "the LAS 1.4 header");
    const auto count64 = get<std::uint64_t>(extended.data(), 247);
    if (count64 != 0) info.point_count = count64;
  }
  for (int k = 0; k < 3; ++k) {
    info.scale[k] = get<double>(head.data(), 131 + 8 * k);
    info.offset[k] = get<double>(head.data(), 155 + 8 * k);
    if (!(info.scale[k] > 0) || !std::isfinite(info.scale[k])) throw InvalidInput(path + ": invalid scale factor in the LAS header");
    if (!std::isfinite(info.offset[k])) throw InvalidInput(path + ": invalid offset in the LAS header");
    info.bounds.max[k] = get<double>(head.data(), 179 + 16 * k);
    info.bounds.min[k] = get<double>(head.data(), 187 + 16 * k);
  }
  if (info.record_length < kMinRecordLength[info.point_format])
    throw InvalidInput(path + ": point record length " + format_number(info.record_length) + " is too short for format " +
                       format_number(info.point_format));
  if (point_offset < header_size || point_offset > file_size) throw InvalidInput(path + ": offset to point data lies outside the file");

  std::vector<std::uint8_t> laszip_vlr;
  std::uint64_t at = header_size;
  for (std::uint32_t i = 0; i < vlr_count; ++i) {
    if (at + 54 > point_offset) throw InvalidInput(path + ": VLR " + format_number(i) + " runs into the point data");
    const std::vector<std::uint8_t> vlr = read_at(at, 54, "a VLR header");
    const auto length = get<std::uint16_t>(vlr.data(), 20);
    const std::string user(reinterpret_cast<const char*>(vlr.data() + 2), strnlen(reinterpret_cast<const char*>(vlr.data() + 2), 16));
    if (user == "laszip encoded" && get<std::uint16_t>(vlr.data(), 18) == 22204) laszip_vlr = read_at(at + 54, length, "the LASzip VLR");
    at += 54 + length;
  }
  if (info.compressed) {
    if (laszip_vlr.empty()) throw InvalidInput(path + ": compressed points but no LASzip VLR");
    read_laz_chunks(laszip_vlr);
  } else {
    const std::uint64_t available = (file_size - point_offset) / info.record_length;
    if (info.point_count > available)
      throw InvalidInput(path + ": header declares " + format_number(info.point_count) + " points but the file holds " +
                         format_number(available) + " (truncated)");
    info.chunks = static_cast<std::size_t>((info.point_count + kLasChunk - 1) / kLasChunk);
  }
}

void LasReader::Impl::read_laz_chunks(const std::vector<std::uint8_t>& laszip_vlr) {
  const io::laz::LaszipVlr vlr = io::laz::parse_laszip_vlr(laszip_vlr.data(), laszip_vlr.size(), path);
  if (vlr.record_length() != info.record_length)
    throw InvalidInput(path + ": the LASzip items make " + format_number(vlr.record_length()) + "-byte records, the header says " +
                       format_number(info.record_length));
  if (info.point_format > 3) throw InvalidInput(path + ": LAZ point format " + format_number(info.point_format) + " is not supported (0-3 are)");
  info.laszip_version = std::to_string(vlr.version_major) + "." + std::to_string(vlr.version_minor) + "r" + std::to_string(vlr.revision);
  info.chunk_size = vlr.chunk_size;
  decoder = std::make_unique<io::laz::ChunkDecoder>(vlr);
  if (vlr.compressor == 1) {  // pointwise: one stream, no chunk table
    chunk_start = {point_offset};
    chunk_bytes = {file_size - point_offset};
    chunk_points = {info.point_count};
  } else {
    // The chunk table's position is at the start of the point data, or, when
    // the writer could not seek back (-1), in the last 8 bytes of the file.
    auto table_offset = get<std::int64_t>(read_at(point_offset, 8, "the chunk table's offset").data(), 0);
    if (table_offset == -1) table_offset = get<std::int64_t>(read_at(file_size - 8, 8, "the chunk table's offset").data(), 0);
    if (table_offset < static_cast<std::int64_t>(point_offset) + 8 || static_cast<std::uint64_t>(table_offset) + 8 > file_size)
      throw InvalidInput(path + ": the LAZ chunk table's offset lies outside the file");
    const std::vector<std::uint8_t> table_head = read_at(static_cast<std::uint64_t>(table_offset), 8, "the chunk table");
    const auto chunks = get<std::uint32_t>(table_head.data(), 4);
    const bool variable = vlr.chunk_size == kVariableChunks;
    if (!variable && info.point_count > std::uint64_t{chunks} * vlr.chunk_size)
      throw InvalidInput(path + ": the header declares " + format_number(info.point_count) + " points but the chunk table holds " +
                         format_number(chunks) + " chunks of " + format_number(vlr.chunk_size));
    const std::uint64_t table_body = static_cast<std::uint64_t>(table_offset) + 8;
    if (chunks > (file_size - table_body) * 8)
      throw InvalidInput(path + ": the LAZ chunk table claims " + format_number(chunks) + " chunks, more than it can hold");
    const std::vector<std::uint8_t> body = read_at(table_body, file_size - table_body, "the chunk table");
    io::laz::decode_chunk_table(body.data(), body.size(), chunks, variable, chunk_bytes, chunk_points, path);
    std::uint64_t start = point_offset + 8, remaining = info.point_count;
    for (std::uint32_t i = 0; i < chunks && remaining > 0; ++i) {
      if (!variable) chunk_points.push_back(std::min<std::uint64_t>(vlr.chunk_size, remaining));
      if (chunk_points[i] > remaining) chunk_points[i] = remaining;
      if (chunk_bytes[i] > static_cast<std::uint64_t>(table_offset) - start)
        throw InvalidInput(path + ": LAZ chunk " + format_number(i) + " runs past the chunk table (corrupt chunk table)");
      chunk_start.push_back(start);
      start += chunk_bytes[i];
      remaining -= chunk_points[i];
    }
    if (remaining > 0)
      throw InvalidInput(path + ": the LAZ chunks hold " + format_number(info.point_count - remaining) + " of the header's " +
                         format_number(info.point_count) + " points");
    chunk_bytes.resize(chunk_start.size());
    chunk_points.resize(chunk_start.size());
  }
  for (std::size_t i = 0; i < chunk_start.size(); ++i)
    if (chunk_points[i] > 1 + kMaxPointsPerByte * chunk_bytes[i])
      throw InvalidInput(path + ": LAZ chunk " + format_number(i) + " claims " + format_number(chunk_points[i]) + " points in " +
                         format_number(chunk_bytes[i]) + " bytes (corrupt point count)");
  info.chunks = chunk_start.size();
}

void LasReader::Impl::to_points(const std::uint8_t* records, std::size_t count, LasPoints& out) const {
  const int f = info.point_format;
  const bool legacy = f <= 5;
  const int time_at = legacy ? (f == 1 || f >= 3 ? 20 : -1) : 22;
  const int rgb_at = f == 2 ? 20 : (f == 3 || f == 5) ? 28 : (f == 7 || f == 8 || f == 10) ? 30 : -1;
  out.positions.resize(count);
  out.intensity.resize(count);
  out.return_number.resize(count);
  out.number_of_returns.resize(count);
  out.classification.resize(count);
  if (time_at >= 0) out.gps_time.resize(count);
  if (rgb_at >= 0) out.colors.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* r = records + i * info.record_length;
    Vec3& p = out.positions[i];
    for (int k = 0; k < 3; ++k) p[k] = get<std::int32_t>(r, 4 * k) * info.scale[k] + info.offset[k];
    io::check_finite(p, path, "point " + std::to_string(i));
    out.intensity[i] = get<std::uint16_t>(r, 12);
    const std::uint8_t returns = r[14];
    out.return_number[i] = legacy ? returns & 7 : returns & 15;
    out.number_of_returns[i] = legacy ? (returns >> 3) & 7 : returns >> 4;
    out.classification[i] = legacy ? r[15] & 31 : r[16];
    if (time_at >= 0) out.gps_time[i] = get<double>(r, static_cast<std::size_t>(time_at));
    if (rgb_at >= 0)
      for (int k = 0; k < 3; ++k) out.colors[i][k] = static_cast<std::uint8_t>(get<std::uint16_t>(r, static_cast<std::size_t>(rgb_at + 2 * k)) >> 8);
  }
}

LasReader::LasReader(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->in.open(path, std::ios::binary);
  if (!impl_->in) throw InvalidInput(path + ": cannot open the file");
  impl_->read_header();
}

LasReader::~LasReader() = default;

const LasInfo& LasReader::info() const { return impl_->info; }
std::size_t LasReader::chunk_count() const { return impl_->info.chunks; }

std::uint64_t LasReader::chunk_first_point(std::size_t chunk) const {
  if (!impl_->info.compressed) return chunk * kLasChunk;
  std::uint64_t first = 0;
  for (std::size_t i = 0; i < chunk && i < impl_->chunk_points.size(); ++i) first += impl_->chunk_points[i];
  return first;
}

LasPoints LasReader::read_chunk(std::size_t chunk) {
  Impl& m = *impl_;
  if (chunk >= m.info.chunks) throw InvalidArgument(m.path + ": chunk " + format_number(chunk) + " of " + format_number(m.info.chunks));
  LasPoints out;
  if (!m.info.compressed) {
    const std::uint64_t first = chunk * kLasChunk;
    const auto count = static_cast<std::size_t>(std::min(kLasChunk, m.info.point_count - first));
    m.records = m.read_at(m.point_offset + first * m.info.record_length, std::uint64_t{count} * m.info.record_length, "point records");
    m.to_points(m.records.data(), count, out);
    return out;
  }
  const auto count = static_cast<std::size_t>(m.chunk_points[chunk]);
  m.buffer = m.read_at(m.chunk_start[chunk], m.chunk_bytes[chunk], "a LAZ chunk");
  m.records.resize(count * m.info.record_length);
  if (!m.decoder->decode(m.buffer.data(), m.buffer.size(), count, m.records.data()))
    throw InvalidInput(m.path + ": LAZ chunk " + format_number(chunk) + " ends before its " + format_number(count) + " points (corrupt or truncated)");
  m.to_points(m.records.data(), count, out);
  return out;
}

bool is_las_path(const std::string& path) {
  const std::string ext = io::extension(path);
  return ext == "las" || ext == "laz";
}

PointSet read_las_points(const std::string& path, const std::vector<int>& classes) {
  LasReader reader(path);
  std::vector<bool> keep_class(256, classes.empty());
  for (int c : classes) {
    if (c < 0 || c > 255) throw InvalidArgument("LAS classes are 0 to 255, got " + format_number(c));
    keep_class[static_cast<std::size_t>(c)] = true;
  }
  PointSet out;
  for (std::size_t chunk = 0; chunk < reader.chunk_count(); ++chunk) {
    const LasPoints points = reader.read_chunk(chunk);
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!keep_class[points.classification[i]]) continue;
      out.points.push_back(points.positions[i]);
      if (!points.colors.empty()) out.colors.push_back(points.colors[i]);
    }
  }
  return out;
}

namespace io {
PointSet read_las(const std::string& path) { return read_las_points(path); }
}  // namespace io

}  // namespace sharpmesh
