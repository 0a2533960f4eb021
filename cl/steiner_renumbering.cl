// clmesh — the final numbering of the Steiner points. Deleted points leave
// empty slots in the point array (thesis §3.6.1); the output numbers the
// survivors densely after the input points.
#include "refinement.h"

// Final numbering: the surviving Steiner points follow the input points in
// slot order (offset: exclusive scan of the survivors among slots first ..);
// the deleted ones take the numbers after them (they are in no triangle).
__kernel void number_steiner_points(__global const int *point_state, __global const int *offset,
                                    const int survivors, __global int *original_id, const int first,
                                    const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int p = first + k;
  original_id[p] =
      point_state[p] != CLM_POINT_DELETED ? first + offset[k] : first + survivors + (k - offset[k]);
}
