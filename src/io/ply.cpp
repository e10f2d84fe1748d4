// PLY (Stanford polygon file format): ASCII and binary little/big endian,
// any scalar type, vertex positions with optional normals and colours, faces
// as a list property. Other elements and properties are skipped.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/text.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {
namespace {

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<Scalar> scalar_from_name(std::string_view name) {
  if (name == "char" || name == "int8") return Scalar::Int8;
  if (name == "uchar" || name == "uint8") return Scalar::UInt8;
  if (name == "short" || name == "int16") return Scalar::Int16;
  if (name == "ushort" || name == "uint16") return Scalar::UInt16;
  if (name == "int" || name == "int32") return Scalar::Int32;
  if (name == "uint" || name == "uint32") return Scalar::UInt32;
  if (name == "float" || name == "float32") return Scalar::Float32;
  if (name == "double" || name == "float64") return Scalar::Float64;
  return std::nullopt;
}

std::size_t scalar_size(Scalar s) {
  switch (s) {
    case Scalar::Int8: case Scalar::UInt8: return 1;
    case Scalar::Int16: case Scalar::UInt16: return 2;
    case Scalar::Int32: case Scalar::UInt32: case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;
  bool is_list = false;
  Scalar count_type = Scalar::UInt8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  std::size_t header_line = 0;
  bool fixed_size() const {
    return std::none_of(properties.begin(), properties.end(), [](const Property& p) { return p.is_list; });
  }
  std::size_t min_record_size() const {
    std::size_t size = 0;
    for (const Property& p : properties) size += p.is_list ? scalar_size(p.count_type) : scalar_size(p.type);
    return size;
  }
};

enum class Encoding { Ascii, BinaryLittle, BinaryBig };

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::size_t data_offset = 0;
  std::size_t data_first_line = 0;
};

Header parse_header(const std::string& path, std::string_view text) {
  auto fail = [&](std::size_t line, const std::string& what) -> InvalidInput {
    return InvalidInput(path + ": line " + std::to_string(line) + ": " + what);
  };
  if (text.substr(0, 3) != "ply") throw InvalidInput(path + ": not a PLY file (it does not start with 'ply')");
  Header header;
  LineCursor cursor(text);
  std::string_view line;
  cursor.next(line);
  bool have_format = false, ended = false;
  while (cursor.next(line)) {
    std::string_view rest = line, keyword;
    if (!next_token(rest, keyword)) continue;
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") { ended = true; break; }
    std::string_view a, b, c, d;
    if (keyword == "format") {
      if (!next_token(rest, a) || !next_token(rest, b)) throw fail(cursor.line_number(), "incomplete 'format' line");
      if (a == "ascii") header.encoding = Encoding::Ascii;
      else if (a == "binary_little_endian") header.encoding = Encoding::BinaryLittle;
      else if (a == "binary_big_endian") header.encoding = Encoding::BinaryBig;
      else throw fail(cursor.line_number(), "unknown format '" + std::string(a) + "'");
      have_format = true;
    } else if (keyword == "element") {
      std::int64_t count = 0;
      if (!next_token(rest, a) || !next_token(rest, b) || !parse_integer(b, count) || count < 0)
        throw fail(cursor.line_number(), "malformed 'element' line (expected: element NAME COUNT)");
      header.elements.push_back({std::string(a), static_cast<std::uint64_t>(count), {}, cursor.line_number()});
    } else if (keyword == "property") {
      if (header.elements.empty()) throw fail(cursor.line_number(), "'property' before any 'element'");
      Property property;
      if (!next_token(rest, a)) throw fail(cursor.line_number(), "incomplete 'property' line");
      if (a == "list") {
        if (!next_token(rest, b) || !next_token(rest, c) || !next_token(rest, d))
          throw fail(cursor.line_number(), "incomplete 'property list' line");
        auto count_type = scalar_from_name(b), item_type = scalar_from_name(c);
        if (!count_type || !item_type) throw fail(cursor.line_number(), "unknown property type in list");
        if (*count_type == Scalar::Float32 || *count_type == Scalar::Float64)
          throw fail(cursor.line_number(), "list count type must be an integer type");
        property = {std::string(d), *item_type, true, *count_type};
      } else {
        auto type = scalar_from_name(a);
        if (!type) throw fail(cursor.line_number(), "unknown property type '" + std::string(a) + "'");
        if (!next_token(rest, b)) throw fail(cursor.line_number(), "property without a name");
        property = {std::string(b), *type, false, Scalar::UInt8};
      }
      header.elements.back().properties.push_back(property);
    } else {
      throw fail(cursor.line_number(), "unexpected header keyword '" + std::string(keyword) + "'");
    }
  }
  if (!ended) throw InvalidInput(path + ": PLY header has no 'end_header' line");
  if (!have_format) throw InvalidInput(path + ": PLY header has no 'format' line");
  header.data_offset = cursor.offset(text);
  header.data_first_line = cursor.line_number() + 1;
  return header;
}

// Reads scalars one after the other, from binary data or ASCII tokens.
class ValueReader {
 public:
  ValueReader(const std::string& path, std::string_view data, Encoding encoding, std::size_t first_line)
      : path_(path), data_(data), encoding_(encoding), lines_(data, first_line) {}

  double read(Scalar type, const char* element, std::uint64_t index) {
    if (encoding_ == Encoding::Ascii) return read_ascii(element, index);
    const std::size_t size = scalar_size(type);
    if (pos_ + size > data_.size())
      throw InvalidInput(path_ + ": file ends inside " + element + " " + format_number(index) + " (truncated binary data)");
    unsigned char bytes[8];
    std::memcpy(bytes, data_.data() + pos_, size);
    pos_ += size;
    if (encoding_ == Encoding::BinaryBig) std::reverse(bytes, bytes + size);
    switch (type) {
      case Scalar::Int8: { std::int8_t v; std::memcpy(&v, bytes, 1); return v; }
      case Scalar::UInt8: return bytes[0];
      case Scalar::Int16: { std::int16_t v; std::memcpy(&v, bytes, 2); return v; }
      case Scalar::UInt16: { std::uint16_t v; std::memcpy(&v, bytes, 2); return v; }
      case Scalar::Int32: { std::int32_t v; std::memcpy(&v, bytes, 4); return v; }
      case Scalar::UInt32: { std::uint32_t v; std::memcpy(&v, bytes, 4); return v; }
      case Scalar::Float32: { float v; std::memcpy(&v, bytes, 4); return v; }
      case Scalar::Float64: { double v; std::memcpy(&v, bytes, 8); return v; }
    }
    return 0;
  }

  /// ASCII: every element is on its own line.
  void begin_record(const char* element, std::uint64_t index) {
    if (encoding_ != Encoding::Ascii) return;
    do {
      if (!lines_.next(line_))
        throw InvalidInput(path_ + ": file ends before " + element + " " + format_number(index) + " (truncated)");
    } while (strip_comment(line_).empty());
  }
  void end_record(const char* element, std::uint64_t index) {
    if (encoding_ != Encoding::Ascii) return;
    std::string_view token;
    if (next_token(line_, token))
      throw InvalidInput(path_ + ": line " + format_number(lines_.line_number()) + ": extra values in " + element +
                         " " + format_number(index));
  }
  std::size_t remaining_bytes() const { return data_.size() - pos_; }

 private:
  double read_ascii(const char* element, std::uint64_t index) {
    std::string_view token;
    double value = 0;
    if (!next_token(line_, token))
      throw InvalidInput(path_ + ": line " + format_number(lines_.line_number()) + ": too few values in " + element +
                         " " + format_number(index));
    if (!parse_double(token, value))
      throw InvalidInput(path_ + ": line " + format_number(lines_.line_number()) + ": '" + std::string(token) +
                         "' is not a number");
    return value;
  }

  const std::string& path_;
  std::string_view data_;
  Encoding encoding_;
  std::size_t pos_ = 0;
  LineCursor lines_;
  std::string_view line_;
};

int index_of(const Element& e, std::initializer_list<const char*> names) {
  for (const char* name : names)
    for (std::size_t i = 0; i < e.properties.size(); ++i)
      if (!e.properties[i].is_list && e.properties[i].name == name) return static_cast<int>(i);
  return -1;
}

double color_scale(Scalar type) {
  switch (type) {
    case Scalar::UInt16: return 255.0 / 65535.0;
    case Scalar::Float32: case Scalar::Float64: return 255.0;
    default: return 1.0;
  }
}

/// Where a vertex record keeps its position, normal and colour.
struct VertexLayout {
  VertexLayout(const std::string& path, const Element& e) : element(&e) {
    ix = index_of(e, {"x"}); iy = index_of(e, {"y"}); iz = index_of(e, {"z"});
    if (ix < 0 || iy < 0 || iz < 0)
      throw InvalidInput(path + ": line " + format_number(e.header_line) + ": vertex element lacks x, y or z");
    inx = index_of(e, {"nx", "normal_x"}); iny = index_of(e, {"ny", "normal_y"}); inz = index_of(e, {"nz", "normal_z"});
    ir = index_of(e, {"red", "r", "diffuse_red"}); ig = index_of(e, {"green", "g", "diffuse_green"});
    ib = index_of(e, {"blue", "b", "diffuse_blue"});
  }
  bool normals() const { return inx >= 0 && iny >= 0 && inz >= 0; }
  bool colors() const { return ir >= 0 && ig >= 0 && ib >= 0; }
  /// Stores record `n`'s values at `at` of `out` (sized by the caller).
  void store(const std::string& path, const std::vector<double>& values, std::uint64_t n, PointSet& out, std::size_t at) const {
    Vec3& q = out.points[at];
    q = {values[ix], values[iy], values[iz]};
    check_finite(q, path, "vertex " + std::to_string(n));
    if (out.has_normals()) {
      out.normals[at] = {values[inx], values[iny], values[inz]};
      check_finite(out.normals[at], path, "normal of vertex " + std::to_string(n));
    }
    if (out.has_colors()) {
      const int idx[3] = {ir, ig, ib};
      for (int c = 0; c < 3; ++c) {
        const double v = values[idx[c]] * color_scale(element->properties[idx[c]].type);
        out.colors[at][c] = static_cast<std::uint8_t>(std::clamp(std::isfinite(v) ? std::round(v) : 0.0, 0.0, 255.0));
      }
    }
  }
  const Element* element;
  int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, ir = -1, ig = -1, ib = -1;
};

}  // namespace

PlyContents read_ply(const std::string& path) {
  const std::string text = read_file(path);
  const Header header = parse_header(path, text);
  const std::string_view data = std::string_view(text).substr(header.data_offset);
  ValueReader reader(path, data, header.encoding, header.data_first_line);

  // Element counts must be plausible for the file size: no allocation is made
  // from a header that declares more records than the file can hold.
  std::uint64_t min_bytes = 0;
  for (const Element& e : header.elements) {
    const std::uint64_t per_record = header.encoding == Encoding::Ascii ? 2 : std::max<std::size_t>(1, e.min_record_size());
    if (e.count > data.size() / per_record + 1)
      throw InvalidInput(path + ": header declares " + format_number(e.count) + " " + e.name +
                         " elements but the file holds at most " + format_number(data.size() / per_record) +
                         " (truncated or corrupt)");
    min_bytes += e.count * per_record;
  }
  if (header.encoding != Encoding::Ascii && min_bytes > data.size())
    throw InvalidInput(path + ": file is truncated: the header needs at least " + format_number(min_bytes) +
                       " bytes of data, the file has " + format_number(data.size()));

  PlyContents out;
  bool have_vertices = false;
  for (const Element& e : header.elements) {
    const bool is_vertex = e.name == "vertex";
    const bool is_face = e.name == "face";
    int iface = -1;
    std::optional<VertexLayout> layout;
    if (is_vertex) {
      if (have_vertices) throw InvalidInput(path + ": more than one 'vertex' element");
      have_vertices = true;
      layout.emplace(path, e);
      out.points.points.resize(e.count);
      if (layout->normals()) out.points.normals.resize(e.count);
      if (layout->colors()) out.points.colors.resize(e.count);
    }
    if (is_face) {
      for (std::size_t i = 0; i < e.properties.size(); ++i)
        if (e.properties[i].is_list && (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index"))
          iface = static_cast<int>(i);
      if (iface < 0)
        throw InvalidInput(path + ": line " + format_number(e.header_line) + ": face element lacks a vertex_indices list");
      out.faces.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(e.count, data.size() / 4 + 1)));
    }
    const char* label = is_vertex ? "vertex" : is_face ? "face" : e.name.c_str();
    std::vector<double> values(e.properties.size());
    std::vector<std::int64_t> polygon;
    for (std::uint64_t n = 0; n < e.count; ++n) {
      reader.begin_record(label, n);
      polygon.clear();
      for (std::size_t p = 0; p < e.properties.size(); ++p) {
        const Property& prop = e.properties[p];
        if (!prop.is_list) {
          values[p] = reader.read(prop.type, label, n);
          continue;
        }
        const double count = reader.read(prop.count_type, label, n);
        if (!(count >= 0) || count != std::floor(count) ||
            (header.encoding != Encoding::Ascii && count * scalar_size(prop.type) > reader.remaining_bytes()) ||
            count > 1e6)
          throw InvalidInput(path + ": " + label + " " + format_number(n) + ": invalid list length " + format_number(count));
        for (std::size_t k = 0; k < static_cast<std::size_t>(count); ++k) {
          const double v = reader.read(prop.type, label, n);
          if (static_cast<int>(p) == iface) {
            if (!(v >= 0) || v != std::floor(v) || v >= static_cast<double>(out.points.size()))
              throw InvalidInput(path + ": face " + format_number(n) + ": vertex index " + format_number(v) +
                                 " out of range (" + format_number(out.points.size()) + " vertices)");
            polygon.push_back(static_cast<std::int64_t>(v));
          }
        }
      }
      reader.end_record(label, n);
      if (is_vertex) {
        layout->store(path, values, n, out.points, static_cast<std::size_t>(n));
      } else if (is_face) {
        if (polygon.size() < 3)
          throw InvalidInput(path + ": face " + format_number(n) + ": has " + format_number(polygon.size()) + " vertices (needs 3 or more)");
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
          out.faces.push_back({static_cast<std::uint32_t>(polygon[0]), static_cast<std::uint32_t>(polygon[k]),
                               static_cast<std::uint32_t>(polygon[k + 1])});
      }
    }
  }
  if (!have_vertices) throw InvalidInput(path + ": PLY file has no 'vertex' element");
  return out;
}

namespace {

/// The vertex records of a PLY file, read block by block (PointStream).
class PlySource final : public PointBlockSource {
 public:
  PlySource(const std::string& path, Header header, std::size_t vertex_element, std::uint64_t skip)
      : path_(path), header_(std::move(header)), element_(header_.elements[vertex_element]), layout_(path, element_),
        values_(element_.properties.size()) {
    if (header_.encoding == Encoding::Ascii) {
      lines_.emplace(path, header_.data_offset);
      cursor_ = LineCursor(std::string_view(), header_.data_first_line);
      skip_records_ = skip;
    } else {
      binary_ = open_file(path);
      binary_.seekg(static_cast<std::streamoff>(header_.data_offset + skip));
      record_size_ = element_.min_record_size();
    }
  }
  bool next(PointSet& block, std::size_t max_points, std::vector<std::uint8_t>* classes) override {
    if (classes) classes->clear();
    const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(max_points, element_.count - done_));
    block = PointSet{};
    block.points.resize(count);
    if (layout_.normals()) block.normals.resize(count);
    if (layout_.colors()) block.colors.resize(count);
    if (header_.encoding == Encoding::Ascii) read_ascii(block, count);
    else read_binary(block, count);
    done_ += count;
    return count > 0;
  }
  std::optional<std::uint64_t> declared_count() const override { return element_.count; }

 private:
  void read_binary(PointSet& block, std::size_t count) {
    bytes_.resize(count * record_size_);
    binary_.read(bytes_.data(), static_cast<std::streamsize>(bytes_.size()));
    if (static_cast<std::size_t>(binary_.gcount()) != bytes_.size())
      throw InvalidInput(path_ + ": file ends inside vertex " + format_number(done_ + binary_.gcount() / record_size_) +
                         " (truncated binary data)");
    ValueReader reader(path_, bytes_, header_.encoding, 0);
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint64_t n = done_ + i;
      for (std::size_t p = 0; p < values_.size(); ++p) values_[p] = reader.read(element_.properties[p].type, "vertex", n);
      layout_.store(path_, values_, n, block, i);
    }
  }
  void read_ascii(PointSet& block, std::size_t count) {
    for (std::size_t i = 0; i < count;) {
      std::string_view line;
      if (!cursor_.next(line)) {
        std::string_view text;
        if (!lines_->next(text))
          throw InvalidInput(path_ + ": file ends before vertex " + format_number(done_ + i) + " (truncated)");
        cursor_ = LineCursor(text, cursor_.line_number() + 1);
        continue;
      }
      if (strip_comment(line).empty()) continue;
      if (skip_records_ > 0) {  // a record of an element before the vertices
        --skip_records_;
        continue;
      }
      const std::uint64_t n = done_ + i;
      ValueReader reader(path_, line, Encoding::Ascii, cursor_.line_number());
      reader.begin_record("vertex", n);
      for (std::size_t p = 0; p < values_.size(); ++p) values_[p] = reader.read(element_.properties[p].type, "vertex", n);
      reader.end_record("vertex", n);
      layout_.store(path_, values_, n, block, i);
      ++i;
    }
  }

  std::string path_;
  Header header_;
  const Element& element_;
  VertexLayout layout_;
  std::vector<double> values_;
  std::uint64_t done_ = 0;
  // ASCII
  std::optional<LineBlocks> lines_;
  LineCursor cursor_{std::string_view(), 1};
  std::uint64_t skip_records_ = 0;
  // binary
  std::ifstream binary_;
  std::size_t record_size_ = 0;
  std::string bytes_;
};

/// The header of a PLY file, read up to its end_header line.
std::string read_ply_header_text(const std::string& path) {
  std::ifstream in = open_file(path);
  std::string text;
  char buffer[65536];
  for (;;) {
    in.read(buffer, sizeof buffer);
    const auto got = static_cast<std::size_t>(in.gcount());
    const std::size_t searched_from = text.size() >= 16 ? text.size() - 16 : 0;
    text.append(buffer, got);
    const std::size_t end = text.find("end_header", searched_from);
    if (end != std::string::npos) {
      const std::size_t newline = text.find('\n', end);
      if (newline != std::string::npos || got < sizeof buffer) return text;
    }
    if (got < sizeof buffer || text.size() > (std::size_t(16) << 20)) return text;  // parse_header names what is missing
  }
}

}  // namespace

std::unique_ptr<PointBlockSource> open_ply_points(const std::string& path) {
  const std::string text = read_ply_header_text(path);
  Header header = parse_header(path, text);
  const auto vertex = std::find_if(header.elements.begin(), header.elements.end(), [](const Element& e) { return e.name == "vertex"; });
  if (vertex == header.elements.end()) throw InvalidInput(path + ": PLY file has no 'vertex' element");
  bool streamable = vertex->fixed_size();
  std::uint64_t skip = 0;  // bytes (binary) or records (ASCII) before the vertices
  for (auto e = header.elements.begin(); e != vertex; ++e) {
    if (header.encoding == Encoding::Ascii) skip += e->count;
    else if (e->fixed_size()) skip += e->count * e->min_record_size();
    else streamable = false;
  }
  if (!streamable) return points_in_memory(read_ply(path).points);
  if (header.encoding != Encoding::Ascii) {
    std::ifstream in = open_file(path);
    in.seekg(0, std::ios::end);
    const auto size = static_cast<std::uint64_t>(std::max<std::streamoff>(0, in.tellg()));
    const std::uint64_t needed = header.data_offset + skip + vertex->count * vertex->min_record_size();
    if (needed > size)
      throw InvalidInput(path + ": file is truncated: the header needs at least " + format_number(needed - header.data_offset) +
                         " bytes of data, the file has " + format_number(size - std::min<std::uint64_t>(size, header.data_offset)));
  }
  const std::size_t index = static_cast<std::size_t>(vertex - header.elements.begin());
  return std::make_unique<PlySource>(path, std::move(header), index, skip);
}

namespace {

void write_ply_header(AtomicFile& file, PlyFormat format, std::size_t vertices, bool normals, bool colors,
                      std::size_t faces, bool with_faces) {
  std::string h = "ply\nformat ";
  h += format == PlyFormat::Binary ? "binary_little_endian 1.0\n" : "ascii 1.0\n";
  h += "comment written by sharpmesh\n";
  h += "element vertex " + std::to_string(vertices) + "\n";
  h += "property double x\nproperty double y\nproperty double z\n";
  if (normals) h += "property float nx\nproperty float ny\nproperty float nz\n";
  if (colors) h += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (with_faces) h += "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\n";
  h += "end_header\n";
  file.write(h);
}

void write_vertices(AtomicFile& file, PlyFormat format, const std::vector<Vec3>& points, const std::vector<Vec3>* normals,
                    const std::vector<Rgb>* colors) {
  std::string buffer;
  char line[256];
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (format == PlyFormat::Binary) {
      buffer.append(reinterpret_cast<const char*>(p.data()), 24);
      if (normals) {
        const float n[3] = {float((*normals)[i][0]), float((*normals)[i][1]), float((*normals)[i][2])};
        buffer.append(reinterpret_cast<const char*>(n), 12);
      }
      if (colors) buffer.append(reinterpret_cast<const char*>((*colors)[i].data()), 3);
    } else {
      int len = std::snprintf(line, sizeof line, "%.17g %.17g %.17g", p[0], p[1], p[2]);
      buffer.append(line, len);
      if (normals) {
        len = std::snprintf(line, sizeof line, " %.9g %.9g %.9g", (*normals)[i][0], (*normals)[i][1], (*normals)[i][2]);
        buffer.append(line, len);
      }
      if (colors) {
        len = std::snprintf(line, sizeof line, " %d %d %d", (*colors)[i][0], (*colors)[i][1], (*colors)[i][2]);
        buffer.append(line, len);
      }
      buffer += '\n';
    }
    if (buffer.size() > (1 << 20)) { file.write(buffer); buffer.clear(); }
  }
  file.write(buffer);
}

}  // namespace

void write_ply_points(const std::string& path, const PointSet& points, PlyFormat format) {
  AtomicFile file(path);
  write_ply_header(file, format, points.size(), points.has_normals(), points.has_colors(), 0, false);
  write_vertices(file, format, points.points, points.has_normals() ? &points.normals : nullptr,
                 points.has_colors() ? &points.colors : nullptr);
  file.commit();
}

void write_ply_mesh(const std::string& path, const SurfaceMesh& mesh, PlyFormat format) {
  AtomicFile file(path);
  write_ply_header(file, format, mesh.vertices.size(), false, false, mesh.faces.size(), true);
  write_vertices(file, format, mesh.vertices, nullptr, nullptr);
  std::string buffer;
  char line[128];
  for (const Triangle& f : mesh.faces) {
    if (format == PlyFormat::Binary) {
      buffer += char(3);
      const std::int32_t idx[3] = {std::int32_t(f[0]), std::int32_t(f[1]), std::int32_t(f[2])};
      buffer.append(reinterpret_cast<const char*>(idx), 12);
    } else {
      const int len = std::snprintf(line, sizeof line, "3 %u %u %u\n", f[0], f[1], f[2]);
      buffer.append(line, len);
    }
    if (buffer.size() > (1 << 20)) { file.write(buffer); buffer.clear(); }
  }
  file.write(buffer);
  file.commit();
}

void write_ply_feature_points(const std::string& path, const std::vector<Vec3>& points, const std::vector<PointFeature>& features,
                              PlyFormat format) {
  AtomicFile file(path);
  std::string h = "ply\nformat ";
  h += format == PlyFormat::Binary ? "binary_little_endian 1.0\n" : "ascii 1.0\n";
  h += "comment sharpmesh feature classification: class 0 smooth, 1 edge, 2 corner\n";
  h += "element vertex " + std::to_string(points.size()) + "\n";
  h += "property double x\nproperty double y\nproperty double z\nproperty uchar class\n"
       "property float dx\nproperty float dy\nproperty float dz\nproperty float l0_l1\nproperty float l1_l2\n"
       "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  file.write(h);
  static const unsigned char colors[3][3] = {{190, 190, 190}, {220, 30, 30}, {30, 60, 220}};
  std::string buffer;
  char line[320];
  for (std::size_t i = 0; i < points.size(); ++i) {
    const PointFeature& f = features[i];
    const auto c = static_cast<int>(f.type);
    const float values[5] = {float(f.direction[0]), float(f.direction[1]), float(f.direction[2]),
                             float(std::min(f.ratio01, 3e38)), float(std::min(f.ratio12, 3e38))};
    if (format == PlyFormat::Binary) {
      buffer.append(reinterpret_cast<const char*>(points[i].data()), 24);
      buffer += static_cast<char>(c);
      buffer.append(reinterpret_cast<const char*>(values), 20);
      buffer.append(reinterpret_cast<const char*>(colors[c]), 3);
    } else {
      const int len = std::snprintf(line, sizeof line, "%.17g %.17g %.17g %d %.7g %.7g %.7g %.7g %.7g %d %d %d\n", points[i][0],
                                    points[i][1], points[i][2], c, values[0], values[1], values[2], values[3], values[4],
                                    colors[c][0], colors[c][1], colors[c][2]);
      buffer.append(line, len);
    }
    if (buffer.size() > (1 << 20)) { file.write(buffer); buffer.clear(); }
  }
  file.write(buffer);
  file.commit();
}

}  // namespace sharpmesh::io
