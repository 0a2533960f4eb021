// clmesh — GPU-QM: parallel Delaunay refinement of a point set's Delaunay
// triangulation to a minimum angle (-q) and a maximum area (-a) (thesis
// chapter 3). The convex hull is the boundary: hull edges are split at their
// midpoints when a candidate falls outside or encroaches them.
#pragma once

#include "clmesh/delaunay.hpp"

#include <cstddef>
#include <vector>

namespace clmesh {

// The thesis's two algorithms differ in step 3, when two Steiner points of an
// iteration would be connected: GPU-QM deletes the one of lower priority
// always, GPU-QM-V only when they are less than orthogonal (thesis §3.5):
// fewer points inserted twice, slightly more points in the end.
enum class RefineAlgorithm { qm, qmv };

struct RefineOptions {
  DelaunayOptions delaunay;
  double min_angle = 20; // degrees; 0: no angle bound (-q alone means 20)
  double max_area = -1;  // -a; <= 0: none
  long max_steiner = -1; // -S; < 0: no limit
  RefineAlgorithm algorithm = RefineAlgorithm::qmv;
  // Rings of neighbouring triangles the insertion filter looks at: 2 or 3;
  // 0 picks the algorithm's (qm: 3, for the fewest points; qmv: 2, faster).
  int filter_rings = 0;
  // Rings further, 0 or 1, where it also leaves out a candidate that would
  // form a GPU-QM-V dependent pair (less than orthogonal) with one that goes
  // first, as step 3 would delete it again; -1 picks the algorithm's (qmv: 1,
  // qm: 0). Within the rings above, such a pair of equal priority too.
  int filter_distance_rings = -1;
  // Within those rings, a better candidate keeps one out only when it is
  // nearer than this multiple of the distance at which the two would be
  // orthogonal (GPU-QM-V: far ones leave their neighbourhoods to themselves);
  // 0: whatever the distance; -1 picks the algorithm's (qmv: 16, qm: 0).
  double filter_near = -1;
  // Midpoint candidates of different hull edges never keep each other out:
  // each splits its own edge, and two midpoints are never a dependent pair, so
  // a hull refines by halves in every iteration (1M uniform q20: 62 -> 42
  // iterations). false: the thesis's filter, where a better midpoint within
  // the rings keeps one out like any better candidate.
  bool parallel_midpoints = true;
  // A bad triangle sends a candidate only when no bad triangle within this
  // many rings of it (0, 1 or 2) has a better priority; the others wait, where
  // the insertion filter would mostly have left their candidates out. 0: every
  // bad triangle sends one (the thesis); -1 picks the algorithm's (qmv: 2,
  // qm: 0).
  int election_rings = -1;
  // Flip-flop passes over at most this many triangles run in one work-group,
  // one launch for the whole pass (0: every pass as separate kernels). A
  // matter of speed only: the mesh is the same.
  std::size_t group_pass_limit = 2048;
};

struct RefineStats {
  long iterations = 0;
  long candidates = 0;              // candidates located (elected), over all iterations
  long insertions = 0;              // candidates inserted (step 2), over all iterations
  long deleted = 0;                 // of them, deleted again as redundant (step 3)
  long kept_redundant = 0;          // redundant points kept: no flip could delete them
  long inserted_more_than_once = 0; // points deleted as redundant, then inserted again
  long inserted = 0;                // Steiner points in the final mesh
  long boundary_splits = 0;         // insertions that split a hull edge at its midpoint
  long delaunay_flips = 0;          // step 3's flips of non-locally-Delaunay edges
  long non_delaunay_flips = 0;      // step 3's flops and 3-1 flips deleting points
  long growths = 0;                 // times the mesh's arrays grew (thesis §3.6.1)
  bool out_of_memory = false;       // stopped: the device cannot hold more points
  long remaining_bad = 0;           // bad triangles left (small hull angles, -S reached)
};

struct RefineResult {
  // Triangles over the input points followed by the Steiner points.
  DelaunayResult mesh;
  std::vector<Point> added_points; // Steiner point n + i is added_points[i]
  RefineStats stats;
};

// Not yet: refinement of PSLGs (-pq).
RefineResult refine_delaunay(Device &device, const std::vector<Point> &points,
                             const RefineOptions &options);

} // namespace clmesh
