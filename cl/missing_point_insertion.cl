// clmesh — Phase 4 of GPU-DT: missing-point insertion (thesis §4.1.2, §2.3).
//
// Every point not yet in the mesh keeps the triangle that contains it. A round
// (1) walks each point to its containing triangle or edge, (2) marks the
// triangles it would split with atomic minimum of its priority, (3) lets the
// points whose marks all survived split their triangles (1-3 flip inside a
// triangle, 2-4 flip on an edge; a ghost triangle receives points outside the
// hull), new slots being allocated by prefix sums so the result is
// deterministic, and (4) relinks neighbours in a second step. The flipping
// phase restores the Delaunay property after each round, so walks always run
// in a Delaunay triangulation, where the visibility walk cannot cycle.
#include "common.h"
#include "group_scan.h"
#include "mesh_params.h"
#include "prefetch.h"

#define CLM_PENDING 0
#define CLM_DUPLICATE 1
#define CLM_LOST 2

// Prefetching for the kernels over the remaining points that read each
// one's container (prefetch.h): its location three stages ahead, then the
// container's record, stamp and mark, then its corners' points.
static inline void
prefetch_container(__global const int *remaining, int gid, int n, __global const double2 *points,
                   __global const int *tri_vertex, __global const int *modified_stamp,
                   volatile __global const uint *tri_mark, __global const int *location) {
  const int p_far = entry_ahead(remaining, gid, 3, n);
  if (p_far >= 0)
    warm(location + p_far);
  const int p_middle = entry_ahead(remaining, gid, 2, n);
  if (p_middle >= 0) {
    const int t = location[p_middle];
    warm(tri_vertex + 3 * t);
    warm(modified_stamp + t);
    warm_for_write(tri_mark + t);
  }
  const int p_near = entry_ahead(remaining, gid, 1, n);
  if (p_near >= 0)
    warm_corners(points, 0, tri_vertex, location[p_near]);
}

// A level of points inserted after coarser ones (DelaunayScheduler's levels):
// each point level[k] starts its walk where anchor[k], the point of a coarser
// level before it on the Hilbert curve, was located when it was inserted, a
// triangle near it (slots are reused, never freed, while the DT is built).
__kernel void start_at_anchors(__global const int *level, __global const int *anchor,
                               __global int *location, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    location[level[k]] = location[anchor[k]];
}

// Walks from location[p] to the triangle holding p; a point whose triangle was
// not rewritten since the last walk (stamp `since`) stays where it is.
// Results: location[p], location_edge[p] (-1: interior or ghost region, i: on
// edge i), status.
__kernel void locate_points(CLM_TRIANGULATION_PARAMS, const int since,
                            __global const int *remaining, __global int *status,
                            const int max_steps, const int n) {
  const int gid = get_global_id(0);
  prefetch_container(remaining, gid, n, points, tri_vertex, modified_stamp, tri_mark, location);
  if (gid >= n)
    return;
  const int p = remaining[gid];
  if (modified_stamp[location[p]] < since) {
    status[gid] = CLM_PENDING; // its triangle has not changed since it was located there
    return;
  }
  const WalkResult walk =
      walk_to_point(points, tri_vertex, tri_neighbor, location[p], points[p], max_steps);
  location[p] = walk.triangle;
  location_edge[p] = walk.edge;
  if (walk.outcome == CLM_WALK_AT_VERTEX)
    duplicate_of[p] = walk.vertex;
  status[gid] = walk.outcome == CLM_WALK_LOCATED
                    ? CLM_PENDING
                    : (walk.outcome == CLM_WALK_AT_VERTEX ? CLM_DUPLICATE : CLM_LOST);
}

// A point outside the hull conflicts with every ghost whose hull edge it
// sees, not only with the one it was located in (`start`): the ghosts next
// to `g` on side `dir` (0: after, 1: before) that it is strictly outside of,
// in turn. Returns the next such ghost, or -1 (also back at `start`, which a
// convex hull never allows).
static inline int next_visible_ghost(__global const double2 *points, __global const int *tri_vertex,
                                     __global const int *tri_neighbor, int g, int start, int p,
                                     int dir) {
  const int h = adjacent_ghost(tri_neighbor, load_vertices(tri_vertex, g), g, dir == 0);
  const VertexTriple next = load_vertices(tri_vertex, h);
  return h != start && orient_vertices(points, ghost_edge_end(next), ghost_edge_start(next), p) > 0
             ? h
             : -1;
}

// The priority of point p in triangle t (on its edge `edge`, or -1 inside):
// the lower, the sooner. The top 32 - index_bits bits say how late, from 0
// to 1 quantized: inside a real triangle, how far p lies from its centre (1
// minus three times its smallest barycentric coordinate), so that a split
// leaves the triangle's other points spread over its three children (fewer
// rounds and fewer flips than a random choice); outside the hull, how near p
// lies to the hull edge of its ghost (for the distance d beyond it over the
// edge's length, 1 / (1 + d)), so that the farthest goes first and takes the
// near ones inside the hull, instead of the ghosts they share making them
// wait for each other round after round; on an edge, 0. Ties go by a
// bijection of p's index_bits bits (the point numbers are below
// 2^index_bits), unique, and scattered so that neighbours along the Hilbert
// order do not wait for each other in turn.
static inline uint insertion_priority(__global const double2 *points,
                                      __global const int *tri_vertex, int p, int t, int edge,
                                      int index_bits) {
  const uint tie = clm_priority_within((uint)p, index_bits);
  const int level_bits = 32 - index_bits;
  if (level_bits <= 0 || edge >= 0)
    return tie;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  const double2 q = points[p];
  double lateness;
  if (is_ghost(tri)) {
    const double2 a = points[ghost_edge_start(tri)], e = points[ghost_edge_end(tri)] - a;
    const double beyond = fabs(e.x * (q.y - a.y) - e.y * (q.x - a.x)) / (e.x * e.x + e.y * e.y);
    lateness = 1.0 / (1.0 + beyond);
  } else {
    const double2 a = points[tri.v[0]], b = points[tri.v[1]], c = points[tri.v[2]];
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    const double la = ((b.x - q.x) * (c.y - q.y) - (b.y - q.y) * (c.x - q.x)) / area,
                 lb = ((c.x - q.x) * (a.y - q.y) - (c.y - q.y) * (a.x - q.x)) / area;
    lateness = 1.0 - 3.0 * fmin(fmin(la, lb), 1.0 - la - lb);
  }
  // A flat triangle or a zero-length hull edge gives NaN: as late as can be.
  lateness = isnan(lateness) ? 1.0 : clamp(lateness, 0.0, 1.0);
  const uint levels = (1u << level_bits) - 1u;
  return ((uint)(lateness * (double)levels) << index_bits) | tie;
}

// Marks the triangle(s) each pending point would split with its priority.
// placed: the points were not walked to (no locate_points), all pending
// where they stand; their status is set here.
static inline void mark_container(int gid, CLM_TRIANGULATION_PARAMS, __global const int *remaining,
                                  __global int *status, const int placed, const int index_bits) {
  if (placed)
    status[gid] = CLM_PENDING;
  else if (status[gid] != CLM_PENDING)
    return;
  const int p = remaining[gid], t = location[p], edge = location_edge[p];
  const uint key = insertion_priority(points, tri_vertex, p, t, edge, index_bits);
  atomic_min(&tri_mark[t], key);
  if (edge >= 0)
    atomic_min(&tri_mark[link_triangle(tri_neighbor[3 * t + edge])], key);
  else if (tri_vertex[3 * t] < 0 || tri_vertex[3 * t + 1] < 0 || tri_vertex[3 * t + 2] < 0)
    for (int dir = 0; dir < 2; ++dir)
      for (int g = t;
           (g = next_visible_ghost(points, tri_vertex, tri_neighbor, g, t, p, dir)) >= 0;)
        atomic_min(&tri_mark[g], key);
}

__kernel void mark_containers(CLM_TRIANGULATION_PARAMS, __global const int *remaining,
                              __global int *status, const int placed, const int index_bits,
                              const int n) {
  const int gid = get_global_id(0);
  prefetch_container(remaining, gid, n, points, tri_vertex, modified_stamp, tri_mark, location);
  if (gid < n)
    mark_container(gid, CLM_TRIANGULATION_ARGS, remaining, status, placed, index_bits);
}

// winner[gid] = 1 when every mark written by the point survived.
static inline void select_winner(int gid, CLM_TRIANGULATION_PARAMS, __global const int *remaining,
                                 __global const int *status, __global int *winner,
                                 const int index_bits) {
  int wins = 0;
  if (status[gid] == CLM_PENDING) {
    const int p = remaining[gid], t = location[p], edge = location_edge[p];
    const uint key = insertion_priority(points, tri_vertex, p, t, edge, index_bits);
    wins = tri_mark[t] == key &&
           (edge < 0 || tri_mark[link_triangle(tri_neighbor[3 * t + edge])] == key);
    if (edge < 0 &&
        (tri_vertex[3 * t] < 0 || tri_vertex[3 * t + 1] < 0 || tri_vertex[3 * t + 2] < 0))
      for (int dir = 0; dir < 2; ++dir)
        for (int g = t;
             wins && (g = next_visible_ghost(points, tri_vertex, tri_neighbor, g, t, p, dir)) >= 0;)
          wins = tri_mark[g] == key;
  }
  winner[gid] = wins;
}

__kernel void select_winners(CLM_TRIANGULATION_PARAMS, __global const int *remaining,
                             __global const int *status, __global int *winner, const int index_bits,
                             const int n) {
  const int gid = get_global_id(0);
  prefetch_container(remaining, gid, n, points, tri_vertex, modified_stamp, tri_mark, location);
  if (gid < n)
    select_winner(gid, CLM_TRIANGULATION_ARGS, remaining, status, winner, index_bits);
}

// Clears the marks of this round (before the topology changes).
static inline void clear_container_mark(int gid, CLM_TRIANGULATION_PARAMS,
                                        __global const int *remaining, __global const int *status) {
  if (status[gid] != CLM_PENDING)
    return;
  const int p = remaining[gid], t = location[p], edge = location_edge[p];
  tri_mark[t] = CLM_NO_MARK;
  if (edge >= 0)
    tri_mark[link_triangle(tri_neighbor[3 * t + edge])] = CLM_NO_MARK;
  else if (tri_vertex[3 * t] < 0 || tri_vertex[3 * t + 1] < 0 || tri_vertex[3 * t + 2] < 0)
    for (int dir = 0; dir < 2; ++dir)
      for (int g = t;
           (g = next_visible_ghost(points, tri_vertex, tri_neighbor, g, t, p, dir)) >= 0;)
        tri_mark[g] = CLM_NO_MARK;
}

__kernel void clear_container_marks(CLM_TRIANGULATION_PARAMS, __global const int *remaining,
                                    __global const int *status, const int n) {
  const int gid = get_global_id(0);
  if (gid < n)
    clear_container_mark(gid, CLM_TRIANGULATION_ARGS, remaining, status);
}

// Prefetching for split_triangles (prefetch.h): a winner's location, then
// the triangle it splits.
static inline void prefetch_split(__global const int *remaining, __global const int *winner,
                                  __global const int *location, __global const int *location_edge,
                                  __global const int *tri_vertex, __global const int *tri_neighbor,
                                  __global const int *modified_stamp, __global const int *children,
                                  int gid, int n) {
  const int far = gid + 2 * CLM_AHEAD, p_far = entry_ahead(remaining, gid, 2, n);
  if (p_far >= 0 && winner[far]) {
    warm(location + p_far);
    warm(location_edge + p_far);
  }
  const int near = gid + CLM_AHEAD, p_near = entry_ahead(remaining, gid, 1, n);
  if (p_near >= 0 && winner[near]) {
    const int t = location[p_near];
    warm_for_write(tri_vertex + 3 * t);
    warm_for_write(tri_neighbor + 3 * t);
    warm_for_write(modified_stamp + t);
    warm_for_write(children + CLM_CHILDREN * t);
  }
}

// Splits the winners' triangles. Each winner takes new slots 2 * winner_offset
// and 2 * winner_offset + 1 of the batch (free slots first, see
// allocate_slot); every child has the new point at index 2,
// so its edge 2 is the only one facing outwards. Children are listed in
// changed[4 * winner_offset .. +3] (-1 when unused) for relinking and flipping.
static inline void split_winner(int gid, CLM_TRIANGULATION_PARAMS, __global const int *remaining,
                                __global const int *winner_offset, __global int *changed,
                                const int stamp, __global const int *free_list,
                                const int free_first, const int free_count, const int first_slot) {
  const int p = remaining[gid], t = location[p], edge = location_edge[p];
  const int s1 =
      allocate_slot(free_list, free_first, free_count, first_slot, 2 * winner_offset[gid]);
  const int s2 =
      allocate_slot(free_list, free_first, free_count, first_slot, 2 * winner_offset[gid] + 1);
  __global int *out = changed + 4 * winner_offset[gid];
  const VertexTriple tri = load_vertices(tri_vertex, t);
  const int n0 = tri_neighbor[3 * t], n1 = tri_neighbor[3 * t + 1], n2 = tri_neighbor[3 * t + 2];
  if (edge < 0) { // 1-3 flip: (a,b,c) -> (a,b,p) (b,c,p) (c,a,p)
    const int a = tri.v[0], b = tri.v[1], c = tri.v[2];
    store_triangle(tri_vertex, tri_neighbor, t, a, b, p, encode_link(s1, 1), encode_link(s2, 0),
                   n2);
    store_triangle(tri_vertex, tri_neighbor, s1, b, c, p, encode_link(s2, 1), encode_link(t, 0),
                   n0);
    store_triangle(tri_vertex, tri_neighbor, s2, c, a, p, encode_link(t, 1), encode_link(s1, 0),
                   n1);
    record_children(modified_stamp, children, t, stamp, t, s1, s2);
    modified_stamp[s1] = modified_stamp[s2] = stamp; // new slots: changed too
    if (regional)
      tri_region[s1] = tri_region[s2] = tri_region[t];
    out[0] = t;
    out[1] = s1;
    out[2] = s2;
    out[3] = -1;
  } else { // 2-4 flip on edge a-b shared by t = (c,a,b) and u = (d,b,a)
    const int c = tri.v[edge], a = tri.v[next3(edge)], b = tri.v[prev3(edge)];
    const int t_opp_a = tri_neighbor[3 * t + next3(edge)],
              t_opp_b = tri_neighbor[3 * t + prev3(edge)];
    const int link = tri_neighbor[3 * t + edge];
    const int u = link_triangle(link), j = link_edge(link);
    const int d = tri_vertex[3 * u + j];
    const int u_opp_b = tri_neighbor[3 * u + next3(j)], u_opp_a = tri_neighbor[3 * u + prev3(j)];
    store_triangle(tri_vertex, tri_neighbor, t, c, a, p, encode_link(s2, 1), encode_link(s1, 0),
                   t_opp_b);
    store_triangle(tri_vertex, tri_neighbor, s1, b, c, p, encode_link(t, 1), encode_link(u, 0),
                   t_opp_a);
    store_triangle(tri_vertex, tri_neighbor, u, d, b, p, encode_link(s1, 1), encode_link(s2, 0),
                   u_opp_a);
    store_triangle(tri_vertex, tri_neighbor, s2, a, d, p, encode_link(u, 1), encode_link(t, 0),
                   u_opp_b);
    record_children(modified_stamp, children, t, stamp, t, s1, -1);
    record_children(modified_stamp, children, u, stamp, u, s2, -1);
    modified_stamp[s1] = modified_stamp[s2] = stamp; // new slots: changed too
    if (regional) { // each side of the edge (a subsegment, perhaps) keeps its region
      tri_region[s1] = tri_region[t];
      tri_region[s2] = tri_region[u];
    }
    out[0] = t;
    out[1] = s1;
    out[2] = u;
    out[3] = s2;
  }
  vertex_triangle[p] = t;
}

#define CLM_SPLIT_ARGS                                                                             \
  remaining, winner_offset, changed, stamp, free_list, free_first, free_count, first_slot

__kernel void split_triangles(CLM_TRIANGULATION_PARAMS, __global const int *remaining,
                              __global const int *winner, __global const int *winner_offset,
                              __global int *changed, const int stamp, __global const int *free_list,
                              const int free_first, const int free_count, const int first_slot,
                              const int n) {
  const int gid = get_global_id(0);
  prefetch_split(remaining, winner, location, location_edge, tri_vertex, tri_neighbor,
                 modified_stamp, children, gid, n);
  if (gid < n && winner[gid])
    split_winner(gid, CLM_TRIANGULATION_ARGS, CLM_SPLIT_ARGS);
}

// Second step: link each child's outward edge (edge 2) to its true neighbour.
__kernel void relink_split_children(CLM_TRIANGULATION_PARAMS, __global const int *changed,
                                    const int stamp, const int n) {
  const int gid = get_global_id(0);
  const int far = entry_ahead(changed, gid, 2, n);
  if (far >= 0)
    warm(tri_neighbor + 3 * far);
  warm_across_edges(tri_neighbor, modified_stamp, children, entry_ahead(changed, gid, 1, n), 2, 3);
  if (gid >= n || changed[gid] < 0)
    return;
  relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, changed[gid], 2);
}

// keep[gid] = 1 for points still waiting (neither inserted nor duplicate);
// counts lost walks, which would be a bug, in counters[0]. Reads what
// select_winners leaves. Returns keep[gid].
static inline int count_waiting(int gid, __global const int *status, __global const int *winner,
                                __global int *keep, volatile __global int *counters) {
  const int waiting = status[gid] == CLM_PENDING && !winner[gid];
  keep[gid] = waiting;
  if (status[gid] == CLM_LOST)
    atomic_inc(&counters[0]);
  return waiting;
}

// The same for every point, the waiting ones added up in counters[1] (a
// running total).
__kernel void count_remaining(__global const int *status, __global const int *winner,
                              __global int *keep, volatile __global int *counters, const int n) {
  const int gid = get_global_id(0);
  const int waiting = gid < n ? count_waiting(gid, status, winner, keep, counters) : 0;
  volatile __local int scratch[2];
  reserve_in_group(waiting, scratch, &counters[1]);
}

// A short round (its points located) by one work-group in one launch:
// mark_containers, select_winners, clear_container_marks and
// count_remaining in turn, the winners' prefix sum into winner_offset (its
// total in counters[2]), split_triangles and relink_split_children.
__kernel void insert_round_in_group(CLM_TRIANGULATION_PARAMS, __global const int *remaining,
                                    __global int *status, __global int *winner,
                                    __global int *winner_offset, __global int *keep,
                                    volatile __global int *counters, __local int *scratch,
                                    const int placed, const int index_bits, __global int *changed,
                                    const int stamp, __global const int *free_list,
                                    const int free_first, const int free_count,
                                    const int first_slot, const int n) {
  const int lid = get_local_id(0), size = get_local_size(0);
  for (int k = lid; k < n; k += size)
    mark_container(k, CLM_TRIANGULATION_ARGS, remaining, status, placed, index_bits);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < n; k += size)
    select_winner(k, CLM_TRIANGULATION_ARGS, remaining, status, winner, index_bits);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  int waiting = 0;
  for (int k = lid; k < n; k += size) {
    clear_container_mark(k, CLM_TRIANGULATION_ARGS, remaining, status);
    waiting += count_waiting(k, status, winner, keep, counters);
  }
  if (waiting > 0)
    atomic_add(&counters[1], waiting);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int winners = group_exclusive_scan(winner, winner_offset, n, scratch);
  for (int k = lid; k < n; k += size)
    if (winner[k])
      split_winner(k, CLM_TRIANGULATION_ARGS, CLM_SPLIT_ARGS);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < 4 * winners; k += size)
    if (changed[k] >= 0)
      relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, changed[k], 2);
  if (lid == 0)
    counters[2] = winners;
}
