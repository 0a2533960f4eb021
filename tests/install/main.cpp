// Meshes a square with an installed clmesh: two triangles.
#include <clmesh/clmesh.hpp>

#include <cstdio>

int main() {
  clmesh::Input input;
  input.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const clmesh::Mesh mesh = clmesh::triangulate(*clmesh::open_device(), input, "zQ");
  for (const auto &t : mesh.triangles)
    std::printf("%d %d %d\n", t[0], t[1], t[2]);
  std::printf("clmesh %s\n", clmesh::version_string);
  return mesh.triangles.size() == 2 ? 0 : 1;
}
