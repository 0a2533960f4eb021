// clmesh — GPU-CDT constraint insertion (thesis chapter 4, §4.3, Algorithms
// 4.1 and 4.2).
//
// Outer loop: one work-item per constraint a-b finds, in the triangle fan of
// a, the triangle the constraint leaves a through, then walks along it to b
// and marks every triangle it crosses with atomic minimum of its index. (The
// device index is the constraint's priority: the host numbers constraints in
// a scrambled order so that neighbouring input segments do not wait for one
// another; the walks still run in input order, walk_order, for locality.) A
// vertex lying exactly on the constraint, or a crossed edge that is itself a
// constraint, is reported to the host (split the constraint there / refuse
// crossing constraints). Inner loop: one work-item per marked triangle A
// classifies the pair (A, C) with C the next triangle along its constraint
// (zero, single, double intersection or concave), decides whether it may
// flip (case 1: zero or single; case 2: double after a double, when B, A, C
// form a convex polygon; case 3: double after a concave pair that the flip
// makes convex, B being the previous triangle), marks A, C (and B) with atomic
// minimum of a key weighted by the case, and flips the pairs that kept every
// mark. New triangles are re-marked if the constraint still crosses them.
#include "common.h"

#define CLM_SEGMENT_PENDING 0
#define CLM_SEGMENT_PRESENT 1
#define CLM_SEGMENT_SPLIT 2 // a vertex lies on the segment: split_vertex
#define CLM_SEGMENT_CROSSING                                                                       \
  3                        // crosses constraint edge split_vertex-crossed_vertex
                           // of triangle crossed_triangle
#define CLM_SEGMENT_LOST 4 // walk failed (a bug)

#define CLM_NO_CONSTRAINT 0x7fffffff

#define CLM_PAIR_ZERO 1
#define CLM_PAIR_SINGLE 2
#define CLM_PAIR_DOUBLE 3
#define CLM_PAIR_CONCAVE 4

// Segment endpoints that are duplicate points stand for their kept point.
__kernel void resolve_duplicate_endpoints(__global const int *duplicate_of, __global int *segment_a,
                                          __global int *segment_b, const int m) {
  const int s = get_global_id(0);
  if (s >= m)
    return;
  if (duplicate_of[segment_a[s]] >= 0)
    segment_a[s] = duplicate_of[segment_a[s]];
  if (duplicate_of[segment_b[s]] >= 0)
    segment_b[s] = duplicate_of[segment_b[s]];
}

// One incident triangle per vertex (thesis §2.2), refreshed before marking.
__kernel void record_vertex_triangles(__global const int *tri_vertex, __global int *vertex_triangle,
                                      const int n) {
  const int t = get_global_id(0);
  if (t >= n)
    return;
  for (int i = 0; i < 3; ++i)
    if (tri_vertex[3 * t + i] < 0)
      return;
  for (int i = 0; i < 3; ++i)
    vertex_triangle[tri_vertex[3 * t + i]] = t; // any incident triangle will do
}

// Is v, collinear with a-b, on the side of b (so strictly between a and b)?
inline bool ahead(__global const double2 *points, int a, int b, int v) {
  const double2 pa = points[a], pb = points[b], pv = points[v];
  return (pv.x - pa.x) * (pb.x - pa.x) + (pv.y - pa.y) * (pb.y - pa.y) > 0;
}

// Walks constraint s (see the header) and marks the triangles it crosses;
// returns how many it marked. *pending: set when s is not yet in the mesh
// and can be walked; *report: set when the host must look at its state.
inline int mark_constraint(__global const double2 *points, __global const int *tri_vertex,
                           __global const int *tri_neighbor, __global const int *vertex_triangle,
                           __global const int *constraint_start,
                           __global const int *constraint_adjacent, int a, int b, int s,
                           __global int *segment_state, __global int *split_vertex,
                           __global int *crossed_vertex, __global int *crossed_triangle,
                           volatile __global int *constraint_mark, int max_steps, int *pending,
                           int *report) {
  // The triangle of a's fan whose cone holds the direction a -> b.
  const int first = vertex_triangle[a];
  int t = first, k = index_in(tri_vertex, t, a), exit_triangle = -1;
  for (int step = 0; step < max_steps; ++step) {
    const int x = tri_vertex[3 * t + next3(k)], y = tri_vertex[3 * t + prev3(k)];
    if (x == b || y == b) {
      segment_state[s] = CLM_SEGMENT_PRESENT;
      return 0;
    }
    // A fan vertex on a-b splits the segment there (y is checked too: the
    // next triangle of the fan may be a ghost).
    const int ox = x >= 0 ? orient_vertices(points, a, x, b) : 0;
    const int oy = y >= 0 ? orient_vertices(points, a, y, b) : 0;
    const int on_segment = (x >= 0 && ox == 0 && ahead(points, a, b, x))   ? x
                           : (y >= 0 && oy == 0 && ahead(points, a, b, y)) ? y
                                                                           : -1;
    if (on_segment >= 0) {
      segment_state[s] = CLM_SEGMENT_SPLIT;
      split_vertex[s] = on_segment;
      *report = 1;
      return 0;
    }
    if (x >= 0 && y >= 0 && ox > 0 && oy < 0) {
      exit_triangle = t;
      break;
    }
    t = link_triangle(tri_neighbor[3 * t + next3(k)]); // counter-clockwise around a
    k = index_in(tri_vertex, t, a);
    if (t == first)
      break;
  }
  if (exit_triangle < 0) {
    segment_state[s] = CLM_SEGMENT_LOST;
    *report = 1;
    return 0;
  }
  *pending = 1;
  // Walk along a-b, crossing edge e of t each step.
  t = exit_triangle;
  int e = k;
  for (int step = 0; step < max_steps; ++step) {
    atomic_min(&constraint_mark[t], s);
    const int p = tri_vertex[3 * t + next3(e)], q = tri_vertex[3 * t + prev3(e)];
    if (is_constraint(constraint_start, constraint_adjacent, p, q)) {
      segment_state[s] = CLM_SEGMENT_CROSSING;
      split_vertex[s] = p;
      crossed_vertex[s] = q;
      crossed_triangle[s] = t;
      *report = 1;
      return step + 1;
    }
    const int link = tri_neighbor[3 * t + e];
    const int u = link_triangle(link), j = link_edge(link);
    const int z = tri_vertex[3 * u + j];
    if (z == b) {
      atomic_min(&constraint_mark[u], s);
      return step + 2;
    }
    const int oz = orient_vertices(points, a, b, z);
    if (oz == 0) {
      segment_state[s] = CLM_SEGMENT_SPLIT; // z lies on a-b
      split_vertex[s] = z;
      *report = 1;
      return step + 1;
    }
    // u = (z, q, p): leave through z-q (opposite p) when z is on p's side.
    e = oz == orient_vertices(points, a, b, p) ? prev3(j) : next3(j);
    t = u;
  }
  segment_state[s] = CLM_SEGMENT_LOST;
  *report = 1;
  return max_steps;
}

__kernel void mark_constraint_triangles(
    __global const double2 *points, __global const int *tri_vertex,
    __global const int *tri_neighbor, __global const int *vertex_triangle,
    __global const int *constraint_start, __global const int *constraint_adjacent,
    __global const int *walk_order, __global const int *segment_a, __global const int *segment_b,
    __global int *segment_state, __global int *split_vertex, __global int *crossed_vertex,
    __global int *crossed_triangle, volatile __global int *constraint_mark,
    volatile __global int *counters, const int max_steps, const int m) {
  // counters[0]: segments still pending, [1]: constraint-triangle intersections,
  // [2]: segments to split, crossing another, or lost (read back only then)
  const int gid = get_global_id(0), s = gid < m ? walk_order[gid] : -1;
  int pending = 0, report = 0, crossings = 0;
  if (s >= 0 && segment_state[s] != CLM_SEGMENT_PRESENT)
    crossings = mark_constraint(points, tri_vertex, tri_neighbor, vertex_triangle, constraint_start,
                                constraint_adjacent, segment_a[s], segment_b[s], s, segment_state,
                                split_vertex, crossed_vertex, crossed_triangle, constraint_mark,
                                max_steps, &pending, &report);
  volatile __local int scratch[2];
  reserve_in_group(pending, scratch, &counters[0]);
  reserve_in_group(crossings, scratch, &counters[1]);
  reserve_in_group(report, scratch, &counters[2]);
}

// Does the open segment a-b cross the interior of triangle t?
inline bool segment_crosses(__global const double2 *points, __global const int *tri_vertex, int t,
                            int a, int b) {
  int v[3];
  for (int i = 0; i < 3; ++i)
    v[i] = tri_vertex[3 * t + i];
  for (int i = 0; i < 3; ++i) {
    if (v[i] == a || v[i] == b) {
      const int from = v[i], to = v[i] == a ? b : a;
      if (v[next3(i)] == to || v[prev3(i)] == to)
        return false; // a-b is an edge of t
      return orient_vertices(points, from, v[next3(i)], to) > 0 &&
             orient_vertices(points, from, v[prev3(i)], to) < 0;
    }
  }
  for (int i = 0; i < 3; ++i) {
    const int p = v[next3(i)], q = v[prev3(i)];
    if (orient_vertices(points, a, b, p) * orient_vertices(points, a, b, q) < 0 &&
        orient_vertices(points, p, q, a) * orient_vertices(points, p, q, b) < 0)
      return true;
  }
  return false;
}

// The edges of marked triangle t where its constraint a-b enters (towards a)
// and leaves (towards b); -1 where t holds that endpoint. Away from a and b,
// one vertex k of t is alone on its side of a-b (no vertex lies on a-b: those
// split the constraint), and t being counter-clockwise, the constraint leaves
// through the edge opposite k+1 when k is on its left, opposite k+2 otherwise.
inline void crossing_edges(__global const double2 *points, __global const int *tri_vertex, int t,
                           int a, int b, int *entry, int *exit) {
  int side[3];
  *entry = -1;
  *exit = -1;
  for (int i = 0; i < 3; ++i) {
    const int v = tri_vertex[3 * t + i];
    if (v == a)
      *exit = i;
    else if (v == b)
      *entry = i;
    else
      side[i] = orient_vertices(points, a, b, v);
  }
  if (*exit >= 0 || *entry >= 0)
    return;
  const int k = side[0] == side[1] ? 2 : (side[0] == side[2] ? 1 : 0);
  *exit = side[k] > 0 ? next3(k) : prev3(k);
  *entry = side[k] > 0 ? prev3(k) : next3(k);
}

// Configuration of the pair sharing edge p-q (crossed by a-b), with apexes x
// (first triangle) and y (second), if p-q were flipped to x-y.
inline int pair_configuration(__global const double2 *points, int p, int q, int x, int y, int a,
                              int b) {
  if (orient_vertices(points, x, y, p) * orient_vertices(points, x, y, q) >= 0)
    return CLM_PAIR_CONCAVE;
  if ((x == a && y == b) || (x == b && y == a))
    return CLM_PAIR_ZERO;
  if (x != a && x != b && y != a && y != b &&
      orient_vertices(points, a, b, x) * orient_vertices(points, a, b, y) < 0 &&
      orient_vertices(points, x, y, a) * orient_vertices(points, x, y, b) < 0)
    return CLM_PAIR_DOUBLE;
  return CLM_PAIR_SINGLE;
}

inline int apex_across(__global const int *tri_vertex, __global const int *tri_neighbor, int t,
                       int e) {
  const int link = tri_neighbor[3 * t + e];
  return tri_vertex[3 * link_triangle(link) + link_edge(link)];
}

// Decides each active triangle A's flip and marks the triangles it involves:
// plan[gid] = A's exit edge | (case << 2), -1 for none; next[gid] = C;
// previous[gid] = B for cases 2 and 3, else -1.
__kernel void plan_constraint_flips(__global const int *active, __global const double2 *points,
                                    __global const int *tri_vertex,
                                    __global const int *tri_neighbor,
                                    __global const int *constraint_mark,
                                    __global const int *segment_a, __global const int *segment_b,
                                    volatile __global uint *tri_mark, __global int *plan,
                                    __global int *next, __global int *previous, const int n) {
  const int gid = get_global_id(0);
  if (gid >= n)
    return;
  plan[gid] = -1;
  const int A = active[gid], s = constraint_mark[A];
  if (s == CLM_NO_CONSTRAINT)
    return;
  const int a = segment_a[s], b = segment_b[s];
  int entry, exit;
  crossing_edges(points, tri_vertex, A, a, b, &entry, &exit);
  if (exit < 0)
    return;
  const int C = link_triangle(tri_neighbor[3 * A + exit]);
  if (constraint_mark[C] != s)
    return;
  const int p = tri_vertex[3 * A + next3(exit)], q = tri_vertex[3 * A + prev3(exit)];
  const int x = tri_vertex[3 * A + exit], y = apex_across(tri_vertex, tri_neighbor, A, exit);
  const int ac = pair_configuration(points, p, q, x, y, a, b);
  int rank = -1, B = -1;
  if (ac == CLM_PAIR_ZERO || ac == CLM_PAIR_SINGLE) {
    rank = 0; // case 1
  } else if (ac == CLM_PAIR_DOUBLE && entry >= 0) {
    B = link_triangle(tri_neighbor[3 * A + entry]);
    if (constraint_mark[B] == s) {
      // The pair (B, A) now, and (B, A') once (A, C) is flipped: the entry
      // edge r-w stays, A's apex across it becomes y.
      const int r = tri_vertex[3 * A + next3(entry)], w = tri_vertex[3 * A + prev3(entry)];
      const int bx = apex_across(tri_vertex, tri_neighbor, A, entry);
      const int before = pair_configuration(points, w, r, bx, tri_vertex[3 * A + entry], a, b);
      const int after = pair_configuration(points, w, r, bx, y, a, b);
      if (before == CLM_PAIR_DOUBLE && (after == CLM_PAIR_SINGLE || after == CLM_PAIR_ZERO))
        rank = 1; // case 2
      else if (before == CLM_PAIR_CONCAVE && after != CLM_PAIR_CONCAVE)
        rank = 2; // case 3
    }
  }
  if (rank < 0)
    return;
  const uint key = ((uint)rank << 29) | (uint)A;
  atomic_min(&tri_mark[A], key);
  atomic_min(&tri_mark[C], key);
  if (rank > 0)
    atomic_min(&tri_mark[B], key);
  plan[gid] = exit | (rank << 2);
  next[gid] = C;
  previous[gid] = rank > 0 ? B : -1;
}

// Flips the planned pairs that kept every mark (A and C, and B for cases 2, 3).
__kernel void apply_constraint_flips(__global const int *active, __global const int *plan,
                                     __global const int *next, __global const int *previous,
                                     __global const uint *tri_mark, __global int *tri_vertex,
                                     __global int *tri_neighbor, __global int *modified_stamp,
                                     __global int *children, __global int *flipped,
                                     volatile __global int *flip_count, const int stamp,
                                     const int n) {
  const int gid = get_global_id(0);
  int flips = 0;
  if (gid < n) {
    const int pl = plan[gid];
    if (pl >= 0) {
      const int A = active[gid], exit = pl & 3, rank = pl >> 2;
      const uint key = ((uint)rank << 29) | (uint)A;
      if (tri_mark[A] == key && tri_mark[next[gid]] == key &&
          (previous[gid] < 0 || tri_mark[previous[gid]] == key)) {
        flip_edge(tri_vertex, tri_neighbor, modified_stamp, children, A, exit, stamp);
        flips = 1;
      }
    }
    flipped[gid] = flips;
  }
  volatile __local int scratch[2];
  reserve_in_group(flips, scratch, flip_count);
}

// Second step of the flips, and the marks of the new triangles.
__kernel void relink_constraint_flips(__global const int *active, __global const int *next,
                                      __global const int *flipped, __global const int *tri_vertex,
                                      __global int *tri_neighbor,
                                      __global const int *modified_stamp,
                                      __global const int *children, const int stamp, const int n) {
  const int gid = get_global_id(0);
  if (gid >= n || !flipped[gid])
    return;
  const int A = active[gid], C = next[gid];
  for (int e = 1; e < 3; ++e) {
    relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, A, e);
    relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, C, e);
  }
}

// Clears this iteration's marks and re-marks the flipped triangles.
__kernel void remark_after_flips(__global const int *active, __global const int *plan,
                                 __global const int *next, __global const int *previous,
                                 __global const int *flipped, __global const double2 *points,
                                 __global const int *tri_vertex, __global int *constraint_mark,
                                 __global uint *tri_mark, __global const int *segment_a,
                                 __global const int *segment_b, const int n) {
  const int gid = get_global_id(0);
  if (gid >= n || plan[gid] < 0)
    return;
  const int A = active[gid], C = next[gid];
  tri_mark[A] = CLM_NO_MARK;
  tri_mark[C] = CLM_NO_MARK;
  if (previous[gid] >= 0)
    tri_mark[previous[gid]] = CLM_NO_MARK;
  if (flipped[gid]) {
    const int s = constraint_mark[A];
    const int a = segment_a[s], b = segment_b[s];
    constraint_mark[A] = segment_crosses(points, tri_vertex, A, a, b) ? s : CLM_NO_CONSTRAINT;
    constraint_mark[C] = segment_crosses(points, tri_vertex, C, a, b) ? s : CLM_NO_CONSTRAINT;
  }
}

// The triangles to classify again in the next inner iteration: only a flip
// can change a pair's configuration, so those are both triangles of each flip
// and their neighbours (their next or previous triangle changed), plus the
// flips that lost a mark. Each enters once (dirty_stamp holds the iteration).
inline void add_dirty(__global const int *constraint_mark, volatile __global int *dirty_stamp,
                      int *found, int *count, int t, int stamp) {
  if (constraint_mark[t] != CLM_NO_CONSTRAINT && atomic_xchg(&dirty_stamp[t], stamp) != stamp)
    found[(*count)++] = t;
}

__kernel void collect_dirty(__global const int *active, __global const int *plan,
                            __global const int *next, __global const int *flipped,
                            __global const int *tri_neighbor, __global const int *constraint_mark,
                            volatile __global int *dirty_stamp, __global int *dirty,
                            volatile __global int *dirty_count, const int stamp, const int n) {
  const int gid = get_global_id(0);
  int found[8], count = 0;
  if (gid < n && plan[gid] >= 0) {
    const int A = active[gid];
    if (!flipped[gid]) {
      add_dirty(constraint_mark, dirty_stamp, found, &count, A, stamp);
    } else {
      const int pair[2] = {A, next[gid]};
      for (int k = 0; k < 2; ++k) {
        add_dirty(constraint_mark, dirty_stamp, found, &count, pair[k], stamp);
        for (int e = 0; e < 3; ++e)
          add_dirty(constraint_mark, dirty_stamp, found, &count,
                    link_triangle(tri_neighbor[3 * pair[k] + e]), stamp);
      }
    }
  }
  volatile __local int scratch[2];
  append_in_group(found, count, dirty, dirty_count, scratch);
}

// Full sweep after the outer loop's marking: every marked slot.
__kernel void flag_marked(__global const int *constraint_mark, __global int *keep, const int n) {
  const int t = get_global_id(0);
  if (t < n)
    keep[t] = constraint_mark[t] != CLM_NO_CONSTRAINT;
}
