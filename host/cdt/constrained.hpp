// clmesh — GPU-CDT (thesis chapter 4): constrained Delaunay triangulation of
// a planar straight-line graph, the phase entry point behind
// clmesh::triangulate() with -p.
#pragma once

#include "clmesh/input.hpp"
#include "dt/delaunay.hpp"

#include <vector>

namespace clmesh {

// The constraints of a PSLG: a view of vectors held elsewhere (an Input's),
// which outlive it; no copy of a large input's points is held while it is
// meshed.
struct Pslg {
  const std::vector<Point> &points;
  const std::vector<Segment> &segments;
  const std::vector<Point> &holes;
  const std::vector<Region> &regions;
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
  // (the mesh's point n + i is added_points[i]), and for each the input
  // segment it lies on (input numbering; the first listed of those crossing
  // there, as Triangle interpolates the point's attributes along it).
  std::vector<Point> added_points;
  std::vector<Segment> crossed_segments;
  // Regional attribute of each triangle (empty unless regional_attributes).
  std::vector<double> triangle_attributes;
  ConstrainedStats stats;
};

// Segments that cross are split at a new vertex at their intersection,
// rounded to the nearest double, as Triangle does (the mesh grows as they
// come). Segment endpoints are checked beforehand by validate(Input); throws
// the errors of delaunay().
ConstrainedResult constrained_delaunay(Device &device, const Pslg &pslg,
                                       const ConstrainedOptions &options = {});

// The steps of constrained_delaunay(), shared with the refinement of a PSLG.
class DelaunayScheduler;
class ExteriorRemoval;

// First room for the vertices added where segments cross (more is made as needed).
std::size_t crossing_room(const Pslg &pslg);

// Drops zero-length and repeated segments (first occurrence kept, with the
// first non-zero marker of its repeats).
std::vector<Segment> distinct_segments(std::vector<Segment> segments, ConstrainedStats &stats);

// GPU-CDT steps 2 and 3 on the scheduler's Delaunay triangulation: the
// constraints inserted, then flipped to constrained Delaunay. Returns them as
// they stand in the mesh (device numbering); added_points: the vertices added
// where segments cross; crossed (when given): per added point, a segment
// through it (device numbering), the first listed of those crossing there.
std::vector<Segment> insert_constraints(Device &device, DelaunayScheduler &scheduler,
                                        const Pslg &pslg, ConstrainedStats &stats,
                                        std::vector<Point> &added_points,
                                        std::vector<Segment> *crossed = nullptr);

// GPU-CDT step 4: the exterior (unless -c) and the holes (unless -O) flagged
// in removal.removed(). Returns whether anything was looked for.
bool remove_exterior(DelaunayScheduler &scheduler, ExteriorRemoval &removal, const Pslg &pslg,
                     const ConstrainedOptions &options, ConstrainedStats &stats);

// Constraints in device numbering, in input numbering (duplicates resolved).
std::vector<Segment> input_numbering(const std::vector<Segment> &constraints,
                                     const DelaunayScheduler &scheduler,
                                     const std::vector<int32_t> &duplicate_of);

// With -c: the hull edges of `mesh` that are not segments yet, marker 1.
void add_hull_edges(const DelaunayResult &mesh, std::vector<Segment> &segments);

} // namespace clmesh
