// clmesh — a sizing field's background mesh from Triangle's files (--size-field).
#include "clmesh/io.hpp"

#include "clmesh/errors.hpp"

#include "predicates.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace clmesh {

namespace {

// The line of `path` that holds vertex `id` (its first field): looked up
// again on the error path only, as read_node() keeps no line numbers.
long line_of_vertex(const std::string &path, long id) {
  std::ifstream in(path);
  std::string text;
  for (long line = 1; std::getline(in, text); ++line) {
    std::istringstream fields(text.substr(0, text.find('#')));
    long first = 0;
    if (line > 1 && fields >> first && first == id)
      return line;
  }
  return 0;
}

} // namespace

SizeField read_size_field(const std::string &base) {
  const std::string node_path = base + ".node", ele_path = base + ".ele";
  PointSet points = read_node(node_path);
  if (points.attribute_count < 1)
    throw InputError(node_path, 1,
                     "a size field's vertices need an attribute, the target area at the vertex; "
                     "this file has none");
  SizeField field;
  field.points = std::move(points.points);
  const auto stride = static_cast<std::size_t>(points.attribute_count);
  for (std::size_t i = 0; i < field.points.size(); ++i) {
    const double area = points.attributes[i * stride];
    if (!(area > 0)) {
      const long id = static_cast<long>(i) + points.first_index;
      char text[40];
      std::snprintf(text, sizeof text, "%.17g", area);
      throw InputError(node_path, line_of_vertex(node_path, id),
                       "the target area " + std::string(text) + " of vertex " + std::to_string(id) +
                           " is not positive");
    }
    field.area.push_back(area);
  }
  EleFile ele = read_ele(ele_path, static_cast<long>(field.points.size()), points.first_index);
  if (ele.triangles.empty())
    throw InputError(ele_path, 1, "a size field needs at least one triangle");
  for (std::size_t t = 0; t < ele.triangles.size(); ++t) {
    const Triangle &v = ele.triangles[t];
    const Point &a = field.points[v[0]], &b = field.points[v[1]], &c = field.points[v[2]];
    if (clm_orient2d(a.x, a.y, b.x, b.y, c.x, c.y) <= 0)
      throw InputError(ele_path, ele.lines[t],
                       "triangle " + std::to_string(static_cast<long>(t) + ele.first_index) +
                           ": its corners are not in counter-clockwise order");
  }
  field.triangles = std::move(ele.triangles);
  return field;
}

} // namespace clmesh
