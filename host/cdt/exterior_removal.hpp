// clmesh — removing the exterior and the holes of a CDT by parallel flood
// fills (Triangle's -p domain semantics). Kernels: cl/exterior_removal.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

#include "clmesh/geometry.hpp"

#include <vector>

namespace clmesh {

class ExteriorRemoval {
public:
  static constexpr const char *kPhase = "exterior_removal";

  ExteriorRemoval(Device &device, DeviceMesh &mesh);

  // Eats from the hull inwards when `from_hull`, and from every hole seed;
  // returns how many triangles were removed. removed() flags them per slot.
  long run(bool from_hull, const std::vector<Point> &holes);
  const DeviceArray<cl_int> &removed() const { return removed_.array; }

  // -c: removes the pockets between the segments and the convex hull whose
  // triangles are all flat, slivers made by rounding (a chain of segments a
  // hair inside a hull edge: see seed_thick_pockets in the kernels); returns
  // how many triangles.
  long remove_flat_pockets();

  // How many removed triangles are flat: the exterior or a hole runs a hair
  // wide between parts of the domain there.
  long count_flat_removed() { return count_flat(false); }

  // A mesh to refine (-r): removes the real triangles whose label is -1 (no
  // input triangle's, MeshReconstruction).
  void remove_unlabelled(const DeviceArray<cl_int> &label);

  // Labels every triangle with the index of the region whose seed reaches it
  // without crossing a constraint (-1: none); later regions win.
  const DeviceArray<cl_int> &label_regions(const std::vector<Point> &seeds);

  // Whether run(), remove_flat_pockets() or remove_unlabelled() removed any
  // real triangle.
  bool removed_any() const { return removed_any_; }

  // Seeds of the last run() or label_regions() ignored because they lie
  // exactly on a segment or at one of its vertices (on neither side of it).
  long seeds_on_segments() const { return seeds_on_segments_; }

private:
  Device &device_;
  DeviceMesh &mesh_;
  // Runs waves from the current frontier until it is empty: removal when
  // region < 0, else labelling with `region`. Returns the triangles reached.
  // Fronts of at most kInGroup triangles take their waves in one launch.
  long flood(int region);
  static constexpr int kInGroup = 4096;
  // Counts the seeds flagged in on_segment[0 .. count).
  void count_seeds_on_segments(const DeviceArray<cl_int> &on_segment, std::size_t count);

  long seeds_on_segments_ = 0;
  bool removed_any_ = false;

  // The mesh's slots in use, removed_ covering them.
  std::size_t slots();
  // Seeds a removal flood from the hull edges that are no constraints.
  void seed_from_hull(std::size_t slots);
  // How many real triangles are flat: every one, or the removed ones.
  long count_flat(bool every);

  cl::Kernel seed_from_hull_, seed_from_points_, spread_, flood_in_group_, seed_label_,
      remove_unlabelled_, seed_thick_pockets_, remove_flat_pockets_, count_flat_;
  // Per slot: removed (1) or not; set as far as the mesh's slots are in use
  // (slots()).
  CoveredArray<cl_int> removed_;
  DeviceArray<cl_int> label_, frontier_, next_frontier_, count_, flood_result_;
  std::size_t flood_group_; // the work-group of flood_in_group
};

} // namespace clmesh
