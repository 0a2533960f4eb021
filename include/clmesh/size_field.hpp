// clmesh — size control beyond -a: a sizing field the device evaluates, and
// a user's test of each triangle (Triangle's -u and triunsuitable(),
// meshpy's refinement_func).
#pragma once

#include "clmesh/geometry.hpp"

#include <functional>
#include <vector>

namespace clmesh {

// A background mesh that gives the largest triangle area wanted at each
// point: the target area at each vertex, interpolated linearly over its
// triangles (and, outside them, from the nearest of them, its coordinates
// clamped to its edges). A triangle is too large when its area exceeds the
// field at its centroid.
struct SizeField {
  std::vector<Point> points;
  std::vector<double> area;        // per point, positive
  std::vector<Triangle> triangles; // counter-clockwise, 0-based
};

// Throws InputError naming "size field" and the point or triangle at fault:
// no triangle, areas of the wrong count or not positive and finite, corners
// out of range, a triangle not counter-clockwise (exact test).
void validate(const SizeField &field);

// The largest area the field wants at p (the interpolation above), as the
// device computes it; for callers that compare a mesh with its field.
double size_at(const SizeField &field, Point p);

// A user's test: true when the triangle with corners a, b, c (counter-
// clockwise) and the given area must be refined. Refinement asks it for
// every triangle it creates: the corners go from the device to the host and
// the answers back, once per iteration, so a callback is slower than a
// SizeField of the same effect. An exception it throws ends the refinement
// and reaches the caller of triangulate().
using Unsuitable = std::function<bool(Point a, Point b, Point c, double area)>;

} // namespace clmesh
