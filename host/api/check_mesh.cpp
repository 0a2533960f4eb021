// clmesh — -C: a mesh checked against its input with exact predicates.
#include "clmesh/report.hpp"

namespace clmesh {

namespace {

// The edges of the mesh with a triangle on one side only.
std::vector<Segment> boundary_edges(const Mesh &mesh) {
  std::vector<Segment> boundary;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i)
      if (mesh.neighbors[t][i] < 0)
        boundary.push_back({mesh.triangles[t][(i + 1) % 3], mesh.triangles[t][(i + 2) % 3], 1});
  return boundary;
}

} // namespace

CheckReport check_mesh(const Input &input, const Mesh &mesh, const Options &options) {
  if (mesh.statistics.refined) {
    // Hull edges split at rounded midpoints may leave the boundary a hair
    // from convex (as Triangle's do), so the boundary edges are checked as
    // constraints and every other edge as locally Delaunay: with -D every
    // one, subsegments included.
    const std::vector<Segment> boundary = boundary_edges(mesh);
    const bool segments = options.pslg || options.refine;
    CheckReport report = {};
    if (!segments || options.conforming_delaunay) {
      report = check_constrained(mesh.points, mesh.triangles, mesh.neighbors, mesh.duplicate_of,
                                 boundary, false);
      // Here only the boundary edges are constraints: an edge that fails is
      // an interior subsegment as readily as any other edge.
      if (!report.ok && segments)
        report.problems.push_back("(-D: every edge off the boundary must be locally Delaunay, "
                                  "subsegments included)");
    }
    // A PSLG's (or a refined mesh's) subsegments are mesh edges, the
    // boundary edges of its domain among them.
    if (report.ok && segments)
      report = check_constrained(mesh.points, mesh.triangles, mesh.neighbors, mesh.duplicate_of,
                                 mesh.segments, false);
    return report;
  }
  if (!options.pslg)
    return check_triangulation(mesh.points, mesh.triangles, mesh.neighbors, mesh.duplicate_of,
                               true);
  // The mesh covers the whole convex hull only with -c and no hole carved.
  const bool whole_hull = options.convex_hull && (input.holes.empty() || options.ignore_holes);
  // With -c the hull edges are segments too: those of mesh.segments that are
  // no input segment (the others are pieces of input segments).
  std::vector<Segment> segments = input.segments;
  if (options.convex_hull)
    segments.insert(segments.end(), mesh.segments.begin(), mesh.segments.end());
  // The points after the input's are where segments cross, rounded; other
  // crossings may have rounded onto vertices already there.
  return check_constrained(mesh.points, mesh.triangles, mesh.neighbors, mesh.duplicate_of, segments,
                           whole_hull, static_cast<int32_t>(input.points.size()),
                           mesh.statistics.constraints.crossings_at_vertices > 0);
}

} // namespace clmesh
