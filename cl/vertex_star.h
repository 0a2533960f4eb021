// clmesh — walking the star of a vertex: the triangles around it,
// counter-clockwise, through the neighbour links (thesis §2.2 data structure).
// Shared by flip-flop (§3.3.2) and the boundary routine (§3.4.1).
#ifndef CLMESH_VERTEX_STAR_H
#define CLMESH_VERTEX_STAR_H

#include "common.h"

// The triangle after t counter-clockwise around its vertex p (at index k).
static inline int next_around(__global const int *tri_neighbor, int t, int k) {
  return link_triangle(tri_neighbor[3 * t + next3(k)]);
}

// The neighbour of p that follows it in star triangle s: x_k for star[k].
static inline int star_vertex(__global const int *tri_vertex, int s, int p) {
  return tri_vertex[3 * s + next3(index_in(tri_vertex, s, p))];
}

#endif
