// STL, ASCII and binary. STL is a triangle soup: identical corners are merged.
#include <cstring>
#include <map>

#include "io/formats.h"
#include "io/text.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {
namespace {

class VertexWelder {
 public:
  explicit VertexWelder(SurfaceMesh& mesh) : mesh_(mesh) {}
  std::uint32_t add(const Vec3& p) {
    auto [it, inserted] = index_.try_emplace(p, static_cast<std::uint32_t>(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.push_back(p);
    return it->second;
  }

 private:
  SurfaceMesh& mesh_;
  std::map<Vec3, std::uint32_t> index_;
};

}  // namespace

SurfaceMesh read_stl(const std::string& path) {
  const std::string data = read_file(path);
  SurfaceMesh mesh;
  VertexWelder welder(mesh);
  std::uint32_t count = 0;
  if (data.size() >= 84) std::memcpy(&count, data.data() + 80, 4);
  const bool binary = data.size() >= 84 && data.size() == 84 + 50ull * count;
  if (binary) {
    mesh.faces.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      const char* record = data.data() + 84 + 50ull * i;
      Triangle face{};
      for (int k = 0; k < 3; ++k) {
        float c[3];
        std::memcpy(c, record + 12 + 12 * k, 12);
        const Vec3 p{c[0], c[1], c[2]};
        check_finite(p, path, "triangle " + std::to_string(i));
        face[k] = welder.add(p);
      }
      mesh.faces.push_back(face);
    }
  } else {
    if (data.compare(0, 5, "solid") != 0) {
      if (data.size() >= 84)
        throw InvalidInput(path + ": binary STL declares " + format_number(count) + " triangles (" +
                           format_number(84 + 50ull * count) + " bytes) but the file has " + format_number(data.size()) +
                           " bytes (truncated or corrupt)");
      throw InvalidInput(path + ": not an STL file (too short for binary, no 'solid' keyword)");
    }
    LineCursor cursor(data);
    std::string_view line, token;
    Triangle face{};
    int corner = 0;
    while (cursor.next(line)) {
      std::string_view rest = line, keyword;
      if (!next_token(rest, keyword)) continue;
      if (keyword == "vertex") {
        double v[3];
        for (double& c : v)
          if (!next_token(rest, token) || !parse_double(token, c))
            throw InvalidInput(path + ": line " + format_number(cursor.line_number()) + ": expected 3 vertex coordinates");
        if (corner == 3) throw InvalidInput(path + ": line " + format_number(cursor.line_number()) + ": facet with more than 3 vertices");
        const Vec3 p{v[0], v[1], v[2]};
        check_finite(p, path, "line " + std::to_string(cursor.line_number()));
        face[corner++] = welder.add(p);
      } else if (keyword == "endloop") {
        if (corner != 3) throw InvalidInput(path + ": line " + format_number(cursor.line_number()) + ": facet without 3 vertices");
        mesh.faces.push_back(face);
        corner = 0;
      }
    }
  }
  if (mesh.faces.empty()) throw InvalidInput(path + ": STL file has no triangles");
  return mesh;
}

}  // namespace sharpmesh::io
