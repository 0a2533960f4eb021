#include "device_mesh.hpp"

#include <algorithm>

namespace clmesh {

DeviceMesh::DeviceMesh(Device &device, std::size_t point_count)
    : point_capacity(point_count), triangle_capacity(2 * point_count + 2),
      list_capacity(std::max(4 * point_count, 2 * point_count + 2) + 16),
      points(device, point_count), original_id(device, point_count),
      tri_vertex(device, 3 * triangle_capacity), tri_neighbor(device, 3 * triangle_capacity),
      tri_mark(device, triangle_capacity), modified_stamp(device, triangle_capacity),
      children(device, 3 * triangle_capacity), vertex_triangle(device, point_count),
      duplicate_of(device, point_count), location(device, point_count),
      location_edge(device, point_count), constraint_start(device, point_count + 1),
      constraint_adjacent(device, 1) {}

} // namespace clmesh
