// GPU-QM: refinement of a point set's Delaunay triangulation to a minimum
// angle and a maximum area, checked exactly on every output.
#include <doctest/doctest.h>

#include "clmesh/clmesh.hpp"
#include "mesh_fixtures.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>

using clmesh::Point;
using test_support::area;
using test_support::device;
using test_support::problems;
using test_support::smallest_angle_degrees;

namespace {

// Refines, then checks: a valid triangulation whose boundary edges (hull
// edges, split at rounded midpoints) bound it and whose other edges are all
// locally Delaunay; every input point used; the bounds met everywhere.
// remaining_allowed: inputs where bad triangles may remain (nearly straight
// runs of hull points, sharp hull angles): then no more triangles than
// reported may miss the bound.
// The tuning of a refinement algorithm.
clmesh::Tuning tuning_of(clmesh::RefineAlgorithm algorithm) {
  clmesh::Tuning tuning;
  return tuning.use(algorithm);
}

// The options of -q<angle> (no angle bound for 0) and -a<max_area> (none for <= 0).
clmesh::Options refine_options(double angle, double max_area = -1,
                               const clmesh::Tuning &tuning = {}) {
  clmesh::Options options;
  options.quality = angle > 0;
  options.min_angle = angle;
  if (max_area > 0)
    options.max_area = max_area;
  options.tuning = tuning;
  return options;
}

clmesh::Mesh refine(const std::vector<Point> &points, const clmesh::Options &options) {
  return test_support::triangulate_points(points, options);
}

// The Steiner points a refined mesh holds.
long steiner_points(const clmesh::Mesh &mesh) {
  return static_cast<long>(mesh.points.size()) - mesh.input_points;
}

clmesh::Mesh refine_checked(const std::vector<Point> &input, double angle, double max_area = -1,
                            const clmesh::Tuning &tuning = {}, bool remaining_allowed = false) {
  const clmesh::Mesh result = refine(input, refine_options(angle, max_area, tuning));
  const clmesh::RefineStats &stats = result.statistics.refinement;
  const std::vector<Point> &points = result.points;
  const clmesh::Mesh &mesh = result;
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
    CHECK(stats.remaining_bad == 0);
  // Every insertion is in the mesh, or was deleted as redundant.
  CHECK(stats.inserted == stats.insertions - stats.deleted);
  CHECK(steiner_points(result) == stats.inserted);
  double worst_angle = 180, largest = 0;
  long below = 0;
  for (const auto &t : mesh.triangles) {
    const double smallest = smallest_angle_degrees(points, t);
    worst_angle = std::min(worst_angle, smallest);
    below += smallest < angle - 1e-6;
    largest = std::max(largest, area(points, t));
  }
  MESSAGE(input.size() << " points, -q" << angle << ": " << steiner_points(result)
                       << " Steiner points, smallest angle " << worst_angle);
  if (remaining_allowed)
    CHECK(below <= stats.remaining_bad);
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
      refine_checked(fixtures::uniform(4000, 71), angle, -1, tuning_of(algorithm));
      refine_checked(fixtures::gaussian(4000, 72), angle, -1, tuning_of(algorithm));
      refine_checked(fixtures::disk(4000, 73), angle, -1, tuning_of(algorithm));
    }
    refine_checked(fixtures::circle(1000, 74), 30, -1, tuning_of(algorithm));
    refine_checked(fixtures::lattice(40), 30, -1,
                   tuning_of(algorithm)); // cocircular: already 45 degrees
    // A lattice cut by an area bound: Steiner points on lattice edges and
    // cocircular with their neighbours, stars where no flop is possible.
    refine_checked(fixtures::lattice(12), 30, 0.05, tuning_of(algorithm));
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
      refine_checked(points, angle, -1, {}, true);
  }
}

TEST_CASE("refine: flip-flop deletes redundant points, GPU-QM more eagerly than GPU-QM-V") {
  // The same insertion filter for both (by priority only): only their
  // deletion rules differ.
  const auto points = fixtures::uniform(6000, 80);
  clmesh::Tuning qmv_tuning = tuning_of(clmesh::RefineAlgorithm::qmv);
  clmesh::Tuning qm_tuning = tuning_of(clmesh::RefineAlgorithm::qm);
  qm_tuning.filter_rings = qmv_tuning.filter_rings = 2;
  qm_tuning.filter_distance_rings = qmv_tuning.filter_distance_rings = 0;
  const auto qmv = refine_checked(points, 30, -1, qmv_tuning);
  const auto qm = refine_checked(points, 30, -1, qm_tuning);
  MESSAGE("GPU-QM-V: " << qmv.statistics.refinement.insertions << " insertions, "
                       << qmv.statistics.refinement.deleted
                       << " deleted; GPU-QM: " << qm.statistics.refinement.insertions
                       << " insertions, " << qm.statistics.refinement.deleted << " deleted");
  CHECK(qmv.statistics.refinement.deleted > 0);
  CHECK(qm.statistics.refinement.deleted > qmv.statistics.refinement.deleted);
  CHECK(qm.statistics.refinement.non_delaunay_flips > qmv.statistics.refinement.non_delaunay_flips);
  CHECK(qmv.statistics.refinement.delaunay_flips > 0);
  // Only a deleted point can come back.
  CHECK(qm.statistics.refinement.inserted_more_than_once <= qm.statistics.refinement.deleted);
  CHECK(qmv.statistics.refinement.inserted_more_than_once <= qmv.statistics.refinement.deleted);
  CHECK(qm.statistics.refinement.inserted_more_than_once > 0);
}

TEST_CASE("refine: an insertion filter that looks further inserts fewer points") {
  const auto points = fixtures::uniform(6000, 80);
  for (const auto algorithm : {clmesh::RefineAlgorithm::qmv, clmesh::RefineAlgorithm::qm}) {
    clmesh::Tuning tuning = tuning_of(algorithm);
    tuning.filter_rings = 2;
    const auto two = refine_checked(points, 30, -1, tuning);
    tuning.filter_rings = 3;
    const auto three = refine_checked(points, 30, -1, tuning);
    MESSAGE("two rings: " << two.statistics.refinement.inserted << " Steiner points, "
                          << two.statistics.refinement.iterations
                          << " iterations; three: " << three.statistics.refinement.inserted << ", "
                          << three.statistics.refinement.iterations);
    CHECK(three.statistics.refinement.inserted < two.statistics.refinement.inserted);
    CHECK(three.statistics.refinement.iterations > two.statistics.refinement.iterations);
  }
  clmesh::Options options = refine_options(30);
  options.tuning.filter_rings = 4;
  CHECK_THROWS_AS(refine(points, options), clmesh::OptionError);
}

TEST_CASE("refine: the filter leaves out the pairs GPU-QM-V's step 3 would break up") {
  // Without the distance test most deletions are of pairs inserted at once
  // (equal priorities on either side of a short edge, or a ring further).
  const auto points = fixtures::uniform(6000, 80);
  const auto qmv = clmesh::RefineAlgorithm::qmv;
  clmesh::Tuning tuning = tuning_of(qmv);
  tuning.filter_distance_rings = 0;
  const auto priority_only = refine_checked(points, 30, -1, tuning);
  tuning.filter_distance_rings = 1;
  const auto with_distance = refine_checked(points, 30, -1, tuning);
  MESSAGE("by priority: " << priority_only.statistics.refinement.insertions << " insertions, "
                          << priority_only.statistics.refinement.deleted
                          << " deleted; with distance: "
                          << with_distance.statistics.refinement.insertions << ", "
                          << with_distance.statistics.refinement.deleted);
  CHECK(with_distance.statistics.refinement.deleted * 5 <
        priority_only.statistics.refinement.deleted);
  CHECK(with_distance.statistics.refinement.insertions <
        priority_only.statistics.refinement.insertions);
  // No more points in the end (within half a percent).
  CHECK(with_distance.statistics.refinement.inserted * 200 <
        priority_only.statistics.refinement.inserted * 201);
  clmesh::Options options = refine_options(30);
  options.tuning.filter_distance_rings = 2;
  CHECK_THROWS_AS(refine(points, options), clmesh::OptionError);
}

TEST_CASE("refine: far better candidates do not hold GPU-QM-V's insertions back") {
  // Along a thin ring the small triangles send their candidates into the same
  // few large triangles inside it; with the filter's priority at any
  // distance they went in about one per large triangle and iteration.
  const auto points = fixtures::ring(20000, 1e-3, 81);
  const auto qmv = clmesh::RefineAlgorithm::qmv;
  clmesh::Tuning any = tuning_of(qmv);
  any.filter_near = 0;
  const auto any_distance = refine_checked(points, 20, -1, any);
  const auto near_only = refine_checked(points, 20, -1, tuning_of(qmv));
  MESSAGE("at any distance: " << any_distance.statistics.refinement.iterations << " iterations, "
                              << any_distance.statistics.refinement.inserted
                              << " points; near only: "
                              << near_only.statistics.refinement.iterations << ", "
                              << near_only.statistics.refinement.inserted);
  CHECK(near_only.statistics.refinement.iterations * 10 <
        any_distance.statistics.refinement.iterations * 9);
  // No more than 1% more points.
  CHECK(near_only.statistics.refinement.inserted * 100 <
        any_distance.statistics.refinement.inserted * 101);
  clmesh::Options options = refine_options(20);
  options.tuning.filter_near = 0.5;
  CHECK_THROWS_AS(refine(points, options), clmesh::OptionError);
}

TEST_CASE("refine: midpoints of different hull edges go in the same iteration") {
  // A square's four corners around points kept off its sides: four long hull
  // edges, halved again and again. When a better midpoint within the rings
  // kept one out, the halves along a side went in about one at a time.
  std::vector<Point> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const Point &p : fixtures::uniform(20000, 82))
    points.push_back({0.01 + 0.98 * p.x, 0.01 + 0.98 * p.y});
  for (const auto algorithm : {clmesh::RefineAlgorithm::qmv, clmesh::RefineAlgorithm::qm}) {
    clmesh::Options options = refine_options(20, -1, tuning_of(algorithm));
    options.tuning.parallel_midpoints = false;
    const auto one_by_one = refine(points, options);
    const auto parallel = refine_checked(points, 20, -1, tuning_of(algorithm));
    MESSAGE("midpoints kept out by better ones: "
            << one_by_one.statistics.refinement.iterations << " iterations, "
            << one_by_one.statistics.refinement.inserted
            << " points; in parallel: " << parallel.statistics.refinement.iterations << ", "
            << parallel.statistics.refinement.inserted);
    CHECK(parallel.statistics.refinement.iterations * 4 <
          one_by_one.statistics.refinement.iterations * 3);
    // No more points (within half a percent).
    CHECK(parallel.statistics.refinement.inserted * 200 <
          one_by_one.statistics.refinement.inserted * 201);
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
    clmesh::Tuning tuning = tuning_of(qmv);
    tuning.election_rings = 0;
    const auto all = refine_checked(points, angle, -1, tuning);
    tuning.election_rings = 1;
    const auto one_ring = refine_checked(points, angle, -1, tuning);
    const auto two_rings = refine_checked(points, angle, -1, tuning_of(qmv));
    MESSAGE("candidates, iterations, points: every bad triangle "
            << all.statistics.refinement.candidates << ", " << all.statistics.refinement.iterations
            << ", " << all.statistics.refinement.inserted << "; elected in one ring "
            << one_ring.statistics.refinement.candidates << ", "
            << one_ring.statistics.refinement.iterations << ", "
            << one_ring.statistics.refinement.inserted << "; in two "
            << two_rings.statistics.refinement.candidates << ", "
            << two_rings.statistics.refinement.iterations << ", "
            << two_rings.statistics.refinement.inserted);
    CHECK(one_ring.statistics.refinement.candidates < all.statistics.refinement.candidates);
    CHECK(two_rings.statistics.refinement.candidates < one_ring.statistics.refinement.candidates);
    CHECK(two_rings.statistics.refinement.candidates * 3 <
          all.statistics.refinement.candidates * 2);
    // At most a third more iterations, and 1.5% more points.
    CHECK(two_rings.statistics.refinement.iterations * 3 <=
          all.statistics.refinement.iterations * 4);
    CHECK(two_rings.statistics.refinement.inserted * 200 <
          all.statistics.refinement.inserted * 203);
  }
  clmesh::Options options = refine_options(30);
  options.tuning.election_rings = 3;
  CHECK_THROWS_AS(refine(points, options), clmesh::OptionError);
}

TEST_CASE("refine: maximum area, alone and with an angle") {
  refine_checked(fixtures::uniform(500, 75), 0, 1e-3);
  refine_checked(fixtures::uniform(500, 76), 28, 2e-4);
}

TEST_CASE("refine: with -a the first room holds the points the area bound asks for") {
  // About 40 times the input in Steiner points, all in the first room (sized
  // from the hull's area over the bound): no growth.
  const auto result = refine_checked(fixtures::uniform(300, 77), 25, 4e-5);
  CHECK(result.statistics.refinement.growths == 0);
  CHECK(steiner_points(result) > 10000);
}

TEST_CASE("refine: small angles of the hull end the refinement, never a hang") {
  // A thin wedge: the hull angle at the apex is about 3 degrees.
  std::vector<Point> points = {{0, 0}, {10, 0.25}, {10, -0.25}};
  for (int i = 1; i < 40; ++i)
    points.push_back({i * 0.25, 0});
  for (const auto algorithm : {clmesh::RefineAlgorithm::qmv, clmesh::RefineAlgorithm::qm}) {
    const auto result = refine(points, refine_options(30, -1, tuning_of(algorithm)));
    const std::vector<Point> &all = result.points;
    CHECK(!result.triangles.empty());
    MESSAGE(result.statistics.refinement.remaining_bad
            << " bad triangles remain after " << result.statistics.refinement.iterations
            << " iterations, " << steiner_points(result) << " Steiner points");
    long bad = 0;
    for (const auto &t : result.triangles) {
      CHECK(area(all, t) > 0);
      if (smallest_angle_degrees(all, t) < 30) {
        ++bad; // only at the apex, whose angle no refinement can mend
        CHECK((t[0] == 0 || t[1] == 0 || t[2] == 0));
      }
    }
    CHECK(bad == result.statistics.refinement.remaining_bad);
  }
}

TEST_CASE("refine: points a hair from collinear along the hull end the refinement") {
  // Points on a slanted line, rounded to doubles, and one below: the hull
  // passes a hair from most of them, and the triangles between are flat.
  // Refinement once split them until its iteration limit; they are left.
  std::vector<Point> points;
  for (int k = 0; k < 60; ++k)
    points.push_back({k / 60.0, k / 60.0 * 3.14159265358979323846 / 3});
  points.push_back({0.5, -1});
  for (const auto algorithm : {clmesh::RefineAlgorithm::qmv, clmesh::RefineAlgorithm::qm}) {
    const auto result = refine_checked(points, 30, -1, tuning_of(algorithm), true);
    const clmesh::RefineStats &stats = result.statistics.refinement;
    CHECK(stats.stop_reason == clmesh::RefineStop::done);
    CHECK(stats.remaining_bad > 0);
    CHECK(stats.iterations < 100);
  }
}

TEST_CASE("refine: the Steiner point limit (-S) is obeyed") {
  clmesh::Options options = clmesh::parse_switches("q30S50");
  // The steps of an iteration in one work-group each or as separate kernels.
  for (const std::size_t limit : {std::size_t{0}, std::size_t{1} << 30}) {
    CAPTURE(limit);
    options.tuning.group_step_limit = limit;
    const auto result = refine(fixtures::uniform(2000, 77), options);
    // Bad triangles remain: the limit is reached, not passed.
    CHECK(result.statistics.refinement.remaining_bad > 0);
    CHECK(steiner_points(result) == 50);
  }
}

TEST_CASE("refine: the same mesh whatever the work-group size, grid or construction") {
  clmesh::Options options = refine_options(30);
  clmesh::Tuning &tuning = options.tuning;
  auto points = fixtures::gaussian(3000, 78);
  for (std::size_t i = 0; i < 3000; i += 10) // duplicates: which copy is meshed must not matter
    points.push_back(points[i]);
  // The same triangles over the same points, coordinate for coordinate.
  const auto check_same = [](const clmesh::Mesh &first, const clmesh::Mesh &other) {
    CHECK(first.triangles == other.triangles);
    REQUIRE(first.points.size() == other.points.size());
    for (std::size_t i = 0; i < first.points.size(); ++i)
      CHECK((first.points[i].x == other.points[i].x && first.points[i].y == other.points[i].y));
  };
  for (const auto algorithm : {clmesh::RefineAlgorithm::qmv, clmesh::RefineAlgorithm::qm}) {
    tuning.use(algorithm);
    tuning.work_group = 1;
    const auto first = refine(points, options);
    tuning.work_group = 128;
    const auto second = refine(points, options);
    tuning.work_group = clmesh::max_work_group_size(device());
    const auto largest = refine(points, options);
    tuning.work_group = 128;
    check_same(first, second);
    CHECK(first.triangles == largest.triangles);
    CHECK(first.statistics.refinement.deleted == second.statistics.refinement.deleted);
    // Nor on the Voronoi grid or the first triangulation's construction.
    tuning.grid = 16;
    const auto third = refine(points, options);
    tuning.grid.reset();
    tuning.construction = clmesh::Construction::fan;
    const auto fourth = refine(points, options);
    CHECK(first.statistics.delaunay.construction == "voronoi");
    CHECK(third.statistics.delaunay.construction == "voronoi");
    CHECK(fourth.statistics.delaunay.construction == "hull_fan");
    CHECK(first.triangles == third.triangles);
    CHECK(first.triangles == fourth.triangles);
    tuning.construction = clmesh::Construction::automatic;
    // Nor on whether flip-flop passes run in one work-group or as separate kernels.
    tuning.group_pass_limit = 0;
    const auto by_kernels = refine(points, options);
    tuning.group_pass_limit = std::size_t{1} << 30;
    const auto in_group = refine(points, options);
    tuning.group_pass_limit = clmesh::Tuning{}.group_pass_limit;
    CHECK(first.triangles == by_kernels.triangles);
    CHECK(first.triangles == in_group.triangles);
    // Nor on whether the search for bad triangles and the placement of the
    // candidates run in one work-group or as separate kernels.
    tuning.group_step_limit = 0;
    const auto steps_by_kernels = refine(points, options);
    tuning.group_step_limit = std::size_t{1} << 30;
    const auto steps_in_group = refine(points, options);
    tuning.group_step_limit = clmesh::Tuning{}.group_step_limit;
    for (const auto *other : {&steps_by_kernels, &steps_in_group}) {
      check_same(first, *other);
      CHECK(first.statistics.refinement.iterations == other->statistics.refinement.iterations);
    }
    // Nor on whether a search keeps the verdicts of unchanged bad triangles.
    tuning.carry_verdicts = false;
    check_same(first, refine(points, options));
    tuning.carry_verdicts = true;
    // Nor on whether the search after a later move into Z-order examines the
    // flagged triangles alone or every slot.
    tuning.search_flagged_after_move = false;
    check_same(first, refine(points, options));
    tuning.search_flagged_after_move = true;
    // Nor on whether the kernels prefetch (on PoCL's CPU devices: from the
    // start, or never).
    for (const std::size_t from : {std::size_t{0}, std::size_t{1} << 40}) {
      tuning.prefetch_from = from;
      check_same(first, refine(points, options));
    }
    tuning.prefetch_from = clmesh::Tuning{}.prefetch_from;
  }
}

TEST_CASE("refine: bad options are refused") {
  CHECK_THROWS_AS(refine(fixtures::uniform(10, 79), refine_options(60)), clmesh::OptionError);
  CHECK_THROWS_AS(refine(fixtures::uniform(10, 79), clmesh::parse_switches("q30a0")),
                  clmesh::OptionError);
  CHECK_THROWS_AS(clmesh::parse_switches("q30u"), clmesh::OptionError);
  CHECK_THROWS_AS(clmesh::parse_switches("qx"), clmesh::OptionError);
  clmesh::Options pslg_quality = clmesh::parse_switches("pq");
  CHECK_NOTHROW(clmesh::validate(pslg_quality));
  CHECK_NOTHROW(clmesh::validate(clmesh::parse_switches("pqAa")));
  CHECK_THROWS_AS(clmesh::validate(clmesh::parse_switches("qa")), clmesh::OptionError);
}

TEST_CASE("refine: an area bound the device cannot hold is refused before any work") {
  const std::vector<Point> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  try {
    refine(square, clmesh::parse_switches("a1e-30"));
    FAIL("-a1e-30 on a unit square was not refused");
  } catch (const clmesh::OptionError &error) {
    const std::string message = error.what();
    INFO(message);
    CHECK(message.find("-a1e-30") != std::string::npos);
    CHECK(message.find("~5e29 points") != std::string::npos);
    CHECK(message.find("(area 1)") != std::string::npos);
    CHECK(message.find("memory holds") != std::string::npos);
  }
  CHECK_THROWS_AS(refine(square, clmesh::parse_switches("q30a1e-9")), clmesh::OptionError);
  // -S stops the refinement well before the device is full: it runs, and
  // says the Steiner point limit stopped it.
  const clmesh::Mesh capped = refine(square, clmesh::parse_switches("a1e-9S100"));
  const clmesh::RefineStats &stats = capped.statistics.refinement;
  CHECK(steiner_points(capped) == 100);
  CHECK(stats.stop_reason == clmesh::RefineStop::steiner_limit);
  CHECK(stats.remaining_bad > 0);
  CHECK(stats.area_bound_points == doctest::Approx(5e8));
  CHECK(std::string(clmesh::stop_reason_name(stats.stop_reason)) == "steiner_limit");
  // A bound within reach: refined to the end.
  const clmesh::Mesh done = refine(square, clmesh::parse_switches("a0.01"));
  CHECK(done.statistics.refinement.stop_reason == clmesh::RefineStop::done);
  CHECK(done.statistics.refinement.area_bound_points == doctest::Approx(50));
}
