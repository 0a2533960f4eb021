// Quality meshing of PSLGs (-pq, -pa): GPU-QM-V on the domain of GPU-CDT,
// every output checked exactly and against the domain and segments of the
// same input's constrained Delaunay triangulation (-p).
#include <doctest/doctest.h>

#include "clmesh/clmesh.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

using clmesh::Point;
using clmesh::Segment;
using test_support::area;
using test_support::device;
using test_support::problems;

namespace {

clmesh::Input load(const std::string &folder, const std::string &name) {
  return clmesh::read_input(std::string(CLMESH_SHARED_DATA) + "/" + folder + "/" + name + ".poly");
}

long double total_area(const clmesh::Mesh &mesh) {
  long double sum = 0;
  for (const auto &t : mesh.triangles)
    sum += area(mesh.points, t);
  return sum;
}

// Is every segment of `cdt` (the -p mesh of the same input: input segments
// split where they cross) a chain of the refined mesh's subsegments, through
// points added on it (within rounding of the line) only?
bool segments_are_chains(const clmesh::Mesh &cdt, const clmesh::Mesh &refined) {
  std::multimap<int32_t, int32_t> next;
  for (const Segment &s : refined.segments) {
    next.insert({s.a, s.b});
    next.insert({s.b, s.a});
  }
  const auto first_steiner = static_cast<int32_t>(cdt.points.size());
  for (const Segment &s : cdt.segments) {
    const Point a = refined.points[s.a], b = refined.points[s.b];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    auto along = [&](int32_t v) { // distance from a along the segment, or -1 off it
      const Point p = refined.points[v];
      const double cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
      if (std::fabs(cross) > 1e-9 * length * length)
        return -1.0;
      return ((p.x - a.x) * (b.x - a.x) + (p.y - a.y) * (b.y - a.y)) / length;
    };
    int32_t at = s.a;
    double reached = 0;
    while (at != s.b) {
      int32_t step = -1;
      for (auto [it, end] = next.equal_range(at); it != end; ++it) {
        const int32_t v = it->second;
        if (v == s.b) {
          step = v;
          break;
        }
        const double d = along(v);
        if (v >= first_steiner && d > reached && d < length)
          step = v;
      }
      if (step < 0)
        return false;
      reached = step == s.b ? length : along(step);
      at = step;
    }
  }
  return true;
}

// Meshes pslg with `switches` (which hold -p and -q or -a), then checks: the
// exact checker (valid, every subsegment an edge, every other edge locally
// Delaunay); the domain of the -p mesh, with its segments as chains; every
// point added on a segment carrying the segment's marker; the area bound
// everywhere, and no angle below the bound beyond the triangles the
// refinement reports it could not mend.
// With `tuning`, those refinement settings instead of the defaults.
clmesh::Mesh refine_checked(const clmesh::Input &pslg, const std::string &switches,
                            const clmesh::Tuning *tuning = nullptr) {
  clmesh::Options options = clmesh::parse_switches(switches);
  if (tuning)
    options.tuning = *tuning;
  clmesh::Options cdt_options = options;
  cdt_options.quality = false;
  cdt_options.max_area.reset();
  cdt_options.conforming_delaunay = false;
  cdt_options.regional_areas = false;
  const clmesh::Mesh cdt = clmesh::triangulate(device(), pslg, cdt_options);
  const clmesh::Mesh mesh = clmesh::triangulate(device(), pslg, options);
  const auto report = clmesh::check_mesh(pslg, mesh, options);
  INFO(switches);
  INFO(problems(report));
  CHECK(report.ok);
  CHECK(mesh.statistics.refined);
  CHECK(mesh.statistics.refinement.stop_reason == clmesh::RefineStop::done);
  REQUIRE(test_support::starts_with(mesh.points, cdt.points));
  const long double domain = total_area(cdt);
  CHECK(std::fabs(static_cast<double>(total_area(mesh) - domain)) <=
        1e-9 * static_cast<double>(domain));
  CHECK(segments_are_chains(cdt, mesh));
  test_support::check_refined_bounds(mesh, options);
  return mesh;
}

} // namespace

TEST_CASE("quality pslg: Triangle's examples, holes and concavities, 20 to 30 degrees") {
  for (const char *name : {"A", "face", "double_hex", "square_circle_hole", "la"})
    for (const char *switches : {"pq20", "pq25", "pq30", "pq30a0.5", "pcq30"}) {
      INFO(std::string(name));
      const clmesh::Mesh mesh = refine_checked(load("triangle-examples/inputs", name), switches);
      CHECK(mesh.triangles.size() > 0);
    }
}

TEST_CASE("quality pslg: segment markers go to the points and subsegments that split them") {
  // box.poly: the left side of the outer box has marker 5, one side of the hole 10. Its
  // outer box has one segment, so the other three sides are added (marker 1).
  clmesh::Input box = load("triangle-examples/inputs", "box");
  box.segments.push_back({0, 2, 1});
  box.segments.push_back({2, 3, 1});
  box.segments.push_back({3, 1, 1});
  const clmesh::Mesh mesh = refine_checked(box, "pq30a0.05");
  const auto input = static_cast<std::size_t>(mesh.input_points);
  std::map<int, long> steiner_markers, subsegment_markers;
  for (std::size_t v = input; v < mesh.points.size(); ++v)
    ++steiner_markers[mesh.point_markers[v]];
  for (const Segment &s : mesh.segments)
    ++subsegment_markers[s.marker];
  // Points on the left side (x = 0, between its ends) carry 5, on the marked side of the hole 10.
  for (std::size_t v = input; v < mesh.points.size(); ++v) {
    const Point p = mesh.points[v];
    if (p.x == 0 && p.y > 0 && p.y < 3)
      CHECK(mesh.point_markers[v] == 5);
    else if (std::fabs(p.y - 2) < 1e-12 && p.x > 1 && p.x < 2)
      CHECK(mesh.point_markers[v] == 10);
  }
  CHECK(steiner_markers[5] > 0);
  CHECK(steiner_markers[10] > 0);
  CHECK(subsegment_markers[5] == steiner_markers[5] + 1);
  CHECK(subsegment_markers[10] == steiner_markers[10] + 1);
}

TEST_CASE("quality pslg: every bundled PSLG at 20, 25 and 30 degrees, vertex counts near "
          "Triangle's") {
  // Vertex counts of the native Triangle 1.6 (../shared/tools/build-triangle.sh) on the same
  // files: `triangle -<switches> name.poly`, first number of name.1.node; and how many of its
  // triangles have an angle below the bound (at small input angles, which it leaves).
  struct Case {
    const char *name;
    const char *switches;
    long triangle_vertices, triangle_below;
    const char *folder = "pslg";
    // At most 5% more vertices than Triangle, and no more triangles left below the bound
    // than it leaves (up to 5%), but for the exceptions below.
    double most_ratio = 1.05;
    long more_below = 0;
  };
  // The exceptions: on a few dozen vertices clmesh's parallel iterations, which put several
  // points in at once where Triangle puts in one at a time (the worst triangle first), place
  // more interior points (building -pq20: 31, -pq25: 43; lettre_A -pq30: 89; double_hex3
  // -pq30: 47), and around small input angles the shells can leave a few more triangles below
  // the bound (simplified-us-border -pq30: 9, la -pq30: 13). Their bounds hold these counts
  // with a margin of a few points.
  const Case cases[] = {{"Capital_A", "pq20", 56, 0},
                        {"Capital_A", "pq25", 65, 0},
                        {"Capital_A", "pq30", 78, 1},
                        {"building", "pq20", 29, 0, "pslg", 1.12},
                        {"building", "pq25", 36, 0, "pslg", 1.25},
                        {"building", "pq30", 59, 0},
                        {"butterfly", "pq20", 23, 0},
                        {"butterfly", "pq25", 23, 0},
                        {"butterfly", "pq30", 27, 0},
                        {"clusters", "pq20", 9, 0},
                        {"clusters", "pq25", 9, 0},
                        {"clusters", "pq30", 9, 0},
                        {"ditch", "pq20", 12, 0},
                        {"ditch", "pq25", 12, 0},
                        {"ditch", "pq30", 12, 0},
                        {"fish", "pq20", 17, 0},
                        {"fish", "pq25", 17, 0},
                        {"fish", "pq30", 35, 2},
                        {"hilbert", "pq20", 1041, 0},
                        {"hilbert", "pq25", 1041, 0},
                        {"hilbert", "pq30", 1041, 0},
                        {"img1", "pq20", 53, 0},
                        {"img1", "pq25", 53, 0},
                        {"img1", "pq30", 53, 0},
                        {"island", "pq20", 119, 0},
                        {"island", "pq25", 136, 0},
                        {"island", "pq30", 151, 0},
                        {"kidney", "pq20", 70, 0},
                        {"kidney", "pq25", 79, 0},
                        {"kidney", "pq30", 99, 0},
                        {"lettre_A", "pq20", 56, 0},
                        {"lettre_A", "pq25", 65, 0},
                        {"lettre_A", "pq30", 78, 1, "pslg", 1.17},
                        {"overlapping_constraints", "pq20", 10, 0},
                        {"overlapping_constraints", "pq25", 10, 0},
                        {"overlapping_constraints", "pq30", 10, 0},
                        {"simplified-us-border", "pq20", 224, 2},
                        {"simplified-us-border", "pq25", 307, 5},
                        {"simplified-us-border", "pq30", 433, 7, "pslg", 1.05, 3},
                        {"square_with_crack", "pq20", 7, 0},
                        {"square_with_crack", "pq25", 7, 0},
                        {"square_with_crack", "pq30", 7, 0},
                        {"water-huge2", "pq20", 12883, 684},
                        {"water-huge2", "pq25", 18007, 931},
                        {"water-huge2", "pq30", 28018, 1283},
                        {"water", "pq20", 5422, 272},
                        {"water", "pq25", 7497, 382},
                        {"water", "pq30", 11604, 529},
                        {"water2", "pq20", 2084, 69},
                        {"water2", "pq25", 2622, 89},
                        {"water2", "pq30", 3570, 100},
                        {"water3", "pq20", 434, 5},
                        {"water3", "pq25", 577, 6},
                        {"water3", "pq30", 876, 11},
                        {"water4", "pq20", 1134, 23},
                        {"water4", "pq25", 1476, 38},
                        {"water4", "pq30", 2330, 46},
                        {"A", "pq20", 56, 0, "triangle-examples/inputs"},
                        {"A", "pq25", 64, 0, "triangle-examples/inputs"},
                        {"A", "pq30", 76, 0, "triangle-examples/inputs"},
                        {"box", "pq20", 8, 0, "triangle-examples/inputs"},
                        {"box", "pq25", 8, 0, "triangle-examples/inputs"},
                        {"box", "pq30", 8, 0, "triangle-examples/inputs"},
                        {"double_hex", "pq20", 146, 0, "triangle-examples/inputs"},
                        {"double_hex", "pq25", 170, 0, "triangle-examples/inputs"},
                        {"double_hex", "pq30", 217, 0, "triangle-examples/inputs"},
                        {"double_hex2", "pq20", 57, 0, "triangle-examples/inputs"},
                        {"double_hex2", "pq25", 63, 0, "triangle-examples/inputs"},
                        {"double_hex2", "pq30", 77, 0, "triangle-examples/inputs"},
                        {"double_hex3", "pq20", 31, 0, "triangle-examples/inputs"},
                        {"double_hex3", "pq25", 37, 0, "triangle-examples/inputs"},
                        {"double_hex3", "pq30", 43, 0, "triangle-examples/inputs", 1.14},
                        {"face", "pq20", 44, 0, "triangle-examples/inputs"},
                        {"face", "pq25", 58, 0, "triangle-examples/inputs"},
                        {"face", "pq30", 100, 0, "triangle-examples/inputs"},
                        {"la", "pq20", 365, 6, "triangle-examples/inputs"},
                        {"la", "pq25", 490, 7, "triangle-examples/inputs"},
                        {"la", "pq30", 891, 10, "triangle-examples/inputs", 1.05, 4},
                        {"square_circle_hole", "pq20", 826, 0, "triangle-examples/inputs"},
                        {"square_circle_hole", "pq25", 826, 0, "triangle-examples/inputs"},
                        {"square_circle_hole", "pq30", 826, 0, "triangle-examples/inputs"},
                        {"water", "pcq30", 21673, 799},
                        {"water2", "pcq30", 7114, 159},
                        {"water4", "pcq30", 2848, 54},
                        {"clusters", "pcq30", 69, 27}};
  for (const Case &c : cases) {
    INFO(std::string(c.name) << " -" << std::string(c.switches));
    const clmesh::Mesh mesh = refine_checked(load(c.folder, c.name), c.switches);
    const double ratio = static_cast<double>(mesh.points.size()) / c.triangle_vertices;
    const long below = mesh.statistics.refinement.remaining_bad;
    MESSAGE(std::string(c.name) << " -" << std::string(c.switches) << ": " << mesh.points.size()
                                << " vertices, Triangle " << c.triangle_vertices << " (" << ratio
                                << "), " << below << " triangles left at small angles, Triangle "
                                << c.triangle_below);
    // Fewer vertices is no fault as long as every bound holds (refine_checked: every triangle
    // below the bound is one of those counted) and no more triangles are left below it:
    // concentric shells around the sharper end of each segment, the triangles left across
    // small input angles and the points deleted beside split segments make clmesh's meshes
    // up to 26% smaller there (clusters -pcq30: 51 vertices and 21 triangles left, Triangle
    // 69 and 27); far fewer would mean refinement stopped early.
    CHECK(ratio > 0.7);
    CHECK(ratio < c.most_ratio);
    CHECK(below <= 1.05 * c.triangle_below + c.more_below);
  }
}

TEST_CASE("quality pslg: along coastlines the election sends few of the off-centers") {
  // Most bad triangles have a corner on a coastline, and most of their
  // candidates are off-centers that would lose in the insertion filter. Only
  // those that split an edge of their own on the boundary are sent whatever
  // their neighbours' priorities; the others take part in the election.
  clmesh::Tuning every_one;
  every_one.election_rings = 0;
  for (const char *name : {"water", "water-huge2", "simplified-us-border"}) {
    INFO(std::string(name));
    const clmesh::Input coast = load("pslg", name);
    const auto all = refine_checked(coast, "pq30", &every_one).statistics.refinement;
    const auto elected = refine_checked(coast, "pq30").statistics.refinement;
    MESSAGE(std::string(name) << ": candidates, iterations, points: every bad triangle "
                              << all.candidates << ", " << all.iterations << ", " << all.inserted
                              << "; elected " << elected.candidates << ", " << elected.iterations
                              << ", " << elected.inserted);
    // Under half the candidates (sending every bad triangle with a corner on
    // the boundary located three quarters of them or more), and but on the
    // smallest coastline (a few hundred points, where the points deleted
    // beside split segments and sent again make the last iterations) no more
    // iterations and at most 5% more points.
    CHECK(elected.candidates * 2 < all.candidates);
    if (all.inserted > 1000) {
      CHECK(elected.iterations <= all.iterations);
      CHECK(elected.inserted * 100 <= all.inserted * 105);
    }
  }
}

TEST_CASE("quality pslg: a search that keeps unchanged bad triangles' verdicts meshes the same") {
  // Each search keeps the verdicts of the last search's bad triangles that
  // nothing their assessment reads has rewritten since (the triangle, and
  // across edges that end on a segment's added vertex the triangle there);
  // what can change (can an edge behind the candidate still be split, did a
  // location find it stuck) is asked again. Assessing every triangle again
  // must give the very same mesh: with segments and shells, -D's obtuse
  // triangles, -Y's and -YY's protected edges, regional bounds and splits
  // that cannot be made within precision (clusters, overlapping constraints).
  clmesh::Tuning assess_all;
  assess_all.carry_verdicts = false;
  for (const char *name :
       {"water", "simplified-us-border", "clusters", "overlapping_constraints", "kidney"})
    for (const char *switches : {"pq30", "pcq30", "pq30D", "pq30Y", "pq30YY", "pAq30a"}) {
      INFO(std::string(name) << " -" << switches);
      const clmesh::Input pslg = load("pslg", name);
      clmesh::Options options = clmesh::parse_switches(switches);
      const clmesh::Mesh carried = clmesh::triangulate(device(), pslg, options);
      options.tuning = assess_all;
      const clmesh::Mesh assessed = clmesh::triangulate(device(), pslg, options);
      CHECK(carried.triangles == assessed.triangles);
      const auto same_segment = [](const clmesh::Segment &s, const clmesh::Segment &t) {
        return s.a == t.a && s.b == t.b;
      };
      CHECK(std::equal(carried.segments.begin(), carried.segments.end(), assessed.segments.begin(),
                       assessed.segments.end(), same_segment));
      const auto same_point = [](Point p, Point q) { return p.x == q.x && p.y == q.y; };
      CHECK(std::equal(carried.points.begin(), carried.points.end(), assessed.points.begin(),
                       assessed.points.end(), same_point));
      CHECK(carried.statistics.refinement.remaining_bad ==
            assessed.statistics.refinement.remaining_bad);
    }
}

TEST_CASE("quality pslg: the search after a later move examines what may be bad, and meshes "
          "the same") {
  // When the triangles move into Z-order again, those the last search found
  // bad or left stuck and those rewritten since carry a flag; the search
  // after the move assesses only those. A search of every slot must find the
  // same bad triangles in the same order: the very same mesh, with segments
  // and shells, -D, -Y, -YY and regional bounds.
  clmesh::Tuning sweep;
  sweep.search_flagged_after_move = false;
  for (const char *name : {"water", "simplified-us-border", "kidney"})
    for (const char *switches : {"pq30", "pcq30", "pq30D", "pq30Y", "pq30YY", "pAq30a"}) {
      INFO(std::string(name) << " -" << switches);
      const clmesh::Input pslg = load("pslg", name);
      clmesh::Options options = clmesh::parse_switches(switches);
      const clmesh::Mesh flagged = clmesh::triangulate(device(), pslg, options);
      CHECK(flagged.statistics.refinement.compactions >= 2); // a later move
      options.tuning = sweep;
      const clmesh::Mesh swept = clmesh::triangulate(device(), pslg, options);
      CHECK(flagged.triangles == swept.triangles);
      REQUIRE(flagged.points.size() == swept.points.size());
      for (std::size_t i = 0; i < flagged.points.size(); ++i)
        CHECK(
            (flagged.points[i].x == swept.points[i].x && flagged.points[i].y == swept.points[i].y));
      CHECK(flagged.statistics.refinement.remaining_bad ==
            swept.statistics.refinement.remaining_bad);
    }
}

TEST_CASE("quality pslg: tiny input angles, cracks and hanging edges finish") {
  for (const char *name : {"img1", "butterfly", "clusters", "simplified-us-border", "island",
                           "kidney", "square_with_crack", "ditch", "overlapping_constraints"})
    for (const char *switches : {"pq30", "pcq30", "pq33"}) {
      INFO(std::string(name));
      refine_checked(load("pslg", name), switches);
    }
}

TEST_CASE("quality pslg: a fan of segments one degree apart") {
  // Forty segments from the origin, one degree apart, closed by a polyline around them: every
  // pair of neighbouring segments meets at an angle far below the bound.
  clmesh::Input fan;
  fan.points.push_back({0, 0});
  const int spokes = 40;
  for (int k = 0; k < spokes; ++k) {
    const double angle = (10 + k) * M_PI / 180;
    fan.points.push_back({std::cos(angle), std::sin(angle)});
    fan.segments.push_back({0, k + 1, 0});
    if (k > 0)
      fan.segments.push_back({k, k + 1, 0});
  }
  fan.segments.push_back({1, spokes, 0}); // closes it around the outside
  const clmesh::Mesh mesh = refine_checked(fan, "pq30");
  CHECK(mesh.statistics.refinement.remaining_bad > 0);
  refine_checked(fan, "pq20a0.01");
}

TEST_CASE("quality pslg: the same mesh whatever the work-group size") {
  const clmesh::Input water = load("pslg", "water2");
  clmesh::Options options = clmesh::parse_switches("pq30");
  const clmesh::Mesh reference = clmesh::triangulate(device(), water, options);
  for (int work_group : {16, 64}) {
    options.tuning.work_group = work_group;
    test_support::check_same_mesh(clmesh::triangulate(device(), water, options), reference);
  }
}

TEST_CASE("quality pslg: the Steiner point limit (-S) is obeyed") {
  const clmesh::Input water = load("pslg", "water2");
  const clmesh::Mesh mesh = clmesh::triangulate(device(), water, "pq30S100");
  const clmesh::Mesh cdt = clmesh::triangulate(device(), water, "p");
  CHECK(mesh.points.size() == cdt.points.size() + 100);
  CHECK(mesh.statistics.refinement.stop_reason == clmesh::RefineStop::steiner_limit);
  CHECK(clmesh::check_mesh(water, mesh, clmesh::parse_switches("pq30S100")).ok);
}

TEST_CASE("quality pslg: -D makes every triangle Delaunay, subsegments included") {
  for (const char *name : {"A", "face", "la"})
    for (const char *switches : {"pD", "pq25D", "pq30a0.5D"}) {
      INFO(std::string(name));
      refine_checked(load("triangle-examples/inputs", name), switches);
    }
  const clmesh::Input water = load("pslg", "water2");
  const clmesh::Mesh conforming = refine_checked(water, "pq25D");
  // The check of -D tests the subsegments too: the same input's -pq25 mesh, only constrained
  // Delaunay, fails it.
  const clmesh::Mesh constrained = refine_checked(water, "pq25");
  CHECK(clmesh::check_mesh(water, conforming, clmesh::parse_switches("pq25D")).ok);
  CHECK_FALSE(clmesh::check_mesh(water, constrained, clmesh::parse_switches("pq25D")).ok);
  CHECK(conforming.points.size() > constrained.points.size());
}

TEST_CASE("quality pslg: above about 33 degrees refinement stops at its limit, or -S's") {
  // la.poly at -q34.5: Triangle ends there, clmesh's refinement does not; it stops at 100
  // Steiner points per input point, with a valid mesh, the same on every run.
  const clmesh::Input la = load("triangle-examples/inputs", "la");
  const clmesh::Options options = clmesh::parse_switches("pq34.5");
  const clmesh::Mesh mesh = clmesh::triangulate(device(), la, options);
  CHECK(mesh.statistics.refinement.stop_reason == clmesh::RefineStop::angle_bound);
  const long steiner = static_cast<long>(mesh.points.size()) - mesh.input_points;
  CHECK(steiner <= 100 * mesh.input_points);
  CHECK(steiner > 90 * mesh.input_points);
  CHECK(mesh.statistics.refinement.remaining_bad > 0);
  INFO(problems(clmesh::check_mesh(la, mesh, options)));
  CHECK(clmesh::check_mesh(la, mesh, options).ok);
  test_support::check_same_mesh(clmesh::triangulate(device(), la, options), mesh);
  const clmesh::Mesh capped = clmesh::triangulate(device(), la, "pq34.5S500");
  CHECK(capped.statistics.refinement.stop_reason == clmesh::RefineStop::steiner_limit);
  CHECK(static_cast<long>(capped.points.size()) - capped.input_points == 500);
}

namespace {

// The index in `mesh` of a triangle that holds point p (inside or on its boundary), or -1.
long containing_triangle(const clmesh::Mesh &mesh, Point p) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    bool inside = true;
    for (int i = 0; i < 3 && inside; ++i) {
      const Point a = mesh.points[mesh.triangles[t][i]],
                  b = mesh.points[mesh.triangles[t][(i + 1) % 3]];
      inside = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) >= 0;
    }
    if (inside)
      return static_cast<long>(t);
  }
  return -1;
}

} // namespace

TEST_CASE("quality pslg: regional area bounds (-a alone) and attributes (-A) on refined meshes") {
  // la.poly: six regions whose lines give no maximum area, so each takes its attribute as its
  // bound (as Triangle reads them). Each refined triangle's region is found independently:
  // the -pA mesh's triangle (not refined) that holds its centroid.
  const clmesh::Input la = load("triangle-examples/inputs", "la");
  const clmesh::Mesh regions = clmesh::triangulate(device(), la, "pA");
  REQUIRE(regions.triangle_attribute_count == 1);
  for (const char *switches : {"pAa", "pAq30a", "pAq25a0.1a", "pAq30"}) {
    INFO(switches);
    const clmesh::Options options = clmesh::parse_switches(switches);
    const clmesh::Mesh mesh = refine_checked(la, switches);
    REQUIRE(mesh.triangle_attribute_count == 1);
    REQUIRE(mesh.triangle_attributes.size() == mesh.triangles.size());
    long wrong_region = 0, above_bound = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const Point a = mesh.points[mesh.triangles[t][0]], b = mesh.points[mesh.triangles[t][1]],
                  c = mesh.points[mesh.triangles[t][2]];
      const long container =
          containing_triangle(regions, {(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3});
      REQUIRE(container >= 0);
      const double attribute = regions.triangle_attributes[static_cast<std::size_t>(container)];
      wrong_region += mesh.triangle_attributes[t] != attribute;
      double bound = options.max_area.value_or(INFINITY);
      if (options.regional_areas)
        for (const clmesh::Region &region : la.regions)
          if (region.attribute == attribute && region.max_area > 0)
            bound = std::min(bound, region.max_area);
      above_bound += area(mesh.points, mesh.triangles[t]) > bound * (1 + 1e-9);
    }
    CHECK(wrong_region == 0);
    CHECK(above_bound == 0);
  }
  // A region's bound refines its region only: without -a alone the mesh is coarser.
  CHECK(clmesh::triangulate(device(), la, "pq30").points.size() * 1.2 <
        clmesh::triangulate(device(), la, "pq30a").points.size());
  CHECK_THROWS_AS(clmesh::validate(clmesh::parse_switches("qa")), clmesh::OptionError);
}

TEST_CASE("quality pslg: -Y puts no Steiner point on the boundary, -YY none on any segment") {
  for (const char *name : {"A", "face", "la"}) {
    INFO(std::string(name));
    const clmesh::Input pslg = load("triangle-examples/inputs", name);
    const clmesh::Mesh cdt = clmesh::triangulate(device(), pslg, "p");
    const auto first_steiner = static_cast<int32_t>(cdt.points.size());
    for (const char *switches : {"pq30Y", "pq30a1YY", "pYa0.5"}) {
      INFO(switches);
      const clmesh::Options options = clmesh::parse_switches(switches);
      const clmesh::Mesh mesh = clmesh::triangulate(device(), pslg, options);
      INFO(problems(clmesh::check_mesh(pslg, mesh, options)));
      CHECK(clmesh::check_mesh(pslg, mesh, options).ok);
      REQUIRE(test_support::starts_with(mesh.points, cdt.points));
      CHECK(std::fabs(static_cast<double>(total_area(mesh) - total_area(cdt))) <=
            1e-9 * static_cast<double>(total_area(cdt)));
      long on_boundary = 0, on_segment = 0;
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (int i = 0; i < 3; ++i)
          if (mesh.neighbors[t][i] < 0)
            on_boundary += mesh.triangles[t][(i + 1) % 3] >= first_steiner;
      for (const Segment &s : mesh.segments)
        on_segment += s.a >= first_steiner || s.b >= first_steiner;
      CHECK(on_boundary == 0);
      if (options.no_steiner_on_segments == 2) {
        CHECK(on_segment == 0);
        CHECK(mesh.segments.size() == cdt.segments.size());
      }
      if (options.quality)
        CHECK(mesh.points.size() > cdt.points.size());
      CHECK(mesh.statistics.refinement.stop_reason == clmesh::RefineStop::done);
    }
  }
}
