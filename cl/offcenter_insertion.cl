// clmesh — GPU-QM step 1 (thesis §3.3.2, §3.4.1): bad triangles, their
// Steiner candidates and the insertion filter.
//
// A triangle is bad when its circumradius-to-shortest-edge ratio exceeds the
// bound of the minimum angle, or its area exceeds the maximum area. Its
// candidate is Üngör's off-center: the circumcenter, moved along the shortest
// edge's bisector to no farther than offconstant times that edge from its
// midpoint (as Triangle computes it). A candidate outside the hull, or inside
// the diametral circle of a hull edge of its container, becomes the midpoint of
// that hull edge (the convex hull is the boundary). Priority: the shorter the
// shortest edge, the worse the triangle; containers are marked with atomic
// minimum of it, and a candidate survives the insertion filter when it owns
// its container's mark and no neighbouring container has a better one.
// Quality decisions use floating point, as Triangle's do; the insertion that
// follows uses the exact predicates.
#include "common.h"

// Per slot t: is_bad[t], and the candidate and priority of a bad triangle.
// Only triangles changed since the last search (modified_stamp >= since), or
// bad then, are examined again (thesis §3.3.2): the others are still good.
__kernel void find_bad_triangles(__global const double2 *points, __global const int *tri_vertex,
                                 __global const int *modified_stamp, const int since,
                                 __global int *was_bad, const double ratio_bound_squared,
                                 const double max_area, const double offconstant,
                                 __global int *is_bad, __global double2 *slot_candidate,
                                 __global uint *slot_priority, const int n) {
  const int t = get_global_id(0);
  if (t >= n)
    return;
  is_bad[t] = 0;
  if (modified_stamp[t] < since && !was_bad[t])
    return;
  was_bad[t] = 0;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (is_ghost(tri))
    return;
  double2 p[3];
  double length_squared[3];
  for (int i = 0; i < 3; ++i)
    p[i] = points[tri.v[i]];
  int shortest = 0;
  for (int i = 0; i < 3; ++i) {
    const double2 d = p[prev3(i)] - p[next3(i)]; // edge opposite vertex i
    length_squared[i] = d.x * d.x + d.y * d.y;
    if (length_squared[i] < length_squared[shortest])
      shortest = i;
  }
  const double2 d1 = p[1] - p[0], d2 = p[2] - p[0];
  const double twice_area = d1.x * d2.y - d1.y * d2.x;
  // R^2 / l^2 = (l0 l1 l2)^2 / (16 K^2 l^2) with l the shortest edge.
  const double ratio_squared = length_squared[0] * length_squared[1] * length_squared[2] /
                               (4.0 * twice_area * twice_area * length_squared[shortest]);
  const bool skinny = ratio_bound_squared > 0 && ratio_squared > ratio_bound_squared;
  const bool large = max_area > 0 && 0.5 * twice_area > max_area;
  if (!skinny && !large)
    return;
  // Circumcenter relative to a, the origin of the shortest edge a-b (r: apex).
  const double2 a = p[next3(shortest)], b = p[prev3(shortest)], r = p[shortest];
  const double2 e = b - a, f = r - a;
  const double e2 = e.x * e.x + e.y * e.y, f2 = f.x * f.x + f.y * f.y;
  const double denominator = 2.0 * (e.x * f.y - e.y * f.x);
  const double2 center =
      (double2)((f.y * e2 - e.y * f2) / denominator, (e.x * f2 - f.x * e2) / denominator);
  const double2 middle = 0.5 * e, away = center - middle; // from the edge's midpoint
  const double reach = offconstant * sqrt(e2), distance = sqrt(away.x * away.x + away.y * away.y);
  const double2 offset = distance > reach ? middle + away * (reach / distance) : center;
  const double2 steiner = a + offset;
  if (!isfinite(steiner.x) || !isfinite(steiner.y))
    return; // a degenerate computation: leave the triangle alone
  is_bad[t] = 1;
  was_bad[t] = 1;
  slot_candidate[t] = steiner;
  slot_priority[t] = as_uint((float)length_squared[shortest]);
}

// The bad triangles as a list in slot order (offsets by prefix sum), so that
// candidate k is the same on every device and for every work-group size.
__kernel void gather_bad_triangles(__global const int *is_bad, __global const int *offset,
                                   __global const double2 *slot_candidate,
                                   __global const uint *slot_priority, __global double2 *candidate,
                                   __global int *origin, __global uint *priority, const int n) {
  const int t = get_global_id(0);
  if (t >= n || !is_bad[t])
    return;
  const int k = offset[t];
  candidate[k] = slot_candidate[t];
  origin[k] = t;
  priority[k] = slot_priority[t];
}

// Locates candidate k walking from its bad triangle. A candidate that ends in a
// ghost triangle, or inside the diametral circle of a hull edge of its
// container, becomes that hull edge's midpoint: hull_split[k] is then the
// edge of container[k] it splits (inserted on that edge whatever the rounding
// of the midpoint, as Triangle splits a segment), else -1.
__kernel void locate_candidates(__global const double2 *points, __global const int *tri_vertex,
                                __global const int *tri_neighbor, __global double2 *candidate,
                                __global int *container, __global int *hull_split,
                                __global const int *origin, const int max_steps, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const double2 c = candidate[k];
  const WalkResult walk = walk_to_point(points, tri_vertex, tri_neighbor, origin[k], c, max_steps);
  int t = walk.outcome == CLM_WALK_LOST ? origin[k] : walk.triangle;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  int hull_edge = -1;
  if (is_ghost(tri)) {
    const int g = tri.v[0] == CLM_INFINITE ? 0 : (tri.v[1] == CLM_INFINITE ? 1 : 2);
    const int link = tri_neighbor[3 * t + g];
    t = link_triangle(link); // the real triangle on that hull edge
    hull_edge = link_edge(link);
  } else {
    // A hull edge of the container or of a neighbour whose diametral circle
    // holds c is encroached: it is split instead.
    for (int r = -1; r < 3 && hull_edge < 0; ++r) {
      const int s = r < 0 ? t : link_triangle(tri_neighbor[3 * t + r]);
      if (is_ghost(load_vertices(tri_vertex, s)))
        continue;
      for (int i = 0; i < 3 && hull_edge < 0; ++i) {
        const int u = link_triangle(tri_neighbor[3 * s + i]);
        if (!is_ghost(load_vertices(tri_vertex, u)))
          continue;
        const double2 pa = points[tri_vertex[3 * s + next3(i)]],
                      pb = points[tri_vertex[3 * s + prev3(i)]];
        const double2 da = c - pa, db = c - pb;
        if (da.x * db.x + da.y * db.y < 0) { // inside the diametral circle
          hull_edge = i;
          t = s;
        }
      }
    }
  }
  if (hull_edge >= 0) {
    const double2 pa = points[tri_vertex[3 * t + next3(hull_edge)]],
                  pb = points[tri_vertex[3 * t + prev3(hull_edge)]];
    candidate[k] = 0.5 * (pa + pb);
  }
  container[k] = walk.outcome == CLM_WALK_AT_VERTEX && hull_edge < 0 ? -1 : t;
  hull_split[k] = hull_edge;
}

// The ghost across the hull edge a candidate splits, or -1.
inline int split_ghost(__global const int *tri_neighbor, __global const int *container,
                       __global const int *hull_split, int k) {
  return hull_split[k] < 0 ? -1 : link_triangle(tri_neighbor[3 * container[k] + hull_split[k]]);
}

// Marks each candidate's container (and the ghost of a hull split) with its priority.
__kernel void mark_candidate_containers(__global const int *container,
                                        __global const int *hull_split,
                                        __global const int *tri_neighbor,
                                        __global const uint *priority,
                                        volatile __global uint *tri_mark, const int n) {
  const int k = get_global_id(0);
  if (k >= n || container[k] < 0)
    return;
  atomic_min(&tri_mark[container[k]], priority[k]);
  const int ghost = split_ghost(tri_neighbor, container, hull_split, k);
  if (ghost >= 0)
    atomic_min(&tri_mark[ghost], priority[k]);
}

// The insertion filter: survive[k] = 1 when candidate k owns its container's
// mark and no neighbouring container is marked with a better priority.
// Among candidates of equal priority, the smallest index keeps the container.
__kernel void mark_candidate_ties(__global const int *container, __global const int *hull_split,
                                  __global const int *tri_neighbor, __global const uint *priority,
                                  __global const uint *tri_mark, volatile __global int *tie_mark,
                                  const int n) {
  const int k = get_global_id(0);
  if (k >= n || container[k] < 0)
    return;
  if (tri_mark[container[k]] == priority[k])
    atomic_min(&tie_mark[container[k]], k);
  const int ghost = split_ghost(tri_neighbor, container, hull_split, k);
  if (ghost >= 0 && tri_mark[ghost] == priority[k])
    atomic_min(&tie_mark[ghost], k);
}

// survive[k]: 0 lost, 1 survives inside the mesh, 2 survives as a hull split.
__kernel void insertion_filter(__global const int *container, __global const int *hull_split,
                               __global const uint *priority, __global const uint *tri_mark,
                               __global const int *tie_mark, __global const int *tri_neighbor,
                               __global int *survive, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int t = container[k];
  bool wins = t >= 0 && tri_mark[t] == priority[k] && tie_mark[t] == k;
  // No container of better priority among the neighbours and theirs.
  for (int i = 0; i < 3 && wins; ++i) {
    const int u = link_triangle(tri_neighbor[3 * t + i]);
    wins = tri_mark[u] >= priority[k];
    for (int j = 0; j < 3 && wins; ++j) {
      const int w = link_triangle(tri_neighbor[3 * u + j]);
      wins = w == t || tri_mark[w] >= priority[k];
    }
  }
  const int ghost = wins ? split_ghost(tri_neighbor, container, hull_split, k) : -1;
  if (ghost >= 0)
    wins = tri_mark[ghost] == priority[k] && tie_mark[ghost] == k;
  survive[k] = !wins ? 0 : (ghost < 0 ? 1 : 2);
}

// The survivors of one kind (1: inside, 2: hull splits) as keep flags.
__kernel void select_survivors(__global const int *survive, const int kind, __global int *keep,
                               const int n) {
  const int k = get_global_id(0);
  if (k < n)
    keep[k] = survive[k] == kind;
}

__kernel void clear_candidate_marks(__global const int *container, __global const int *hull_split,
                                    __global const int *tri_neighbor, __global uint *tri_mark,
                                    __global int *tie_mark, const int n) {
  const int k = get_global_id(0);
  if (k >= n || container[k] < 0)
    return;
  tri_mark[container[k]] = CLM_NO_MARK;
  tie_mark[container[k]] = 0x7fffffff;
  const int ghost = split_ghost(tri_neighbor, container, hull_split, k);
  if (ghost >= 0) {
    tri_mark[ghost] = CLM_NO_MARK;
    tie_mark[ghost] = 0x7fffffff;
  }
}

// The survivors become points first, first + 1, ... of the mesh (in candidate
// order, by prefix sum), each to walk from its container.
// location_edge: the hull edge of a hull split (the point is put on it), -1 otherwise.
__kernel void append_survivors(__global const double2 *candidate, __global const int *container,
                               __global const int *hull_split, __global const int *keep,
                               __global const int *offset, __global double2 *points,
                               __global int *location, __global int *location_edge,
                               __global int *original_id, const int first, const int n) {
  const int k = get_global_id(0);
  if (k >= n || !keep[k])
    return;
  const int p = first + offset[k];
  points[p] = candidate[k];
  location[p] = container[k];
  location_edge[p] = hull_split[k];
  original_id[p] = p; // Steiner points follow the input points
}
