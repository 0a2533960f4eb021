// clmesh — Phase 3 of GPU-DT: shifting the sites back to their real
// coordinates and checking what that leaves (thesis §4.1.2). Kernels:
// cl/shifting.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

namespace clmesh {

class Shifting {
public:
  static constexpr const char *kPhase = "shifting";
  // A bound on untangle's passes; each pass after the first flips only what
  // the flips before made possible, and few of them flip anything.
  static constexpr int kUntanglingPasses = 8;

  Shifting(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // The check at the real coordinates of the triangles in slots [0, real)
  // (ghosts follow up to `slots`): turned ones (not strictly counter-
  // clockwise) are untangled by flips where their middle site lies inside
  // the triangle across their longest edge or beyond a hull edge there
  // (cl/shifting.cl), pass after pass while flips go ahead, each pass with
  // a stamp of its own from `stamp` (the flips' children; the slots get
  // their stamps first); the middle sites of those still turned are flagged
  // in `bad`. Returns how many flips there were.
  long untangle(std::size_t real, std::size_t slots, const DeviceArray<cl_int> &bad, int &stamp);

  // Leaves the sites flagged in `bad` out of the next diagram (site_state),
  // with the other points of their pixels (`diagram` and `pixel_of`: this
  // round's), and clears `bad`; returns how many sites were flagged.
  long leave_out_flagged(const DeviceArray<cl_int> &bad, const DeviceArray<cl_int> &site_state,
                         const DeviceArray<cl_int> &diagram, const DeviceArray<cl_int> &pixel_of);

  // After the ghost flips: whether the outer cycle of the mesh's slots is
  // convex and winds around once.
  bool boundary_winds_once();

  // Lists the points that are in no triangle (Phase 4's missing points) in
  // `missing`, each located at a triangle of the site of its pixel; returns
  // how many there are.
  std::size_t collect_missing(const DeviceArray<cl_int> &diagram,
                              const DeviceArray<cl_int> &pixel_of,
                              const DeviceArray<cl_int> &missing);

private:
  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel list_turned_, claim_flips_, apply_flips_, relink_, flag_turned_, leave_out_,
      count_lowest_, record_triangles_, flag_missing_;
  DeviceArray<cl_int> counter_;
  // untangle's: the turned triangles and the claims of slots.
  DeviceArray<cl_int> turned_, claim_;
};

} // namespace clmesh
