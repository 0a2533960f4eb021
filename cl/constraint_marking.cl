// clmesh — GPU-CDT constraint insertion (thesis chapter 4, §4.3, Algorithms
// 4.1 and 4.2).
//
// Outer loop: one work-item per constraint a-b finds, in the triangle fan of
// a, the triangle the constraint leaves a through, then walks along it to b
// and marks every triangle it crosses with atomic minimum of its index (with
// the edges it enters and leaves through in the low bits). (The device index
// is the constraint's priority: the host numbers constraints in a scrambled
// order so that neighbouring input segments do not wait for one another; the
// walks run in walk_order, along the Hilbert curve of their first endpoints,
// for locality.) A vertex lying
// exactly on the constraint, or a crossed edge that is itself a constraint,
// is reported to the host (split the constraint there / split both at their
// crossing). Inner loop: the thesis's flips, classified as it does: the pair
// (A, C), C the next triangle along A's constraint, is zero, single, double
// intersection or concave, and may flip in case 1 (zero or single), case 2
// (double after a double, when B, A, C form a convex polygon) or case 3
// (double after a concave pair that the flip makes convex), B being the
// previous triangle. The thesis gives every triangle a work-item and resolves
// conflicts by marking A, C and B with atomic minimum; here the marked
// triangles are cut into runs (consecutive triangles with the same mark), one
// work-item flips along each run, and the links between runs are mended in a
// second step (see find_run_starts). A constraint of smallest index owns all
// the triangles it crosses, so each outer iteration inserts it (thesis Claim
// 4.4.1) and the loop ends; every flip is one of the thesis's cases, so the
// flips inside a run end too (Claim 4.4.2).
#include "common.h"
#include "mesh_params.h"

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
static inline bool ahead(__global const double2 *points, int a, int b, int v) {
  const double2 pa = points[a], pb = points[b], pv = points[v];
  return (pv.x - pa.x) * (pb.x - pa.x) + (pv.y - pa.y) * (pb.y - pa.y) > 0;
}

// A triangle's mark: the constraint crossing it with the smallest index s,
// and the edges s enters and leaves it through (CLM_NO_EDGE at a and b).
#define CLM_NO_EDGE 3
static inline int mark_of(int s, int entry, int exit) { return (s << 4) | (entry << 2) | exit; }
static inline int mark_constraint_index(int mark) { return mark >> 4; }
static inline int mark_entry(int mark) { return (mark >> 2) & 3; }
static inline int mark_exit(int mark) { return mark & 3; }

// Where constraint a-b leaves a: the triangle t of a's fan whose edge k
// opposite a it crosses (CLM_FAN_EXIT), or b is a neighbour of a
// (CLM_FAN_PRESENT), or a fan vertex *on lies on a-b (CLM_FAN_ON_SEGMENT; y is
// checked too: the next triangle of the fan may be a ghost), or none was found
// (CLM_FAN_LOST, a bug).
#define CLM_FAN_EXIT 0
#define CLM_FAN_PRESENT 1
#define CLM_FAN_ON_SEGMENT 2
#define CLM_FAN_LOST 3

static inline int leave_endpoint(__global const double2 *points, __global const int *tri_vertex,
                                 __global const int *tri_neighbor,
                                 __global const int *vertex_triangle, int a, int b, int max_steps,
                                 int *t_out, int *k_out, int *on) {
  const int first = vertex_triangle[a];
  int t = first, k = index_in(tri_vertex, t, a);
  for (int step = 0; step < max_steps; ++step) {
    const int x = tri_vertex[3 * t + next3(k)], y = tri_vertex[3 * t + prev3(k)];
    if (x == b || y == b)
      return CLM_FAN_PRESENT;
    const int ox = x >= 0 ? orient_vertices(points, a, x, b) : 0;
    const int oy = y >= 0 ? orient_vertices(points, a, y, b) : 0;
    *on = (x >= 0 && ox == 0 && ahead(points, a, b, x))   ? x
          : (y >= 0 && oy == 0 && ahead(points, a, b, y)) ? y
                                                          : -1;
    if (*on >= 0)
      return CLM_FAN_ON_SEGMENT;
    if (x >= 0 && y >= 0 && ox > 0 && oy < 0) {
      *t_out = t;
      *k_out = k;
      return CLM_FAN_EXIT;
    }
    t = link_triangle(tri_neighbor[3 * t + next3(k)]); // counter-clockwise around a
    k = index_in(tri_vertex, t, a);
    if (t == first)
      break;
  }
  return CLM_FAN_LOST;
}

// One step of the walk along a-b: from triangle *t, whose edge *e a-b
// crosses, into the triangle u beyond it, entered through its edge *entry.
// Returns 1 when u holds b (*t = u), -1 when u's third vertex *on lies on
// a-b, else 0 with *t = u and *e the edge a-b leaves u through.
static inline int walk_step(__global const double2 *points, __global const int *tri_vertex,
                            __global const int *tri_neighbor, int a, int b, int *t, int *e,
                            int *entry, int *on) {
  const int link = tri_neighbor[3 * *t + *e];
  const int u = link_triangle(link), j = link_edge(link);
  const int z = tri_vertex[3 * u + j];
  *entry = j;
  if (z == b) {
    *t = u;
    return 1;
  }
  const int oz = orient_vertices(points, a, b, z);
  if (oz == 0) {
    *on = z;
    return -1;
  }
  // u = (z, q, p): leave through z-q (opposite p) when z is on p's side.
  const int p = tri_vertex[3 * *t + next3(*e)];
  *e = oz == orient_vertices(points, a, b, p) ? prev3(j) : next3(j);
  *t = u;
  return 0;
}

// Walks constraint s (see the header) and marks the triangles it crosses;
// returns how many it marked. *pending: set when s is not yet in the mesh
// and can be walked; *report: set when the host must look at its state.
static inline int
mark_constraint(__global const double2 *points, __global const int *tri_vertex,
                __global const int *tri_neighbor, __global const int *vertex_triangle,
                __global const int *constraint_start, __global const int *constraint_adjacent,
                int a, int b, int s, __global int *segment_state, __global int *split_vertex,
                __global int *crossed_vertex, __global int *crossed_triangle,
                volatile __global int *constraint_mark, int max_steps, int *pending, int *report) {
  int t, e, on;
  const int fan = leave_endpoint(points, tri_vertex, tri_neighbor, vertex_triangle, a, b, max_steps,
                                 &t, &e, &on);
  if (fan == CLM_FAN_PRESENT) {
    segment_state[s] = CLM_SEGMENT_PRESENT;
    return 0;
  }
  if (fan != CLM_FAN_EXIT) {
    segment_state[s] = fan == CLM_FAN_ON_SEGMENT ? CLM_SEGMENT_SPLIT : CLM_SEGMENT_LOST;
    split_vertex[s] = on;
    *report = 1;
    return 0;
  }
  *pending = 1;
  int entry = CLM_NO_EDGE;
  for (int step = 0; step < max_steps; ++step) {
    atomic_min(&constraint_mark[t], mark_of(s, entry, e));
    const int p = tri_vertex[3 * t + next3(e)], q = tri_vertex[3 * t + prev3(e)];
    if (is_constraint(constraint_start, constraint_adjacent, p, q)) {
      segment_state[s] = CLM_SEGMENT_CROSSING;
      split_vertex[s] = p;
      crossed_vertex[s] = q;
      crossed_triangle[s] = t;
      *report = 1;
      return step + 1;
    }
    const int next = walk_step(points, tri_vertex, tri_neighbor, a, b, &t, &e, &entry, &on);
    if (next > 0) {
      atomic_min(&constraint_mark[t], mark_of(s, entry, CLM_NO_EDGE));
      return step + 2;
    }
    if (next < 0) {
      segment_state[s] = CLM_SEGMENT_SPLIT; // on lies on a-b
      split_vertex[s] = on;
      *report = 1;
      return step + 1;
    }
  }
  segment_state[s] = CLM_SEGMENT_LOST;
  *report = 1;
  return max_steps;
}

__kernel void mark_constraint_triangles(CLM_TRIANGULATION_PARAMS, __global const int *walk_order,
                                        __global const int *segment_a,
                                        __global const int *segment_b, __global int *segment_state,
                                        __global int *split_vertex, __global int *crossed_vertex,
                                        __global int *crossed_triangle,
                                        volatile __global int *constraint_mark,
                                        volatile __global int *counters, const int max_steps,
                                        const int m) {
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
static inline bool segment_crosses(__global const double2 *points, __global const int *tri_vertex,
                                   int t, int a, int b) {
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
static inline void crossing_edges(__global const double2 *points, __global const int *tri_vertex,
                                  int t, int a, int b, int *entry, int *exit) {
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
static inline int pair_configuration(__global const double2 *points, int p, int q, int x, int y,
                                     int a, int b) {
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

static inline int apex_across(__global const int *tri_vertex, __global const int *tri_neighbor,
                              int t, int e) {
  const int link = tri_neighbor[3 * t + e];
  return tri_vertex[3 * link_triangle(link) + link_edge(link)];
}

// The thesis's case (0: case 1, 1: case 2, 2: case 3; -1: not flippable) of
// the pair (A, C) crossing edge `exit` of A, with B the previous triangle
// across A's edge `entry` (-1: none, or not ours).
static inline int flip_case(__global const double2 *points, __global const int *tri_vertex,
                            __global const int *tri_neighbor, int A, int entry, int exit, int B,
                            int a, int b) {
  const int p = tri_vertex[3 * A + next3(exit)], q = tri_vertex[3 * A + prev3(exit)];
  const int x = tri_vertex[3 * A + exit], y = apex_across(tri_vertex, tri_neighbor, A, exit);
  const int ac = pair_configuration(points, p, q, x, y, a, b);
  if (ac == CLM_PAIR_ZERO || ac == CLM_PAIR_SINGLE)
    return 0;
  if (ac != CLM_PAIR_DOUBLE || B < 0)
    return -1;
  // The pair (B, A) now, and (B, A') once (A, C) is flipped: the entry edge
  // r-w stays, A's apex across it becomes y.
  const int r = tri_vertex[3 * A + next3(entry)], w = tri_vertex[3 * A + prev3(entry)];
  const int bx = apex_across(tri_vertex, tri_neighbor, A, entry);
  const int before = pair_configuration(points, w, r, bx, tri_vertex[3 * A + entry], a, b);
  const int after = pair_configuration(points, w, r, bx, y, a, b);
  if (before == CLM_PAIR_DOUBLE && (after == CLM_PAIR_SINGLE || after == CLM_PAIR_ZERO))
    return 1;
  if (before == CLM_PAIR_CONCAVE && after != CLM_PAIR_CONCAVE)
    return 2;
  return -1;
}

// Inner loop, by runs. A run is a maximal chain of consecutive triangles
// along constraint s that all carry s's mark; every marked triangle lies in
// exactly one run, so runs are disjoint and one work-item may flip inside its
// run with no further marking (the thesis marks A, C and B because its
// work-items are triangles). A run starts at the triangle holding a, or at one
// entered from a triangle without s's mark; the list of runs may come in any
// order (a run's flips do not depend on it). run_counters: [0] runs, [1]
// boundary log entries, [2] flips.
__kernel void find_run_starts(__global const int *constraint_mark, __global const int *tri_neighbor,
                              __global int *run_start, volatile __global int *run_counters,
                              const int n) {
  const int t = get_global_id(0);
  int starts = 0;
  if (t < n && constraint_mark[t] != CLM_NO_CONSTRAINT) {
    const int mark = constraint_mark[t], entry = mark_entry(mark);
    starts = entry == CLM_NO_EDGE ||
             mark_constraint_index(constraint_mark[link_triangle(tri_neighbor[3 * t + entry])]) !=
                 mark_constraint_index(mark);
  }
  volatile __local int scratch[2];
  append_in_group(&t, starts, run_start, &run_counters[0], scratch);
}

// run_of[t] = the run's first triangle, for every triangle of the run.
__kernel void claim_runs(__global const int *run_start, __global const int *tri_neighbor,
                         __global const int *constraint_mark, __global int *run_of,
                         const int max_steps, const int n) {
  const int gid = get_global_id(0);
  if (gid >= n)
    return;
  const int first = run_start[gid], s = mark_constraint_index(constraint_mark[first]);
  int t = first;
  for (int step = 0; step < max_steps; ++step) {
    run_of[t] = first;
    const int exit = mark_exit(constraint_mark[t]);
    if (exit == CLM_NO_EDGE)
      return;
    t = link_triangle(tri_neighbor[3 * t + exit]);
    if (mark_constraint_index(constraint_mark[t]) != s)
      return;
  }
}

// Is the triangle across edge e of t in a run other than `run`? Nobody else
// rewrites the triangles of `run` or of no run, so their links back may be
// written at once; an edge facing another run waits for
// relink_run_boundaries.
static inline bool faces_other_run(__global const int *tri_neighbor, __global const int *run_of,
                                   int t, int e, int run) {
  const int x = link_triangle(tri_neighbor[3 * t + e]);
  return run_of[x] >= 0 && run_of[x] != run;
}

// Reserves the log entries of the flip of edge i of t: one per outer edge
// facing another run (*first: the first entry). Returns false when the log
// is full (the flip is not made).
static inline bool log_room(__global const int *tri_neighbor, __global const int *run_of, int t,
                            int i, int run, __global int *boundary_log,
                            volatile __global int *log_count, int log_capacity, int *first) {
  const int link = tri_neighbor[3 * t + i];
  const int u = link_triangle(link), j = link_edge(link);
  int foreign = 0;
  for (int e = 0; e < 3; ++e)
    foreign += (e != i && faces_other_run(tri_neighbor, run_of, t, e, run)) +
               (e != j && faces_other_run(tri_neighbor, run_of, u, e, run));
  if (foreign == 0)
    return true;
  *first = atomic_add(log_count, foreign);
  if (*first + foreign <= log_capacity)
    return true;
  for (int k = *first; k < log_capacity; ++k)
    boundary_log[k] = -1; // reserved but unused
  return false;
}

// After a flip, links the outer neighbours of the new triangle t back to it,
// or logs the edges that face another run.
static inline void link_outer_edges(__global int *tri_neighbor, __global const int *run_of, int run,
                                    int t, __global int *boundary_log, int *next_entry) {
  for (int e = 1; e < 3; ++e) {
    if (faces_other_run(tri_neighbor, run_of, t, e, run)) {
      boundary_log[(*next_entry)++] = encode_link(t, e);
    } else {
      const int link = tri_neighbor[3 * t + e];
      tri_neighbor[3 * link_triangle(link) + link_edge(link)] = encode_link(t, e);
    }
  }
}

// One work-item per run walks it from its first triangle A and flips (A, C),
// C the next triangle, whenever the thesis's cases allow (case 1, else case 2
// or 3 with B the previous triangle, when B is in the run); after a flip it
// steps back to B, whose pair has changed, and otherwise goes on to C. When
// the walk leaves the run, no pair of the run is flippable.
__kernel void flip_along_runs(CLM_TRIANGULATION_PARAMS, __global const int *run_start,
                              __global const int *constraint_mark, __global const int *segment_a,
                              __global const int *segment_b, __global const int *run_of,
                              __global int *boundary_log, volatile __global int *run_counters,
                              __global int *touched, const int log_capacity, const int max_steps,
                              const int n) {
  const int gid = get_global_id(0);
  int flips = 0;
  if (gid < n) {
    const int run = run_start[gid], s = mark_constraint_index(constraint_mark[run]);
    const int a = segment_a[s], b = segment_b[s];
    int A = run;
    for (int step = 0; step < max_steps; ++step) {
      int entry, exit;
      crossing_edges(points, tri_vertex, A, a, b, &entry, &exit);
      if (exit < 0)
        break; // A holds b
      const int C = link_triangle(tri_neighbor[3 * A + exit]);
      if (run_of[C] != run)
        break; // the run ends
      int B = entry >= 0 ? link_triangle(tri_neighbor[3 * A + entry]) : -1;
      if (B >= 0 && run_of[B] != run)
        B = -1;
      if (flip_case(points, tri_vertex, tri_neighbor, A, entry, exit, B, a, b) < 0) {
        A = C;
        continue;
      }
      int entry_index = 0;
      if (!log_room(tri_neighbor, run_of, A, exit, run, boundary_log, &run_counters[1],
                    log_capacity, &entry_index))
        break; // the rest waits for the next outer iteration
      // The entry edge (opposite A's vertex after or before the exit edge)
      // ends up in A's slot or in C's (see flip_pair).
      const int entered = entry == prev3(exit) ? A : C;
      flip_pair(tri_vertex, tri_neighbor, A, exit);
      link_outer_edges(tri_neighbor, run_of, run, A, boundary_log, &entry_index);
      link_outer_edges(tri_neighbor, run_of, run, C, boundary_log, &entry_index);
      touched[A] = touched[C] = 1;
      // A = (a, d, c) and C = (b, c, d) (see flip_pair): each region's last
      // write for a vertex names a triangle that still holds it.
      for (int k = 0; k < 3; ++k)
        vertex_triangle[tri_vertex[3 * A + k]] = A;
      vertex_triangle[tri_vertex[3 * C]] = C;
      ++flips;
      if (B >= 0 || entry >= 0) {
        A = B >= 0 ? B : entered;
      } else if (!segment_crosses(points, tri_vertex, A, a, b)) {
        // Both new triangles hold a: go on with the one a-b leaves through.
        if (!segment_crosses(points, tri_vertex, C, a, b))
          break; // a-b is the new diagonal
        A = C;
      }
    }
  }
  volatile __local int scratch[2];
  reserve_in_group(flips, scratch, &run_counters[2]);
}

// Second step: an edge between two runs may have moved on both sides. Each
// logged edge p-q (triangle t, edge e) links to where its twin q-p was before
// the pass; if the twin is still there, both are linked at once, otherwise the
// two sides meet in a hash table keyed by the edge (open addressing).
static inline uint edge_hash(int p, int q) {
  const uint lo = (uint)min(p, q), hi = (uint)max(p, q);
  return (lo * 0x9E3779B1u) ^ (hi * 0x85EBCA77u) ^ (hi >> 15);
}

static inline bool holds_edge(__global const int *tri_vertex, int t, int e, int from, int to) {
  return tri_vertex[3 * t + next3(e)] == from && tri_vertex[3 * t + prev3(e)] == to;
}

__kernel void relink_run_boundaries(__global const int *boundary_log,
                                    __global const int *tri_vertex, __global int *tri_neighbor,
                                    __global const int *run_of, volatile __global int *edge_table,
                                    const uint table_mask, const int n) {
  const int gid = get_global_id(0);
  if (gid >= n)
    return;
  const int code = boundary_log[gid];
  if (code < 0)
    return;
  const int t = link_triangle(code), e = link_edge(code);
  const int link = tri_neighbor[3 * t + e], x = link_triangle(link), j = link_edge(link);
  if (run_of[x] < 0 || run_of[x] == run_of[t])
    return; // the entry is stale: another flip moved a different edge here
  const int p = tri_vertex[3 * t + next3(e)], q = tri_vertex[3 * t + prev3(e)];
  if (holds_edge(tri_vertex, x, j, q, p)) {
    tri_neighbor[3 * x + j] = code;
    return;
  }
  for (uint slot = edge_hash(p, q) & table_mask;; slot = (slot + 1) & table_mask) {
    const int other = atomic_cmpxchg(&edge_table[slot], -1, code);
    if (other == -1 || other == code)
      return; // inserted: the twin will find it (or this entry is a duplicate)
    const int y = link_triangle(other), f = link_edge(other);
    if (holds_edge(tri_vertex, y, f, q, p)) {
      tri_neighbor[3 * t + e] = other;
      tri_neighbor[3 * y + f] = code;
      return;
    }
  }
}
