// clmesh — GPU-CDT (thesis chapter 4): constrained Delaunay triangulation of
// a planar straight-line graph, the phase entry point behind
// clmesh::triangulate() with -p.
#pragma once

#include "clmesh/input.hpp"
#include "dt/delaunay.hpp"

#include <vector>

namespace clmesh {

// The constraints of a PSLG.
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
// of segments such vertices). Segment endpoints are checked beforehand by
// validate(Input); throws the errors of delaunay().
ConstrainedResult constrained_delaunay(Device &device, const Pslg &pslg,
                                       const ConstrainedOptions &options = {});

} // namespace clmesh
