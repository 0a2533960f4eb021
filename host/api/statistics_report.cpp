// clmesh — a run's statistics as text (-V) and as JSON (--stats-json).
#include "clmesh/report.hpp"

#include <cmath>
#include <cstdio>
#include <iterator>

namespace clmesh {

namespace {

std::string json_string(const std::string &text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    switch (c) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\r':
      out += "\\r";
      break;
    case '\t':
      out += "\\t";
      break;
    default:
      if (c < 0x20) {
        char escaped[8];
        std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
        out += escaped;
      } else {
        out += static_cast<char>(c);
      }
    }
  }
  return out + "\"";
}

std::string json_number(double value) {
  if (!std::isfinite(value))
    return "0";
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

// One "name": count member of an object, four spaces in.
std::string count(const char *name, long value, bool last = false) {
  return "    " + json_string(name) + ": " + std::to_string(value) + (last ? "\n" : ",\n");
}

} // namespace

const char *stop_reason_name(RefineStop reason) {
  // In the order of RefineStop's values.
  static const char *const names[] = {"done",        "steiner_limit", "area_bound",
                                      "angle_bound", "device_memory", "iteration_limit",
                                      "no_insertion"};
  const auto index = static_cast<std::size_t>(reason);
  return index < std::size(names) ? names[index] : "unknown";
}

std::string format_statistics(const Mesh &mesh) {
  const DelaunayStats &s = mesh.statistics.delaunay;
  std::string out;
  char line[200];
  auto add = [&](const char *format, auto... values) {
    std::snprintf(line, sizeof line, format, values...);
    out += line;
  };
  add("  Device: %s\n", s.device.c_str());
  add("  Duplicate vertices: %ld\n", s.duplicates);
  add("  First triangulation: %s\n", s.construction == "voronoi"
                                         ? "from the digital Voronoi diagram"
                                     : s.construction == "given_mesh" ? "the given mesh (-r)"
                                                                      : "fan of the convex hull");
  if (s.grid > 0) {
    add("  Voronoi grid: %d x %d, %ld diagram(s)\n", s.grid, s.grid, s.construction_rounds);
    add("  Triangles from Voronoi vertices: %ld\n", s.constructed_triangles);
    add("  Turned-over triangles mended by flips: %ld\n", s.untangling_flips);
    add("  Sites left out after shifting: %ld\n", s.dropped_sites);
  }
  add("  Vertices placed by missing-point insertion: %ld\n", s.missing_points);
  add("  Insertion levels: %ld, rounds: %ld\n", s.insertion_levels, s.insertion_rounds);
  add("  Flip passes: %ld\n", s.flip_passes);
  add("  Flips: %ld\n", s.flips);
  add("  Exact predicate fallbacks: %ld\n\n", s.exact_predicate_calls);
  if (mesh.statistics.constrained) {
    const ConstrainedStats &c = mesh.statistics.constraints;
    add("  Constraints:\n");
    add("    Segments kept: %ld\n", c.segments);
    add("    Duplicate or zero-length segments dropped: %ld\n", c.dropped_segments);
    add("    Input segments split: %ld\n", c.split_segments);
    add("    Segment crossings (new vertices): %ld\n", c.crossings);
    if (c.crossings_at_vertices > 0)
      add("    Segment crossings rounded onto vertices: %ld\n", c.crossings_at_vertices);
    add("    Segment-triangle intersections: %ld\n", c.intersections);
    add("    Constraint flips: %ld\n", c.constraint_flips);
    add("    Outer iterations / runs flipped along: %ld / %ld\n", c.outer_iterations,
        c.inner_iterations);
    add("    Constrained Delaunay flips: %ld\n", c.delaunay_flips);
    add("    Triangles eaten (exterior and holes): %ld\n", c.eaten_triangles);
    add("    Hole and region seeds on segments (ignored): %ld and %ld\n\n", c.ignored_holes,
        c.ignored_regions);
  }
  if (mesh.statistics.refined) {
    const RefineStats &r = mesh.statistics.refinement;
    add("  Refinement:\n");
    add("    Iterations: %ld\n", r.iterations);
    add("    Candidates located / inserted / deleted again: %ld / %ld / %ld\n", r.candidates,
        r.insertions, r.deleted);
    add("    Steiner points: %ld (%ld hull midpoints)\n", r.inserted, r.boundary_splits);
    add("    Delaunay flips / deleting flips: %ld / %ld\n", r.delaunay_flips, r.non_delaunay_flips);
    add("    Triangles left below the bounds: %ld\n", r.remaining_bad);
    add("    Stopped: %s\n\n", stop_reason_name(r.stop_reason));
  }
  add("  Phases (seconds):\n");
  for (const PhaseTime &p : s.phases)
    add("    %-28s %.6f\n", p.name.c_str(), p.seconds);
  return out;
}

std::string statistics_json(const Mesh &mesh, const RunSeconds &seconds) {
  const DelaunayStats &s = mesh.statistics.delaunay;
  std::string json = "{\n  \"device\": " + json_string(s.device) + ",\n";
  json += "  \"seconds\": {\"read\": " + json_number(seconds.read) +
          ", \"compute\": " + json_number(seconds.compute) +
          ", \"write\": " + json_number(seconds.write) + "},\n";
  json += "  \"phases\": [";
  for (std::size_t i = 0; i < s.phases.size(); ++i)
    json += std::string(i ? ",\n    " : "\n    ") + "{\"name\": " + json_string(s.phases[i].name) +
            ", \"seconds\": " + json_number(s.phases[i].seconds) + "}";
  json += s.phases.empty() ? "],\n" : "\n  ],\n";
  json += "  \"counts\": {\n";
  json += count("input_points", s.input_points);
  json += count("duplicates", s.duplicates);
  json += count("missing_points", s.missing_points);
  json += count("flips", s.flips);
  json += count("triangles", static_cast<long>(mesh.triangles.size()));
  json += count("construction_rounds", s.construction_rounds);
  json += count("constructed_triangles", s.constructed_triangles);
  json += count("dropped_sites", s.dropped_sites);
  json += count("untangling_flips", s.untangling_flips);
  json += count("pixel_collisions", s.pixel_collisions);
  json += count("insertion_levels", s.insertion_levels);
  json += count("insertion_rounds", s.insertion_rounds);
  json += count("flip_passes", s.flip_passes);
  json += count("exact_predicate_calls", s.exact_predicate_calls, true);
  json += "  },\n";
  if (mesh.statistics.constrained) {
    const ConstrainedStats &c = mesh.statistics.constraints;
    json += "  \"constraints\": {\n";
    json += count("segments", c.segments);
    json += count("dropped_segments", c.dropped_segments);
    json += count("split_segments", c.split_segments);
    json += count("crossings", c.crossings);
    json += count("crossings_at_vertices", c.crossings_at_vertices);
    json += count("intersections", c.intersections);
    json += count("constraint_flips", c.constraint_flips);
    json += count("outer_iterations", c.outer_iterations);
    json += count("inner_iterations", c.inner_iterations);
    json += count("delaunay_flips", c.delaunay_flips);
    json += count("eaten_triangles", c.eaten_triangles);
    json += count("ignored_holes", c.ignored_holes);
    json += count("ignored_regions", c.ignored_regions, true);
    json += "  },\n";
  }
  if (mesh.statistics.refined) {
    const RefineStats &r = mesh.statistics.refinement;
    json += "  \"refinement\": {\n";
    json += count("iterations", r.iterations);
    json += count("candidates", r.candidates);
    json += count("insertions", r.insertions);
    json += count("deleted_redundant", r.deleted);
    json += count("kept_redundant", r.kept_redundant);
    json += count("inserted_more_than_once", r.inserted_more_than_once);
    json += count("steiner_points", r.inserted);
    json += count("boundary_splits", r.boundary_splits);
    json += count("delaunay_flips", r.delaunay_flips);
    json += count("non_delaunay_flips", r.non_delaunay_flips);
    json += count("growths", r.growths);
    json += count("compactions", r.compactions);
    json += count("remaining_bad_triangles", r.remaining_bad);
    json += "    \"area_bound_points\": " + json_number(r.area_bound_points) + ",\n";
    json += "    \"stop_reason\": " + json_string(stop_reason_name(r.stop_reason)) + "\n";
    json += "  },\n";
  }
  json += "  \"construction\": " + json_string(s.construction) + ",\n";
  json += "  \"grid\": " + std::to_string(s.grid) + "\n}\n";
  return json;
}

} // namespace clmesh
