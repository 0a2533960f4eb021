// clmesh — exact validity checks of a triangulation (used by tests and -C).
#pragma once

#include "clmesh/geometry.hpp"
#include "clmesh/input.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace clmesh {

struct CheckReport {
  bool ok = true;
  std::vector<std::string> problems; // first few problems found, human-readable
  void fail(const std::string &problem);
};

// Checks with exact predicates: every triangle counter-clockwise, neighbour
// links symmetric, each edge in at most two triangles, the boundary equal to
// the convex hull of the points used, every point not marked duplicate used,
// and (when check_delaunay) every interior edge locally Delaunay.
CheckReport check_triangulation(const std::vector<Point> &points,
                                const std::vector<Triangle> &triangles,
                                const std::vector<std::array<int32_t, 3>> &neighbors,
                                const std::vector<int32_t> &duplicate_of,
                                bool check_delaunay = true);

// Segments are in input numbering, as Input::segments.

// Checks a constrained Delaunay triangulation of the points and segments (input indices, as in
// a Pslg; segment endpoints are mapped through duplicate_of, zero-length and repeated segments
// are ignored, endpoints out of range are reported) with exact predicates:
//  - whole_hull (the mesh covers the whole convex hull, -c without holes): the topology,
//    hull and vertex checks of check_triangulation (without its Delaunay test), and every
//    segment present as one mesh edge or a chain of collinear mesh edges through the vertices
//    lying on it;
//  - otherwise (exterior or holes eaten): every triangle valid and counter-clockwise, each edge
//    in at most two triangles with opposite directions, neighbour links symmetric, the fan of
//    triangles around every vertex turning at most once, and every boundary edge of the mesh
//    part of a segment.  (Local checks: two pieces overlapping without sharing a vertex are not
//    detected; checking that the mesh is a subset of the whole-hull mesh closes that gap.)
// Points from first_added on were computed where segments cross, and rounded: a segment's chain
// may pass through one that lies within rounding of the segment (not exactly on it). With
// crossings_at_vertices (some crossing rounded onto a vertex already there, which then splits
// both segments), it may pass through any vertex within rounding of it.
// In both modes every edge between two triangles that is not part of a segment must be
// locally Delaunay with the symbolically perturbed in-circle test (clm_incircle_sos, the rule
// of check_triangulation and of CGAL), so the constrained Delaunay triangulation accepted is
// unique even for cocircular points.
CheckReport check_constrained(const std::vector<Point> &points,
                              const std::vector<Triangle> &triangles,
                              const std::vector<std::array<int32_t, 3>> &neighbors,
                              const std::vector<int32_t> &duplicate_of,
                              const std::vector<Segment> &segments, bool whole_hull,
                              int32_t first_added = INT32_MAX, bool crossings_at_vertices = false);

} // namespace clmesh
