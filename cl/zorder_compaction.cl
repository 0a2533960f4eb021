// clmesh — compaction of the triangle and Steiner point arrays (thesis §3.6.1
// collects the empty slots; here the live ones also move into spatial
// order, so that a triangle's neighbours share its cache lines: the
// refinement's kernels are bound by those random accesses on a CPU).
//
// Each live triangle gets the cell of its centre on a Z-order curve over the
// bounding box (2^bits cells a side, scale: cells per unit); the host buckets
// them by cell (PrefixScan::bucket), each cell is sorted (sort_cells), and the
// triangles move there. The Steiner points follow likewise.
#include "common.h"
#include "mesh_params.h"
#include "prefetch.h"
#include "refinement.h"

static inline uint spread_bits(uint x) { // bit i of x to bit 2i
  x &= 0xffffu;
  x = (x | (x << 8)) & 0x00ff00ffu;
  x = (x | (x << 4)) & 0x0f0f0f0fu;
  x = (x | (x << 2)) & 0x33333333u;
  return (x | (x << 1)) & 0x55555555u;
}

static inline int cell_coordinate(double x, double low, double scale, int bits) {
  return clamp((int)((x - low) * scale), 0, (1 << bits) - 1);
}

static inline int z_cell(double2 p, double2 low, double scale, int bits) {
  return (int)(spread_bits((uint)cell_coordinate(p.x, low.x, scale, bits)) |
               (spread_bits((uint)cell_coordinate(p.y, low.y, scale, bits)) << 1));
}

// The triangles leave the compaction in a layout that depends on the mesh
// alone, not on the slots it came in (so refinement, which breaks ties by
// slot, gives the same mesh whichever construction built the first
// triangulation): each triangle starts at its smallest vertex (the vertex at
// infinity counts as the largest), and a cell's triangles go in the order of
// their first two vertices, a directed edge that no other triangle starts with.
// (The output's canonical order, mesh_output.cl, starts triangles likewise.)
static inline VertexTriple rotated_by(VertexTriple tri, int r) {
  const int a = tri.v[0], b = tri.v[1], c = tri.v[2];
  VertexTriple rotated; // rotated.v[i] = tri.v[(i + r) % 3], without private indexing
  rotated.v[0] = r == 0 ? a : (r == 1 ? b : c);
  rotated.v[1] = r == 0 ? b : (r == 1 ? c : a);
  rotated.v[2] = r == 0 ? c : (r == 1 ? a : b);
  return rotated;
}

// cell[t]: the Z-order cell of triangle t, -1 for an empty slot; key[t]: its
// place inside the cell, the first two vertices after the rotation (a point
// number is below 2^30, so the first fits 30 bits), then the rotation.
__kernel void triangle_cells(__global const double2 *points, __global const int *tri_vertex,
                             const double2 low, const double scale, const int bits,
                             __global int *cell, __global ulong *key, const int n) {
  const int t = get_global_id(0);
  warm_corners(points, 0, tri_vertex, slot_ahead(t, 1, n)); // prefetching (prefetch.h)
  if (t >= n)
    return;
  VertexTriple tri = load_vertices(tri_vertex, t);
  if (is_dead(tri)) {
    cell[t] = -1;
    return;
  }
  const int r = canonical_start(tri);
  tri = rotated_by(tri, r);
  double2 sum = (double2)(0, 0); // of the real vertices (two for a ghost)
  int real = 0;
  for (int i = 0; i < 3; ++i)
    if (tri.v[i] >= 0) {
      sum += points[tri.v[i]];
      ++real;
    }
  cell[t] = z_cell(sum / (double)real, low, scale, bits);
  key[t] = ((ulong)tri.v[0] << 34) | ((ulong)(uint)tri.v[1] << 2) | (ulong)r;
}

// The Steiner points move likewise (their triangles' loads of points and
// states follow): cell[k] of point first + k, -1 for a deleted one. The
// input points keep their slots, hence their numbers; key[k]: the slot (a
// cell's points keep their order).
__kernel void steiner_point_cells(__global const double2 *points, __global const int *point_state,
                                  const double2 low, const double scale, const int bits,
                                  __global int *cell, __global ulong *key, const int first,
                                  const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  cell[k] = point_state[first + k] == CLM_POINT_DELETED
                ? -1
                : z_cell(points[first + k], low, scale, bits);
  key[k] = (ulong)k;
}

// Moves a[root] down the max-heap a[0 .. size), ordered by key[a[i]], to its place.
static inline void sift_down_by_key(__global int *a, __global const ulong *key, int root,
                                    int size) {
  const int x = a[root];
  const ulong x_key = key[x];
  for (int child = 2 * root + 1; child < size; child = 2 * root + 1) {
    if (child + 1 < size && key[a[child]] < key[a[child + 1]])
      ++child;
    if (key[a[child]] <= x_key)
      break;
    a[root] = a[child];
    root = child;
  }
  a[root] = x;
}

// Sorts a[0 .. size) by key[a[i]] ascending: insertion sort when short, else
// heap sort (a crowded cell must not cost its size squared).
static inline void sort_by_key(__global int *a, __global const ulong *key, int size) {
  if (size <= 32) {
    for (int i = 1; i < size; ++i) {
      const int x = a[i];
      const ulong x_key = key[x];
      int j = i - 1;
      for (; j >= 0 && key[a[j]] > x_key; --j)
        a[j + 1] = a[j];
      a[j + 1] = x;
    }
    return;
  }
  for (int root = size / 2 - 1; root >= 0; --root)
    sift_down_by_key(a, key, root, size);
  for (int end = size - 1; end > 0; --end) {
    const int top = a[0];
    a[0] = a[end];
    a[end] = top;
    sift_down_by_key(a, key, 0, end);
  }
}

// new_slot[item] for the items of each cell, in the order of their keys:
// the new place, or with `rotated` (triangles) the new place and the
// rotation (key's low two bits) as a link, (place << 2) | rotation.
__kernel void sort_cells(__global const int *cell_start, __global const int *cell_size,
                         __global const ulong *key, const int rotated, __global int *order,
                         __global int *new_slot, const int cells) {
  const int c = get_global_id(0);
  if (c >= cells)
    return;
  const int start = cell_start[c], size = cell_size[c];
  sort_by_key(order + start, key, size);
  for (int i = 0; i < size; ++i) {
    const int item = order[start + i];
    new_slot[item] = rotated ? encode_link(start + i, (int)(key[item] & 3)) : start + i;
  }
}

// Triangle order[k] moves to slot k, rotated to start at its smallest vertex
// (new_slot: (slot << 2) | rotation of every old slot), with its region and,
// when flagged, its flag (slot_flag, one per slot).
__kernel void move_triangles(__global const int *order, __global const int *new_slot,
                             __global const int *tri_vertex, __global const int *tri_neighbor,
                             __global const int *tri_region, const int regional,
                             __global const int *slot_flag, const int flagged,
                             __global const double *slot_value, const int valued,
                             __global int *moved_vertex, __global int *moved_neighbor,
                             __global int *moved_region, __global int *moved_flag,
                             __global double *moved_value, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int t = order[k];
  if (regional)
    moved_region[k] = tri_region[t];
  if (flagged)
    moved_flag[k] = slot_flag[t];
  if (valued)
    moved_value[k] = slot_value[t];
  const int r = link_edge(new_slot[t]);
  for (int i = 0; i < 3; ++i) { // new index i, old index (i + r) % 3
    const int link = tri_neighbor[3 * t + (i + r) % 3];
    const int u = new_slot[link_triangle(link)];
    moved_vertex[3 * k + i] = tri_vertex[3 * t + (i + r) % 3];
    moved_neighbor[3 * k + i] =
        encode_link(link_triangle(u), (link_edge(link) + 3 - link_edge(u)) % 3);
  }
}

// Every point q < n of the new arrays takes its coordinates, state,
// insertion radius, priority and segment from point p: itself for an input point
// (q < first), first + order[q - first] for a Steiner point.
__kernel void move_steiner_points(CLM_MESH_PARAMS, __global const int *order,
                                  __global double2 *moved_point, __global int *moved_state,
                                  __global double *moved_radius2, __global uint *moved_priority,
                                  __global int *moved_segment, const int first, const int n) {
  const int q = get_global_id(0);
  if (q >= n)
    return;
  const int p = q < first ? q : first + order[q - first];
  moved_point[q] = points[p];
  moved_state[q] = point_state[p];
  moved_radius2[q] = insertion_radius2[p];
  moved_priority[q] = point_priority[p];
  moved_segment[q] = point_segment[p];
  if (q >= first)
    original_id[q] = q; // numbered again at the end (number_steiner_points)
}

// The triangles' Steiner vertices take their new slots (new_slot[k]: of
// point first + k, relative to first).
__kernel void renumber_steiner_vertices(__global const int *new_slot, __global int *tri_vertex,
                                        const int first, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int v = tri_vertex[k];
  if (v >= first)
    tri_vertex[k] = first + new_slot[v - first];
}
