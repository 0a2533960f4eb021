// clmesh — GPU-QM: parallel Delaunay refinement of a point set's Delaunay
// triangulation to a minimum angle (-q) and a maximum area (-a) (thesis
// chapter 3). The convex hull is the boundary: hull edges are split at their
// midpoints when a candidate falls outside or encroaches them.
#pragma once

#include "clmesh/delaunay.hpp"

#include <vector>

namespace clmesh {

struct RefineOptions {
  DelaunayOptions delaunay;
  double min_angle = 20; // degrees; 0: no angle bound (-q alone means 20)
  double max_area = -1;  // -a; <= 0: none
  long max_steiner = -1; // -S; < 0: no limit
};

struct RefineStats {
  long iterations = 0;
  long candidates = 0;      // bad triangles' candidates, over all iterations
  long inserted = 0;        // Steiner points in the mesh
  long boundary_splits = 0; // of them, midpoints of hull edges
  long remaining_bad = 0;   // bad triangles left (small hull angles, -S reached)
};

struct RefineResult {
  // Triangles over the input points followed by the Steiner points.
  DelaunayResult mesh;
  std::vector<Point> added_points; // Steiner point n + i is added_points[i]
  RefineStats stats;
};

// Not yet: deletion of redundant Steiner points by flip-flop (thesis §3.3.2
// step 3) and the QM-V variant; refinement of PSLGs (-pq).
RefineResult refine_delaunay(Device &device, const std::vector<Point> &points,
                             const RefineOptions &options);

} // namespace clmesh
