// Tests of the exact triangulation checker (host/check.cpp).
#include <doctest/doctest.h>

#include "clmesh/check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#ifdef CLMESH_HAVE_CGAL
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#endif

using clmesh::check_triangulation;
using clmesh::CheckReport;
using clmesh::Point;
using clmesh::Triangle;
using Neighbors = std::vector<std::array<int32_t, 3>>;

namespace {

struct Mesh {
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  Neighbors neighbors;
  std::vector<int32_t> duplicate_of;

  CheckReport check(bool delaunay = true) const {
    return check_triangulation(points, triangles, neighbors, duplicate_of, delaunay);
  }
};

std::string problems(const CheckReport &report) {
  std::string all;
  for (const std::string &p : report.problems)
    all += "\n  " + p;
  return all;
}

bool mentions(const CheckReport &report, const std::string &word) {
  for (const std::string &p : report.problems)
    if (p.find(word) != std::string::npos)
      return true;
  return false;
}

// Fills neighbours from the triangles (the side opposite vertex i is (v[i+1], v[i+2])).
Neighbors build_neighbors(const std::vector<Triangle> &triangles) {
  std::map<std::pair<int32_t, int32_t>, std::pair<int32_t, int32_t>> sides;
  for (int32_t t = 0; t < int32_t(triangles.size()); ++t)
    for (int32_t i = 0; i < 3; ++i)
      sides[{triangles[t][(i + 1) % 3], triangles[t][(i + 2) % 3]}] = {t, i};
  Neighbors nb(triangles.size(), {-1, -1, -1});
  for (int32_t t = 0; t < int32_t(triangles.size()); ++t)
    for (int32_t i = 0; i < 3; ++i) {
      auto it = sides.find({triangles[t][(i + 2) % 3], triangles[t][(i + 1) % 3]});
      if (it != sides.end())
        nb[t][i] = it->second.first;
    }
  return nb;
}

Mesh make_mesh(std::vector<Point> points, std::vector<Triangle> triangles) {
  Mesh m;
  m.points = std::move(points);
  m.triangles = std::move(triangles);
  m.neighbors = build_neighbors(m.triangles);
  m.duplicate_of.assign(m.points.size(), -1);
  return m;
}

// The unit square split along (1,0)-(0,1): the diagonal the perturbed in-circle test keeps.
Mesh square() { return make_mesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0, 1, 3}, {1, 2, 3}}); }

// Removes triangle t, turning its neighbours' links to it into boundary links.
void remove_triangle(Mesh &m, int32_t t) {
  for (auto &nb : m.neighbors)
    for (int32_t &u : nb)
      if (u == t)
        u = -1;
      else if (u > t)
        --u;
  m.triangles.erase(m.triangles.begin() + t);
  m.neighbors.erase(m.neighbors.begin() + t);
}

#ifdef CLMESH_HAVE_CGAL
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int32_t, K>;
using Fb = CGAL::Triangulation_face_base_with_info_2<int32_t, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using DT = CGAL::Delaunay_triangulation_2<K, Tds>;

// CGAL's Delaunay triangulation of the points as triangles + neighbours (finite faces only).
Mesh cgal_delaunay(const std::vector<Point> &points) {
  std::vector<std::pair<K::Point_2, int32_t>> input;
  for (int32_t i = 0; i < int32_t(points.size()); ++i)
    input.push_back({K::Point_2(points[i].x, points[i].y), i});
  DT dt(input.begin(), input.end());
  Mesh m;
  m.points = points;
  m.duplicate_of.assign(points.size(), -1);
  // Points CGAL merged: mark them duplicates of the vertex it kept.
  std::map<std::pair<double, double>, int32_t> kept;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
    kept[{v->point().x(), v->point().y()}] = v->info();
  for (int32_t i = 0; i < int32_t(points.size()); ++i) {
    const int32_t k = kept.at({points[i].x, points[i].y});
    if (k != i)
      m.duplicate_of[i] = k;
  }
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    f->info() = int32_t(m.triangles.size());
    m.triangles.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  }
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    std::array<int32_t, 3> nb;
    for (int i = 0; i < 3; ++i)
      nb[i] = dt.is_infinite(f->neighbor(i)) ? -1 : f->neighbor(i)->info();
    m.neighbors.push_back(nb);
  }
  return m;
}

std::vector<Point> random_points(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Point> pts(n);
  for (Point &p : pts)
    p = {u(rng), u(rng)};
  return pts;
}

// Flips the edge opposite vertex i of triangle t (a convex quadrilateral), keeping every
// triangle counter-clockwise and every neighbour link consistent.
void flip(Mesh &m, int32_t t, int32_t i) {
  const int32_t u = m.neighbors[t][i];
  REQUIRE(u >= 0);
  int32_t j = 0;
  while (m.neighbors[u][j] != t)
    ++j;
  const int32_t a = m.triangles[t][i], b = m.triangles[t][(i + 1) % 3],
                c = m.triangles[t][(i + 2) % 3], d = m.triangles[u][j];
  // t = (a, b, c), u = (d, c, b); after the flip t = (a, b, d), u = (d, c, a).
  const int32_t n_ab = m.neighbors[t][(i + 2) % 3], n_ca = m.neighbors[t][(i + 1) % 3];
  const int32_t n_bd = m.neighbors[u][(j + 1) % 3], n_dc = m.neighbors[u][(j + 2) % 3];
  m.triangles[t] = {a, b, d};
  m.triangles[u] = {d, c, a};
  m.neighbors[t] = {n_bd, u, n_ab};
  m.neighbors[u] = {n_ca, t, n_dc};
  auto relink = [&](int32_t w, int32_t from, int32_t to) {
    if (w < 0)
      return;
    for (int32_t &x : m.neighbors[w])
      if (x == from)
        x = to;
  };
  relink(n_bd, u, t);
  relink(n_ca, t, u);
}
#endif

} // namespace

TEST_CASE("check: accepts a correctly split square") {
  const Mesh m = square();
  const CheckReport r = m.check();
  INFO(problems(r));
  CHECK(r.ok);
  CHECK(r.problems.empty());
}

TEST_CASE("check: square split along the other diagonal is valid but not Delaunay") {
  // (0,0),(1,0),(1,1),(0,1) are cocircular: only the symbolic perturbation decides, and it
  // keeps the diagonal (1,0)-(0,1).
  const Mesh m = make_mesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0, 1, 2}, {0, 2, 3}});
  CHECK(m.check(false).ok);
  const CheckReport r = m.check(true);
  CHECK_FALSE(r.ok);
  CHECK(mentions(r, "not locally Delaunay"));
}

TEST_CASE("check: rejects a non-Delaunay edge") {
  // Kite: diagonal 0-2 is Delaunay, 1-3 is not.
  const std::vector<Point> pts = {{0, 0}, {1, -3}, {2, 0}, {1, 3}};
  CHECK(make_mesh(pts, {{0, 1, 2}, {0, 2, 3}}).check().ok);
  const Mesh bad = make_mesh(pts, {{0, 1, 3}, {1, 2, 3}});
  CHECK(bad.check(false).ok);
  const CheckReport r = bad.check();
  CHECK_FALSE(r.ok);
  CHECK(mentions(r, "not locally Delaunay"));
}

TEST_CASE("check: rejects a clockwise triangle") {
  Mesh m = square();
  std::swap(m.triangles[0][1], m.triangles[0][2]);
  std::swap(m.neighbors[0][1], m.neighbors[0][2]);
  const CheckReport r = m.check();
  CHECK_FALSE(r.ok);
  CHECK(mentions(r, "clockwise"));
}

TEST_CASE("check: rejects a degenerate triangle and bad indices") {
  Mesh m = make_mesh({{0, 0}, {1, 0}, {2, 0}, {0, 1}}, {{0, 1, 3}, {1, 2, 3}});
  CHECK(m.check().ok);
  Mesh flat = m;
  flat.triangles.push_back({0, 1, 2});
  flat.neighbors.push_back({-1, -1, -1});
  CHECK_FALSE(flat.check().ok);
  CHECK(mentions(flat.check(), "degenerate"));
  Mesh out = m;
  out.triangles[1][2] = 7;
  CHECK(mentions(out.check(), "out of range"));
  Mesh repeated = m;
  repeated.triangles[1] = {1, 1, 3};
  CHECK(mentions(repeated.check(), "repeated vertex"));
}

TEST_CASE("check: rejects broken neighbour links") {
  {
    Mesh m = square();
    m.neighbors[0][0] = -1; // one side of a shared edge says boundary
    const CheckReport r = m.check();
    CHECK_FALSE(r.ok);
    CHECK(mentions(r, "neighbour"));
  }
  {
    Mesh m = square();
    m.neighbors[1][1] = 1; // hull edge pointing at a triangle
    CHECK_FALSE(m.check().ok);
  }
  {
    Mesh m = square();
    std::swap(m.neighbors[0][0], m.neighbors[0][1]); // link across the wrong edge
    CHECK_FALSE(m.check().ok);
  }
  {
    Mesh m = square();
    m.neighbors.pop_back(); // wrong size
    CHECK_FALSE(m.check().ok);
  }
}

TEST_CASE("check: rejects a missing point") {
  Mesh m = square();
  m.points.push_back({0.25, 0.25});
  m.duplicate_of.push_back(-1);
  const CheckReport r = m.check();
  CHECK_FALSE(r.ok);
  CHECK(mentions(r, "not a vertex"));
}

TEST_CASE("check: duplicates") {
  Mesh m = square();
  m.points.push_back({1, 1});
  m.duplicate_of.push_back(2);
  CHECK(m.check().ok);
  Mesh wrong = m;
  wrong.duplicate_of[4] = 1; // (1,1) is not a copy of (1,0)
  CHECK_FALSE(wrong.check().ok);
  Mesh unmarked = m;
  unmarked.duplicate_of[4] = -1; // two mesh points with the same coordinates
  CHECK_FALSE(unmarked.check().ok);
  Mesh chained = m;
  chained.points.push_back({1, 1});
  chained.duplicate_of.push_back(4); // points at a duplicate
  CHECK_FALSE(chained.check().ok);
}

TEST_CASE("check: collinear points need no triangles") {
  Mesh m;
  m.points = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  m.duplicate_of.assign(4, -1);
  CHECK(m.check().ok);
  m.points.push_back({0, 1});
  m.duplicate_of.push_back(-1);
  CHECK_FALSE(m.check().ok); // not collinear any more: points are not used
}

TEST_CASE("check: rejects any triangle removed from a small grid") {
  // A 3 x 3 grid of points (collinear points on the hull edges), 8 triangles split along
  // the diagonals the perturbed in-circle test keeps; the middle point is interior.
  std::vector<Point> pts;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x)
      pts.push_back({double(x), double(y)});
  std::vector<Triangle> tris;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const int32_t p = 3 * y + x;
      tris.push_back({p, p + 1, p + 3});
      tris.push_back({p + 1, p + 4, p + 3});
    }
  const Mesh m = make_mesh(pts, tris);
  const CheckReport good = m.check();
  INFO(problems(good));
  REQUIRE(good.ok);
  // Every removal leaves a reflex boundary vertex or an unused corner.
  for (int32_t t = 0; t < int32_t(tris.size()); ++t) {
    Mesh holed = m;
    remove_triangle(holed, t);
    const CheckReport r = holed.check(false);
    CHECK_FALSE(r.ok);
    const bool interior = tris[t][0] == 4 || tris[t][1] == 4 || tris[t][2] == 4;
    if (interior)
      CHECK(mentions(r, "boundary"));
  }
}

TEST_CASE("check: rejects an overlapping extra triangle") {
  const Mesh base = make_mesh({{0, 0}, {4, 0}, {4, 4}, {0, 4}, {1, 2}}, {});
  // Fan from the interior point 4.
  Mesh m = make_mesh(base.points, {{4, 0, 1}, {4, 1, 2}, {4, 2, 3}, {4, 3, 0}});
  REQUIRE(m.check(false).ok);
  {
    Mesh extra = m; // covers everything a second time, no shared edge direction clash
    extra.triangles.push_back({0, 1, 2});
    extra.neighbors.push_back({-1, -1, -1});
    CHECK_FALSE(extra.check(false).ok);
  }
  {
    Mesh copy = m; // the same triangle twice
    copy.triangles.push_back(m.triangles[0]);
    copy.neighbors.push_back(m.neighbors[0]);
    CHECK_FALSE(copy.check(false).ok);
  }
}

TEST_CASE("check: rejects a fan wound twice around its centre") {
  // Five triangles of 144 degrees each around (0,0): every edge is shared consistently and
  // the outer boundary (a pentagram) turns left everywhere, but it winds twice: every point
  // near the centre is covered twice.
  std::vector<Point> pts = {{0, 0}};
  for (int k = 0; k < 5; ++k) {
    const double angle = 2.0 * 3.14159265358979323846 * (2 * k % 5) / 5.0;
    pts.push_back({std::cos(angle), std::sin(angle)});
  }
  std::vector<Triangle> tris;
  for (int32_t k = 0; k < 5; ++k)
    tris.push_back({0, 1 + k, 1 + (k + 1) % 5});
  const Mesh m = make_mesh(pts, tris);
  for (const auto &nb : m.neighbors) // spokes shared, outer sides on the boundary
    CHECK((nb[0] == -1 && nb[1] >= 0 && nb[2] >= 0));
  const CheckReport r = m.check(false);
  INFO(problems(r));
  CHECK_FALSE(r.ok);
  CHECK(mentions(r, "winds"));
}

#ifdef CLMESH_HAVE_CGAL
TEST_CASE("check: accepts CGAL's Delaunay triangulation of random points") {
  const Mesh m = cgal_delaunay(random_points(200, 5));
  REQUIRE(m.triangles.size() > 300);
  const CheckReport r = m.check();
  INFO(problems(r));
  CHECK(r.ok);
}

TEST_CASE("check: defects in CGAL's triangulation of random points") {
  const Mesh m = cgal_delaunay(random_points(200, 9));
  REQUIRE(m.check().ok);
  const int32_t nt = int32_t(m.triangles.size());
  // An interior triangle (no boundary side).
  int32_t inner = 0;
  while (std::count(m.neighbors[inner].begin(), m.neighbors[inner].end(), -1) != 0)
    ++inner;
  SUBCASE("clockwise") {
    Mesh d = m;
    std::swap(d.triangles[inner][0], d.triangles[inner][1]);
    std::swap(d.neighbors[inner][0], d.neighbors[inner][1]);
    CHECK(mentions(d.check(), "clockwise"));
  }
  SUBCASE("broken link") {
    Mesh d = m;
    d.neighbors[inner][2] = (d.neighbors[inner][2] + 1) % nt;
    CHECK(mentions(d.check(), "neighbour"));
  }
  SUBCASE("not Delaunay") {
    // Flip an interior edge whose quadrilateral is convex: still a valid triangulation.
    Mesh d = m;
    bool flipped = false;
    for (int32_t t = 0; t < nt && !flipped; ++t)
      for (int32_t i = 0; i < 3 && !flipped; ++i) {
        const int32_t u = d.neighbors[t][i];
        if (u < 0)
          continue;
        Mesh trial = d;
        flip(trial, t, i);
        if (trial.check(false).ok) {
          d = trial;
          flipped = true;
        }
      }
    REQUIRE(flipped);
    const CheckReport r = d.check();
    CHECK_FALSE(r.ok);
    CHECK(mentions(r, "not locally Delaunay"));
  }
  SUBCASE("missing point") {
    Mesh d = m;
    d.points.push_back({0.001, 0.002});
    d.duplicate_of.push_back(-1);
    CHECK(mentions(d.check(), "not a vertex"));
  }
  SUBCASE("hole") {
    Mesh d = m;
    remove_triangle(d, inner);
    const CheckReport r = d.check();
    CHECK_FALSE(r.ok);
    CHECK(mentions(r, "cycles"));
  }
  SUBCASE("hull triangle removed") {
    Mesh d = m;
    int32_t outer = 0;
    while (std::count(d.neighbors[outer].begin(), d.neighbors[outer].end(), -1) == 0)
      ++outer;
    remove_triangle(d, outer);
    CHECK_FALSE(d.check().ok);
  }
  SUBCASE("overlapping triangle") {
    // A counter-clockwise triangle over two neighbours: (a, b, d) for t = (a, b, c) and d
    // the vertex across side bc.
    Mesh d = m;
    bool added = false;
    for (int32_t t = 0; t < nt && !added; ++t)
      for (int32_t i = 0; i < 3 && !added; ++i) {
        const int32_t u = m.neighbors[t][i];
        if (u < 0)
          continue;
        int32_t j = 0;
        while (m.neighbors[u][j] != t)
          ++j;
        const Point &a = m.points[m.triangles[t][i]], &b = m.points[m.triangles[t][(i + 1) % 3]];
        const Point &p = m.points[m.triangles[u][j]];
        if ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) > 1e-6) {
          d.triangles.push_back(
              {m.triangles[t][i], m.triangles[t][(i + 1) % 3], m.triangles[u][j]});
          d.neighbors.push_back({-1, -1, -1});
          added = true;
        }
      }
    REQUIRE(added);
    const CheckReport r = d.check();
    CHECK_FALSE(r.ok);
    CHECK_FALSE(mentions(r, "clockwise"));
  }
}

TEST_CASE("check: accepts CGAL's Delaunay triangulation of cocircular grids") {
  // Integer grids are full of cocircular quadruples: the checker's perturbed in-circle test
  // must keep exactly the diagonals CGAL keeps.
  for (const double offset : {0.0, 1e15}) {
    std::vector<Point> pts;
    for (int x = 0; x < 20; ++x)
      for (int y = 0; y < 20; ++y)
        pts.push_back({offset + x, offset + y});
    // Lattice points of a circle of radius 25 around the centre as well.
    for (int x = -25; x <= 25; ++x)
      for (int y = -25; y <= 25; ++y)
        if (x * x + y * y == 625)
          pts.push_back({offset + 10 + x, offset + 10 + y});
    pts.push_back({offset + 3, offset + 3}); // a duplicate
    const Mesh m = cgal_delaunay(pts);
    CHECK(std::count(m.duplicate_of.begin(), m.duplicate_of.end(), -1) == int64_t(pts.size()) - 1);
    const CheckReport r = m.check();
    INFO(problems(r));
    CHECK(r.ok);
  }
}

TEST_CASE("check: tiny and huge coordinates") {
  for (const double scale : {1e-40, 1e40}) {
    std::vector<Point> pts = random_points(300, 3);
    for (Point &p : pts)
      p = {p.x * scale, p.y * scale};
    const CheckReport r = cgal_delaunay(pts).check();
    INFO(problems(r));
    CHECK(r.ok);
  }
}

TEST_CASE("check: accepts a large CGAL triangulation") {
  const Mesh m = cgal_delaunay(random_points(100000, 12));
  const CheckReport r = m.check();
  INFO(problems(r));
  CHECK(r.ok);
}
#endif
