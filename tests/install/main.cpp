// Meshes a square with an installed clmesh: two triangles.
#include "clmesh/delaunay.hpp"
#include "clmesh/device.hpp"
#include "clmesh/version.hpp"

#include <cstdio>

int main() {
  auto device = clmesh::open_device();
  const auto mesh = clmesh::delaunay(*device, {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  for (const auto &t : mesh.triangles)
    std::printf("%d %d %d\n", t[0], t[1], t[2]);
  std::printf("clmesh %s\n", clmesh::version_string);
  return mesh.triangles.size() == 2 ? 0 : 1;
}
