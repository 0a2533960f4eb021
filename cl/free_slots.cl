// clmesh — free lists of thesis §3.6.1 (Dealing with variable-size arrays):
// flags of the empty triangle slots and of the deleted points' slots, which
// the host's scan compacts into sorted lists of slots to reuse.
#include "common.h"
#include "refinement.h"

__kernel void flag_dead_triangles(__global const int *tri_vertex, __global int *keep, const int n) {
  const int t = get_global_id(0);
  if (t < n)
    keep[t] = tri_vertex[3 * t] == CLM_DEAD;
}

// keep[k] = whether point first + k is deleted (deleted = 1) or not (deleted = 0).
__kernel void flag_deleted_points(__global const int *point_state, const int deleted,
                                  __global int *keep, const int first, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    keep[k] = (point_state[first + k] == CLM_POINT_DELETED) == deleted;
}
