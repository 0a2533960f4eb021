// clmesh — device data structure shared by every phase (thesis §2.2).
//
// Triangles are stored as three vertex indices, counter-clockwise, in
// tri_vertex[3t + i], and three neighbour links in tri_neighbor[3t + i]: the
// neighbour opposite vertex i, encoded as (triangle << 2) | (its edge index).
// The mesh is closed by ghost triangles around the symbolic vertex at infinity
// CLM_INFINITE, one per convex-hull edge, so every edge has two triangles and
// points outside the hull are located in a ghost triangle.
#ifndef CLMESH_COMMON_H
#define CLMESH_COMMON_H

#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF

#include "predicates.h"
#include "priority.h"

#define CLM_INFINITE (-1)
#define CLM_NO_MARK 0xffffffffu
// The vertices of an empty slot (a triangle deleted by a 3-1 flip, thesis
// §3.6.1), waiting in the free list.
#define CLM_DEAD (-2)

// Site states of GPU-DT Phases 1-3: a point may colour the digital Voronoi
// diagram, or has been left out of it (a missing point).
#define CLM_SITE 0
#define CLM_LEFT_OUT 1

typedef struct {
  int v[3];
} VertexTriple;

static inline int next3(int i) { return i == 2 ? 0 : i + 1; }
static inline int prev3(int i) { return i == 0 ? 2 : i - 1; }

static inline int encode_link(int triangle, int edge) { return (triangle << 2) | edge; }
static inline int link_triangle(int link) { return link >> 2; }
static inline int link_edge(int link) { return link & 3; }

// The index (0-2) of vertex v in triangle t, or -1.
static inline int index_in(__global const int *tri_vertex, int t, int v) {
  return tri_vertex[3 * t] == v
             ? 0
             : (tri_vertex[3 * t + 1] == v ? 1 : (tri_vertex[3 * t + 2] == v ? 2 : -1));
}

static inline VertexTriple load_vertices(__global const int *tri_vertex, int t) {
  VertexTriple tri;
  tri.v[0] = tri_vertex[3 * t];
  tri.v[1] = tri_vertex[3 * t + 1];
  tri.v[2] = tri_vertex[3 * t + 2];
  return tri;
}

// The index of a triangle's smallest vertex, where its canonical rotation
// starts (the vertex at infinity, negative, counts as the largest).
static inline int canonical_start(VertexTriple tri) {
  const uint a = (uint)tri.v[0], b = (uint)tri.v[1], c = (uint)tri.v[2];
  return a < b ? (a < c ? 0 : 2) : (b < c ? 1 : 2);
}

static inline void store_triangle(__global int *tri_vertex, __global int *tri_neighbor, int t,
                                  int a, int b, int c, int na, int nb, int nc) {
  tri_vertex[3 * t] = a;
  tri_vertex[3 * t + 1] = b;
  tri_vertex[3 * t + 2] = c;
  tri_neighbor[3 * t] = na;
  tri_neighbor[3 * t + 1] = nb;
  tri_neighbor[3 * t + 2] = nc;
}

// Slot k of a batch of new slots: the free list's entries free_first ..
// free_first + free_count - 1 first, then the slots from first_new on (thesis
// §3.6.1: empty slots are reused before the arrays grow). The free list is
// sorted, so the result is deterministic.
static inline int allocate_slot(__global const int *free_list, int free_first, int free_count,
                                int first_new, int k) {
  return k < free_count ? free_list[free_first + k] : first_new + (k - free_count);
}

// Reserves `count` consecutive entries of a list whose length is *total, with
// one global atomic per work-group instead of one per item (a shared counter
// hit by every item serialises the device). Returns the first entry of this
// work-item's range. The ranges' order depends on scheduling: use it only for
// lists whose order cannot reach the output, and for counts. Every work-item
// of the group must call it (it holds barriers); scratch: two __local ints.
static inline int reserve_in_group(int count, volatile __local int *scratch,
                                   volatile __global int *total) {
  if (get_local_id(0) == 0)
    scratch[0] = 0;
  barrier(CLK_LOCAL_MEM_FENCE);
  const int offset = count > 0 ? atomic_add(&scratch[0], count) : 0;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (get_local_id(0) == 0)
    scratch[1] = scratch[0] > 0 ? atomic_add(total, scratch[0]) : 0;
  barrier(CLK_LOCAL_MEM_FENCE);
  return scratch[1] + offset;
}

// Appends this work-item's items[0 .. count) to a worklist whose length is
// *length (reserve_in_group: every work-item of the group must call it).
static inline void append_in_group(const int *items, int count, __global int *list,
                                   volatile __global int *length, volatile __local int *scratch) {
  const int first = reserve_in_group(count, scratch, length);
  for (int k = 0; k < count; ++k)
    list[first + k] = items[k];
}

// The share of work-item gid (of `size`) in the entries [0, n) of a list
// whose length only the device knows (host: sharing_items): entries first,
// first + step, ... below end. On the CPU paths (CLM_ITEMS_IN_TURN: a
// work-group's work-items run one after another) a run of consecutive entries
// each, so that the list and what it leads to are read in order; elsewhere
// every size-th entry, neighbouring work-items reading neighbouring entries.
typedef struct {
  int first, end, step;
} Share;
static inline Share share_of(int gid, int size, int n) {
#ifdef CLM_ITEMS_IN_TURN
  const int run = n / size + (n % size != 0);
  return (Share){min(n, gid * run), min(n, gid * run + run), 1};
#else
  return (Share){gid, n, size};
#endif
}

static inline bool is_dead(VertexTriple tri) { return tri.v[0] == CLM_DEAD; }

static inline bool is_ghost(VertexTriple tri) {
  return tri.v[0] == CLM_INFINITE || tri.v[1] == CLM_INFINITE || tri.v[2] == CLM_INFINITE;
}

// Index (0-2) of the vertex at infinity of a ghost triangle.
static inline int infinite_index(VertexTriple tri) {
  return tri.v[0] == CLM_INFINITE ? 0 : (tri.v[1] == CLM_INFINITE ? 1 : 2);
}

// A ghost stands on the hull edge from its vertex before infinity to its
// vertex after it (counter-clockwise along the hull).
static inline int ghost_edge_start(VertexTriple ghost) {
  return ghost.v[prev3(infinite_index(ghost))];
}
static inline int ghost_edge_end(VertexTriple ghost) {
  return ghost.v[next3(infinite_index(ghost))];
}

// The ghost after ghost g along the hull (after: 1) or before it (after: 0).
static inline int adjacent_ghost(__global const int *tri_neighbor, VertexTriple ghost, int g,
                                 int after) {
  const int k = infinite_index(ghost);
  return link_triangle(tri_neighbor[3 * g + (after ? prev3(k) : next3(k))]);
}

// |v|^2 in plain floating point, no fused multiply-add (FP_CONTRACT OFF).
static inline double squared_length(double2 v) { return v.x * v.x + v.y * v.y; }

// How far apart two points near p and q may lie and still be the same point
// to the arithmetic: four units in the last place of their largest
// coordinate (the noise within which constraint insertion snaps crossings).
static inline double rounding_noise(double2 p, double2 q) {
  return 4 * DBL_EPSILON * fmax(fmax(fabs(p.x), fabs(p.y)), fmax(fabs(q.x), fabs(q.y)));
}

// Are p and q within `noise` of each other (in each coordinate)?
static inline bool indistinct(double2 p, double2 q, double noise) {
  return fabs(p.x - q.x) <= noise && fabs(p.y - q.y) <= noise;
}

// Do corners p[0..2] lie within rounding noise of the line of their longest
// edge? Such a triangle is flat: a sliver made by rounding.
static inline bool flat_corners(const double2 *p) {
  const double2 d1 = p[1] - p[0], d2 = p[2] - p[0], d3 = p[2] - p[1];
  const double twice_area = d1.x * d2.y - d1.y * d2.x;
  const double longest2 = fmax(fmax(squared_length(d1), squared_length(d2)), squared_length(d3));
  // The noise of the largest coordinate among the three corners.
  const double noise = fmax(rounding_noise(p[0], p[1]), rounding_noise(p[1], p[2]));
  return fabs(twice_area) <= noise * sqrt(longest2);
}

static inline int orient_vertices(__global const double2 *points, int a, int b, int c) {
  const double2 pa = points[a], pb = points[b], pc = points[c];
  return clm_orient2d(pa.x, pa.y, pb.x, pb.y, pc.x, pc.y);
}

static inline int orient_point(__global const double2 *points, int a, int b, double2 p) {
  const double2 pa = points[a], pb = points[b];
  return clm_orient2d(pa.x, pa.y, pb.x, pb.y, p.x, p.y);
}

// Is p strictly inside the circumcircle of the real (counter-clockwise)
// triangle tri? Exact.
static inline bool circumcircle_holds(__global const double2 *points, VertexTriple tri, double2 p) {
  const double2 pa = points[tri.v[0]], pb = points[tri.v[1]], pc = points[tri.v[2]];
  return clm_incircle(pa.x, pa.y, pb.x, pb.y, pc.x, pc.y, p.x, p.y) > 0;
}

#define CLM_WALK_LOST 0
#define CLM_WALK_LOCATED 1
#define CLM_WALK_AT_VERTEX 2

typedef struct {
  int outcome;  // CLM_WALK_*
  int triangle; // containing triangle (a ghost: outside the hull)
  int edge;     // -1, or the edge of `triangle` the point lies on
  int vertex;   // the vertex at the point's position (CLM_WALK_AT_VERTEX)
} WalkResult;

// One step of a walk in the real triangle tri: the first edge, counted from
// edge `first`, that separates p from it, or -1 when p is in it (then
// `result` says where: inside, on an edge, or at a vertex).
static inline int edge_to_cross(__global const double2 *points, VertexTriple tri, double2 p,
                                WalkResult *result, int first) {
  int zeros = 0, nonzero = -1, on_edge = -1;
  for (int k = 0; k < 3; ++k) {
    const int i = (first + k) % 3;
    const int side = orient_point(points, tri.v[next3(i)], tri.v[prev3(i)], p);
    if (side < 0)
      return i;
    if (side == 0) {
      ++zeros;
      on_edge = i;
    } else
      nonzero = i;
  }
  if (zeros == 2) { // p coincides with the vertex shared by both edges
    result->outcome = CLM_WALK_AT_VERTEX;
    result->vertex = tri.v[nonzero];
  } else {
    result->outcome = CLM_WALK_LOCATED;
    result->edge = zeros == 1 ? on_edge : -1;
  }
  return -1;
}

// The edge a walk tests first at its step `step` in triangle t: edge 0 for
// its first CLM_PLAIN_STEPS steps, so that short walks are the same as ever;
// then an edge that varies with the step and the triangle. A visibility walk
// that always tests edge 0 first cannot cycle in a Delaunay triangulation, but
// it can in a constrained one (GPU-CDT, refinement); varying the first edge
// breaks such cycles (the stochastic walk of Devillers, Pion and Teillaud,
// made deterministic).
#define CLM_PLAIN_STEPS 64
static inline int first_edge_to_test(int t, int step) {
  return step < CLM_PLAIN_STEPS ? 0 : (int)(((uint)t * 2654435761u ^ (uint)step) % 3u);
}

// Visibility walk from triangle t to point p, stepping across the first edge
// that separates p from the triangle (first_edge_to_test); max_steps guards
// against anything else.
static inline WalkResult walk_to_point(__global const double2 *points,
                                       __global const int *tri_vertex,
                                       __global const int *tri_neighbor, int t, double2 p,
                                       int max_steps) {
  WalkResult result = {CLM_WALK_LOST, t, -1, -1};
  for (int step = 0; step < max_steps; ++step) {
    const VertexTriple tri = load_vertices(tri_vertex, t);
    int cross = -1;
    if (is_ghost(tri)) {
      const int k = infinite_index(tri);
      const int a = tri.v[next3(k)], b = tri.v[prev3(k)];
      const int side = orient_point(points, a, b, p);
      if (side > 0) { // strictly outside hull edge a-b
        result.outcome = CLM_WALK_LOCATED;
        break;
      }
      cross = k;       // back into the hull through the real edge
      if (side == 0) { // on the line of the hull edge: inside the segment it splits the edge
        const double2 pa = points[a], pb = points[b];
        const bool x_axis = pa.x != pb.x;
        const double lo = x_axis ? fmin(pa.x, pb.x) : fmin(pa.y, pb.y),
                     hi = x_axis ? fmax(pa.x, pb.x) : fmax(pa.y, pb.y), q = x_axis ? p.x : p.y;
        if (q > lo && q < hi) {
          result.outcome = CLM_WALK_LOCATED;
          result.edge = k;
          break;
        }
        // Beyond an end (not on it): along the hull to the ghost past that end.
        if (q != lo && q != hi)
          cross = (q > hi) == ((x_axis ? pa.x : pa.y) == hi) ? prev3(k) : next3(k);
      }
    } else {
      cross = edge_to_cross(points, tri, p, &result, first_edge_to_test(t, step));
      if (cross < 0)
        break;
    }
    t = link_triangle(tri_neighbor[3 * t + cross]);
    result.triangle = t;
  }
  return result;
}

// Triangles rewritten by one split round or flip pass record their slot's
// replacements ("children") and the stamp of that step. A link that points
// at a rewritten slot is resolved by finding, among its children, the triangle
// holding the reversed edge (thesis §3.3.2: neighbours updated in two steps).
#define CLM_CHILDREN 3

// Records that slot x was rewritten at `stamp` into the slots c0, c1, c2 (-1: none).
static inline void record_children(__global int *modified_stamp, __global int *children, int x,
                                   int stamp, int c0, int c1, int c2) {
  modified_stamp[x] = stamp;
  children[CLM_CHILDREN * x] = c0;
  children[CLM_CHILDREN * x + 1] = c1;
  children[CLM_CHILDREN * x + 2] = c2;
}

// Second step of every topological update: for edge `edge` of triangle t
// (vertices p -> q), find the true neighbour across it and link both sides.
static inline void relink_edge(__global const int *tri_vertex, __global int *tri_neighbor,
                               __global const int *modified_stamp, __global const int *children,
                               int stamp, int t, int edge) {
  const int link = tri_neighbor[3 * t + edge];
  const int x = link_triangle(link);
  if (modified_stamp[x] != stamp) {
    // The neighbour was not rewritten: its link slot still faces this edge.
    tri_neighbor[3 * x + link_edge(link)] = encode_link(t, edge);
    return;
  }
  const int p = tri_vertex[3 * t + next3(edge)];
  const int q = tri_vertex[3 * t + prev3(edge)];
  for (int k = 0; k < CLM_CHILDREN; ++k) {
    const int y = children[CLM_CHILDREN * x + k];
    if (y < 0)
      continue;
    for (int j = 0; j < 3; ++j) {
      // Edge j of y runs from vertex j+1 to vertex j+2; we need q -> p.
      if (tri_vertex[3 * y + next3(j)] == q && tri_vertex[3 * y + prev3(j)] == p) {
        tri_neighbor[3 * t + edge] = encode_link(y, j);
        return; // y is rewritten too: it links itself back in its own pass
      }
    }
  }
}

// 2-2 flip of edge i of t: t = (c,a,b), u = (d,b,a) across edge a-b become
// t = (a,d,c), u = (b,c,d); edge 0 of both is the new diagonal c-d, edges 1
// and 2 face outwards and keep the links of the old triangles (the outer
// neighbours' links back are the caller's). Returns u.
static inline int flip_pair(__global int *tri_vertex, __global int *tri_neighbor, int t, int i) {
  const int link = tri_neighbor[3 * t + i];
  const int u = link_triangle(link), j = link_edge(link);
  const int c = tri_vertex[3 * t + i], a = tri_vertex[3 * t + next3(i)],
            b = tri_vertex[3 * t + prev3(i)];
  const int t_opp_a = tri_neighbor[3 * t + next3(i)], t_opp_b = tri_neighbor[3 * t + prev3(i)];
  const int d = tri_vertex[3 * u + j];
  const int u_opp_b = tri_neighbor[3 * u + next3(j)], u_opp_a = tri_neighbor[3 * u + prev3(j)];
  store_triangle(tri_vertex, tri_neighbor, t, a, d, c, encode_link(u, 0), t_opp_b, u_opp_b);
  store_triangle(tri_vertex, tri_neighbor, u, b, c, d, encode_link(t, 0), u_opp_a, t_opp_a);
  return u;
}

// flip_pair for a parallel pass: the outer neighbours are relinked afterwards
// with relink_edge.
static inline void flip_edge(__global int *tri_vertex, __global int *tri_neighbor,
                             __global int *modified_stamp, __global int *children, int t, int i,
                             int stamp) {
  const int u = flip_pair(tri_vertex, tri_neighbor, t, i);
  record_children(modified_stamp, children, t, stamp, t, u, -1);
  record_children(modified_stamp, children, u, stamp, u, t, -1);
}

// Is u-v a constraint? The constraints are stored per vertex (both
// directions) in compressed rows: constraint_adjacent[start[u] .. start[u+1]).
static inline bool is_constraint(__global const int *constraint_start,
                                 __global const int *constraint_adjacent, int u, int v) {
  if (u < 0 || v < 0)
    return false;
  for (int k = constraint_start[u]; k < constraint_start[u + 1]; ++k)
    if (constraint_adjacent[k] == v)
      return true;
  return false;
}

// The verdicts of the edge tests of Delaunay flipping (CLM_UNCERTAIN, from
// predicates.h: the floating-point filter could not tell).
#define CLM_KEEP 0
#define CLM_FLIP 1

// The in-circle test of the real edge a-b between (c,a,b) and (d,b,a): the
// floating-point filter, which may answer CLM_UNCERTAIN, or with `exact` the
// exact, perturbed predicate, which never does (thesis §3.6.3: the uncertain
// ones go to a second kernel).
static inline int incircle_verdict(__global const double2 *points, int c, int a, int b, int d,
                                   int exact) {
  const double2 pc = points[c], pa = points[a], pb = points[b], pd = points[d];
  const int inside = exact ? clm_incircle_sos_exact(pc.x, pc.y, pa.x, pa.y, pb.x, pb.y, pd.x, pd.y)
                           : clm_incircle_filter(pc.x, pc.y, pa.x, pa.y, pb.x, pb.y, pd.x, pd.y);
  if (inside == CLM_UNCERTAIN)
    return CLM_UNCERTAIN;
  return inside > 0 ? CLM_FLIP : CLM_KEEP;
}

// Must the edge a-b between triangles (c,a,b) and (d,b,a) flip? Ghost edges
// are decided with the exact orientation test: two ghosts sharing a hull
// vertex flip when that vertex is reflex, real-ghost edges never do, and with
// fixed_boundary (refinement) no ghost edge flips. Constraints never flip
// (constrained: whether the mesh has any; thesis §4.2 step 3). Real edges take
// the in-circle test (incircle_verdict).
static inline int edge_must_flip(__global const double2 *points,
                                 __global const int *constraint_start,
                                 __global const int *constraint_adjacent, int constrained,
                                 int fixed_boundary, int c, int a, int b, int d, int exact) {
  if (fixed_boundary && (a == CLM_INFINITE || b == CLM_INFINITE))
    return CLM_KEEP;     // refinement: the boundary stays as split, convex or not
  if (a == CLM_INFINITE) // ghost-ghost edge at hull vertex b: flip if b is reflex
    return orient_vertices(points, d, b, c) > 0 ? CLM_FLIP : CLM_KEEP;
  if (b == CLM_INFINITE)
    return orient_vertices(points, c, a, d) > 0 ? CLM_FLIP : CLM_KEEP;
  if (c == CLM_INFINITE || d == CLM_INFINITE)
    return CLM_KEEP; // a hull edge: the hull only grows
  if (constrained && is_constraint(constraint_start, constraint_adjacent, a, b))
    return CLM_KEEP;
  return incircle_verdict(points, c, a, b, d, exact);
}

#endif
