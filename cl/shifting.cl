// clmesh — Phase 3 of GPU-DT: shifting the sites back from their pixels to
// their real coordinates (thesis §4.1.2, Phase 3; [QCT12]).
//
// The triangles of Phase 2 join sites as the digital diagram saw them, at
// pixel positions; at the real coordinates a triangle may turn over. Every
// predicate of the mesh reads the real coordinates, so shifting is a check,
// and a repair where one flip does it: a turned-over triangle whose middle
// site (opposite its longest edge) has crossed into the triangle beyond that
// edge, or beyond the hull there, is flipped with it (untangling below). Of
// a triangle still turned over, that site is left out of the diagram (it
// becomes a missing point, inserted exactly in Phase 4) and the construction
// is repeated until nothing turns over. Then the ghost flips of Phase 5 make
// the outer cycle convex, and a last check proves the result a triangulation
// of the convex hull of its vertices: all triangles counter-clockwise (flips
// keep them so), every link returned, and an outer cycle that turns left or
// goes straight on at every vertex and winds around once (a single lowest
// vertex). Missing points outside it are inserted in Phase 4 like the
// others, in the ghost triangles.
#include "common.h"

// The corner (0-2) of triangle (a, b, c) opposite its longest edge: of a
// turned-over triangle, which is nearly flat, the site that lies on the wrong
// side of the other two.
static inline int middle_corner(__global const double2 *points, int a, int b, int c) {
  const double2 pa = points[a], pb = points[b], pc = points[c];
  const double lab = squared_length(pb - pa), lbc = squared_length(pc - pb),
               lca = squared_length(pa - pc);
  if (lab >= lbc && lab >= lca)
    return 2;
  return lbc >= lca ? 0 : 1;
}

// Lists the triangles of [0, real) that are not strictly counter-clockwise
// (turned) and counts them. The list's order depends on the schedule; what
// is done with it does not (the claims below).
__kernel void list_turned_triangles(__global const double2 *points, __global const int *tri_vertex,
                                    __global int *turned, volatile __global int *count,
                                    const int real) {
  const int t = get_global_id(0);
  if (t >= real)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (orient_vertices(points, tri.v[0], tri.v[1], tri.v[2]) <= 0)
    turned[atomic_inc(count)] = t;
}

static inline bool is_turned(__global const double2 *points, VertexTriple tri) {
  return !is_ghost(tri) && orient_vertices(points, tri.v[0], tri.v[1], tri.v[2]) <= 0;
}

// Untangling (thesis §4.1.2: "modify the triangulation if necessary"). A
// turned triangle t = (c, a, b) is nearly flat: its middle corner c, opposite
// its longest edge, has crossed a-b. Where c lies strictly inside the real
// triangle u = (d, b, a) beyond a-b, t and u cover the part (b, a, c) of u
// with opposite signs: the flip of a-b into c-d leaves (a, d, c) and
// (b, c, d), both counter-clockwise, covering what the two covered together.
// Where a-b is a hull edge (u a ghost, d at infinity) and c lies strictly
// beyond it, the same flip makes t two ghosts: c joins the hull between a and
// b, and the ghost flips of Phase 5 make the hull convex again. The edge of t
// to flip, or -1.
static inline int untangling_edge(__global const double2 *points, __global const int *tri_vertex,
                                  __global const int *tri_neighbor, int t) {
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (!is_turned(points, tri))
    return -1;
  const int i = middle_corner(points, tri.v[0], tri.v[1], tri.v[2]);
  const int link = tri_neighbor[3 * t + i];
  const int c = tri.v[i], a = tri.v[next3(i)], b = tri.v[prev3(i)];
  const int d = tri_vertex[3 * link_triangle(link) + link_edge(link)];
  if (orient_vertices(points, b, a, c) <= 0)
    return -1;
  if (d == CLM_INFINITE)
    return i;
  return orient_vertices(points, a, d, c) > 0 && orient_vertices(points, d, b, c) > 0 ? i : -1;
}

// A pass of untangling over the turned triangles listed, in four launches:
// the claims of each flip's two slots are reset (reset: 1), then taken with
// the atomic minimum of the turned slot (reset: 0), so that the flips that go
// ahead are disjoint and the same whatever the schedule; the flips that own
// both claims (flip_edge, recording the pass's stamp and the pair as each
// other's children); the outer neighbours relinked (relink_edge).
__kernel void claim_untangling_flips(__global const double2 *points, __global const int *tri_vertex,
                                     __global const int *tri_neighbor, __global const int *turned,
                                     volatile __global int *claim, const int reset,
                                     const int count) {
  const int k = get_global_id(0);
  if (k >= count)
    return;
  const int t = turned[k];
  const int i = untangling_edge(points, tri_vertex, tri_neighbor, t);
  if (i < 0)
    return;
  const int u = link_triangle(tri_neighbor[3 * t + i]);
  if (reset) {
    claim[t] = INT_MAX;
    claim[u] = INT_MAX;
  } else {
    atomic_min(&claim[t], t);
    atomic_min(&claim[u], t);
  }
}

// flips[0] counts the flips.
__kernel void apply_untangling_flips(__global const double2 *points, __global int *tri_vertex,
                                     __global int *tri_neighbor, __global int *modified_stamp,
                                     __global int *children, __global const int *turned,
                                     __global const int *claim, volatile __global int *flips,
                                     const int stamp, const int count) {
  const int k = get_global_id(0);
  if (k >= count)
    return;
  const int t = turned[k];
  // Owning its claim, t is no other flip's; its edge is read only then.
  if (claim[t] != t)
    return;
  const int i = untangling_edge(points, tri_vertex, tri_neighbor, t);
  if (i < 0 || claim[link_triangle(tri_neighbor[3 * t + i])] != t)
    return;
  flip_edge(tri_vertex, tri_neighbor, modified_stamp, children, t, i, stamp);
  atomic_inc(flips);
}

// The outer edges (1 and 2) of both triangles of each flip of the pass.
__kernel void relink_untangled(__global const int *tri_vertex, __global int *tri_neighbor,
                               __global const int *modified_stamp, __global const int *children,
                               __global const int *turned, __global const int *claim,
                               const int stamp, const int count) {
  const int k = get_global_id(0);
  if (k >= count)
    return;
  const int t = turned[k];
  if (claim[t] != t || modified_stamp[t] != stamp)
    return; // no flip of its own this pass
  const int u = children[CLM_CHILDREN * t + 1];
  for (int edge = 1; edge < 3; ++edge) {
    relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, t, edge);
    relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, u, edge);
  }
}

// Flags in `bad` the middle corner of each listed triangle still turned:
// leaving out only that site keeps the others, hull sites often, as sites;
// all three would expose the next layer of a dense hull to the same fate,
// round after round.
__kernel void flag_turned_sites(__global const double2 *points, __global const int *tri_vertex,
                                __global const int *turned, __global int *bad, const int count) {
  const int k = get_global_id(0);
  if (k >= count)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, turned[k]);
  if (!is_turned(points, tri))
    return;
  bad[tri.v[middle_corner(points, tri.v[0], tri.v[1], tri.v[2])]] = 1;
}

// Leaves the flagged sites out of the next diagram, each with every other
// point of its pixel (`diagram` and `pixel_of`: the diagram of this round):
// one of those would take the pixel over and turn the same triangle over
// again, round after round. Counts the flagged sites; `bad` is cleared after.
__kernel void leave_out_flagged_pixels(__global const int *bad, __global int *site_state,
                                       __global const int *diagram, __global const int *pixel_of,
                                       volatile __global int *count, const int n) {
  const int p = get_global_id(0);
  if (p >= n || site_state[p] != CLM_SITE)
    return;
  const int site = diagram[pixel_of[p]]; // p's pixel has a site: p or another of its points
  if (!bad[site])
    return;
  site_state[p] = CLM_LEFT_OUT;
  if (site == p)
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
