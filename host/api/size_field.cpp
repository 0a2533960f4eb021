// clmesh — checks of a sizing field, and its value at a point on the host.
#include "clmesh/size_field.hpp"

#include "clmesh/errors.hpp"

#include "predicates.h"

#include <cmath>
#include <limits>
#include <string>

namespace clmesh {

void validate(const SizeField &field) {
  const std::size_t n = field.points.size();
  if (field.triangles.empty())
    throw InputError("size field", 0, "the background mesh has no triangle");
  if (field.area.size() != n)
    throw InputError("size field", 0,
                     std::to_string(field.area.size()) + " target areas for " + std::to_string(n) +
                         " points");
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(field.points[i].x) || !std::isfinite(field.points[i].y))
      throw InputError("size field: point " + std::to_string(i), 0, "coordinate is not finite");
    if (!(field.area[i] > 0) || !std::isfinite(field.area[i]))
      throw InputError("size field: point " + std::to_string(i), 0,
                       "the target area must be positive and finite");
  }
  for (std::size_t t = 0; t < field.triangles.size(); ++t) {
    const Triangle &v = field.triangles[t];
    const std::string name = "size field: triangle " + std::to_string(t);
    for (int32_t corner : v)
      if (corner < 0 || static_cast<std::size_t>(corner) >= n)
        throw InputError(name, 0,
                         "corner " + std::to_string(corner) + " is out of range (" +
                             std::to_string(n) + " points)");
    const Point &a = field.points[v[0]], &b = field.points[v[1]], &c = field.points[v[2]];
    if (clm_orient2d(a.x, a.y, b.x, b.y, c.x, c.y) <= 0)
      throw InputError(name, 0, "its corners are not in counter-clockwise order");
  }
}

double size_at(const SizeField &field, Point p) {
  // The triangle whose smallest barycentric coordinate of p is largest (the
  // one holding p, or the nearest), first in order on ties; the same
  // arithmetic as cl/size_bound.cl.
  double best = -std::numeric_limits<double>::infinity(), value = 0;
  for (const Triangle &v : field.triangles) {
    const Point a = field.points[v[0]], b = field.points[v[1]], c = field.points[v[2]];
    const double twice = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    const double l0 = ((b.x - p.x) * (c.y - p.y) - (b.y - p.y) * (c.x - p.x)) / twice;
    const double l1 = ((c.x - p.x) * (a.y - p.y) - (c.y - p.y) * (a.x - p.x)) / twice;
    const double l2 = 1 - l0 - l1;
    const double score = std::fmin(l0, std::fmin(l1, l2));
    if (score > best) {
      best = score;
      const double w0 = std::fmax(l0, 0), w1 = std::fmax(l1, 0), w2 = std::fmax(l2, 0);
      value =
          (w0 * field.area[v[0]] + w1 * field.area[v[1]] + w2 * field.area[v[2]]) / (w0 + w1 + w2);
    }
  }
  return value;
}

} // namespace clmesh
