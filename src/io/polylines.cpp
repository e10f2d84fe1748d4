// CGAL's polyline text format: one polyline per line, `n x1 y1 z1 ... xn yn zn`.
#include <cstdio>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/text.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {

std::vector<Polyline> read_polylines_text(const std::string& path) {
  const std::string text = read_file(path);
  LineCursor cursor(text);
  std::string_view line, token;
  std::vector<Polyline> out;
  while (cursor.next(line)) {
    std::string_view rest = strip_comment(line);
    if (rest.empty()) continue;
    auto where = [&] { return path + ": line " + std::to_string(cursor.line_number()) + ": "; };
    std::int64_t n = 0;
    if (!next_token(rest, token) || !parse_integer(token, n) || n < 1 || static_cast<std::size_t>(n) > line.size())
      throw InvalidInput(where() + "expected a point count followed by that many x y z triples");
    Polyline polyline(static_cast<std::size_t>(n));
    for (Vec3& p : polyline) {
      for (double& c : p)
        if (!next_token(rest, token) || !parse_double(token, c))
          throw InvalidInput(where() + "expected " + format_number(n) + " points (x y z each)");
      check_finite(p, path, "line " + std::to_string(cursor.line_number()));
    }
    if (next_token(rest, token)) throw InvalidInput(where() + "more values than the " + format_number(n) + " points announced");
    out.push_back(std::move(polyline));
  }
  return out;
}

void write_polylines_text(const std::string& path, const std::vector<Polyline>& polylines) {
  AtomicFile file(path);
  std::string buffer;
  char number[96];
  for (const Polyline& polyline : polylines) {
    buffer += std::to_string(polyline.size());
    for (const Vec3& p : polyline) buffer.append(number, std::snprintf(number, sizeof number, " %.17g %.17g %.17g", p[0], p[1], p[2]));
    buffer += '\n';
    if (buffer.size() > (1 << 20)) { file.write(buffer); buffer.clear(); }
  }
  file.write(buffer);
  file.commit();
}

}  // namespace sharpmesh::io
