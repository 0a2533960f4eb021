// clmesh — the mesh's last steps on the device before its download (thesis
// §3.6.1): ghost triangles, removed ones and empty slots are dropped, the
// real triangles sorted into a canonical order and numbered by it, and the
// neighbour links rewritten to those numbers (-1 on the hull).
#include "common.h"

// Real triangles, less those flagged in removed[] when use_removed (the
// exterior and holes of a CDT).
__kernel void flag_real_triangles(__global const int *tri_vertex, __global const int *removed,
                                  const int use_removed, __global int *is_real, const int n) {
  const int t = get_global_id(0);
  if (t < n)
    is_real[t] = tri_vertex[3 * t] >= 0 && tri_vertex[3 * t + 1] >= 0 &&
                 tri_vertex[3 * t + 2] >= 0 && !(use_removed && removed[t]);
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

// device_of_input[original_id[p]] = p: from input numbers back to slots.
__kernel void invert_numbering(__global const int *original_id, __global int *device_of_input,
                               const int n) {
  const int p = get_global_id(0);
  if (p < n)
    device_of_input[original_id[p]] = p;
}

// Canonical order of the output, so that files depend only on the input and
// not on --grid or the work-group size: each triangle starts at its smallest
// vertex; triangles are grouped by that vertex, the groups in the order of
// its device slot (the Hilbert curve, so that the sort reads memory that lies
// together), and sorted inside a group by their second and third vertices: a
// counting sort on the first vertex's slot (PrefixScan::bucket), then a sort
// of each small bucket, which fixes the order the bucketing's atomic cursor left.
//
// Per device point p: its name in the output, the input index of the
// smallest of its group of identical points (representative, by input
// index), and home[p], the device slot of that point.
__kernel void name_points(__global const int *original_id, __global const int *representative,
                          __global const int *device_of_input, __global int *name,
                          __global int *home, const int n) {
  const int p = get_global_id(0);
  if (p >= n)
    return;
  const int named = representative[original_id[p]];
  name[p] = named;
  home[p] = device_of_input[named];
}

// In place, per slot t: a real triangle's corners by their names
// (name_points), rotated to start at the smallest, its links as the slots
// of real neighbours (-1 for none), and first_slot[t] the home of its
// first corner; first_slot[t] = -1 for the other slots, which the bucketing
// leaves out.
__kernel void canonical_triangles(__global int *tri_vertex, __global int *tri_neighbor,
                                  __global const int *is_real, __global const int *name,
                                  __global const int *home, __global int *first_slot, const int n) {
  const int t = get_global_id(0);
  if (t >= n)
    return;
  if (!is_real[t]) {
    first_slot[t] = -1;
    return;
  }
  const int va = tri_vertex[3 * t], vb = tri_vertex[3 * t + 1], vc = tri_vertex[3 * t + 2];
  const VertexTriple named = {{name[va], name[vb], name[vc]}};
  const int xa = link_triangle(tri_neighbor[3 * t]), xb = link_triangle(tri_neighbor[3 * t + 1]),
            xc = link_triangle(tri_neighbor[3 * t + 2]);
  const int na = is_real[xa] ? xa : -1, nb = is_real[xb] ? xb : -1, nc = is_real[xc] ? xc : -1;
  const int a = named.v[0], b = named.v[1], c = named.v[2];
  const int r = canonical_start(named); // the rotation, spelled out (no private array)
  if (r == 0) {
    first_slot[t] = home[va];
    store_triangle(tri_vertex, tri_neighbor, t, a, b, c, na, nb, nc);
  } else if (r == 1) {
    first_slot[t] = home[vb];
    store_triangle(tri_vertex, tri_neighbor, t, b, c, a, nb, nc, na);
  } else {
    first_slot[t] = home[vc];
    store_triangle(tri_vertex, tri_neighbor, t, c, a, b, nc, na, nb);
  }
}

static inline bool triangle_before(__global const int *out_vertex, int s, int t) {
  const int s1 = out_vertex[3 * s + 1], t1 = out_vertex[3 * t + 1];
  return s1 < t1 || (s1 == t1 && out_vertex[3 * s + 2] < out_vertex[3 * t + 2]);
}

// Moves the root of the max-heap bucket[0 .. size) down to its place.
static inline void sift_down(__global const int *out_vertex, __global int *bucket, int root,
                             int size) {
  const int t = bucket[root];
  for (int child = 2 * root + 1; child < size; child = 2 * root + 1) {
    if (child + 1 < size && triangle_before(out_vertex, bucket[child], bucket[child + 1]))
      ++child;
    if (!triangle_before(out_vertex, t, bucket[child]))
      break;
    bucket[root] = bucket[child];
    root = child;
  }
  bucket[root] = t;
}

// Buckets are small (a vertex's triangles), but not always: the centre of a
// wheel owns them all, so large ones are heap-sorted (O(d log d)).
__kernel void sort_buckets(__global const int *out_vertex, __global const int *bucket_start,
                           __global const int *bucket_size, __global int *order,
                           __global int *position, const int points) {
  const int v = get_global_id(0);
  if (v >= points)
    return;
  const int start = bucket_start[v], size = bucket_size[v];
  __global int *bucket = order + start;
  if (size <= 32) {
    for (int i = 1; i < size; ++i) {
      const int t = bucket[i];
      int j = i - 1;
      while (j >= 0 && triangle_before(out_vertex, t, bucket[j])) {
        bucket[j + 1] = bucket[j];
        --j;
      }
      bucket[j + 1] = t;
    }
  } else {
    for (int root = size / 2 - 1; root >= 0; --root)
      sift_down(out_vertex, bucket, root, size);
    for (int end = size - 1; end > 0; --end) {
      const int top = bucket[0];
      bucket[0] = bucket[end];
      bucket[end] = top;
      sift_down(out_vertex, bucket, 0, end);
    }
  }
  for (int i = 0; i < size; ++i)
    position[bucket[i]] = start + i;
}

// Entry k of the output: the triangle in slot order[k], its neighbours
// renumbered to their output positions (position: per slot).
__kernel void write_sorted(__global const int *order, __global const int *position,
                           __global const int *out_vertex, __global const int *out_neighbor,
                           __global const int *label, const int use_label,
                           __global int *sorted_vertex, __global int *sorted_neighbor,
                           __global int *sorted_label, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int t = order[k];
  if (use_label)
    sorted_label[k] = label[t];
  for (int i = 0; i < 3; ++i) {
    const int m = out_neighbor[3 * t + i];
    sorted_vertex[3 * k + i] = out_vertex[3 * t + i];
    sorted_neighbor[3 * k + i] = m < 0 ? -1 : position[m];
  }
}
