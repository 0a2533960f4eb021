// clmesh — the device's own check of its exact predicates (thesis §3.6.3:
// every orientation and in-circle decision is exact). An OpenCL compiler that
// contracts, reorders or otherwise changes the expansion arithmetic of
// predicates.h breaks exactness only where points are nearly collinear or
// cocircular: meshes come out wrong there, or flipping never ends. So before
// the first mesh the host (runtime/predicate_check.cpp) has the device
// evaluate hard cases and compares each sign with its own.

#include "common.h"

// Case k: points a, b, c, d at coords[8k .. 8k + 8). Five signs each: the
// orientation of a, b, c (filter with exact fallback, then exact alone), the
// in-circle sign of d against a, b, c (filter with exact fallback, then the
// exact stages alone) and the perturbed in-circle sign.
__kernel void evaluate_predicates(__global const double *coords, __global int *signs,
                                  const int cases) {
  const int k = get_global_id(0);
  if (k >= cases)
    return;
  const double ax = coords[8 * k], ay = coords[8 * k + 1], bx = coords[8 * k + 2],
               by = coords[8 * k + 3], cx = coords[8 * k + 4], cy = coords[8 * k + 5],
               dx = coords[8 * k + 6], dy = coords[8 * k + 7];
  signs[5 * k] = clm_orient2d(ax, ay, bx, by, cx, cy);
  signs[5 * k + 1] = clm_orient2d_exact(ax, ay, bx, by, cx, cy);
  signs[5 * k + 2] = clm_incircle(ax, ay, bx, by, cx, cy, dx, dy);
  signs[5 * k + 3] = clm_incircle_after_filter(ax, ay, bx, by, cx, cy, dx, dy);
  signs[5 * k + 4] = clm_incircle_sos(ax, ay, bx, by, cx, cy, dx, dy);
}
