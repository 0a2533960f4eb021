// clmesh — GPU-CDT step 2: inserting the constraints by marking and flipping
// (thesis §4.3, Algorithms 4.1 and 4.2). Kernels: cl/constraint_marking.cl.
#pragma once

#include "prefix_scan.hpp"

#include "clmesh/constrained.hpp"

#include <array>
#include <vector>

namespace clmesh {

class ConstraintInsertion {
public:
  static constexpr const char *kPhase = "constraint_insertion";
  static constexpr int kInnerIterations = 8; // inner loop passes per outer iteration

  ConstraintInsertion(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // Maps segment endpoints that are duplicate points to the kept point.
  std::vector<Segment> resolve_duplicates(const std::vector<Segment> &segments);

  // Uploads the constraints (device point numbers, no duplicates, no
  // zero-length ones) as compressed rows per vertex, for every later phase.
  void set_constraints(const std::vector<Segment> &segments);

  // Inserts every constraint. Segments through a vertex are split there
  // (segments() then holds the pieces). Throws InputError when two segments
  // cross away from a vertex; original_id maps device points to input ones.
  void run(int &stamp, ConstrainedStats &stats, const std::vector<int32_t> &original_id);

  const std::vector<Segment> &segments() const { return segments_; }

private:
  // One outer iteration's marking; returns the segments still to insert, or
  // -1 when segments were split at vertices (the marking must be redone).
  long mark(ConstrainedStats &stats, bool first, const std::vector<int32_t> &original_id);
  // Active list of every marked triangle; returns its length.
  std::size_t collect_marked();
  // One inner iteration over `active` triangles; returns the flips made and
  // leaves the still-marked triangles in active_.
  long inner_iteration(std::size_t &active, int stamp);

  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel resolve_duplicates_, record_vertex_triangles_, mark_, plan_, apply_, relink_, remark_,
      keep_marked_, flag_marked_;
  std::vector<Segment> segments_;
  std::vector<int32_t> origin_;    // input segment each constraint comes from
  std::vector<char> split_origin_; // input segments already counted as split
  DeviceArray<cl_int> segment_a_, segment_b_, segment_state_, split_vertex_, counters_,
      constraint_mark_, active_, next_active_, keep_, offset_, plan_list_, next_, previous_,
      flipped_, flip_count_;
};

} // namespace clmesh
