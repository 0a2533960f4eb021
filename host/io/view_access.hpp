// clmesh — what the writers read of a MeshView, checked: its arrays (an
// InternalError when one is missing or inconsistent) and the numbers the
// written vertices get.
#pragma once

#include "clmesh/errors.hpp"
#include "clmesh/io.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace clmesh {

inline const std::vector<Point> &points_of(const MeshView &mesh) {
  if (!mesh.points)
    throw InternalError("output writer called without points");
  return *mesh.points;
}
inline const std::vector<Triangle> &triangles_of(const MeshView &mesh) {
  if (!mesh.triangles)
    throw InternalError("output writer called without triangles");
  return *mesh.triangles;
}
inline const std::vector<std::array<int32_t, 3>> &neighbors_of(const MeshView &mesh) {
  if (!mesh.neighbors || mesh.neighbors->size() != triangles_of(mesh).size())
    throw InternalError("output writer called without neighbours for every triangle");
  return *mesh.neighbors;
}

// Vertex number as written: renumbered for -j, then shifted to first_index.
inline int32_t written_vertex(const std::vector<int32_t> &numbers, int32_t vertex,
                              const WriteOptions &o) {
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= numbers.size() || numbers[vertex] < 0)
    throw InternalError("mesh refers to vertex " + std::to_string(vertex) +
                        ", which is not written");
  return numbers[vertex] + o.first_index;
}

inline std::size_t written_count(const std::vector<int32_t> &numbers) {
  std::size_t written = 0;
  for (int32_t number : numbers)
    written += number >= 0;
  return written;
}

inline std::size_t attributes_of(const MeshView &mesh) {
  return static_cast<std::size_t>(std::max(mesh.attribute_count, 0));
}

// Attributes per triangle (0 without them), checked against the triangles.
inline std::size_t triangle_attributes_of(const MeshView &mesh) {
  if (!mesh.triangle_attributes)
    return 0;
  const auto columns = static_cast<std::size_t>(std::max(mesh.triangle_attribute_count, 0));
  if (columns == 0 || mesh.triangle_attributes->size() != triangles_of(mesh).size() * columns)
    throw InternalError("output writer called with " +
                        std::to_string(mesh.triangle_attributes->size()) +
                        " triangle attributes for " + std::to_string(triangles_of(mesh).size()) +
                        " triangles of " + std::to_string(columns) + " attributes each");
  return columns;
}

// -o2's middle nodes, checked against the triangles; empty without -o2.
inline const std::vector<Point> &midpoints_of(const MeshView &mesh) {
  static const std::vector<Point> none;
  if (!mesh.edge_midpoints)
    return none;
  const std::size_t count = mesh.edge_midpoints->size(), attributes = attributes_of(mesh);
  if (!mesh.triangle_midpoints || mesh.triangle_midpoints->size() != triangles_of(mesh).size() ||
      !mesh.edge_midpoint_markers || mesh.edge_midpoint_markers->size() != count ||
      !mesh.edge_midpoint_attributes || mesh.edge_midpoint_attributes->size() != count * attributes)
    throw InternalError("output writer called with inconsistent middle nodes (-o2)");
  return *mesh.edge_midpoints;
}

} // namespace clmesh
