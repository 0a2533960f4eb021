// clmesh — Triangle's Voronoi diagram of a finished mesh (-v): a vertex per
// triangle (its circumcentre, computed on the device by VoronoiVertices) and
// an edge per mesh edge, a ray on the hull.
#pragma once

#include "runtime/opencl_context.hpp"

#include "clmesh/mesh.hpp"

namespace clmesh {

// Fills mesh.voronoi_points, voronoi_point_attributes and voronoi_edges from
// its points, attributes, triangles and neighbours.
void add_voronoi_diagram(Device &device, Mesh &mesh);

} // namespace clmesh
