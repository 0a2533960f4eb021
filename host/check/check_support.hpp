// clmesh — helpers shared by the exact mesh checkers (check.cpp, check_constrained.cpp).
#pragma once

#include "clmesh/geometry.hpp"

#include "predicates.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <string>
#include <vector>

namespace clmesh::check_support {

inline std::string point_text(const std::vector<Point> &points, int32_t i) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%" PRId32 " (%.17g, %.17g)", i, points[i].x, points[i].y);
  return buf;
}

inline std::string triangle_text(const std::vector<Triangle> &triangles, std::size_t t) {
  const Triangle &v = triangles[t];
  return "triangle " + std::to_string(t) + " (" + std::to_string(v[0]) + ", " +
         std::to_string(v[1]) + ", " + std::to_string(v[2]) + ")";
}

inline bool lex_less(const Point &p, const Point &q) {
  return p.x < q.x || (p.x == q.x && p.y < q.y);
}

inline bool same_point(const Point &p, const Point &q) { return p.x == q.x && p.y == q.y; }

inline int orient(const std::vector<Point> &pts, int32_t a, int32_t b, int32_t c) {
  return clm_orient2d(pts[a].x, pts[a].y, pts[b].x, pts[b].y, pts[c].x, pts[c].y);
}

// An undirected edge as one 64-bit key: (smaller vertex << 32) | larger.
inline uint64_t edge_key(int32_t a, int32_t b) {
  const auto lo = static_cast<uint32_t>(std::min(a, b)), hi = static_cast<uint32_t>(std::max(a, b));
  return (uint64_t{lo} << 32) | hi;
}

// One side of a triangle: the directed edge opposite triangles[tri][slot].
struct EdgeRecord {
  uint64_t key; // edge_key of its endpoints
  int32_t tri;
  int32_t slot;
};

// Records that sides e and f are the two sides of one edge.
inline void pair_sides(std::vector<int32_t> &partner, std::vector<int32_t> &partner_slot,
                       const EdgeRecord &e, const EdgeRecord &f) {
  partner[3 * e.tri + e.slot] = f.tri;
  partner_slot[3 * e.tri + e.slot] = f.slot;
  partner[3 * f.tri + f.slot] = e.tri;
  partner_slot[3 * f.tri + f.slot] = e.slot;
}

// Every side of the usable triangles, sorted by edge (then triangle, side),
// so the sides of one edge are adjacent.
inline std::vector<EdgeRecord> sorted_sides(const std::vector<Triangle> &triangles,
                                            const std::vector<char> &usable) {
  std::vector<EdgeRecord> sides;
  sides.reserve(3 * triangles.size());
  for (int32_t t = 0; t < static_cast<int32_t>(triangles.size()); ++t)
    if (usable[t])
      for (int32_t i = 0; i < 3; ++i)
        sides.push_back({edge_key(triangles[t][(i + 1) % 3], triangles[t][(i + 2) % 3]), t, i});
  std::sort(sides.begin(), sides.end(), [](const EdgeRecord &p, const EdgeRecord &q) {
    return p.key < q.key ||
           (p.key == q.key && (p.tri < q.tri || (p.tri == q.tri && p.slot < q.slot)));
  });
  return sides;
}

} // namespace clmesh::check_support
