// clmesh — whether closed polylines are simple polygons apart from each
// other, and which way one turns, decided exactly: for taking a given mesh
// (-r) as it is (DelaunayScheduler::take_triangles).
#pragma once

#include "clmesh/geometry.hpp"

#include <cstddef>
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

// The same for several loops, loop l through points[corners[starts[l]]] ..
// points[corners[starts[l + 1] - 1]] (starts: the loops' first corners,
// then corners.size()): each simple, and no two meeting at all. The budget
// is linear in the corners of all loops.
bool are_simple_loops(const std::vector<Point> &points, const std::vector<int32_t> &corners,
                      const std::vector<std::size_t> &starts);

// Which way the simple loop of corners[first .. end) turns: 1 counter-
// clockwise, -1 clockwise (exact: the turn at its lowest corner, leftmost
// of the lowest, where a simple loop never goes straight).
int loop_turn(const std::vector<Point> &points, const std::vector<int32_t> &corners,
              std::size_t first, std::size_t end);

} // namespace clmesh
