// clmesh — one int per triangle slot that two steps of a refinement
// iteration use in turn (thesis §3.3.2): step 1's tie marks, the smallest
// candidate of the best priority a triangle holds (mark_candidate_ties,
// cl/offcenter_insertion.cl), and step 3's removal claims, the smallest entry
// removing a star whose smallest slot it is (cl/flip_flop.cl). Each step
// leaves every entry empty (kNoClaim) when it ends, so one array serves both.
#pragma once

#include "runtime/device_mesh.hpp"

#include <cstddef>

namespace clmesh {

class TriangleClaims {
public:
  static constexpr cl_int kNoClaim = 0x7fffffff; // CLM_NO_CANDIDATE, CLM_NO_POINT

  TriangleClaims(Device &device, const DeviceMesh &mesh)
      : device_(device), claims_(device, mesh.triangle_capacity) {}

  // Empty entries for the slots below `slots`: those that came into use
  // since the last call are set then (a little ahead, fill_ahead), so that
  // the pages past the used slots are not touched.
  void cover(std::size_t slots, const char *phase) {
    if (slots <= filled_)
      return;
    const std::size_t end = fill_ahead(slots, claims_.size());
    claims_.fill_range(device_, kNoClaim, filled_, end - filled_, phase);
    filled_ = end;
  }
  const cl::Buffer &buffer() const { return claims_.buffer(); }

private:
  Device &device_;
  DeviceArray<cl_int> claims_;
  std::size_t filled_ = 0; // entries below this are set
};

} // namespace clmesh
