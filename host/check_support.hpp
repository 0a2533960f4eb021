// clmesh — helpers shared by the exact mesh checkers (check.cpp, check_constrained.cpp).
#pragma once

#include "clmesh/geometry.hpp"

#include "predicates.h"

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

} // namespace clmesh::check_support
