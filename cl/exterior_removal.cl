// clmesh — removing the exterior and the holes of a CDT (Triangle's -p
// semantics, run as parallel flood fills): triangles are eaten from the convex
// hull inwards and from each hole seed outwards, never across a constraint.
// Each wave appends the triangles it claims (atomic exchange on removed[]) to
// the next frontier; the order of a frontier never reaches the output, only
// the set of removed triangles does. A hole or region seed that lies exactly
// on a segment or at one of its vertices (exact orientation tests) starts on
// neither side of it: it is ignored, and reported.
#include "common.h"
#include "group_scan.h"
#include "mesh_params.h"

static inline void claim(__global int *removed, __global int *frontier,
                         volatile __global int *count, int t) {
  if (atomic_xchg(&removed[t], 1) == 0)
    frontier[atomic_inc(count)] = t;
}

// The real triangle across edge e of t, or -1 when that edge is a constraint,
// the hull, or leads to a removed triangle: where a flood may go.
static inline int flood_neighbor(__global const int *tri_vertex, __global const int *tri_neighbor,
                                 __global const int *constraint_start,
                                 __global const int *constraint_adjacent,
                                 __global const int *removed, int t, int e) {
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

// A mesh to refine (-r): its real triangles that match none of the input's
// (label -1, mesh_reconstruction.cl) are outside it and removed; the holes'
// floods then stop at them.
__kernel void remove_unlabelled(CLM_TRIANGULATION_PARAMS, __global const int *label,
                                __global int *removed, volatile __global int *count, const int n) {
  const int t = get_global_id(0);
  if (t >= n)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (label[t] < 0 && !is_ghost(tri) && !is_dead(tri)) {
    removed[t] = 1;
    atomic_inc(count);
  }
}

#define CLM_SEED_OUTSIDE -1
#define CLM_SEED_ON_SEGMENT -2

// The real triangle holding seed p; CLM_SEED_OUTSIDE outside the hull,
// CLM_SEED_ON_SEGMENT on a segment or at one of its vertices. A seed on an
// edge that is no segment may start on either side: the flood crosses it.
static inline int seed_triangle(CLM_TRIANGULATION_PARAMS, double2 p, int start, int max_steps) {
  const WalkResult walk = walk_to_point(points, tri_vertex, tri_neighbor, start, p, max_steps);
  const int t = walk.triangle;
  if (walk.outcome == CLM_WALK_LOST)
    return CLM_SEED_OUTSIDE;
  if (walk.outcome == CLM_WALK_AT_VERTEX) // t is a real triangle around the vertex
    return constraint_start[walk.vertex] < constraint_start[walk.vertex + 1] ? CLM_SEED_ON_SEGMENT
                                                                             : t;
  if (walk.edge >= 0) { // on edge a-b of t (of a ghost: its hull edge)
    const int a = tri_vertex[3 * t + next3(walk.edge)], b = tri_vertex[3 * t + prev3(walk.edge)];
    if (is_constraint(constraint_start, constraint_adjacent, a, b))
      return CLM_SEED_ON_SEGMENT;
    if (is_ghost(load_vertices(tri_vertex, t)))
      return link_triangle(tri_neighbor[3 * t + walk.edge]);
  }
  return is_ghost(load_vertices(tri_vertex, t)) ? CLM_SEED_OUTSIDE : t;
}

// Hole seeds: the real triangle holding each seed (seeds outside the hull are
// ignored); on_segment[i] = 1 for a seed ignored as on a segment.
__kernel void seed_from_points(CLM_TRIANGULATION_PARAMS, __global const double2 *seeds,
                               const int start, const int max_steps, __global int *removed,
                               __global int *frontier, volatile __global int *count,
                               __global int *on_segment, const int n) {
  const int i = get_global_id(0);
  if (i >= n)
    return;
  const int t = seed_triangle(CLM_TRIANGULATION_ARGS, seeds[i], start, max_steps);
  on_segment[i] = t == CLM_SEED_ON_SEGMENT;
  if (t >= 0)
    claim(removed, frontier, count, t);
}

// Regional attributes (-A): region r's seed floods its area, bounded by
// constraints; regions are run in order, so a later seed in the same area
// wins. on_segment[region] = 1 for a seed ignored as on a segment.
__kernel void seed_label(CLM_TRIANGULATION_PARAMS, __global const int *removed, const double2 seed,
                         const int start, const int max_steps, const int region,
                         __global int *label, __global int *frontier, volatile __global int *count,
                         __global int *on_segment) {
  if (get_global_id(0) != 0)
    return;
  const int t = seed_triangle(CLM_TRIANGULATION_ARGS, seed, start, max_steps);
  on_segment[region] = t == CLM_SEED_ON_SEGMENT;
  if (t < 0 || removed[t])
    return;
  label[t] = region;
  frontier[atomic_inc(count)] = t;
}

// Whether wave-front triangle t claims its neighbour u (>= 0): for removal
// (region < 0) or for region `region` (a later region takes over an earlier
// one's triangle). Each triangle is claimed once per flood, whatever the order.
static inline bool claim_for_flood(int u, volatile __global int *removed, int region,
                                   volatile __global int *label) {
  return u >= 0 &&
         (region < 0 ? atomic_xchg(&removed[u], 1) == 0 : atomic_xchg(&label[u], region) != region);
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
      if (claim_for_flood(u, removed, region, label))
        claimed[count++] = u;
    }
  }
  volatile __local int scratch[2];
  append_in_group(claimed, count, next_frontier, next_count, scratch);
}

// Waves of a flood by one work-group, for short fronts: spread_flood's waves
// with barriers between them instead of launches (a hole's flood takes as
// many waves as the hole is triangles across). The first front is
// frontier[0 .. n); each wave writes the next into the other list. Stops
// when the front is empty or longer than `limit` (the host goes on with
// spread_flood). result: [0] the front's length, [1] the triangles of the
// waves run, [2] the waves run (odd: the front is in next_frontier).
__kernel void flood_in_group(CLM_TRIANGULATION_PARAMS, __global int *frontier,
                             volatile __global int *removed, const int region,
                             volatile __global int *label, __global int *next_frontier, const int n,
                             const int limit, __global int *result) {
  const int lid = get_local_id(0), size = get_local_size(0);
  volatile __local int next_n[1];
  int front = n, reached = 0, waves = 0;
  while (front > 0 && front <= limit) {
    __global const int *from = waves % 2 ? next_frontier : frontier;
    __global int *to = waves % 2 ? frontier : next_frontier;
    if (lid == 0)
      next_n[0] = 0;
    group_barrier(CLK_LOCAL_MEM_FENCE);
    for (int i = lid; i < front; i += size) {
      const int t = from[i];
      for (int e = 0; e < 3; ++e) {
        const int u = flood_neighbor(tri_vertex, tri_neighbor, constraint_start,
                                     constraint_adjacent, (__global const int *)removed, t, e);
        if (claim_for_flood(u, removed, region, label))
          to[atomic_inc(&next_n[0])] = u;
      }
    }
    group_barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
    reached += front;
    front = next_n[0];
    ++waves;
    group_barrier(CLK_LOCAL_MEM_FENCE); // every work-item has read the length
  }
  if (lid == 0) {
    result[0] = front;
    result[1] = reached;
    result[2] = waves;
  }
}

// -c keeps the convex hull; but a pocket between the segments and the hull
// (the triangles a flood from the hull reaches without crossing a
// constraint: pocket[]) whose triangles are all flat (flat_corners) is a
// sliver made by rounding, a chain of segments a hair inside a hull edge,
// and the chain is the boundary there. seed_thick_pockets closes every
// triangle outside the pockets to a flood (outside[]) and seeds it (label 0)
// with the pocket triangles that are not flat; the flood reaches every
// pocket that has one, and remove_flat_pockets removes the rest.
__kernel void seed_thick_pockets(CLM_TRIANGULATION_PARAMS, __global const int *pocket,
                                 __global int *outside, __global int *label, __global int *frontier,
                                 volatile __global int *count, const int n) {
  const int t = get_global_id(0);
  if (t >= n)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  const bool in_pocket = !is_ghost(tri) && !is_dead(tri) && pocket[t];
  outside[t] = !in_pocket;
  label[t] = -1;
  if (!in_pocket)
    return;
  const double2 p[3] = {points[tri.v[0]], points[tri.v[1]], points[tri.v[2]]};
  if (!flat_corners(p)) {
    label[t] = 0;
    frontier[atomic_inc(count)] = t;
  }
}

__kernel void remove_flat_pockets(__global const int *pocket, __global const int *label,
                                  __global int *removed, volatile __global int *count,
                                  const int n) {
  const int t = get_global_id(0);
  if (t < n && pocket[t] && label[t] < 0) {
    removed[t] = 1;
    atomic_inc(count);
  }
}

// count: the real triangles that are flat (flat_corners), among those
// flagged in among[] (or all of them with every). Among the removed ones:
// the exterior or a hole runs a hair wide between parts of the domain there.
__kernel void count_flat_triangles(CLM_TRIANGULATION_PARAMS, __global const int *among,
                                   const int every, volatile __global int *count, const int n) {
  const int t = get_global_id(0);
  if (t >= n || !(every || among[t]))
    return;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (is_ghost(tri) || is_dead(tri))
    return;
  const double2 p[3] = {points[tri.v[0]], points[tri.v[1]], points[tri.v[2]]};
  if (flat_corners(p))
    atomic_inc(count);
}
