// The library's -v and -o2 results, checked independently of how they are
// computed: the Voronoi vertices are circumcentres within the documented
// bound (distances to the corners compared in long double), the Voronoi edges
// are dual to the mesh's edges (finite ones perpendicular to them, rays along
// the outward normals of hull edges); the -o2 middle nodes are the midpoints
// of the edges rounded once, shared by the two triangles of their edge.
#include <doctest/doctest.h>

#include "clmesh/clmesh.hpp"
#include "mesh_fixtures.hpp"
#include "test_support.hpp"

#ifdef CLMESH_HAVE_CGAL
#include <CGAL/Exact_rational.h>
#endif

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

using clmesh::Point;
using test_support::check_same_mesh;
using test_support::device;

namespace {

using Real = long double;
constexpr Real kEps = 0x1p-53L; // half an ulp of 1.0 in double

// Hull edges of a mesh: neighbour entries -1.
std::size_t hull_edges(const clmesh::Mesh &mesh) {
  std::size_t hull = 0;
  for (const auto &across : mesh.neighbors)
    for (int32_t other : across)
      hull += other == -1;
  return hull;
}

std::size_t edge_count(const clmesh::Mesh &mesh) {
  return (3 * mesh.triangles.size() + hull_edges(mesh)) / 2;
}

// The documented bound on the error of the circumcentre of triangle t, as a
// length: per coordinate 4 eps |offset from the first corner| + eps |coordinate|.
Real center_error_bound(const clmesh::Mesh &mesh, std::size_t t) {
  const Point &c = mesh.voronoi_points[t], &a = mesh.points[mesh.triangles[t][0]];
  const Real bx = 4 * kEps * std::fabs(Real(c.x) - a.x) + kEps * std::fabs(Real(c.x));
  const Real by = 4 * kEps * std::fabs(Real(c.y) - a.y) + kEps * std::fabs(Real(c.y));
  return std::sqrt(bx * bx + by * by);
}

Real distance(const Point &p, const Point &q) {
  const Real dx = Real(p.x) - q.x, dy = Real(p.y) - q.y;
  return std::sqrt(dx * dx + dy * dy);
}

#ifdef CLMESH_HAVE_CGAL
// Each circumcentre against the exact one (rational arithmetic), per
// coordinate within the documented bound and the exact value's own rounding.
void check_exact_centers(const clmesh::Mesh &mesh) {
  using Q = CGAL::Exact_rational;
  std::size_t off = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Point &a = mesh.points[mesh.triangles[t][0]], &b = mesh.points[mesh.triangles[t][1]],
                &c = mesh.points[mesh.triangles[t][2]];
    const Q bx = Q(b.x) - Q(a.x), by = Q(b.y) - Q(a.y), cx = Q(c.x) - Q(a.x), cy = Q(c.y) - Q(a.y);
    const Q b2 = bx * bx + by * by, c2 = cx * cx + cy * cy, d2 = 2 * (bx * cy - by * cx);
    const Q x = Q(a.x) + (cy * b2 - by * c2) / d2, y = Q(a.y) + (bx * c2 - cx * b2) / d2;
    const Point &got = mesh.voronoi_points[t];
    const double exact[2] = {CGAL::to_double(x), CGAL::to_double(y)};
    const double computed[2] = {got.x, got.y}, origin[2] = {a.x, a.y};
    for (int k = 0; k < 2; ++k) {
      const Real ulp = std::nextafter(std::fabs(exact[k]), INFINITY) - std::fabs(exact[k]);
      const Real bound =
          4 * kEps * std::fabs(Real(exact[k]) - origin[k]) + kEps * std::fabs(Real(exact[k])) + ulp;
      if (std::fabs(Real(computed[k]) - exact[k]) > bound) {
        ++off;
        INFO("triangle " << t << " coordinate " << k << ": " << computed[k] << ", exact "
                         << exact[k]);
        CHECK(false);
      }
    }
  }
  CHECK(off == 0);
}
#endif

// Every property of Triangle's Voronoi diagram of `mesh`.
void check_voronoi(const clmesh::Mesh &mesh) {
  const std::size_t triangles = mesh.triangles.size();
  REQUIRE(mesh.voronoi_points.size() == triangles);
  REQUIRE(mesh.voronoi_point_attributes.size() ==
          triangles * static_cast<std::size_t>(mesh.attribute_count));
  REQUIRE(mesh.voronoi_edges.size() == edge_count(mesh));
  // The vertices: equidistant from the corners.
  std::size_t far = 0;
  for (std::size_t t = 0; t < triangles; ++t) {
    const Point &c = mesh.voronoi_points[t];
    Real r[3];
    for (int i = 0; i < 3; ++i)
      r[i] = distance(c, mesh.points[mesh.triangles[t][i]]);
    const Real tolerance = 2 * center_error_bound(mesh, t) + 64 * 0x1p-64L * r[0];
    for (int i = 1; i < 3; ++i)
      if (std::fabs(r[i] - r[0]) > tolerance) {
        ++far;
        INFO("triangle " << t << ": radii " << double(r[0]) << " and " << double(r[i])
                         << " differ by " << double(std::fabs(r[i] - r[0])) << " > "
                         << double(tolerance));
        CHECK(false);
      }
  }
  CHECK(far == 0);
  // The edges: each pair of neighbours once, each hull edge once as a ray.
  std::set<std::pair<int32_t, int32_t>> pairs;
  std::set<std::pair<int32_t, int>> rays; // (triangle, its hull edge)
  for (const clmesh::VoronoiEdge &edge : mesh.voronoi_edges) {
    REQUIRE(edge.a >= 0);
    REQUIRE(static_cast<std::size_t>(edge.a) < triangles);
    const clmesh::Triangle &ta = mesh.triangles[edge.a];
    if (edge.b >= 0) {
      REQUIRE(static_cast<std::size_t>(edge.b) < triangles);
      CHECK(pairs.insert({std::min(edge.a, edge.b), std::max(edge.a, edge.b)}).second);
      int side = -1;
      for (int i = 0; i < 3; ++i)
        if (mesh.neighbors[edge.a][i] == edge.b)
          side = i;
      REQUIRE(side >= 0); // the two triangles are neighbours
      // Perpendicular to the shared mesh edge, within both centres' bounds.
      const Point &p = mesh.points[ta[(side + 1) % 3]], &q = mesh.points[ta[(side + 2) % 3]];
      const Point &ca = mesh.voronoi_points[edge.a], &cb = mesh.voronoi_points[edge.b];
      const Real ex = Real(q.x) - p.x, ey = Real(q.y) - p.y;
      const Real dot = (Real(cb.x) - ca.x) * ex + (Real(cb.y) - ca.y) * ey;
      const Real length = std::sqrt(ex * ex + ey * ey);
      const Real tolerance =
          (center_error_bound(mesh, edge.a) + center_error_bound(mesh, edge.b)) * length * 1.001L +
          64 * 0x1p-64L * distance(ca, cb) * length;
      CHECK(std::fabs(dot) <= tolerance);
      CHECK(edge.direction.x == 0);
      CHECK(edge.direction.y == 0);
    } else {
      CHECK(edge.b == -1);
      int side = -1;
      for (int i = 0; i < 3; ++i)
        if (mesh.neighbors[edge.a][i] == -1 && !rays.count({edge.a, i})) {
          const Point &p = mesh.points[ta[(i + 1) % 3]], &q = mesh.points[ta[(i + 2) % 3]];
          if (edge.direction.x == q.y - p.y && edge.direction.y == p.x - q.x)
            side = i;
        }
      REQUIRE(side >= 0); // the hull edge's normal, as Triangle computes it
      rays.insert({edge.a, side});
      // Outward: away from the triangle's third corner.
      const Point &p = mesh.points[ta[(side + 1) % 3]], &apex = mesh.points[ta[side]];
      CHECK(Real(edge.direction.x) * (Real(apex.x) - p.x) +
                Real(edge.direction.y) * (Real(apex.y) - p.y) <
            0);
    }
  }
  CHECK(rays.size() == hull_edges(mesh));
#ifdef CLMESH_HAVE_CGAL
  check_exact_centers(mesh);
#endif
}

// Every property of the -o2 middle nodes of `mesh` (no -p: markers 1 on the hull).
void check_second_order(const clmesh::Mesh &mesh, bool hull_markers) {
  const std::size_t edges = edge_count(mesh), attributes = mesh.attribute_count;
  REQUIRE(mesh.edge_midpoints.size() == edges);
  REQUIRE(mesh.edge_midpoint_markers.size() == edges);
  REQUIRE(mesh.edge_midpoint_attributes.size() == edges * attributes);
  REQUIRE(mesh.triangle_midpoints.size() == mesh.triangles.size());
  std::vector<int> uses(edges, 0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int32_t k = mesh.triangle_midpoints[t][i];
      REQUIRE(k >= 0);
      REQUIRE(static_cast<std::size_t>(k) < edges);
      ++uses[k];
      const int32_t a = mesh.triangles[t][(i + 1) % 3], b = mesh.triangles[t][(i + 2) % 3];
      const Point &p = mesh.points[a], &q = mesh.points[b], &m = mesh.edge_midpoints[k];
      // The exact midpoint, rounded once: within half an ulp of it.
      for (const auto &[got, exact] : {std::pair<double, Real>{m.x, (Real(p.x) + q.x) / 2},
                                       std::pair<double, Real>{m.y, (Real(p.y) + q.y) / 2}}) {
        const Real ulp = std::nextafter(std::fabs(got), INFINITY) - std::fabs(got);
        CHECK(std::fabs(got - exact) <= ulp / 2 + 0x1p-63L * std::fabs(exact));
      }
      for (std::size_t j = 0; j < attributes; ++j)
        CHECK(mesh.edge_midpoint_attributes[k * attributes + j] ==
              doctest::Approx((mesh.point_attributes[a * attributes + j] +
                               mesh.point_attributes[b * attributes + j]) /
                              2));
      const int32_t across = mesh.neighbors[t][i];
      if (hull_markers)
        CHECK(mesh.edge_midpoint_markers[k] == (across == -1 ? 1 : 0));
      if (across >= 0) // the same node in the triangle across the edge
        for (int j = 0; j < 3; ++j) {
          const int32_t v = mesh.triangles[across][j];
          if (v != a && v != b)
            CHECK(mesh.triangle_midpoints[across][j] == k);
        }
    }
  for (std::size_t k = 0; k < edges; ++k)
    CHECK((uses[k] == 1 || uses[k] == 2));
}

clmesh::Mesh mesh_of(const std::vector<Point> &points, const std::string &switches) {
  clmesh::Input input;
  input.points = points;
  return clmesh::triangulate(device(), input, switches);
}

} // namespace

TEST_CASE("outputs: the Voronoi diagram (-v) of point sets, quality meshes and PSLGs") {
  const std::string inputs = std::string(CLMESH_SHARED_DATA) + "/triangle-examples/inputs/";
  SUBCASE("uniform points; the mesh is the same as without -v") {
    const auto points = fixtures::uniform(3000, 11);
    const clmesh::Mesh mesh = mesh_of(points, "v");
    check_voronoi(mesh);
    check_same_mesh(mesh, mesh_of(points, ""));
  }
  SUBCASE("cocircular points (a lattice, Triangle's diamond example)") {
    check_voronoi(mesh_of(fixtures::lattice(20), "v"));
    check_voronoi(
        clmesh::triangulate(device(), clmesh::read_input(inputs + "diamond_02_00009.node"), "v"));
  }
  SUBCASE("a quality mesh and a PSLG with attributes") {
    check_voronoi(mesh_of(fixtures::disk(500, 3), "q30v"));
    const clmesh::Mesh a =
        clmesh::triangulate(device(), clmesh::read_input(inputs + "A.poly"), "pv");
    REQUIRE(a.attribute_count == 1);
    check_voronoi(a);
  }
  SUBCASE("a nearly flat triangle: its far circumcentre keeps the bound") {
    // (0.4, 0.41 + 1e-11) lies 1e-11 above the line through the first two
    // points: a hull triangle whose circumcentre is about 1e10 away. A
    // circumcentre computed from rounded differences misses it by far more.
    const std::vector<Point> points = {{0.1, 0.2}, {0.7, 0.62}, {0.4, 0.41 + 1e-11},
                                       {0.1, 1.0}, {0.4, 1.0},  {0.7, 1.0}};
    const clmesh::Mesh mesh = mesh_of(points, "v");
    check_voronoi(mesh);
    double farthest = 0;
    for (const Point &c : mesh.voronoi_points)
      farthest = std::max(farthest, std::hypot(c.x, c.y));
    CHECK(farthest > 1e8);
  }
  SUBCASE("scaled from 1e-30 to 1e30, the bound holds") {
    for (const double scale : {1e-30, 1e-9, 1e9, 1e30}) {
      CAPTURE(scale);
      std::vector<Point> points = fixtures::disk(300, 17);
      points.push_back({0.1, 0.2});
      points.push_back({0.7, 0.62});
      points.push_back({0.4, 0.41 + 1e-11});
      for (Point &p : points)
        p = {p.x * scale, p.y * scale};
      check_voronoi(mesh_of(points, "v"));
    }
  }
  SUBCASE("attributes are interpolated: a linear field is reproduced") {
    clmesh::Input input;
    input.points = fixtures::uniform(400, 5);
    input.attribute_count = 1;
    for (const Point &p : input.points)
      input.point_attributes.push_back(2 * p.x - 3 * p.y + 1);
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, "v");
    check_voronoi(mesh);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const Point &c = mesh.voronoi_points[t];
      const double scale = 1 + std::fabs(c.x) + std::fabs(c.y);
      CHECK(std::fabs(mesh.voronoi_point_attributes[t] - (2 * c.x - 3 * c.y + 1)) <= 1e-9 * scale);
    }
  }
  SUBCASE("collinear points: no triangle, no Voronoi diagram") {
    const clmesh::Mesh mesh = mesh_of({{0, 0}, {1, 1}, {2, 2}}, "v");
    CHECK(mesh.voronoi_points.empty());
    CHECK(mesh.voronoi_edges.empty());
  }
}

TEST_CASE("outputs: second-order triangles (-o2)") {
  SUBCASE("a point set with attributes; the mesh is the same as without -o2") {
    clmesh::Input input;
    input.points = fixtures::gaussian(2000, 7);
    input.attribute_count = 2;
    for (const Point &p : input.points)
      input.point_attributes.insert(input.point_attributes.end(), {p.x * p.y, 1 - p.x});
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, "o2");
    check_second_order(mesh, true);
    check_same_mesh(mesh, clmesh::triangulate(device(), input, ""));
    CHECK(clmesh::triangulate(device(), input, "").edge_midpoints.empty());
  }
  SUBCASE("a quality mesh, and the order of -e's edges") {
    const clmesh::Mesh mesh = mesh_of(fixtures::disk(300, 9), "q30o2e");
    check_second_order(mesh, true);
    REQUIRE(mesh.edges.size() == mesh.edge_midpoints.size());
    for (std::size_t k = 0; k < mesh.edges.size(); ++k) {
      const Point &p = mesh.points[mesh.edges[k].a], &q = mesh.points[mesh.edges[k].b];
      CHECK(mesh.edge_midpoints[k].x == (p.x + q.x) * 0.5);
      CHECK(mesh.edge_midpoints[k].y == (p.y + q.y) * 0.5);
    }
  }
  SUBCASE("a PSLG: middle nodes on segments take the segment's marker") {
    clmesh::Input input;
    input.points = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 1}};
    input.segments = {{0, 1, 7}, {1, 2, 0}, {2, 3, 0}, {3, 0, 0}};
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, "po2");
    check_second_order(mesh, false);
    std::map<std::pair<double, double>, int> marker_at;
    for (std::size_t k = 0; k < mesh.edge_midpoints.size(); ++k)
      marker_at[{mesh.edge_midpoints[k].x, mesh.edge_midpoints[k].y}] =
          mesh.edge_midpoint_markers[k];
    CHECK(marker_at.at({1, 0}) == 7);
    CHECK(marker_at.at({2, 1}) == 1); // a segment marked 0 on the boundary
    CHECK(marker_at.at({0.5, 0.5}) == 0);
  }
}
