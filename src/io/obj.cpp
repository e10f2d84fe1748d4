// Wavefront OBJ: `v x y z [w]` and `f a[/t][/n] ...` (negative indices are relative).
#include <cstdio>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/text.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {

SurfaceMesh read_obj(const std::string& path) {
  const std::string text = read_file(path);
  LineCursor cursor(text);
  std::string_view line, token;
  SurfaceMesh mesh;
  std::vector<std::int64_t> polygon;
  std::vector<std::size_t> face_lines;
  auto where = [&] { return path + ": line " + std::to_string(cursor.line_number()) + ": "; };
  while (cursor.next(line)) {
    std::string_view rest = strip_comment(line), keyword;
    if (!next_token(rest, keyword)) continue;
    if (keyword == "v") {
      double v[3];
      for (double& c : v)
        if (!next_token(rest, token) || !parse_double(token, c)) throw InvalidInput(where() + "expected 3 vertex coordinates");
      mesh.vertices.push_back({v[0], v[1], v[2]});
      check_finite(mesh.vertices.back(), path, "line " + std::to_string(cursor.line_number()));
    } else if (keyword == "f") {
      polygon.clear();
      while (next_token(rest, token)) {
        std::int64_t k = 0;
        const std::string_view first = token.substr(0, token.find('/'));
        if (!parse_integer(first, k) || k == 0) throw InvalidInput(where() + "invalid vertex reference '" + std::string(token) + "'");
        const std::int64_t n = static_cast<std::int64_t>(mesh.vertices.size());
        const std::int64_t index = k > 0 ? k - 1 : n + k;
        if (index < 0 || index >= n)
          throw InvalidInput(where() + "vertex reference " + format_number(k) + " out of range (" + format_number(n) + " vertices so far)");
        polygon.push_back(index);
      }
      if (polygon.size() < 3) throw InvalidInput(where() + "face with fewer than 3 vertices");
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
        mesh.faces.push_back({std::uint32_t(polygon[0]), std::uint32_t(polygon[k]), std::uint32_t(polygon[k + 1])});
    }
  }
  if (mesh.faces.empty()) throw InvalidInput(path + ": OBJ file has no faces (a mesh is expected)");
  return mesh;
}

void write_obj(const std::string& path, const SurfaceMesh& mesh) {
  AtomicFile file(path);
  std::string buffer = "# written by sharpmesh\n";
  char line[256];
  for (const Vec3& p : mesh.vertices) {
    buffer.append(line, std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]));
    if (buffer.size() > (1 << 20)) { file.write(buffer); buffer.clear(); }
  }
  for (const Triangle& f : mesh.faces) {
    buffer.append(line, std::snprintf(line, sizeof line, "f %u %u %u\n", f[0] + 1, f[1] + 1, f[2] + 1));
    if (buffer.size() > (1 << 20)) { file.write(buffer); buffer.clear(); }
  }
  file.write(buffer);
  file.commit();
}

}  // namespace sharpmesh::io
