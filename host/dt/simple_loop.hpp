// clmesh — whether a closed polyline is a simple polygon, decided exactly:
// for taking a given mesh (-r) as it is (DelaunayScheduler::take_triangles).
#pragma once

#include "clmesh/geometry.hpp"

#include <cstdint>
#include <vector>

namespace clmesh {

// Whether the polygon through points[loop[0]], points[loop[1]], ... and back
// to the first is simple: no two of its edges meet but consecutive ones, at
// their shared corner only (no spike back along an edge, no corner on
// another edge, no two corners at one place). Exact (orient2d). The edges
// are paired through a grid of cells; a loop whose edges crowd the cells
// beyond a budget of work linear in its length gives false, as does one of
// fewer than three corners.
bool is_simple_loop(const std::vector<Point> &points, const std::vector<int32_t> &loop);

} // namespace clmesh
