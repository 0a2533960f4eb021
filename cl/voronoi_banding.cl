// clmesh — Phase 1 of GPU-DT: the digital Voronoi diagram by the parallel
// banding algorithm (thesis §4.1.2, ref. [CTMT10]: Cao, Tang, Mohamed, Tan,
// "Parallel Banding Algorithm to compute exact distance transform with the
// GPU", I3D 2010). Points are mapped to a grid x grid texture; a pixel shared
// by several points keeps the one nearest its centre as its site and the
// others become missing points. Then (1) every column is swept to find each pixel's nearest
// site in that column, (2) every row builds the stack of its proximate sites
// (those whose Voronoi region meets the row) from the column results, and (3)
// colours its pixels by walking that stack. Ties are broken the same way on
// every device, so the diagram is deterministic. Integer arithmetic only.
#include "common.h"

#define CLM_NO_SITE (-1)

// Pixel of a point, and how far the point lies from the pixel's centre (its
// squared distance in pixel units, in fixed point).
static inline int pixel_and_centre_distance(double2 q, double min_x, double min_y, double scale,
                                            int grid, int *pixel) {
  const double fx = (q.x - min_x) * scale, fy = (q.y - min_y) * scale;
  const int x = min((int)fx, grid - 1), y = min((int)fy, grid - 1);
  *pixel = y * grid + x;
  const double dx = fx - (x + 0.5), dy = fy - (y + 0.5);
  return (int)(min(dx * dx + dy * dy, 64.0) * (double)(1 << 24));
}

// Pixel of each point, and atomic minimum per pixel of the distance of its
// points to its centre (points left out take no pixel; site_state may be
// absent: use_state == 0). best_distance starts at INT_MAX.
__kernel void map_points_to_pixels(__global const double2 *points, __global const int *site_state,
                                   const int use_state, __global int *pixel_of,
                                   volatile __global int *best_distance, const double min_x,
                                   const double min_y, const double scale, const int grid,
                                   const int n) {
  const int p = get_global_id(0);
  if (p >= n)
    return;
  int pixel;
  const int distance = pixel_and_centre_distance(points[p], min_x, min_y, scale, grid, &pixel);
  pixel_of[p] = pixel;
  if (!use_state || site_state[p] == CLM_SITE)
    atomic_min(&best_distance[pixel], distance);
}

// A pixel's site is the point nearest its centre (the smallest index among
// equals), so that the digital diagram is close to the real one and few
// triangles turn over when the sites move back (Phase 3).
__kernel void claim_pixels(__global const double2 *points, __global const int *site_state,
                           const int use_state, __global const int *best_distance,
                           volatile __global int *site_of_pixel, const double min_x,
                           const double min_y, const double scale, const int grid, const int n) {
  const int p = get_global_id(0);
  if (p >= n || (use_state && site_state[p] != CLM_SITE))
    return;
  int pixel;
  const int distance = pixel_and_centre_distance(points[p], min_x, min_y, scale, grid, &pixel);
  if (distance == best_distance[pixel])
    atomic_min(&site_of_pixel[pixel], p);
}

// site_of_pixel starts at INT_MAX; empty pixels become CLM_NO_SITE.
__kernel void clear_empty_pixels(__global int *site_of_pixel, const int pixels) {
  const int i = get_global_id(0);
  if (i < pixels && site_of_pixel[i] == 0x7fffffff)
    site_of_pixel[i] = CLM_NO_SITE;
}

// A point whose pixel kept another point is a missing point of phase 1.
__kernel void count_missing_points(__global const int *pixel_of, __global const int *site_of_pixel,
                                   __global int *missing, const int n) {
  const int p = get_global_id(0);
  if (p < n)
    missing[p] = site_of_pixel[pixel_of[p]] != p;
}

// Step 1 (one work-item per column): nearest site of each pixel within its
// column, by a sweep up and a sweep down. column_site holds the site's row.
__kernel void column_sweep(__global const int *site_of_pixel, __global int *column_site_row,
                           const int grid) {
  const int x = get_global_id(0);
  if (x >= grid)
    return;
  int last = -1;
  for (int y = 0; y < grid; ++y) {
    if (site_of_pixel[y * grid + x] != CLM_NO_SITE)
      last = y;
    column_site_row[y * grid + x] = last;
  }
  int next = -1;
  for (int y = grid - 1; y >= 0; --y) {
    if (site_of_pixel[y * grid + x] != CLM_NO_SITE)
      next = y;
    const int below = column_site_row[y * grid + x];
    // The nearer of the sites below and above; a tie goes to the lower one.
    if (next >= 0 && (below < 0 || next - y < y - below))
      column_site_row[y * grid + x] = next;
  }
}

// Is the middle site b (column bx) hidden on row y by its neighbours a and c
// (ax < bx < cx)? True when the a|b bisector meets the row no left of the b|c one.
static inline bool dominated(long ax, long ay, long bx, long by, long cx, long cy, long y) {
  const long ab = (bx * bx - ax * ax) + (by - y) * (by - y) - (ay - y) * (ay - y);
  const long bc = (cx * cx - bx * bx) + (cy - y) * (cy - y) - (by - y) * (by - y);
  return ab * (cx - bx) >= bc * (bx - ax);
}

static inline long squared_distance(long x, long y, long sx, long sy) {
  return (x - sx) * (x - sx) + (y - sy) * (y - sy);
}

// Steps 2 and 3 (one work-item per row): proximate sites, then colouring.
// stack_x/stack_y are scratch rows of the texture size.
__kernel void row_proximate_and_colour(__global const int *site_of_pixel,
                                       __global const int *column_site_row, __global int *stack_x,
                                       __global int *stack_y, __global int *voronoi,
                                       const int grid) {
  const int y = get_global_id(0);
  if (y >= grid)
    return;
  __global int *sx = stack_x + y * grid;
  __global int *sy = stack_y + y * grid;
  int top = 0;
  for (int x = 0; x < grid; ++x) {
    const int row = column_site_row[y * grid + x];
    if (row < 0)
      continue;
    while (top >= 2 && dominated(sx[top - 2], sy[top - 2], sx[top - 1], sy[top - 1], x, row, y))
      --top;
    sx[top] = x;
    sy[top] = row;
    ++top;
  }
  int k = 0;
  for (int x = 0; x < grid; ++x) {
    if (top == 0) {
      voronoi[y * grid + x] = CLM_NO_SITE;
      continue;
    }
    while (k + 1 < top &&
           squared_distance(x, y, sx[k + 1], sy[k + 1]) < squared_distance(x, y, sx[k], sy[k]))
      ++k;
    voronoi[y * grid + x] = site_of_pixel[sy[k] * grid + sx[k]];
  }
}

// The diagram in the input numbering, for pictures.
__kernel void voronoi_input_numbering(__global const int *voronoi, __global const int *original_id,
                                      __global int *out, const int pixels) {
  const int i = get_global_id(0);
  if (i < pixels)
    out[i] = voronoi[i] < 0 ? -1 : original_id[voronoi[i]];
}
