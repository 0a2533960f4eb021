// clmesh — software prefetching on CPU devices (thesis §3.6: the refinement
// kernels walk lists of triangles).
//
// On a CPU, PoCL runs the work-items of a work-group one after another, and
// the refinement kernels spend most of their time waiting on chains of
// dependent loads that miss the cache: list entry -> triangle -> neighbour ->
// vertex -> point. So a work-item warms the cache for the work-items a few
// places after it, one link of the chain per stage: the triangles of the
// entries 3 * CLM_AHEAD places on, their neighbours and corners 2 * CLM_AHEAD
// on (their triangles are warm by then), the points across their edges
// CLM_AHEAD on. The host defines CLM_PREFETCH for CPU devices only; elsewhere
// every helper here is empty. Prefetches change no result, and the loads that
// lead them read only slots that hold valid indices whatever the moment.
#ifndef CLMESH_PREFETCH_H
#define CLMESH_PREFETCH_H

#include "common.h"

#define CLM_AHEAD 6 // work-items between two stages

#ifdef CLM_PREFETCH
// (volatile: the marks taken with atomics can be warmed too.)
static inline void warm(const volatile __global void *p) {
  __builtin_prefetch((const __global void *)p, 0, 3);
}
static inline void warm_for_write(const volatile __global void *p) {
  __builtin_prefetch((const __global void *)p, 1, 3);
}
#else
static inline void warm(const volatile __global void *p) {}
static inline void warm_for_write(const volatile __global void *p) {}
#endif

// The entry `stage` stages ahead of gid in list[0 .. n), or -1.
static inline int entry_ahead(__global const int *list, int gid, int stage, int n) {
#ifdef CLM_PREFETCH
  const int k = gid + stage * CLM_AHEAD;
  return k < n ? list[k] : -1;
#else
  return -1;
#endif
}

// The slot `stage` stages ahead of slot t in a sweep of slots [0 .. n), or -1.
static inline int slot_ahead(int t, int stage, int n) {
#ifdef CLM_PREFETCH
  const int k = t + stage * CLM_AHEAD;
  return k < n ? k : -1;
#else
  return -1;
#endif
}

// Triangle t's vertices and links.
static inline void warm_triangle(__global const int *tri_vertex, __global const int *tri_neighbor,
                                 int t) {
  if (t < 0)
    return;
  warm(tri_vertex + 3 * t);
  warm(tri_neighbor + 3 * t);
}

// A vertex's point and state (point_state may be 0: none; nothing for the
// vertex at infinity or a dead slot's mark).
static inline void warm_vertex(__global const double2 *points, __global const int *point_state,
                               int v) {
  if (v < 0)
    return;
  warm(points + v);
  if (point_state)
    warm(point_state + v);
}

// The points of triangle t's corners (t's record warm).
static inline void warm_corners(__global const double2 *points, __global const int *point_state,
                                __global const int *tri_vertex, int t) {
  if (t < 0)
    return;
  for (int i = 0; i < 3; ++i)
    warm_vertex(points, point_state, tri_vertex[3 * t + i]);
}

// The vertices of triangle t's neighbours (t's record warm).
static inline void warm_neighbours(__global const int *tri_vertex, __global const int *tri_neighbor,
                                   int t) {
  if (t < 0)
    return;
  for (int i = 0; i < 3; ++i) {
    const int u = link_triangle(tri_neighbor[3 * t + i]);
    if (u >= 0)
      warm(tri_vertex + 3 * u);
  }
}

// The points across triangle t's edges (its neighbours' records warm).
static inline void warm_opposite(__global const double2 *points, __global const int *point_state,
                                 __global const int *tri_vertex, __global const int *tri_neighbor,
                                 int t) {
  if (t < 0)
    return;
  for (int i = 0; i < 3; ++i) {
    const int link = tri_neighbor[3 * t + i];
    if (link >= 0)
      warm_vertex(points, point_state, tri_vertex[3 * link_triangle(link) + link_edge(link)]);
  }
}

// What a flip or a removal rewrites in triangle t: its vertices and links,
// its mark, its stamp and its record of children.
static inline void warm_rewritten(__global const int *tri_vertex, __global const int *tri_neighbor,
                                  __global const int *modified_stamp, __global const int *children,
                                  volatile __global const uint *tri_mark, int t) {
  if (t < 0)
    return;
  warm_for_write(tri_vertex + 3 * t);
  warm_for_write(tri_neighbor + 3 * t);
  warm_for_write(tri_mark + t);
  warm_for_write(modified_stamp + t);
  warm_for_write(children + CLM_CHILDREN * t);
}

// What relink_edge reads across edges first .. last - 1 of triangle t (t's
// record warm): the neighbour's stamp, link slots and children.
static inline void warm_across_edges(__global const int *tri_neighbor,
                                     __global const int *modified_stamp,
                                     __global const int *children, int t, int first, int last) {
  if (t < 0)
    return;
  for (int e = first; e < last; ++e) {
    const int x = link_triangle(tri_neighbor[3 * t + e]);
    if (x < 0)
      continue;
    warm(modified_stamp + x);
    warm_for_write(tri_neighbor + 3 * x);
    warm(children + CLM_CHILDREN * x);
  }
}

// For a kernel that reads, per entry of `list`, a triangle, its corners,
// its neighbours' vertices and the points across its edges (point_state: 0
// when the kernel does not read the states).
static inline void prefetch_triangle_and_neighbours(__global const int *list, int gid, int n,
                                                    __global const double2 *points,
                                                    __global const int *point_state,
                                                    __global const int *tri_vertex,
                                                    __global const int *tri_neighbor) {
  warm_triangle(tri_vertex, tri_neighbor, entry_ahead(list, gid, 3, n));
  const int t = entry_ahead(list, gid, 2, n);
  warm_neighbours(tri_vertex, tri_neighbor, t);
  warm_corners(points, point_state, tri_vertex, t);
  warm_opposite(points, point_state, tri_vertex, tri_neighbor, entry_ahead(list, gid, 1, n));
}

// The marks of triangle t and of its neighbours, which a proposal to flip
// one of its edges takes (t's record warm).
static inline void warm_marks_around(volatile __global const uint *tri_mark,
                                     __global const int *tri_neighbor, int t) {
  if (t < 0)
    return;
  warm_for_write(tri_mark + t);
  for (int i = 0; i < 3; ++i)
    warm_for_write(tri_mark + link_triangle(tri_neighbor[3 * t + i]));
}

// What the subsegment test (refinement.h is_subsegment) reads of triangle t's
// corners (t's record warm): the segment each lies on and where its
// constraint row starts.
static inline void warm_corner_segments(__global const int *point_segment,
                                        __global const int *constraint_start,
                                        __global const int *tri_vertex, int t) {
  if (t < 0)
    return;
  for (int i = 0; i < 3; ++i) {
    const int v = tri_vertex[3 * t + i];
    if (v >= 0) {
      warm(point_segment + v);
      warm(constraint_start + v);
    }
  }
}

// The constraint rows of triangle t's corners (t's record and the rows'
// starts warm).
static inline void warm_corner_rows(__global const int *constraint_start,
                                    __global const int *constraint_adjacent,
                                    __global const int *tri_vertex, int t) {
  if (t < 0)
    return;
  for (int i = 0; i < 3; ++i) {
    const int v = tri_vertex[3 * t + i];
    if (v >= 0)
      warm(constraint_adjacent + constraint_start[v]);
  }
}

// For a kernel that tests, per entry of `list`, whether edges of a triangle
// are subsegments (after prefetch_triangle_and_neighbours, which warms the
// triangles three stages ahead).
static inline void prefetch_subsegment_tests(__global const int *list, int gid, int n,
                                             __global const int *point_segment,
                                             __global const int *constraint_start,
                                             __global const int *constraint_adjacent,
                                             __global const int *tri_vertex) {
  warm_corner_segments(point_segment, constraint_start, tri_vertex, entry_ahead(list, gid, 2, n));
  warm_corner_rows(constraint_start, constraint_adjacent, tri_vertex, entry_ahead(list, gid, 1, n));
}

// For a kernel that reads, per entry of `list`, a triangle's vertices and
// their points (and states, unless point_state is 0).
static inline void prefetch_corners(__global const int *list, int gid, int n,
                                    __global const double2 *points, __global const int *point_state,
                                    __global const int *tri_vertex) {
  const int t = entry_ahead(list, gid, 2, n);
  if (t >= 0)
    warm(tri_vertex + 3 * t);
  warm_corners(points, point_state, tri_vertex, entry_ahead(list, gid, 1, n));
}

#endif
