// clmesh — the algorithms' tuning: choices that change speed or the number of
// Steiner points, never what a valid mesh is. The defaults are GPU-QM-V's.
#pragma once

#include <cstddef>
#include <optional>

namespace clmesh {

// The thesis's two refinement algorithms (chapter 3) differ in step 3, when
// two Steiner points of an iteration would be connected: GPU-QM deletes the
// one of lower priority always, GPU-QM-V only when they are less than
// orthogonal (§3.5): fewer points inserted twice, slightly more points in
// the end.
enum class RefineAlgorithm { qm, qmv };

// How GPU-DT builds its first triangulation (thesis §4.1.2): from the
// digital Voronoi diagram (Phases 1-3), or from a fan of the convex hull
// whose other points missing-point insertion places. `automatic` fans the
// hull of inputs below Tuning::kFanBelow points (unless a grid is set),
// where the diagram's rounds (a dozen launches each, more rounds for
// clustered points) cost more than inserting every point.
enum class Construction { automatic, voronoi, fan };

// Whether triangulate_many packs small point sets (plain Delaunay options,
// at most 65536 points each): many meshes in one device mesh, meshed by one
// run of the phases, each mesh the same as alone. `automatic` packs on
// devices that take the GPU paths, where every launch costs a round trip
// that a small mesh cannot fill; a CPU meshes small sets faster one by one,
// each in its caches (from a pack of a million points it would fetch every
// array from memory).
enum class Packing { automatic, always, never };

struct Tuning {
  // --- Delaunay triangulation (GPU-DT, thesis §4.1.2); the mesh never depends on these.
  // Side of the digital Voronoi texture of Phase 1; unset: chosen from the points.
  std::optional<int> grid;
  // Work-group size of every kernel; unset: the device's default (64).
  std::optional<std::size_t> work_group;
  // The first triangulation (see Construction). The Voronoi route fans the
  // hull itself when its result cannot be used.
  Construction construction = Construction::automatic;
  static constexpr std::size_t kFanBelow = 1024;
  // Batches of small point sets (see Packing).
  Packing packing = Packing::automatic;
  // triangulate_many: inputs that do not pack meshed at once, each on a
  // thread and a stream of its own (open_stream); the meshes never depend
  // on it. 0: on a device that takes the GPU paths, one per hardware thread
  // (at least 4, at most 16), where the streams' launches overlap; else 1.
  // PoCL's in-thread driver takes 1 whatever this says, and on PoCL's other
  // devices the streams take turns (its kernel cache is not thread-safe).
  std::size_t streams = 0;
  // On PoCL's CPU devices, kernels prefetch (cl/prefetch.h) for meshes of
  // at least this many points (their capacity, Steiner points included):
  // a smaller mesh stays in the caches, where the prefetches only cost.
  std::size_t prefetch_from = 32768;
  // Flip (and flip-flop) passes over at most this many triangles run in one
  // work-group, pass after pass, in one launch; 0: every pass as separate
  // kernels.
  std::size_t group_pass_limit = 2048;
  // A refinement iteration's search for bad triangles (with its election)
  // and its placement of candidates (location, filter, appending) over at
  // most this many entries run in one work-group each, in one launch; 0:
  // as separate kernels.
  std::size_t group_step_limit = 4096;

  // --- Quality refinement (-q, -a); see use() for each algorithm's values.
  RefineAlgorithm algorithm = RefineAlgorithm::qmv;
  // Rings of neighbouring triangles the insertion filter looks at: 2 or 3.
  // The further it looks, the closer the parallel insertion comes to the
  // sequential order of priorities: fewer points, more iterations.
  int filter_rings = 2;
  // Rings further, 0 or 1, where the filter also leaves out a candidate that
  // would form a GPU-QM-V dependent pair (less than orthogonal) with one that
  // goes first, as step 3 would delete it again (Claim 3.5.1 applied before
  // inserting instead of after).
  int filter_distance_rings = 1;
  // Within the filter's rings, a better candidate keeps one out only when it
  // is nearer than this multiple of the distance at which the two would be
  // orthogonal; 0: at any distance (the thesis's filter). Otherwise at
  // least 1.
  double filter_near = 16;
  // Midpoint candidates of different hull edges never keep each other out:
  // each splits its own edge, so an encroached hull is halved in every
  // iteration. false: the thesis's filter.
  bool parallel_midpoints = true;
  // A bad triangle sends a candidate only when no bad triangle within this
  // many rings (0, 1 or 2) has a better priority; 0: every bad triangle sends
  // one (the thesis).
  int election_rings = 2;
  // A search keeps the verdict of a bad triangle of the last search that
  // nothing its assessment reads has rewritten since, and asks only what can
  // change; false assesses every listed triangle again. The mesh never
  // depends on it.
  bool carry_verdicts = true;
  // When the triangles move into Z-order again (not the first time), those
  // that may be bad carry a flag, and the search after the move examines
  // those alone; false: every slot. The mesh never depends on it.
  bool search_flagged_after_move = true;

  // Selects a refinement algorithm with its own values of the refinement
  // fields: GPU-QM-V (filter 2 rings, dependent pairs 1 ring further, near 16,
  // election 2 rings: the fast one) or the thesis's GPU-QM (filter 3 rings,
  // no dependent-pair ring, any distance, no election: the fewest points).
  Tuning &use(RefineAlgorithm refine_algorithm) {
    const bool qmv = refine_algorithm == RefineAlgorithm::qmv;
    algorithm = refine_algorithm;
    filter_rings = qmv ? 2 : 3;
    filter_distance_rings = qmv ? 1 : 0;
    filter_near = qmv ? 16 : 0;
    election_rings = qmv ? 2 : 0;
    return *this;
  }
};

} // namespace clmesh
