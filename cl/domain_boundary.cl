// clmesh — the domain of a PSLG as refinement's boundary (the thesis's
// GPU-QM refines within the convex hull, closed by ghost triangles, §2.2 and
// §3.4.1; chapter 4 leaves PSLGs to future work). After GPU-CDT has flagged
// the exterior and the holes (exterior_removal.cl), every edge between a kept
// triangle and a removed one or a ghost gets a ghost of its own, and the
// removed triangles and the old ghosts die. The ghosts close each boundary
// loop of the domain (the outer one and one per hole), so refinement sees the
// domain's boundary as it sees a hull: points outside it are located in a
// ghost, boundary edges split on ghosts, and no flip crosses them.
// New ghosts take slots by prefix sum over the kept triangles, in slot and
// edge order, so the layout is the same on every run.
#include "common.h"
#include "mesh_params.h"
#include "vertex_star.h"

// Is edge e of kept triangle t on the domain's boundary?
static inline bool on_boundary(__global const int *tri_vertex, __global const int *tri_neighbor,
                               __global const int *removed, int t, int e) {
  const int u = link_triangle(tri_neighbor[3 * t + e]);
  return removed[u] || is_ghost(load_vertices(tri_vertex, u));
}

static inline bool is_kept(__global const int *tri_vertex, __global const int *removed, int t) {
  const VertexTriple tri = load_vertices(tri_vertex, t);
  return !removed[t] && !is_dead(tri) && !is_ghost(tri);
}

// How many boundary edges each triangle slot has (0 unless kept).
__kernel void count_boundary_edges(CLM_TRIANGULATION_PARAMS, __global const int *removed,
                                   __global int *boundary_edges, const int n) {
  const int t = get_global_id(0);
  if (t >= n)
    return;
  int count = 0;
  if (is_kept(tri_vertex, removed, t))
    for (int e = 0; e < 3; ++e)
      count += on_boundary(tri_vertex, tri_neighbor, removed, t, e);
  boundary_edges[t] = count;
}

// The ghost slot of boundary edge e of kept triangle t.
static inline int ghost_slot(__global const int *tri_vertex, __global const int *tri_neighbor,
                             __global const int *removed, __global const int *offset,
                             int first_ghost, int t, int e) {
  int rank = 0;
  for (int i = 0; i < e; ++i)
    rank += on_boundary(tri_vertex, tri_neighbor, removed, t, i);
  return first_ghost + offset[t] + rank;
}

// The boundary edge that ends at vertex p next counter-clockwise around p from
// kept triangle t (p at index k), as encode_link(triangle, edge): the ghost on
// it follows the ghost on the edge of t that starts at p.
static inline int boundary_edge_into(__global const int *tri_vertex,
                                     __global const int *tri_neighbor, __global const int *removed,
                                     int t, int p, int max_steps) {
  for (int step = 0; step < max_steps; ++step) {
    const int k = index_in(tri_vertex, t, p);
    if (on_boundary(tri_vertex, tri_neighbor, removed, t, next3(k)))
      return encode_link(t, next3(k));
    t = next_around(tri_neighbor, t, k);
  }
  return -1;
}

// The boundary edge that starts at vertex q next clockwise around q from t.
static inline int boundary_edge_out_of(__global const int *tri_vertex,
                                       __global const int *tri_neighbor,
                                       __global const int *removed, int t, int q, int max_steps) {
  for (int step = 0; step < max_steps; ++step) {
    const int k = index_in(tri_vertex, t, q);
    if (on_boundary(tri_vertex, tri_neighbor, removed, t, prev3(k)))
      return encode_link(t, prev3(k));
    t = link_triangle(tri_neighbor[3 * t + prev3(k)]);
  }
  return -1;
}

// The ghosts: on boundary edge p -> q of kept triangle t (edge e), ghost
// (infinity, q, p): its edge 0 faces t, its edge 1 (p -> infinity) the ghost
// on the boundary edge that ends at p, its edge 2 (infinity -> q) the ghost on
// the one that starts at q. The kept triangles are not changed here (the
// rotations read them); link_kept_triangles turns them to their ghosts.
__kernel void make_ghosts(CLM_TRIANGULATION_PARAMS, __global const int *removed,
                          __global const int *offset, const int first_ghost, const int max_steps,
                          volatile __global int *lost, const int n) {
  const int t = get_global_id(0);
  if (t >= n || !is_kept(tri_vertex, removed, t))
    return;
  for (int e = 0; e < 3; ++e) {
    if (!on_boundary(tri_vertex, tri_neighbor, removed, t, e))
      continue;
    const int g = ghost_slot(tri_vertex, tri_neighbor, removed, offset, first_ghost, t, e);
    const int p = tri_vertex[3 * t + next3(e)], q = tri_vertex[3 * t + prev3(e)];
    const int before = boundary_edge_into(tri_vertex, tri_neighbor, removed, t, p, max_steps);
    const int after = boundary_edge_out_of(tri_vertex, tri_neighbor, removed, t, q, max_steps);
    if (before < 0 || after < 0) {
      atomic_inc(lost);
      continue;
    }
    const int g_before = ghost_slot(tri_vertex, tri_neighbor, removed, offset, first_ghost,
                                    link_triangle(before), link_edge(before));
    const int g_after = ghost_slot(tri_vertex, tri_neighbor, removed, offset, first_ghost,
                                   link_triangle(after), link_edge(after));
    store_triangle(tri_vertex, tri_neighbor, g, CLM_INFINITE, q, p, encode_link(t, e),
                   encode_link(g_before, 2), encode_link(g_after, 1));
  }
}

// Each kept triangle links its boundary edges to their ghosts.
__kernel void link_kept_triangles(CLM_TRIANGULATION_PARAMS, __global const int *removed,
                                  __global const int *offset, const int first_ghost, const int n) {
  const int t = get_global_id(0);
  if (t >= n || !is_kept(tri_vertex, removed, t))
    return;
  int links[3];
  for (int e = 0; e < 3; ++e)
    links[e] =
        on_boundary(tri_vertex, tri_neighbor, removed, t, e)
            ? encode_link(ghost_slot(tri_vertex, tri_neighbor, removed, offset, first_ghost, t, e),
                          0)
            : tri_neighbor[3 * t + e];
  for (int e = 0; e < 3; ++e)
    tri_neighbor[3 * t + e] = links[e];
}

// The removed triangles and the old ghosts die (their slots are empty, as
// those of refinement's deletions, thesis §3.6.1); with keep_ghosts (nothing
// removed, DomainBoundary::keep_hull) the ghosts stay. owner[v] is set to the
// smallest kept triangle at each vertex.
__kernel void retire_exterior(CLM_TRIANGULATION_PARAMS, __global const int *removed,
                              const int keep_ghosts, volatile __global int *owner, const int n) {
  const int t = get_global_id(0);
  if (t >= n)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (is_dead(tri) || (keep_ghosts && is_ghost(tri)))
    return;
  if (removed[t] || is_ghost(tri)) {
    store_triangle(tri_vertex, tri_neighbor, t, CLM_DEAD, CLM_DEAD, CLM_DEAD, -1, -1, -1);
    return;
  }
  for (int i = 0; i < 3; ++i)
    atomic_min(&owner[tri.v[i]], t);
}

// Every vertex of the domain points at a kept triangle.
__kernel void point_at_kept_triangles(CLM_TRIANGULATION_PARAMS, __global const int *owner,
                                      const int n) {
  const int v = get_global_id(0);
  if (v < n && owner[v] != 0x7fffffff)
    vertex_triangle[v] = owner[v];
}
