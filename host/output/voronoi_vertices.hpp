// clmesh — the vertices of the Voronoi diagram (-v) on the device: the
// circumcentre of every triangle of a finished mesh, exact to a few ulps (the
// bound is in the kernel file), and the point attributes interpolated there
// as Triangle does. Kernels: cl/voronoi_vertices.cl.
#pragma once

#include "runtime/opencl_context.hpp"

#include "clmesh/geometry.hpp"

#include <vector>

namespace clmesh {

class VoronoiVertices {
public:
  static constexpr const char *kPhase = "voronoi_vertices";

  explicit VoronoiVertices(Device &device);

  // centers[t]: the circumcentre of triangles[t]; center_attributes:
  // attribute_count values per triangle, interpolated from its corners'.
  // Throws InternalError for a triangle whose corners are collinear.
  void compute(const std::vector<Point> &points, const std::vector<double> &attributes,
               int attribute_count, const std::vector<Triangle> &triangles,
               std::vector<Point> &centers, std::vector<double> &center_attributes);

private:
  Device &device_;
  cl::Kernel vertices_;
};

} // namespace clmesh
