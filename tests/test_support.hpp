// Helpers shared by the device tests.
#pragma once

#include "clmesh/clmesh.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace test_support {

// An environment variable set to `value` (nullopt: unset) while it lives.
class Environment {
public:
  Environment(const char *name, const std::optional<std::string> &value) : name_(name) {
    if (const char *old = std::getenv(name))
      old_ = old;
    set(value);
  }
  ~Environment() { set(old_); }
  Environment(const Environment &) = delete;
  Environment &operator=(const Environment &) = delete;

private:
  void set(const std::optional<std::string> &value) {
    if (value)
      setenv(name_, value->c_str(), 1);
    else
      unsetenv(name_);
  }
  const char *name_;
  std::optional<std::string> old_;
};

// One device for the whole test run ($CLMESH_DEVICE or the first with fp64).
inline clmesh::Device &device() {
  static std::shared_ptr<clmesh::Device> opened = clmesh::open_device();
  return *opened;
}

// Whether device() takes streams (clmesh::open_stream): all but PoCL's
// in-thread driver.
inline bool device_takes_streams() {
  try {
    clmesh::open_stream(device());
    return true;
  } catch (const clmesh::DeviceError &) {
    return false;
  }
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
  return points.size() >= first.size() &&
         (first.empty() ||
          std::memcmp(points.data(), first.data(), first.size() * sizeof(clmesh::Point)) == 0);
}

// Both meshes the same: points bit for bit, triangles, links, duplicates,
// markers, attributes and segments.
inline void check_same_mesh(const clmesh::Mesh &a, const clmesh::Mesh &b) {
  REQUIRE(a.points.size() == b.points.size());
  CHECK(starts_with(a.points, b.points));
  CHECK(a.input_points == b.input_points);
  CHECK(a.triangles == b.triangles);
  CHECK(a.neighbors == b.neighbors);
  CHECK(a.duplicate_of == b.duplicate_of);
  CHECK(a.point_markers == b.point_markers);
  CHECK(a.point_attributes == b.point_attributes);
  CHECK(a.triangle_attributes == b.triangle_attributes);
  REQUIRE(a.segments.size() == b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i)
    CHECK((a.segments[i].a == b.segments[i].a && a.segments[i].b == b.segments[i].b &&
           a.segments[i].marker == b.segments[i].marker));
}

// A check report's problems, one per line, for failure messages.
inline std::string problems(const clmesh::CheckReport &report) {
  std::string text;
  for (const auto &p : report.problems)
    text += p + "\n";
  return text;
}

// The smallest angle of triangle t, in degrees (floating point).
inline double smallest_angle_degrees(const std::vector<clmesh::Point> &p,
                                     const clmesh::Triangle &t) {
  double smallest = 180;
  for (int i = 0; i < 3; ++i) {
    const clmesh::Point &a = p[t[i]], &b = p[t[(i + 1) % 3]], &c = p[t[(i + 2) % 3]];
    const double ux = b.x - a.x, uy = b.y - a.y, vx = c.x - a.x, vy = c.y - a.y;
    smallest = std::min(smallest,
                        std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / M_PI);
  }
  return smallest;
}

// The area of triangle t, positive when counter-clockwise (floating point).
inline double area(const std::vector<clmesh::Point> &p, const clmesh::Triangle &t) {
  const clmesh::Point &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

// A refined mesh's bounds: no angle below -q's beyond the triangles the
// refinement reports it could not mend (remaining_bad), no triangle larger
// than -a's bound.
inline void check_refined_bounds(const clmesh::Mesh &mesh, const clmesh::Options &options) {
  long below = 0;
  double largest = 0;
  for (const auto &t : mesh.triangles) {
    below += options.quality && smallest_angle_degrees(mesh.points, t) < options.min_angle - 1e-6;
    largest = std::max(largest, area(mesh.points, t));
  }
  CHECK(below <= mesh.statistics.refinement.remaining_bad);
  if (options.max_area)
    CHECK(largest <= *options.max_area * (1 + 1e-9));
}

} // namespace test_support
