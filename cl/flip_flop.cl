// clmesh — GPU-QM step 3: flip-flop (thesis §3.3.2, Algorithms 3.1 and 3.2;
// §3.5 for the orthogonal test of GPU-QM-V).
//
// After the Steiner points of an iteration are inserted, Delaunay flips and
// the deletion of redundant points run together over an active list of
// triangles. A pass (1) lets each active triangle propose one operation
// (Algorithm 3.1), testing its edges with the flipping phase's in-circle
// test (common.h; the filter, then a second kernel with the exact predicate
// for the few triangles it could not decide, §3.6.3): a non-Delaunay flip ("flop") that
// lowers the degree of a redundant vertex, a 3-1 flip that deletes a
// redundant vertex of degree 3 (or a 4-2 flip one of degree 4 lying on the
// segment between two of its neighbours, where no flop is possible), or a
// Delaunay flip; a Delaunay flip that would
// connect two points new in this iteration marks the one of lower priority
// redundant instead (GPU-QM: always; GPU-QM-V: only when the two are less than
// orthogonal). Non-Delaunay operations take precedence: their keys are smaller.
// (3) Operations owning the atomic-minimum marks of all their triangles are
// applied, (4) neighbours are relinked in a second step, (5) the touched and
// the still-unhappy triangles form the next active list, to which the stars
// of the redundant points are added (Algorithm 3.2), without duplicates.
#include "common.h"
#include "group_scan.h"
#include "mesh_params.h"
#include "prefetch.h"
#include "refinement.h"
#include "vertex_star.h"

#define CLM_OP_NONE 0
#define CLM_OP_DELAUNAY 1 // 2-2 flip of a non-locally-Delaunay edge
#define CLM_OP_FLOP 2     // 2-2 flip that removes an edge of a redundant point
#define CLM_OP_REMOVE 3   // 3-1 (or 4-2) flip that deletes a redundant point
#define CLM_OP_MARKED 4   // marked a point redundant: stays active, nothing flipped

#define CLM_DELAUNAY_KEYS 0x80000000u // Delaunay flips after every non-Delaunay one

#define CLM_NO_POINT 0x7fffffff

// The running totals (FlipFlop reads them once an iteration): Delaunay
// flips, flops and removals (0 to 2, CLM_OP_* - 1), the hull midpoints that
// survived their iteration, the redundant points kept in degenerate stars,
// the stars lost (a bug).
#define CLM_TOTAL_MIDPOINTS 3
#define CLM_TOTAL_KEPT 4
#define CLM_TOTAL_FAILURES 5
#define CLM_TOTALS 6

// The flip-flop's lists and per-point arrays, FlipFlop's buffers, bound by
// FlipFlop::bind_lists in this order. Per entry of the active list:
// operation, proposal, star (4 per entry), applied, count and offset (of its
// entries in next_active); exact_list: the entries the filter left
// undecided; per tracked point (this iteration's and the boundary routine's):
// star_size, star_offset; per point: redundant_mark, redundant_anchor;
// counters: exact_count, marked_count, totals (running totals, never
// cleared: CLM_TOTAL_*); per triangle slot: removal_claim (the smallest entry
// proposing a removal whose star's smallest slot it is; empty, 0x7fffffff,
// between passes).
#define CLM_FLIPFLOP_PARAMS                                                                        \
  __global int *active, __global int *operation, __global int *proposal, __global int *star,       \
      __global int *applied, __global int *count, __global int *offset, __global int *next_active, \
      __global int *exact_list, volatile __global int *exact_count, __global int *redundant_mark,  \
      __global int *redundant_anchor, volatile __global int *marked_count, __global int *tracked,  \
      __global int *star_size, __global int *star_offset, volatile __global int *totals,           \
      volatile __global int *removal_claim

#define CLM_FLIPFLOP_ARGS CLM_FLIPFLOP_ARGS_WITH_LISTS(active, next_active)
// The same with other active and next lists.
#define CLM_FLIPFLOP_ARGS_WITH_LISTS(active_list, next_list)                                       \
  active_list, operation, proposal, star, applied, count, offset, next_list, exact_list,           \
      exact_count, redundant_mark, redundant_anchor, marked_count, tracked, star_size,             \
      star_offset, totals, removal_claim

// The triangles around p, counter-clockwise, in star[0 .. 3] when there are
// three or four, all real (star[3] = -1 for three). Returns the
// count, or 0 for a larger star or one touching the hull.
static inline int small_star(__global const int *tri_vertex, __global const int *tri_neighbor,
                             int t, int p, int *star) {
  star[3] = -1;
  int s = t, degree = 0;
  for (int step = 0; step < 4 && degree == 0; ++step) {
    const int k = index_in(tri_vertex, s, p);
    if (k < 0 || is_ghost(load_vertices(tri_vertex, s)))
      return 0;
    star[step] = s;
    s = next_around(tri_neighbor, s, k);
    if (s == t)
      degree = step + 1;
  }
  if (degree < 3)
    return 0;
  // From the smallest slot on, whichever triangle found it: every proposer
  // of the removal lists the same star, so its result does not depend on
  // which of them applies it.
  while (star[0] != min(min(star[0], star[1]), degree == 4 ? min(star[2], star[3]) : star[2])) {
    const int first = star[0];
    for (int k = 0; k + 1 < degree; ++k)
      star[k] = star[k + 1];
    star[degree - 1] = first;
  }
  return degree;
}

// Can p, with the small star found above, be deleted in one flip? Always with
// three triangles; with four only when p lies on a diagonal x0-x2 or x1-x3 of
// its star (then no flop can lower its degree): *diagonal = 0 or 1.
static inline bool removable(__global const double2 *points, __global const int *tri_vertex, int p,
                             const int *star, int degree, int *diagonal) {
  *diagonal = 0;
  if (degree == 3)
    return true;
  if (degree != 4)
    return false;
  int x[4];
  for (int k = 0; k < 4; ++k)
    x[k] = star_vertex(tri_vertex, star[k], p);
  if (orient_vertices(points, x[0], x[2], p) == 0)
    return true;
  *diagonal = 1;
  return orient_vertices(points, x[1], x[3], p) == 0;
}

static inline int smallest_slot(const int *star) {
  int m = min(star[0], min(star[1], star[2]));
  return star[3] >= 0 ? min(m, star[3]) : m;
}

// The slots a removal leaves: the smallest one (3-1), or the two smallest (4-2).
static inline void removal_slots(const int *star, int *first, int *second) {
  *first = smallest_slot(star);
  *second = -1;
  if (star[3] < 0)
    return;
  for (int k = 0; k < 4; ++k)
    if (star[k] != *first && (*second < 0 || star[k] < *second))
      *second = star[k];
}

static inline void load_star(__global const int *star, int gid, int *s) {
  for (int k = 0; k < 4; ++k)
    s[k] = star[4 * gid + k];
}

// Would connecting c and d join two points new in this iteration that cannot
// both stay? Two midpoints always stay (each splits its own hull edge).
static inline bool dependent_pair(__global const double2 *points, __global const int *point_state,
                                  __global const double *insertion_radius2,
                                  const int orthogonal_test, int c, int d) {
  if (c < 0 || d < 0)
    return false;
  const int sc = point_state[c], sd = point_state[d];
  if (!is_new_point(sc) || !is_new_point(sd))
    return false;
  if (sc == CLM_POINT_NEW_MIDPOINT && sd == CLM_POINT_NEW_MIDPOINT)
    return false;
  if (!orthogonal_test)
    return true; // GPU-QM: any two connected new points are dependent
  // GPU-QM-V (Claim 3.5.1): less than orthogonal, |c - d|^2 < q^2 + r^2.
  const double2 e = points[c] - points[d];
  return squared_length(e) < insertion_radius2[c] + insertion_radius2[d];
}

// The one of a dependent pair to delete: never a midpoint; otherwise the one
// of lower priority (larger value: a longer shortest edge), then the larger index.
static inline int redundant_one(__global const int *point_state,
                                __global const uint *point_priority, int c, int d) {
  if (point_state[c] == CLM_POINT_NEW_MIDPOINT)
    return d;
  if (point_state[d] == CLM_POINT_NEW_MIDPOINT)
    return c;
  const uint pc = point_priority[c], pd = point_priority[d];
  if (pc != pd)
    return pc > pd ? c : d;
  return max(c, d);
}

// Algorithm 3.1 for the active triangle t = active[gid]: operation[gid], the
// 2-2 flip's edge in proposal[gid] (encode_link(neighbour, edge)) or, for a
// 3-1 flip, the deleted point in proposal[gid] and its triangles in
// star[4 gid ..]. The in-circle tests run here, edge by edge as the
// proposal needs them: the floating-point filter, or with `exact` the exact
// predicate. Returns false, having written nothing, when the filter could
// not tell an edge it needed (then the exact kernel proposes for t).
// any_redundant: whether any point is redundant now.
static inline bool propose_operation(const int gid, const int exact, CLM_MESH_PARAMS,
                                     CLM_FLIPFLOP_PARAMS, const int orthogonal_test,
                                     const int any_redundant) {
  const int t = active[gid];
  if (t < 0)
    return true;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (is_dead(tri) || is_ghost(tri))
    return true;
  int own = CLM_NO_POINT; // the smallest redundant vertex of t
  for (int i = 0; i < 3 && any_redundant; ++i)
    if (point_state[tri.v[i]] == CLM_POINT_REDUNDANT)
      own = min(own, tri.v[i]);
  for (int i = 0; i < 3; ++i) {
    const int link = tri_neighbor[3 * t + i];
    const int u = link_triangle(link);
    const int c = tri.v[i], a = tri.v[next3(i)], b = tri.v[prev3(i)];
    const int d = tri_vertex[3 * u + link_edge(link)];
    int smallest = own;
    if (any_redundant && d >= 0 && point_state[d] == CLM_POINT_REDUNDANT)
      smallest = min(smallest, d);
    bool flop = false;
    if (smallest != CLM_NO_POINT) {
      // A redundant point in this pair: no Delaunay flip here until it is
      // gone; only the smallest one is worked on, when it is on edge a-b.
      if (smallest != a && smallest != b)
        continue;
      int s[4], diagonal;
      const int degree = small_star(tri_vertex, tri_neighbor, t, smallest, s);
      if (removable(points, tri_vertex, smallest, s, degree, &diagonal)) {
        const uint key = 4u * (uint)smallest_slot(s) + 3u;
        for (int k = 0; k < 4; ++k) {
          if (s[k] >= 0)
            atomic_min(&tri_mark[s[k]], key);
          star[4 * gid + k] = s[k];
        }
        atomic_min(&removal_claim[smallest_slot(s)], gid);
        operation[gid] = CLM_OP_REMOVE;
        proposal[gid] = smallest;
        return true;
      }
      // A flop must leave both new triangles counter-clockwise.
      if (d < 0 || is_ghost(load_vertices(tri_vertex, u)) ||
          orient_vertices(points, a, d, c) <= 0 || orient_vertices(points, b, c, d) <= 0)
        continue;
      flop = true;
    } else {
      // Constraints are subsegments (tested below): a segment refinement has
      // split no longer stands between its ends. The in-circle filter comes
      // first: it keeps most edges, and the subsegment test, which reads
      // more of the mesh, is then not needed.
      const int verdict =
          edge_must_flip(points, constraint_start, constraint_adjacent, 0, 1, c, a, b, d, exact);
      if (verdict == CLM_KEEP)
        continue;
      if (constrained && is_subsegment(points, constraint_start, constraint_adjacent,
                                       constraint_segment, point_segment, segment_end, a, b, c, d))
        continue; // subsegments stay, split only
      if (verdict == CLM_UNCERTAIN)
        return false;
    }
    if (dependent_pair(points, point_state, insertion_radius2, orthogonal_test, c, d)) {
      const int r = redundant_one(point_state, point_priority, c, d);
      redundant_mark[r] = 1;
      redundant_anchor[r] = r == c ? t : u; // a triangle of its star
      atomic_inc(marked_count);
      operation[gid] = CLM_OP_MARKED;
      return true;
    }
    const uint key = (flop ? 0u : CLM_DELAUNAY_KEYS) | (uint)(4 * t + i);
    atomic_min(&tri_mark[t], key);
    atomic_min(&tri_mark[u], key);
    operation[gid] = flop ? CLM_OP_FLOP : CLM_OP_DELAUNAY;
    proposal[gid] = encode_link(u, i);
    return true;
  }
  return true;
}

// The proposals decided by the filter; the others are listed in exact_list.
__kernel void flipflop_propose(CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, const int orthogonal_test,
                               const int any_redundant, const int n) {
  const int gid = get_global_id(0);
  if (gid >= n)
    return;
  operation[gid] = CLM_OP_NONE;
  // (The states: redundant points, and dependent_pair for every edge that flips.)
  prefetch_triangle_and_neighbours(active, gid, n, points, point_state, tri_vertex, tri_neighbor);
  warm_marks_around(tri_mark, tri_neighbor, entry_ahead(active, gid, 2, n));
  if (constrained)
    prefetch_subsegment_tests(active, gid, n, point_segment, constraint_start, constraint_adjacent,
                              tri_vertex);
  if (!propose_operation(gid, 0, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, orthogonal_test, any_redundant))
    exact_list[atomic_inc(exact_count)] = gid; // a worklist: its order reaches nothing
}

// The proposals of the triangles the filter left undecided, as many as
// flipflop_propose counted (read here, not by the host: no round trip), each
// work-item taking its share (share_of).
__kernel void flipflop_propose_exact(CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS,
                                     const int orthogonal_test, const int any_redundant) {
  const int n = *exact_count;
  const Share share = share_of(get_global_id(0), get_global_size(0), n);
  for (int k = share.first; k < share.end; k += share.step)
    propose_operation(exact_list[k], 1, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, orthogonal_test,
                      any_redundant);
}

// Deletes p from its star (a small star, see small_star and removable). 3-1:
// (p,x0,x1) (p,x1,x2) (p,x2,x0) become (x0,x1,x2). 4-2 with p on x0-x2:
// (p,x0,x1) .. (p,x3,x0) become (x0,x1,x2) and (x2,x3,x0) (x1-x3: the same,
// turned by one). The results take the smallest slots (removal_slots), the
// other slots are emptied; every slot records the results as its children,
// for relink_edge.
static inline void remove_point(__global const double2 *points, __global int *tri_vertex,
                                __global int *tri_neighbor, __global int *modified_stamp,
                                __global int *children, const int *star, int p, int stamp) {
  const int degree = star[3] >= 0 ? 4 : 3;
  int diagonal;
  removable(points, tri_vertex, p, star, degree, &diagonal);
  int x[4], outer[4];
  for (int k = 0; k < degree; ++k) {
    const int s = star[(k + diagonal) % degree], i = index_in(tri_vertex, s, p);
    x[k] = tri_vertex[3 * s + next3(i)];
    outer[k] = tri_neighbor[3 * s + i]; // across x_k - x_k+1
  }
  int first, second;
  removal_slots(star, &first, &second);
  for (int k = 0; k < degree; ++k) {
    if (star[k] != first && star[k] != second)
      store_triangle(tri_vertex, tri_neighbor, star[k], CLM_DEAD, CLM_DEAD, CLM_DEAD, -1, -1, -1);
    record_children(modified_stamp, children, star[k], stamp, first, second, -1);
  }
  if (degree == 3) {
    store_triangle(tri_vertex, tri_neighbor, first, x[0], x[1], x[2], outer[1], outer[2], outer[0]);
    return;
  }
  store_triangle(tri_vertex, tri_neighbor, first, x[0], x[1], x[2], outer[1],
                 encode_link(second, 1), outer[0]);
  store_triangle(tri_vertex, tri_neighbor, second, x[2], x[3], x[0], outer[3],
                 encode_link(first, 1), outer[2]);
}

// Applies the operation of entry gid if it owns every mark it wrote.
// applied[gid]: the (first) slot that holds the result, or -1; done: this
// work-item's Delaunay flips, flops and removals so far.
static inline void apply_operation(int gid, CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, int *done,
                                   const int stamp) {
  const int op = operation[gid], t = active[gid];
  applied[gid] = -1;
  if (op == CLM_OP_REMOVE) {
    int s[4];
    load_star(star, gid, s);
    const int smallest = smallest_slot(s);
    const uint key = 4u * (uint)smallest + 3u;
    bool owned = true;
    for (int k = 0; k < 4; ++k)
      owned = owned && (s[k] < 0 || tri_mark[s[k]] == key);
    // Up to four proposers share this flip (and proposers of another point's
    // removal may share its key): the smallest entry applies it, so that the
    // results go to the same place in the next list whatever the schedule.
    // The proposers of the smallest key all own their marks, so one applies.
    if (owned && removal_claim[smallest] == gid) {
      const int p = proposal[gid];
      remove_point(points, tri_vertex, tri_neighbor, modified_stamp, children, s, p, stamp);
      applied[gid] = smallest;
      point_state[p] = CLM_POINT_DELETED;
      ++done[2];
    }
  } else if (op == CLM_OP_DELAUNAY || op == CLM_OP_FLOP) {
    const int u = link_triangle(proposal[gid]), i = link_edge(proposal[gid]);
    const uint key = (op == CLM_OP_FLOP ? 0u : CLM_DELAUNAY_KEYS) | (uint)(4 * t + i);
    if (tri_mark[t] == key && tri_mark[u] == key) {
      flip_edge(tri_vertex, tri_neighbor, modified_stamp, children, t, i, stamp);
      applied[gid] = t;
      ++done[op == CLM_OP_DELAUNAY ? 0 : 1];
    }
  }
}

// Prefetching for flipflop_apply and flipflop_relink (prefetch.h).
static inline void prefetch_operation(__global const int *active, __global const int *operation,
                                      __global const int *proposal, __global const int *star,
                                      __global const int *tri_vertex,
                                      __global const int *tri_neighbor,
                                      __global const int *modified_stamp,
                                      __global const int *children,
                                      volatile __global const uint *tri_mark, int gid, int n) {
  const int k = gid + CLM_AHEAD, op = entry_ahead(operation, gid, 1, n);
  if (op == CLM_OP_DELAUNAY || op == CLM_OP_FLOP) {
    warm_rewritten(tri_vertex, tri_neighbor, modified_stamp, children, tri_mark, active[k]);
    warm_rewritten(tri_vertex, tri_neighbor, modified_stamp, children, tri_mark,
                   link_triangle(proposal[k]));
  } else if (op == CLM_OP_REMOVE) {
    for (int j = 0; j < 4; ++j)
      warm_rewritten(tri_vertex, tri_neighbor, modified_stamp, children, tri_mark, star[4 * k + j]);
  }
}

static inline void prefetch_relink(__global const int *operation, __global const int *proposal,
                                   __global const int *star, __global const int *applied,
                                   __global const int *tri_vertex, __global const int *tri_neighbor,
                                   __global const int *modified_stamp, __global const int *children,
                                   volatile __global const uint *tri_mark, int gid, int n) {
  const int far = gid + 2 * CLM_AHEAD, t_far = entry_ahead(applied, gid, 2, n);
  if (t_far >= 0) {
    const bool removal = operation[far] == CLM_OP_REMOVE;
    for (int j = 0; j < (removal ? 4 : 2); ++j)
      warm_rewritten(tri_vertex, tri_neighbor, modified_stamp, children, tri_mark,
                     removal  ? star[4 * far + j]
                     : j == 0 ? t_far
                              : link_triangle(proposal[far]));
  }
  const int near = gid + CLM_AHEAD, t_near = entry_ahead(applied, gid, 1, n);
  if (t_near >= 0) {
    const bool removal = operation[near] == CLM_OP_REMOVE;
    for (int j = 0; j < (removal ? 4 : 2); ++j)
      warm_across_edges(tri_neighbor, modified_stamp, children,
                        removal  ? star[4 * near + j]
                        : j == 0 ? t_near
                                 : link_triangle(proposal[near]),
                        0, 3);
  }
}

// Applies the operations that own every mark they wrote; counts them in
// totals[0 .. 2] (Delaunay flips, flops, removals).
__kernel void flipflop_apply(CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, const int stamp, const int n) {
  const int gid = get_global_id(0);
  int done[3] = {0, 0, 0}; // Delaunay flips, flops, removals by this work-item
  prefetch_operation(active, operation, proposal, star, tri_vertex, tri_neighbor, modified_stamp,
                     children, tri_mark, gid, n);
  if (gid < n)
    apply_operation(gid, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, done, stamp);
  volatile __local int scratch[2];
  for (int k = 0; k < 3; ++k)
    reserve_in_group(done[k], scratch, &totals[k]);
}

// Entries passed to the next list (count[gid]): the triangles an operation
// produced, or the proposer itself when its operation was not applied and
// its triangle was not rewritten by another's.
static inline int next_entries(__global const int *active, __global const int *operation,
                               __global const int *star, __global const int *applied,
                               __global const int *modified_stamp, int stamp, int gid) {
  const int op = operation[gid];
  if (applied[gid] >= 0)
    return op == CLM_OP_REMOVE && star[4 * gid + 3] < 0 ? 1 : 2;
  return op != CLM_OP_NONE && modified_stamp[active[gid]] != stamp ? 1 : 0;
}

// This pass's marks and removal claims are cleared (apply, the last kernel to
// read them, has run).
static inline void clear_pass_marks(__global const int *active, __global const int *operation,
                                    __global const int *proposal, __global const int *star,
                                    volatile __global uint *tri_mark,
                                    volatile __global int *removal_claim, int gid) {
  const int op = operation[gid];
  if (op == CLM_OP_REMOVE) {
    int s[4];
    load_star(star, gid, s);
    removal_claim[smallest_slot(s)] = CLM_NO_POINT;
    for (int k = 0; k < 4; ++k)
      if (s[k] >= 0)
        tri_mark[s[k]] = CLM_NO_MARK;
  } else if (op == CLM_OP_DELAUNAY || op == CLM_OP_FLOP) {
    tri_mark[active[gid]] = CLM_NO_MARK;
    tri_mark[link_triangle(proposal[gid])] = CLM_NO_MARK;
  }
}

// Entry gid's count of next entries, its marks cleared, its results linked.
static inline void relink_results(int gid, CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, const int stamp) {
  count[gid] = next_entries(active, operation, star, applied, modified_stamp, stamp, gid);
  clear_pass_marks(active, operation, proposal, star, tri_mark, removal_claim, gid);
  if (applied[gid] < 0)
    return;
  const int t = applied[gid];
  if (operation[gid] == CLM_OP_REMOVE) {
    int s[4], first, second;
    load_star(star, gid, s);
    removal_slots(s, &first, &second);
    for (int e = 0; e < 3; ++e)
      if (second < 0 || e != 1) // edge 1 of a 4-2 flip's triangles is their shared one
        relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, first, e);
    if (second >= 0) {
      relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, second, 0);
      relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, second, 2);
    }
    return;
  }
  const int u = link_triangle(proposal[gid]);
  for (int e = 1; e < 3; ++e) {
    relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, t, e);
    relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, u, e);
  }
}

// Second step, after flipflop_apply: the applied operations' outer edges are relinked,
// each entry counts what it passes to the next list, and the marks are
// cleared (one kernel: these read only what apply wrote).
__kernel void flipflop_relink(CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, const int stamp, const int n) {
  const int gid = get_global_id(0);
  prefetch_relink(operation, proposal, star, applied, tri_vertex, tri_neighbor, modified_stamp,
                  children, tri_mark, gid, n);
  if (gid < n)
    relink_results(gid, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, stamp);
}

// Entry gid's results (or itself) at next_active[offset[gid] ..].
static inline void gather_results(int gid, CLM_FLIPFLOP_PARAMS) {
  if (count[gid] == 0)
    return;
  const int o = offset[gid];
  if (applied[gid] < 0) {
    next_active[o] = active[gid];
    return;
  }
  if (operation[gid] == CLM_OP_REMOVE) {
    int s[4], first, second;
    load_star(star, gid, s);
    removal_slots(s, &first, &second);
    next_active[o] = first;
    if (second >= 0)
      next_active[o + 1] = second;
    return;
  }
  next_active[o] = applied[gid];
  next_active[o + 1] = link_triangle(proposal[gid]);
}

__kernel void flipflop_gather_next(CLM_FLIPFLOP_PARAMS, const int n) {
  const int gid = get_global_id(0);
  if (gid < n)
    gather_results(gid, CLM_FLIPFLOP_ARGS);
}

// Over the tracked points (this iteration's, then old ones the boundary
// routine marked): the ones marked in this pass become redundant; every redundant point finds a
// triangle of its star again (its anchor may have been rewritten in this pass: then one of the
// slot's children holds it) and counts its star in star_size[k] (0 for the others).
static inline void track_point(int k, CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, const int stamp) {
  star_size[k] = 0;
  const int p = tracked[k];
  if (redundant_mark[p]) {
    redundant_mark[p] = 0;
    point_state[p] = CLM_POINT_REDUNDANT;
  }
  if (point_state[p] != CLM_POINT_REDUNDANT)
    return;
  int t = redundant_anchor[p];
  if (index_in(tri_vertex, t, p) < 0 && modified_stamp[t] == stamp) {
    const int x = t;
    for (int c = 0; c < CLM_CHILDREN; ++c) {
      const int y = children[CLM_CHILDREN * x + c];
      if (y >= 0 && index_in(tri_vertex, y, p) >= 0)
        t = y;
    }
  }
  if (index_in(tri_vertex, t, p) < 0) {
    atomic_inc(&totals[CLM_TOTAL_FAILURES]);
    return;
  }
  // The star's smallest slot becomes the anchor, where its listing starts:
  // the same whichever triangle found the point.
  int size = 0, s = t, smallest = t;
  do {
    ++size;
    smallest = min(smallest, s);
    s = next_around(tri_neighbor, s, index_in(tri_vertex, s, p));
  } while (s != t && size < 4096);
  redundant_anchor[p] = smallest;
  star_size[k] = size;
}

__kernel void track_redundant_points(CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, const int stamp,
                                     const int n) {
  const int k = get_global_id(0);
  if (k < n)
    track_point(k, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, stamp);
}

// Appends the star of every redundant point to the next active list at
// next_active[base + star_offset[k] ..] (Algorithm 3.2, lines 6-10).
static inline void emit_star(int k, CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, const int base) {
  if (star_size[k] == 0)
    return;
  const int p = tracked[k];
  int s = redundant_anchor[p];
  for (int j = 0; j < star_size[k]; ++j) {
    next_active[base + star_offset[k] + j] = s;
    s = next_around(tri_neighbor, s, index_in(tri_vertex, s, p));
  }
}

__kernel void emit_redundant_stars(CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, const int base,
                                   const int n) {
  const int k = get_global_id(0);
  if (k < n)
    emit_star(k, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, base);
}

// A whole pass by one work-group, for short lists: the kernels above in
// order (propose, exact proposals, apply, relink and count, gather, and when
// stars are looked for, tracking, stars and duplicate removal into active),
// with barriers between them instead of launches: most passes list a few
// hundred triangles, for which a launch costs more than the work. Entry by
// entry the results are those of the kernels. The pass's entries in
// next_active are also appended to `rewritten` from rewritten_size on (room
// for 2 n), as FlipFlop::run does after the kernels. Returns (the pass's
// entries in next_active, points marked, stars listed (-1: not looked for,
// -2: no room for them), the next list's length), the same to every
// work-item; exact proposals are added to exact[0].
static inline int4 pass_in_group(CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, const int orthogonal_test,
                                 const int any_redundant, const int next_capacity, const int m,
                                 const int find_stars, __global int *rewritten,
                                 const int rewritten_size, __local int *scratch,
                                 volatile __global int *exact_total, const int stamp, const int n) {
  const int lid = get_local_id(0), size = get_local_size(0);
  if (lid == 0)
    marked_count[0] = 0;
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  int exact = 0;
  for (int k = lid; k < n; k += size) {
    operation[k] = CLM_OP_NONE;
    if (!propose_operation(k, 0, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, orthogonal_test,
                           any_redundant)) {
      propose_operation(k, 1, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, orthogonal_test, any_redundant);
      ++exact;
    }
  }
  if (exact > 0)
    atomic_add(exact_total, exact);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  // The counts are added before the next barrier: PoCL's CPU device
  // miscompiles a private array that lives across barriers in a loop
  // (flipflop_passes_in_group's).
  int done[3] = {0, 0, 0};
  for (int k = lid; k < n; k += size)
    apply_operation(k, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, done, stamp);
  for (int j = 0; j < 3; ++j)
    if (done[j] > 0)
      atomic_add(&totals[j], done[j]);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < n; k += size)
    relink_results(k, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, stamp);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int next = group_exclusive_scan(count, offset, n, scratch);
  for (int k = lid; k < n; k += size)
    gather_results(k, CLM_FLIPFLOP_ARGS);
  const int marked = marked_count[0];
  // The pass's entries (results and losers) appended to `rewritten`.
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < next; k += size)
    rewritten[rewritten_size + k] = next_active[k];
  int stars = -1, length = next;
  if (marked > 0 || find_stars) {
    group_barrier(CLK_GLOBAL_MEM_FENCE);
    for (int k = lid; k < m; k += size)
      track_point(k, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, stamp);
    group_barrier(CLK_GLOBAL_MEM_FENCE);
    stars = group_exclusive_scan(star_size, star_offset, m, scratch);
    if (next + stars > next_capacity) {
      stars = -2;
    } else {
      for (int k = lid; k < m; k += size)
        emit_star(k, CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS, next);
      group_barrier(CLK_GLOBAL_MEM_FENCE);
      length = group_unique(next_active, next + stars, tri_mark, count, offset, active, scratch);
    }
  }
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  return (int4)(next, marked, stars, length);
}

// A stall (no operation left, yet redundant points remain, in degenerate
// stars where neither a flop nor a removal is possible): the tracked point
// k, when redundant, is kept, as a Steiner point of earlier iterations,
// after its star was listed.
static inline void keep_stuck_point(__global const int *tracked, __global int *point_state,
                                    volatile __global int *totals, int k) {
  if (point_state[tracked[k]] == CLM_POINT_REDUNDANT) {
    point_state[tracked[k]] = CLM_POINT_STEINER;
    atomic_inc(&totals[CLM_TOTAL_KEPT]);
  }
}

__kernel void keep_stuck_points(__global const int *tracked, __global int *point_state,
                                volatile __global int *totals, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    keep_stuck_point(tracked, point_state, totals, k);
}

// End of an iteration: its points become points of earlier iterations;
// the surviving hull midpoints are counted in totals.
static inline void finish_point(__global const int *new_points, __global int *point_state,
                                volatile __global int *totals, int k) {
  const int p = new_points[k], state = point_state[p];
  if (state == CLM_POINT_NEW_MIDPOINT) {
    atomic_inc(&totals[CLM_TOTAL_MIDPOINTS]);
    point_state[p] = CLM_POINT_MIDPOINT;
  } else if (state == CLM_POINT_NEW) {
    point_state[p] = CLM_POINT_STEINER;
  }
}

__kernel void finish_iteration(__global const int *new_points, __global int *point_state,
                               volatile __global int *totals, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    finish_point(new_points, point_state, totals, k);
}

// Pass after pass by one work-group (pass_in_group), as FlipFlop::run goes
// on from a pass: while the active list is not empty and holds at most
// group_pass_limit entries, at most max_passes passes, each while
// `rewritten` (rewritten_capacity entries) has room for 2 n more. The
// first pass of the run (first_pass) looks at no redundant point; the
// passes take the stamps stamp, stamp + 1, ... A pass that did not look for
// stars leaves the next list in next_active: the two lists swap places; a
// stall keeps the stuck points (keep_stuck_point). result: [0] the active
// list's length, [1] passes, [2] 0, or -2: no room for the stars, -3: the
// next list longer than list_capacity, [3] whether redundant points are
// left, [4] exact proposals, [5] whether the lists swapped places (an odd
// number of times), [6] entries appended to `rewritten`, [7] the most
// entries a pass's lists took, [8] whether the run ended here: the list
// empty, finish_iteration's work done over new_points[0 .. new_count) in
// the same launch, and the totals then in result[9 ..], [15] the points
// tracked: tracked_known, or when it is negative new_count plus the
// boundary routine's old_tracked[0] (read here, not by the host); passes run
// only while they are at most tracked_limit.
__kernel void flipflop_passes_in_group(
    CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, const int orthogonal_test, const int first_pass,
    const int next_capacity, const int list_capacity, const int group_pass_limit,
    const int max_passes, const int tracked_known, __global const int *old_tracked,
    const int tracked_limit, const int redundant_at_start, __global int *rewritten,
    const int rewritten_at_start, const int rewritten_capacity, __local int *scratch,
    volatile __global int *result, __global const int *new_points, const int new_count,
    const int stamp, const int entries) {
  const int lid = get_local_id(0), size = get_local_size(0);
  if (lid == 0)
    result[4] = 0;
  const int m = tracked_known >= 0 ? tracked_known : new_count + old_tracked[0];
  // The arguments stay as they are: every work-item keeps its own copy of
  // what changes from pass to pass (the same in all).
  int n = entries, redundant_left = redundant_at_start, rewritten_size = rewritten_at_start;
  int passes = 0, status = 0, swapped = 0, appended = 0, most = 0;
  while (status == 0 && n > 0 && n <= group_pass_limit && m <= tracked_limit &&
         passes < max_passes && rewritten_size + 2 * n <= rewritten_capacity) {
    const int any_redundant = redundant_left && (passes > 0 || !first_pass);
    __global int *const from = swapped ? next_active : active;
    __global int *const to = swapped ? active : next_active;
    const int4 pass =
        pass_in_group(CLM_MESH_ARGS, CLM_FLIPFLOP_ARGS_WITH_LISTS(from, to), orthogonal_test,
                      any_redundant, next_capacity, m, redundant_left, rewritten, rewritten_size,
                      scratch, &result[4], stamp + passes, n);
    ++passes;
    rewritten_size += pass.s0;
    appended += pass.s0;
    most = max(most, max(pass.s0, pass.s3));
    if (pass.s2 == -2) {
      status = -2;
    } else if (pass.s2 < 0) { // no stars looked for: the next list is in `to`
      swapped ^= 1;
      n = pass.s0;
    } else {
      redundant_left = pass.s2 > 0;
      n = pass.s3;
      if (n > list_capacity) {
        status = -3;
      }
    }
    // Stalled: what is left cannot be deleted. Their stars are listed.
    const bool stalled = status == 0 && pass.s2 > 0 && pass.s0 == 0 && pass.s1 == 0;
    for (int k = lid; stalled && k < m; k += size)
      keep_stuck_point(tracked, point_state, totals, k);
    group_barrier(CLK_GLOBAL_MEM_FENCE);
    if (stalled)
      redundant_left = 0;
  }
  const bool finished = status == 0 && n == 0;
  for (int k = lid; finished && k < new_count; k += size)
    finish_point(new_points, point_state, totals, k);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  if (lid == 0) {
    result[8] = finished;
    for (int j = 0; finished && j < CLM_TOTALS; ++j)
      result[9 + j] = totals[j];
    result[9 + CLM_TOTALS] = m;
    result[0] = n;
    result[1] = passes;
    result[2] = status;
    result[3] = redundant_left;
    result[5] = swapped;
    result[6] = appended;
    result[7] = most;
  }
}

// The coordinates of the points this iteration deleted (the followed ones,
// tracked[0 .. n), of state deleted) after the earlier ones, to count the
// points inserted more than once at the end; logged[0]: the entries so far.
// A worklist counter places them: their order reaches nothing.
__kernel void log_deleted_points(__global const int *tracked, __global const int *point_state,
                                 __global const double2 *points, __global double2 *deletion_log,
                                 volatile __global int *logged, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int p = tracked[k];
  if (point_state[p] == CLM_POINT_DELETED)
    deletion_log[atomic_inc(logged)] = points[p];
}
