// Helpers shared by the device tests.
#pragma once

#include "clmesh/clmesh.hpp"

#include <memory>
#include <string>
#include <vector>

namespace test_support {

// One device for the whole test run ($CLMESH_DEVICE or the first with fp64).
inline clmesh::Device &device() {
  static std::shared_ptr<clmesh::Device> opened = clmesh::open_device();
  return *opened;
}

// The mesh of a point set (no segments) with `options`, on device().
inline clmesh::Mesh triangulate_points(const std::vector<clmesh::Point> &points,
                                       const clmesh::Options &options = {}) {
  clmesh::Input input;
  input.points = points;
  return clmesh::triangulate(device(), input, options);
}

// Whether `points` begins with `first`, bit for bit (a mesh keeps its input's
// points first and unchanged).
inline bool starts_with(const std::vector<clmesh::Point> &points,
                        const std::vector<clmesh::Point> &first) {
  if (points.size() < first.size())
    return false;
  for (std::size_t i = 0; i < first.size(); ++i)
    if (points[i].x != first[i].x || points[i].y != first[i].y)
      return false;
  return true;
}

// A check report's problems, one per line, for failure messages.
inline std::string problems(const clmesh::CheckReport &report) {
  std::string text;
  for (const auto &p : report.problems)
    text += p + "\n";
  return text;
}

} // namespace test_support
