// clmesh — GPU-DT (thesis §4.1.2): exact Delaunay triangulation of a point
// set, the phase entry point behind clmesh::triangulate().
#pragma once

#include "clmesh/device.hpp"
#include "clmesh/geometry.hpp"
#include "clmesh/statistics.hpp"
#include "clmesh/tuning.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace clmesh {

struct DelaunayOptions {
  Tuning tuning; // grid, work_group, construction, prefetch_from, group_pass_limit
  bool want_voronoi_image = false;
};

struct DelaunayResult {
  // Counter-clockwise triangles over input point indices, in the canonical
  // order of Mesh::triangles.
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

// Whether delaunay_packed takes the point set (its coordinates checked
// already, clmesh::validate): three points or more, at most `largest`, not
// all collinear.
bool packable(const std::vector<Point> &points, std::size_t largest);

// Several point sets (each packable) triangulated together: one device mesh
// holds them all, each set's triangles apart from the others', so that every
// phase's launches serve them all (batches of small meshes). Each result
// holds what delaunay() gives for its set alone, the same triangles in the
// same order; its statistics count its own points, duplicates and
// triangles, and the pack's seconds, flips and rounds (construction
// "packed").
std::vector<DelaunayResult> delaunay_packed(Device &device,
                                            const std::vector<const std::vector<Point> *> &sets,
                                            const DelaunayOptions &options = {});

} // namespace clmesh
