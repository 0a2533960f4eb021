#include "device_mesh.hpp"

#include <algorithm>

namespace clmesh {

DeviceMesh::DeviceMesh(Device &device, std::size_t input_points, std::size_t extra_points)
    : point_capacity(input_points + extra_points), point_count(input_points),
      triangle_capacity(2 * point_capacity + 2),
      // Each winner of an insertion round owns a triangle and adds two, so the
      // 4 entries per winner stay below 4/3 of the triangle slots.
      list_capacity(4 * triangle_capacity / 3 + 16), points(device, point_capacity),
      original_id(device, point_capacity), tri_vertex(device, 3 * triangle_capacity),
      tri_neighbor(device, 3 * triangle_capacity), tri_mark(device, triangle_capacity),
      modified_stamp(device, triangle_capacity), children(device, 3 * triangle_capacity),
      vertex_triangle(device, point_capacity), duplicate_of(device, point_capacity),
      location(device, point_capacity), location_edge(device, point_capacity),
      constraint_start(device, point_capacity + 1), constraint_adjacent(device, 1) {}

} // namespace clmesh
