// clmesh — Phase 3 of GPU-DT: shifting the sites back from their pixels to
// their real coordinates (thesis §4.1.2, Phase 3; [QCT12]).
//
// The triangles of Phase 2 join sites as the digital diagram saw them, at
// pixel positions; at the real coordinates a triangle may turn over. Every
// predicate of the mesh reads the real coordinates, so shifting is a check:
// of a triangle that is not strictly counter-clockwise there, the site
// opposite its longest edge is left out of the diagram (it becomes a missing
// point, inserted exactly in Phase 4) and the construction is repeated until
// nothing turns over. Then
// the ghost flips of Phase 5 make the outer cycle convex, and a last check
// proves the result a triangulation of the convex hull of its vertices: all
// triangles counter-clockwise (flips keep them so), every link returned, and
// an outer cycle that turns left or goes straight on at every vertex and
// winds around once (a single lowest vertex). Missing points outside it are
// inserted in Phase 4 like the others, in the ghost triangles.
#include "common.h"

__kernel void flag_inverted_triangles(__global const double2 *points,
                                      __global const int *tri_vertex, __global int *bad,
                                      const int real) {
  const int t = get_global_id(0);
  if (t >= real)
    return;
  const int a = tri_vertex[3 * t], b = tri_vertex[3 * t + 1], c = tri_vertex[3 * t + 2];
  if (orient_vertices(points, a, b, c) > 0)
    return;
  // A turned-over triangle is nearly flat: its middle site, opposite the
  // longest edge, lies on the wrong side of the other two. Leaving out only
  // that one keeps the others, hull sites often, as sites: all three would
  // expose the next layer of a dense hull to the same fate, round after round.
  const double2 pa = points[a], pb = points[b], pc = points[c];
  const double lab = squared_length(pb - pa), lbc = squared_length(pc - pb),
               lca = squared_length(pa - pc);
  if (lab >= lbc && lab >= lca)
    bad[c] = 1;
  else if (lbc >= lca)
    bad[a] = 1;
  else
    bad[b] = 1;
}

// Leaves the flagged sites out of the next diagram, counting them; clears
// the flags.
__kernel void leave_out_flagged_sites(__global int *bad, __global int *site_state,
                                      volatile __global int *count, const int n) {
  const int p = get_global_id(0);
  if (p >= n || !bad[p])
    return;
  bad[p] = 0;
  site_state[p] = CLM_LEFT_OUT;
  atomic_inc(count);
}

static inline bool lexicographically_below(double2 p, double2 q) {
  return p.y < q.y || (p.y == q.y && p.x < q.x);
}

// Counts the vertices of the outer cycle lower (by y, then x) than both
// neighbours on it, and 2 for a vertex where it turns right or back: one in
// all for a convex cycle that winds around once.
__kernel void count_lowest_boundary_vertices(__global const double2 *points,
                                             __global const int *tri_vertex,
                                             __global const int *tri_neighbor,
                                             volatile __global int *count, const int slots) {
  const int t = get_global_id(0);
  if (t >= slots)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (!is_ghost(tri))
    return;
  // This ghost stands on the boundary edge u -> w; the previous one on z -> u.
  const int u = ghost_edge_start(tri), w = ghost_edge_end(tri);
  const int z =
      ghost_edge_start(load_vertices(tri_vertex, adjacent_ghost(tri_neighbor, tri, t, 0)));
  const double2 pz = points[z], pu = points[u], pw = points[w];
  const int turn = clm_orient2d(pz.x, pz.y, pu.x, pu.y, pw.x, pw.y);
  // Straight on: u strictly between z and w (a turn back is no convex cycle).
  const bool between = pz.x != pw.x
                           ? (pz.x < pu.x) == (pu.x < pw.x) && pu.x != pz.x && pu.x != pw.x
                           : (pz.y < pu.y) == (pu.y < pw.y) && pu.y != pz.y && pu.y != pw.y;
  if (turn < 0 || (turn == 0 && !between))
    atomic_add(count, 2); // never one
  else if (lexicographically_below(pu, pz) && lexicographically_below(pu, pw))
    atomic_inc(count);
}

// One incident real triangle per vertex (the smallest slot, so the same on
// every run); vertex_triangle starts at INT_MAX.
__kernel void record_vertex_triangles(__global const int *tri_vertex,
                                      volatile __global int *vertex_triangle, const int slots) {
  const int t = get_global_id(0);
  if (t >= slots)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (is_ghost(tri))
    return;
  for (int i = 0; i < 3; ++i)
    atomic_min(&vertex_triangle[tri.v[i]], t);
}

// Points in no triangle are Phase 4's missing points; each starts its walk
// from a triangle of the site that coloured its pixel.
__kernel void flag_missing_points(__global const int *vertex_triangle, __global const int *pixel_of,
                                  __global const int *voronoi, __global int *location,
                                  __global int *missing, const int n) {
  const int p = get_global_id(0);
  if (p >= n)
    return;
  missing[p] = vertex_triangle[p] == INT_MAX;
  if (missing[p]) {
    const int start = vertex_triangle[voronoi[pixel_of[p]]];
    location[p] = start == INT_MAX ? 0 : start;
  }
}
