// clmesh — whether a closed polyline is a simple polygon (simple_loop.hpp).
#include "dt/simple_loop.hpp"

#include "predicates.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace clmesh {

namespace {

int orient(const Point &a, const Point &b, const Point &c) {
  return clm_orient2d(a.x, a.y, b.x, b.y, c.x, c.y);
}

// Whether c, collinear with a and b, lies within their bounding box (then
// on the closed segment ab).
bool within(const Point &a, const Point &b, const Point &c) {
  return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
         c.y <= std::max(a.y, b.y);
}

// Whether the closed segments pq and rs have a point in common.
bool segments_meet(const Point &p, const Point &q, const Point &r, const Point &s) {
  const int d1 = orient(p, q, r), d2 = orient(p, q, s), d3 = orient(r, s, p), d4 = orient(r, s, q);
  if (d1 * d2 < 0 && d3 * d4 < 0)
    return true;
  return (d1 == 0 && within(p, q, r)) || (d2 == 0 && within(p, q, s)) ||
         (d3 == 0 && within(r, s, p)) || (d4 == 0 && within(r, s, q));
}

} // namespace

bool is_simple_loop(const std::vector<Point> &points, const std::vector<int32_t> &loop) {
  return are_simple_loops(points, loop, {0, loop.size()});
}

bool are_simple_loops(const std::vector<Point> &points, const std::vector<int32_t> &corners,
                      const std::vector<std::size_t> &starts) {
  const std::size_t m = corners.size();
  // Edge k of all goes from corner k to the next of its loop, next[k].
  std::vector<std::size_t> next(m);
  for (std::size_t l = 0; l + 1 < starts.size(); ++l) {
    const std::size_t first = starts[l], end = starts[l + 1];
    if (end < first + 3)
      return false;
    for (std::size_t k = first; k < end; ++k)
      next[k] = k + 1 < end ? k + 1 : first;
  }
  if (m == 0)
    return false;
  auto corner = [&](std::size_t k) -> const Point & {
    return points[static_cast<std::size_t>(corners[k])];
  };
  // Consecutive edges meet at their corner alone: no spike back along the
  // edge before (a straight corner goes on forward).
  for (std::size_t k = 0; k < m; ++k) {
    const Point &a = corner(k), &b = corner(next[k]), &c = corner(next[next[k]]);
    if (orient(a, b, c) == 0 && (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y) <= 0)
      return false;
  }
  // Every other pair of edges apart: the edges go into the cells of a grid
  // of about one cell per edge that their boxes meet, and the edges of a
  // cell are tested in pairs.
  double low_x = corner(0).x, high_x = low_x, low_y = corner(0).y, high_y = low_y;
  for (std::size_t k = 1; k < m; ++k) {
    low_x = std::min(low_x, corner(k).x);
    high_x = std::max(high_x, corner(k).x);
    low_y = std::min(low_y, corner(k).y);
    high_y = std::max(high_y, corner(k).y);
  }
  const auto side =
      static_cast<std::size_t>(std::clamp(std::sqrt(static_cast<double>(m)), 1.0, 4096.0));
  const double width = high_x - low_x, height = high_y - low_y;
  auto cell_of = [&](double value, double low, double span) {
    if (!(span > 0))
      return std::size_t{0};
    const double at = (value - low) / span * static_cast<double>(side);
    return std::min(side - 1, static_cast<std::size_t>(std::max(0.0, at)));
  };
  const std::size_t budget = 16 * m + 1024;
  std::vector<std::vector<std::uint32_t>> cells(side * side);
  std::size_t entries = 0;
  for (std::size_t k = 0; k < m; ++k) {
    const Point &a = corner(k), &b = corner(next[k]);
    const std::size_t x0 = cell_of(std::min(a.x, b.x), low_x, width),
                      x1 = cell_of(std::max(a.x, b.x), low_x, width),
                      y0 = cell_of(std::min(a.y, b.y), low_y, height),
                      y1 = cell_of(std::max(a.y, b.y), low_y, height);
    entries += (x1 - x0 + 1) * (y1 - y0 + 1);
    if (entries > budget)
      return false; // long edges across many cells: not worth deciding
    for (std::size_t y = y0; y <= y1; ++y)
      for (std::size_t x = x0; x <= x1; ++x)
        cells[y * side + x].push_back(static_cast<std::uint32_t>(k));
  }
  std::size_t tests = 0;
  for (const std::vector<std::uint32_t> &cell : cells)
    for (std::size_t i = 0; i < cell.size(); ++i)
      for (std::size_t j = i + 1; j < cell.size(); ++j) {
        const std::size_t e = cell[i], f = cell[j];
        if (next[e] == f || next[f] == e)
          continue; // consecutive: checked above
        if (++tests > 4 * budget)
          return false;
        if (segments_meet(corner(e), corner(next[e]), corner(f), corner(next[f])))
          return false;
      }
  return true;
}

int loop_turn(const std::vector<Point> &points, const std::vector<int32_t> &corners,
              std::size_t first, std::size_t end) {
  auto at = [&](std::size_t k) -> const Point & {
    return points[static_cast<std::size_t>(corners[k])];
  };
  std::size_t lowest = first;
  for (std::size_t k = first + 1; k < end; ++k)
    if (at(k).y < at(lowest).y || (at(k).y == at(lowest).y && at(k).x < at(lowest).x))
      lowest = k;
  const std::size_t before = lowest > first ? lowest - 1 : end - 1,
                    after = lowest + 1 < end ? lowest + 1 : first;
  return orient(at(before), at(lowest), at(after)) > 0 ? 1 : -1;
}

} // namespace clmesh
