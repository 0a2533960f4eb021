// clmesh — the boundary routine of thesis §3.4.1, at the start of step 3:
// the Steiner points in the diametral circle of a hull edge or subsegment
// split in this iteration are marked redundant, for flip-flop to delete (as Triangle
// deletes them when it splits a subsegment). Kernels:
// cl/hull_encroachment.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

#include <optional>

namespace clmesh {

class HullEncroachment {
public:
  static constexpr const char *kPhase = "flipflop_deletion"; // timed with step 3

  HullEncroachment(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // `tracked` receives new_points[0 .. m). For each midpoint among them,
  // the off-centers around the apexes of its former hull edge or subsegment
  // that lie in the edge's diametral circle are marked redundant
  // (redundant_mark, redundant_anchor), and the old ones among them are
  // appended to `tracked` from entry m on. Returns how many were appended, or
  // none with few new points: the count is then left in appended()[0] on the
  // device (read_appended() reads it). Which midpoint claims an encroacher is
  // decided by index, so the list is the same on every run.
  std::optional<std::size_t> mark_encroaching(const DeviceArray<cl_int> &new_points, std::size_t m,
                                              const DeviceArray<cl_int> &redundant_mark,
                                              const DeviceArray<cl_int> &redundant_anchor,
                                              const DeviceArray<cl_int> &tracked);
  // Between calls: the per-new-point lists keep the memory of the last
  // call's entries, which the next one (of about the same size) writes
  // again, and give the rest back to the system (DeviceArray::discard).
  void trim_lists();
  const DeviceArray<cl_int> &appended() const { return appended_; }
  std::size_t read_appended() const { return static_cast<std::size_t>(appended_.read(device_, 0)); }

private:
  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  // At most this many new points go through the steps by one work-group in
  // one launch (mark_encroaching_in_group), more by a launch a step.
  static constexpr std::size_t kInGroup = 4096;
  cl::Kernel mark_, clear_claims_, mark_in_group_;
  // Per point: the smallest midpoint claiming it (empty: 0x7fffffff between calls).
  DeviceArray<cl_int> claim_;
  std::size_t claims_filled_ = 0;      // claim_ is set (empty) below this point
  DeviceArray<cl_int> owned_, offset_; // per new point: old encroachers it claims
  std::size_t new_points_ = 0;         // of the last call
  DeviceArray<cl_int> appended_;       // mark_encroaching_in_group's result
  std::size_t group_;                  // and its work-group size
};

} // namespace clmesh
