#include "fixtures.h"

#include "sharpmesh/eval.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

namespace sharpmesh::test {

PointSet sample_with_normals(const SurfaceMesh& mesh, std::size_t count, std::uint64_t seed) {
  SampleOptions options;
  options.count = count;
  options.seed = seed;
  options.with_normals = true;
  return sample_mesh(mesh, options);
}

SurfaceMesh cube_mesh(double h) {
  SurfaceMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.push_back({(i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h});
  // Two triangles per face, counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
    m.faces.push_back({std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  }
  return m;
}

SurfaceMesh tetrahedron_mesh() {
  SurfaceMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

SurfaceMesh chamfered_cube_mesh(double c) {
  SurfaceMesh m;
  // The pentagon A B C1 C2 D at z = -1 (vertices 0-4) and z = 1 (5-9).
  const double xy[5][2] = {{-1, -1}, {1, -1}, {1, 1 - c}, {1 - c, 1}, {-1, 1}};
  for (double z : {-1.0, 1.0})
    for (const auto& p : xy) m.vertices.push_back({p[0], p[1], z});
  auto tri = [&](int a, int b, int d) { m.faces.push_back({std::uint32_t(a), std::uint32_t(b), std::uint32_t(d)}); };
  for (int k = 1; k + 1 < 5; ++k) {
    tri(0, k + 1, k);          // bottom, seen from below
    tri(5, 5 + k, 5 + k + 1);  // top
  }
  for (int k = 0; k < 5; ++k) {  // the five side quads, counter-clockwise from outside
    const int a = k, b = (k + 1) % 5;
    tri(a, b, 5 + b);
    tri(a, 5 + b, 5 + a);
  }
  return m;
}

SurfaceMesh stepped_prism_mesh(double h) {
  SurfaceMesh m;
  // The hexagon A B C D E F at z = -1 (vertices 0-5) and z = 1 (6-11); D is
  // the step's concave corner and sees every other vertex.
  const double xy[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {0, 1}, {0, 1 + h}, {-1, 1 + h}};
  for (double z : {-1.0, 1.0})
    for (const auto& p : xy) m.vertices.push_back({p[0], p[1], z});
  auto tri = [&](int a, int b, int d) { m.faces.push_back({std::uint32_t(a), std::uint32_t(b), std::uint32_t(d)}); };
  for (int k : {4, 5, 0, 1}) {
    const int next = (k + 1) % 6;
    tri(3, next, k);              // bottom, seen from below
    tri(6 + 3, 6 + k, 6 + next);  // top
  }
  for (int k = 0; k < 6; ++k) {  // the six side quads, counter-clockwise from outside
    const int a = k, b = (k + 1) % 6;
    tri(a, b, 6 + b);
    tri(a, 6 + b, 6 + a);
  }
  return m;
}

SurfaceMesh hollow_box_mesh(double half_size, double cavity_half_size, double ball_radius, int ball_levels) {
  SurfaceMesh hollow = cube_mesh(half_size);
  SurfaceMesh cavity = cube_mesh(cavity_half_size);
  for (auto& f : cavity.faces) std::swap(f[1], f[2]);
  SurfaceMesh ball = sphere_mesh(ball_levels, ball_radius);
  for (const SurfaceMesh* part : {&cavity, &ball}) {
    const auto base = static_cast<std::uint32_t>(hollow.vertices.size());
    hollow.vertices.insert(hollow.vertices.end(), part->vertices.begin(), part->vertices.end());
    for (auto f : part->faces) hollow.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  }
  return hollow;
}

SurfaceMesh sphere_mesh(int levels, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  SurfaceMesh m;
  m.vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
             {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      m.vertices.push_back(0.5 * (m.vertices[a] + m.vertices[b]));
      return middle[key] = static_cast<std::uint32_t>(m.vertices.size() - 1);
    };
    std::vector<Triangle> faces;
    for (const Triangle& f : m.faces) {
      const std::uint32_t a = mid(f[0], f[1]), b = mid(f[1], f[2]), c = mid(f[2], f[0]);
      faces.push_back({f[0], a, c});
      faces.push_back({f[1], b, a});
      faces.push_back({f[2], c, b});
      faces.push_back({a, b, c});
    }
    m.faces = faces;
  }
  for (Vec3& v : m.vertices) v = (radius / norm(v)) * v;
  return m;
}

SurfaceMesh cylinder_mesh(double radius, double height, int segments) {
  SurfaceMesh m;
  for (int ring = 0; ring < 2; ++ring)
    for (int i = 0; i < segments; ++i) {
      const double a = 2 * M_PI * i / segments;
      m.vertices.push_back({radius * std::cos(a), radius * std::sin(a), ring ? height / 2 : -height / 2});
    }
  const auto bottom = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.push_back({0, 0, -height / 2});
  m.vertices.push_back({0, 0, height / 2});
  const auto n = static_cast<std::uint32_t>(segments);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.faces.push_back({i, j, n + j});
    m.faces.push_back({i, n + j, n + i});
    m.faces.push_back({bottom, j, i});
    m.faces.push_back({bottom + 1, n + i, n + j});
  }
  return m;
}

TempDir::TempDir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "sharpmesh-test-XXXXXX").string();
  dir_ = ::mkdtemp(pattern.data());
}

TempDir::~TempDir() { std::filesystem::remove_all(dir_); }

std::size_t TempDir::file_count() const {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++n;
  return n;
}

std::string data_file(const std::string& relative) {
  const std::string path = std::string(SHARPMESH_DATA_DIR) + "/" + relative;
  return std::filesystem::exists(path) ? path : "";
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace sharpmesh::test
