// clmesh — GPU-CDT step 2: inserting the constraints by marking and flipping
// (thesis §4.3, Algorithms 4.1 and 4.2). Kernels: cl/constraint_marking.cl.
#pragma once

#include "runtime/device_mesh.hpp"

#include "cdt/constrained.hpp"

#include <array>
#include <functional>
#include <map>
#include <vector>

namespace clmesh {

// first[i] = 1 unless segments[i] repeats an earlier segment (either direction).
// A first occurrence whose marker is 0 takes the first non-zero marker of its
// repeats, as in Triangle, where a repeated segment marks one without a marker.
std::vector<char> first_occurrences(std::vector<Segment> &segments);

class ConstraintInsertion {
public:
  static constexpr const char *kPhase = "constraint_insertion";
  // Room in the log of edges between runs, per triangle slot (a flip logs at
  // most four; when the log is full, the remaining flips wait for the next
  // outer iteration).
  static constexpr std::size_t kLogPerTriangle = 2;

  ConstraintInsertion(Device &device, DeviceMesh &mesh);

  // Maps segment endpoints that are duplicate points to the kept point.
  std::vector<Segment> resolve_duplicates(const std::vector<Segment> &segments);

  // Uploads the constraints (device point numbers, no zero-length ones) as
  // compressed rows per vertex, for every later phase. Repeats (the pieces
  // of overlapping collinear segments) are dropped (first_occurrences).
  void set_constraints(std::vector<Segment> segments);

  // Adds points (where segments cross) to the mesh, each walking from a
  // triangle; returns their device numbers.
  using PointInserter =
      std::function<std::vector<int32_t>(const std::vector<Point> &, const std::vector<int32_t> &)>;

  // Inserts every constraint. A segment through a vertex is split there; two
  // segments that cross are both split at a new vertex at their intersection
  // (rounded to the nearest double), as Triangle does. segments() then holds
  // the pieces, added_points() the new vertices.
  void run(ConstrainedStats &stats, const PointInserter &insert_points);

  const std::vector<Point> &added_points() const { return added_points_; }
  // Per added point, the first constraint given to set_constraints that
  // crosses there (its index in that list).
  const std::vector<int32_t> &added_origins() const { return added_origins_; }

  const std::vector<Segment> &segments() const { return segments_; }

  // Per triangle slot: 1 where run() flipped (only there may an edge not be
  // locally Delaunay afterwards); moved out.
  DeviceArray<cl_int> take_touched() { return std::move(touched_.array); }

private:
  // One outer iteration's marking; returns the segments still to insert, or
  // -1 when segments were split at vertices (the marking must be redone).
  long mark(ConstrainedStats &stats, bool first, const PointInserter &insert_points);
  // Splits crossing segments at new vertices (one split per segment and call).
  void split_crossings(const std::vector<cl_int> &state, const std::vector<cl_int> &vertex,
                       ConstrainedStats &stats, const PointInserter &insert_points);
  // The per-slot arrays resized after the mesh grew (insert_points).
  void fit_to_mesh();
  // A per-constraint device array, in the order of segments_.
  std::vector<cl_int> download_by_segment(const DeviceArray<cl_int> &array);
  // The inner loop: splits the marked triangles into runs along their
  // constraints, flips inside every run, then relinks the edges between runs.
  struct RunPass {
    long runs, flips;
  };
  RunPass flip_runs();

  Device &device_;
  DeviceMesh &mesh_;
  cl::Kernel resolve_duplicates_, record_vertex_triangles_, mark_, find_run_starts_, claim_runs_,
      flip_along_runs_, relink_run_boundaries_;
  std::vector<Segment> segments_;
  std::vector<int32_t> origin_;         // input segment each constraint comes from
  std::vector<int32_t> priority_order_; // device constraint d is segments_[priority_order_[d]]
  std::vector<char> split_origin_;      // input segments already counted as split
  std::vector<Point> added_points_;     // vertices added where segments cross
  std::vector<int32_t> added_origins_;  // added_origins()
  // Their vertices by x, for crossings that fall within rounding of one.
  std::multimap<double, std::pair<Point, int32_t>> crossing_vertices_;
  bool vertex_triangles_recorded_ = false; // mesh_.vertex_triangle is up to date
  DeviceArray<cl_int> walk_order_, segment_a_, segment_b_, segment_state_, split_vertex_,
      crossed_vertex_, crossed_triangle_, counters_, constraint_mark_, run_start_, run_of_,
      boundary_log_, edge_table_, run_counters_;
  // Per triangle slot: 1 where run() flipped; 0 as far as the slots are in
  // use (fit_to_mesh covers them).
  CoveredArray<cl_int> touched_;
};

} // namespace clmesh
