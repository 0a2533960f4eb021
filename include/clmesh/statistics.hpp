// clmesh — what a run counted and how long it took.
#pragma once

#include <string>
#include <vector>

namespace clmesh {

struct PhaseTime {
  std::string name;
  double seconds = 0;
};

// GPU-DT (thesis §4.1.2): the Delaunay triangulation every mesh starts from.
struct DelaunayStats {
  std::string device;
  double compute_seconds = 0; // host->device copy until the mesh is back on the host
  std::vector<PhaseTime> phases;
  long input_points = 0;
  long duplicates = 0;
  long missing_points = 0;   // points inserted by Phase 4
  long pixel_collisions = 0; // points that lost their Voronoi pixel to another (Phase 1)
  // "voronoi" (Phases 1-3 built the first triangulation), "hull_fan", or
  // "given_mesh" (-r: the given triangles, a disk, were the first mesh).
  std::string construction;
  long construction_rounds = 0;   // diagrams built by Phases 1-3
  long constructed_triangles = 0; // triangles of the last Phase 2 (ghosts excluded)
  long dropped_sites = 0;         // sites Phase 3 left out (their triangles turned over)
  long untangling_flips = 0;      // flips by which Phase 3 mended turned-over triangles
  long flips = 0;
  long insertion_levels = 0; // Phase 4's levels (1, or more after a first mesh of few triangles)
  long insertion_rounds = 0;
  long flip_passes = 0;
  long exact_predicate_calls = 0; // items that needed the exact fallback
  long triangles = 0;
  int grid = 0; // side of the digital Voronoi texture, 0 when Phase 1 did not run
};

// GPU-CDT (thesis chapter 4), with -p.
struct ConstrainedStats {
  long segments = 0;              // input segments kept (after dropping duplicates/zero length)
  long dropped_segments = 0;      // duplicate or zero-length segments
  long split_segments = 0;        // input segments split (at a vertex on them or a crossing)
  long crossings = 0;             // segment-segment crossings, each a new vertex
  long crossings_at_vertices = 0; // crossings that rounded onto a vertex already there
  long intersections = 0;         // constraint-triangle intersections found by the first marking
  long constraint_flips = 0;      // flips of the constraint-insertion phase
  long outer_iterations = 0;      // markings that led to flips
  long inner_iterations = 0; // runs flipped along (the inner loop's work-items), all iterations
  long delaunay_flips = 0;   // flips of the final constrained Delaunay flipping
  // Triangles removed as exterior or hole (with -c and refinement, also the
  // flat pockets between segments and hull: slivers of rounding).
  long eaten_triangles = 0;
  // Hole seeds (unless -O) and region seeds (with -A) lying exactly on a
  // segment or at one of its vertices: on neither side, ignored.
  long ignored_holes = 0;
  long ignored_regions = 0;
};

// Why the refinement stopped.
enum class RefineStop {
  done,            // no triangle left to mend (those at small input angles stay)
  steiner_limit,   // the -S limit was reached
  area_bound,      // out of device memory: the area bound (-a) needs more points
  angle_bound,     // angles above about 33 degrees need not terminate: without -S refinement
                   // stops at 100 Steiner points per input point (beyond what -a needs),
                   // or when the device's memory is full
  device_memory,   // out of device memory, with neither bound to blame (a large input)
  iteration_limit, // the bound on iterations was reached
  no_insertion,    // no candidate could be inserted
};

// GPU-QM / GPU-QM-V (thesis chapter 3), with -q or -a.
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
  long compactions = 0;             // moves of the triangles into Z-order (thesis §3.6.1)
  bool out_of_memory = false;       // stopped: the device cannot hold more points
  // Bad triangles left: small input angles, flat slivers of rounding, -Y, -S reached.
  long remaining_bad = 0;
  RefineStop stop_reason = RefineStop::done;
  // -a: at least this many points mesh the convex hull within the area bound
  // (half its area over the bound); 0 without -a.
  double area_bound_points = 0;
};

// Everything a run reports: the Delaunay phases always, the constraint
// phases with -p, the refinement with -q or -a.
struct Statistics {
  DelaunayStats delaunay;
  bool constrained = false; // -p: `constraints` was filled
  ConstrainedStats constraints;
  bool refined = false; // -q/-a: `refinement` was filled
  RefineStats refinement;
};

} // namespace clmesh
