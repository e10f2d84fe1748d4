// ASPRS LAS 1.2-1.4 point clouds, uncompressed point data record formats 0-10:
// X/Y/Z integers with the header's scale and offset; RGB where the format has it.
#include <cmath>
#include <cstring>

#include "io/formats.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {
namespace {

template <class T>
T get(const std::string& data, std::size_t offset) {
  T value;
  std::memcpy(&value, data.data() + offset, sizeof(T));
  return value;
}

}  // namespace

PointSet read_las(const std::string& path) {
  if (extension(path) == "laz")
    throw InvalidInput(path + ": LAZ (compressed LAS) is not supported: decompress it first (e.g. `laszip -i in.laz -o out.las`)");
  const std::string data = read_file(path);
  if (data.size() < 227 || data.compare(0, 4, "LASF") != 0) throw InvalidInput(path + ": not a LAS file (no 'LASF' signature)");
  const int major = static_cast<unsigned char>(data[24]), minor = static_cast<unsigned char>(data[25]);
  if (major != 1 || minor < 0 || minor > 4)
    throw InvalidInput(path + ": LAS version " + format_number(major) + "." + format_number(minor) + " is not supported (1.0-1.4)");
  const auto header_size = get<std::uint16_t>(data, 94);
  const auto point_offset = get<std::uint32_t>(data, 96);
  const auto format_byte = static_cast<unsigned char>(data[104]);
  const auto record_length = get<std::uint16_t>(data, 105);
  if (format_byte & 0xC0)
    throw InvalidInput(path + ": point records are compressed (LAZ); decompress them first (e.g. with laszip)");
  const int format = format_byte;
  if (format > 10) throw InvalidInput(path + ": unknown LAS point data record format " + format_number(format));
  static const int min_length[11] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  static const int rgb_offset[11] = {-1, -1, 20, 28, -1, 28, -1, 30, 30, -1, 30};
  if (record_length < min_length[format])
    throw InvalidInput(path + ": point record length " + format_number(record_length) + " is too short for format " + format_number(format));
  std::uint64_t count = get<std::uint32_t>(data, 107);
  if (minor >= 4 && header_size >= 375 && data.size() >= 375) {
    const auto count64 = get<std::uint64_t>(data, 247);
    if (count64 != 0) count = count64;
  }
  const double scale[3] = {get<double>(data, 131), get<double>(data, 139), get<double>(data, 147)};
  const double offset[3] = {get<double>(data, 155), get<double>(data, 163), get<double>(data, 171)};
  for (double s : scale)
    if (!(s > 0) || !std::isfinite(s)) throw InvalidInput(path + ": invalid scale factor in the LAS header");
  if (point_offset < header_size || point_offset > data.size())
    throw InvalidInput(path + ": offset to point data lies outside the file");
  const std::uint64_t available = (data.size() - point_offset) / record_length;
  if (count > available)
    throw InvalidInput(path + ": header declares " + format_number(count) + " points but the file holds " + format_number(available) +
                       " (truncated)");
  PointSet out;
  out.points.resize(count);
  const int rgb = rgb_offset[format];
  if (rgb >= 0) out.colors.resize(count);
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::size_t base = point_offset + i * record_length;
    for (int k = 0; k < 3; ++k) out.points[i][k] = get<std::int32_t>(data, base + 4 * k) * scale[k] + offset[k];
    check_finite(out.points[i], path, "point " + std::to_string(i));
    if (rgb >= 0)
      for (int k = 0; k < 3; ++k) out.colors[i][k] = static_cast<std::uint8_t>(get<std::uint16_t>(data, base + rgb + 2 * k) >> 8);
  }
  return out;
}

}  // namespace sharpmesh::io
