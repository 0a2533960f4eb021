// clmesh — Phase 5 of GPU-DT: parallel edge flipping over active lists
// (thesis §3.3.2, §3.6.2, §3.6.3). Kernels: cl/flipping.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

namespace clmesh {

struct FlipCounts {
  long flips = 0;
  long passes = 0;
  long exact_checks = 0; // active triangles the filter could not decide
};

class Flipping {
public:
  static constexpr const char *kPhase = "flipping";

  // group_pass_limit: DelaunayOptions::group_pass_limit.
  Flipping(Device &device, DeviceMesh &mesh, std::size_t group_pass_limit);

  // Flips until every edge of the triangles reachable from `active` (n
  // entries, -1 entries ignored) is locally Delaunay. `stamp` numbers each
  // pass; it is advanced past the last one used. Returns false when
  // `max_passes` passes (-1: no limit) did not finish the work.
  bool run(const DeviceArray<cl_int> &active, std::size_t n, int &stamp, FlipCounts &counts,
           long max_passes = -1);

  // During refinement the boundary is fixed: split hull edges stay as they
  // are (a rounded midpoint may leave it a hair from convex), as in Triangle.
  void set_fixed_boundary(bool fixed) { fixed_boundary_ = fixed; }
  // The lists' pages go back to the system between runs (a later run
  // writes those it takes again).
  void trim_lists();
  bool fixed_boundary() const { return fixed_boundary_; }

private:
  // Lists `active` as this round's (active_round_ = ++round_).
  void mark_active(const DeviceArray<cl_int> &active, std::size_t n);
  // flags_[k] bit i set when edge i of triangle active_[k] (n entries,
  // marked for round_) is not locally Delaunay: the filter, then the exact
  // predicate on the uncertain ones; each triangle proposes its first
  // flippable edge (proposal_, marks in tri_mark). *uncertain gets how many
  // went to the exact predicate once the queue has run this far.
  void propose(std::size_t n, cl_int *uncertain);

  Device &device_;
  DeviceMesh &mesh_;
  bool fixed_boundary_ = false;
  // Lists of at most group_pass_limit_ triangles take one work-group for all
  // their passes (flip_passes_in_group) while they stay that short.
  std::size_t group_pass_limit_;
  cl::Kernel mark_active_, check_fast_, check_exact_, apply_, relink_and_collect_, passes_in_group_;
  std::size_t passes_group_limit_ = 1; // CL_KERNEL_WORK_GROUP_SIZE of flip_passes_in_group
  DeviceArray<cl_int> active_, next_active_, exact_list_, proposal_, exact_count_;
  // Per entry of the active list: the edge flags while proposing, then
  // whether the entry flipped (apply, relink): one array, for less memory.
  DeviceArray<cl_int> flags_;
  DeviceArray<cl_int> pass_counts_; // of a pass: {flips, entries of the next list}
  // Per triangle: the last check that listed it (0: none yet), set as far as
  // the mesh's slots are in use (covered before each run).
  CoveredArray<cl_int> active_round_;
  DeviceArray<cl_int> group_result_; // flip_passes_in_group's passes, flips, length, uncertain
  cl_int round_ = 0;
};

} // namespace clmesh
