// clmesh — plain geometric data shared by the library, the CLI and the tests.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace clmesh {

struct Point {
  double x = 0, y = 0;
};

// A triangle as three vertex indices (0-based, counter-clockwise).
using Triangle = std::array<int32_t, 3>;

// Vertices as read from a Triangle .node file (or the node section of a .poly).
struct PointSet {
  std::vector<Point> points;
  int attribute_count = 0;        // attributes per point
  std::vector<double> attributes; // points.size() * attribute_count, row-major
  bool has_markers = false;
  std::vector<int> markers; // points.size() when has_markers
  int first_index = 0;      // 0 or 1: numbering used by the input file
};

// Largest coordinate magnitude the exact predicates carry without overflow,
// and smallest non-zero magnitude they carry without underflow.
constexpr double kMaxCoordinate = 1e50;
constexpr double kMinCoordinate = 1e-50;

} // namespace clmesh
