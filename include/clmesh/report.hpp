// clmesh — what is said about a mesh: Triangle's quality statistics, the
// statistics as JSON, and the exact check of -C.
#pragma once

#include "clmesh/check.hpp"
#include "clmesh/input.hpp"
#include "clmesh/mesh.hpp"
#include "clmesh/options.hpp"
#include "clmesh/statistics.hpp"

#include <array>
#include <string>

namespace clmesh {

// Triangle's -V quality statistics (aspect ratio: longest edge over
// shortest altitude).
struct QualityStatistics {
  long triangles = 0;
  double smallest_area = 0, largest_area = 0;
  double shortest_edge = 0, longest_edge = 0;
  double shortest_altitude = 0, largest_aspect_ratio = 0;
  double smallest_angle = 0, largest_angle = 0;
  // Triangles by aspect ratio: below 1.5, 2, 2.5, 3, 4, 6, 10, 15, 25, 50,
  // 100, 300, 1000, 10000, 100000, and above.
  std::array<long, 16> aspect_ratio_histogram{};
  // Angles by tens of degrees: 0-10, 10-20, ..., 170-180.
  std::array<long, 18> angle_histogram{};
};
QualityStatistics quality_statistics(const Mesh &mesh);
// The table Triangle prints under "Mesh quality statistics".
std::string format_quality(const QualityStatistics &quality);

// The refinement's stop reason as a word: "done", "steiner_limit",
// "area_bound", "angle_bound", "device_memory", "iteration_limit",
// "no_insertion".
const char *stop_reason_name(RefineStop reason);

// The counts of a run as text, as -V prints them.
std::string format_statistics(const Mesh &mesh);

// Seconds of the run's parts that the caller timed (reading, writing).
struct RunSeconds {
  double read = 0, compute = 0, write = 0;
};
// The statistics as a JSON object: device, seconds, phases, counts, and the
// constraint and refinement counts when the run had them.
std::string statistics_json(const Mesh &mesh, const RunSeconds &seconds);

// -C: the mesh checked with exact predicates against the input: a Delaunay
// triangulation of the points; with -p a constrained Delaunay triangulation
// whose boundary edges are all segments (the whole convex hull with -c and no
// hole); a refined mesh's boundary edges are taken as constraints.
CheckReport check_mesh(const Input &input, const Mesh &mesh, const Options &options);

} // namespace clmesh
