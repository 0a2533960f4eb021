// Refining a given mesh (-r): the mesh taken as it is, made constrained
// Delaunay by flips and refined within its own domain, its boundary edges
// and segments kept, each new triangle inheriting the area bound and the
// attributes of the input triangle it refines. Every output is checked
// exactly (valid, subsegments present, every other edge locally Delaunay)
// and against the given mesh: the same domain area, its segments as chains.
#include <doctest/doctest.h>

#include "clmesh/clmesh.hpp"
#include "dt/simple_loop.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <set>
#include <string>

using clmesh::Point;
using clmesh::Segment;
using test_support::area;
using test_support::device;
using test_support::problems;

namespace {

long double total_area(const std::vector<Point> &points,
                       const std::vector<clmesh::Triangle> &triangles) {
  long double sum = 0;
  for (const auto &t : triangles)
    sum += area(points, t);
  return sum;
}

// The mesh as the input of a later -r run: its points (with their markers),
// triangles and segments, and the holes of the input it came from.
clmesh::Input as_input(const clmesh::Mesh &mesh, const clmesh::Input &from = {}) {
  clmesh::Input input;
  input.points = mesh.points;
  input.point_markers = mesh.point_markers;
  input.triangles = mesh.triangles;
  input.segments = mesh.segments;
  input.holes = from.holes;
  return input;
}

// Is every segment of `given` a chain of collinear subsegments of `refined`?
bool segments_kept(const clmesh::Input &given, const clmesh::Mesh &refined) {
  std::set<std::pair<int32_t, int32_t>> pieces;
  for (const Segment &s : refined.segments)
    pieces.insert(std::minmax(s.a, s.b));
  for (const Segment &s : given.segments) {
    const Point a = refined.points[s.a], b = refined.points[s.b];
    // The vertices on the segment, in order from a.
    std::vector<std::pair<double, int32_t>> on;
    for (std::size_t v = 0; v < refined.points.size(); ++v) {
      const Point p = refined.points[v];
      const double cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
      const double length2 = (b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y);
      const double along = (p.x - a.x) * (b.x - a.x) + (p.y - a.y) * (b.y - a.y);
      // An input vertex on it only when exactly so (it splits the segment).
      if (std::fabs(cross) <= 1e-9 * length2 && along >= 0 && along <= length2 &&
          (v < given.points.size() ? v == static_cast<std::size_t>(s.a) ||
                                         v == static_cast<std::size_t>(s.b) || cross == 0
                                   : true))
        on.emplace_back(along, static_cast<int32_t>(v));
    }
    std::sort(on.begin(), on.end());
    for (std::size_t i = 1; i < on.size(); ++i)
      if (!pieces.count(std::minmax(on[i - 1].second, on[i].second)))
        return false;
  }
  return true;
}

// Refines `given` with `switches` (which hold -r) and checks the result:
// exact validity against the given mesh's segments and boundary, the same
// domain area, the segments kept, the angle bound beyond the triangles the
// refinement could not mend, every triangle within its area bound.
// `eaten`: the area the .poly's holes remove.
clmesh::Mesh refine_checked(const clmesh::Input &given, const std::string &switches,
                            long double eaten = 0) {
  INFO(switches);
  const clmesh::Options options = clmesh::parse_switches(switches);
  const clmesh::Mesh mesh = clmesh::triangulate(device(), given, options);
  const auto report = clmesh::check_mesh(given, mesh, options);
  INFO(problems(report));
  CHECK(report.ok);
  CHECK(mesh.statistics.refinement.stop_reason == clmesh::RefineStop::done);
  REQUIRE(test_support::starts_with(mesh.points, given.points));
  const long double domain = total_area(given.points, given.triangles) - eaten;
  CHECK(std::fabs(static_cast<double>(total_area(mesh.points, mesh.triangles) - domain)) <=
        1e-9 * static_cast<double>(domain));
  if (options.pslg)
    CHECK(segments_kept(given, mesh));
  test_support::check_refined_bounds(mesh, options);
  return mesh;
}

// A rows x columns grid of rectangles over [0, width] x [0, 1], each cut by
// the diagonal that is not Delaunay when the rectangles are wide: a valid
// triangulation, far from Delaunay.
clmesh::Input skewed_grid(int rows, int columns, double width) {
  clmesh::Input input;
  for (int r = 0; r <= rows; ++r)
    for (int c = 0; c <= columns; ++c)
      input.points.push_back({width * c / columns, static_cast<double>(r) / rows});
  auto at = [&](int r, int c) { return static_cast<int32_t>(r * (columns + 1) + c); };
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      input.triangles.push_back({at(r, c), at(r, c + 1), at(r + 1, c + 1)});
      input.triangles.push_back({at(r, c), at(r + 1, c + 1), at(r + 1, c)});
    }
  return input;
}

// The mesh's triangles, each from its smallest corner on (corners in order).
std::set<std::array<int32_t, 3>> triangle_set(const clmesh::Mesh &mesh) {
  std::set<std::array<int32_t, 3>> triangles;
  for (const clmesh::Triangle &t : mesh.triangles) {
    const int first = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
    triangles.insert({t[first], t[(first + 1) % 3], t[(first + 2) % 3]});
  }
  return triangles;
}

} // namespace

TEST_CASE("refine mesh: a simple polygon is told from loops that meet themselves, exactly") {
  // 0-3 a unit square, 4 its right edge's midpoint, 5 the square's centre,
  // 6 the double just to the left of that midpoint, 7 the top left again.
  const std::vector<Point> p = {
      {0, 0}, {1, 0}, {1, 1}, {0, 1}, {1, 0.5}, {0.5, 0.5}, {0x1.fffffffffffffp-1, 0.5}, {0, 1}};
  using Loop = std::vector<int32_t>;
  CHECK(clmesh::is_simple_loop(p, Loop{0, 1, 2, 3}));
  CHECK(clmesh::is_simple_loop(p, Loop{0, 1, 4, 2, 3}));     // a straight corner
  CHECK(clmesh::is_simple_loop(p, Loop{0, 1, 2, 5, 3}));     // concave
  CHECK(!clmesh::is_simple_loop(p, Loop{0, 2, 1, 3}));       // a figure eight
  CHECK(!clmesh::is_simple_loop(p, Loop{0, 1, 2, 4, 3}));    // a spike back along an edge
  CHECK(!clmesh::is_simple_loop(p, Loop{0, 1, 2, 7, 5, 3})); // two corners at one place
  CHECK(!clmesh::is_simple_loop(p, Loop{0, 1, 2, 3, 5, 4})); // a corner on another edge
  CHECK(clmesh::is_simple_loop(p, Loop{0, 1, 2, 3, 5, 6}));  // a hair off it
  CHECK(!clmesh::is_simple_loop(p, Loop{0, 1}));
  // Several loops: each simple and none meeting another; which way one turns.
  const std::vector<Point> q = {{0, 0},   {4, 0},   {4, 4}, {0, 4},     {1, 1},   {1, 2},
                                {2, 2},   {2, 1},   {3, 1}, {3, 3},     {2.5, 3}, {4, 2},
                                {1.5, 1}, {1.5, 0}, {2, 0}, {1.5, 0.5}, {3, 1.5}, {1.5, 1.5}};
  using Starts = std::vector<std::size_t>;
  CHECK(clmesh::are_simple_loops(q, Loop{0, 1, 2, 3, 4, 5, 6, 7}, Starts{0, 4, 8}));
  CHECK(clmesh::are_simple_loops(q, Loop{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, Starts{0, 4, 8, 11}));
  CHECK(!clmesh::are_simple_loops(q, Loop{0, 1, 2, 3, 8, 11, 9}, Starts{0, 4, 7}));   // touching
  CHECK(!clmesh::are_simple_loops(q, Loop{4, 5, 6, 7, 15, 16, 17}, Starts{0, 4, 7})); // crossing
  CHECK(!clmesh::are_simple_loops(q, Loop{0, 1, 2, 3, 4, 5, 7, 6}, Starts{0, 4, 8})); // a knot
  CHECK(!clmesh::are_simple_loops(q, Loop{0, 1, 2, 3, 4, 5}, Starts{0, 4, 6}));       // too short
  CHECK(!clmesh::are_simple_loops(q, Loop{0, 1, 2, 3, 12, 13, 14}, Starts{0, 4, 7})); // through
  CHECK(clmesh::loop_turn(q, Loop{0, 1, 2, 3}, 0, 4) == 1);
  CHECK(clmesh::loop_turn(q, Loop{0, 1, 2, 3, 4, 5, 6, 7}, 4, 8) == -1);
  CHECK(clmesh::loop_turn(q, Loop{3, 0, 13, 1, 2}, 0, 5) == 1); // a straight corner at the lowest
}

TEST_CASE("refine mesh: a mesh that is a disk is the first mesh itself, others are found in the "
          "Delaunay triangulation of their points") {
  // The skewed grid's inner points moved a little: general position.
  clmesh::Input grid = skewed_grid(6, 8, 8);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  for (int r = 1; r < 6; ++r)
    for (int c = 1; c < 8; ++c) {
      Point &p = grid.points[static_cast<std::size_t>(r * 9 + c)];
      p.x += jitter(random);
      p.y += jitter(random) / 8;
    }
  const clmesh::Mesh taken = refine_checked(grid, "r");
  CHECK(taken.statistics.delaunay.construction == "given_mesh");
  CHECK(taken.statistics.constraints.delaunay_flips > 0);
  // Flipped to the Delaunay triangulation of its points (its outline is
  // their hull).
  CHECK(triangle_set(taken) == triangle_set(test_support::triangulate_points(grid.points)));
  CHECK(refine_checked(grid, "rq30a0.01").statistics.delaunay.construction == "given_mesh");
  // A segment on an edge: taken as it is; one along two edges (through a
  // vertex, no edge itself): found, the segment kept as two.
  clmesh::Input segmented = grid;
  segmented.segments = {{0, 1, 5}, {10, 20, 6}};
  CHECK(refine_checked(segmented, "rpq30").statistics.delaunay.construction == "given_mesh");
  segmented.segments = {{0, 2, 5}};
  CHECK(refine_checked(segmented, "rpq30").statistics.delaunay.construction != "given_mesh");
  // The grid's rectangles (row r, column c: triangles 16 r + 2 c and the
  // next) but some.
  auto without = [&](auto left_out) {
    clmesh::Input mesh = grid;
    mesh.triangles.clear();
    for (std::size_t t = 0; t < grid.triangles.size(); ++t)
      if (!left_out(t / 16, t % 16 / 2))
        mesh.triangles.push_back(grid.triangles[t]);
    return mesh;
  };
  // An L (concave): taken as it is.
  const clmesh::Input ell = without([](std::size_t r, std::size_t c) { return r >= 3 && c >= 4; });
  const clmesh::Mesh ell_taken = refine_checked(ell, "r");
  CHECK(ell_taken.statistics.delaunay.construction == "given_mesh");
  CHECK(ell_taken.triangles.size() == ell.triangles.size());
  refine_checked(ell, "rq30");
  // One hole, two holes, a hole in a corner of the rectangle (touching the
  // outline along two edges): taken as they are, the holes kept.
  for (const auto &holed :
       {without([](std::size_t r, std::size_t c) { return r >= 2 && r < 4 && c >= 3 && c < 5; }),
        without([](std::size_t r, std::size_t c) {
          return r >= 1 && r < 5 && (c == 1 || c == 2 || c == 5 || c == 6) && !(r == 3 && c == 2);
        }),
        without([](std::size_t r, std::size_t c) { return r >= 4 && c < 2; })}) {
    const clmesh::Mesh holed_taken = refine_checked(holed, "r");
    CHECK(holed_taken.statistics.delaunay.construction == "given_mesh");
    CHECK(holed_taken.triangles.size() == holed.triangles.size());
    CHECK(refine_checked(holed, "rq30").statistics.delaunay.construction == "given_mesh");
  }
  // A hole whose corner is a corner of a notch in the outline, two blocks
  // that meet at one corner, two blocks apart, a block in the hole of a
  // ring: found in the Delaunay triangulation, the same domains.
  for (const clmesh::Input &other :
       {without([](std::size_t r, std::size_t c) {
          return (r >= 1 && r < 3 && c >= 1 && c < 3) || (r == 0 && c == 0);
        }),
        without([](std::size_t r, std::size_t c) { return (r < 3) != (c < 4); }),
        without([](std::size_t, std::size_t c) { return c == 4; }),
        without([](std::size_t r, std::size_t c) {
          return r >= 1 && r < 5 && c >= 1 && c < 7 && !(r >= 2 && r < 4 && c >= 3 && c < 5);
        })}) {
    const clmesh::Mesh found = refine_checked(other, "r");
    CHECK(found.statistics.delaunay.construction != "given_mesh");
    CHECK(found.triangles.size() == other.triangles.size());
    refine_checked(other, "rq30");
  }
}

TEST_CASE("refine mesh: a mesh clmesh wrote, refined twice (-pq then -rpq30a, -rpq30a)") {
  for (const char *name : {"A", "face", "square_circle_hole", "la"}) {
    INFO(std::string(name));
    const clmesh::Input pslg = clmesh::read_input(std::string(CLMESH_SHARED_DATA) +
                                                  "/triangle-examples/inputs/" + name + ".poly");
    const clmesh::Mesh first = clmesh::triangulate(device(), pslg, "pq");
    const double area =
        static_cast<double>(total_area(first.points, first.triangles)) / first.triangles.size();
    const clmesh::Input once = as_input(first, pslg);
    const clmesh::Mesh second = refine_checked(once, "rpq30a" + std::to_string(area / 2));
    CHECK(second.points.size() > first.points.size());
    const clmesh::Input twice = as_input(second, pslg);
    const clmesh::Mesh third = refine_checked(twice, "rpq30a" + std::to_string(area / 8));
    CHECK(third.points.size() > second.points.size());
    // The same run again gives the same mesh.
    test_support::check_same_mesh(
        third, clmesh::triangulate(device(), twice, "rpq30a" + std::to_string(area / 8)));
  }
}

TEST_CASE("refine mesh: -r alone makes a valid mesh constrained Delaunay, adding no point") {
  const clmesh::Input grid = skewed_grid(6, 8, 8);
  const clmesh::Mesh mesh = refine_checked(grid, "r");
  CHECK(mesh.points.size() == grid.points.size());
  CHECK(mesh.triangles.size() == grid.triangles.size());
  CHECK(mesh.statistics.constraints.delaunay_flips > 0);
  // Without -p, the boundary edges are the segments, marker 1.
  CHECK(mesh.segments.size() == 2 * (6 + 8));
  for (const Segment &s : mesh.segments)
    CHECK(s.marker == 1);
  // Refined further: the boundary is kept, split only.
  const clmesh::Mesh quality = refine_checked(grid, "rq30");
  CHECK(quality.points.size() > grid.points.size());
}

TEST_CASE("refine mesh: holes in the mesh stay holes, .poly holes carve, regions are ignored") {
  // A frame: the grid less its middle triangles.
  clmesh::Input frame = skewed_grid(6, 6, 1);
  std::vector<clmesh::Triangle> kept;
  for (const auto &t : frame.triangles) {
    const Point c{(frame.points[t[0]].x + frame.points[t[1]].x + frame.points[t[2]].x) / 3,
                  (frame.points[t[0]].y + frame.points[t[1]].y + frame.points[t[2]].y) / 3};
    if (std::fabs(c.x - 0.5) > 0.3 || std::fabs(c.y - 0.5) > 0.3)
      kept.push_back(t);
  }
  frame.triangles = kept;
  refine_checked(frame, "rq30a0.002");
  // A hole seed in the frame's hole changes nothing.
  frame.holes = {{0.5, 0.5}};
  refine_checked(frame, "rpq30");
  // One in the corner square, which segments (-p) close, eats it.
  frame.holes = {{1.0 / 12, 1.0 / 12}};
  frame.segments = {{0, 1, 3}, {1, 8, 3}, {8, 7, 3}, {7, 0, 3}};
  const clmesh::Mesh carved = refine_checked(frame, "rpq30", 1.0 / 36);
  CHECK(carved.statistics.constraints.eaten_triangles == 2);
  // Without -p the .poly's holes and segments are not read.
  refine_checked(frame, "rq30");
  // Regions, regional attributes and areas of a .poly play no part in -r.
  frame.regions = {{{0.5, 0.1}, 7, 1e-5}};
  const clmesh::Mesh ignored = refine_checked(frame, "rpq30aA", 1.0 / 36);
  CHECK(ignored.points.size() == carved.points.size());
  CHECK(ignored.triangle_attribute_count == 0);
}

// The .area bound at p: that of the given triangle holding p (the largest
// of them when p lies on an edge between two; none: infinite).
double area_bound_at(const clmesh::Input &given, Point p) {
  double bound = -1;
  for (std::size_t k = 0; k < given.triangles.size(); ++k) {
    const auto &t = given.triangles[k];
    bool inside = true;
    for (int i = 0; i < 3 && inside; ++i) {
      const Point a = given.points[t[i]], b = given.points[t[(i + 1) % 3]];
      inside = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) >= 0;
    }
    if (inside)
      bound =
          std::max(bound, given.triangle_max_area[k] > 0 ? given.triangle_max_area[k] : HUGE_VAL);
  }
  return bound;
}

TEST_CASE("refine mesh: .area bounds the triangles in each given triangle, attributes diffuse") {
  clmesh::Input grid = skewed_grid(4, 4, 1);
  // Attributes: the triangle's index, and its row.
  grid.triangle_attribute_count = 2;
  for (std::size_t t = 0; t < grid.triangles.size(); ++t) {
    grid.triangle_attributes.push_back(static_cast<double>(t));
    grid.triangle_attributes.push_back(static_cast<double>(t / 8));
    // Dense in the left half, none elsewhere but in one triangle.
    grid.triangle_max_area.push_back(t % 8 < 4 ? 0.0005 : (t == 13 ? 0.002 : -1));
  }
  for (const char *switches : {"ra", "rq25a", "rq30a0.01a"}) {
    const clmesh::Mesh mesh = refine_checked(grid, switches);
    const std::optional<double> global = clmesh::parse_switches(switches).max_area;
    long dense = 0;
    for (const auto &t : mesh.triangles) {
      const Point a = mesh.points[t[0]], b = mesh.points[t[1]], c = mesh.points[t[2]];
      const Point centroid{(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3};
      double bound = area_bound_at(grid, centroid);
      REQUIRE(bound > 0);
      dense += bound == 0.0005;
      if (global)
        bound = std::min(bound, *global);
      CHECK(area(mesh.points, t) <= bound * (1 + 1e-9));
    }
    // The left half (1/2 of the domain) holds at least its area over the bound.
    CHECK(dense >= 1000);
    // Each triangle carries the attributes of one given triangle (those of
    // the triangle it came from by splits; flips pass them on, as Triangle's do).
    REQUIRE(mesh.triangle_attribute_count == 2);
    REQUIRE(mesh.triangle_attributes.size() == 2 * mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const double origin = mesh.triangle_attributes[2 * t];
      REQUIRE(origin >= 0);
      REQUIRE(origin < grid.triangles.size());
      CHECK(mesh.triangle_attributes[2 * t + 1] ==
            static_cast<double>(static_cast<int>(origin) / 8));
    }
  }
}

// Without attributes, a slot's label is only where the search for the given
// triangle that holds its centroid starts, and follows what it found
// (size_bound.cl): the bounds hold all the same.
TEST_CASE("refine mesh: .area bounds hold where the labels follow the walks") {
  clmesh::Input grid = skewed_grid(6, 5, 2);
  for (std::size_t t = 0; t < grid.triangles.size(); ++t)
    grid.triangle_max_area.push_back(t % 3 == 0 ? 0.0004 : (t % 3 == 1 ? 0.002 : -1));
  for (const char *switches : {"ra", "rq30a"}) {
    CAPTURE(switches);
    const clmesh::Mesh mesh = refine_checked(grid, switches);
    long bounded = 0;
    for (const auto &t : mesh.triangles) {
      const Point a = mesh.points[t[0]], b = mesh.points[t[1]], c = mesh.points[t[2]];
      const double bound = area_bound_at(grid, {(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3});
      if (bound > 0) {
        ++bounded;
        CHECK(area(mesh.points, t) <= bound * (1 + 1e-9));
      }
    }
    CHECK(bounded >= 500);
  }
}

TEST_CASE("refine mesh: triangles that are no triangulation are refused, naming one") {
  clmesh::Input input;
  input.points = {{0, 0}, {4, 0}, {0, 4}, {1, 1}, {5, 1}, {1, 5}};
  input.triangles = {{0, 1, 2}, {3, 4, 5}}; // overlapping, no edge shared
  input.triangles_source = "two.ele";
  input.triangle_lines = {2, 3};
  input.first_index = 1;
  std::string message;
  try {
    clmesh::triangulate(device(), input, "rq");
  } catch (const clmesh::InputError &error) {
    message = error.what();
  }
  CHECK(message.find("two.ele:") != std::string::npos);
  CHECK(message.find("overlaps another triangle") != std::string::npos);
  // A vertex that no triangle uses stays out of the mesh, as in Triangle
  // (the middle nodes of a six-node mesh, here one inside and one on an edge).
  input.points = {{0, 0}, {4, 0}, {0, 4}, {1, 1}, {2, 0}};
  input.triangles = {{0, 1, 2}};
  input.triangles_source.clear();
  const clmesh::Mesh unused = clmesh::triangulate(device(), input, "r");
  CHECK(unused.triangles == std::vector<clmesh::Triangle>{{0, 1, 2}});
  CHECK(unused.points.size() == 5);
  const clmesh::Mesh refined = refine_checked(input, "rq30a0.5");
  for (const auto &t : refined.triangles)
    for (int32_t v : t)
      CHECK((v < 3 || v >= 5));
  // -r needs triangles.
  input.triangles.clear();
  CHECK_THROWS_AS(clmesh::triangulate(device(), input, "rq"), clmesh::InputError);
}
