// clmesh — checks of an Input before it goes to the device.
#include "clmesh/input.hpp"

#include "clmesh/errors.hpp"

#include <cmath>
#include <cstdio>

namespace clmesh {

namespace {

// Where a problem lies: the input's file, or the item of an input built in memory.
std::string where(const Input &input, const std::string &item) {
  return input.source.empty() ? item : input.source + ": " + item;
}

bool finite(const Point &p) { return std::isfinite(p.x) && std::isfinite(p.y); }

} // namespace

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
  if (!input.triangles.empty() || !input.triangle_max_area.empty())
    throw InputError(source, 0,
                     "refining an existing mesh (its triangles or their maximum areas) is not "
                     "supported yet");
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
}

} // namespace clmesh
