// clmesh — what a user chooses: Triangle's switches, one field each.
#pragma once

#include "clmesh/size_field.hpp"
#include "clmesh/tuning.hpp"

#include <memory>
#include <optional>
#include <string>

namespace clmesh {

struct Options {
  bool pslg = false;                // -p: triangulate a planar straight-line graph
  bool refine = false;              // -r: refine Input::triangles (with -p: its segments, holes)
  bool convex_hull = false;         // -c: with -p, keep every triangle of the convex hull
  bool ignore_holes = false;        // -O: with -p, ignore the holes
  bool regional_attributes = false; // -A: with -p, each triangle gets its region's attribute
  bool conforming_delaunay = false; // -D: with -p, every triangle Delaunay (segments split)
  int no_steiner_on_segments = 0;   // -Y: none on the boundary; -YY: none on any segment
  bool quality = false;             // -q: quality mesh, no angle below min_angle
  double min_angle = 20;            // -q<angle>, degrees (0 to 45)
  std::optional<double> max_area;   // -a<area>: no triangle larger
  // Not Triangle's switches: a sizing field (--size-field) and a test of
  // each triangle (Triangle's -u, from the library only). Either refines,
  // alone or with -q and -a; a triangle is refined when any bound asks.
  std::shared_ptr<const SizeField> size_field;
  Unsuitable unsuitable;
  bool regional_areas = false;      // -a alone: with -r each triangle's (.area), else with -p
                                    // each region's maximum area (.poly)
  std::optional<long> max_steiner;  // -S<n>: at most n Steiner points (-S alone: 0)
  bool zero_based = false;          // -z: number the output from zero
  bool edges = false;               // -e: return (and write) the edges
  bool neighbors = false;           // -n: write the neighbours
  bool jettison = false;            // -j: leave duplicate (and unused) points out of the output
  bool no_boundary_markers = false; // -B: no boundary markers in the output files
  bool no_node_file = false;        // -N: no .node output
  bool no_ele_file = false;         // -E: no .ele output
  bool no_iteration_number = false; // -I: outputs named name.ele, not name.1.ele
  bool no_poly_file = false;        // -P: no .poly output
  bool off_file = false;            // -g: also write the mesh as an Object File Format .off
  bool voronoi = false;             // -v: return (and write) the mesh's Voronoi diagram
  bool second_order = false;        // -o2: six-node triangles (a node at every edge's middle)
  bool quiet = false;               // -Q: print nothing but errors
  int verbose = 0;                  // -V (repeatable): statistics, timings, quality
  bool check = false;               // -C: check the mesh with exact predicates
  bool help = false;                // -h
  // -X -i -F -l -s: Triangle's choices of arithmetic and algorithm, accepted
  // and without effect (the mesh is the same); the letters, in the order given.
  std::string no_effect_switches;

  // Not Triangle's: return Phase 1's digital Voronoi diagram (Mesh::voronoi_image).
  bool voronoi_image = false;
  // The OpenCL device (see open_device()); "": $CLMESH_DEVICE, else the first with fp64.
  std::string device;
  // Speed and point-count trade-offs; the defaults suit every input.
  Tuning tuning;
};

// Triangle's switch letters ("pq30a0.1", a leading '-' allowed) as Options.
// Throws OptionError naming an unknown letter, a switch of Triangle's that
// clmesh does not support (with why), or a malformed number.
Options parse_switches(const std::string &switches);
// The same, added to `options` (a command line with several switch words).
void parse_switches(const std::string &switches, Options &options);

// Throws OptionError for choices that do not go together or are out of range
// (-q/-a with -p, an angle outside 0..45, a non-positive area, tuning out of
// range). triangulate() calls it.
void validate(const Options &options);

// The switch letters clmesh supports, as "-p -c -O ...", for messages.
const char *supported_switches();

} // namespace clmesh
