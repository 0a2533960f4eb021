// triangulate_many(): many inputs on one device give, input by input, the
// meshes of separate triangulate() calls, and a bad input its own error while
// the others are meshed; without a device, on the shared one.
#include <doctest/doctest.h>

#include "api/shared_device.hpp"
#include "clmesh/clmesh.hpp"
#include "mesh_fixtures.hpp"
#include "test_support.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using test_support::check_same_mesh;
using test_support::device;

namespace {

clmesh::Input points_input(std::vector<clmesh::Point> points) {
  clmesh::Input input;
  input.points = std::move(points);
  return input;
}

// A unit square with a square hole, as a PSLG.
clmesh::Input square_with_hole() {
  clmesh::Input input;
  input.points = {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {1, 1}, {3, 1}, {3, 3}, {1, 3}, {0.5, 2.5}};
  for (int32_t i = 0; i < 4; ++i) {
    input.segments.push_back({i, (i + 1) % 4, 1});
    input.segments.push_back({4 + i, 4 + (i + 1) % 4, 2});
  }
  input.holes = {{2, 2}};
  return input;
}

bool same_edges(const std::vector<clmesh::Edge> &a, const std::vector<clmesh::Edge> &b) {
  if (a.size() != b.size())
    return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].a != b[i].a || a[i].b != b[i].b || a[i].marker != b[i].marker)
      return false;
  return true;
}

// The message of the InputError `result` carries ("" when it carries none).
std::string input_error(const clmesh::BatchResult &result) {
  try {
    if (result.error)
      std::rethrow_exception(result.error);
  } catch (const clmesh::InputError &error) {
    return error.what();
  }
  return "";
}

} // namespace

TEST_CASE("batch: each input's mesh is that of its own triangulate() call") {
  const std::vector<clmesh::Input> inputs = {
      points_input(fixtures::uniform(500, 1)), points_input(fixtures::lattice(12)),
      points_input(fixtures::gaussian(300, 7)), points_input(fixtures::uniform(40, 3))};
  for (const std::string switches : {"zen", "q30", "q25a0.01"}) {
    CAPTURE(switches);
    const std::vector<clmesh::BatchResult> results =
        clmesh::triangulate_many(device(), inputs, switches);
    REQUIRE(results.size() == inputs.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      CAPTURE(i);
      REQUIRE(results[i].ok());
      CHECK(results[i].message.empty());
      CHECK(!results[i].mesh.triangles.empty());
      const clmesh::Mesh alone = clmesh::triangulate(device(), inputs[i], switches);
      check_same_mesh(results[i].mesh, alone);
      CHECK(same_edges(results[i].mesh.edges, alone.edges));
    }
  }
  const std::vector<clmesh::Input> pslgs = {square_with_hole(), square_with_hole()};
  const std::vector<clmesh::BatchResult> refined =
      clmesh::triangulate_many(device(), pslgs, "pq30");
  REQUIRE(refined.size() == 2);
  REQUIRE(refined[0].ok());
  REQUIRE(refined[1].ok());
  check_same_mesh(refined[0].mesh, clmesh::triangulate(device(), pslgs[0], "pq30"));
  check_same_mesh(refined[1].mesh, refined[0].mesh);
}

TEST_CASE("batch: small point sets are packed, each mesh that of its own triangulate() call") {
  // Degenerate sets among them: cocircular lattices, duplicates, a thin ring,
  // collinear runs inside a hull, three points. A collinear set (no triangle)
  // and one larger than a pack takes are meshed alone, between packs.
  std::vector<clmesh::Point> duplicates = fixtures::uniform(700, 11);
  const std::vector<clmesh::Point> copy = duplicates;
  duplicates.insert(duplicates.end(), copy.begin(), copy.end());
  std::vector<clmesh::Point> collinear_run = fixtures::lattice(3, 1, {-1, -1});
  for (int i = 0; i < 50; ++i)
    collinear_run.push_back({-0.5 + i / 50.0, 0.25});
  std::vector<clmesh::Point> line;
  for (int i = 0; i < 20; ++i)
    line.push_back({i * 0.5, i * 0.25});
  // Sets far apart in scale share a pack: nothing of one reaches another.
  std::vector<clmesh::Point> huge = fixtures::uniform(900, 5), tiny = fixtures::disk(900, 6);
  for (clmesh::Point &p : huge)
    p = {p.x * 1e30 - 3e29, p.y * 1e30};
  for (clmesh::Point &p : tiny)
    p = {p.x * 1e-30, p.y * 1e-30 + 1e-31};
  const std::vector<clmesh::Input> inputs = {points_input(fixtures::uniform(2000, 1)),
                                             points_input(fixtures::lattice(25)),
                                             points_input(duplicates),
                                             points_input(fixtures::ring(3000, 1e-3, 2)),
                                             points_input({{0, 0}, {1, 0}, {0, 1}}),
                                             points_input(line),
                                             points_input(collinear_run),
                                             points_input(fixtures::lattice(17, 0.125, {3, 5})),
                                             points_input(fixtures::gaussian(1500, 4)),
                                             points_input(huge),
                                             points_input(tiny),
                                             points_input(fixtures::uniform(70000, 3))};
  // A pack of one input is meshed alone.
  const std::vector<bool> packed = {true, true, true, true, true, false,
                                    true, true, true, true, true, false};
  for (const std::string switches : {"z", "ven"}) {
    CAPTURE(switches);
    clmesh::Options options = clmesh::parse_switches(switches);
    options.tuning.packing = clmesh::Packing::always; // on PoCL's CPU device too
    const std::vector<clmesh::BatchResult> results =
        clmesh::triangulate_many(device(), inputs, options);
    REQUIRE(results.size() == inputs.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      CAPTURE(i);
      REQUIRE(results[i].ok());
      const clmesh::Mesh alone = clmesh::triangulate(device(), inputs[i], switches);
      check_same_mesh(results[i].mesh, alone);
      CHECK(same_edges(results[i].mesh.edges, alone.edges));
      CHECK(results[i].mesh.voronoi_points.size() == alone.voronoi_points.size());
      CHECK(test_support::starts_with(results[i].mesh.voronoi_points, alone.voronoi_points));
      CHECK((results[i].mesh.statistics.delaunay.construction == "packed") == packed[i]);
      CHECK(results[i].mesh.statistics.delaunay.triangles ==
            static_cast<long>(alone.triangles.size()));
      CHECK(results[i].mesh.statistics.delaunay.duplicates == alone.statistics.delaunay.duplicates);
    }
  }
}

TEST_CASE("batch: a bad input gets its error, the others their meshes") {
  clmesh::Input two_points = points_input({{0, 0}, {1, 0}});
  two_points.source = "two.node";
  clmesh::Input not_finite = points_input(fixtures::uniform(20, 5));
  not_finite.points[7].x = std::numeric_limits<double>::quiet_NaN();
  const std::vector<clmesh::Input> inputs = {points_input(fixtures::uniform(200, 2)), two_points,
                                             points_input(fixtures::lattice(6)), not_finite};
  const std::vector<clmesh::BatchResult> results = clmesh::triangulate_many(device(), inputs, "e");
  REQUIRE(results.size() == 4);
  for (std::size_t i : {0, 2}) {
    REQUIRE(results[i].ok());
    check_same_mesh(results[i].mesh, clmesh::triangulate(device(), inputs[i], "e"));
  }
  for (std::size_t i : {1, 3}) {
    CAPTURE(i);
    CHECK(!results[i].ok());
    CHECK(results[i].mesh.triangles.empty());
    CHECK(results[i].mesh.points.empty());
    // The error is the one triangulate() throws for that input alone.
    std::string alone;
    try {
      clmesh::triangulate(device(), inputs[i], "e");
    } catch (const clmesh::InputError &error) {
      alone = error.what();
    }
    CHECK(!alone.empty());
    CHECK(input_error(results[i]) == alone);
    CHECK(results[i].message == alone);
  }
  CHECK(results[1].message.find("two.node") != std::string::npos);
}

TEST_CASE("batch: the streaming form takes inputs and hands results in order") {
  std::vector<std::size_t> asked, handed;
  std::vector<clmesh::BatchResult> results(3);
  const clmesh::Options options = clmesh::parse_switches("z");
  clmesh::triangulate_many(
      device(), 3,
      [&](std::size_t i) -> clmesh::Input {
        asked.push_back(i);
        if (i == 1)
          throw clmesh::InputError("unreadable.node", 0, "cannot open");
        return points_input(fixtures::uniform(100, static_cast<unsigned>(10 + i)));
      },
      options,
      [&](std::size_t i, clmesh::BatchResult &&result) {
        handed.push_back(i);
        results[i] = std::move(result);
      });
  CHECK(asked == std::vector<std::size_t>{0, 1, 2});
  CHECK(handed == std::vector<std::size_t>{0, 1, 2});
  CHECK(results[0].ok());
  CHECK(results[2].ok());
  check_same_mesh(results[2].mesh,
                  clmesh::triangulate(device(), points_input(fixtures::uniform(100, 12)), options));
  CHECK(input_error(results[1]) == "unreadable.node: cannot open");
}

TEST_CASE("batch: invalid options are the whole batch's error, thrown before meshing") {
  clmesh::Options options;
  options.regional_areas = true; // -a alone needs -p
  std::size_t asked = 0;
  CHECK_THROWS_AS(clmesh::triangulate_many(
                      device(), 2,
                      [&](std::size_t) {
                        ++asked;
                        return points_input(fixtures::uniform(10, 1));
                      },
                      options, [](std::size_t, clmesh::BatchResult &&) {}),
                  clmesh::OptionError);
  CHECK(asked == 0);
  CHECK_THROWS_AS(
      clmesh::triangulate_many(device(), {points_input(fixtures::uniform(10, 1))}, "qx"),
      clmesh::OptionError);
}

TEST_CASE("batch: without a device, on the shared device of triangulate(input, options)") {
  clmesh::Input not_finite = points_input(fixtures::uniform(30, 4));
  not_finite.points[3].y = std::numeric_limits<double>::infinity();
  const std::vector<clmesh::Input> inputs = {points_input(fixtures::uniform(300, 8)), not_finite,
                                             square_with_hole()};
  clmesh::Options options = clmesh::parse_switches("q30e");
  const std::vector<clmesh::BatchResult> results = clmesh::triangulate_many(inputs, options);
  REQUIRE(results.size() == 3);
  for (std::size_t i : {0, 2}) {
    CAPTURE(i);
    REQUIRE(results[i].ok());
    const clmesh::Mesh alone = clmesh::triangulate(inputs[i], options);
    check_same_mesh(results[i].mesh, alone);
    CHECK(same_edges(results[i].mesh.edges, alone.edges));
  }
  CHECK(!input_error(results[1]).empty());

  // The streaming form holds each input's device until done() returns (on
  // one stream: streams are the batch's own, the device stays free).
  options.tuning.streams = 1;
  const std::shared_ptr<clmesh::SharedDevice> shared =
      clmesh::shared_device_for(inputs[0], options, clmesh::Meshing::batch);
  REQUIRE(shared == clmesh::shared_device_for(inputs[2], options, clmesh::Meshing::batch));
  std::vector<bool> free_while_meshing;
  clmesh::triangulate_many(
      2, [&](std::size_t i) { return inputs[2 * i]; }, options, // the two good ones
      [&](std::size_t, clmesh::BatchResult &&result) {
        CHECK(result.ok());
        const bool free = shared->busy.try_lock();
        if (free)
          shared->busy.unlock();
        free_while_meshing.push_back(free);
      });
  CHECK(free_while_meshing == std::vector<bool>{false, false});
  REQUIRE(shared->busy.try_lock());
  shared->busy.unlock();

  std::size_t asked = 0;
  const auto count_asked = [&](std::size_t i) {
    ++asked;
    return inputs[i];
  };
  options.device = "no such device anywhere";
  CHECK_THROWS_AS(
      clmesh::triangulate_many(1, count_asked, options, [](std::size_t, clmesh::BatchResult &&) {}),
      clmesh::DeviceError);
  options = clmesh::parse_switches("a");
  CHECK_THROWS_AS(clmesh::triangulate_many(inputs, options), clmesh::OptionError);
  CHECK_THROWS_AS(
      clmesh::triangulate_many(1, count_asked, options, [](std::size_t, clmesh::BatchResult &&) {}),
      clmesh::OptionError);
  CHECK(asked == 0);
}

TEST_CASE("streams: threads meshing at once, each on a stream of one device, get the meshes "
          "of one thread") {
  std::vector<clmesh::Input> inputs;
  for (unsigned seed = 1; seed <= 8; ++seed)
    inputs.push_back(points_input(fixtures::uniform(400 + 50 * seed, seed)));
  inputs.push_back(square_with_hole());
  const std::vector<std::string> switches = {"pq30", "q25", "zen", "pq30a0.05"};
  std::vector<clmesh::Mesh> alone;
  for (std::size_t i = 0; i < inputs.size(); ++i)
    alone.push_back(clmesh::triangulate(device(), inputs[i], switches[i % switches.size()]));
  constexpr unsigned kThreads = 3;
  if (clmesh::describe(device()).rfind("basic", 0) == 0) { // PoCL's in-thread driver
    CHECK_THROWS_AS(clmesh::open_stream(device()), clmesh::DeviceError);
    return;
  }
  std::vector<std::shared_ptr<clmesh::Device>> streams;
  for (unsigned t = 0; t < kThreads; ++t)
    streams.push_back(clmesh::open_stream(device()));
  std::vector<clmesh::Mesh> meshed(inputs.size());
  std::vector<std::string> errors(kThreads);
  std::vector<std::thread> threads;
  for (unsigned t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      try {
        for (int round = 0; round < 3; ++round)
          for (std::size_t i = t; i < inputs.size(); i += kThreads)
            meshed[i] = clmesh::triangulate(*streams[t], inputs[i], switches[i % switches.size()]);
      } catch (const std::exception &error) {
        errors[t] = error.what();
      }
    });
  for (std::thread &thread : threads)
    thread.join();
  for (unsigned t = 0; t < kThreads; ++t)
    CHECK(errors[t] == "");
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    CAPTURE(i);
    check_same_mesh(meshed[i], alone[i]);
  }
}

TEST_CASE("batch: on streams, inputs meshed at once come back in order, each mesh and error "
          "that of its own call, packs between them") {
  if (!test_support::device_takes_streams())
    return; // PoCL's in-thread driver: one stream (the test above checks its refusal)
  // Point sets that pack (plain Delaunay, with Packing::always) between
  // inputs that do not (PSLGs), a bad one among the streamed ones.
  clmesh::Input bad = square_with_hole();
  bad.segments.push_back({0, 42, 0});
  std::vector<clmesh::Input> inputs;
  for (unsigned seed = 1; seed <= 5; ++seed)
    inputs.push_back(points_input(fixtures::uniform(300 + 40 * seed, seed)));
  inputs.push_back(square_with_hole());
  inputs.push_back(points_input(fixtures::uniform(500, 9)));
  inputs.push_back(bad);
  for (unsigned seed = 11; seed <= 14; ++seed)
    inputs.push_back(points_input(fixtures::gaussian(200 + 30 * seed, seed)));
  for (const std::string switches : {"q30", "z"}) {
    CAPTURE(switches);
    clmesh::Options options = clmesh::parse_switches(switches);
    options.tuning.streams = 3;
    options.tuning.packing = clmesh::Packing::always;
    std::vector<std::size_t> handed;
    std::vector<clmesh::BatchResult> results(inputs.size());
    clmesh::triangulate_many(
        device(), inputs.size(), [&](std::size_t i) { return inputs[i]; }, options,
        [&](std::size_t i, clmesh::BatchResult &&result) {
          handed.push_back(i);
          results[i] = std::move(result);
        });
    REQUIRE(handed.size() == inputs.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      CAPTURE(i);
      CHECK(handed[i] == i);
      if (i == 7) {
        CHECK(!results[i].ok());
        CHECK(results[i].message.find("segment") != std::string::npos);
        continue;
      }
      REQUIRE(results[i].ok());
      check_same_mesh(results[i].mesh, clmesh::triangulate(device(), inputs[i], options));
    }
  }
  // What done() throws ends the batch, with inputs still being meshed.
  clmesh::Options options = clmesh::parse_switches("q30");
  options.tuning.streams = 4;
  std::size_t handed = 0;
  CHECK_THROWS_AS(clmesh::triangulate_many(
                      device(), inputs.size(), [&](std::size_t i) { return inputs[i]; }, options,
                      [&](std::size_t i, clmesh::BatchResult &&) {
                        ++handed;
                        if (i == 2)
                          throw std::runtime_error("enough");
                      }),
                  std::runtime_error);
  CHECK(handed == 3);
}
