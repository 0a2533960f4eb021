// clmesh — the attributes of the points a run adds, interpolated from the
// input's (Triangle gives its new vertices interpolated attributes too, where
// other meshers give none).
//
// A point where segments cross takes them along the first listed segment
// through it, as in Triangle. A Steiner point of a refinement takes those of
// the triangulation the refinement started from, linear in the triangle that
// holds it: the (constrained) Delaunay triangulation of the input's convex
// hull, or with -r the given mesh. Attributes linear over the domain are so
// reproduced exactly (up to rounding) at every new point, whatever the
// order of insertion; Triangle instead extrapolates from each bad triangle in
// turn, which agrees with this for linear attributes only.
#pragma once

#include "clmesh/geometry.hpp"
#include "clmesh/input.hpp"

#include <vector>

namespace clmesh {

// The attributes (`count` per point) of each of `points` along its segment
// (segments[i] for points[i], ends indices into `ends` and `attributes`):
// linear in the parameter of the segment's point nearest to it.
std::vector<double> interpolate_along(const std::vector<Point> &ends,
                                      const std::vector<double> &attributes, int count,
                                      const std::vector<Segment> &segments,
                                      const std::vector<Point> &points);

// A triangulation with attributes at its points, to interpolate over.
struct AttributeField {
  std::vector<Point> points;
  std::vector<double> attributes; // `count` per point
  std::vector<Triangle> triangles;
};

// The attributes (`count` per query point) interpolated linearly in the
// triangle of `field` that holds each query point; for a point outside
// every triangle (rounding at the boundary), in the nearest one, clamped to
// its edge. Zeros when the field has no triangle.
std::vector<double> interpolate_attributes(const AttributeField &field, int count,
                                           const std::vector<Point> &queries);

} // namespace clmesh
