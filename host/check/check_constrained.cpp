// clmesh — exact checks of a constrained Delaunay triangulation (tests and -C with -p).
//
// See check.hpp for what is checked.  Every decision uses the exact predicates of
// cl/predicates.h compiled on the host; coordinates are only ever compared, never computed.
//
//  - Topology: with whole_hull the proof of check_triangulation (one convex boundary cycle, the
//    triangles cover the hull exactly once); otherwise local checks: valid counter-clockwise
//    triangles, edges shared by at most two triangles in opposite directions, symmetric
//    neighbour links, and every vertex fan turning at most once around its vertex (a closed fan
//    exactly once, an open one less than once).
//  - Segments: each segment a-b (after mapping its endpoints to the points standing for their
//    duplicates) is walked from a: from the current vertex c the mesh edge c-w with w on the
//    segment, strictly beyond c and not beyond b, continues the chain.  With whole_hull a
//    missing edge is an error; otherwise the segment may leave the mesh (its part outside the
//    domain was eaten) and the walk goes on at the next point lying on the segment, found in
//    the lexicographically sorted points (points on a segment are in lexicographic order along
//    it, so only points between c and b in that order are candidates).
//    Points the run added where segments cross (first_added on) are rounded: the walk steps
//    onto one where it lies within rounding of the segment, a test in floating point.
//  - Constrained Delaunay: every edge between two triangles that is not part of a segment is
//    locally Delaunay (clm_incircle_sos == -1 for the vertex across it); without whole_hull
//    every boundary edge is part of a segment.
#include "cdt/constrained.hpp"
#include "clmesh/check.hpp"

#include "check/check_support.hpp"
#include "predicates.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <unordered_set>

namespace clmesh {

namespace {

using namespace check_support;

int sgn(double u, double w) { return (u > w) - (u < w); }

// For w collinear with segment a-b: is w strictly beyond c (towards b) and not beyond b?  Along
// a segment the lexicographic order of its points is monotone, so comparing with it decides.
bool between_on_segment(const Point &c, const Point &w, const Point &b) {
  const bool forward = lex_less(c, b);
  return forward ? (lex_less(c, w) && !lex_less(b, w)) : (lex_less(w, c) && !lex_less(w, b));
}

// Is w ahead of c along the direction from a to b? The offset w - c, of two
// points near each other, keeps its digits; a projection from a would not.
bool ahead_along(const Point &a, const Point &b, const Point &c, const Point &w) {
  return (w.x - c.x) * (b.x - a.x) + (w.y - c.y) * (b.y - a.y) > 0;
}

// In a mesh with rounded crossings: does w lie on a-b up to rounding? Its
// distance from the line, measured from the endpoint nearer to it, is at most
// 1e-12 of the magnitude of its coordinates and that endpoint's (a rounded
// crossing is a few units in the last place off; a far endpoint, at 1e20 say,
// does not widen the test).
bool within_rounding_of(const Point &a, const Point &b, const Point &w) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const Point &e =
      std::abs(w.x - a.x) + std::abs(w.y - a.y) <= std::abs(w.x - b.x) + std::abs(w.y - b.y) ? a
                                                                                             : b;
  const double cross = dx * (w.y - e.y) - dy * (w.x - e.x);
  const double magnitude = std::max({std::abs(e.x), std::abs(e.y), std::abs(w.x), std::abs(w.y)});
  return std::abs(cross) <= 1e-12 * magnitude * std::hypot(dx, dy);
}

} // namespace

CheckReport check_constrained(const std::vector<Point> &points,
                              const std::vector<Triangle> &triangles,
                              const std::vector<std::array<int32_t, 3>> &neighbors,
                              const std::vector<int32_t> &duplicate_of,
                              const std::vector<Segment> &segments, bool whole_hull,
                              int32_t first_added, bool crossings_at_vertices) {
  CheckReport report;
  const int64_t n = static_cast<int64_t>(points.size());
  const int64_t nt = static_cast<int64_t>(triangles.size());
  if (n > INT32_MAX || nt > INT32_MAX / 3) {
    report.fail("too many points or triangles for 32-bit indices");
    return report;
  }
  // With whole_hull the topology is proved by check_triangulation; the local checks below
  // then only report what it does not.
  if (whole_hull)
    report = check_triangulation(points, triangles, neighbors, duplicate_of, false);
  const bool local = !whole_hull;
  const bool duplicates_known = duplicate_of.size() == points.size();
  if (local && !duplicates_known && !duplicate_of.empty())
    report.fail("duplicate_of has " + std::to_string(duplicate_of.size()) + " entries for " +
                std::to_string(n) + " points");
  auto representative = [&](int32_t i) {
    if (!duplicates_known || duplicate_of[i] < 0 || duplicate_of[i] >= n)
      return i;
    return duplicate_of[i];
  };

  // --- Triangles ----------------------------------------------------------------------------
  std::vector<char> valid(triangles.size(), 0);
  for (int64_t t = 0; t < nt; ++t) {
    const Triangle &v = triangles[t];
    bool ok = true;
    for (int32_t id : v)
      ok = ok && id >= 0 && id < n;
    ok = ok && v[0] != v[1] && v[1] != v[2] && v[0] != v[2];
    if (ok && orient(points, v[0], v[1], v[2]) <= 0)
      ok = false;
    if (!ok) {
      if (local)
        report.fail(triangle_text(triangles, t) + ": out of range, repeated vertex or not "
                                                  "counter-clockwise");
      continue;
    }
    if (local)
      for (int32_t id : v)
        if (representative(id) != id)
          report.fail(triangle_text(triangles, t) + ": uses point " + std::to_string(id) +
                      ", marked a duplicate");
    valid[t] = 1;
  }

  // --- Edge pairing and neighbour links -----------------------------------------------------
  const std::vector<EdgeRecord> edges = sorted_sides(triangles, valid);
  auto from_of = [&](const EdgeRecord &e) { return triangles[e.tri][(e.slot + 1) % 3]; };
  auto to_of = [&](const EdgeRecord &e) { return triangles[e.tri][(e.slot + 2) % 3]; };
  // partner[3t + i]: triangle across side i of t (-1: boundary, -2: unusable side).
  std::vector<int32_t> partner(3 * triangles.size(), -2), partner_slot(3 * triangles.size(), -1);
  bool topology_ok = true;
  for (std::size_t lo = 0, hi; lo < edges.size(); lo = hi) {
    for (hi = lo + 1; hi < edges.size() && edges[hi].key == edges[lo].key;)
      ++hi;
    const EdgeRecord &e = edges[lo];
    if (hi - lo > 2) {
      if (local)
        report.fail("edge " + std::to_string(from_of(e)) + "-" + std::to_string(to_of(e)) +
                    " is in " + std::to_string(hi - lo) + " triangles");
      topology_ok = false;
    } else if (hi - lo == 2) {
      const EdgeRecord &f = edges[lo + 1];
      if (from_of(e) != to_of(f)) {
        if (local)
          report.fail("edge " + std::to_string(from_of(e)) + "-" + std::to_string(to_of(e)) +
                      " has the same direction in two triangles (overlap)");
        topology_ok = false;
        continue;
      }
      pair_sides(partner, partner_slot, e, f);
    } else {
      partner[3 * e.tri + e.slot] = -1;
    }
  }
  if (local) {
    if (neighbors.size() != triangles.size())
      report.fail("neighbors has " + std::to_string(neighbors.size()) + " entries for " +
                  std::to_string(nt) + " triangles");
    else
      for (int32_t t = 0; t < nt; ++t)
        for (int32_t i = 0; valid[t] && i < 3; ++i)
          if (partner[3 * t + i] != -2 && neighbors[t][i] != partner[3 * t + i])
            report.fail(triangle_text(triangles, t) + ": neighbour " + std::to_string(i) + " is " +
                        std::to_string(neighbors[t][i]) + ", the triangle across that edge is " +
                        std::to_string(partner[3 * t + i]));
  }

  // --- Vertex fans turn at most once (local mode) -------------------------------------------
  // Around vertex v the triangle (v, a, b) turns counter-clockwise from direction a to b by
  // less than a half turn; the next triangle around v is the one across edge v-b.  Relative to
  // the first direction d0 of the fan, a direction is in the "upper" half [0, pi) or the
  // "lower" half [pi, 2 pi); a step from lower to upper passes 2 pi, a full turn.
  if (local && topology_ok) {
    std::vector<char> seen(3 * triangles.size(), 0);
    int64_t bad_fans = 0;
    for (int32_t t0 = 0; t0 < nt; ++t0) {
      for (int32_t i0 = 0; valid[t0] && i0 < 3; ++i0) {
        if (seen[3 * t0 + i0])
          continue;
        const int32_t v = triangles[t0][i0];
        // Rewind clockwise to the start of an open fan (or once around a closed one).
        int32_t t = t0, i = i0;
        bool closed = false;
        for (int64_t steps = 0;; ++steps) {
          const int32_t u = partner[3 * t + (i + 2) % 3]; // across edge v-a
          if (u < 0 || steps > nt) // boundary (or an unusable side) starts the fan
            break;
          const int32_t s = partner_slot[3 * t + (i + 2) % 3];
          // In u, v is the vertex after the shared edge's far end: the slot s is opposite the
          // edge a-v, so v is at (s + 1) % 3 or (s + 2) % 3.
          const int32_t j = triangles[u][(s + 1) % 3] == v ? (s + 1) % 3 : (s + 2) % 3;
          t = u, i = j;
          if (t == t0 && i == i0) {
            closed = true;
            break;
          }
        }
        const int32_t d0 = triangles[t][(i + 1) % 3];
        auto upper = [&](int32_t w) {
          const int o = orient(points, v, d0, w);
          if (o != 0)
            return o > 0;
          const Point &pv = points[v], &pd = points[d0], &pw = points[w];
          return sgn(pw.x, pv.x) == sgn(pd.x, pv.x) && sgn(pw.y, pv.y) == sgn(pd.y, pv.y);
        };
        int64_t turns = 0;
        const int32_t start_t = t, start_i = i;
        for (int64_t steps = 0; steps <= nt; ++steps) {
          seen[3 * t + i] = 1;
          const int32_t a = triangles[t][(i + 1) % 3], b = triangles[t][(i + 2) % 3];
          if (!upper(a) && upper(b))
            ++turns;
          const int32_t u = partner[3 * t + (i + 1) % 3]; // across edge v-b
          if (u < 0)
            break;
          const int32_t s = partner_slot[3 * t + (i + 1) % 3];
          const int32_t j = triangles[u][(s + 1) % 3] == v ? (s + 1) % 3 : (s + 2) % 3;
          t = u, i = j;
          if (t == start_t && i == start_i)
            break;
        }
        if (turns != (closed ? 1 : 0) && bad_fans++ < 5)
          report.fail("the triangles around vertex " + point_text(points, v) + " turn " +
                      std::to_string(turns) + " times (" + (closed ? "closed" : "open") +
                      " fan): they overlap");
      }
    }
    if (bad_fans > 5)
      report.fail(std::to_string(bad_fans) + " vertex fans in all overlap");
  }

  // --- Segments -------------------------------------------------------------------------------
  // Mesh adjacency (CSR) over the edges of the valid triangles.
  std::vector<int32_t> first(points.size() + 1, 0), adjacent;
  for (const EdgeRecord &e : edges)
    ++first[from_of(e) + 1], ++first[to_of(e) + 1];
  for (std::size_t k = 1; k < first.size(); ++k)
    first[k] += first[k - 1];
  adjacent.resize(first.back());
  {
    std::vector<int32_t> fill(first.begin(), first.end() - 1);
    for (const EdgeRecord &e : edges) {
      adjacent[fill[from_of(e)]++] = to_of(e);
      adjacent[fill[to_of(e)]++] = from_of(e);
    }
  }
  // Points from first_added on are rounded crossings (and with
  // crossings_at_vertices some crossings are vertices that were there):
  // segments split at them are followed within rounding too.
  const bool rounded = first_added < n || crossings_at_vertices;
  std::vector<int32_t> sorted; // for the search of points on a segment that left the mesh
  std::unordered_set<uint64_t> segment_edges, seen_segments;
  int64_t missing = 0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const int32_t ia = segments[k].a, ib = segments[k].b;
    if (ia < 0 || ia >= n || ib < 0 || ib >= n) {
      report.fail("segment " + std::to_string(k) + " (" + std::to_string(ia) + ", " +
                  std::to_string(ib) + "): endpoint out of range");
      continue;
    }
    const int32_t a = representative(ia), b = representative(ib);
    if (a == b || !seen_segments.insert(edge_key(a, b)).second)
      continue; // zero length or repeated
    const Point &pb = points[b];
    // The mesh neighbours of c that continue the segment towards b, the
    // likeliest first: exactly on it (ordered lexicographically, and ahead of
    // c, which may be a rounded crossing a hair off the segment), nearest
    // first; then, in a mesh with rounded crossings, points within rounding
    // of it (crossings before vertices that were there, unless crossings
    // rounded onto such vertices), ordered by their offset along the segment
    // (the rounding may break the lexicographic order on a nearly vertical
    // or horizontal one).
    auto continuations = [&](int32_t c) {
      std::vector<int32_t> exact, crossings, others;
      for (int32_t q = first[c]; q < first[c + 1]; ++q) {
        const int32_t w = adjacent[q];
        if (orient(points, a, b, w) == 0 && between_on_segment(points[c], points[w], pb) &&
            ahead_along(points[a], pb, points[c], points[w]))
          exact.push_back(w);
        else if (rounded && within_rounding_of(points[a], pb, points[w]) &&
                 ahead_along(points[a], pb, points[c], points[w]) &&
                 !ahead_along(points[a], pb, pb, points[w]))
          (w >= first_added || crossings_at_vertices ? crossings : others).push_back(w);
      }
      std::sort(exact.begin(), exact.end(), [&](int32_t u, int32_t w) {
        return between_on_segment(points[c], points[u], points[w]) && u != w;
      });
      for (std::vector<int32_t> *list : {&crossings, &others})
        std::sort(list->begin(), list->end(), [&](int32_t u, int32_t w) {
          return ahead_along(points[a], pb, points[u], points[w]);
        });
      exact.insert(exact.end(), crossings.begin(), crossings.end());
      exact.insert(exact.end(), others.begin(), others.end());
      return exact;
    };
    // Where the segment leaves the mesh at c (not in whole_hull mode): the
    // next point lying on it, where it comes back.
    auto resumption = [&](int32_t c) {
      if (sorted.empty()) {
        for (int32_t p = 0; p < n; ++p)
          if (representative(p) == p)
            sorted.push_back(p);
        std::sort(sorted.begin(), sorted.end(),
                  [&](int32_t p, int32_t q) { return lex_less(points[p], points[q]); });
      }
      const bool forward = lex_less(points[c], pb);
      // b, or a point ahead of c exactly on the segment or (a rounded
      // crossing) within rounding of it.
      auto on_line = [&](int32_t p) {
        return p == b || ((orient(points, a, b, p) == 0 ||
                           (rounded && within_rounding_of(points[a], pb, points[p]))) &&
                          ahead_along(points[a], pb, points[c], points[p]));
      };
      auto by_point = [&](int32_t p, const Point &q) { return lex_less(points[p], q); };
      auto point_by = [&](const Point &q, int32_t p) { return lex_less(q, points[p]); };
      int32_t next = -1;
      if (forward) {
        auto it = std::upper_bound(sorted.begin(), sorted.end(), points[c], point_by);
        for (; it != sorted.end() && next < 0; ++it)
          if (on_line(*it))
            next = *it;
      } else {
        auto it = std::lower_bound(sorted.begin(), sorted.end(), points[c], by_point);
        while (it != sorted.begin() && next < 0) {
          --it;
          if (on_line(*it))
            next = *it;
        }
      }
      // Rounding may put a point ahead along a nearly vertical or horizontal
      // segment behind c in the lexicographic order: the nearest ahead of all.
      if (rounded && next >= 0)
        for (const int32_t p : sorted)
          if (p != c && within_rounding_of(points[a], pb, points[p]) &&
              ahead_along(points[a], pb, points[c], points[p]) &&
              ahead_along(points[a], pb, points[p], points[next]))
            next = p;
      return next; // b itself is always a candidate
    };
    // A depth-first search from a to b over those steps, the likeliest
    // first: nearly collinear pieces that overlap (a hair apart) can offer a
    // step that leads nowhere. A point found to lead nowhere is not tried
    // again; more steps than four per point means the rounding turned the
    // walk around.
    struct Step {
      int32_t at;
      std::vector<int32_t> next; // the mesh's steps left to try from `at`
      bool resumed;              // `at` was reached by a resumption, not a mesh edge
      bool may_resume;           // a resumption from `at` is still to try
    };
    std::vector<Step> path{{a, continuations(a), false, !whole_hull}};
    std::unordered_set<int32_t> dead;
    int64_t steps = 0;
    int32_t deepest = a; // where the longest attempt stopped, for the message
    std::size_t longest = 1;
    bool found = false, endless = false;
    while (!path.empty()) {
      Step &top = path.back();
      if (top.at == b) {
        found = true;
        break;
      }
      if (++steps > 4 * n + 16) {
        endless = true;
        break;
      }
      int32_t next = -1;
      while (!top.next.empty() && next < 0) {
        next = top.next.front();
        top.next.erase(top.next.begin());
        if (dead.count(next))
          next = -1;
      }
      bool resumed = false;
      if (next < 0 && top.may_resume) {
        top.may_resume = false;
        next = resumption(top.at);
        resumed = next >= 0 && !dead.count(next);
        if (!resumed)
          next = -1;
      }
      if (next < 0) {
        dead.insert(top.at);
        path.pop_back();
        continue;
      }
      path.push_back({next, continuations(next), resumed, !whole_hull});
      if (path.size() > longest) {
        longest = path.size();
        deepest = next;
      }
    }
    if (found) {
      for (std::size_t i = 1; i < path.size(); ++i)
        if (!path[i].resumed)
          segment_edges.insert(edge_key(path[i - 1].at, path[i].at));
      continue;
    }
    if (endless) {
      report.fail("segment " + std::to_string(k) + " (" + point_text(points, ia) + ", " +
                  point_text(points, ib) + "): the walk along it does not end");
      continue;
    }
    if (missing++ < 5)
      report.fail("segment " + std::to_string(k) + " (" + point_text(points, ia) + ", " +
                  point_text(points, ib) + ") is missing: no mesh edge along it from " +
                  point_text(points, deepest));
  }
  if (missing > 5)
    report.fail(std::to_string(missing) + " segments in all are missing");

  // --- Boundary edges are segments (local mode); other edges locally Delaunay ----------------
  // In a mesh with rounded crossings, pieces of segments that overlap a hair
  // from collinear can make several chains along one segment, of which the
  // walk above followed one: an edge the walks left out is still a segment's
  // when both its ends lie on one within rounding, inside its extent.
  auto along_a_segment = [&](int32_t p, int32_t q) {
    if (!rounded)
      return false;
    for (const Segment &segment : segments) {
      if (segment.a < 0 || segment.a >= n || segment.b < 0 || segment.b >= n)
        continue;
      const Point &sa = points[representative(segment.a)], &sb = points[representative(segment.b)];
      auto on = [&](const Point &w) {
        return within_rounding_of(sa, sb, w) && !ahead_along(sa, sb, w, sa) &&
               !ahead_along(sa, sb, sb, w);
      };
      if (on(points[p]) && on(points[q]))
        return true;
    }
    return false;
  };
  int64_t bad_boundary = 0, bad_delaunay = 0;
  for (int32_t t = 0; t < nt; ++t) {
    if (!valid[t])
      continue;
    const Triangle &v = triangles[t];
    for (int32_t i = 0; i < 3; ++i) {
      const int32_t p = v[(i + 1) % 3], q = v[(i + 2) % 3];
      const int32_t u = partner[3 * t + i];
      const bool is_segment = segment_edges.count(edge_key(p, q)) != 0;
      if (u == -1 && local && !is_segment && !along_a_segment(p, q) && bad_boundary++ < 5)
        report.fail("boundary edge " + std::to_string(p) + "-" + std::to_string(q) + " of " +
                    triangle_text(triangles, t) + " is not part of a segment");
      if (u < t || is_segment) // boundary, unusable, checked from u, or constrained
        continue;
      const int32_t d = triangles[u][partner_slot[3 * t + i]];
      const Point &pa = points[v[0]], &pb = points[v[1]], &pc = points[v[2]], &pd = points[d];
      if (clm_incircle_sos(pa.x, pa.y, pb.x, pb.y, pc.x, pc.y, pd.x, pd.y) != -1 &&
          !along_a_segment(p, q) && bad_delaunay++ < 5)
        report.fail("edge " + std::to_string(p) + "-" + std::to_string(q) +
                    " is not a segment and not locally Delaunay: point " + point_text(points, d) +
                    " is inside the circumcircle of " + triangle_text(triangles, t));
    }
  }
  if (bad_boundary > 5)
    report.fail(std::to_string(bad_boundary) + " boundary edges in all are not segments");
  if (bad_delaunay > 5)
    report.fail(std::to_string(bad_delaunay) + " edges in all are not locally Delaunay");
  return report;
}

} // namespace clmesh
