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

#define CLM_INFINITE (-1)
#define CLM_NO_MARK 0xffffffffu

typedef struct {
  int v[3];
} VertexTriple;

inline int next3(int i) { return i == 2 ? 0 : i + 1; }
inline int prev3(int i) { return i == 0 ? 2 : i - 1; }

inline int encode_link(int triangle, int edge) { return (triangle << 2) | edge; }
inline int link_triangle(int link) { return link >> 2; }
inline int link_edge(int link) { return link & 3; }

inline VertexTriple load_vertices(__global const int *tri_vertex, int t) {
  VertexTriple tri;
  tri.v[0] = tri_vertex[3 * t];
  tri.v[1] = tri_vertex[3 * t + 1];
  tri.v[2] = tri_vertex[3 * t + 2];
  return tri;
}

inline void store_triangle(__global int *tri_vertex, __global int *tri_neighbor, int t, int a,
                           int b, int c, int na, int nb, int nc) {
  tri_vertex[3 * t] = a;
  tri_vertex[3 * t + 1] = b;
  tri_vertex[3 * t + 2] = c;
  tri_neighbor[3 * t] = na;
  tri_neighbor[3 * t + 1] = nb;
  tri_neighbor[3 * t + 2] = nc;
}

inline bool is_ghost(VertexTriple tri) {
  return tri.v[0] == CLM_INFINITE || tri.v[1] == CLM_INFINITE || tri.v[2] == CLM_INFINITE;
}

inline int orient_vertices(__global const double2 *points, int a, int b, int c) {
  const double2 pa = points[a], pb = points[b], pc = points[c];
  return clm_orient2d(pa.x, pa.y, pb.x, pb.y, pc.x, pc.y);
}

inline int orient_point(__global const double2 *points, int a, int b, double2 p) {
  const double2 pa = points[a], pb = points[b];
  return clm_orient2d(pa.x, pa.y, pb.x, pb.y, p.x, p.y);
}

// A bijective mix of 32-bit integers: a deterministic pseudo-random priority,
// so that conflict-free rounds do not degrade on sorted input.
inline uint priority_of(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// Triangles rewritten by one split round or flip pass record their slot's
// replacements ("children") and the stamp of that step. A link that points
// at a rewritten slot is resolved by finding, among its children, the triangle
// holding the reversed edge (thesis §3.3.2: neighbours updated in two steps).
#define CLM_CHILDREN 3

// Second step of every topological update: for edge `edge` of triangle t
// (vertices p -> q), find the true neighbour across it and link both sides.
inline void relink_edge(__global const int *tri_vertex, __global int *tri_neighbor,
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

#endif
