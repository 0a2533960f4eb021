// clmesh — the final numbering of the Steiner points: deleted points leave
// empty slots (thesis §3.6.1), and the output numbers the survivors after
// the input points, in slot order. Kernels: cl/steiner_renumbering.cl and
// cl/free_slots.cl's flags of deleted points.
#pragma once

#include "runtime/prefix_scan.hpp"

#include "clmesh/geometry.hpp"

#include <vector>

namespace clmesh {

class SteinerRenumbering {
public:
  static constexpr const char *kPhase = "steiner_renumbering";

  SteinerRenumbering(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // Numbers the surviving Steiner points (slots first ..) after the input
  // points in slot order, the deleted ones after them (in original_id), and
  // returns the survivors' coordinates in that order; `segments`, when
  // given, receives the segment each survivor lies on (cl/refinement.h
  // point_segment).
  std::vector<Point> number(std::size_t first, std::vector<int32_t> *segments = nullptr);

private:
  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel flag_deleted_, number_;
};

} // namespace clmesh
