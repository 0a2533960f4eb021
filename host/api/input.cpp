// clmesh — checks of an Input before it goes to the device.
#include "clmesh/input.hpp"

#include "api/triangle_error.hpp"
#include "io/directed_edges.hpp"

#include "clmesh/errors.hpp"

#include "predicates.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace clmesh {

namespace {

// Where a problem lies: the input's file, or the item of an input built in memory.
std::string where(const Input &input, const std::string &item) {
  return input.source.empty() ? item : input.source + ": " + item;
}

bool finite(const Point &p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// -r: the mesh to refine is a triangulation: corners in range and distinct,
// every triangle counter-clockwise (exact orientation), and no edge taken
// twice in the same direction (two triangles folded over each other, or
// more than two around one edge). Overlaps between triangles that share no
// edge are found on the device (refine_mesh).
void validate_triangles(const Input &input) {
  const std::size_t n = input.points.size(), count = input.triangles.size();
  const std::string source = input.triangles_source.empty()
                                 ? (input.source.empty() ? "input" : input.source)
                                 : input.triangles_source;
  if (input.triangle_attribute_count < 0 ||
      input.triangle_attributes.size() !=
          count * static_cast<std::size_t>(input.triangle_attribute_count))
    throw InputError(source, 0,
                     std::to_string(input.triangle_attributes.size()) +
                         " triangle attributes for " + std::to_string(count) + " triangles of " +
                         std::to_string(input.triangle_attribute_count) + " attributes each");
  if (!input.triangle_max_area.empty() && input.triangle_max_area.size() != count)
    throw InputError(source, 0,
                     std::to_string(input.triangle_max_area.size()) + " maximum areas for " +
                         std::to_string(count) + " triangles");
  for (std::size_t t = 0; t < input.triangle_max_area.size(); ++t)
    if (std::isnan(input.triangle_max_area[t]))
      throw_triangle_error(input, t, "its maximum area is not a number");
  for (std::size_t t = 0; t < count; ++t) {
    const Triangle &v = input.triangles[t];
    for (int32_t corner : v)
      if (corner < 0 || static_cast<std::size_t>(corner) >= n)
        throw_triangle_error(input, t,
                             "corner " +
                                 std::to_string(static_cast<long>(corner) + input.first_index) +
                                 " is out of range (" + std::to_string(n) + " vertices)");
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
      throw_triangle_error(input, t, "a corner is repeated");
    const Point &a = input.points[v[0]], &b = input.points[v[1]], &c = input.points[v[2]];
    const int side = clm_orient2d(a.x, a.y, b.x, b.y, c.x, c.y);
    if (side <= 0)
      throw_triangle_error(input, t,
                           side == 0
                               ? "its corners are collinear (it has no area)"
                               : "its corners are in clockwise order (counter-clockwise expected)");
  }
  // The first edge taken twice, in the order of (from, to, triangle).
  const DirectedEdges directed(input.triangles, n);
  const std::vector<DirectedEdges::Edge> &edges = directed.edges();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t e = directed.first(a) + 1; e < directed.first(a + 1); ++e)
      if (edges[e].head == edges[e - 1].head)
        throw_triangle_error(
            input, edges[e].triangle,
            "it overlaps triangle " +
                std::to_string(static_cast<long>(edges[e - 1].triangle) + input.first_index) +
                " (both take the edge from vertex " +
                std::to_string(static_cast<long>(a) + input.first_index) + " to " +
                std::to_string(edges[e].head + input.first_index) + ")");
}

} // namespace

void throw_triangle_error(const Input &input, std::size_t t, const std::string &problem) {
  const std::string name = "triangle " + std::to_string(static_cast<long>(t) + input.first_index);
  if (!input.triangles_source.empty())
    throw InputError(input.triangles_source,
                     t < input.triangle_lines.size() ? input.triangle_lines[t] : 0,
                     name + ": " + problem);
  throw InputError(where(input, name), 0, problem);
}

void validate(const Input &input) {
  const std::size_t n = input.points.size();
  const std::string source = input.source.empty() ? "input" : input.source;
  if (n < 3)
    throw InputError(source, 0,
                     "input must have at least three vertices, found " + std::to_string(n));
  if (input.attribute_count < 0 ||
      input.point_attributes.size() != n * static_cast<std::size_t>(input.attribute_count))
    throw InputError(source, 0,
                     std::to_string(input.point_attributes.size()) + " point attributes for " +
                         std::to_string(n) + " points of " + std::to_string(input.attribute_count) +
                         " attributes each");
  if (!input.point_markers.empty() && input.point_markers.size() != n)
    throw InputError(source, 0,
                     std::to_string(input.point_markers.size()) + " point markers for " +
                         std::to_string(n) + " points");
  for (std::size_t i = 0; i < n; ++i)
    for (const double value : {input.points[i].x, input.points[i].y}) {
      const double magnitude = std::fabs(value);
      if (!std::isfinite(value) || magnitude > kMaxCoordinate ||
          (value != 0 && magnitude < kMinCoordinate)) {
        char text[64];
        std::snprintf(text, sizeof text, "%.17g", value);
        throw InputError(where(input, "point " + std::to_string(i)), 0,
                         std::string("coordinate ") + text +
                             " is outside what exact arithmetic carries (non-zero magnitudes "
                             "from 1e-50 to 1e50)");
      }
    }
  const auto count = static_cast<long>(n);
  for (std::size_t i = 0; i < input.segments.size(); ++i) {
    const Segment &s = input.segments[i];
    if (s.a < 0 || s.a >= count || s.b < 0 || s.b >= count)
      throw InputError(where(input, "segment " + std::to_string(i)), 0,
                       "endpoint out of range (" + std::to_string(s.a) + ", " +
                           std::to_string(s.b) + " of " + std::to_string(n) + " points)");
  }
  for (std::size_t i = 0; i < input.holes.size(); ++i)
    if (!finite(input.holes[i]))
      throw InputError(where(input, "hole " + std::to_string(i)), 0, "coordinate is not finite");
  for (std::size_t i = 0; i < input.regions.size(); ++i)
    if (!finite(input.regions[i].seed) || !std::isfinite(input.regions[i].attribute))
      throw InputError(where(input, "region " + std::to_string(i)), 0,
                       "coordinate or attribute is not finite");
  validate_triangles(input);
}

} // namespace clmesh
