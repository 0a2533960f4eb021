// GPU-QM: refinement of a point set's Delaunay triangulation to a minimum
// angle and a maximum area, checked exactly on every output.
#include <doctest/doctest.h>

#include "clmesh/check.hpp"
#include "clmesh/constrained.hpp"
#include "clmesh/errors.hpp"
#include "clmesh/refine.hpp"
#include "mesh_fixtures.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>

using clmesh::Point;
using test_support::device;
using test_support::problems;

namespace {

double smallest_angle_degrees(const std::vector<Point> &p, const clmesh::Triangle &t) {
  double smallest = 180;
  for (int i = 0; i < 3; ++i) {
    const Point &a = p[t[i]], &b = p[t[(i + 1) % 3]], &c = p[t[(i + 2) % 3]];
    const double ux = b.x - a.x, uy = b.y - a.y, vx = c.x - a.x, vy = c.y - a.y;
    smallest = std::min(smallest,
                        std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / M_PI);
  }
  return smallest;
}

double area(const std::vector<Point> &p, const clmesh::Triangle &t) {
  const Point &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

// Refines, then checks: a valid triangulation whose boundary edges (hull
// edges, split at rounded midpoints) bound it and whose other edges are all
// locally Delaunay; every input point used; the bounds met everywhere.
// remaining_allowed: inputs where bad triangles may remain (nearly straight
// runs of hull points, sharp hull angles): then no more triangles than
// reported may miss the bound.
clmesh::RefineResult
refine_checked(const std::vector<Point> &input, double angle, double max_area = -1,
               clmesh::RefineAlgorithm algorithm = clmesh::RefineAlgorithm::qmv,
               bool remaining_allowed = false, int filter_rings = 0, int filter_distance_rings = -1,
               double filter_near = -1, int election_rings = -1) {
  clmesh::RefineOptions options;
  options.min_angle = angle;
  options.max_area = max_area;
  options.algorithm = algorithm;
  options.filter_rings = filter_rings;
  options.filter_distance_rings = filter_distance_rings;
  options.filter_near = filter_near;
  options.election_rings = election_rings;
  clmesh::RefineResult result = clmesh::refine_delaunay(device(), input, options);
  std::vector<Point> points = input;
  points.insert(points.end(), result.added_points.begin(), result.added_points.end());
  const auto &mesh = result.mesh;
  REQUIRE(mesh.duplicate_of.size() == points.size());
  std::vector<clmesh::Segment> boundary;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i)
      if (mesh.neighbors[t][i] < 0)
        boundary.push_back({mesh.triangles[t][(i + 1) % 3], mesh.triangles[t][(i + 2) % 3], 1});
  const auto report = clmesh::check_constrained(points, mesh.triangles, mesh.neighbors,
                                                mesh.duplicate_of, boundary, false);
  INFO(problems(report));
  CHECK(report.ok);
  std::vector<char> used(points.size(), 0);
  for (const auto &t : mesh.triangles)
    for (int32_t v : t)
      used[v] = 1;
  long unused = 0;
  for (std::size_t i = 0; i < input.size(); ++i)
    unused += !used[i] && mesh.duplicate_of[i] < 0;
  CHECK(unused == 0);
  if (!remaining_allowed)
    CHECK(result.stats.remaining_bad == 0);
  // Every insertion is in the mesh, or was deleted as redundant.
  CHECK(result.stats.inserted == result.stats.insertions - result.stats.deleted);
  CHECK(static_cast<long>(result.added_points.size()) == result.stats.inserted);
  double worst_angle = 180, largest = 0;
  long below = 0;
  for (const auto &t : mesh.triangles) {
    const double smallest = smallest_angle_degrees(points, t);
    worst_angle = std::min(worst_angle, smallest);
    below += smallest < angle - 1e-6;
    largest = std::max(largest, area(points, t));
  }
  MESSAGE(input.size() << " points, -q" << angle << ": " << result.added_points.size()
                       << " Steiner points, smallest angle " << worst_angle);
  if (remaining_allowed)
    CHECK(below <= result.stats.remaining_bad);
  else
    CHECK(worst_angle >= angle - 1e-6);
  if (max_area > 0)
    CHECK(largest <= max_area * (1 + 1e-9));
  return result;
}

} // namespace

TEST_CASE("refine: minimum angles on the thesis distributions, GPU-QM-V and GPU-QM") {
  for (const auto algorithm : {clmesh::RefineAlgorithm::qmv, clmesh::RefineAlgorithm::qm}) {
    INFO((algorithm == clmesh::RefineAlgorithm::qm ? "GPU-QM" : "GPU-QM-V"));
    for (const double angle : {20.0, 25.0, 30.0}) {
      INFO("angle " << angle);
      refine_checked(fixtures::uniform(4000, 71), angle, -1, algorithm);
      refine_checked(fixtures::gaussian(4000, 72), angle, -1, algorithm);
      refine_checked(fixtures::disk(4000, 73), angle, -1, algorithm);
    }
    refine_checked(fixtures::circle(1000, 74), 30, -1, algorithm);
    refine_checked(fixtures::lattice(40), 30, -1, algorithm); // cocircular: already 45 degrees
    // A lattice cut by an area bound: Steiner points on lattice edges and
    // cocircular with their neighbours, stars where no flop is possible.
    refine_checked(fixtures::lattice(12), 30, 0.05, algorithm);
  }
}

TEST_CASE("refine: nearly straight runs of hull points (delaunator fixtures)") {
  // issue43: four of five points nearly on one line; a rounded hull midpoint
  // there once made a flat triangle (now such a split is not made).
  const std::string data = CLMESH_SHARED_DATA;
  for (const char *name : {"issue43", "issue44", "robustness3", "robustness4", "ukraine"}) {
    INFO(name);
    const auto points = fixtures::json_points(data + "/delaunator/" + name + ".json");
    for (const double angle : {20.0, 25.0})
      refine_checked(points, angle, -1, clmesh::RefineAlgorithm::qmv, true);
  }
}

TEST_CASE("refine: flip-flop deletes redundant points, GPU-QM more eagerly than GPU-QM-V") {
  // The same insertion filter for both (by priority only): only their
  // deletion rules differ.
  const auto points = fixtures::uniform(6000, 80);
  const auto qmv = refine_checked(points, 30, -1, clmesh::RefineAlgorithm::qmv, false, 2, 0);
  const auto qm = refine_checked(points, 30, -1, clmesh::RefineAlgorithm::qm, false, 2, 0);
  MESSAGE("GPU-QM-V: " << qmv.stats.insertions << " insertions, " << qmv.stats.deleted
                       << " deleted; GPU-QM: " << qm.stats.insertions << " insertions, "
                       << qm.stats.deleted << " deleted");
  CHECK(qmv.stats.deleted > 0);
  CHECK(qm.stats.deleted > qmv.stats.deleted);
  CHECK(qm.stats.non_delaunay_flips > qmv.stats.non_delaunay_flips);
  CHECK(qmv.stats.delaunay_flips > 0);
  // Only a deleted point can come back.
  CHECK(qm.stats.inserted_more_than_once <= qm.stats.deleted);
  CHECK(qmv.stats.inserted_more_than_once <= qmv.stats.deleted);
  CHECK(qm.stats.inserted_more_than_once > 0);
}

TEST_CASE("refine: an insertion filter that looks further inserts fewer points") {
  const auto points = fixtures::uniform(6000, 80);
  for (const auto algorithm : {clmesh::RefineAlgorithm::qmv, clmesh::RefineAlgorithm::qm}) {
    const auto two = refine_checked(points, 30, -1, algorithm, false, 2);
    const auto three = refine_checked(points, 30, -1, algorithm, false, 3);
    MESSAGE("two rings: " << two.stats.inserted << " Steiner points, " << two.stats.iterations
                          << " iterations; three: " << three.stats.inserted << ", "
                          << three.stats.iterations);
    CHECK(three.stats.inserted < two.stats.inserted);
    CHECK(three.stats.iterations > two.stats.iterations);
  }
  clmesh::RefineOptions options;
  options.min_angle = 30;
  options.filter_rings = 4;
  CHECK_THROWS_AS(clmesh::refine_delaunay(device(), points, options), clmesh::UsageError);
}

TEST_CASE("refine: the filter leaves out the pairs GPU-QM-V's step 3 would break up") {
  // Without the distance test most deletions are of pairs inserted at once
  // (equal priorities on either side of a short edge, or a ring further).
  const auto points = fixtures::uniform(6000, 80);
  const auto qmv = clmesh::RefineAlgorithm::qmv;
  const auto priority_only = refine_checked(points, 30, -1, qmv, false, 2, 0);
  const auto with_distance = refine_checked(points, 30, -1, qmv, false, 2, 1);
  MESSAGE("by priority: " << priority_only.stats.insertions << " insertions, "
                          << priority_only.stats.deleted << " deleted; with distance: "
                          << with_distance.stats.insertions << ", " << with_distance.stats.deleted);
  CHECK(with_distance.stats.deleted * 5 < priority_only.stats.deleted);
  CHECK(with_distance.stats.insertions < priority_only.stats.insertions);
  // No more points in the end (within half a percent).
  CHECK(with_distance.stats.inserted * 200 < priority_only.stats.inserted * 201);
  clmesh::RefineOptions options;
  options.min_angle = 30;
  options.filter_distance_rings = 2;
  CHECK_THROWS_AS(clmesh::refine_delaunay(device(), points, options), clmesh::UsageError);
}

TEST_CASE("refine: far better candidates do not hold GPU-QM-V's insertions back") {
  // Along a thin ring the small triangles send their candidates into the same
  // few large triangles inside it; with the filter's priority at any
  // distance they went in about one per large triangle and iteration.
  const auto points = fixtures::ring(20000, 1e-3, 81);
  const auto qmv = clmesh::RefineAlgorithm::qmv;
  const auto any_distance = refine_checked(points, 20, -1, qmv, false, 0, -1, 0);
  const auto near_only = refine_checked(points, 20, -1, qmv);
  MESSAGE("at any distance: " << any_distance.stats.iterations << " iterations, "
                              << any_distance.stats.inserted << " points; near only: "
                              << near_only.stats.iterations << ", " << near_only.stats.inserted);
  CHECK(near_only.stats.iterations * 10 < any_distance.stats.iterations * 9);
  // No more than 1% more points.
  CHECK(near_only.stats.inserted * 100 < any_distance.stats.inserted * 101);
  clmesh::RefineOptions options;
  options.filter_near = 0.5;
  CHECK_THROWS_AS(clmesh::refine_delaunay(device(), points, options), clmesh::UsageError);
}

TEST_CASE("refine: midpoints of different hull edges go in the same iteration") {
  // A square's four corners around points kept off its sides: four long hull
  // edges, halved again and again. When a better midpoint within the rings
  // kept one out, the halves along a side went in about one at a time.
  std::vector<Point> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const Point &p : fixtures::uniform(20000, 82))
    points.push_back({0.01 + 0.98 * p.x, 0.01 + 0.98 * p.y});
  for (const auto algorithm : {clmesh::RefineAlgorithm::qmv, clmesh::RefineAlgorithm::qm}) {
    clmesh::RefineOptions options;
    options.min_angle = 20;
    options.algorithm = algorithm;
    options.parallel_midpoints = false;
    const auto one_by_one = clmesh::refine_delaunay(device(), points, options);
    const auto parallel = refine_checked(points, 20, -1, algorithm);
    MESSAGE("midpoints kept out by better ones: "
            << one_by_one.stats.iterations << " iterations, " << one_by_one.stats.inserted
            << " points; in parallel: " << parallel.stats.iterations << ", "
            << parallel.stats.inserted);
    CHECK(parallel.stats.iterations * 4 < one_by_one.stats.iterations * 3);
    // No more points (within half a percent).
    CHECK(parallel.stats.inserted * 200 < one_by_one.stats.inserted * 201);
  }
}

TEST_CASE("refine: GPU-QM-V's election locates fewer candidates for the same mesh size") {
  // Most candidates of bad triangles near worse ones lose in the insertion
  // filter: only the elected bad triangles send theirs, the others wait. A
  // square's corners bound the points, so that the hull's long edges are
  // halved again and again (bad triangles at the hull are always elected).
  std::vector<Point> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const Point &p : fixtures::uniform(20000, 83))
    points.push_back({0.01 + 0.98 * p.x, 0.01 + 0.98 * p.y});
  const auto qmv = clmesh::RefineAlgorithm::qmv;
  for (const double angle : {20.0, 30.0}) {
    INFO("angle " << angle);
    const auto all = refine_checked(points, angle, -1, qmv, false, 0, -1, -1, 0);
    const auto one_ring = refine_checked(points, angle, -1, qmv, false, 0, -1, -1, 1);
    const auto two_rings = refine_checked(points, angle, -1, qmv);
    MESSAGE("candidates, iterations, points: every bad triangle "
            << all.stats.candidates << ", " << all.stats.iterations << ", " << all.stats.inserted
            << "; elected in one ring " << one_ring.stats.candidates << ", "
            << one_ring.stats.iterations << ", " << one_ring.stats.inserted << "; in two "
            << two_rings.stats.candidates << ", " << two_rings.stats.iterations << ", "
            << two_rings.stats.inserted);
    CHECK(one_ring.stats.candidates < all.stats.candidates);
    CHECK(two_rings.stats.candidates < one_ring.stats.candidates);
    CHECK(two_rings.stats.candidates * 3 < all.stats.candidates * 2);
    // At most a third more iterations, and 1.5% more points.
    CHECK(two_rings.stats.iterations * 3 <= all.stats.iterations * 4);
    CHECK(two_rings.stats.inserted * 200 < all.stats.inserted * 203);
  }
  clmesh::RefineOptions options;
  options.min_angle = 30;
  options.election_rings = 3;
  CHECK_THROWS_AS(clmesh::refine_delaunay(device(), points, options), clmesh::UsageError);
}

TEST_CASE("refine: maximum area, alone and with an angle") {
  refine_checked(fixtures::uniform(500, 75), 0, 1e-3);
  refine_checked(fixtures::uniform(500, 76), 28, 2e-4);
}

TEST_CASE("refine: a mesh that outgrows its first room, several times") {
  // About 40 times the input's room in Steiner points: the arrays grow while
  // candidates wait, and the search starts over on the grown mesh.
  const auto result = refine_checked(fixtures::uniform(300, 77), 25, 4e-5);
  CHECK(result.stats.growths >= 2);
  CHECK(result.added_points.size() > 10000);
}

TEST_CASE("refine: small angles of the hull end the refinement, never a hang") {
  // A thin wedge: the hull angle at the apex is about 3 degrees.
  std::vector<Point> points = {{0, 0}, {10, 0.25}, {10, -0.25}};
  for (int i = 1; i < 40; ++i)
    points.push_back({i * 0.25, 0});
  clmesh::RefineOptions options;
  options.min_angle = 30;
  for (const auto algorithm : {clmesh::RefineAlgorithm::qmv, clmesh::RefineAlgorithm::qm}) {
    options.algorithm = algorithm;
    const auto result = clmesh::refine_delaunay(device(), points, options);
    std::vector<Point> all = points;
    all.insert(all.end(), result.added_points.begin(), result.added_points.end());
    CHECK(!result.mesh.triangles.empty());
    MESSAGE(result.stats.remaining_bad << " bad triangles remain after " << result.stats.iterations
                                       << " iterations, " << result.added_points.size()
                                       << " Steiner points");
    long bad = 0;
    for (const auto &t : result.mesh.triangles) {
      CHECK(area(all, t) > 0);
      if (smallest_angle_degrees(all, t) < 30) {
        ++bad; // only at the apex, whose angle no refinement can mend
        CHECK((t[0] == 0 || t[1] == 0 || t[2] == 0));
      }
    }
    CHECK(bad == result.stats.remaining_bad);
  }
}

TEST_CASE("refine: the Steiner point limit (-S) is obeyed") {
  clmesh::RefineOptions options;
  options.min_angle = 30;
  options.max_steiner = 50;
  const auto result = clmesh::refine_delaunay(device(), fixtures::uniform(2000, 77), options);
  // Bad triangles remain: the limit is reached, not passed.
  CHECK(result.stats.remaining_bad > 0);
  CHECK(result.added_points.size() == 50u);
}

TEST_CASE("refine: the same mesh whatever the work-group size, grid or construction") {
  clmesh::RefineOptions options;
  options.min_angle = 30;
  auto points = fixtures::gaussian(3000, 78);
  for (std::size_t i = 0; i < 3000; i += 10) // duplicates: which copy is meshed must not matter
    points.push_back(points[i]);
  for (const auto algorithm : {clmesh::RefineAlgorithm::qmv, clmesh::RefineAlgorithm::qm}) {
    options.algorithm = algorithm;
    options.delaunay.work_group = 1;
    const auto first = clmesh::refine_delaunay(device(), points, options);
    options.delaunay.work_group = 128;
    const auto second = clmesh::refine_delaunay(device(), points, options);
    options.delaunay.work_group = clmesh::max_work_group_size(device());
    const auto largest = clmesh::refine_delaunay(device(), points, options);
    options.delaunay.work_group = 128;
    CHECK(first.mesh.triangles == second.mesh.triangles);
    CHECK(first.mesh.triangles == largest.mesh.triangles);
    REQUIRE(first.added_points.size() == second.added_points.size());
    for (std::size_t i = 0; i < first.added_points.size(); ++i)
      CHECK((first.added_points[i].x == second.added_points[i].x &&
             first.added_points[i].y == second.added_points[i].y));
    CHECK(first.stats.deleted == second.stats.deleted);
    // Nor on the Voronoi grid or the first triangulation's construction.
    options.delaunay.grid = 16;
    const auto third = clmesh::refine_delaunay(device(), points, options);
    options.delaunay.grid = 0;
    options.delaunay.voronoi_construction = false;
    const auto fourth = clmesh::refine_delaunay(device(), points, options);
    CHECK(first.mesh.stats.construction == "voronoi");
    CHECK(third.mesh.stats.construction == "voronoi");
    CHECK(fourth.mesh.stats.construction == "hull_fan");
    CHECK(first.mesh.triangles == third.mesh.triangles);
    CHECK(first.mesh.triangles == fourth.mesh.triangles);
    options.delaunay.voronoi_construction = true;
    // Nor on whether flip-flop passes run in one work-group or as separate kernels.
    options.group_pass_limit = 0;
    const auto by_kernels = clmesh::refine_delaunay(device(), points, options);
    options.group_pass_limit = std::size_t{1} << 30;
    const auto in_group = clmesh::refine_delaunay(device(), points, options);
    options.group_pass_limit = clmesh::RefineOptions{}.group_pass_limit;
    CHECK(first.mesh.triangles == by_kernels.mesh.triangles);
    CHECK(first.mesh.triangles == in_group.mesh.triangles);
  }
}

TEST_CASE("refine: bad options are refused") {
  clmesh::RefineOptions options;
  options.min_angle = 60;
  CHECK_THROWS_AS(clmesh::refine_delaunay(device(), fixtures::uniform(10, 79), options),
                  clmesh::UsageError);
}
