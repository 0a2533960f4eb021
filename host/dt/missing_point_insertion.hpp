// clmesh — Phase 4 of GPU-DT: missing-point insertion in conflict-free rounds
// (thesis §2.3, §4.1.2). Kernels: cl/missing_point_insertion.cl.
#pragma once

#include "runtime/prefix_scan.hpp"
#include "runtime/scratch_watermark.hpp"

#include <vector>

namespace clmesh {

class MissingPointInsertion {
public:
  static constexpr const char *kPhase = "missing_point_insertion";

  MissingPointInsertion(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // Points still to insert, each starting its walk from location[point].
  void set_points(const std::vector<cl_int> &points);
  // The same from a list on the device (its first `count` entries).
  void set_points(const DeviceArray<cl_int> &points, std::size_t count);
  std::size_t pending() const { return pending_; }

  // One round: locate, mark, split the winners' triangles and relink.
  // Returns how many points were inserted; their new triangles are listed in
  // changed() (4 entries per insertion, -1 where unused).
  // walk == false: the points keep the triangle and edge already in
  // location[] and location_edge[] (refinement's hull splits, which must not
  // be moved off their edge by the rounding of their coordinates).
  std::size_t run_round(int stamp, bool walk = true);
  const DeviceArray<cl_int> &changed() const { return changed_; }
  std::size_t duplicates() const { return duplicates_; }
  // With no point pending: the lists give their memory back to the system
  // once their use shrinks (ScratchWatermark); changed() is then lost.
  void trim_lists();

private:
  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel locate_, mark_, select_, clear_marks_, split_, relink_, count_remaining_;
  DeviceArray<cl_int> remaining_, remaining_next_, status_, winner_;
  DeviceArray<cl_int> offset_; // prefix sums: of winner_ (split), then of keep_ (compact)
  DeviceArray<cl_int> keep_, changed_, failures_;
  std::size_t pending_ = 0;
  std::size_t round_points_ = 0; // points of the last round
  ScratchWatermark watermark_;
  int located_since_ = 0; // stamp of the last walk: older triangles keep their points
  std::size_t duplicates_ = 0;
};

} // namespace clmesh
