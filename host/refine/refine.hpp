// clmesh — GPU-QM and GPU-QM-V (thesis chapter 3): parallel Delaunay
// refinement of a point set's Delaunay triangulation to a minimum angle (-q)
// and a maximum area (-a), the phase entry point behind clmesh::triangulate().
// The convex hull is the boundary: hull edges are split at their midpoints
// when a candidate falls outside or encroaches them.
#pragma once

#include "dt/delaunay.hpp"

#include <optional>
#include <vector>

namespace clmesh {

struct RefineOptions {
  DelaunayOptions delaunay; // its tuning also chooses the refinement algorithm
  double min_angle = 20;    // degrees; 0: no angle bound
  std::optional<double> max_area;
  std::optional<long> max_steiner;
};

struct RefineResult {
  // Triangles over the input points followed by the Steiner points.
  DelaunayResult mesh;
  std::vector<Point> added_points; // Steiner point n + i is added_points[i]
  RefineStats stats;
};

RefineResult refine_delaunay(Device &device, const std::vector<Point> &points,
                             const RefineOptions &options);

} // namespace clmesh
