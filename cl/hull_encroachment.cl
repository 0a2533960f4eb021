// clmesh — the boundary routine of thesis §3.4.1 (Mechanisms for GPU-QM to
// handle boundary refining), run at the start of step 3: the Steiner points
// in the diametral circle of a hull edge or subsegment split in this iteration are marked
// redundant, for flip-flop (flip_flop.cl) to delete, as Triangle deletes the
// free vertices in the diametral circle of a subsegment it splits.
#include "common.h"
#include "group_scan.h"
#include "mesh_params.h"
#include "refinement.h"
#include "vertex_star.h"

// For each midpoint v of this iteration, on the former hull edge a-b with apex c (or
// subsegment a-b with apexes c and d), the off-centers among c and c's neighbours (and d and
// d's) that lie in a-b's diametral circle (see a-b at an obtuse angle) are marked redundant.
// Triangle would not have inserted the new ones among them (it splits the edge instead), and
// deletes the old ones when it splits the edge: near the boundary they were put where the halves
// and their triangles need none, and a bad triangle left by the deletion sends its point again.
// Three kernels over the new points, so that the list of the old points marked is the same on every
// run: each encroacher is claimed by the smallest midpoint (claim), the midpoints count the old
// ones they own (count), and write them after a prefix sum (write).
#define CLM_ENCROACH_CLAIM 0
#define CLM_ENCROACH_COUNT 1
#define CLM_ENCROACH_WRITE 2

// The off-centers among apex c (of triangle t, which has corner c) and c's
// neighbours in the diametral circle of a-b, claimed (step CLAIM) by
// midpoint k, or marked and counted from `count` on (COUNT, WRITE) when k
// holds the claim. Returns the count so far.
static inline int mark_around_apex(CLM_MESH_PARAMS, int k, int step, int t, int a, int b, int c,
                                   volatile __global int *claim, __global int *redundant_mark,
                                   __global int *redundant_anchor, __global const int *offset,
                                   __global int *tracked, int first, int count) {
  int s = t, q = c;
  for (int around = 0; around < 64; ++around) {
    if (q >= 0) {
      const int state = point_state[q];
      if ((state == CLM_POINT_STEINER || state == CLM_POINT_NEW) &&
          in_lens(points[a], points[b], points[q], 0.0)) {
        if (step == CLM_ENCROACH_CLAIM) {
          atomic_min(&claim[q], k);
        } else if (claim[q] == k) {
          if (step == CLM_ENCROACH_COUNT) {
            redundant_mark[q] = 1;
            redundant_anchor[q] = s;
          }
          if (state == CLM_POINT_STEINER) {
            if (step == CLM_ENCROACH_WRITE)
              tracked[first + offset[k] + count] = q;
            ++count;
          }
        }
      }
    }
    const int kc = index_in(tri_vertex, s, c);
    s = next_around(tri_neighbor, s, kc);
    if (s == t)
      break;
    q = star_vertex(tri_vertex, s, c);
  }
  return count;
}

// Does w lie on segment sv (added on it, or one of its ends)?
static inline bool on_segment(__global const int *point_segment, __global const int *segment_end,
                              int sv, int w) {
  return w >= 0 &&
         (point_segment[w] == sv || segment_end[2 * sv] == w || segment_end[2 * sv + 1] == w);
}

// Midpoint k's step of the routine (the three steps above).
static inline void mark_encroaching(int k, CLM_MESH_PARAMS, __global const int *new_points,
                                    const int step, volatile __global int *claim,
                                    __global int *redundant_mark, __global int *redundant_anchor,
                                    __global int *owned, __global const int *offset,
                                    __global int *tracked, const int first) {
  const int v = new_points[k];
  if (step == CLM_ENCROACH_COUNT)
    owned[k] = 0;
  if (point_state[v] != CLM_POINT_NEW_MIDPOINT)
    return;
  const int t = vertex_triangle[v], i = index_in(tri_vertex, t, v);
  const int x = tri_vertex[3 * t + next3(i)], y = tri_vertex[3 * t + prev3(i)];
  const int across_vx = link_triangle(tri_neighbor[3 * t + prev3(i)]);
  const int across_yv = link_triangle(tri_neighbor[3 * t + next3(i)]);
  const bool x_on_hull = is_ghost(load_vertices(tri_vertex, across_vx));
  int count = 0;
  if (!x_on_hull && !is_ghost(load_vertices(tri_vertex, across_yv))) {
    // A split of an interior subsegment: four triangles around v, the
    // segment's pieces to a and b, the apexes c and d between them.
    const int sv = point_segment[v];
    if (sv < 0)
      return;
    int w[4], st[4], s = t;
    for (int j = 0; j < 4; ++j) {
      st[j] = s;
      w[j] = star_vertex(tri_vertex, s, v);
      s = next_around(tri_neighbor, s, index_in(tri_vertex, s, v));
    }
    if (s != t)
      return;
    int j = 0;
    while (j < 2 && !(on_segment(point_segment, segment_end, sv, w[j]) &&
                      on_segment(point_segment, segment_end, sv, w[j + 2])))
      ++j;
    if (j == 2)
      return;
    const int a = w[j], b = w[j + 2];
    // st[j] holds v, w[j] and w[j + 1]; st[j + 2] v, w[j + 2] and w[(j + 3) % 4].
    count = mark_around_apex(CLM_MESH_ARGS, k, step, st[j], a, b, w[j + 1], claim, redundant_mark,
                             redundant_anchor, offset, tracked, first, count);
    count = mark_around_apex(CLM_MESH_ARGS, k, step, st[j + 2], a, b, w[(j + 3) % 4], claim,
                             redundant_mark, redundant_anchor, offset, tracked, first, count);
  } else {
    // Just after its 1-2 split, v has two real triangles (v,a,c) and (v,c,b).
    const int a = x_on_hull ? x : y, c = x_on_hull ? y : x,
              other = x_on_hull ? across_yv : across_vx;
    const int j = index_in(tri_vertex, other, v);
    int b = tri_vertex[3 * other + next3(j)];
    if (b == c)
      b = tri_vertex[3 * other + prev3(j)];
    if (a < 0 || b < 0 || c < 0)
      return;
    count = mark_around_apex(CLM_MESH_ARGS, k, step, t, a, b, c, claim, redundant_mark,
                             redundant_anchor, offset, tracked, first, count);
  }
  if (step == CLM_ENCROACH_COUNT)
    owned[k] = count;
}

#define CLM_ENCROACH_ARGS(step)                                                                    \
  new_points, step, claim, redundant_mark, redundant_anchor, owned, offset, tracked, first

__kernel void mark_encroaching_points(CLM_MESH_PARAMS, __global const int *new_points,
                                      const int step, volatile __global int *claim,
                                      __global int *redundant_mark, __global int *redundant_anchor,
                                      __global int *owned, __global const int *offset,
                                      __global int *tracked, const int first, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    mark_encroaching(k, CLM_MESH_ARGS, CLM_ENCROACH_ARGS(step));
}

// Resets the claims of the boundary routine for the next iteration.
__kernel void clear_encroaching_claims(__global const int *tracked, __global int *claim,
                                       const int n) {
  const int k = get_global_id(0);
  if (k < n)
    claim[tracked[k]] = 0x7fffffff;
}

// The three steps, the prefix sum between them and the reset of the claims
// by one work-group, in one launch, for few new points (copied to tracked
// first, as the host does for the kernels): entry by entry the results of
// the kernels. The old points appended go to tracked[first ..], their
// number to appended[0].
__kernel void mark_encroaching_in_group(CLM_MESH_PARAMS, __global const int *new_points,
                                        volatile __global int *claim, __global int *redundant_mark,
                                        __global int *redundant_anchor, __global int *owned,
                                        __global int *offset, __global int *tracked,
                                        __local int *scratch, __global int *appended,
                                        const int first) {
  const int lid = get_local_id(0), size = get_local_size(0), n = first;
  for (int k = lid; k < n; k += size) {
    tracked[k] = new_points[k];
    mark_encroaching(k, CLM_MESH_ARGS, CLM_ENCROACH_ARGS(CLM_ENCROACH_CLAIM));
  }
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < n; k += size)
    mark_encroaching(k, CLM_MESH_ARGS, CLM_ENCROACH_ARGS(CLM_ENCROACH_COUNT));
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int old = group_exclusive_scan(owned, offset, n, scratch);
  for (int k = lid; old > 0 && k < n; k += size)
    mark_encroaching(k, CLM_MESH_ARGS, CLM_ENCROACH_ARGS(CLM_ENCROACH_WRITE));
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < n + old; k += size)
    claim[tracked[k]] = 0x7fffffff;
  if (lid == 0)
    appended[0] = old;
}
