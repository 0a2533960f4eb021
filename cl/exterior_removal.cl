// clmesh — removing the exterior and the holes of a CDT (Triangle's -p
// semantics, run as parallel flood fills): triangles are eaten from the convex
// hull inwards and from each hole seed outwards, never across a constraint.
// Each wave appends the triangles it claims (atomic exchange on removed[]) to
// the next frontier; the order of a frontier never reaches the output, only
// the set of removed triangles does.
#include "common.h"
#include "mesh_params.h"

inline void claim(__global int *removed, __global int *frontier, volatile __global int *count,
                  int t) {
  if (atomic_xchg(&removed[t], 1) == 0)
    frontier[atomic_inc(count)] = t;
}

// The real triangle across edge e of t, or -1 when that edge is a constraint,
// the hull, or leads to a removed triangle: where a flood may go.
inline int flood_neighbor(__global const int *tri_vertex, __global const int *tri_neighbor,
                          __global const int *constraint_start,
                          __global const int *constraint_adjacent, __global const int *removed,
                          int t, int e) {
  const int a = tri_vertex[3 * t + next3(e)], b = tri_vertex[3 * t + prev3(e)];
  const int u = link_triangle(tri_neighbor[3 * t + e]);
  if (is_ghost(load_vertices(tri_vertex, u)) || removed[u] ||
      is_constraint(constraint_start, constraint_adjacent, a, b))
    return -1;
  return u;
}

// Real triangles on the hull whose hull edge is not a constraint.
__kernel void seed_from_hull(CLM_TRIANGULATION_PARAMS, __global int *removed,
                             __global int *frontier, volatile __global int *count, const int n) {
  const int g = get_global_id(0);
  if (g >= n)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, g);
  for (int k = 0; k < 3; ++k)
    if (tri.v[k] == CLM_INFINITE) {
      const int a = tri.v[next3(k)], b = tri.v[prev3(k)];
      if (!is_constraint(constraint_start, constraint_adjacent, a, b))
        claim(removed, frontier, count, link_triangle(tri_neighbor[3 * g + k]));
    }
}

// Hole seeds: the real triangle holding each seed (seeds outside the hull are ignored).
__kernel void seed_from_points(CLM_TRIANGULATION_PARAMS, __global const double2 *seeds,
                               const int start, const int max_steps, __global int *removed,
                               __global int *frontier, volatile __global int *count, const int n) {
  const int i = get_global_id(0);
  if (i >= n)
    return;
  const WalkResult walk =
      walk_to_point(points, tri_vertex, tri_neighbor, start, seeds[i], max_steps);
  if (walk.outcome == CLM_WALK_LOST || is_ghost(load_vertices(tri_vertex, walk.triangle)))
    return;
  claim(removed, frontier, count, walk.triangle);
}

// Regional attributes (-A): region r's seed floods its area, bounded by
// constraints; regions are run in order, so a later seed in the same area wins.
__kernel void seed_label(CLM_TRIANGULATION_PARAMS, __global const int *removed, const double2 seed,
                         const int start, const int max_steps, const int region,
                         __global int *label, __global int *frontier,
                         volatile __global int *count) {
  if (get_global_id(0) != 0)
    return;
  const WalkResult walk = walk_to_point(points, tri_vertex, tri_neighbor, start, seed, max_steps);
  const int t = walk.triangle;
  if (walk.outcome == CLM_WALK_LOST || is_ghost(load_vertices(tri_vertex, t)) || removed[t])
    return;
  label[t] = region;
  frontier[atomic_inc(count)] = t;
}

// One wave of a flood: removal (region < 0: claims removed[]) or labelling
// of region `region` (claims label[]), never across a constraint.
__kernel void spread_flood(CLM_TRIANGULATION_PARAMS, __global const int *frontier,
                           volatile __global int *removed, const int region,
                           volatile __global int *label, __global int *next_frontier,
                           volatile __global int *next_count, const int n) {
  const int i = get_global_id(0);
  int claimed[3], count = 0;
  if (i < n) {
    const int t = frontier[i];
    for (int e = 0; e < 3; ++e) {
      const int u = flood_neighbor(tri_vertex, tri_neighbor, constraint_start, constraint_adjacent,
                                   (__global const int *)removed, t, e);
      if (u >= 0 && (region < 0 ? atomic_xchg(&removed[u], 1) == 0
                                : atomic_xchg(&label[u], region) != region))
        claimed[count++] = u;
    }
  }
  volatile __local int scratch[2];
  append_in_group(claimed, count, next_frontier, next_count, scratch);
}
