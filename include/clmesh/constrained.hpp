// clmesh — GPU-CDT: constrained Delaunay triangulation of a planar
// straight-line graph (thesis chapter 4) on an OpenCL device.
#pragma once

#include "clmesh/delaunay.hpp"

#include <cstdint>
#include <vector>

namespace clmesh {

struct Segment {
  int32_t a = 0, b = 0; // 0-based point indices
  int marker = 0;
};

struct Region {
  Point seed;
  double attribute = 0;
  double max_area = -1; // -1: no constraint (used by refinement, not by the CDT)
};

// A PSLG as read from a Triangle .poly file.
struct Pslg {
  std::vector<Point> points;
  std::vector<Segment> segments;
  std::vector<Point> holes;
  std::vector<Region> regions;
};

struct ConstrainedOptions {
  DelaunayOptions delaunay;
  bool keep_convex_hull = false;    // -c: keep every triangle of the convex hull
  bool ignore_holes = false;        // -O
  bool regional_attributes = false; // -A: label triangles with their region's attribute
};

struct ConstrainedStats {
  long segments = 0;         // input segments kept (after dropping duplicates/zero length)
  long dropped_segments = 0; // duplicate or zero-length segments
  long split_segments = 0;   // input segments split (at a vertex on them or a crossing)
  long crossings = 0;        // segment-segment crossings, each a new vertex
  long intersections = 0;    // constraint-triangle intersections found by the first marking
  long constraint_flips = 0; // flips of the constraint-insertion phase
  long outer_iterations = 0; // markings that led to flips
  long inner_iterations = 0; // runs flipped along (the inner loop's work-items), all iterations
  long delaunay_flips = 0;   // flips of the final constrained Delaunay flipping
  long eaten_triangles = 0;  // triangles removed as exterior or hole
};

struct ConstrainedResult {
  // Triangles of the domain (counter-clockwise, canonical order), neighbour
  // links (-1 across the domain boundary), duplicates as in DelaunayResult.
  DelaunayResult mesh;
  // The segments as they stand in the mesh: every input segment, split into
  // a chain where vertices lie on it, with its marker; with -c also the hull
  // edges that are not segments (marker 1).
  std::vector<Segment> segments;
  // Vertices added where segments cross, numbered after the input points
  // (the mesh's point n + i is added_points[i]).
  std::vector<Point> added_points;
  // Regional attribute of each triangle (empty unless regional_attributes).
  std::vector<double> triangle_attributes;
  ConstrainedStats stats;
};

// Segments that cross are split at a new vertex at their intersection,
// rounded to the nearest double, as Triangle does (at most 1024 + the number
// of segments such vertices). Throws InputError for segment endpoints out of
// range, and the errors of delaunay().
ConstrainedResult constrained_delaunay(Device &device, const Pslg &pslg,
                                       const ConstrainedOptions &options = {});

} // namespace clmesh
