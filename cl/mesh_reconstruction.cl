// clmesh — a mesh given to refine (Triangle's -r) recovered on the device.
// Its vertices are triangulated by GPU-DT and every edge of its triangles is
// inserted as a constraint by GPU-CDT (thesis chapter 4), so that each of
// its triangles is a triangle of the CDT. This phase finds them: every real
// triangle of the CDT whose corners are those of an input triangle gets
// that triangle's index as its label (the .area bound and attributes it
// passes on); the rest (-1) lie outside the mesh, in its exterior or its
// holes. An input triangle that no CDT triangle matches overlaps another
// one or holds a vertex, which makes the input no triangulation.
// Input triangles come as rows by their smallest corner (device numbering):
// row v lists, for each input triangle whose smallest corner is v, the other
// two corners in counter-clockwise order and the triangle's index; points
// added since the rows were made (where segments cross) have none.
#include "common.h"

// Each real triangle slot t < n: label[t] = the matching input triangle, or
// -1; found[k] = 1 for every input triangle k matched, and *matched counts
// them (each input triangle is matched once at most: the CDT holds no
// triangle twice).
__kernel void match_input_triangles(__global const int *tri_vertex, __global const int *row_start,
                                    __global const int4 *row_entry, __global int *label,
                                    __global int *found, volatile __global int *matched,
                                    const int rows, const int n) {
  const int t = get_global_id(0);
  if (t >= n)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  label[t] = -1;
  if (is_ghost(tri) || is_dead(tri))
    return;
  // The corners from the smallest one, in the triangle's own (counter-
  // clockwise) order.
  int k = 0;
  if (tri.v[1] < tri.v[k])
    k = 1;
  if (tri.v[2] < tri.v[k])
    k = 2;
  const int v = tri.v[k], b = tri.v[next3(k)], c = tri.v[prev3(k)];
  if (v >= rows)
    return;
  for (int i = row_start[v]; i < row_start[v + 1]; ++i) {
    const int4 entry = row_entry[i];
    if (entry.x == b && entry.y == c) {
      label[t] = entry.z;
      found[entry.z] = 1;
      atomic_inc(matched);
      return;
    }
  }
}
