// clmesh — exact validity checks of a triangulation (used by tests and -C).
//
// Every topological and geometric decision below uses the exact predicates of
// cl/predicates.h, compiled on the host.  The checks together prove that the triangles form a
// triangulation of the points:
//   1. every triangle has three distinct in-range vertices and is strictly counter-clockwise;
//   2. every undirected edge lies in at most two triangles, and when in two, with opposite
//      directions; neighbour links are exactly these pairings (symmetric, same edge);
//   3. the unpaired ("boundary") edges form one closed cycle that is a convex polygon turned
//      once counter-clockwise and passes through every vertex of the convex hull of the used
//      points, so it is the boundary of that hull (every used point is on its left or on it);
//   4. the non-duplicate points have distinct coordinates and are all triangle vertices.
// Summing the triangles as an oriented 2-chain, interior edges cancel (2) and the boundary is
// the hull boundary turned once (3), so every point of the hull not on an edge is covered by
// exactly one (positively oriented, 1) triangle: no overlap and no hole.  The floating-point
// comparison of the triangle areas with the hull area comes after these exact checks and is
// only a sanity check.  With check_delaunay every interior edge is also tested to be locally
// Delaunay with the symbolically perturbed in-circle test (the rule of CGAL's
// Delaunay_triangulation_2), so cocircular inputs have exactly one accepted triangulation.
//
// Cost: O(n log n) (sorting of points and edges), a few seconds for a million triangles.
#include "clmesh/check.hpp"

#include "check/check_support.hpp"
#include "predicates.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <limits>

namespace clmesh {

namespace {

using namespace check_support;

constexpr std::size_t kMaxProblems = 20;

// Vertices of the convex hull of the given point indices, counter-clockwise, without
// collinear points (Andrew's monotone chain with the exact orientation).  `ids` must be sorted
// lexicographically by coordinates with no two equal points.
std::vector<int32_t> strict_hull(const std::vector<Point> &pts, const std::vector<int32_t> &ids) {
  if (ids.size() < 3)
    return ids;
  std::vector<int32_t> hull(2 * ids.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) { // lower chain
    while (k >= 2 && orient(pts, hull[k - 2], hull[k - 1], ids[i]) <= 0)
      --k;
    hull[k++] = ids[i];
  }
  for (std::size_t i = ids.size() - 1, lower = k + 1; i-- > 0;) { // upper chain
    while (k >= lower && orient(pts, hull[k - 2], hull[k - 1], ids[i]) <= 0)
      --k;
    hull[k++] = ids[i];
  }
  hull.resize(k - 1); // the last point repeats the first
  return hull;
}

} // namespace

void CheckReport::fail(const std::string &problem) {
  ok = false;
  if (problems.size() < kMaxProblems)
    problems.push_back(problem);
  else if (problems.size() == kMaxProblems)
    problems.push_back("(further problems not listed)");
}

CheckReport check_triangulation(const std::vector<Point> &points,
                                const std::vector<Triangle> &triangles,
                                const std::vector<std::array<int32_t, 3>> &neighbors,
                                const std::vector<int32_t> &duplicate_of, bool check_delaunay) {
  CheckReport report;
  const int64_t n = static_cast<int64_t>(points.size());
  const int64_t nt = static_cast<int64_t>(triangles.size());
  if (n > INT32_MAX || nt > INT32_MAX / 3) {
    report.fail("too many points or triangles for 32-bit indices");
    return report;
  }

  // --- Duplicates -------------------------------------------------------------------------
  bool duplicates_known = duplicate_of.size() == points.size();
  if (!duplicates_known && !duplicate_of.empty())
    report.fail("duplicate_of has " + std::to_string(duplicate_of.size()) + " entries for " +
                std::to_string(n) + " points");
  auto is_duplicate = [&](int32_t i) { return duplicates_known && duplicate_of[i] != -1; };
  std::vector<int32_t> distinct; // non-duplicate points, sorted lexicographically
  distinct.reserve(points.size());
  for (int32_t i = 0; i < n; ++i) {
    if (!is_duplicate(i)) {
      distinct.push_back(i);
      continue;
    }
    const int32_t j = duplicate_of[i];
    if (j < 0 || j >= n || j == i)
      report.fail("point " + std::to_string(i) + ": duplicate_of is " + std::to_string(j));
    else if (duplicate_of[j] != -1)
      report.fail("point " + std::to_string(i) + " is a duplicate of " + std::to_string(j) +
                  ", itself marked a duplicate");
    else if (!same_point(points[i], points[j]))
      report.fail("point " + point_text(points, i) + " marked a duplicate of " +
                  point_text(points, j) + " with different coordinates");
  }
  std::sort(distinct.begin(), distinct.end(), [&](int32_t a, int32_t b) {
    return lex_less(points[a], points[b]) || (same_point(points[a], points[b]) && a < b);
  });
  for (std::size_t k = 1; k < distinct.size(); ++k)
    if (same_point(points[distinct[k - 1]], points[distinct[k]]))
      report.fail("points " + point_text(points, distinct[k - 1]) + " and " +
                  std::to_string(distinct[k]) + " coincide but neither is marked a duplicate");

  // --- Triangles: indices and exact orientation --------------------------------------------
  std::vector<char> valid(triangles.size(), 0); // usable by the checks below
  std::vector<char> used(points.size(), 0);
  int64_t valid_count = 0;
  for (int64_t t = 0; t < nt; ++t) {
    const Triangle &v = triangles[t];
    bool in_range = true;
    for (int32_t id : v)
      in_range = in_range && id >= 0 && id < n;
    if (!in_range) {
      report.fail(triangle_text(triangles, t) + ": vertex index out of range");
      continue;
    }
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
      report.fail(triangle_text(triangles, t) + ": repeated vertex");
      continue;
    }
    for (int32_t id : v)
      if (is_duplicate(id))
        report.fail(triangle_text(triangles, t) + ": uses point " + std::to_string(id) +
                    ", marked a duplicate");
    const int o = orient(points, v[0], v[1], v[2]);
    if (o <= 0) {
      report.fail(triangle_text(triangles, t) +
                  (o < 0 ? ": clockwise" : ": degenerate (collinear vertices)"));
      continue;
    }
    valid[t] = 1;
    ++valid_count;
    for (int32_t id : v)
      used[id] = 1;
  }

  // --- Edges: at most two triangles, opposite directions; neighbour links ------------------
  const bool have_neighbors = neighbors.size() == triangles.size();
  if (!have_neighbors)
    report.fail("neighbors has " + std::to_string(neighbors.size()) + " entries for " +
                std::to_string(nt) + " triangles");
  const std::vector<EdgeRecord> edges = sorted_sides(triangles, valid);
  auto from_of = [&](const EdgeRecord &e) { return triangles[e.tri][(e.slot + 1) % 3]; };
  auto to_of = [&](const EdgeRecord &e) { return triangles[e.tri][(e.slot + 2) % 3]; };
  // partner[3t + i]: the triangle across side i of t from the edge pairing (-1: boundary),
  // partner_slot: its side; -2 for sides of unusable triangles or of over-shared edges.
  std::vector<int32_t> partner(3 * triangles.size(), -2), partner_slot(3 * triangles.size(), -1);
  std::vector<int32_t> boundary_next(points.size(), -1); // boundary edge v -> boundary_next[v]
  int64_t boundary_edges = 0;
  bool boundary_ok = true;
  for (std::size_t lo = 0, hi; lo < edges.size(); lo = hi) {
    for (hi = lo + 1; hi < edges.size() && edges[hi].key == edges[lo].key;)
      ++hi;
    const EdgeRecord &e = edges[lo];
    const std::string edge_text =
        "edge " + std::to_string(from_of(e)) + "-" + std::to_string(to_of(e));
    if (hi - lo > 2) {
      report.fail(edge_text + " is in " + std::to_string(hi - lo) + " triangles");
      boundary_ok = false;
    } else if (hi - lo == 2) {
      const EdgeRecord &f = edges[lo + 1];
      if (from_of(e) != to_of(f)) {
        report.fail(edge_text + " has the same direction in triangles " + std::to_string(e.tri) +
                    " and " + std::to_string(f.tri) + " (overlap)");
        boundary_ok = false;
        continue;
      }
      pair_sides(partner, partner_slot, e, f);
    } else {
      partner[3 * e.tri + e.slot] = -1;
      ++boundary_edges;
      const int32_t from = from_of(e);
      if (boundary_next[from] != -1) {
        report.fail("point " + std::to_string(from) + " starts two boundary edges");
        boundary_ok = false;
      }
      boundary_next[from] = to_of(e);
    }
  }
  if (have_neighbors) {
    for (int32_t t = 0; t < nt; ++t) {
      if (!valid[t])
        continue;
      for (int32_t i = 0; i < 3; ++i) {
        const int32_t u = neighbors[t][i], expected = partner[3 * t + i];
        if (expected == -2 || u == expected)
          continue;
        std::string problem = triangle_text(triangles, t) + ": neighbour " + std::to_string(i) +
                              " is " + std::to_string(u);
        if (expected == -1)
          problem += ", but no other triangle has that edge";
        else
          problem += ", but the triangle across that edge is " + std::to_string(expected);
        report.fail(problem);
      }
    }
  }

  // --- Every point not marked a duplicate is a vertex --------------------------------------
  const std::vector<int32_t> all_hull = strict_hull(points, distinct);
  const bool all_collinear = all_hull.size() < 3;
  if (!(valid_count == 0 && nt == 0 && all_collinear)) {
    int64_t unused = 0;
    for (int32_t i : distinct)
      if (!used[i] && unused++ < 5)
        report.fail("point " + point_text(points, i) + " is not a vertex of any triangle");
    if (unused > 5)
      report.fail(std::to_string(unused) + " points in all are not vertices of any triangle");
  }

  // --- Boundary: one convex cycle, turned once, through every hull vertex -----------------
  std::vector<int32_t> used_sorted;
  for (int32_t i : distinct)
    if (used[i])
      used_sorted.push_back(i);
  const std::vector<int32_t> hull = strict_hull(points, used_sorted);
  if (valid_count > 0 && boundary_edges == 0) {
    report.fail("the triangles have no boundary edge");
    boundary_ok = false;
  }
  if (valid_count > 0 && boundary_ok) {
    // Split the boundary edges into cycles; the boundary must be one cycle.
    std::vector<int32_t> cycle;
    std::vector<char> seen(points.size(), 0);
    int64_t cycles = 0;
    for (int32_t start = 0; start < n; ++start) {
      if (boundary_next[start] == -1 || seen[start])
        continue;
      ++cycles;
      std::vector<int32_t> walk;
      int32_t v = start;
      while (v != -1 && !seen[v]) {
        seen[v] = 1;
        walk.push_back(v);
        v = boundary_next[v];
      }
      if (v != start) {
        report.fail("the boundary edges from point " + std::to_string(start) +
                    " do not close into a cycle");
        boundary_ok = false;
      }
      if (cycles == 1)
        cycle.swap(walk);
    }
    if (cycles != 1) {
      report.fail("the boundary is " + std::to_string(cycles) +
                  " cycles, not one (a hole or a separate piece)");
      boundary_ok = false;
    }
    if (boundary_ok) {
      // Convex and turned once: no right turn, no reversal at a straight vertex, and exactly
      // one vertex lexicographically smaller than both its boundary neighbours (the edge
      // direction, turning monotonically, passes "downwards to upwards" once per turn).
      const std::size_t m = cycle.size();
      int64_t minima = 0;
      for (std::size_t k = 0; k < m; ++k) {
        const Point &p = points[cycle[(k + m - 1) % m]];
        const Point &c = points[cycle[k]];
        const Point &q = points[cycle[(k + 1) % m]];
        const int o = clm_orient2d(p.x, p.y, c.x, c.y, q.x, q.y);
        auto sgn = [](double u, double w) { return (u > w) - (u < w); };
        if (o < 0) {
          report.fail("the boundary turns right at point " + point_text(points, cycle[k]) +
                      ": it is not the convex hull");
          boundary_ok = false;
        } else if (o == 0 && (sgn(c.x, p.x) != sgn(q.x, c.x) || sgn(c.y, p.y) != sgn(q.y, c.y))) {
          report.fail("the boundary turns back at point " + point_text(points, cycle[k]));
          boundary_ok = false;
        }
        if (lex_less(c, p) && lex_less(c, q))
          ++minima;
      }
      if (boundary_ok && minima != 1) {
        report.fail("the boundary winds " + std::to_string(minima) +
                    " times around the triangulation");
        boundary_ok = false;
      }
      // A convex cycle of used points through every hull vertex bounds the hull itself, so
      // every used point is on the left of every boundary edge or on it.
      for (int32_t h : hull)
        if (boundary_next[h] == -1) {
          report.fail("convex hull vertex " + point_text(points, h) +
                      " is not on the boundary of the triangulation");
          boundary_ok = false;
        }
    }
  }

  // --- Sanity check: the triangle areas add up to the hull area -----------------------------
  // After the exact checks above this can only fail on an inconsistency they missed.  Both
  // sums are of cross products relative to a vertex, in long double, compared with a
  // relative tolerance of 1e-9, widened by the rounding of the products: slivers of a hull a
  // hair from flat have areas far below their products' terms.
  if (valid_count > 0 && hull.size() >= 3) {
    long double triangle_area = 0, hull_area = 0, terms = 0;
    auto cross = [&](int32_t a, int32_t b, int32_t c) {
      const long double ax = points[a].x, ay = points[a].y;
      const long double u = (points[b].x - ax) * (points[c].y - ay),
                        w = (points[b].y - ay) * (points[c].x - ax);
      terms += std::fabs(u) + std::fabs(w);
      return u - w;
    };
    for (int64_t t = 0; t < nt; ++t)
      if (valid[t])
        triangle_area += cross(triangles[t][0], triangles[t][1], triangles[t][2]);
    for (std::size_t k = 1; k + 1 < hull.size(); ++k)
      hull_area += cross(hull[0], hull[k], hull[k + 1]);
    const long double rounding = 8 * std::numeric_limits<long double>::epsilon() * terms;
    if (std::fabs(triangle_area - hull_area) > 1e-9L * std::fabs(hull_area) + rounding) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "triangle areas sum to %.17Lg, the convex hull's is %.17Lg",
                    triangle_area / 2, hull_area / 2);
      report.fail(buf);
    }
  }

  // --- Delaunay: every interior edge locally Delaunay (perturbed in-circle) -----------------
  if (check_delaunay) {
    int64_t bad = 0;
    for (int32_t t = 0; t < nt; ++t) {
      if (!valid[t])
        continue;
      const Triangle &v = triangles[t];
      for (int32_t i = 0; i < 3; ++i) {
        const int32_t u = partner[3 * t + i];
        if (u < t) // boundary, unusable, or checked from u (the test is symmetric)
          continue;
        const int32_t d = triangles[u][partner_slot[3 * t + i]];
        const Point &a = points[v[0]], &b = points[v[1]], &c = points[v[2]], &p = points[d];
        if (clm_incircle_sos(a.x, a.y, b.x, b.y, c.x, c.y, p.x, p.y) != -1 && bad++ < 5)
          report.fail("edge " + std::to_string(v[(i + 1) % 3]) + "-" +
                      std::to_string(v[(i + 2) % 3]) + " is not locally Delaunay: point " +
                      point_text(points, d) + " is inside the circumcircle of " +
                      triangle_text(triangles, t));
      }
    }
    if (bad > 5)
      report.fail(std::to_string(bad) + " edges in all are not locally Delaunay");
  }
  return report;
}

} // namespace clmesh
