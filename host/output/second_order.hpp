// clmesh — second-order (six-node) triangles (-o2): a node at the middle of
// every edge of a finished mesh, as Triangle's highorder() adds them.
#pragma once

#include "clmesh/mesh.hpp"

namespace clmesh {

// Fills mesh.edge_midpoints, edge_midpoint_attributes, edge_midpoint_markers
// and triangle_midpoints (see clmesh/mesh.hpp) from its points, attributes,
// triangles, neighbours and, when constrained, segments.
void add_second_order_nodes(Mesh &mesh);

} // namespace clmesh
