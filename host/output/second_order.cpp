#include "output/second_order.hpp"

#include "clmesh/errors.hpp"
#include "clmesh/io.hpp"
#include "io/edge_order.hpp"

namespace clmesh {

void add_second_order_nodes(Mesh &mesh) {
  const std::vector<Edge> edges = mesh.statistics.constrained
                                      ? mesh_edges(mesh.triangles, mesh.neighbors, mesh.segments)
                                      : mesh_edges(mesh.triangles, mesh.neighbors);
  const auto attributes = static_cast<std::size_t>(mesh.attribute_count);
  mesh.edge_midpoints.assign(edges.size(), Point{});
  mesh.edge_midpoint_attributes.assign(edges.size() * attributes, 0.0);
  mesh.edge_midpoint_markers.assign(edges.size(), 0);
  mesh.triangle_midpoints.assign(mesh.triangles.size(), {-1, -1, -1});
  int32_t next = 0;
  visit_edges(mesh.triangles, mesh.neighbors, [&](std::size_t t, int i, int32_t other) {
    const int32_t k = next++;
    const Edge &edge = edges[static_cast<std::size_t>(k)];
    const Point &a = mesh.points[edge.a], &b = mesh.points[edge.b];
    // The sum is rounded once; halving it is exact.
    mesh.edge_midpoints[k] = Point{(a.x + b.x) * 0.5, (a.y + b.y) * 0.5};
    for (std::size_t j = 0; j < attributes; ++j)
      mesh.edge_midpoint_attributes[k * attributes + j] =
          (mesh.point_attributes[edge.a * attributes + j] +
           mesh.point_attributes[edge.b * attributes + j]) *
          0.5;
    mesh.edge_midpoint_markers[k] = edge.marker;
    mesh.triangle_midpoints[t][i] = k;
    if (other == -1)
      return;
    // The same edge in the triangle across: opposite its vertex off the edge.
    for (int j = 0; j < 3; ++j) {
      const int32_t v = mesh.triangles[other][j];
      if (v != edge.a && v != edge.b)
        mesh.triangle_midpoints[other][j] = k;
    }
  });
  for (const auto &midpoints : mesh.triangle_midpoints)
    for (int32_t k : midpoints)
      if (k < 0)
        throw InternalError("-o2: a triangle edge has no middle node (inconsistent neighbours)");
}

} // namespace clmesh
