// clmesh — Phase 5 of GPU-DT: parallel edge flipping over active lists
// (thesis §3.3.2, §3.6.2, §3.6.3). Kernels: cl/flipping.cl.
#pragma once

#include "prefix_scan.hpp"

namespace clmesh {

struct FlipCounts {
  long flips = 0;
  long passes = 0;
  long exact_checks = 0; // active triangles the filter could not decide
};

class Flipping {
public:
  static constexpr const char *kPhase = "flipping";

  Flipping(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // Flips until every edge of the triangles reachable from `active` (n
  // entries, -1 entries ignored) is locally Delaunay. `stamp` numbers each
  // pass; it is advanced past the last one used. Returns false when
  // `max_passes` passes (-1: no limit) did not finish the work.
  bool run(const DeviceArray<cl_int> &active, std::size_t n, int &stamp, FlipCounts &counts,
           long max_passes = -1);

  // The first step of a pass, shared with flip-flop: flags[k] bit i set when
  // edge i of triangle active[k] is not locally Delaunay (the filter, then
  // the exact predicate on the uncertain ones). flags holds n entries.
  void check(const DeviceArray<cl_int> &active, std::size_t n, const DeviceArray<cl_int> &flags,
             FlipCounts &counts);

  // During refinement the boundary is fixed: split hull edges stay as they
  // are (a rounded midpoint may leave it a hair from convex), as in Triangle.
  void set_fixed_boundary(bool fixed) { fixed_boundary_ = fixed; }
  bool fixed_boundary() const { return fixed_boundary_; }

private:
  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  bool fixed_boundary_ = false;
  cl::Kernel mark_active_, check_fast_, check_exact_, propose_, apply_, relink_, count_next_,
      clear_marks_, gather_next_;
  DeviceArray<cl_int> active_, next_active_, flags_, exact_list_, proposal_, flipped_, count_,
      offset_, exact_count_, flip_count_;
  DeviceArray<cl_int> active_round_; // per triangle: the last check that listed it
  cl_int round_ = 0;
};

} // namespace clmesh
