#include "output/voronoi_diagram.hpp"

#include "io/edge_order.hpp"
#include "output/voronoi_vertices.hpp"

namespace clmesh {

void add_voronoi_diagram(Device &device, Mesh &mesh) {
  VoronoiVertices(device).compute(mesh.points, mesh.point_attributes, mesh.attribute_count,
                                  mesh.triangles, mesh.voronoi_points,
                                  mesh.voronoi_point_attributes);
  mesh.voronoi_edges.clear();
  mesh.voronoi_edges.reserve(mesh.triangles.size() * 3 / 2 + 3);
  visit_edges(mesh.triangles, mesh.neighbors, [&](std::size_t t, int i, int32_t other) {
    VoronoiEdge edge{static_cast<int32_t>(t), other, Point{}};
    if (other == -1) {
      // Triangle's ray: (dest.y - org.y, org.x - dest.x) of the hull edge
      // org -> dest, which has the triangle on its left.
      const Point &org = mesh.points[mesh.triangles[t][(i + 1) % 3]];
      const Point &dest = mesh.points[mesh.triangles[t][(i + 2) % 3]];
      edge.direction = Point{dest.y - org.y, org.x - dest.x};
    }
    mesh.voronoi_edges.push_back(edge);
  });
}

} // namespace clmesh
