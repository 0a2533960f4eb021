// clmesh — Phase 4 of GPU-DT: missing-point insertion in conflict-free rounds
// (thesis §2.3, §4.1.2). Kernels: cl/missing_point_insertion.cl.
#pragma once

#include "runtime/prefix_scan.hpp"
#include "runtime/scratch_pool.hpp"

#include <vector>

namespace clmesh {

class MissingPointInsertion {
public:
  static constexpr const char *kPhase = "missing_point_insertion";

  // With a `pool`, the lists of a round but changed() are those of the pool
  // (scratch_lists): no other user of the pool runs from set_points to the
  // end of the round, and the lists' contents are not needed after it
  // (refinement inserts its points in one round).
  MissingPointInsertion(Device &device, DeviceMesh &mesh, PrefixScan &scan,
                        const ScratchPool *pool = nullptr);
  // The sizes in bytes of the lists it takes from a ScratchPool.
  static std::vector<std::size_t> scratch_lists(const DeviceMesh &mesh);

  // Points still to insert, each starting its walk from location[point].
  void set_points(const std::vector<cl_int> &points);
  // The same from a list on the device (its first `count` entries).
  void set_points(const DeviceArray<cl_int> &points, std::size_t count);
  // Points of a later level (none pending), each starting its walk where
  // anchors[k], a point inserted before, was located (cl start_at_anchors).
  void set_points_near(const std::vector<cl_int> &points, const std::vector<cl_int> &anchors);
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
  // Points of the last round: the most entries a list took, but changed().
  std::size_t entries_used() const { return round_points_; }
  // With no point pending: changed() keeps the memory of the last round's
  // entries, which the next round (of about the same size) writes again,
  // and gives the rest back to the system (DeviceArray::discard); so do
  // the other lists without a pool.
  void trim_lists();

private:
  // The lists that a pool may hold, in the order of scratch_lists.
  enum List { kRemaining, kRemainingNext, kStatus, kWinner, kOffset, kKeep, kLists };
  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel locate_, mark_, select_, clear_marks_, split_, relink_, count_remaining_,
      round_in_group_, start_at_anchors_;
  // Rounds of at most this many points (with room for all to win) run by
  // one work-group in one launch, from the marks to the relinking
  // (insert_round_in_group).
  static constexpr std::size_t kInGroup = 4096;
  std::size_t group_ = 1; // insert_round_in_group's work-group size
  DeviceArray<cl_int> remaining_, remaining_next_, status_, winner_;
  DeviceArray<cl_int> offset_; // prefix sums: of winner_ (split), then of keep_ (compact)
  DeviceArray<cl_int> keep_, changed_;
  // Lost walks, the running total of points left waiting (count_remaining)
  // and the winners of a round by one work-group.
  static constexpr std::size_t kCounters = 3;
  DeviceArray<cl_int> counters_;
  cl_uint waiting_total_ = 0; // counters_[1] as last read
  std::size_t pending_ = 0;
  std::size_t round_points_ = 0; // points of the last round
  bool pooled_ = false;
  int located_since_ = 0; // stamp of the last walk: older triangles keep their points
  std::size_t duplicates_ = 0;
};

} // namespace clmesh
