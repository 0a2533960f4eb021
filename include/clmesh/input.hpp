// clmesh — what is meshed: points, and for a planar straight-line graph (-p)
// segments, holes and regions, as in Triangle's triangulateio.
#pragma once

#include "clmesh/geometry.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace clmesh {

struct Segment {
  int32_t a = 0, b = 0; // 0-based point indices
  int marker = 0;
};

struct Region {
  Point seed;
  double attribute = 0;
  double max_area = -1; // maximum triangle area in the region; <= 0: none
};

struct Input {
  std::vector<Point> points;
  // attribute_count values per point, row-major (points.size() * attribute_count).
  int attribute_count = 0;
  std::vector<double> point_attributes;
  // One boundary marker per point, or empty (no markers).
  std::vector<int> point_markers;
  // -p: the constraints (0-based endpoints) with their markers, hole seeds
  // and region seeds.
  std::vector<Segment> segments;
  std::vector<Point> holes;
  std::vector<Region> regions;
  // -r: the mesh to refine (Triangle's .ele): 0-based corners, counter-
  // clockwise, each triangle with triangle_attribute_count attributes
  // (row-major) that the triangles refining it inherit, and an optional
  // maximum area each (Triangle's .area file: <= 0 none; empty: no file).
  // The mesh need not be Delaunay; its triangles must not overlap.
  std::vector<Triangle> triangles;
  int triangle_attribute_count = 0;
  std::vector<double> triangle_attributes;
  std::vector<double> triangle_max_area;
  // The file the triangles came from and each one's line there, for
  // messages; empty when built in memory (messages then name "triangle k").
  std::string triangles_source;
  std::vector<long> triangle_lines;
  // Numbering of the file the input came from (0 or 1); the output files keep it.
  int first_index = 0;
  // The file the input came from ("" when built in memory), named in messages.
  std::string source;
};

// Throws InputError when the input cannot be meshed: fewer than three points,
// coordinates that are not finite or beyond what the exact predicates carry,
// attributes or markers of the wrong count, segment endpoints out of range,
// triangle corners out of range or repeated, a triangle that is not
// counter-clockwise (exact test), an edge two triangles take in the same
// direction, attributes or maximum areas of the wrong count.
// Messages name input.source, or the point or segment index.
void validate(const Input &input);

} // namespace clmesh
