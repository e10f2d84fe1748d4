// OFF (Object File Format) with its variants [C][N]OFF; ASCII only.
#include <cstdio>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/text.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {

SurfaceMesh read_off(const std::string& path, bool require_faces, PointSet* attributes) {
  const std::string text = read_file(path);
  LineCursor cursor(text);
  std::string_view line, token;
  auto where = [&] { return path + ": line " + std::to_string(cursor.line_number()) + ": "; };
  auto next_content = [&](const char* what) {
    while (cursor.next(line)) {
      std::string_view s = strip_comment(line);
      if (!s.empty()) return s;
    }
    throw InvalidInput(path + ": file ends before " + what + " (truncated)");
  };

  std::string_view rest = next_content("the OFF header");
  next_token(rest, token);
  if (token.size() < 3 || token.substr(token.size() - 3) != "OFF")
    throw InvalidInput(path + ": not an OFF file (first keyword is '" + std::string(token) + "')");
  const bool has_normals = token.find('N') != std::string_view::npos;
  const bool has_colors = token.find('C') != std::string_view::npos;
  if (token.find("4") != std::string_view::npos || token.find("n") != std::string_view::npos)
    throw InvalidInput(path + ": OFF variant '" + std::string(token) + "' is not supported (only 3D [C][N]OFF)");
  std::string_view t2;
  std::string_view save = rest;
  if (next_token(save, t2) && t2 == "BINARY") throw InvalidInput(path + ": binary OFF is not supported");
  if (rest.find_first_not_of(" \t") == std::string_view::npos) rest = next_content("the OFF counts");

  std::int64_t counts[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    if (!next_token(rest, token)) {
      if (i == 2) break;  // the edge count is optional
      throw InvalidInput(where() + "expected vertex and face counts");
    }
    if (!parse_integer(token, counts[i]) || counts[i] < 0) throw InvalidInput(where() + "invalid count '" + std::string(token) + "'");
  }
  const std::int64_t nv = counts[0], nf = counts[1];
  // Every vertex and face needs at least one line of text: reject impossible counts before allocating.
  if (static_cast<std::uint64_t>(nv) > text.size() / 6 + 1 || static_cast<std::uint64_t>(nf) > text.size() / 6 + 1)
    throw InvalidInput(path + ": header declares " + format_number(nv) + " vertices and " + format_number(nf) +
                       " faces, more than the file can hold (truncated or corrupt)");
  if (require_faces && nf == 0) throw InvalidInput(path + ": OFF file has no faces (a mesh is expected)");

  SurfaceMesh mesh;
  mesh.vertices.resize(static_cast<std::size_t>(nv));
  if (attributes) {
    if (has_normals) attributes->normals.resize(mesh.vertices.size());
  }
  for (std::int64_t i = 0; i < nv; ++i) {
    rest = next_content("all vertices are read");
    double v[6];
    const int wanted = has_normals ? 6 : 3;
    for (int k = 0; k < wanted; ++k)
      if (!next_token(rest, token) || !parse_double(token, v[k]))
        throw InvalidInput(where() + "vertex " + format_number(i) + ": expected " + format_number(wanted) + " numbers");
    mesh.vertices[i] = {v[0], v[1], v[2]};
    check_finite(mesh.vertices[i], path, "line " + std::to_string(cursor.line_number()));
    if (attributes && has_normals) attributes->normals[i] = {v[3], v[4], v[5]};
  }
  (void)has_colors;
  if (!require_faces) return mesh;  // point-set reading ignores faces
  mesh.faces.reserve(static_cast<std::size_t>(nf));
  for (std::int64_t i = 0; i < nf; ++i) {
    rest = next_content("all faces are read");
    std::int64_t n = 0;
    if (!next_token(rest, token) || !parse_integer(token, n) || n < 3 || n > 1000000)
      throw InvalidInput(where() + "face " + format_number(i) + ": invalid vertex count");
    std::vector<std::uint32_t> polygon(static_cast<std::size_t>(n));
    for (auto& index : polygon) {
      std::int64_t k = -1;
      if (!next_token(rest, token) || !parse_integer(token, k))
        throw InvalidInput(where() + "face " + format_number(i) + ": expected " + format_number(n) + " vertex indices");
      if (k < 0 || k >= nv)
        throw InvalidInput(where() + "face " + format_number(i) + ": vertex index " + format_number(k) + " out of range (" +
                           format_number(nv) + " vertices)");
      index = static_cast<std::uint32_t>(k);
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) mesh.faces.push_back({polygon[0], polygon[k], polygon[k + 1]});
  }
  return mesh;
}

void write_off(const std::string& path, const SurfaceMesh& mesh) {
  AtomicFile file(path);
  std::string buffer = "OFF\n" + std::to_string(mesh.vertices.size()) + " " + std::to_string(mesh.faces.size()) + " 0\n";
  char line[256];
  for (const Vec3& p : mesh.vertices) {
    buffer.append(line, std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p[0], p[1], p[2]));
    if (buffer.size() > (1 << 20)) { file.write(buffer); buffer.clear(); }
  }
  for (const Triangle& f : mesh.faces) {
    buffer.append(line, std::snprintf(line, sizeof line, "3 %u %u %u\n", f[0], f[1], f[2]));
    if (buffer.size() > (1 << 20)) { file.write(buffer); buffer.clear(); }
  }
  file.write(buffer);
  file.commit();
}

}  // namespace sharpmesh::io
