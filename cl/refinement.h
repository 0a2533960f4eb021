// clmesh — per-point state of Delaunay refinement (thesis §3.3.2: pStatus =
// input, oldSteiner, newSteiner, redundant; §3.4.1: midpoints), shared by
// off-center insertion and flip-flop deletion.
#ifndef CLMESH_REFINEMENT_H
#define CLMESH_REFINEMENT_H

#include "common.h"
#include "mesh_params.h"

#define CLM_POINT_INPUT 0
#define CLM_POINT_STEINER 1      // inserted in an earlier iteration
#define CLM_POINT_NEW 2          // off-center inserted in this iteration
#define CLM_POINT_NEW_MIDPOINT 3 // hull midpoint inserted in this iteration
#define CLM_POINT_REDUNDANT 4    // to be deleted by flip-flop
#define CLM_POINT_DELETED 5      // deleted: its slot is free
#define CLM_POINT_MIDPOINT 6     // hull midpoint inserted in an earlier iteration
#define CLM_POINT_ACUTE_HULL 7   // input point at a hull angle below the minimum angle
#define CLM_POINT_HULL 8         // any other input point on the hull

// Hull vertices stay on the hull, segment vertices on their segments: the
// boundary and the segments are fixed during refinement. (Hull here is the
// domain's boundary: the convex hull of a point set, or the segments around a
// PSLG's domain, which stand on ghost triangles as the hull does.) Midpoint
// states mark every vertex added on a segment or hull edge.
static inline bool on_hull(int state) {
  return state == CLM_POINT_HULL || state == CLM_POINT_ACUTE_HULL || state == CLM_POINT_MIDPOINT ||
         state == CLM_POINT_NEW_MIDPOINT;
}

static inline bool is_new_point(int state) {
  return state == CLM_POINT_NEW || state == CLM_POINT_NEW_MIDPOINT;
}

// Is c inside the diametral lens of the edge pa-pb? Triangle's encroachment
// test: c sees the edge at an angle whose cosine squared is at least `lens`
// (cos(2 x minimum angle) squared) while negative.
static inline bool in_lens(double2 pa, double2 pb, double2 c, double lens) {
  const double2 da = pa - c, db = pb - c;
  const double dot = da.x * db.x + da.y * db.y;
  return dot < 0 && dot * dot >= lens * (da.x * da.x + da.y * da.y) * (db.x * db.x + db.y * db.y);
}

// point_segment of a vertex: the segment (an index into segment_end) that a
// vertex added on a segment lies on; for the others one of these.
#define CLM_NO_SEGMENT (-1)    // on no segment, or the end of a single segment
#define CLM_SEGMENT_JOINT (-2) // an input vertex where two or more segments meet

// point_segment where a mesh has segments, else 0: without them every point's
// is CLM_NO_SEGMENT, and the tests and prefetches given 0 read none (for a
// function with the mesh's parameters, CLM_MESH_PARAMS, in scope).
#define CLM_SEGMENTS_IF_ANY (constrained ? point_segment : 0)

// The entry of edge a-b in the constraint rows, or -1.
static inline int constraint_entry(__global const int *constraint_start,
                                   __global const int *constraint_adjacent, int a, int b) {
  for (int k = constraint_start[a]; k < constraint_start[a + 1]; ++k)
    if (constraint_adjacent[k] == b)
      return k;
  return -1;
}

// constraint_segment holds each entry's segment s as it is, or -1 - s once
// refinement has split the segment: then the edge between its ends, should
// flips make one, is an ordinary edge.
static inline int segment_of_entry(__global const int *constraint_segment, int k) {
  const int s = constraint_segment[k];
  return s >= 0 ? s : -1 - s;
}

// Does vertex w, a vertex added on segment s, lie strictly between a and b
// (on s or its ends) along s? Distances from s's first end order them.
static inline bool between_on_segment(__global const double2 *points,
                                      __global const int *point_segment,
                                      __global const int *segment_end, int s, int w, int a, int b) {
  if (w < 0 || point_segment[w] != s)
    return false;
  const double2 origin = points[segment_end[2 * s]];
  const double dw = squared_length(points[w] - origin), da = squared_length(points[a] - origin),
               db = squared_length(points[b] - origin);
  return fmin(da, db) < dw && dw < fmax(da, db);
}

// Is edge a-b, with apexes c and d on its two sides (-1 or a ghost's
// CLM_INFINITE: none), a subsegment: an input segment (as the constraints
// stand after GPU-CDT, compressed rows per vertex) not split since, or a piece
// of one split during refinement? A vertex added on segment s lies on s, so
// an edge from it to s's ends or to another vertex on s runs along s; it is a
// piece of s unless a vertex of s lies between its ends. Rounded split points
// leave s a hair from straight, and flips may join two vertices of s around
// one between them: that vertex is then an apex of the edge.
static inline bool is_subsegment(__global const double2 *points,
                                 __global const int *constraint_start,
                                 __global const int *constraint_adjacent,
                                 __global const int *constraint_segment,
                                 __global const int *point_segment, __global const int *segment_end,
                                 int a, int b, int c, int d) {
  if (a < 0 || b < 0)
    return false;
  const int sa = point_segment[a], sb = point_segment[b];
  int s = -1;
  if (sa >= 0 && sb >= 0)
    s = sa == sb ? sa : -1;
  else if (sa >= 0)
    s = segment_end[2 * sa] == b || segment_end[2 * sa + 1] == b ? sa : -1;
  else if (sb >= 0)
    s = segment_end[2 * sb] == a || segment_end[2 * sb + 1] == a ? sb : -1;
  else {
    const int k = constraint_entry(constraint_start, constraint_adjacent, a, b);
    return k >= 0 && constraint_segment[k] >= 0;
  }
  return s >= 0 && !between_on_segment(points, point_segment, segment_end, s, c, a, b) &&
         !between_on_segment(points, point_segment, segment_end, s, d, a, b);
}

// Is edge i of triangle t (opposite its vertex i) a subsegment? An edge with
// neither end added on a segment and no constraint row at its first end is
// none (is_subsegment's answer, told without reading the triangle across).
static inline bool subsegment_at(CLM_MESH_PARAMS, int t, int i) {
  if (!constrained)
    return false;
  const int a = tri_vertex[3 * t + next3(i)], b = tri_vertex[3 * t + prev3(i)];
  if (a >= 0 && b >= 0 && point_segment[a] < 0 && point_segment[b] < 0 &&
      constraint_start[a] == constraint_start[a + 1])
    return false;
  const int link = tri_neighbor[3 * t + i];
  const int across = tri_vertex[3 * link_triangle(link) + link_edge(link)];
  return is_subsegment(points, constraint_start, constraint_adjacent, constraint_segment,
                       point_segment, segment_end, a, b, tri_vertex[3 * t + i], across);
}

// The segment that subsegment a-b is part of (is_subsegment holds), or -1 for
// a hull edge of a point set.
static inline int segment_of_edge(__global const int *constraint_start,
                                  __global const int *constraint_adjacent,
                                  __global const int *constraint_segment,
                                  __global const int *point_segment, int a, int b) {
  if (point_segment[a] >= 0)
    return point_segment[a];
  if (point_segment[b] >= 0)
    return point_segment[b];
  const int k = constraint_entry(constraint_start, constraint_adjacent, a, b);
  return k >= 0 ? segment_of_entry(constraint_segment, k) : -1;
}

// Refinement splits input segment a-b (both ends input vertices): both of
// its entries in the constraint rows say so.
static inline void mark_segment_split(__global const int *constraint_start,
                                      __global const int *constraint_adjacent,
                                      __global int *constraint_segment, int a, int b) {
  const int ab = constraint_entry(constraint_start, constraint_adjacent, a, b),
            ba = constraint_entry(constraint_start, constraint_adjacent, b, a);
  if (ab >= 0 && constraint_segment[ab] >= 0)
    constraint_segment[ab] = -1 - constraint_segment[ab];
  if (ba >= 0 && constraint_segment[ba] >= 0)
    constraint_segment[ba] = -1 - constraint_segment[ba];
}

#endif
