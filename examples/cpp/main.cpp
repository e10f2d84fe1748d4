#include <cstdio>

#include "sharpmesh/errors.h"
#include "sharpmesh/io.h"
#include "sharpmesh/reconstruct.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s CLOUD MESH\n", argv[0]);
    return 2;
  }
  try {
    const sharpmesh::PointSet cloud = sharpmesh::read_point_set(argv[1]);
    const sharpmesh::ReconstructResult result = sharpmesh::reconstruct(cloud, sharpmesh::ReconstructOptions{});
    sharpmesh::write_mesh(argv[2], result.mesh);
    std::printf("%zu facets, %zu feature lines\n", result.mesh.faces.size(), result.features.graph.polylines.size());
  } catch (const sharpmesh::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
