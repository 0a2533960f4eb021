// clmesh — GPU-DT: exact Delaunay triangulation of a point set on an OpenCL device.
#pragma once

#include "clmesh/device.hpp"
#include "clmesh/geometry.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace clmesh {

struct DelaunayOptions {
  int grid = 0;               // side of the digital Voronoi texture; 0: chosen from n
  std::size_t work_group = 0; // work-group size; 0: device default (64)
  bool want_voronoi_image = false;
  // Build the first triangulation from the digital Voronoi diagram (Phases
  // 1-3); false starts from a fan of the convex hull instead, as the Voronoi
  // route itself does when its result cannot be used. The mesh is the same.
  bool voronoi_construction = true;
  // Flip passes over lists of at most this many triangles run in one
  // work-group, pass after pass, in one launch (0: never). The mesh is the same.
  std::size_t group_pass_limit = 2048;
};

struct PhaseTime {
  std::string name;
  double seconds = 0;
};

struct DelaunayStats {
  std::string device;
  double compute_seconds = 0; // host->device copy until the mesh is back on the host
  std::vector<PhaseTime> phases;
  long input_points = 0;
  long duplicates = 0;
  long missing_points = 0;   // points inserted by Phase 4
  long pixel_collisions = 0; // points that lost their Voronoi pixel to another (Phase 1)
  // "voronoi" (Phases 1-3 built the first triangulation) or "hull_fan".
  std::string construction;
  long construction_rounds = 0;   // diagrams built by Phases 1-3
  long constructed_triangles = 0; // triangles of the last Phase 2 (ghosts excluded)
  long dropped_sites = 0;         // sites Phase 3 left out (their triangles turned over)
  long flips = 0;
  long insertion_rounds = 0;
  long flip_passes = 0;
  long exact_predicate_calls = 0; // items that needed the exact fallback
  long triangles = 0;
  int grid = 0; // side of the digital Voronoi texture, 0 when Phase 1 did not run
};

struct DelaunayResult {
  // Counter-clockwise triangles over input point indices, in a canonical
  // order that depends only on the input: each starts at its smallest vertex;
  // the triangles of a first vertex come together, sorted by their other two
  // vertices, and these groups follow the Hilbert curve of the first vertices.
  std::vector<Triangle> triangles;
  // neighbors[t][i]: triangle opposite triangles[t][i], -1 on the convex hull.
  std::vector<std::array<int32_t, 3>> neighbors;
  // duplicate_of[i] == -1 for a point in the mesh, else the index of the
  // point with identical coordinates that stands for it.
  std::vector<int32_t> duplicate_of;
  // Digital Voronoi diagram of phase 1 (grid*grid site indices, -1: none),
  // filled when DelaunayOptions::want_voronoi_image.
  std::vector<int32_t> voronoi;
  DelaunayStats stats;
};

// Throws InputError for coordinates that are not finite or outside what the
// exact predicates carry, DeviceError/OpenCLError for device failures.
DelaunayResult delaunay(Device &device, const std::vector<Point> &points,
                        const DelaunayOptions &options = {});

// Largest coordinate magnitude the exact predicates carry without overflow,
// and smallest non-zero magnitude they carry without underflow.
constexpr double kMaxCoordinate = 1e50;
constexpr double kMinCoordinate = 1e-50;

} // namespace clmesh
