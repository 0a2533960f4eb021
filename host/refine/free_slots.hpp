// clmesh — the free lists of thesis §3.6.1 (Dealing with variable-size
// arrays): the slots of deleted triangles and points, collected when the
// room past the used ranges runs short, are reused before the arrays grow.
// Kernels: cl/free_slots.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

namespace clmesh {

class FreeSlots {
public:
  static constexpr const char *kPhase = "free_slots";

  FreeSlots(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // Lists the empty triangle and point slots, in slot order, in the mesh's
  // free lists (DeviceMesh::free_triangles, free_points).
  void collect();

private:
  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel flag_dead_, flag_deleted_;
};

} // namespace clmesh
