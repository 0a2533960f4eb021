// clmesh — Phase 3 of GPU-DT: shifting the sites back to their real
// coordinates and checking what that leaves (thesis §4.1.2). Kernels:
// cl/shifting.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

namespace clmesh {

class Shifting {
public:
  static constexpr const char *kPhase = "shifting";

  Shifting(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // Flags in `bad` the sites of the triangles in slots [0, real) that are not
  // strictly counter-clockwise at the real coordinates.
  void flag_inverted(std::size_t real, const DeviceArray<cl_int> &bad);

  // Leaves the sites flagged in `bad` out of the next diagram (site_state)
  // and clears `bad`; returns how many were left out.
  long leave_out_flagged(const DeviceArray<cl_int> &bad, const DeviceArray<cl_int> &site_state);

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
  cl::Kernel flag_inverted_, leave_out_, count_lowest_, record_triangles_, flag_missing_;
  DeviceArray<cl_int> counter_;
};

} // namespace clmesh
