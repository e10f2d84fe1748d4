// XYZ / PWN: `x y z` or `x y z nx ny nz` per line; '#' comments and blank lines allowed.
#include <cstdio>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/text.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {

namespace {

/// XYZ lines, parsed block by block: the first line with numbers sets the
/// column count (3, or 6 with normals) for the whole file.
class XyzSource final : public PointBlockSource {
 public:
  explicit XyzSource(const std::string& path) : path_(path), lines_(path, 0) {}

  bool next(PointSet& block, std::size_t max_points, std::vector<std::uint8_t>* classes) override {
    block = PointSet{};
    if (classes) classes->clear();
    while (block.size() < max_points) {
      std::string_view line;
      if (!cursor_.next(line)) {
        std::string_view text;
        if (!lines_.next(text)) break;
        cursor_ = LineCursor(text, cursor_.line_number() + 1);
        continue;
      }
      parse(line, block);
    }
    return !block.empty();
  }

 private:
  void parse(std::string_view line, PointSet& block) {
    std::string_view rest = strip_comment(line), token;
    if (rest.empty()) return;
    const std::size_t number = cursor_.line_number();
    double v[7];
    int n = 0;
    while (next_token(rest, token)) {
      if (n == 7) break;
      if (!parse_double(token, v[n]))
        throw InvalidInput(path_ + ": line " + format_number(number) + ": '" + std::string(token) + "' is not a number");
      ++n;
    }
    if (n != 3 && n != 6)
      throw InvalidInput(path_ + ": line " + format_number(number) + ": expected 3 or 6 numbers (x y z [nx ny nz]), found " +
                         (n == 7 ? std::string("more than 6") : format_number(n)));
    if (columns_ == 0) columns_ = n;
    if (n != columns_)
      throw InvalidInput(path_ + ": line " + format_number(number) + ": " + format_number(n) + " numbers where the previous lines have " +
                         format_number(columns_));
    const Vec3 p{v[0], v[1], v[2]};
    check_finite(p, path_, "line " + std::to_string(number));
    block.points.push_back(p);
    if (n == 6) {
      const Vec3 normal{v[3], v[4], v[5]};
      check_finite(normal, path_, "line " + std::to_string(number));
      block.normals.push_back(normal);
    }
  }

  std::string path_;
  LineBlocks lines_;
  LineCursor cursor_{std::string_view(), 1};
  int columns_ = 0;
};

}  // namespace

std::unique_ptr<PointBlockSource> open_xyz_points(const std::string& path) { return std::make_unique<XyzSource>(path); }

PointSet read_xyz(const std::string& path) {
  XyzSource source(path);
  PointSet out, block;
  while (source.next(block, std::size_t(1) << 20, nullptr)) {
    out.points.insert(out.points.end(), block.points.begin(), block.points.end());
    out.normals.insert(out.normals.end(), block.normals.begin(), block.normals.end());
  }
  return out;
}

void write_xyz(const std::string& path, const PointSet& points) {
  AtomicFile file(path);
  std::string buffer;
  char line[256];
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points.points[i];
    int len = std::snprintf(line, sizeof line, "%.17g %.17g %.17g", p[0], p[1], p[2]);
    buffer.append(line, len);
    if (points.has_normals()) {
      const Vec3& n = points.normals[i];
      len = std::snprintf(line, sizeof line, " %.9g %.9g %.9g", n[0], n[1], n[2]);
      buffer.append(line, len);
    }
    buffer += '\n';
    if (buffer.size() > (1 << 20)) { file.write(buffer); buffer.clear(); }
  }
  file.write(buffer);
  file.commit();
}

}  // namespace sharpmesh::io
