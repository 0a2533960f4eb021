// The public API (clmesh/clmesh.hpp): Triangle's switches as Options, the
// validation of options and input, triangulate() and every field of the Mesh
// it returns, the quality statistics, the statistics JSON and the -C check.
// Meshes are checked with clmesh's exact checker (CGAL comparisons are in
// test_delaunay.cpp and test_cdt.cpp).
#include <doctest/doctest.h>

#include "clmesh/clmesh.hpp"
#include "mesh_fixtures.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

using clmesh::Point;
using clmesh::Segment;
using test_support::check_same_mesh;
using test_support::device;
using test_support::problems;
using test_support::starts_with;
using test_support::triangulate_points;

namespace {

// The message of the `Error` that call() throws ("" when it throws none; other
// exceptions go on).
template <class Error, class Call> std::string error_of(const Call &call) {
  try {
    call();
  } catch (const Error &error) {
    return error.what();
  }
  return "";
}

// The message of the OptionError that parsing `switches` throws.
std::string option_error(const std::string &switches) {
  return error_of<clmesh::OptionError>([&] { clmesh::parse_switches(switches); });
}

// The message of the OptionError that validate(options) throws.
std::string validation_error(const clmesh::Options &options) {
  return error_of<clmesh::OptionError>([&] { clmesh::validate(options); });
}

// The message of the InputError that validate(input) throws.
std::string input_error(const clmesh::Input &input) {
  return error_of<clmesh::InputError>([&] { clmesh::validate(input); });
}

bool contains(const std::string &text, const std::string &part) {
  return text.find(part) != std::string::npos;
}

// The switches that are one flag each, with their fields.
const std::vector<std::pair<char, bool clmesh::Options::*>> kFlags = {
    {'p', &clmesh::Options::pslg},
    {'r', &clmesh::Options::refine},
    {'c', &clmesh::Options::convex_hull},
    {'O', &clmesh::Options::ignore_holes},
    {'A', &clmesh::Options::regional_attributes},
    {'B', &clmesh::Options::no_boundary_markers},
    {'z', &clmesh::Options::zero_based},
    {'e', &clmesh::Options::edges},
    {'n', &clmesh::Options::neighbors},
    {'N', &clmesh::Options::no_node_file},
    {'E', &clmesh::Options::no_ele_file},
    {'I', &clmesh::Options::no_iteration_number},
    {'j', &clmesh::Options::jettison},
    {'Q', &clmesh::Options::quiet},
    {'C', &clmesh::Options::check},
    {'P', &clmesh::Options::no_poly_file},
    {'g', &clmesh::Options::off_file},
    {'v', &clmesh::Options::voronoi},
    {'h', &clmesh::Options::help},
    {'q', &clmesh::Options::quality}};

// How many of the flags (and -V, -a, -S) an Options sets.
int fields_set(const clmesh::Options &options) {
  int set = 0;
  for (const auto &[letter, field] : kFlags)
    set += options.*field;
  return set + (options.verbose != 0) + options.max_area.has_value() +
         options.max_steiner.has_value() + options.second_order +
         !options.no_effect_switches.empty();
}

using Edge = std::pair<int32_t, int32_t>; // (smaller, larger) vertex index

Edge edge(int32_t a, int32_t b) { return {std::min(a, b), std::max(a, b)}; }

// Every edge of the mesh's triangles, undirected.
std::set<Edge> triangle_edges(const clmesh::Mesh &mesh) {
  std::set<Edge> edges;
  for (const auto &t : mesh.triangles)
    for (int i = 0; i < 3; ++i)
      edges.insert(edge(t[i], t[(i + 1) % 3]));
  return edges;
}

// The unit square with both diagonals as segments (crossing at its centre),
// sides marked side_marker and diagonals diagonal_marker.
clmesh::Input square_with_diagonals(int side_marker = 0, int diagonal_marker = 0) {
  clmesh::Input input;
  input.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  input.segments = {{0, 1, side_marker}, {1, 2, side_marker},     {2, 3, side_marker},
                    {3, 0, side_marker}, {0, 2, diagonal_marker}, {1, 3, diagonal_marker}};
  return input;
}

} // namespace

TEST_CASE("api: parse_switches sets the field of every supported letter") {
  const clmesh::Options defaults;
  CHECK(fields_set(defaults) == 0);
  CHECK(defaults.min_angle == 20);
  // Each flag alone sets its field and no other.
  for (const auto &[letter, field] : kFlags) {
    INFO("switch -" << letter);
    const clmesh::Options options = clmesh::parse_switches(std::string(1, letter));
    CHECK(options.*field);
    CHECK(fields_set(options) == 1);
  }
  const clmesh::Options all = clmesh::parse_switches("prcOABzenNEIjQVCPgv");
  for (const auto &[letter, field] : kFlags) {
    INFO("switch -" << letter);
    CHECK(all.*field == (letter != 'h' && letter != 'q'));
  }
  CHECK(all.verbose == 1);
  CHECK_FALSE(all.max_area);
  CHECK_FALSE(all.max_steiner);
  CHECK(clmesh::parse_switches("VVV").verbose == 3);

  SUBCASE("-q, with and without an angle") {
    const clmesh::Options q = clmesh::parse_switches("q");
    CHECK(q.quality);
    CHECK(q.min_angle == 20);
    const clmesh::Options q32 = clmesh::parse_switches("q32.5");
    CHECK(q32.quality);
    CHECK(q32.min_angle == 32.5);
    CHECK_FALSE(q32.max_area);
    CHECK(clmesh::parse_switches("q0").min_angle == 0);
  }
  SUBCASE("-a with a number") {
    const clmesh::Options a = clmesh::parse_switches("a0.25");
    REQUIRE(a.max_area);
    CHECK(*a.max_area == 0.25);
    CHECK_FALSE(a.quality);
    const clmesh::Options exponent = clmesh::parse_switches("a1e-3");
    REQUIRE(exponent.max_area);
    CHECK(*exponent.max_area == 1e-3);
    CHECK(fields_set(exponent) == 1);
  }
  SUBCASE("-o2, and -o without its order") {
    const clmesh::Options o2 = clmesh::parse_switches("o2");
    CHECK(o2.second_order);
    CHECK(fields_set(o2) == 1);
    const clmesh::Options with_edges = clmesh::parse_switches("po2e");
    CHECK(with_edges.second_order);
    CHECK(with_edges.pslg);
    CHECK(with_edges.edges);
    CHECK(fields_set(with_edges) == 3);
    for (const std::string bad : {"o", "o3", "po1e"}) {
      INFO(bad);
      CHECK_THROWS_AS(clmesh::parse_switches(bad), clmesh::OptionError);
    }
  }
  SUBCASE("-X -i -F -l -s: accepted, recorded, nothing else set") {
    const clmesh::Options options = clmesh::parse_switches("XiFlsX");
    CHECK(options.no_effect_switches == "XiFls");
    CHECK(fields_set(options) == 1);
    CHECK(clmesh::parse_switches("pX").no_effect_switches == "X");
  }
  SUBCASE("-S, with and without a number") {
    const clmesh::Options s = clmesh::parse_switches("S");
    REQUIRE(s.max_steiner);
    CHECK(*s.max_steiner == 0);
    const clmesh::Options s100 = clmesh::parse_switches("S100");
    REQUIRE(s100.max_steiner);
    CHECK(*s100.max_steiner == 100);
    CHECK(fields_set(s100) == 1);
  }
  SUBCASE("numbers followed by more letters, a leading '-'") {
    const clmesh::Options options = clmesh::parse_switches("-q30a0.1S7pe");
    CHECK(options.quality);
    CHECK(options.min_angle == 30);
    REQUIRE(options.max_area);
    CHECK(*options.max_area == 0.1);
    REQUIRE(options.max_steiner);
    CHECK(*options.max_steiner == 7);
    CHECK(options.pslg);
    CHECK(options.edges);
    CHECK(fields_set(options) == 5);
    // 'e' after a number without digits after it is -e, not an exponent.
    const clmesh::Options area_edges = clmesh::parse_switches("a2e");
    REQUIRE(area_edges.max_area);
    CHECK(*area_edges.max_area == 2);
    CHECK(area_edges.edges);
    CHECK(clmesh::parse_switches("-p").pslg);
  }
  SUBCASE("several calls accumulate") {
    clmesh::Options options;
    clmesh::parse_switches("-pV", options);
    clmesh::parse_switches("cV", options);
    clmesh::parse_switches("q25", options);
    CHECK(options.pslg);
    CHECK(options.convex_hull);
    CHECK(options.verbose == 2);
    CHECK(options.quality);
    CHECK(options.min_angle == 25);
    CHECK(fields_set(options) == 4);
    // A later angle replaces an earlier one.
    clmesh::parse_switches("q33", options);
    CHECK(options.min_angle == 33);
  }
}

TEST_CASE("api: parse_switches refuses Triangle's switches clmesh lacks, unknown letters and "
          "malformed numbers") {
  for (const char letter : std::string("u")) {
    INFO("switch -" << letter);
    const std::string alone = option_error(std::string(1, letter));
    CHECK(contains(alone, std::string("switch -") + letter + " ("));
    CHECK(contains(alone, "not supported"));
    // Also among supported ones.
    CHECK(contains(option_error(std::string("pz") + letter + "e"),
                   std::string("switch -") + letter + " ("));
  }
  for (const std::string switches : {"a", "pa", "aq", "pqa0.5a"}) {
    INFO(switches);
    CHECK(option_error(switches) == "");
    CHECK(clmesh::parse_switches(switches).regional_areas);
  }
  CHECK(contains(validation_error(clmesh::parse_switches("qa")), "needs -p or -r"));
  CHECK(validation_error(clmesh::parse_switches("rqa")) == "");
  const std::string unknown = option_error("pxq");
  CHECK(contains(unknown, "unknown switch -x"));
  CHECK(contains(option_error("K"), "unknown switch -K"));
  // An unknown letter is named even after an unsupported one.
  CHECK(contains(option_error("rx"), "unknown switch -x"));
  // -u says why: it needs a library callback.
  CHECK(contains(option_error("u"), "callback"));
  for (const std::string malformed : {"q30.5.5", "a.", "a1e-", "q1e999", "a0", "S1e30", "q."}) {
    INFO(malformed);
    CHECK(option_error(malformed) != "");
  }
  CHECK(contains(option_error("q."), "-q"));
  CHECK(contains(option_error("a1..2"), "-a"));
  // Valid switches throw nothing.
  CHECK(option_error("pcOADYBzenNEIjQVCh") == "");
  CHECK(option_error("pvgo2PXiFlsh") == "");
  CHECK(option_error("-q30a1e-3S5") == "");
}

TEST_CASE("api: validate(Options) refuses choices that do not go together or are out of range") {
  CHECK(validation_error(clmesh::Options{}) == "");
  CHECK(validation_error(clmesh::parse_switches("pcOAeVC")) == "");
  CHECK(validation_error(clmesh::parse_switches("q45a0.5S10")) == "");
  CHECK(validation_error(clmesh::parse_switches("pq30a0.5")) == "");
  CHECK(validation_error(clmesh::parse_switches("pqA")) == "");
  CHECK(contains(validation_error(clmesh::parse_switches("q50")), "minimum angle"));
  CHECK(contains(validation_error(clmesh::parse_switches("q45.5")), "minimum angle"));
  clmesh::Options options;
  options.min_angle = 50; // without -q the angle is not used
  CHECK(validation_error(options) == "");
  options.quality = true;
  options.min_angle = -1;
  CHECK(validation_error(options) != "");
  options = {};
  options.max_area = 0;
  CHECK(contains(validation_error(options), "-a"));
  options = {};
  options.max_steiner = -1;
  CHECK(contains(validation_error(options), "-S"));

  // Tuning: each field at the ends of its range and just past them.
  auto tuning_error = [](auto change) {
    clmesh::Options tuned;
    change(tuned.tuning);
    return validation_error(tuned);
  };
  CHECK(tuning_error([](clmesh::Tuning &t) { t.grid = 2; }) == "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.grid = 8192; }) == "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.grid = 1; }) != "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.grid = 8193; }) != "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.work_group = 1; }) == "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.work_group = 0; }) != "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.filter_rings = 3; }) == "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.filter_rings = 1; }) != "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.filter_rings = 4; }) != "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.filter_distance_rings = 0; }) == "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.filter_distance_rings = -1; }) != "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.filter_distance_rings = 2; }) != "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.election_rings = 0; }) == "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.election_rings = -1; }) != "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.election_rings = 3; }) != "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.filter_near = 0; }) == "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.filter_near = 1; }) == "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.filter_near = 0.5; }) != "");
  CHECK(tuning_error([](clmesh::Tuning &t) { t.use(clmesh::RefineAlgorithm::qm); }) == "");
  // triangulate() validates too.
  clmesh::Input input;
  input.points = fixtures::uniform(10, 1);
  CHECK_THROWS_AS(clmesh::triangulate(device(), input, "q50"), clmesh::OptionError);
  clmesh::Options bad_grid;
  bad_grid.tuning.grid = 1;
  CHECK_THROWS_AS(clmesh::triangulate(device(), input, bad_grid), clmesh::OptionError);
}

TEST_CASE("api: validate(Input) refuses input that cannot be meshed") {
  clmesh::Input input = square_with_diagonals();
  CHECK(input_error(input) == "");
  SUBCASE("fewer than three points") {
    clmesh::Input two;
    two.points = {{0, 0}, {1, 1}};
    CHECK(contains(input_error(two), "at least three"));
    CHECK_THROWS_AS(clmesh::triangulate(device(), two, clmesh::Options{}), clmesh::InputError);
  }
  SUBCASE("attributes of the wrong count") {
    input.attribute_count = 2;
    input.point_attributes.assign(7, 0.5);
    CHECK(contains(input_error(input), "point attributes"));
    input.point_attributes.assign(8, 0.5);
    CHECK(input_error(input) == "");
    input.attribute_count = -1;
    input.point_attributes.clear();
    CHECK(input_error(input) != "");
  }
  SUBCASE("markers of the wrong count") {
    input.point_markers = {1, 2, 3};
    CHECK(contains(input_error(input), "point markers"));
    input.point_markers = {1, 2, 3, 4};
    CHECK(input_error(input) == "");
  }
  SUBCASE("segment endpoints out of range") {
    input.segments.push_back({2, 4, 0});
    CHECK(contains(input_error(input), "segment 6"));
    input.segments.back() = {-1, 2, 0};
    CHECK(contains(input_error(input), "segment 6"));
    input.source = "shape.poly";
    CHECK(contains(input_error(input), "shape.poly"));
    CHECK_THROWS_AS(clmesh::triangulate(device(), input, "p"), clmesh::InputError);
  }
  SUBCASE("coordinates that are not finite or beyond what exact arithmetic carries") {
    for (const double bad : {std::nan(""), HUGE_VAL, 1e300, -1e51, 1e-300, -1e-51}) {
      INFO(bad);
      input.points[2] = {0.5, bad};
      CHECK(contains(input_error(input), "point 2"));
      CHECK_THROWS_AS(clmesh::triangulate(device(), input, "p"), clmesh::InputError);
    }
    // Zero and the extremes are fine.
    input.points[2] = {0, 1e50};
    input.points[3] = {-1e-50, 1};
    CHECK(input_error(input) == "");
  }
  SUBCASE("triangles to refine (-r) that are no triangulation") {
    input.triangles = {{0, 1, 2}, {0, 2, 3}};
    CHECK(input_error(input) == "");
    input.triangles[1] = {0, 3, 2};
    CHECK(contains(input_error(input), "triangle 1: its corners are in clockwise order"));
    input.triangles[1] = {0, 2, 4};
    CHECK(contains(input_error(input), "corner 4 is out of range"));
    input.triangles[1] = {0, 2, 0};
    CHECK(contains(input_error(input), "a corner is repeated"));
    // Two triangles folded over the edge 0-2.
    input.points.push_back({0.5, 0.25});
    input.triangles[1] = {0, 4, 2};
    CHECK(contains(input_error(input), "overlaps triangle"));
    input.triangles[1] = {0, 2, 3};
    input.triangle_max_area = {0.5};
    CHECK(contains(input_error(input), "1 maximum areas for 2 triangles"));
    input.triangle_max_area = {0.5, -1};
    input.triangle_attribute_count = 1;
    CHECK(contains(input_error(input), "0 triangle attributes for 2 triangles"));
    input.triangle_attributes = {1, 2};
    CHECK(input_error(input) == "");
    // Messages name the file and line the triangles came from.
    input.triangles_source = "shape.ele";
    input.triangle_lines = {3, 4};
    input.triangles[1] = {0, 3, 2};
    CHECK(contains(input_error(input), "shape.ele:4: triangle 1"));
    CHECK_THROWS_AS(clmesh::triangulate(device(), input, "r"), clmesh::InputError);
  }
  SUBCASE("holes and regions that are not finite") {
    input.holes = {{0.5, std::nan("")}};
    CHECK(contains(input_error(input), "hole 0"));
    input.holes = {{0.5, 0.5}};
    CHECK(input_error(input) == "");
    input.regions = {{{0.5, 0.5}, 1, -1}, {{INFINITY, 0.5}, 1, -1}};
    CHECK(contains(input_error(input), "region 1"));
    input.regions = {{{0.5, 0.5}, std::nan(""), -1}};
    CHECK(contains(input_error(input), "region 0"));
  }
}

TEST_CASE("api: triangulate a PSLG whose segments cross") {
  // The diagonals of the square cross at its centre: a fifth point, after the input's.
  SUBCASE("points, duplicates, segments, markers and edges") {
    const clmesh::Input input = square_with_diagonals();
    clmesh::Options options = clmesh::parse_switches("pe");
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, options);
    CHECK(mesh.input_points == 4);
    REQUIRE(mesh.points.size() == 5);
    CHECK(starts_with(mesh.points, input.points));
    CHECK(mesh.points[4].x == 0.5);
    CHECK(mesh.points[4].y == 0.5);
    REQUIRE(mesh.duplicate_of.size() == mesh.points.size());
    CHECK(mesh.duplicate_of == std::vector<int32_t>(5, -1));
    CHECK(mesh.statistics.constrained);
    CHECK_FALSE(mesh.statistics.refined);
    CHECK(mesh.statistics.constraints.crossings == 1);
    CHECK(mesh.statistics.constraints.split_segments == 2);
    // Four triangles around the crossing.
    REQUIRE(mesh.triangles.size() == 4);
    REQUIRE(mesh.neighbors.size() == 4);
    for (const auto &t : mesh.triangles)
      CHECK((t[0] == 4 || t[1] == 4 || t[2] == 4));
    // The segments as they stand: four sides and four half diagonals, each a mesh edge.
    const std::set<Edge> edges = triangle_edges(mesh);
    CHECK(edges.size() == 8);
    std::set<Edge> segments;
    for (const Segment &s : mesh.segments) {
      CHECK(edges.count(edge(s.a, s.b)) == 1);
      segments.insert(edge(s.a, s.b));
    }
    CHECK(mesh.segments.size() == 8);
    CHECK(segments == edges);
    // Markers: 1 on the boundary, 0 at the crossing (the segments' markers are 0).
    CHECK(mesh.point_markers == std::vector<int>{1, 1, 1, 1, 0});
    // -e: every edge once; the sides (segments on the boundary, marker 0 promoted) 1, the half
    // diagonals 0.
    REQUIRE(mesh.edges.size() == 8);
    std::set<Edge> listed;
    for (const clmesh::Edge &e : mesh.edges) {
      listed.insert(edge(e.a, e.b));
      CHECK(e.marker == (e.a == 4 || e.b == 4 ? 0 : 1));
    }
    CHECK(listed == edges);
    // No attributes asked for, none given.
    CHECK(mesh.attribute_count == 0);
    CHECK(mesh.point_attributes.empty());
    CHECK(mesh.triangle_attribute_count == 0);
    CHECK(mesh.triangle_attributes.empty());
    CHECK(mesh.voronoi_image.empty());
    const auto report = clmesh::check_mesh(input, mesh, options);
    INFO(problems(report));
    CHECK(report.ok);
    // Without -e no edges.
    options.edges = false;
    CHECK(clmesh::triangulate(device(), input, options).edges.empty());
  }
  SUBCASE("segment markers go to the points and edges") {
    // Sides 3, diagonals 0: corners 3, the crossing 0.
    const clmesh::Mesh sides = clmesh::triangulate(device(), square_with_diagonals(3, 0), "pe");
    CHECK(sides.point_markers == std::vector<int>{3, 3, 3, 3, 0});
    REQUIRE(sides.edges.size() == 8);
    for (const clmesh::Edge &e : sides.edges)
      CHECK(e.marker == (e.a == 4 || e.b == 4 ? 0 : 3));
    // Diagonals 7: the crossing (and the corners, which the diagonals end at too) 7.
    const clmesh::Mesh diagonals = clmesh::triangulate(device(), square_with_diagonals(0, 7), "pe");
    CHECK(diagonals.point_markers == std::vector<int>{7, 7, 7, 7, 7});
    REQUIRE(diagonals.edges.size() == 8);
    for (const clmesh::Edge &e : diagonals.edges)
      CHECK(e.marker == (e.a == 4 || e.b == 4 ? 7 : 1));
    for (const Segment &s : diagonals.segments)
      CHECK(s.marker == (s.a == 4 || s.b == 4 ? 7 : 0));
    // A point's own non-zero marker wins.
    clmesh::Input marked = square_with_diagonals(3, 0);
    marked.point_markers = {5, 0, 0, 0};
    CHECK(clmesh::triangulate(device(), marked, "p").point_markers ==
          std::vector<int>{5, 3, 3, 3, 0});
  }
  SUBCASE("point attributes are carried, the crossing's interpolated along the first diagonal") {
    clmesh::Input input = square_with_diagonals();
    input.attribute_count = 2;
    input.point_attributes = {1, 10, 2, 20, 3, 30, 4, 40};
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, "p");
    CHECK(mesh.attribute_count == 2);
    // Half way from point 0 to point 2 (segment 4, listed before 1-3, which would give 3, 30).
    CHECK(mesh.point_attributes == std::vector<double>{1, 10, 2, 20, 3, 30, 4, 40, 2, 20});
  }
  SUBCASE("a repeated segment gives its non-zero marker to the one it repeats") {
    clmesh::Input input = square_with_diagonals();
    input.segments.push_back({2, 0, 6}); // the first diagonal again, reversed, marker 6
    input.segments.push_back({0, 2, 9}); // and once more: the first non-zero marker counts
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, "pe");
    CHECK(mesh.statistics.constraints.dropped_segments == 2);
    CHECK(mesh.point_markers == std::vector<int>{6, 1, 6, 1, 6});
    for (const Segment &s : mesh.segments) {
      const bool first_diagonal = (s.a == 4 || s.b == 4) && (s.a % 2 == 0 || s.b % 2 == 0) &&
                                  s.a != 1 && s.b != 1 && s.a != 3 && s.b != 3;
      CHECK(s.marker == (first_diagonal ? 6 : 0));
    }
  }
  SUBCASE("-A: each triangle gets its region's attribute") {
    clmesh::Input input = square_with_diagonals();
    // One region in each quarter the diagonals cut: bottom 1, right 2, top 3, left 4.
    input.regions = {
        {{0.5, 0.1}, 1, -1}, {{0.9, 0.5}, 2, -1}, {{0.5, 0.9}, 3, -1}, {{0.1, 0.5}, 4, -1}};
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, "pA");
    CHECK(mesh.triangle_attribute_count == 1);
    REQUIRE(mesh.triangle_attributes.size() == mesh.triangles.size());
    REQUIRE(mesh.triangles.size() == 4);
    std::set<double> seen;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      double cx = 0, cy = 0;
      for (const int32_t v : mesh.triangles[t])
        cx += mesh.points[v].x / 3, cy += mesh.points[v].y / 3;
      const double expected = cy < cx && cy < 1 - cx ? 1 : cy < cx ? 2 : cy > 1 - cx ? 3 : 4;
      CHECK(mesh.triangle_attributes[t] == expected);
      seen.insert(mesh.triangle_attributes[t]);
    }
    CHECK(seen.size() == 4);
    // Without -A, none; nor with -A and no regions (as in Triangle).
    const clmesh::Mesh plain = clmesh::triangulate(device(), input, "p");
    CHECK(plain.triangle_attribute_count == 0);
    CHECK(plain.triangle_attributes.empty());
    const clmesh::Mesh no_regions = clmesh::triangulate(device(), square_with_diagonals(), "pA");
    CHECK(no_regions.triangle_attribute_count == 0);
    CHECK(no_regions.triangle_attributes.empty());
  }
}

TEST_CASE("api: the points a refinement adds get the attributes interpolated from the input's") {
  // Attributes linear in x and y come out exact (to rounding) at every added
  // point: crossings, Steiner points inside and on segments, of every kind of
  // refinement; the input's points keep theirs.
  const auto linear = [](const Point &p) {
    return std::array<double, 2>{2 * p.x - 3 * p.y + 1, 0.25 * p.x + 7};
  };
  clmesh::Input input;
  input.points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}, {2, 2},   {8, 8}, {2, 8},
                  {8, 2}, {5, 1},  {1, 5},   {3, 6},  {7, 4.5}, {6, 9}};
  input.segments = {{0, 1, 0}, {1, 2, 0}, {2, 3, 0}, {3, 0, 0}, {4, 5, 0}, {6, 7, 0}, {8, 9, 0}};
  input.attribute_count = 2;
  for (const Point &p : input.points)
    for (const double value : linear(p))
      input.point_attributes.push_back(value);
  auto check_linear = [&](const clmesh::Mesh &mesh) {
    REQUIRE(mesh.point_attributes.size() == 2 * mesh.points.size());
    CHECK(std::equal(input.point_attributes.begin(), input.point_attributes.end(),
                     mesh.point_attributes.begin()));
    double worst = 0;
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
      for (std::size_t k = 0; k < 2; ++k)
        worst =
            std::max(worst, std::abs(mesh.point_attributes[2 * i + k] - linear(mesh.points[i])[k]));
    CHECK(worst < 1e-12);
  };
  for (const char *switches : {"p", "pq30", "pq30a0.5", "pcq25", "pDq", "pYq30", "q30a0.3"}) {
    INFO("switches " << switches);
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, switches);
    CHECK(mesh.points.size() > input.points.size()); // two crossings at least
    check_linear(mesh);
  }
  SUBCASE("-r: from the mesh refined") {
    clmesh::Input coarse = input;
    const clmesh::Mesh first = clmesh::triangulate(device(), input, "p");
    coarse.points = first.points;
    coarse.point_attributes = first.point_attributes;
    coarse.triangles = first.triangles;
    coarse.segments.clear();
    const clmesh::Mesh refined = clmesh::triangulate(device(), coarse, "rq30a0.2");
    CHECK(refined.points.size() > 2 * coarse.points.size());
    check_linear(refined);
  }
}

TEST_CASE("api: the three triangulate() overloads give the same mesh") {
  clmesh::Input points;
  points.points = fixtures::uniform(500, 3);
  for (const std::string switches : {"", "q25", "a0.01e"}) {
    INFO("switches '" << switches << "'");
    const clmesh::Options options = clmesh::parse_switches(switches);
    const clmesh::Mesh by_options = clmesh::triangulate(device(), points, options);
    const clmesh::Mesh by_switches = clmesh::triangulate(device(), points, switches);
    const clmesh::Mesh own_device = clmesh::triangulate(points, options);
    check_same_mesh(by_options, by_switches);
    check_same_mesh(by_options, own_device);
    CHECK(by_options.edges.size() == own_device.edges.size());
    CHECK(by_options.statistics.refined == !switches.empty());
    CHECK(by_options.statistics.refinement.inserted == own_device.statistics.refinement.inserted);
    const auto report = clmesh::check_mesh(points, by_options, options);
    INFO(problems(report));
    CHECK(report.ok);
  }
  const clmesh::Input pslg = square_with_diagonals(2, 5);
  const clmesh::Mesh by_options = clmesh::triangulate(device(), pslg, clmesh::parse_switches("pc"));
  check_same_mesh(by_options, clmesh::triangulate(device(), pslg, "pc"));
  check_same_mesh(by_options, clmesh::triangulate(pslg, clmesh::parse_switches("pc")));
  CHECK_THROWS_AS(clmesh::triangulate(device(), pslg, "pu"), clmesh::OptionError);
}

TEST_CASE(
    "api: find_device names the device open_device opens, and every spec of it gives one mesh") {
  const clmesh::DeviceDescription found = clmesh::find_device();
  CHECK(found.has_fp64);
  CHECK(clmesh::describe(*clmesh::open_device()) ==
        found.device_name + " (" + found.platform_name + ")");
  const std::string spec =
      std::to_string(found.platform_index) + ":" + std::to_string(found.device_index);
  const clmesh::DeviceDescription by_spec = clmesh::find_device(spec);
  CHECK(by_spec.platform_index == found.platform_index);
  CHECK(by_spec.device_index == found.device_index);
  CHECK_THROWS_AS(clmesh::find_device("no such device anywhere"), clmesh::DeviceError);
  // triangulate(input, options) opens the device once for both specs.
  clmesh::Input points;
  points.points = fixtures::uniform(300, 5);
  clmesh::Options options;
  const clmesh::Mesh by_default = clmesh::triangulate(points, options);
  options.device = spec;
  check_same_mesh(by_default, clmesh::triangulate(points, options));
}

TEST_CASE("api: check_mesh accepts good meshes and finds broken ones") {
  const auto points = fixtures::uniform(400, 4);
  clmesh::Input input;
  input.points = points;
  SUBCASE("a Delaunay triangulation") {
    const clmesh::Options options;
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, options);
    REQUIRE(mesh.triangles.size() > 100);
    const auto good = clmesh::check_mesh(input, mesh, options);
    INFO(problems(good));
    CHECK(good.ok);
    CHECK(good.problems.empty());
    clmesh::Mesh flipped = mesh; // one triangle turned clockwise
    std::swap(flipped.triangles[7][1], flipped.triangles[7][2]);
    std::swap(flipped.neighbors[7][1], flipped.neighbors[7][2]);
    const auto report = clmesh::check_mesh(input, flipped, options);
    CHECK_FALSE(report.ok);
    CHECK_FALSE(report.problems.empty());
    clmesh::Mesh relinked = mesh; // a neighbour link to the wrong triangle
    int32_t t = 0;
    while (relinked.neighbors[t][0] < 0)
      ++t;
    relinked.neighbors[t][0] = relinked.neighbors[t][0] == 0 ? 1 : 0;
    CHECK_FALSE(clmesh::check_mesh(input, relinked, options).ok);
    clmesh::Mesh missing = mesh; // a triangle left out
    missing.triangles.pop_back();
    missing.neighbors.pop_back();
    for (auto &n : missing.neighbors)
      for (auto &k : n)
        if (k == static_cast<int32_t>(missing.triangles.size()))
          k = -1;
    CHECK_FALSE(clmesh::check_mesh(input, missing, options).ok);
  }
  SUBCASE("a constrained Delaunay triangulation") {
    // The square with one diagonal, checked against the square with the other.
    clmesh::Input one;
    one.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    one.segments = {{0, 1, 0}, {1, 2, 0}, {2, 3, 0}, {3, 0, 0}, {0, 2, 0}};
    clmesh::Input other = one;
    other.segments.back() = {1, 3, 0};
    const clmesh::Options options = clmesh::parse_switches("p");
    const clmesh::Mesh mesh = clmesh::triangulate(device(), one, options);
    CHECK(mesh.triangles == std::vector<clmesh::Triangle>{{0, 1, 2}, {0, 2, 3}});
    CHECK(clmesh::check_mesh(one, mesh, options).ok);
    CHECK(clmesh::check_mesh(other, clmesh::triangulate(device(), other, options), options).ok);
    CHECK_FALSE(clmesh::check_mesh(other, mesh, options).ok);
    // A triangle turned clockwise.
    clmesh::Mesh flipped = mesh;
    std::swap(flipped.triangles[1][1], flipped.triangles[1][2]);
    std::swap(flipped.neighbors[1][1], flipped.neighbors[1][2]);
    CHECK_FALSE(clmesh::check_mesh(one, flipped, options).ok);
  }
  SUBCASE("-D: an interior subsegment must be locally Delaunay too") {
    // A box with a segment across it and a point just off each side of the
    // segment: each point lies in the circumcircle beyond the segment, so the
    // constrained triangulation keeps a subsegment that is not locally
    // Delaunay, which a conforming (-D) mesh may not.
    clmesh::Input box;
    box.points = {{0, 0}, {4, 0}, {4, 3}, {0, 3}, {1, 1.5}, {3, 1.5}, {2, 1.4}, {2, 1.6}};
    box.segments = {{0, 1, 0}, {1, 2, 0}, {2, 3, 0}, {3, 0, 0}, {4, 5, 0}};
    const clmesh::Options constrained = clmesh::parse_switches("p");
    clmesh::Mesh mesh = clmesh::triangulate(device(), box, constrained);
    REQUIRE(clmesh::check_mesh(box, mesh, constrained).ok);
    mesh.statistics.refined = true; // checked as a -pq and a -pqD mesh
    const auto quality = clmesh::check_mesh(box, mesh, clmesh::parse_switches("pq20"));
    INFO(problems(quality));
    CHECK(quality.ok);
    const auto conforming = clmesh::check_mesh(box, mesh, clmesh::parse_switches("pq20D"));
    INFO(problems(conforming));
    CHECK_FALSE(conforming.ok);
    CHECK(problems(conforming).find("4-5 is not a segment and not locally Delaunay") !=
          std::string::npos);
    CHECK(problems(conforming).find("-D: every edge off the boundary") != std::string::npos);
  }
  SUBCASE("a quality mesh") {
    const clmesh::Options options = clmesh::parse_switches("q30");
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, options);
    const auto good = clmesh::check_mesh(input, mesh, options);
    INFO(problems(good));
    CHECK(good.ok);
    clmesh::Mesh moved = mesh; // a Steiner point moved off its place
    REQUIRE(moved.points.size() > points.size());
    const std::size_t steiner = points.size() + (moved.points.size() - points.size()) / 2;
    moved.points[steiner].x += 0.02;
    moved.points[steiner].y -= 0.02;
    CHECK_FALSE(clmesh::check_mesh(input, moved, options).ok);
  }
}

TEST_CASE("api: quality statistics of a known mesh") {
  // The unit right triangle cut from its right angle to the middle of its hypotenuse: two
  // right isosceles triangles with legs sqrt(1/2).
  clmesh::Input input;
  input.points = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0.5}};
  const clmesh::Mesh mesh = clmesh::triangulate(device(), input, clmesh::Options{});
  REQUIRE(mesh.triangles.size() == 2);
  const clmesh::QualityStatistics q = clmesh::quality_statistics(mesh);
  CHECK(q.triangles == 2);
  CHECK(q.smallest_area == 0.25);
  CHECK(q.largest_area == 0.25);
  CHECK(q.shortest_edge == doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
  CHECK(q.longest_edge == 1);
  CHECK(q.shortest_altitude == 0.5);
  CHECK(q.largest_aspect_ratio == 2);
  CHECK(q.smallest_angle == doctest::Approx(45).epsilon(1e-12));
  CHECK(q.largest_angle == doctest::Approx(90).epsilon(1e-12));
  // Both triangles have aspect ratio 2: the bin [2, 2.5).
  std::array<long, 16> ratios{};
  ratios[2] = 2;
  CHECK(q.aspect_ratio_histogram == ratios);
  // Four angles of 45 degrees, two of 90 (in the bin 80-90 or 90-100, by rounding).
  long angles = 0;
  for (const long count : q.angle_histogram)
    angles += count;
  CHECK(angles == 6);
  CHECK(q.angle_histogram[4] == 4);
  CHECK(q.angle_histogram[8] + q.angle_histogram[9] == 2);
  const std::string table = clmesh::format_quality(q);
  CHECK(contains(table, "Mesh quality statistics"));
  CHECK(contains(table, "Smallest area:             0.25"));
  CHECK(contains(table, "Largest aspect ratio:        2"));
  CHECK(contains(table, "Smallest angle:              45"));
  CHECK(contains(table, "Largest angle:              90"));
  // No triangles: nothing to say.
  const clmesh::QualityStatistics none = clmesh::quality_statistics(clmesh::Mesh{});
  CHECK(none.triangles == 0);
  CHECK(clmesh::format_quality(none) == "");
}

TEST_CASE("api: statistics JSON and text have the counts, constraints only with -p, refinement "
          "only with -q") {
  const clmesh::RunSeconds seconds{1.5, 2, 0.25};
  clmesh::Input input;
  input.points = fixtures::uniform(300, 5);
  const clmesh::Mesh plain = clmesh::triangulate(device(), input, clmesh::Options{});
  const std::string json = clmesh::statistics_json(plain, seconds);
  CHECK(contains(json, "\"input_points\": 300,"));
  CHECK(contains(json, "\"triangles\": " + std::to_string(plain.triangles.size()) + ","));
  CHECK(contains(json, "\"flips\": " + std::to_string(plain.statistics.delaunay.flips) + ","));
  CHECK(contains(json, "\"read\": 1.5, \"compute\": 2, \"write\": 0.25"));
  CHECK(contains(json, "\"construction\": \"" + plain.statistics.delaunay.construction + "\""));
  CHECK_FALSE(contains(json, "\"constraints\""));
  CHECK_FALSE(contains(json, "\"refinement\""));

  const clmesh::Mesh cdt = clmesh::triangulate(device(), square_with_diagonals(), "p");
  const std::string cdt_json = clmesh::statistics_json(cdt, seconds);
  CHECK(contains(cdt_json, "\"constraints\""));
  CHECK(contains(cdt_json, "\"crossings\": 1,"));
  CHECK(contains(cdt_json, "\"segments\": 6,"));
  CHECK(contains(cdt_json, "\"input_points\": 4,"));
  CHECK(contains(cdt_json, "\"triangles\": 4,"));
  CHECK_FALSE(contains(cdt_json, "\"refinement\""));

  const clmesh::Mesh refined = clmesh::triangulate(device(), input, "q30");
  const std::string refined_json = clmesh::statistics_json(refined, seconds);
  CHECK(contains(refined_json, "\"refinement\""));
  CHECK(contains(refined_json,
                 "\"steiner_points\": " + std::to_string(refined.points.size() - 300) + ","));
  CHECK(contains(refined_json,
                 "\"iterations\": " + std::to_string(refined.statistics.refinement.iterations)));
  CHECK_FALSE(contains(refined_json, "\"constraints\""));
  // The -V counts: the same sections.
  CHECK(contains(clmesh::format_statistics(plain),
                 "Flips: " + std::to_string(plain.statistics.delaunay.flips)));
  CHECK_FALSE(contains(clmesh::format_statistics(plain), "Constraints:"));
  CHECK_FALSE(contains(clmesh::format_statistics(plain), "Refinement:"));
  CHECK(contains(clmesh::format_statistics(cdt), "Segment crossings (new vertices): 1\n"));
  CHECK_FALSE(contains(clmesh::format_statistics(cdt), "Refinement:"));
  CHECK(contains(clmesh::format_statistics(refined),
                 "Steiner points: " + std::to_string(refined.points.size() - 300) + " ("));
  CHECK_FALSE(contains(clmesh::format_statistics(refined), "Constraints:"));
  // -a alone refines too.
  CHECK(contains(clmesh::statistics_json(clmesh::triangulate(device(), input, "a0.01"), seconds),
                 "\"refinement\""));
}

TEST_CASE("api: a quality mesh is the same on every run, GPU-QM and GPU-QM-V both valid") {
  clmesh::Input input;
  input.points = fixtures::gaussian(3000, 6);
  const clmesh::Options options = clmesh::parse_switches("q30");
  const clmesh::Mesh first = clmesh::triangulate(device(), input, options);
  const clmesh::Mesh second = clmesh::triangulate(device(), input, options);
  check_same_mesh(first, second);
  CHECK(first.statistics.refinement.iterations == second.statistics.refinement.iterations);
  CHECK(first.statistics.refinement.candidates == second.statistics.refinement.candidates);
  CHECK(first.statistics.refinement.deleted == second.statistics.refinement.deleted);

  // The default tuning is GPU-QM-V's.
  clmesh::Tuning qmv;
  qmv.use(clmesh::RefineAlgorithm::qmv);
  const clmesh::Tuning defaults;
  CHECK(qmv.algorithm == defaults.algorithm);
  CHECK(qmv.filter_rings == defaults.filter_rings);
  CHECK(qmv.filter_distance_rings == defaults.filter_distance_rings);
  CHECK(qmv.filter_near == defaults.filter_near);
  CHECK(qmv.election_rings == defaults.election_rings);
  // GPU-QM: the thesis's filter, no election.
  clmesh::Options qm_options = options;
  qm_options.tuning = clmesh::Tuning{}.use(clmesh::RefineAlgorithm::qm);
  CHECK(qm_options.tuning.algorithm == clmesh::RefineAlgorithm::qm);
  CHECK(qm_options.tuning.filter_rings == 3);
  CHECK(qm_options.tuning.filter_distance_rings == 0);
  CHECK(qm_options.tuning.filter_near == 0);
  CHECK(qm_options.tuning.election_rings == 0);
  const clmesh::Mesh qm = clmesh::triangulate(device(), input, qm_options);
  for (const clmesh::Mesh *mesh : {&first, &qm}) {
    const auto report = clmesh::check_mesh(input, *mesh, options);
    INFO(problems(report));
    CHECK(report.ok);
    CHECK(mesh->statistics.refinement.remaining_bad == 0);
    CHECK(mesh->input_points == 3000);
    CHECK(mesh->duplicate_of.size() == mesh->points.size());
    CHECK(static_cast<long>(mesh->points.size()) - 3000 == mesh->statistics.refinement.inserted);
    // The input's points come first, unchanged.
    CHECK(starts_with(mesh->points, input.points));
  }
  // The algorithms differ: GPU-QM elects no candidates away, GPU-QM-V does.
  MESSAGE("GPU-QM-V: " << first.statistics.refinement.candidates << " candidates, "
                       << first.statistics.refinement.inserted
                       << " points; GPU-QM: " << qm.statistics.refinement.candidates << ", "
                       << qm.statistics.refinement.inserted);
  CHECK(qm.statistics.refinement.candidates > first.statistics.refinement.candidates);
  // The same algorithm chosen explicitly: the same mesh as the default.
  clmesh::Options explicit_qmv = options;
  explicit_qmv.tuning = qmv;
  check_same_mesh(first, clmesh::triangulate(device(), input, explicit_qmv));
}
