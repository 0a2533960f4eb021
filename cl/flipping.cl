// clmesh — Phase 5 of GPU-DT: parallel edge flipping (thesis §4.1.2, §3.3.2, §3.6).
//
// Works on an active list of triangles (§3.6.2). A pass (1) tests the edges of
// every active triangle with the floating-point filter and sends the few
// uncertain ones to a second kernel that runs the exact predicate (§3.6.3);
// each triangle then proposes its first non-Delaunay edge and marks both
// sides with atomic minimum of the edge key; (2) flips the edges that own both
// marks (2-2 flip); (3) relinks neighbours in a second step and collects the
// flipped and the still-unhappy triangles as the next active list. The list
// is a worklist: which edges flip depends only on the keys, never on the
// order of its entries. Ghost triangles make the hull convex: two ghosts
// sharing a hull vertex flip when that vertex is reflex; real-ghost edges
// never flip.
#include "common.h"
#include "mesh_params.h"
#include "prefetch.h"

// active_round[t] = round for the triangles of this pass's list.
__kernel void flip_mark_active(__global const int *active, __global int *active_round,
                               const int round, const int n) {
  const int gid = get_global_id(0);
  if (gid < n && active[gid] >= 0)
    active_round[active[gid]] = round;
}

// The proposal of triangle t (-1 when none): its first flippable edge i (bits:
// the edges that must flip), keyed 3t + i; both triangles of the edge take
// atomic minimum of the key.
static inline int propose_flip(__global const int *tri_neighbor, volatile __global uint *tri_mark,
                               int t, int bits) {
  if (t < 0 || bits == 0)
    return -1;
  const int i = (bits & 1) ? 0 : ((bits & 2) ? 1 : 2);
  const int u = link_triangle(tri_neighbor[3 * t + i]);
  const uint key = (uint)(3 * t + i);
  atomic_min(&tri_mark[t], key);
  atomic_min(&tri_mark[u], key);
  return encode_link(u, i);
}

// The edges of listed triangle t (-1: none) that must flip, bit i for edge
// i, and bit 3+i for an edge the filter could not tell. An edge between two
// listed triangles is tested once, by the smaller one (thesis §3.3.2,
// Algorithm 3.1 line 8).
static inline int check_triangle(int t, __global const double2 *points,
                                 __global const int *tri_vertex, __global const int *tri_neighbor,
                                 __global const int *constraint_start,
                                 __global const int *constraint_adjacent, int constrained,
                                 int fixed_boundary, __global const int *active_round, int round) {
  int bits = 0;
  const VertexTriple tri = t >= 0 ? load_vertices(tri_vertex, t) : (VertexTriple){{CLM_DEAD}};
  if (t >= 0 && !is_dead(tri)) {
    for (int i = 0; i < 3; ++i) {
      const int link = tri_neighbor[3 * t + i], u = link_triangle(link);
      if (u < t && active_round[u] == round)
        continue;
      const int verdict = edge_must_flip(points, constraint_start, constraint_adjacent, constrained,
                                         fixed_boundary, tri.v[i], tri.v[next3(i)], tri.v[prev3(i)],
                                         tri_vertex[3 * u + link_edge(link)], 0);
      if (verdict == CLM_FLIP)
        bits |= 1 << i;
      else if (verdict == CLM_UNCERTAIN)
        bits |= 8 << i;
    }
  }
  return bits;
}

// check_triangle's bits with the uncertain edges decided by the exact,
// perturbed in-circle test (only real edges that are not constraints are
// uncertain).
static inline int resolve_uncertain(int t, int bits, __global const double2 *points,
                                    __global const int *tri_vertex,
                                    __global const int *tri_neighbor) {
  for (int i = 0; i < 3; ++i)
    if (bits & (8 << i)) {
      const int link = tri_neighbor[3 * t + i];
      const int c = tri_vertex[3 * t + i], a = tri_vertex[3 * t + next3(i)],
                b = tri_vertex[3 * t + prev3(i)],
                d = tri_vertex[3 * link_triangle(link) + link_edge(link)];
      if (incircle_verdict(points, c, a, b, d, 1) == CLM_FLIP)
        bits |= 1 << i;
    }
  return bits & 7;
}

// Flips proposal prop of triangle t when it owns both marks (see
// flip_edge); returns whether it did.
static inline int apply_proposal(int t, int prop, volatile __global const uint *tri_mark,
                                 __global int *tri_vertex, __global int *tri_neighbor,
                                 __global int *modified_stamp, __global int *children, int stamp) {
  if (prop < 0)
    return 0;
  const int u = link_triangle(prop), i = link_edge(prop);
  const uint key = (uint)(3 * t + i);
  if (tri_mark[t] != key || tri_mark[u] != key)
    return 0;
  flip_edge(tri_vertex, tri_neighbor, modified_stamp, children, t, i, stamp);
  return 1;
}

// After the flips of a pass: relinks the outward edges (1 and 2) of both
// triangles of an applied flip, clears the proposal's marks, and lists in
// listed[] what goes to the next pass: both sides of a flip, or a proposer
// whose flip lost (a triangle flipped by a neighbour is listed by that
// neighbour; a happy one leaves). Returns how many were listed.
static inline int relink_and_list(int t, int prop, int flipped, __global const int *tri_vertex,
                                  __global int *tri_neighbor, __global const int *modified_stamp,
                                  __global const int *children, volatile __global uint *tri_mark,
                                  int stamp, int *listed) {
  if (prop < 0)
    return 0;
  const int u = link_triangle(prop);
  int count = 0;
  if (flipped) {
    for (int e = 1; e < 3; ++e) {
      relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, t, e);
      relink_edge(tri_vertex, tri_neighbor, modified_stamp, children, stamp, u, e);
    }
    listed[count++] = t;
    listed[count++] = u;
  } else if (modified_stamp[t] != stamp) {
    listed[count++] = t;
  }
  tri_mark[t] = CLM_NO_MARK;
  tri_mark[u] = CLM_NO_MARK;
  return count;
}

// Prefetching for flip_check_fast (prefetch.h): what
// prefetch_triangle_and_neighbours warms, and the rounds and marks of the
// neighbours of the triangle two stages ahead (its links warm), which the
// test of each edge and the proposal read.
static inline void prefetch_check(__global const int *active, int gid, int n,
                                  __global const double2 *points, __global const int *tri_vertex,
                                  __global const int *tri_neighbor,
                                  __global const int *active_round,
                                  volatile __global const uint *tri_mark) {
  prefetch_triangle_and_neighbours(active, gid, n, points, 0, tri_vertex, tri_neighbor);
  const int t = entry_ahead(active, gid, 2, n);
  warm_marks_around(tri_mark, tri_neighbor, t);
  for (int i = 0; i < 3 && t >= 0; ++i)
    warm(active_round + link_triangle(tri_neighbor[3 * t + i]));
}

// flags[gid]: check_triangle's bits for active[gid]. The triangles the
// filter decided propose at once (proposal[gid]); the others do in
// flip_check_exact.
__kernel void flip_check_fast(CLM_TRIANGULATION_PARAMS, __global const int *active,
                              const int fixed_boundary, __global const int *active_round,
                              const int round, __global int *flags, __global int *exact_list,
                              volatile __global int *exact_count, __global int *proposal,
                              const int n) {
  const int gid = get_global_id(0);
  prefetch_check(active, gid, n, points, tri_vertex, tri_neighbor, active_round, tri_mark);
  if (gid >= n)
    return;
  const int t = active[gid];
  const int bits =
      check_triangle(t, points, tri_vertex, tri_neighbor, constraint_start, constraint_adjacent,
                     constrained, fixed_boundary, active_round, round);
  flags[gid] = bits;
  if (bits & 0x38)
    exact_list[atomic_inc(exact_count)] = gid; // proposes after the exact check
  else
    proposal[gid] = propose_flip(tri_neighbor, tri_mark, t, bits);
}

// Resolves the uncertain edges with the exact, perturbed in-circle test: as
// many as flip_check_fast counted (read here, not by the host: no round
// trip), each work-item taking its share (share_of).
__kernel void flip_check_exact(CLM_TRIANGULATION_PARAMS, __global const int *exact_list,
                               __global const int *active, __global int *flags,
                               __global int *proposal, __global const int *exact_count) {
  const int n = *exact_count;
  const Share share = share_of(get_global_id(0), get_global_size(0), n);
  for (int k = share.first; k < share.end; k += share.step) {
    const int index = exact_list[k], t = active[index];
    const int bits = resolve_uncertain(t, flags[index], points, tri_vertex, tri_neighbor);
    flags[index] = bits;
    proposal[index] = propose_flip(tri_neighbor, tri_mark, t, bits);
  }
}

// 2-2 flip of the proposals that own both marks (apply_proposal).
__kernel void flip_apply(CLM_TRIANGULATION_PARAMS, __global const int *active,
                         __global const int *proposal, __global int *flipped,
                         volatile __global int *pass_counts, const int stamp, const int n) {
  const int gid = get_global_id(0);
  const int ahead = entry_ahead(proposal, gid, 1, n); // prefetching (prefetch.h)
  if (ahead >= 0) {
    warm_rewritten(tri_vertex, tri_neighbor, modified_stamp, children, tri_mark,
                   active[gid + CLM_AHEAD]);
    warm_rewritten(tri_vertex, tri_neighbor, modified_stamp, children, tri_mark,
                   link_triangle(ahead));
  }
  int did_flip = 0;
  if (gid < n) {
    did_flip = apply_proposal(active[gid], proposal[gid], tri_mark, tri_vertex, tri_neighbor,
                              modified_stamp, children, stamp);
    flipped[gid] = did_flip;
  }
  volatile __local int scratch[2];
  reserve_in_group(did_flip, scratch, &pass_counts[0]); // counts the flips
}

// Second step (relink_and_list): listed triangles get active_round =
// next_round; pass_counts[1]: the next list's length.
__kernel void flip_relink_and_collect(CLM_TRIANGULATION_PARAMS, __global const int *active,
                                      __global const int *proposal, __global const int *flipped,
                                      const int stamp, __global int *next_active,
                                      __global int *active_round, const int next_round,
                                      volatile __global int *pass_counts, const int n) {
  const int gid = get_global_id(0);
  const int ahead = gid + CLM_AHEAD; // prefetching (prefetch.h)
  if (entry_ahead(flipped, gid, 1, n) > 0) {
    warm_across_edges(tri_neighbor, modified_stamp, children, active[ahead], 1, 3);
    warm_across_edges(tri_neighbor, modified_stamp, children, link_triangle(proposal[ahead]), 1, 3);
  }
  int listed[2];
  const int count =
      gid < n ? relink_and_list(active[gid], proposal[gid], flipped[gid], tri_vertex, tri_neighbor,
                                modified_stamp, children, tri_mark, stamp, listed)
              : 0;
  for (int k = 0; k < count; ++k)
    active_round[listed[k]] = next_round;
  volatile __local int scratch[2];
  append_in_group(listed, count, next_active, &pass_counts[1], scratch);
}

// Passes by one work-group, for short lists: the kernels above in order
// (check with the exact test at once, apply, relink and collect), with
// barriers between them instead of launches, pass after pass while the list
// is not empty and at most `limit` long, at most max_passes of them. The
// list alternates between list_a and list_b (2 * limit entries each),
// starting in list_a with n_first entries marked for round `round`; pass k
// uses stamp + k. Entry by entry the results are those of the kernels: which
// edges flip depends only on the keys. result: [0] passes, [1] flips, [2]
// the last list's length (in list_b after an odd number of passes), [3]
// uncertain triangles.
__kernel void flip_passes_in_group(CLM_TRIANGULATION_PARAMS, __global int *list_a,
                                   __global int *list_b, const int n_first,
                                   const int fixed_boundary, __global int *active_round,
                                   const int round, __global int *proposal, __global int *flipped,
                                   const int stamp, const int limit, const int max_passes,
                                   __global int *result) {
  const int lid = get_local_id(0), size = get_local_size(0);
  volatile __local int counts[3]; // next list's length, flips, uncertain triangles
  if (lid == 0)
    counts[1] = counts[2] = 0;
  barrier(CLK_LOCAL_MEM_FENCE); // cleared before any work-item counts
  int n = n_first, pass = 0;
  while (n > 0 && n <= limit && pass < max_passes) {
    __global int *active = pass % 2 ? list_b : list_a;
    __global int *next_active = pass % 2 ? list_a : list_b;
    if (lid == 0)
      counts[0] = 0;
    for (int k = lid; k < n; k += size) {
      const int t = active[k];
      int bits =
          check_triangle(t, points, tri_vertex, tri_neighbor, constraint_start, constraint_adjacent,
                         constrained, fixed_boundary, active_round, round + pass);
      if (bits & 0x38) {
        atomic_inc(&counts[2]);
        bits = resolve_uncertain(t, bits, points, tri_vertex, tri_neighbor);
      }
      proposal[k] = propose_flip(tri_neighbor, tri_mark, t, bits);
    }
    barrier(CLK_GLOBAL_MEM_FENCE | CLK_LOCAL_MEM_FENCE);
    for (int k = lid; k < n; k += size) {
      flipped[k] = apply_proposal(active[k], proposal[k], tri_mark, tri_vertex, tri_neighbor,
                                  modified_stamp, children, stamp + pass);
      if (flipped[k])
        atomic_inc(&counts[1]);
    }
    barrier(CLK_GLOBAL_MEM_FENCE);
    for (int k = lid; k < n; k += size) {
      int listed[2];
      const int count =
          relink_and_list(active[k], proposal[k], flipped[k], tri_vertex, tri_neighbor,
                          modified_stamp, children, tri_mark, stamp + pass, listed);
      const int first = count > 0 ? atomic_add(&counts[0], count) : 0;
      for (int j = 0; j < count; ++j) {
        next_active[first + j] = listed[j];
        active_round[listed[j]] = round + pass + 1;
      }
    }
    barrier(CLK_GLOBAL_MEM_FENCE | CLK_LOCAL_MEM_FENCE);
    n = counts[0];
    ++pass;
    barrier(CLK_LOCAL_MEM_FENCE); // every work-item has read the length
  }
  if (lid == 0) {
    result[0] = pass;
    result[1] = counts[1];
    result[2] = n;
    result[3] = counts[2];
  }
}
