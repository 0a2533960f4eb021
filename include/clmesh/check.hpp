// clmesh — exact validity checks of a triangulation (used by tests and -C).
#pragma once

#include "clmesh/geometry.hpp"

#include <array>
#include <string>
#include <vector>

namespace clmesh {

struct CheckReport {
  bool ok = true;
  std::vector<std::string> problems; // first few problems found, human-readable
  void fail(const std::string &problem);
};

// Checks with exact predicates: every triangle counter-clockwise, neighbour
// links symmetric, each edge in at most two triangles, the boundary equal to
// the convex hull of the points used, every point not marked duplicate used,
// and (when check_delaunay) every interior edge locally Delaunay.
CheckReport check_triangulation(const std::vector<Point> &points,
                                const std::vector<Triangle> &triangles,
                                const std::vector<std::array<int32_t, 3>> &neighbors,
                                const std::vector<int32_t> &duplicate_of,
                                bool check_delaunay = true);

} // namespace clmesh
