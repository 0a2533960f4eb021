// clmesh — GPU-QM and GPU-QM-V (thesis chapter 3): parallel Delaunay
// refinement of a point set's Delaunay triangulation to a minimum angle (-q)
// and a maximum area (-a), the phase entry point behind clmesh::triangulate().
// The convex hull is the boundary: hull edges are split at their midpoints
// when a candidate falls outside or encroaches them.
#pragma once

#include "cdt/constrained.hpp"
#include "dt/delaunay.hpp"

#include "clmesh/size_field.hpp"

#include <optional>
#include <vector>

namespace clmesh {

struct RefineOptions {
  DelaunayOptions delaunay; // its tuning also chooses the refinement algorithm
  double min_angle = 20;    // degrees; 0: no angle bound
  std::optional<double> max_area;
  std::optional<long> max_steiner;
  // -D: a subsegment (or hull edge) whose diametral circle holds a vertex is
  // split, so that every triangle is Delaunay.
  bool conforming = false;
  // A PSLG's regions: with regional_areas (-a alone) each region's maximum
  // area bounds its triangles too; with attributes (-A) the result holds
  // each triangle's region attribute.
  bool regional_areas = false;
  bool attributes = false;
  // -Y (1): no Steiner point on the domain's boundary; -YY (2): on no segment.
  int protected_segments = 0;
  // A sizing field and a user's test of each triangle (null: none).
  const SizeField *size_field = nullptr;
  const Unsuitable *unsuitable = nullptr;
};

struct RefineResult {
  // Triangles over the input points followed by the added points.
  DelaunayResult mesh;
  // Point n + i is added_points[i]: the vertices added where segments cross
  // (PSLG), then the Steiner points.
  std::vector<Point> added_points;
  RefineStats stats;
  // PSLG only: the subsegments (each input segment split into a chain at
  // the vertices on it) with their segment's marker; with -c the hull edges
  // too (marker 1); and the statistics of GPU-CDT.
  std::vector<Segment> segments;
  ConstrainedStats constraints;
  std::vector<double> triangle_attributes; // -A: per triangle, its region's attribute (0: none)
  // -r with attributes (RefineOptions::attributes): per triangle, the input
  // triangle it refines.
  std::vector<int32_t> triangle_origin;
};

// refine_mesh's input is no triangulation: input triangle `triangle` is not
// a triangle of the CDT of the mesh's edges (it overlaps another one, or a
// vertex lies inside it).
struct TriangleNotInMesh {
  std::size_t triangle;
};

RefineResult refine_delaunay(Device &device, const std::vector<Point> &points,
                             const RefineOptions &options);

// Quality refinement of a PSLG's domain: GPU-CDT, the exterior and holes
// removed (as constrained_delaunay()), then GPU-QM/QM-V within the domain,
// every segment split where a candidate falls beyond or encroaches on it.
RefineResult refine_constrained(Device &device, const Pslg &pslg,
                                const ConstrainedOptions &constrained,
                                const RefineOptions &options);

// Refinement of a given mesh (Triangle's -r). pslg.points are its vertices,
// pslg.segments the .poly's segments and pslg.holes its holes (regions are
// not used); `triangles` (counter-clockwise, input numbering) its
// triangles, and `max_area` (empty, or one per triangle; <= 0: none) their
// area bounds, used with options.regional_areas. The mesh's boundary edges
// (marker 1) and the segments are constraints; its vertices, these and
// (unless the mesh is constrained Delaunay already) its inner edges go
// through GPU-CDT, the input triangles are found in it (the rest is outside
// the mesh), the inner edges cease to be constraints and flips make the mesh
// constrained Delaunay; then GPU-QM/QM-V refines it, every
// triangle within the bound of the input triangle that holds its centroid,
// each inheriting the input triangle it descends from (triangle_origin,
// with options.attributes). Throws
// TriangleNotInMesh when the triangles overlap.
RefineResult refine_mesh(Device &device, const Pslg &pslg, const std::vector<Triangle> &triangles,
                         const std::vector<double> &max_area, const ConstrainedOptions &constrained,
                         const RefineOptions &options);

} // namespace clmesh
