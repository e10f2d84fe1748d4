// XYZ / PWN: `x y z` or `x y z nx ny nz` per line; '#' comments and blank lines allowed.
#include <cstdio>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/text.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {

PointSet read_xyz(const std::string& path) {
  const std::string text = read_file(path);
  PointSet out;
  LineCursor cursor(text);
  std::string_view line, token;
  int columns = 0;
  out.points.reserve(text.size() / 24);
  while (cursor.next(line)) {
    std::string_view rest = strip_comment(line);
    if (rest.empty()) continue;
    double v[7];
    int n = 0;
    while (next_token(rest, token)) {
      if (n == 7) break;
      if (!parse_double(token, v[n]))
        throw InvalidInput(path + ": line " + format_number(cursor.line_number()) + ": '" + std::string(token) +
                           "' is not a number");
      ++n;
    }
    if (n != 3 && n != 6)
      throw InvalidInput(path + ": line " + format_number(cursor.line_number()) + ": expected 3 or 6 numbers (x y z [nx ny nz]), found " +
                         (n == 7 ? std::string("more than 6") : format_number(n)));
    if (columns == 0) columns = n;
    if (n != columns)
      throw InvalidInput(path + ": line " + format_number(cursor.line_number()) + ": " + format_number(n) +
                         " numbers where the previous lines have " + format_number(columns));
    const Vec3 p{v[0], v[1], v[2]};
    check_finite(p, path, "line " + std::to_string(cursor.line_number()));
    out.points.push_back(p);
    if (n == 6) {
      const Vec3 normal{v[3], v[4], v[5]};
      check_finite(normal, path, "line " + std::to_string(cursor.line_number()));
      out.normals.push_back(normal);
    }
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
