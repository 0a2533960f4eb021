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
  // An existing mesh to refine (Triangle's -r) and a maximum area per
  // triangle (its .area file; <= 0: none). Refining is not supported yet:
  // validate() refuses an input with triangles.
  std::vector<Triangle> triangles;
  std::vector<double> triangle_max_area;
  // Numbering of the file the input came from (0 or 1); the output files keep it.
  int first_index = 0;
  // The file the input came from ("" when built in memory), named in messages.
  std::string source;
};

// Throws InputError when the input cannot be meshed: fewer than three points,
// coordinates that are not finite or beyond what the exact predicates carry,
// attributes or markers of the wrong count, segment endpoints out of range,
// triangles (refining a mesh is not supported yet).
// Messages name input.source, or the point or segment index.
void validate(const Input &input);

} // namespace clmesh
