// clmesh — parallel primitives: exclusive scan of counts (slot allocation by
// prefix sums, thesis §3.6.1-3.6.2) and list compaction. Results never
// depend on the work-group size: only its local scratch does.

// Each work-item scans CLM_SCAN_ITEMS consecutive entries on its own; the
// work-group then scans the work-items' sums in local memory, so a block of
// CLM_SCAN_ITEMS x (work-group size) entries costs a handful of barriers.
#define CLM_SCAN_ITEMS 8

#include "group_scan.h"
#include "prefetch.h"

// Exclusive scan of each block; block_sums[g] = block total.
__kernel void scan_blocks(__global const int *in, __global int *out, __global int *block_sums,
                          __local int *scratch, const int n) {
  const int lid = get_local_id(0), size = get_local_size(0);
  const int first = get_global_id(0) * CLM_SCAN_ITEMS;
  int prefix[CLM_SCAN_ITEMS];
  int sum = 0;
  for (int j = 0; j < CLM_SCAN_ITEMS; ++j) {
    prefix[j] = sum;
    sum += first + j < n ? in[first + j] : 0;
  }
  scratch[lid] = sum;
  local_inclusive_scan(scratch, lid, size);
  const int before = scratch[lid] - sum;
  for (int j = 0; j < CLM_SCAN_ITEMS; ++j)
    if (first + j < n)
      out[first + j] = before + prefix[j];
  if (lid == size - 1)
    block_sums[get_group_id(0)] = scratch[lid];
}

// Adds the scanned block offsets to each block of `block` entries.
__kernel void scan_add_offsets(__global int *out, __global const int *block_offsets,
                               const int block, const int n) {
  const int gid = get_global_id(0);
  if (gid < n)
    out[gid] += block_offsets[gid / block];
}

// CPU devices (PrefixScan::Method::runs): a work-group of one work-item per run
// of `run` consecutive entries, each summed, then scanned, by a plain loop.
// A CPU runs a work-group's work-items one after another, so the barriers
// of scan_blocks cost more than the sums; the integer result is the same. run_sum[r] = the sum of
// run r.
__kernel void sum_runs(__global const int *in, __global int *run_sum, const int run, const int n) {
  const int r = get_global_id(0);
  const int first = r * run;
  run_sum[r] = sum_run(in, first, min(first + run, n));
}

// out = exclusive scan of in, run r from the sum of the runs before it (at
// most four a compute unit); the last run writes the total to total[0].
__kernel void scan_runs(__global const int *in, __global int *out, __global const int *run_sum,
                        __global int *total, const int run, const int runs, const int n) {
  const int r = get_global_id(0);
  int before = 0;
  for (int k = 0; k < r; ++k)
    before += run_sum[k];
  const int first = r * run;
  const int sum = scan_run(in, out, first, min(first + run, n), before);
  if (r == runs - 1)
    total[0] = sum;
}

// Stream compaction: out[offset[i]] = list[i] where keep[i] (offset: exclusive scan of keep).
__kernel void compact_list(__global const int *list, __global const int *keep,
                           __global const int *offset, __global int *out, const int n) {
  const int gid = get_global_id(0);
  if (gid < n && keep[gid])
    out[offset[gid]] = list[gid];
}

// Stream compaction of indices: out[offset[i]] = i where keep[i].
__kernel void compact_indices(__global const int *keep, __global const int *offset,
                              __global int *out, const int n) {
  const int gid = get_global_id(0);
  if (gid < n && keep[gid])
    out[offset[gid]] = gid;
}

// Duplicates in a list of slots (negative entries are dropped): each slot
// keeps its first position, found with atomic minimum in marks[] (all
// 0xffffffff outside these kernels, restored by unique_compact), so the list
// kept is the same however the work is scheduled. unique_mark warms the
// marks of the slots a few entries on (prefetch.h).
__kernel void unique_mark(__global const int *list, volatile __global uint *marks, const int n) {
  const int gid = get_global_id(0);
  const int ahead = entry_ahead(list, gid, 1, n);
  if (ahead >= 0)
    warm_for_write(marks + ahead);
  if (gid < n)
    mark_first_entry(list, marks, gid);
}

__kernel void unique_keep(__global const int *list, __global const uint *marks, __global int *keep,
                          const int n) {
  const int gid = get_global_id(0);
  if (gid < n)
    keep[gid] = is_first_entry(list, marks, gid);
}

// out[offset[i]] = list[i] for the kept entries (offset: exclusive scan of
// keep), each clearing its slot's mark: one is kept per distinct slot.
__kernel void unique_compact(__global const int *list, __global const int *keep,
                             __global const int *offset, __global uint *marks, __global int *out,
                             const int n) {
  const int gid = get_global_id(0);
  if (gid < n && keep[gid])
    move_first_entry(list, offset, marks, out, gid);
}

// The same for a short list, by one work-group in one launch
// (group_unique); its length goes to length[0].
__kernel void unique_in_group(__global const int *list, volatile __global uint *marks,
                              __global int *keep, __global int *offset, __global int *out,
                              __local int *scratch, __global int *length, const int n) {
  const int kept = group_unique(list, n, marks, keep, offset, out, scratch);
  if (get_local_id(0) == 0)
    length[0] = kept;
}

// Bucketing (a counting sort's first half): key[i] in [0, buckets) or
// negative (left out). The order inside a bucket comes from the atomic
// cursor, so callers sort each bucket before its order reaches anything.
__kernel void count_keys(__global const int *key, volatile __global int *bucket_size, const int n) {
  const int i = get_global_id(0);
  if (i < n && key[i] >= 0)
    atomic_inc(&bucket_size[key[i]]);
}

__kernel void scatter_by_key(__global const int *key, __global const int *bucket_start,
                             volatile __global int *cursor, __global int *order, const int n) {
  const int i = get_global_id(0);
  if (i < n && key[i] >= 0)
    order[bucket_start[key[i]] + atomic_inc(&cursor[key[i]])] = i;
}
