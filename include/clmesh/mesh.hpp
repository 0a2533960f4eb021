// clmesh — the result of a run: one mesh with everything Triangle returns.
#pragma once

#include "clmesh/geometry.hpp"
#include "clmesh/input.hpp"
#include "clmesh/statistics.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace clmesh {

// A mesh edge with its boundary marker: with -p the marker of the segment it
// lies on (0 promoted to 1 on the mesh boundary), else 1 on the boundary, 0
// inside.
struct Edge {
  int32_t a, b;
  int marker;
};

// -v: an edge of the Voronoi diagram, dual to one edge of the mesh: from the
// circumcentre of triangle a to that of triangle b, or, with b == -1 (a hull
// edge), a ray from a's circumcentre in `direction`: the hull edge turned a
// quarter clockwise (so pointing out of the mesh, as long as the edge), as
// Triangle writes it.
struct VoronoiEdge {
  int32_t a, b;
  Point direction; // (0, 0) for a finite edge
};

struct Mesh {
  // Every point: the input's, then those the run added (where segments cross,
  // Steiner points), numbered on from the input's.
  std::vector<Point> points;
  long input_points = 0; // how many of `points` came from the input
  // attribute_count values per point (added points get them interpolated
  // from the input's: docs/reference.md, "Files read and written").
  int attribute_count = 0;
  std::vector<double> point_attributes;
  // Boundary marker of every point as Triangle reports it: its input marker
  // when non-zero; else that of the first segment with a non-zero marker
  // ending at it; else 1 on the mesh boundary; else 0.
  std::vector<int> point_markers;
  // -1 for a point in the mesh, else the index of the point with identical
  // coordinates that stands for it.
  std::vector<int32_t> duplicate_of;
  // Counter-clockwise triangles over `points` (0-based), in a canonical order
  // that depends only on the input: each starts at its smallest vertex; the
  // triangles of a first vertex come together, sorted by their other two
  // vertices, and these groups follow the Hilbert curve of the first vertices.
  std::vector<Triangle> triangles;
  // -A: the attribute of each triangle's region (triangle_attribute_count 1;
  // otherwise 0 and empty).
  int triangle_attribute_count = 0;
  std::vector<double> triangle_attributes;
  // neighbors[t][i]: the triangle opposite triangles[t][i], -1 on the boundary.
  std::vector<std::array<int32_t, 3>> neighbors;
  // -p: the segments as they stand in the mesh (every input segment, split
  // into a chain where points lie on it, with its marker; with -c also the
  // hull edges that are no segment, marker 1). Empty otherwise.
  std::vector<Segment> segments;
  // -e: every edge once, in Triangle's order (by triangle, then edge).
  std::vector<Edge> edges;
  // -v: the Voronoi diagram of the mesh, as Triangle's .v.node and .v.edge.
  // voronoi_points[t] is the circumcentre of triangles[t], each coordinate
  // within 4 eps |its offset from triangles[t][0]'s| + eps |itself| of the
  // exact one (eps = 2^-53), with attribute_count attributes each in
  // voronoi_point_attributes, interpolated from the corners' as Triangle
  // does; voronoi_edges holds one edge per mesh edge, in mesh_edges()' order.
  std::vector<Point> voronoi_points;
  std::vector<double> voronoi_point_attributes;
  std::vector<VoronoiEdge> voronoi_edges;
  // -o2: six-node triangles. edge_midpoints: one node at the middle of every
  // edge, (a + b) / 2 rounded once, in mesh_edges()' order (that of `edges`
  // with -e); the files number them after the vertices. Each has the mean of
  // its edge's endpoints' attributes (attribute_count each) and its edge's
  // boundary marker. triangle_midpoints[t][i] is the index in edge_midpoints
  // of the middle of the edge opposite triangles[t][i] (Triangle's nodes 4,
  // 5, 6). Empty without -o2.
  std::vector<Point> edge_midpoints;
  std::vector<double> edge_midpoint_attributes;
  std::vector<int> edge_midpoint_markers;
  std::vector<std::array<int32_t, 3>> triangle_midpoints;
  // With Options::voronoi_image: Phase 1's digital Voronoi diagram
  // (grid * grid site indices, -1: none; grid is statistics.delaunay.grid).
  std::vector<int32_t> voronoi_image;
  Statistics statistics;
};

} // namespace clmesh
