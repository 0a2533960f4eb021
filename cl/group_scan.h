// clmesh — prefix sums inside one work-group (thesis §3.6.1-3.6.2: slots
// and list positions come from prefix sums). Every work-item of the group
// must call these, with the same arguments.
#ifndef CLMESH_GROUP_SCAN_H
#define CLMESH_GROUP_SCAN_H

// The barrier of a kernel that runs as one work-group (host:
// Device::single_group; step_one_in_group, flipflop_passes_in_group, ...)
// and of the helpers below that only such kernels call. On the CPU paths
// (CLM_ITEMS_IN_TURN) that group is one work-item, which has nothing to
// wait for: the barrier is left out. With it, PoCL compiled those kernels
// for every group size when clmesh's program cache asked for the program's
// binary, about 40 s of a machine's first run for the two named above.
#ifdef CLM_ITEMS_IN_TURN
#define group_barrier(flags) ((void)0)
#else
#define group_barrier(flags) barrier(flags)
#endif

// Hillis-Steele inclusive scan of scratch[0 .. size), one entry per work-item.
static inline void local_inclusive_scan(__local int *scratch, int lid, int size) {
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int offset = 1; offset < size; offset <<= 1) {
    const int add = lid >= offset ? scratch[lid - offset] : 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    scratch[lid] += add;
    barrier(CLK_LOCAL_MEM_FENCE);
  }
}

// A run of consecutive entries, by one work-item: the sum of in[first ..
// end), and its exclusive scan from `running` into out (returns the sum
// after the run; each entry is read before out is written).
static inline int sum_run(__global const int *in, int first, int end) {
  int sum = 0;
  for (int i = first; i < end; ++i)
    sum += in[i];
  return sum;
}

static inline int scan_run(__global const int *in, __global int *out, int first, int end,
                           int running) {
  for (int i = first; i < end; ++i) {
    const int count = in[i];
    out[i] = running;
    running += count;
  }
  return running;
}

// out[i] = in[0] + .. + in[i - 1] for i < n, by the whole group (each
// work-item a run of consecutive entries); returns the total to all.
static inline int group_exclusive_scan(__global const int *in, __global int *out, int n,
                                       __local int *scratch) {
#ifdef CLM_ITEMS_IN_TURN // one work-item (group_barrier): its run is the scan
  return scan_run(in, out, 0, n, 0);
#else
  const int lid = get_local_id(0), size = get_local_size(0);
  const int run = (n + size - 1) / size;
  const int first = min(lid * run, n), end = min(first + run, n);
  const int sum = sum_run(in, first, end);
  scratch[lid] = sum;
  local_inclusive_scan(scratch, lid, size);
  const int total = scratch[size - 1];
  scan_run(in, out, first, end, scratch[lid] - sum);
  barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE); // scratch free, out visible
  return total;
#endif
}

// Duplicate removal (PrefixScan::unique): the first entry of each slot
// takes the slot's mark, is kept, and clears the mark as it moves to its place.
static inline void mark_first_entry(__global const int *list, volatile __global uint *marks,
                                    int i) {
  if (list[i] >= 0)
    atomic_min(&marks[list[i]], (uint)i);
}

static inline int is_first_entry(__global const int *list, __global const uint *marks, int i) {
  return list[i] >= 0 && marks[list[i]] == (uint)i;
}

static inline void move_first_entry(__global const int *list, __global const int *offset,
                                    __global uint *marks, __global int *out, int i) {
  out[offset[i]] = list[i];
  marks[list[i]] = 0xffffffffu;
}

// The same inside one group: out receives list[0 .. n) without negative
// entries and repeats, in list order; marks (all clear before and after) and
// keep/offset are scratch. Returns the length.
static inline int group_unique(__global const int *list, int n, volatile __global uint *marks,
                               __global int *keep, __global int *offset, __global int *out,
                               __local int *scratch) {
  const int lid = get_local_id(0), size = get_local_size(0);
  for (int i = lid; i < n; i += size)
    mark_first_entry(list, marks, i);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int i = lid; i < n; i += size)
    keep[i] = is_first_entry(list, (__global const uint *)marks, i);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int kept = group_exclusive_scan(keep, offset, n, scratch);
  for (int i = lid; i < n; i += size)
    if (keep[i])
      move_first_entry(list, offset, (__global uint *)marks, out, i);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  return kept;
}

#endif
