// clmesh — final stream compaction before download (thesis §3.6.1): ghost
// triangles and empty slots are dropped, real triangles renumbered by a prefix
// sum, and neighbour links rewritten to the new numbers (-1 on the hull).
#include "common.h"

__kernel void flag_real_triangles(__global const int *tri_vertex, __global int *is_real,
                                  const int n) {
  const int t = get_global_id(0);
  if (t < n)
    is_real[t] = tri_vertex[3 * t] >= 0 && tri_vertex[3 * t + 1] >= 0 && tri_vertex[3 * t + 2] >= 0;
}

__kernel void write_real_triangles(__global const int *tri_vertex, __global const int *tri_neighbor,
                                   __global const int *is_real, __global const int *new_index,
                                   __global int *out_vertex, __global int *out_neighbor,
                                   const int n) {
  const int t = get_global_id(0);
  if (t >= n || !is_real[t])
    return;
  const int o = new_index[t];
  for (int i = 0; i < 3; ++i) {
    const int x = link_triangle(tri_neighbor[3 * t + i]);
    out_vertex[3 * o + i] = tri_vertex[3 * t + i];
    out_neighbor[3 * o + i] = is_real[x] ? new_index[x] : -1;
  }
}

__kernel void fill_identity(__global int *out, const int n) {
  const int i = get_global_id(0);
  if (i < n)
    out[i] = i;
}

// Points live on the device in spatial order; duplicate_of goes back to the
// input numbering (original_id[internal] = input index).
__kernel void restore_input_numbering(__global const int *duplicate_of,
                                      __global const int *original_id,
                                      __global int *input_duplicate_of, const int n) {
  const int i = get_global_id(0);
  if (i >= n)
    return;
  const int d = duplicate_of[i];
  input_duplicate_of[original_id[i]] = d >= 0 ? original_id[d] : -1;
}

// Among points with identical coordinates the smallest index stands for the
// group, whichever of them the insertion happened to keep.
__kernel void smallest_representative(__global const int *duplicate_of,
                                      volatile __global int *representative, const int n) {
  const int i = get_global_id(0);
  if (i < n && duplicate_of[i] >= 0)
    atomic_min(&representative[duplicate_of[i]], i);
}

__kernel void redirect_duplicates(__global int *duplicate_of, __global const int *representative,
                                  const int n) {
  const int i = get_global_id(0);
  if (i >= n)
    return;
  const int kept = duplicate_of[i] >= 0 ? duplicate_of[i] : i;
  const int smallest = representative[kept];
  duplicate_of[i] = smallest == i ? -1 : smallest;
}

__kernel void rename_vertices(__global int *out_vertex, __global const int *original_id,
                              __global const int *representative, const int n) {
  const int i = get_global_id(0);
  if (i < n)
    out_vertex[i] = representative[original_id[out_vertex[i]]];
}
