// clmesh — size control beyond -a (not in the thesis, whose GPU-QM bounds
// angles and one area, §3.3): each triangle slot's own area bound, set when
// the slot is (re)written and read by the bad-triangle test
// (offcenter_insertion.cl, area_bound_of). From background meshes the
// device evaluates at the triangle's centroid: a sizing field's target
// areas interpolated linearly, or a refined mesh's maximum area per
// triangle (-r's .area) taken from the triangle that holds the centroid;
// the background triangle is found through a grid of cells, each listing
// the background triangles its box meets (an empty cell: those of the
// nearest cell that has some), or for -r's .area by a walk from the given
// triangle the slot descends from. Or from a user's callback on the host: the
// corners gathered here, the answers scattered back.
#include "common.h"
#include "prefetch.h"

// The slot of entry i: list[i] (use_list), else i; -1 for none.
static inline int slot_of(__global const int *list, int use_list, int i) {
  return use_list ? list[i] : i;
}

// The tighter of two area bounds (<= 0: none).
static inline double tighter(double a, double b) {
  if (b <= 0)
    return a;
  return a > 0 ? fmin(a, b) : b;
}

// The barycentric coordinates of p in background triangle k (l[0..2]);
// returns the smallest.
static inline double barycentric(double2 p, __global const double2 *field_points,
                                 __global const int *field_triangles, int k, double *l) {
  const double2 a = field_points[field_triangles[3 * k]],
                b = field_points[field_triangles[3 * k + 1]],
                c = field_points[field_triangles[3 * k + 2]];
  const double twice = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  l[0] = ((b.x - p.x) * (c.y - p.y) - (b.y - p.y) * (c.x - p.x)) / twice;
  l[1] = ((c.x - p.x) * (a.y - p.y) - (c.y - p.y) * (a.x - p.x)) / twice;
  l[2] = 1 - l[0] - l[1];
  return fmin(l[0], fmin(l[1], l[2]));
}

// Steps of the walk from a slot's given triangle (field_at).
#define CLM_FIELD_WALK 8

// The background at p: among the cell's background triangles, the one whose
// smallest barycentric coordinate of p is largest (the one holding p, or
// the nearest), first on ties; its value (per_triangle), else the values of
// its corners interpolated, its coordinates clamped to its edges. The
// arithmetic of clmesh::size_at on the host. Per triangle, `hint` (>= 0: the
// given triangle the slot descends from, which usually holds p) is tried
// first, then a walk from it across the edge p lies farthest beyond
// (`across`: the neighbours), which takes a triangle holding p strictly
// inside; a walk that leaves the mesh or takes too many steps leaves p to
// the cell. *walked: the triangle the walk took, else -1.
static inline double field_at(double2 p, __global const double2 *field_points,
                              __global const double *field_area, int per_triangle,
                              __global const int *field_triangles, __global const int *across,
                              __global const int *cell_start, __global const int *cell_entry,
                              double4 grid, int columns, int rows, int hint, int *walked) {
  *walked = -1;
  double l[3];
  if (per_triangle && hint >= 0) {
    if (barycentric(p, field_points, field_triangles, hint, l) >= 0)
      return field_area[hint];
    int k = hint;
    for (int step = 0; step < CLM_FIELD_WALK; ++step) {
      const int beyond = l[0] <= l[1] && l[0] <= l[2] ? 0 : (l[1] <= l[2] ? 1 : 2);
      k = across[3 * k + beyond];
      if (k < 0)
        break;
      if (barycentric(p, field_points, field_triangles, k, l) > 0) {
        *walked = k;
        return field_area[k];
      }
    }
  }
  const int column = clamp((int)floor((p.x - grid.x) * grid.z), 0, columns - 1);
  const int row = clamp((int)floor((p.y - grid.y) * grid.w), 0, rows - 1);
  const int cell = row * columns + column;
  double best = -INFINITY, value = 0;
  for (int i = cell_start[cell]; i < cell_start[cell + 1]; ++i) {
    const int k = cell_entry[i];
    const double score = barycentric(p, field_points, field_triangles, k, l);
    if (score > best && per_triangle) {
      best = score;
      value = field_area[k];
    } else if (score > best) {
      best = score;
      const double w0 = fmax(l[0], 0.0), w1 = fmax(l[1], 0.0), w2 = fmax(l[2], 0.0);
      value =
          (w0 * field_area[field_triangles[3 * k]] + w1 * field_area[field_triangles[3 * k + 1]] +
           w2 * field_area[field_triangles[3 * k + 2]]) /
          (w0 + w1 + w2);
    }
  }
  return value;
}

// Prefetching for evaluate_size_field (prefetch.h): the slot's record and
// hint two stages ahead, then its corners and its hinted background
// triangle's record.
static inline void prefetch_slot(__global const int *list, int use_list, int i, int n,
                                 __global const double2 *points, __global const int *tri_vertex,
                                 __global const int *hint, int hinted,
                                 __global const int *field_triangles) {
  const int far = use_list ? entry_ahead(list, i, 2, n) : slot_ahead(i, 2, n);
  if (far >= 0) {
    warm(tri_vertex + 3 * far);
    if (hinted)
      warm(hint + far);
  }
  const int near = use_list ? entry_ahead(list, i, 1, n) : slot_ahead(i, 1, n);
  if (near < 0)
    return;
  warm_corners(points, 0, tri_vertex, near);
  if (hinted && hint[near] >= 0)
    warm(field_triangles + 3 * hint[near]);
}

// bound[t] for the slot of each entry: the background at its centroid (-1
// for a ghost or a dead slot); with combine, the tighter of that and the
// bound already there. hint (hinted): per slot, a background triangle to
// try first (-1: none); with relabel, replaced by the triangle a walk from it
// found, so that the slot's next triangles start there. least (> 0): the
// background's smallest value; a triangle smaller than it by a margin far
// beyond rounding is within its bound wherever it lies, and gets `least`
// without a lookup (the bound is read only to tell whether this very
// triangle is too large, which it is under neither).
__kernel void evaluate_size_field(__global const double2 *points, __global const int *tri_vertex,
                                  __global const int *list, const int use_list,
                                  __global const double2 *field_points,
                                  __global const double *field_area, const int per_triangle,
                                  __global const int *field_triangles, __global const int *across,
                                  __global const int *cell_start, __global const int *cell_entry,
                                  const double4 grid, const int columns, const int rows,
                                  __global int *hint, const int hinted, const int relabel,
                                  const int combine, const double least, __global double *bound,
                                  const int n) {
  const int i = get_global_id(0);
  if (i >= n)
    return;
  prefetch_slot(list, use_list, i, n, points, tri_vertex, hint, hinted, field_triangles);
  const int t = slot_of(list, use_list, i);
  if (t < 0)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (is_ghost(tri) || is_dead(tri)) {
    bound[t] = -1;
    return;
  }
  const double2 a = points[tri.v[0]], b = points[tri.v[1]], c = points[tri.v[2]];
  const double twice_area = fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  if (least > 0 && twice_area <= 2 * least * (1 - 1e-9)) {
    bound[t] = combine ? tighter(bound[t], least) : least;
    return;
  }
  const double2 centroid = (double2)((a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3);
  int walked;
  const double value =
      field_at(centroid, field_points, field_area, per_triangle, field_triangles, across,
               cell_start, cell_entry, grid, columns, rows, hinted ? hint[t] : -1, &walked);
  bound[t] = combine ? tighter(bound[t], value) : value;
  if (relabel && walked >= 0)
    hint[t] = walked;
}

// The corners of each entry's slot for the host's callback (NaN for a ghost,
// a dead slot or none).
__kernel void gather_corners(__global const double2 *points, __global const int *tri_vertex,
                             __global const int *list, const int use_list,
                             __global double2 *corners, const int n) {
  const int i = get_global_id(0);
  if (i >= n)
    return;
  const int t = slot_of(list, use_list, i);
  const VertexTriple tri =
      t < 0 ? (VertexTriple){{CLM_DEAD, CLM_DEAD, CLM_DEAD}} : load_vertices(tri_vertex, t);
  const bool real = t >= 0 && !is_ghost(tri) && !is_dead(tri);
  for (int k = 0; k < 3; ++k)
    corners[3 * i + k] = real ? points[tri.v[k]] : (double2)(NAN, NAN);
}

// The callback's answers: value[i] is half the triangle's area where it
// asks for refinement (the triangle is then too large whatever else bounds
// it), else -1: the slot keeps the field's bound (combine) or has none.
__kernel void scatter_bounds(__global const int *list, const int use_list,
                             __global const double *value, const int combine,
                             __global double *bound, const int n) {
  const int i = get_global_id(0);
  if (i >= n)
    return;
  const int t = slot_of(list, use_list, i);
  if (t < 0)
    return;
  const double v = value[i];
  bound[t] = combine && v < 0 ? bound[t] : v;
}
