// Size control beyond -a: a sizing field the device evaluates (a background
// mesh's target areas interpolated at each triangle's centroid) and a user's
// callback the host runs (Triangle's triunsuitable). Every triangle must
// meet the field at its centroid, the mesh must grade with the field, and
// the callback that asks what the field asks must give the same mesh.
#include <doctest/doctest.h>

#include "clmesh/clmesh.hpp"
#include "test_support.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

using clmesh::Point;
using test_support::area;
using test_support::device;
using test_support::problems;
using test_support::smallest_angle_degrees;

namespace {

// Over the unit square: `left` at x = 0, half of it at x = 1 (a background
// mesh of two triangles, so linear in x).
std::shared_ptr<const clmesh::SizeField> halving_field(double left) {
  auto field = std::make_shared<clmesh::SizeField>();
  field->points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  field->area = {left, left / 2, left / 2, left};
  field->triangles = {{0, 1, 2}, {0, 2, 3}};
  return field;
}

Point centroid(const clmesh::Mesh &mesh, const clmesh::Triangle &t) {
  const Point a = mesh.points[t[0]], b = mesh.points[t[1]], c = mesh.points[t[2]];
  return {(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3};
}

// Every triangle meets the field at its centroid; when `graded`, the
// triangles in the field's large end are larger, on average, than those in
// its small end.
void check_meets_field(const clmesh::Mesh &mesh, const clmesh::SizeField &field,
                       bool graded = true) {
  double left = 0, right = 0;
  long left_count = 0, right_count = 0;
  for (const auto &t : mesh.triangles) {
    const Point c = centroid(mesh, t);
    const double a = area(mesh.points, t);
    CHECK(a <= clmesh::size_at(field, c) * (1 + 1e-9));
    if (c.x < 0.25) {
      left += a;
      ++left_count;
    } else if (c.x > 0.75) {
      right += a;
      ++right_count;
    }
  }
  REQUIRE(left_count > 0);
  REQUIRE(right_count > 0);
  if (graded)
    CHECK(left / left_count > 1.3 * (right / right_count));
}

clmesh::Input unit_square() {
  clmesh::Input input;
  input.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.31, 0.47}, {0.62, 0.23}};
  input.segments = {{0, 1, 1}, {1, 2, 1}, {2, 3, 1}, {3, 0, 1}};
  return input;
}

} // namespace

TEST_CASE("size field: every triangle meets the field at its centroid, graded with it") {
  const auto field = halving_field(0.002);
  const clmesh::Input input = unit_square();
  for (const char *switches : {"", "q30", "p", "pq25", "pq30a0.0012"}) {
    INFO(std::string(switches));
    clmesh::Options options = clmesh::parse_switches(switches);
    options.size_field = field;
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, options);
    CHECK(mesh.statistics.refined);
    CHECK(mesh.statistics.refinement.stop_reason == clmesh::RefineStop::done);
    const auto report = clmesh::check_mesh(input, mesh, options);
    INFO(problems(report));
    CHECK(report.ok);
    // About the field's area over its mean target (0.0015) at least.
    CHECK(mesh.triangles.size() > 600);
    // A global -a below most of the field leaves little grading.
    check_meets_field(mesh, *field, !options.max_area);
    if (options.quality)
      for (const auto &t : mesh.triangles)
        CHECK(smallest_angle_degrees(mesh.points, t) >= options.min_angle - 1e-6);
    if (options.max_area)
      for (const auto &t : mesh.triangles)
        CHECK(area(mesh.points, t) <= *options.max_area * (1 + 1e-9));
  }
}

TEST_CASE("size field: a mesh that outgrows its first room, several times") {
  // The first room knows nothing of the field, which asks for thousands of
  // times the input's points: the arrays grow while candidates wait, and the
  // search starts over on the grown mesh.
  auto field = std::make_shared<clmesh::SizeField>(*halving_field(1e-4));
  const clmesh::Input input = unit_square();
  clmesh::Options options = clmesh::parse_switches("pq25");
  options.size_field = field;
  const clmesh::Mesh mesh = clmesh::triangulate(device(), input, options);
  CHECK(mesh.statistics.refinement.stop_reason == clmesh::RefineStop::done);
  CHECK(mesh.statistics.refinement.growths >= 2);
  CHECK(mesh.points.size() > 10000);
  const auto report = clmesh::check_mesh(input, mesh, options);
  INFO(problems(report));
  CHECK(report.ok);
  check_meets_field(mesh, *field);
  // The same mesh whether the steps of an iteration run in one work-group
  // (the search placing its candidates in the same launch, while growth
  // waits for room) or as separate kernels.
  for (const std::size_t limit : {std::size_t{0}, std::size_t{1} << 30}) {
    CAPTURE(limit);
    options.tuning.group_step_limit = limit;
    const clmesh::Mesh other = clmesh::triangulate(device(), input, options);
    CHECK(other.statistics.refinement.growths == mesh.statistics.refinement.growths);
    CHECK(other.triangles == mesh.triangles);
    REQUIRE(other.points.size() == mesh.points.size());
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
      CHECK((other.points[i].x == mesh.points[i].x && other.points[i].y == mesh.points[i].y));
  }
}

TEST_CASE("size field: a callback that asks what the field asks gives the same mesh") {
  const auto field = halving_field(0.004);
  const clmesh::Input input = unit_square();
  for (const char *switches : {"q25", "pq30"}) {
    INFO(std::string(switches));
    clmesh::Options by_field = clmesh::parse_switches(switches);
    by_field.size_field = field;
    clmesh::Options by_callback = clmesh::parse_switches(switches);
    long asked = 0;
    by_callback.unsuitable = [&](Point a, Point b, Point c, double triangle_area) {
      ++asked;
      const Point middle{(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3};
      return triangle_area > clmesh::size_at(*field, middle);
    };
    const clmesh::Mesh expected = clmesh::triangulate(device(), input, by_field);
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, by_callback);
    CHECK(asked >= static_cast<long>(mesh.triangles.size()));
    test_support::check_same_mesh(mesh, expected);
    check_meets_field(mesh, *field);
  }
}

TEST_CASE("size field: what the callback throws reaches the caller, bad fields are refused") {
  const clmesh::Input input = unit_square();
  clmesh::Options options = clmesh::parse_switches("pq");
  long asked = 0;
  options.unsuitable = [&](Point, Point, Point, double) -> bool {
    if (++asked > 5)
      throw std::runtime_error("the solver's estimate failed");
    return true;
  };
  CHECK_THROWS_WITH_AS(clmesh::triangulate(device(), input, options),
                       "the solver's estimate failed", std::runtime_error);
  // The device is still usable after the throw.
  options.unsuitable = nullptr;
  CHECK(clmesh::triangulate(device(), input, options).triangles.size() > 0);

  auto field = std::make_shared<clmesh::SizeField>(*halving_field(0.01));
  options.size_field = field;
  field->area[2] = 0;
  CHECK_THROWS_AS(clmesh::triangulate(device(), input, options), clmesh::InputError);
  field->area[2] = 0.01;
  field->area.pop_back();
  CHECK_THROWS_AS(clmesh::triangulate(device(), input, options), clmesh::InputError);
  field->area.push_back(0.01);
  field->triangles[1] = {0, 3, 2};
  CHECK_THROWS_AS(clmesh::triangulate(device(), input, options), clmesh::InputError);
  field->triangles[1] = {0, 2, 7};
  CHECK_THROWS_AS(clmesh::triangulate(device(), input, options), clmesh::InputError);
}

TEST_CASE("size field: a refined mesh (-r) follows the field too, beyond the background mesh") {
  // The field covers the left half only; the right half takes the values
  // at its edge x = 0.5.
  auto field = std::make_shared<clmesh::SizeField>();
  field->points = {{0, 0}, {0.5, 0}, {0.5, 1}, {0, 1}};
  field->area = {0.004, 0.002, 0.002, 0.004};
  field->triangles = {{0, 1, 2}, {0, 2, 3}};
  clmesh::Input first = unit_square();
  const clmesh::Mesh coarse = clmesh::triangulate(device(), first, "pq");
  clmesh::Input given;
  given.points = coarse.points;
  given.triangles = coarse.triangles;
  clmesh::Options options = clmesh::parse_switches("rq30");
  options.size_field = field;
  const clmesh::Mesh mesh = clmesh::triangulate(device(), given, options);
  const auto report = clmesh::check_mesh(given, mesh, options);
  INFO(problems(report));
  CHECK(report.ok);
  for (const auto &t : mesh.triangles) {
    const Point c = centroid(mesh, t);
    CHECK(area(mesh.points, t) <= clmesh::size_at(*field, c) * (1 + 1e-9));
    if (c.x > 0.5) // clamped to the edge x = 0.5
      CHECK(clmesh::size_at(*field, c) == doctest::Approx(0.002));
  }
}
