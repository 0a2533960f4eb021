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
#include "prefetch.h"
#include "refinement.h"

#define CLM_OP_NONE 0
#define CLM_OP_DELAUNAY 1 // 2-2 flip of a non-locally-Delaunay edge
#define CLM_OP_FLOP 2     // 2-2 flip that removes an edge of a redundant point
#define CLM_OP_REMOVE 3   // 3-1 (or 4-2) flip that deletes a redundant point
#define CLM_OP_MARKED 4   // marked a point redundant: stays active, nothing flipped

#define CLM_DELAUNAY_KEYS 0x80000000u // Delaunay flips after every non-Delaunay one
#define CLM_APPLIED 0xfffffffeu       // a 3-1 flip taken by one of its proposers

#define CLM_NO_POINT 0x7fffffff

// The triangle after t counter-clockwise around its vertex p (at index k).
inline int next_around(__global const int *tri_neighbor, int t, int k) {
  return link_triangle(tri_neighbor[3 * t + next3(k)]);
}

// The triangles around p, counter-clockwise, in star[0 .. 3] when there are
// three or four, all real (star[3] = -1 for three). Returns the
// count, or 0 for a larger star or one touching the hull.
inline int small_star(__global const int *tri_vertex, __global const int *tri_neighbor, int t,
                      int p, int *star) {
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

// The neighbour of p that follows it in star triangle s: x_k for star[k].
inline int star_vertex(__global const int *tri_vertex, int s, int p) {
  return tri_vertex[3 * s + next3(index_in(tri_vertex, s, p))];
}

// Can p, with the small star found above, be deleted in one flip? Always with
// three triangles; with four only when p lies on a diagonal x0-x2 or x1-x3 of
// its star (then no flop can lower its degree): *diagonal = 0 or 1.
inline bool removable(__global const double2 *points, __global const int *tri_vertex, int p,
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

inline int smallest_slot(const int *star) {
  int m = min(star[0], min(star[1], star[2]));
  return star[3] >= 0 ? min(m, star[3]) : m;
}

// The slots a removal leaves: the smallest one (3-1), or the two smallest (4-2).
inline void removal_slots(const int *star, int *first, int *second) {
  *first = smallest_slot(star);
  *second = -1;
  if (star[3] < 0)
    return;
  for (int k = 0; k < 4; ++k)
    if (star[k] != *first && (*second < 0 || star[k] < *second))
      *second = star[k];
}

inline void load_star(__global const int *star, int gid, int *s) {
  for (int k = 0; k < 4; ++k)
    s[k] = star[4 * gid + k];
}

// Would connecting c and d join two points new in this iteration that cannot
// both stay? Two midpoints always stay (each splits its own hull edge).
inline bool dependent_pair(__global const double2 *points, __global const int *point_state,
                           __global const double *insertion_radius2, const int orthogonal_test,
                           int c, int d) {
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
inline int redundant_one(__global const int *point_state, __global const uint *point_priority,
                         int c, int d) {
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
inline bool propose_operation(const int gid, const int exact, __global const int *active,
                              __global const double2 *points, __global const int *tri_vertex,
                              __global const int *tri_neighbor,
                              __global const int *constraint_start,
                              __global const int *constraint_adjacent, const int constrained,
                              __global const int *point_state,
                              __global const double *insertion_radius2,
                              __global const uint *point_priority, const int orthogonal_test,
                              const int any_redundant, __global int *redundant_mark,
                              __global int *redundant_anchor, volatile __global int *marked_count,
                              volatile __global uint *tri_mark, __global int *operation,
                              __global int *proposal, __global int *star) {
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
      const int verdict = edge_must_flip(points, constraint_start, constraint_adjacent, constrained,
                                         1, c, a, b, d, exact);
      if (verdict == CLM_UNCERTAIN)
        return false;
      if (verdict == CLM_KEEP)
        continue;
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
__kernel void flipflop_propose(
    __global const int *active, __global const double2 *points, __global const int *tri_vertex,
    __global const int *tri_neighbor, __global const int *constraint_start,
    __global const int *constraint_adjacent, const int constrained, __global const int *point_state,
    __global const double *insertion_radius2, __global const uint *point_priority,
    const int orthogonal_test, const int any_redundant, __global int *redundant_mark,
    __global int *redundant_anchor, volatile __global int *marked_count,
    volatile __global uint *tri_mark, __global int *operation, __global int *proposal,
    __global int *star, __global int *exact_list, volatile __global int *exact_count, const int n) {
  const int gid = get_global_id(0);
  if (gid >= n)
    return;
  operation[gid] = CLM_OP_NONE;
  prefetch_triangle_and_neighbours(active, gid, n, points, any_redundant ? point_state : 0,
                                   tri_vertex, tri_neighbor);
  if (!propose_operation(gid, 0, active, points, tri_vertex, tri_neighbor, constraint_start,
                         constraint_adjacent, constrained, point_state, insertion_radius2,
                         point_priority, orthogonal_test, any_redundant, redundant_mark,
                         redundant_anchor, marked_count, tri_mark, operation, proposal, star))
    exact_list[atomic_inc(exact_count)] = gid; // a worklist: its order reaches nothing
}

// The proposals of the triangles the filter left undecided.
__kernel void
flipflop_propose_exact(__global const int *exact_list, __global const int *active,
                       __global const double2 *points, __global const int *tri_vertex,
                       __global const int *tri_neighbor, __global const int *constraint_start,
                       __global const int *constraint_adjacent, const int constrained,
                       __global const int *point_state, __global const double *insertion_radius2,
                       __global const uint *point_priority, const int orthogonal_test,
                       const int any_redundant, __global int *redundant_mark,
                       __global int *redundant_anchor, volatile __global int *marked_count,
                       volatile __global uint *tri_mark, __global int *operation,
                       __global int *proposal, __global int *star, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  propose_operation(exact_list[k], 1, active, points, tri_vertex, tri_neighbor, constraint_start,
                    constraint_adjacent, constrained, point_state, insertion_radius2,
                    point_priority, orthogonal_test, any_redundant, redundant_mark,
                    redundant_anchor, marked_count, tri_mark, operation, proposal, star);
}

// Deletes p from its star (a small star, see small_star and removable). 3-1:
// (p,x0,x1) (p,x1,x2) (p,x2,x0) become (x0,x1,x2). 4-2 with p on x0-x2:
// (p,x0,x1) .. (p,x3,x0) become (x0,x1,x2) and (x2,x3,x0) (x1-x3: the same,
// turned by one). The results take the smallest slots (removal_slots), the
// other slots are emptied; every slot records the results as its children,
// for relink_edge.
inline void remove_point(__global const double2 *points, __global int *tri_vertex,
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
inline void apply_operation(int gid, __global const int *active, __global const int *operation,
                            __global const int *proposal, __global const int *star,
                            volatile __global uint *tri_mark, __global const double2 *points,
                            __global int *tri_vertex, __global int *tri_neighbor,
                            __global int *modified_stamp, __global int *children,
                            __global int *point_state, __global int *applied, int *done,
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
    // Up to four proposers share this flip: the first to take the mark applies it.
    if (owned && atomic_cmpxchg(&tri_mark[smallest], key, CLM_APPLIED) == key) {
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
inline void prefetch_operation(__global const int *active, __global const int *operation,
                               __global const int *proposal, __global const int *star,
                               __global const int *tri_vertex, __global const int *tri_neighbor,
                               __global const int *modified_stamp, __global const int *children,
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

inline void prefetch_relink(__global const int *operation, __global const int *proposal,
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

// Applies the operations that own every mark they wrote. flip_counts:
// Delaunay flips, flops, removals.
__kernel void flipflop_apply(__global const int *active, __global const int *operation,
                             __global const int *proposal, __global const int *star,
                             volatile __global uint *tri_mark, __global const double2 *points,
                             __global int *tri_vertex, __global int *tri_neighbor,
                             __global int *modified_stamp, __global int *children,
                             __global int *point_state, __global int *applied,
                             volatile __global int *flip_counts, const int stamp, const int n) {
  const int gid = get_global_id(0);
  int done[3] = {0, 0, 0}; // Delaunay flips, flops, removals by this work-item
  prefetch_operation(active, operation, proposal, star, tri_vertex, tri_neighbor, modified_stamp,
                     children, tri_mark, gid, n);
  if (gid < n)
    apply_operation(gid, active, operation, proposal, star, tri_mark, points, tri_vertex,
                    tri_neighbor, modified_stamp, children, point_state, applied, done, stamp);
  volatile __local int scratch[2];
  for (int k = 0; k < 3; ++k)
    reserve_in_group(done[k], scratch, &flip_counts[k]);
}

// Entries passed to the next list (count[gid]): the triangles an operation
// produced, or the proposer itself when its operation was not applied and
// its triangle was not rewritten by another's.
inline int next_entries(__global const int *active, __global const int *operation,
                        __global const int *star, __global const int *applied,
                        __global const int *modified_stamp, int stamp, int gid) {
  const int op = operation[gid];
  if (applied[gid] >= 0)
    return op == CLM_OP_REMOVE && star[4 * gid + 3] < 0 ? 1 : 2;
  return op != CLM_OP_NONE && modified_stamp[active[gid]] != stamp ? 1 : 0;
}

// This pass's marks are cleared (apply, the last kernel to read them, has run).
inline void clear_pass_marks(__global const int *active, __global const int *operation,
                             __global const int *proposal, __global const int *star,
                             __global uint *tri_mark, int gid) {
  const int op = operation[gid];
  if (op == CLM_OP_REMOVE) {
    for (int k = 0; k < 4; ++k)
      if (star[4 * gid + k] >= 0)
        tri_mark[star[4 * gid + k]] = CLM_NO_MARK;
  } else if (op == CLM_OP_DELAUNAY || op == CLM_OP_FLOP) {
    tri_mark[active[gid]] = CLM_NO_MARK;
    tri_mark[link_triangle(proposal[gid])] = CLM_NO_MARK;
  }
}

// Entry gid's count of next entries, its marks cleared, its results linked.
inline void relink_results(int gid, __global const int *active, __global const int *operation,
                           __global const int *proposal, __global const int *star,
                           __global const int *applied, __global const int *tri_vertex,
                           __global int *tri_neighbor, __global const int *modified_stamp,
                           __global const int *children, __global uint *tri_mark,
                           __global int *count, const int stamp) {
  count[gid] = next_entries(active, operation, star, applied, modified_stamp, stamp, gid);
  clear_pass_marks(active, operation, proposal, star, tri_mark, gid);
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
__kernel void flipflop_relink(__global const int *active, __global const int *operation,
                              __global const int *proposal, __global const int *star,
                              __global const int *applied, __global const int *tri_vertex,
                              __global int *tri_neighbor, __global const int *modified_stamp,
                              __global const int *children, __global uint *tri_mark,
                              __global int *count, const int stamp, const int n) {
  const int gid = get_global_id(0);
  prefetch_relink(operation, proposal, star, applied, tri_vertex, tri_neighbor, modified_stamp,
                  children, tri_mark, gid, n);
  if (gid < n)
    relink_results(gid, active, operation, proposal, star, applied, tri_vertex, tri_neighbor,
                   modified_stamp, children, tri_mark, count, stamp);
}

// Entry gid's results (or itself) at next_active[offset[gid] ..].
inline void gather_results(int gid, __global const int *active, __global const int *proposal,
                           __global const int *operation, __global const int *star,
                           __global const int *applied, __global const int *count,
                           __global const int *offset, __global int *next_active) {
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

__kernel void flipflop_gather_next(__global const int *active, __global const int *proposal,
                                   __global const int *operation, __global const int *star,
                                   __global const int *applied, __global const int *count,
                                   __global const int *offset, __global int *next_active,
                                   const int n) {
  const int gid = get_global_id(0);
  if (gid < n)
    gather_results(gid, active, proposal, operation, star, applied, count, offset, next_active);
}

// Over the tracked points (this iteration's, then old ones the boundary
// routine marked): the ones marked in this pass become redundant; every redundant point finds a
// triangle of its star again (its anchor may have been rewritten in this pass: then one of the
// slot's children holds it) and counts its star in star_size[k] (0 for the others).
inline void track_point(int k, __global const int *tracked, __global int *point_state,
                        __global int *redundant_mark, __global int *redundant_anchor,
                        __global const int *tri_vertex, __global const int *tri_neighbor,
                        __global const int *modified_stamp, __global const int *children,
                        __global int *star_size, volatile __global int *failures, const int stamp) {
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
    atomic_inc(failures);
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

__kernel void track_redundant_points(__global const int *tracked, __global int *point_state,
                                     __global int *redundant_mark, __global int *redundant_anchor,
                                     __global const int *tri_vertex,
                                     __global const int *tri_neighbor,
                                     __global const int *modified_stamp,
                                     __global const int *children, __global int *star_size,
                                     volatile __global int *failures, const int stamp,
                                     const int n) {
  const int k = get_global_id(0);
  if (k < n)
    track_point(k, tracked, point_state, redundant_mark, redundant_anchor, tri_vertex, tri_neighbor,
                modified_stamp, children, star_size, failures, stamp);
}

// Appends the star of every redundant point to the next active list at
// out[base + offset[k] ..] (Algorithm 3.2, lines 6-10).
inline void emit_star(int k, __global const int *tracked, __global const int *redundant_anchor,
                      __global const int *tri_vertex, __global const int *tri_neighbor,
                      __global const int *star_size, __global const int *offset, __global int *out,
                      const int base) {
  if (star_size[k] == 0)
    return;
  const int p = tracked[k];
  int s = redundant_anchor[p];
  for (int j = 0; j < star_size[k]; ++j) {
    out[base + offset[k] + j] = s;
    s = next_around(tri_neighbor, s, index_in(tri_vertex, s, p));
  }
}

__kernel void emit_redundant_stars(__global const int *tracked,
                                   __global const int *redundant_anchor,
                                   __global const int *tri_vertex, __global const int *tri_neighbor,
                                   __global const int *star_size, __global const int *offset,
                                   __global int *out, const int base, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    emit_star(k, tracked, redundant_anchor, tri_vertex, tri_neighbor, star_size, offset, out, base);
}

// A whole pass by one work-group, for short lists: the kernels above in
// order (propose, exact proposals, apply, relink and count, gather, and when
// stars are looked for, tracking, stars and duplicate removal into active),
// with barriers between them instead of launches. PoCL pays about 30 us a
// launch, and most passes, all of GPU-QM's on hard inputs, list a few
// hundred triangles. Entry by entry the results are those of the kernels.
// result: [0] the pass's entries in next_active, [1] points marked, [2]
// stars listed (-1: not looked for, -2: no room for them), [3] the next
// list's length, [4] exact proposals.
__kernel void flipflop_pass_in_group(
    __global int *active, __global const double2 *points, __global int *tri_vertex,
    __global int *tri_neighbor, __global const int *constraint_start,
    __global const int *constraint_adjacent, const int constrained, __global int *point_state,
    __global const double *insertion_radius2, __global const uint *point_priority,
    const int orthogonal_test, const int any_redundant, __global int *redundant_mark,
    __global int *redundant_anchor, volatile __global int *marked_count,
    volatile __global uint *tri_mark, __global int *operation, __global int *proposal,
    __global int *star, __global int *modified_stamp, __global int *children, __global int *applied,
    volatile __global int *flip_counts, __global int *count, __global int *offset,
    __global int *next_active, const int next_capacity, __global const int *tracked, const int m,
    const int find_stars, __global int *star_size, __global int *star_offset,
    volatile __global int *failures, __local int *scratch, volatile __global int *result,
    const int stamp, const int n) {
  const int lid = get_local_id(0), size = get_local_size(0);
  if (lid == 0) {
    marked_count[0] = 0;
    result[4] = 0;
  }
  barrier(CLK_GLOBAL_MEM_FENCE);
  int exact = 0;
  for (int k = lid; k < n; k += size) {
    operation[k] = CLM_OP_NONE;
    if (!propose_operation(k, 0, active, points, tri_vertex, tri_neighbor, constraint_start,
                           constraint_adjacent, constrained, point_state, insertion_radius2,
                           point_priority, orthogonal_test, any_redundant, redundant_mark,
                           redundant_anchor, marked_count, tri_mark, operation, proposal, star)) {
      propose_operation(k, 1, active, points, tri_vertex, tri_neighbor, constraint_start,
                        constraint_adjacent, constrained, point_state, insertion_radius2,
                        point_priority, orthogonal_test, any_redundant, redundant_mark,
                        redundant_anchor, marked_count, tri_mark, operation, proposal, star);
      ++exact;
    }
  }
  barrier(CLK_GLOBAL_MEM_FENCE);
  int done[3] = {0, 0, 0};
  for (int k = lid; k < n; k += size)
    apply_operation(k, active, operation, proposal, star, tri_mark, points, tri_vertex,
                    tri_neighbor, modified_stamp, children, point_state, applied, done, stamp);
  barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < n; k += size)
    relink_results(k, active, operation, proposal, star, applied, tri_vertex, tri_neighbor,
                   modified_stamp, children, (__global uint *)tri_mark, count, stamp);
  barrier(CLK_GLOBAL_MEM_FENCE);
  const int next = group_exclusive_scan(count, offset, n, scratch);
  for (int k = lid; k < n; k += size)
    gather_results(k, active, proposal, operation, star, applied, count, offset, next_active);
  for (int j = 0; j < 3; ++j)
    if (done[j] > 0)
      atomic_add(&flip_counts[j], done[j]);
  if (exact > 0)
    atomic_add(&result[4], exact);
  const int marked = marked_count[0];
  int stars = -1, length = next;
  if (marked > 0 || find_stars) {
    barrier(CLK_GLOBAL_MEM_FENCE);
    for (int k = lid; k < m; k += size)
      track_point(k, tracked, point_state, redundant_mark, redundant_anchor, tri_vertex,
                  tri_neighbor, modified_stamp, children, star_size, failures, stamp);
    barrier(CLK_GLOBAL_MEM_FENCE);
    stars = group_exclusive_scan(star_size, star_offset, m, scratch);
    if (next + stars > next_capacity) {
      stars = -2;
    } else {
      for (int k = lid; k < m; k += size)
        emit_star(k, tracked, redundant_anchor, tri_vertex, tri_neighbor, star_size, star_offset,
                  next_active, next);
      barrier(CLK_GLOBAL_MEM_FENCE);
      length = group_unique(next_active, next + stars, tri_mark, count, offset, active, scratch);
    }
  }
  if (lid == 0) {
    result[0] = next;
    result[1] = marked;
    result[2] = stars;
    result[3] = length;
  }
}

// End of an iteration: its points become points of earlier iterations.
// midpoints[0] counts the surviving hull midpoints.
__kernel void finish_iteration(__global const int *new_points, __global int *point_state,
                               volatile __global int *midpoints, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int p = new_points[k], state = point_state[p];
  if (state == CLM_POINT_NEW_MIDPOINT) {
    atomic_inc(midpoints);
    point_state[p] = CLM_POINT_MIDPOINT;
  } else if (state == CLM_POINT_NEW) {
    point_state[p] = CLM_POINT_STEINER;
  }
}

// The coordinates of the points this iteration deleted (the followed ones,
// tracked[0 .. n), of state deleted) after the `logged` earlier ones, to
// count the points inserted more than once at the end. A worklist counter
// places them: their order reaches nothing.
__kernel void log_deleted_points(__global const int *tracked, __global const int *point_state,
                                 __global const double2 *points, __global double2 *deletion_log,
                                 const int logged, volatile __global int *count, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int p = tracked[k];
  if (point_state[p] == CLM_POINT_DELETED)
    deletion_log[logged + atomic_inc(count)] = points[p];
}

// The boundary routine of thesis §3.4.1, before step 3: for each hull
// midpoint v of this iteration, on the former hull edge a-b with apex c, the
// off-centers among c and c's neighbours that encroach a-b are marked
// redundant (Triangle would not have inserted them: it splits the edge
// instead). Three kernels over the new points, so that the list of the old
// points marked is the same on every run: each encroacher is claimed by the
// smallest midpoint (claim), the midpoints count the old ones they own
// (count), and write them after a prefix sum (write).
#define CLM_ENCROACH_CLAIM 0
#define CLM_ENCROACH_COUNT 1
#define CLM_ENCROACH_WRITE 2

__kernel void
mark_encroaching_points(__global const int *new_points, __global const double2 *points,
                        __global const int *tri_vertex, __global const int *tri_neighbor,
                        __global const int *vertex_triangle, __global const int *point_state,
                        const double lens, const int step, volatile __global int *claim,
                        __global int *redundant_mark, __global int *redundant_anchor,
                        __global int *owned, __global const int *offset, __global int *tracked,
                        const int first, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int v = new_points[k];
  if (step == CLM_ENCROACH_COUNT)
    owned[k] = 0;
  if (point_state[v] != CLM_POINT_NEW_MIDPOINT)
    return;
  // Just after its 1-2 split, v has two real triangles (v,a,c) and (v,c,b).
  const int t = vertex_triangle[v], i = index_in(tri_vertex, t, v);
  const int x = tri_vertex[3 * t + next3(i)], y = tri_vertex[3 * t + prev3(i)];
  const int across_vx = link_triangle(tri_neighbor[3 * t + prev3(i)]);
  const int across_yv = link_triangle(tri_neighbor[3 * t + next3(i)]);
  const bool x_on_hull = is_ghost(load_vertices(tri_vertex, across_vx));
  const int a = x_on_hull ? x : y, c = x_on_hull ? y : x, other = x_on_hull ? across_yv : across_vx;
  const int j = index_in(tri_vertex, other, v);
  int b = tri_vertex[3 * other + next3(j)];
  if (b == c)
    b = tri_vertex[3 * other + prev3(j)];
  if (a < 0 || b < 0 || c < 0)
    return;
  // c, then its neighbours around it.
  int s = t, q = c, count = 0;
  for (int around = 0; around < 64; ++around) {
    if (q >= 0) {
      const int state = point_state[q];
      if ((state == CLM_POINT_STEINER || state == CLM_POINT_NEW) &&
          in_lens(points[a], points[b], points[q], lens)) {
        if (step == CLM_ENCROACH_CLAIM) {
          atomic_min(&claim[q], k);
        } else if (claim[q] == k) {
          if (step == CLM_ENCROACH_COUNT) {
            redundant_mark[q] = 1;
            redundant_anchor[q] = s;
          }
          if (state == CLM_POINT_STEINER) {
            if (step == CLM_ENCROACH_WRITE)
              tracked[first + offset[k] + count] = q;
            ++count;
          }
        }
      }
    }
    const int kc = index_in(tri_vertex, s, c);
    s = next_around(tri_neighbor, s, kc);
    if (s == t)
      break;
    q = star_vertex(tri_vertex, s, c);
  }
  if (step == CLM_ENCROACH_COUNT)
    owned[k] = count;
}

// Resets the claims of the boundary routine for the next iteration.
__kernel void clear_encroaching_claims(__global const int *tracked, __global int *claim,
                                       const int n) {
  const int k = get_global_id(0);
  if (k < n)
    claim[tracked[k]] = 0x7fffffff;
}

// A stall (no operation left, yet redundant points remain, in degenerate
// stars where neither a flop nor a removal is possible): they are kept, as
// Steiner points of earlier iterations, after their stars were listed.
__kernel void keep_stuck_points(__global const int *tracked, __global int *point_state,
                                volatile __global int *kept, const int n) {
  const int k = get_global_id(0);
  if (k < n && point_state[tracked[k]] == CLM_POINT_REDUNDANT) {
    point_state[tracked[k]] = CLM_POINT_STEINER;
    atomic_inc(kept);
  }
}

// Free lists (thesis §3.6.1): flags of the empty triangle slots (and, below,
// of the deleted points' slots), compacted into sorted lists by the host's scan.
__kernel void flag_dead_triangles(__global const int *tri_vertex, __global int *keep, const int n) {
  const int t = get_global_id(0);
  if (t < n)
    keep[t] = tri_vertex[3 * t] == CLM_DEAD;
}

// Compaction (thesis §3.6.1 collects the empty slots; here the live
// triangles also move into spatial order, so that a triangle's neighbours
// share its cache lines: the refinement's kernels are bound by those random
// accesses on a CPU). Each live triangle gets the cell of its centre on a
// Z-order curve over the bounding box (2^bits cells a side, scale: cells per
// unit); the host buckets them by cell (PrefixScan::bucket), each cell is
// sorted (below), and the triangles move there.
inline uint spread_bits(uint x) { // bit i of x to bit 2i
  x &= 0xffffu;
  x = (x | (x << 8)) & 0x00ff00ffu;
  x = (x | (x << 4)) & 0x0f0f0f0fu;
  x = (x | (x << 2)) & 0x33333333u;
  return (x | (x << 1)) & 0x55555555u;
}

inline int cell_coordinate(double x, double low, double scale, int bits) {
  return clamp((int)((x - low) * scale), 0, (1 << bits) - 1);
}

inline int z_cell(double2 p, double2 low, double scale, int bits) {
  return (int)(spread_bits((uint)cell_coordinate(p.x, low.x, scale, bits)) |
               (spread_bits((uint)cell_coordinate(p.y, low.y, scale, bits)) << 1));
}

// The triangles leave the compaction in a layout that depends on the mesh
// alone, not on the slots it came in (so refinement, which breaks ties by
// slot, gives the same mesh whichever construction built the first
// triangulation): each triangle starts at its smallest vertex (the vertex at
// infinity counts as the largest), and a cell's triangles go in the order of
// their first two vertices, a directed edge that no other triangle starts with.
// (The output's canonical order, mesh_output.cl, starts triangles likewise.)
inline VertexTriple rotated_by(VertexTriple tri, int r) {
  const int a = tri.v[0], b = tri.v[1], c = tri.v[2];
  VertexTriple rotated; // rotated.v[i] = tri.v[(i + r) % 3], without private indexing
  rotated.v[0] = r == 0 ? a : (r == 1 ? b : c);
  rotated.v[1] = r == 0 ? b : (r == 1 ? c : a);
  rotated.v[2] = r == 0 ? c : (r == 1 ? a : b);
  return rotated;
}

// cell[t]: the Z-order cell of triangle t, -1 for an empty slot; key[t]: its
// place inside the cell, the first two vertices after the rotation (a point
// number is below 2^30, so the first fits 30 bits), then the rotation.
__kernel void triangle_cells(__global const double2 *points, __global const int *tri_vertex,
                             const double2 low, const double scale, const int bits,
                             __global int *cell, __global ulong *key, const int n) {
  const int t = get_global_id(0);
  warm_corners(points, 0, tri_vertex, slot_ahead(t, 1, n)); // prefetching (prefetch.h)
  if (t >= n)
    return;
  VertexTriple tri = load_vertices(tri_vertex, t);
  if (is_dead(tri)) {
    cell[t] = -1;
    return;
  }
  const int r = canonical_start(tri);
  tri = rotated_by(tri, r);
  double2 sum = (double2)(0, 0); // of the real vertices (two for a ghost)
  int real = 0;
  for (int i = 0; i < 3; ++i)
    if (tri.v[i] >= 0) {
      sum += points[tri.v[i]];
      ++real;
    }
  cell[t] = z_cell(sum / (double)real, low, scale, bits);
  key[t] = ((ulong)tri.v[0] << 34) | ((ulong)(uint)tri.v[1] << 2) | (ulong)r;
}

// The Steiner points move likewise (their triangles' loads of points and
// states follow): cell[k] of point first + k, -1 for a deleted one. The
// input points keep their slots, hence their numbers; key[k]: the slot (a
// cell's points keep their order).
__kernel void steiner_point_cells(__global const double2 *points, __global const int *point_state,
                                  const double2 low, const double scale, const int bits,
                                  __global int *cell, __global ulong *key, const int first,
                                  const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  cell[k] = point_state[first + k] == CLM_POINT_DELETED
                ? -1
                : z_cell(points[first + k], low, scale, bits);
  key[k] = (ulong)k;
}

// Moves a[root] down the max-heap a[0 .. size), ordered by key[a[i]], to its place.
inline void sift_down_by_key(__global int *a, __global const ulong *key, int root, int size) {
  const int x = a[root];
  const ulong x_key = key[x];
  for (int child = 2 * root + 1; child < size; child = 2 * root + 1) {
    if (child + 1 < size && key[a[child]] < key[a[child + 1]])
      ++child;
    if (key[a[child]] <= x_key)
      break;
    a[root] = a[child];
    root = child;
  }
  a[root] = x;
}

// Sorts a[0 .. size) by key[a[i]] ascending: insertion sort when short, else
// heap sort (a crowded cell must not cost its size squared).
inline void sort_by_key(__global int *a, __global const ulong *key, int size) {
  if (size <= 32) {
    for (int i = 1; i < size; ++i) {
      const int x = a[i];
      const ulong x_key = key[x];
      int j = i - 1;
      for (; j >= 0 && key[a[j]] > x_key; --j)
        a[j + 1] = a[j];
      a[j + 1] = x;
    }
    return;
  }
  for (int root = size / 2 - 1; root >= 0; --root)
    sift_down_by_key(a, key, root, size);
  for (int end = size - 1; end > 0; --end) {
    const int top = a[0];
    a[0] = a[end];
    a[end] = top;
    sift_down_by_key(a, key, 0, end);
  }
}

// new_slot[item] for the items of each cell, in the order of their keys:
// the new place, or with `rotated` (triangles) the new place and the
// rotation (key's low two bits) as a link, (place << 2) | rotation.
__kernel void sort_cells(__global const int *cell_start, __global const int *cell_size,
                         __global const ulong *key, const int rotated, __global int *order,
                         __global int *new_slot, const int cells) {
  const int c = get_global_id(0);
  if (c >= cells)
    return;
  const int start = cell_start[c], size = cell_size[c];
  sort_by_key(order + start, key, size);
  for (int i = 0; i < size; ++i) {
    const int item = order[start + i];
    new_slot[item] = rotated ? encode_link(start + i, (int)(key[item] & 3)) : start + i;
  }
}

// Triangle order[k] moves to slot k, rotated to start at its smallest vertex
// (new_slot: (slot << 2) | rotation of every old slot).
__kernel void move_triangles(__global const int *order, __global const int *new_slot,
                             __global const int *tri_vertex, __global const int *tri_neighbor,
                             __global int *moved_vertex, __global int *moved_neighbor,
                             const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int t = order[k];
  const int r = link_edge(new_slot[t]);
  for (int i = 0; i < 3; ++i) { // new index i, old index (i + r) % 3
    const int link = tri_neighbor[3 * t + (i + r) % 3];
    const int u = new_slot[link_triangle(link)];
    moved_vertex[3 * k + i] = tri_vertex[3 * t + (i + r) % 3];
    moved_neighbor[3 * k + i] =
        encode_link(link_triangle(u), (link_edge(link) + 3 - link_edge(u)) % 3);
  }
}

// Every point q < n of the new arrays takes its coordinates, state,
// insertion radius and priority from point p: itself for an input point
// (q < first), first + order[q - first] for a Steiner point.
__kernel void move_steiner_points(__global const int *order, __global const double2 *points,
                                  __global const int *point_state,
                                  __global const double *insertion_radius2,
                                  __global const uint *point_priority,
                                  __global double2 *moved_point, __global int *moved_state,
                                  __global double *moved_radius2, __global uint *moved_priority,
                                  __global int *original_id, const int first, const int n) {
  const int q = get_global_id(0);
  if (q >= n)
    return;
  const int p = q < first ? q : first + order[q - first];
  moved_point[q] = points[p];
  moved_state[q] = point_state[p];
  moved_radius2[q] = insertion_radius2[p];
  moved_priority[q] = point_priority[p];
  if (q >= first)
    original_id[q] = q; // numbered again at the end (number_steiner_points)
}

// The triangles' Steiner vertices take their new slots (new_slot[k]: of
// point first + k, relative to first).
__kernel void renumber_steiner_vertices(__global const int *new_slot, __global int *tri_vertex,
                                        const int first, const int n) {
  const int k = get_global_id(0);
  if (k >= n)
    return;
  const int v = tri_vertex[k];
  if (v >= first)
    tri_vertex[k] = first + new_slot[v - first];
}

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

// keep[k] = whether point first + k is deleted (deleted = 1) or not (deleted = 0).
__kernel void flag_deleted_points(__global const int *point_state, const int deleted,
                                  __global int *keep, const int first, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    keep[k] = (point_state[first + k] == CLM_POINT_DELETED) == deleted;
}
