// GPU-DT end to end on the OpenCL device: every result passes the exact
// checker and equals CGAL's Delaunay triangulation triangle for triangle (both
// break cocircular ties with the same symbolic perturbation, so the equality
// holds for degenerate input too).
#include <doctest/doctest.h>

#include "clmesh/clmesh.hpp"
#include "mesh_fixtures.hpp"
#include "priority.h"
#include "runtime/opencl_context.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <set>

#ifdef CLMESH_HAVE_CGAL
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#endif

using clmesh::Point;
using clmesh::Triangle;

namespace {

using test_support::device;
using test_support::problems;
using test_support::triangulate_points;

#ifdef CLMESH_HAVE_CGAL
// CGAL's triangles over input indices, each duplicate group named by its smallest index.
std::set<Triangle> cgal_triangles(const std::vector<Point> &points) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb>;
  using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
  std::map<std::pair<double, double>, int> smallest;
  std::vector<std::pair<K::Point_2, int>> input;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    smallest.emplace(std::make_pair(points[i].x, points[i].y), i);
    input.push_back({K::Point_2(points[i].x, points[i].y), i});
  }
  DT dt(input.begin(), input.end());
  std::set<Triangle> triangles;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      const auto &p = f->vertex(k)->point();
      t[k] = smallest.at({p.x(), p.y()});
    }
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    triangles.insert(t);
  }
  return triangles;
}
#endif

clmesh::Mesh triangulate_and_check(const std::vector<Point> &points,
                                   const clmesh::Options &options = {}) {
  clmesh::Mesh result = triangulate_points(points, options);
  const clmesh::DelaunayStats &stats = result.statistics.delaunay;
  // The points are the input's, none added.
  REQUIRE(result.input_points == static_cast<long>(points.size()));
  REQUIRE(result.points.size() == points.size());
  CHECK(test_support::starts_with(result.points, points));
  REQUIRE(result.duplicate_of.size() == points.size());
  const auto report = clmesh::check_triangulation(points, result.triangles, result.neighbors,
                                                  result.duplicate_of, true);
  INFO(problems(report));
  CHECK(report.ok);
  CHECK(stats.triangles == static_cast<long>(result.triangles.size()));
  CHECK_FALSE(result.statistics.constrained);
  CHECK_FALSE(result.statistics.refined);
  // Duplicates are named by the smallest index of their group.
  for (std::size_t i = 0; i < points.size(); ++i)
    if (result.duplicate_of[i] >= 0)
      CHECK(result.duplicate_of[i] < static_cast<int32_t>(i));
#ifdef CLMESH_HAVE_CGAL
  const std::set<Triangle> ours(result.triangles.begin(), result.triangles.end());
  CHECK(ours.size() == result.triangles.size());
  CHECK(ours == cgal_triangles(points));
#endif
  return result;
}

} // namespace

TEST_CASE("delaunay: thesis distributions equal CGAL") {
  SUBCASE("uniform") { triangulate_and_check(fixtures::uniform(30000, 1)); }
  SUBCASE("gaussian") { triangulate_and_check(fixtures::gaussian(30000, 2)); }
  SUBCASE("disk") { triangulate_and_check(fixtures::disk(30000, 3)); }
  SUBCASE("circle") { triangulate_and_check(fixtures::circle(5000, 4)); }
  SUBCASE("thin circle") {
    // About ten points a pixel along a ring a pixel wide: a turned-over
    // triangle's site is left out with the other points of its pixel (one of
    // them would take the pixel over and turn the triangle over again), and
    // the diagrams settle.
    const auto points = fixtures::ring(30000, 1e-3, 5);
    const auto result = triangulate_and_check(points);
    CHECK(result.statistics.delaunay.construction == "voronoi");
    CHECK(result.statistics.delaunay.dropped_sites > 0);
    // Every point outside the hull's octagon: the hull is found by dropping
    // the points inside its chords, then the hull is fanned.
    clmesh::Options fan;
    fan.tuning.construction = clmesh::Construction::fan;
    CHECK(triangulate_and_check(points, fan).statistics.delaunay.construction == "hull_fan");
  }
  SUBCASE("thin circle fanned, its hull found on two threads") {
    // More than 2^16 points outside the hull's octagon: the octagon's test
    // and the chords' take two threads (convex_hull), with the same hull.
    clmesh::Options fan;
    fan.tuning.construction = clmesh::Construction::fan;
    const auto result = triangulate_and_check(fixtures::ring(70000, 1e-3, 6), fan);
    CHECK(result.statistics.delaunay.construction == "hull_fan");
    // The fan's few triangles take the points in levels, each later one's
    // points starting their walks at their anchors.
    CHECK(result.statistics.delaunay.insertion_levels == 2);
  }
  SUBCASE("tight clusters: levels after few sites, crowded cells ordered again") {
    // Each cluster lies in one cell of the 2^16 grid of the Hilbert order:
    // its points are ordered again inside it, and the few sites (at most one
    // a cluster) leave the rest to levels of insertion.
    const auto result = triangulate_and_check(fixtures::clusters(90000, 30, 1e-9, 7));
    CHECK(result.statistics.delaunay.insertion_levels > 1);
  }
  SUBCASE("uniform points go in one level") {
    CHECK(triangulate_and_check(fixtures::uniform(70000, 8)).statistics.delaunay.insertion_levels ==
          1);
  }
  SUBCASE("512x512 grid") { triangulate_and_check(fixtures::lattice(512)); }
}

TEST_CASE("delaunay: degenerate input") {
  SUBCASE("full lattice, every quad cocircular") {
    const auto result = triangulate_and_check(fixtures::lattice(60));
    CHECK(result.triangles.size() == 2u * 59 * 59);
    CHECK(result.statistics.delaunay.exact_predicate_calls > 0);
  }
  SUBCASE("heavy duplicates") {
    std::vector<Point> points;
    const auto base = fixtures::uniform(2000, 5);
    for (int copy = 0; copy < 5; ++copy)
      points.insert(points.end(), base.begin(), base.end());
    const auto result = triangulate_and_check(points);
    CHECK(result.statistics.delaunay.duplicates == 4 * 2000);
    for (int i = 2000; i < 10000; ++i)
      CHECK(result.duplicate_of[i] == i % 2000);
  }
  SUBCASE("duplicates of hull corners") {
    auto points = fixtures::lattice(10);
    points.push_back({0, 0});
    points.push_back({9, 9});
    points.push_back({0, 0});
    const auto result = triangulate_and_check(points);
    CHECK(result.statistics.delaunay.duplicates == 3);
  }
  SUBCASE("a wheel: cocircular points around one vertex that owns every triangle") {
    std::vector<Point> points = {{0, 0}};
    const int spokes = 4000;
    for (int i = 0; i < spokes; ++i) {
      const double angle = 2 * M_PI * i / spokes;
      points.push_back({std::cos(angle), std::sin(angle)});
    }
    const auto result = triangulate_and_check(points);
    // In general position the centre is in every triangle; rounded points on
    // the circle may shave a few off, never most.
    long at_centre = 0;
    for (const auto &t : result.triangles)
      at_centre += t[0] == 0;
    CHECK(at_centre > spokes / 2);
  }
  SUBCASE("a line plus one point") {
    std::vector<Point> points;
    for (int i = 0; i < 3000; ++i)
      points.push_back({static_cast<double>(i), 0.0});
    points.push_back({1500.5, 1.0});
    const auto result = triangulate_and_check(points);
    CHECK(result.triangles.size() == 2999u);
  }
  SUBCASE("collinear runs on the hull and inside") {
    auto points = fixtures::lattice(30);
    for (int i = 0; i < 100; ++i)
      points.push_back({i * 0.29, i * 0.29}); // the diagonal, densely
    triangulate_and_check(points);
  }
  SUBCASE("tiny box far from the origin") {
    auto points = fixtures::uniform(5000, 6);
    for (auto &p : points)
      p = {1e6 + p.x * 1e-9, -3e5 + p.y * 1e-9};
    triangulate_and_check(points);
  }
  SUBCASE("lattice far from the origin") {
    triangulate_and_check(fixtures::lattice(40, 1e-6, {12345.0, -6789.0}));
  }
  SUBCASE("huge and tiny magnitudes") {
    for (const double scale : {1e-40, 1e40}) {
      auto points = fixtures::uniform(3000, 7);
      for (auto &p : points)
        p = {p.x * scale, p.y * scale};
      triangulate_and_check(points);
    }
  }
  SUBCASE("points on a circle, exactly cocircular") {
    // 3-4-5 style Pythagorean points: exactly on the circle of radius 5525.
    std::vector<Point> points;
    const int r = 5525;
    for (int x = -r; x <= r; ++x)
      for (int y : {-1, 1}) {
        const long long yy = static_cast<long long>(r) * r - static_cast<long long>(x) * x;
        const auto root = static_cast<long long>(std::llround(std::sqrt(static_cast<double>(yy))));
        if (root * root == yy)
          points.push_back({static_cast<double>(x), static_cast<double>(y * root)});
      }
    points.push_back({0.5, 0.25});
    REQUIRE(points.size() > 20);
    triangulate_and_check(points);
  }
}

TEST_CASE("delaunay: all points collinear give no triangle") {
  std::vector<Point> points;
  for (int i = 0; i < 100; ++i)
    points.push_back({i * 0.5, i * 0.25});
  points.push_back({0, 0});
  const auto result = triangulate_points(points);
  CHECK(result.triangles.empty());
  CHECK(result.duplicate_of[100] == 0);
}

TEST_CASE("delaunay: reference inputs") {
  const std::string data = CLMESH_SHARED_DATA;
  SUBCASE("delaunator robustness fixtures") {
    for (const char *name : {"issue13", "issue43", "issue44", "robustness1", "robustness2",
                             "robustness3", "robustness4", "ukraine"}) {
      INFO(name);
      const auto points = fixtures::json_points(data + "/delaunator/" + name + ".json");
      REQUIRE(points.size() >= 3);
      triangulate_and_check(points);
      // Delaunator re-runs its fixtures scaled from 1e-9 to 1e9.
      for (const double scale : {1e-9, 1e9}) {
        auto scaled = points;
        for (auto &p : scaled)
          p = {p.x * scale, p.y * scale};
        triangulate_and_check(scaled);
      }
    }
  }
  SUBCASE("Triangle's example .node files") {
    for (const char *name : {"greenland", "spiral", "dots", "diamond_02_00009", "ell"}) {
      INFO(name);
      const auto set = clmesh::read_node(data + "/triangle-examples/inputs/" + name + ".node");
      triangulate_and_check(set.points);
    }
  }
}

TEST_CASE("delaunay: the same triangles whatever the work-group size") {
  const auto points = fixtures::gaussian(20000, 8);
  clmesh::Options options;
  options.tuning.work_group = 1;
  const auto first = triangulate_points(points, options);
  options.tuning.work_group = 256;
  const auto second = triangulate_points(points, options);
  options.tuning.work_group = 64;
  const auto third = triangulate_points(points, options);
  // The largest the device allows (PoCL: 4096; private arrays of every
  // work-item of a group must then fit a worker thread's stack).
  options.tuning.work_group = clmesh::max_work_group_size(device());
  const auto largest = triangulate_points(points, options);
  // A run that names no size gets the default again on the shared device.
  const auto unnamed = triangulate_points(points);
  CHECK(device().work_group() == device().default_work_group());
  CHECK(unnamed.triangles == first.triangles);
  CHECK(first.triangles == second.triangles);
  CHECK(first.neighbors == second.neighbors);
  CHECK(first.triangles == third.triangles);
  CHECK(first.triangles == largest.triangles);
  CHECK(first.statistics.delaunay.flips == third.statistics.delaunay.flips);
  CHECK(first.statistics.delaunay.construction == "voronoi");
  CHECK(first.statistics.delaunay.dropped_sites == second.statistics.delaunay.dropped_sites);
  CHECK(first.statistics.delaunay.construction_rounds ==
        second.statistics.delaunay.construction_rounds);
  CHECK(first.statistics.delaunay.missing_points == second.statistics.delaunay.missing_points);
}

// Short flip passes run in one work-group, pass after pass
// (flip_passes_in_group), or as separate kernels: the same flips.
TEST_CASE("delaunay: the same triangles whether short flip passes run in one work-group or not") {
  const std::vector<std::pair<std::string, std::vector<Point>>> inputs = {
      {"gaussian", fixtures::gaussian(20000, 31)}, {"lattice", fixtures::lattice(120)}};
  for (const auto &[name, points] : inputs) {
    CAPTURE(name);
    clmesh::Options options;
    options.tuning.group_pass_limit = 0;
    const auto by_kernels = triangulate_points(points, options);
    options.tuning.group_pass_limit = std::size_t{1} << 30;
    const auto in_group = triangulate_points(points, options);
    options.tuning.group_pass_limit = clmesh::Tuning{}.group_pass_limit;
    const auto mixed = triangulate_and_check(points, options);
    CHECK(by_kernels.triangles == in_group.triangles);
    CHECK(by_kernels.neighbors == in_group.neighbors);
    CHECK(by_kernels.triangles == mixed.triangles);
    CHECK(by_kernels.statistics.delaunay.flips == in_group.statistics.delaunay.flips);
    CHECK(by_kernels.statistics.delaunay.flip_passes == mixed.statistics.delaunay.flip_passes);
    CHECK(by_kernels.statistics.delaunay.exact_predicate_calls ==
          in_group.statistics.delaunay.exact_predicate_calls);
  }
}

// Phases 1-3 against the hull fan: the same triangles, whatever the grid.
// Coarse grids leave out most points, hull corners among them, so Phase 4
// also inserts points outside the first triangulation's hull.
TEST_CASE("delaunay: the Voronoi construction gives the hull fan's mesh, on any grid") {
  const std::vector<std::pair<std::string, std::vector<Point>>> inputs = {
      {"uniform", fixtures::uniform(20000, 21)},
      {"gaussian", fixtures::gaussian(20000, 22)},
      {"disk", fixtures::disk(20000, 23)},
      {"lattice", fixtures::lattice(120)},
      {"lattice far from the origin", fixtures::lattice(60, 1e-3, {1e6, -2e6})}};
  for (const auto &[name, points] : inputs)
    for (const int grid : {4, 16, 64, 0, 1024}) {
      CAPTURE(name);
      CAPTURE(grid);
      clmesh::Options options;
      options.tuning.construction = clmesh::Construction::fan;
      const auto fan = triangulate_points(points, options);
      CHECK(fan.statistics.delaunay.construction == "hull_fan");
      options.tuning.construction = clmesh::Construction::automatic;
      if (grid > 0) // 0: the default grid, chosen from the points
        options.tuning.grid = grid;
      const auto result = triangulate_and_check(points, options);
      CHECK(result.triangles == fan.triangles);
      CHECK(result.statistics.delaunay.construction_rounds >= 1);
      if (grid == 0 && name.rfind("lattice", 0) != 0) { // the default grid: no fallback
        CHECK(result.statistics.delaunay.construction == "voronoi");
        CHECK(result.statistics.delaunay.constructed_triangles >
              static_cast<long>(points.size()) / 10);
        CHECK(result.statistics.delaunay.missing_points < static_cast<long>(points.size()));
      }
      if (grid == 0 && name.rfind("lattice", 0) == 0) {
        // A pixel for every lattice point: one construction, nothing missing.
        CHECK(result.statistics.delaunay.grid == 128 >> (name == "lattice" ? 0 : 1));
        CHECK(result.statistics.delaunay.construction == "voronoi");
        CHECK(result.statistics.delaunay.missing_points == 0);
      }
    }
}

// A dense disk: at the default grid, the outer sites turn over at their real
// coordinates layer after layer (nearly collinear along the hull). Leaving out
// only the middle site of each turned-over triangle lets the rounds settle,
// where leaving out all three sites fell back to the hull fan at 400k points.
TEST_CASE("delaunay: the construction settles on a dense disk") {
  const auto points = fixtures::disk(400000, 41);
  const clmesh::Mesh result = triangulate_points(points);
  const auto report = clmesh::check_triangulation(points, result.triangles, result.neighbors,
                                                  result.duplicate_of, true);
  INFO(problems(report));
  CHECK(report.ok);
  CHECK(result.statistics.delaunay.construction == "voronoi");
  CHECK(result.statistics.delaunay.constructed_triangles > static_cast<long>(points.size()) / 4);
}

// Phase 3 mends turned-over triangles by flips (untangling, cl/shifting.cl)
// instead of leaving their middle sites out and building the diagram again.
// Uniform points at the default grid turn dozens of triangles over, each
// with its middle site just across the edge into the next triangle: one
// diagram, no site left out, and the hull fan's mesh.
TEST_CASE("delaunay: turned-over triangles are mended by flips in the first diagram") {
  const auto points = fixtures::uniform(300000, 43);
  const clmesh::Mesh result = triangulate_and_check(points);
  const clmesh::DelaunayStats &stats = result.statistics.delaunay;
  CHECK(stats.construction == "voronoi");
  CHECK(stats.untangling_flips > 10);
  CHECK(stats.construction_rounds == 1);
  CHECK(stats.dropped_sites == 0);
  clmesh::Options options;
  options.tuning.construction = clmesh::Construction::fan;
  CHECK(triangulate_points(points, options).triangles == result.triangles);
  // Any work-group size: the same flips, the same mesh.
  options.tuning.construction = clmesh::Construction::automatic;
  options.tuning.work_group = 1;
  const clmesh::Mesh single = triangulate_points(points, options);
  CHECK(single.statistics.delaunay.untangling_flips == stats.untangling_flips);
  CHECK(single.triangles == result.triangles);
  CHECK(single.neighbors == result.neighbors);
}

// Inputs that turn many triangles over in Phase 3, on coarse and default
// grids: whatever the flips mend and the rounds leave out, the result is the
// hull fan's mesh and CGAL's (triangulate_and_check).
TEST_CASE("delaunay: untangling on rings, hairs and near duplicates gives the fan's mesh") {
  const std::vector<std::pair<std::string, std::vector<Point>>> inputs = {
      {"rings and hairs", fixtures::rings_and_hairs(9000, 61)},
      {"concentric rings", fixtures::concentric_rings(9000, 62)},
      {"near duplicates", fixtures::near_duplicates(6000, 63)}};
  long flips = 0;
  for (const auto &[name, points] : inputs) {
    clmesh::Options options;
    options.tuning.construction = clmesh::Construction::fan;
    const auto fan = triangulate_points(points, options);
    options.tuning.construction = clmesh::Construction::automatic;
    for (const int grid : {16, 64, 0}) {
      CAPTURE(name);
      CAPTURE(grid);
      if (grid > 0)
        options.tuning.grid = grid;
      const auto result = triangulate_and_check(points, options);
      CHECK(result.triangles == fan.triangles);
      flips += result.statistics.delaunay.untangling_flips;
    }
  }
  CHECK(flips > 100);
}

// By default, inputs below Tuning::kFanBelow points start from the hull fan
// and larger ones from the diagram; a grid or --construction overrides it,
// and the triangles never change.
TEST_CASE("delaunay: the first triangulation's default depends on the input's size only") {
  const clmesh::Mesh large =
      triangulate_and_check(fixtures::gaussian(clmesh::Tuning::kFanBelow, 42));
  CHECK(large.statistics.delaunay.construction == "voronoi");
  auto points = fixtures::gaussian(clmesh::Tuning::kFanBelow - 2, 43);
  points.push_back(points[7]); // a duplicate
  const clmesh::Mesh small = triangulate_and_check(points);
  CHECK(small.statistics.delaunay.construction == "hull_fan");
  clmesh::Options options;
  options.tuning.construction = clmesh::Construction::voronoi;
  const clmesh::Mesh voronoi = triangulate_and_check(points, options);
  CHECK(voronoi.statistics.delaunay.construction == "voronoi");
  options.tuning.construction = clmesh::Construction::automatic;
  options.tuning.grid = 32;
  const clmesh::Mesh gridded = triangulate_and_check(points, options);
  CHECK(gridded.statistics.delaunay.construction == "voronoi");
  CHECK(small.triangles == voronoi.triangles);
  CHECK(small.neighbors == voronoi.neighbors);
  CHECK(small.duplicate_of == voronoi.duplicate_of);
  CHECK(small.triangles == gridded.triangles);
}

TEST_CASE("delaunay: the ties of missing-point insertion are unique: a bijection on so many bits") {
  // cl/priority.h clm_priority_within: the points' priorities are unique
  // only if it maps the numbers below 2^bits one to one onto them.
  for (int bits = 1; bits <= 20; ++bits) {
    const unsigned n = 1u << bits;
    std::vector<char> seen(n, 0);
    unsigned repeated = 0;
    for (unsigned x = 0; x < n; ++x) {
      const unsigned y = clm_priority_within(x, bits);
      repeated += y >= n || seen[y];
      if (y < n)
        seen[y] = 1;
    }
    INFO("bits " << bits);
    CHECK(repeated == 0);
  }
  for (const unsigned x : {0u, 1u, 12345u, 0xffffffffu})
    CHECK(clm_priority_within(x, 32) == clm_priority_of(x));
}

TEST_CASE("delaunay: bad input is refused with a typed error") {
  CHECK_THROWS_AS(triangulate_points({{0, 0}, {1, 1}}), clmesh::InputError);
  CHECK_THROWS_AS(triangulate_points({{0, 0}, {1, 1}, {1e300, 0}}), clmesh::InputError);
  CHECK_THROWS_AS(triangulate_points({{0, 0}, {1, 1}, {1e-300, 0}}), clmesh::InputError);
  CHECK_THROWS_AS(triangulate_points({{0, 0}, {1, 1}, {std::nan(""), 0}}), clmesh::InputError);
}

TEST_CASE("voronoi banding: every pixel is coloured with a nearest site") {
  for (const int grid : {37, 64, 256}) {
    auto points = fixtures::gaussian(300, 9);
    points.push_back(points[5]); // a pixel shared by two points
    clmesh::Options options;
    options.voronoi_image = true;
    options.tuning.grid = grid;
    const auto result = triangulate_points(points, options);
    REQUIRE(result.statistics.delaunay.grid == grid);
    REQUIRE(result.voronoi_image.size() == static_cast<std::size_t>(grid) * grid);
    CHECK(result.statistics.delaunay.pixel_collisions >= 1);
    double min_x = points[0].x, min_y = points[0].y, max_x = min_x, max_y = min_y;
    for (const auto &p : points) {
      min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
      min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
    }
    const double scale = grid / std::max(max_x - min_x, max_y - min_y);
    std::vector<std::pair<long, long>> pixel(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      pixel[i] = {std::min<long>(static_cast<long>((points[i].x - min_x) * scale), grid - 1),
                  std::min<long>(static_cast<long>((points[i].y - min_y) * scale), grid - 1)};
    long wrong = 0;
    for (long y = 0; y < grid; ++y)
      for (long x = 0; x < grid; ++x) {
        const int site = result.voronoi_image[y * grid + x];
        REQUIRE(site >= 0);
        long best = -1;
        for (const auto &[px, py] : pixel) {
          const long d = (px - x) * (px - x) + (py - y) * (py - y);
          best = best < 0 ? d : std::min(best, d);
        }
        const auto [sx, sy] = pixel[site];
        wrong += (sx - x) * (sx - x) + (sy - y) * (sy - y) != best;
      }
    CHECK(wrong == 0);
  }
}
