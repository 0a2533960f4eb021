// GPU-CDT end to end: every result passes the exact constrained Delaunay checker
// (clmesh::check_constrained) and, with CGAL, equals CGAL's
// Constrained_Delaunay_triangulation_2 triangle for triangle.  Both break cocircular ties with
// the same symbolic perturbation of the in-circle test (CGAL's CDT flips with
// side_of_oriented_circle(..., perturb = true)), and a constrained Delaunay triangulation under
// a consistent perturbation is unique, so the equality is expected for lattices too.
//
// The meshes with exterior or holes eaten are checked locally (check_constrained without
// whole_hull) and to be a subset of the whole-hull mesh of the same PSLG (with -cO), which
// the whole-hull check proves to be a triangulation: together no overlap is possible.
#include <doctest/doctest.h>

#include "clmesh/clmesh.hpp"
#include "mesh_fixtures.hpp"
#include "predicates.h"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <utility>

#ifdef CLMESH_HAVE_CGAL
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#endif

using clmesh::Point;
using clmesh::Segment;
using clmesh::Triangle;

namespace {

using Edge = std::pair<int32_t, int32_t>; // (smaller, larger) vertex index

using test_support::device;
using test_support::problems;

Edge edge(int32_t a, int32_t b) { return {std::min(a, b), std::max(a, b)}; }

int orient(const std::vector<Point> &p, int32_t a, int32_t b, int32_t c) {
  return clm_orient2d(p[a].x, p[a].y, p[b].x, p[b].y, p[c].x, p[c].y);
}

bool lex_less(const Point &p, const Point &q) { return p.x < q.x || (p.x == q.x && p.y < q.y); }

Triangle canonical(Triangle t) {
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

long double area_of(const std::vector<Point> &p, const std::vector<Triangle> &triangles) {
  long double sum = 0;
  for (const Triangle &t : triangles) {
    const long double ax = p[t[0]].x, ay = p[t[0]].y;
    sum += ((p[t[1]].x - ax) * (p[t[2]].y - ay) - (p[t[1]].y - ay) * (p[t[2]].x - ax)) / 2;
  }
  return sum;
}

// Neighbour links of a list of triangles (for meshes built in the tests).
std::vector<std::array<int32_t, 3>> neighbors_of(const std::vector<Triangle> &triangles) {
  std::map<std::pair<int32_t, int32_t>, std::pair<int32_t, int32_t>>
      directed; // (from, to) -> (t, i)
  for (int32_t t = 0; t < static_cast<int32_t>(triangles.size()); ++t)
    for (int32_t i = 0; i < 3; ++i)
      directed[{triangles[t][(i + 1) % 3], triangles[t][(i + 2) % 3]}] = {t, i};
  std::vector<std::array<int32_t, 3>> neighbors(triangles.size(), {-1, -1, -1});
  for (int32_t t = 0; t < static_cast<int32_t>(triangles.size()); ++t)
    for (int32_t i = 0; i < 3; ++i) {
      auto it = directed.find({triangles[t][(i + 2) % 3], triangles[t][(i + 1) % 3]});
      if (it != directed.end())
        neighbors[t][i] = it->second.first;
    }
  return neighbors;
}

// --- PSLG generation -----------------------------------------------------------------------

// Exact: do segments p-q and r-s meet anywhere but at a shared endpoint?  Conservative: a
// segment touching the other's interior (at an endpoint or along a collinear overlap) counts.
bool conflict(const std::vector<Point> &pts, int32_t p, int32_t q, int32_t r, int32_t s) {
  const int shared = (p == r) + (p == s) + (q == r) + (q == s);
  if (shared >= 2)
    return true;
  if (shared == 1) {
    const int32_t c = (p == r || p == s) ? p : q, u = c == p ? q : p, w = c == r ? s : r;
    if (orient(pts, c, u, w) != 0)
      return false;
    // Collinear through c: they overlap when u and w are on the same side of c.
    return lex_less(pts[c], pts[u]) == lex_less(pts[c], pts[w]);
  }
  const int o1 = orient(pts, p, q, r), o2 = orient(pts, p, q, s);
  const int o3 = orient(pts, r, s, p), o4 = orient(pts, r, s, q);
  if (o1 == 0 && o2 == 0) { // collinear: overlap of the lexicographic intervals
    auto lo = [&](int32_t a, int32_t b) { return lex_less(pts[a], pts[b]) ? a : b; };
    auto hi = [&](int32_t a, int32_t b) { return lex_less(pts[a], pts[b]) ? b : a; };
    return !(lex_less(pts[hi(p, q)], pts[lo(r, s)]) || lex_less(pts[hi(r, s)], pts[lo(p, q)]));
  }
  return o1 * o2 <= 0 && o3 * o4 <= 0;
}

// Accepts segments that conflict with none accepted before (linear scan: a few thousand).
struct SegmentSet {
  const std::vector<Point> &pts;
  std::vector<Segment> segments;
  bool add(int32_t a, int32_t b, int marker = 0) {
    if (a == b)
      return false;
    for (const Segment &s : segments)
      if (conflict(pts, a, b, s.a, s.b))
        return false;
    segments.push_back({a, b, marker});
    return true;
  }
};

// Nearest input point to a location, by a bucket grid (approximate beyond a few cells).
class Buckets {
public:
  Buckets(const std::vector<Point> &pts, int side) : pts_(pts), side_(side), cells_(side * side) {
    lo_ = hi_ = pts[0];
    for (const Point &p : pts) {
      lo_.x = std::min(lo_.x, p.x), lo_.y = std::min(lo_.y, p.y);
      hi_.x = std::max(hi_.x, p.x), hi_.y = std::max(hi_.y, p.y);
    }
    for (int32_t i = 0; i < static_cast<int32_t>(pts.size()); ++i)
      cells_[cell(pts[i].x, lo_.x, hi_.x) * side_ + cell(pts[i].y, lo_.y, hi_.y)].push_back(i);
  }
  int32_t nearest(Point t) const {
    if (t.x < lo_.x || t.x > hi_.x || t.y < lo_.y || t.y > hi_.y)
      return -1;
    const int cx = cell(t.x, lo_.x, hi_.x), cy = cell(t.y, lo_.y, hi_.y);
    int32_t best = -1;
    double best_d = 0;
    for (int ring = 0; ring <= 3 && best < 0; ++ring)
      for (int i = std::max(0, cx - ring); i <= std::min(side_ - 1, cx + ring); ++i)
        for (int j = std::max(0, cy - ring); j <= std::min(side_ - 1, cy + ring); ++j)
          for (int32_t k : cells_[i * side_ + j]) {
            const double d =
                (pts_[k].x - t.x) * (pts_[k].x - t.x) + (pts_[k].y - t.y) * (pts_[k].y - t.y);
            if (best < 0 || d < best_d)
              best = k, best_d = d;
          }
    return best;
  }

private:
  int cell(double v, double lo, double hi) const {
    return std::min(side_ - 1, static_cast<int>((v - lo) / (hi - lo) * side_));
  }
  const std::vector<Point> &pts_;
  int side_;
  std::vector<std::vector<int32_t>> cells_;
  Point lo_, hi_;
};

// Random non-crossing segments between input points, lengths log-uniform in
// [min_length, max_length]: from a random point towards a random direction, ending at the input
// point nearest the target.  Candidates that conflict with an accepted segment are skipped.
std::vector<Segment> random_segments(const std::vector<Point> &pts, int candidates,
                                     double min_length, double max_length, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int32_t> pick(0, static_cast<int32_t>(pts.size()) - 1);
  std::uniform_real_distribution<double> u(0, 1);
  const Buckets buckets(pts, std::max(1, static_cast<int>(std::sqrt(pts.size() / 2.0))));
  SegmentSet set{pts, {}};
  for (int k = 0; k < candidates; ++k) {
    const int32_t a = pick(rng);
    const double length = min_length * std::pow(max_length / min_length, u(rng));
    const double angle = 2 * M_PI * u(rng);
    const int32_t b =
        buckets.nearest({pts[a].x + length * std::cos(angle), pts[a].y + length * std::sin(angle)});
    if (b >= 0)
      set.add(a, b, 2 + k % 5);
  }
  return set.segments;
}

// A PSLG of points and segments.
clmesh::Input pslg_of(std::vector<Point> points, std::vector<Segment> segments) {
  clmesh::Input input;
  input.points = std::move(points);
  input.segments = std::move(segments);
  return input;
}

clmesh::Input closed_polygon(std::vector<Point> ring, const std::vector<Point> &extra, int marker) {
  clmesh::Input pslg;
  pslg.points = std::move(ring);
  const int32_t m = static_cast<int32_t>(pslg.points.size());
  for (int32_t i = 0; i < m; ++i)
    pslg.segments.push_back({i, (i + 1) % m, marker});
  pslg.points.insert(pslg.points.end(), extra.begin(), extra.end());
  return pslg;
}

// --- CGAL's constrained Delaunay triangulation ---------------------------------------------

struct Reference {
  std::set<Triangle> triangles;  // canonical, over input indices (smallest of duplicates)
  std::set<Edge> constrained;    // constrained edges of the whole triangulation
  std::set<Edge> hull;           // convex hull edges
  long whole_hull_triangles = 0; // finite faces before any eating
};

#ifdef CLMESH_HAVE_CGAL
// The CDT of the PSLG (points inserted as a range, then every segment as a constraint), with
// the exterior and the holes eaten as Triangle does: the exterior spreads from the hull edges
// that are not constrained, a hole from the triangle containing its point, both stopping at
// constrained edges.
Reference cgal_cdt(const clmesh::Input &pslg, bool eat_exterior, bool eat_holes) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int32_t, K>;
  using Cfb = CGAL::Constrained_triangulation_face_base_2<K>;
  using Fb = CGAL::Triangulation_face_base_with_info_2<int, K, Cfb>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds>;
  const auto &pts = pslg.points;
  std::map<std::pair<double, double>, int32_t> smallest;
  std::vector<std::pair<K::Point_2, int32_t>> input;
  for (int32_t i = 0; i < static_cast<int32_t>(pts.size()); ++i) {
    smallest.emplace(std::make_pair(pts[i].x, pts[i].y), i);
    input.push_back({K::Point_2(pts[i].x, pts[i].y), i});
  }
  CDT cdt;
  cdt.insert(input.begin(), input.end());
  std::map<int32_t, CDT::Vertex_handle> handle; // by smallest index
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    v->info() = smallest.at({v->point().x(), v->point().y()});
    handle[v->info()] = v;
  }
  auto id = [&](int32_t i) { return smallest.at({pts[i].x, pts[i].y}); };
  for (const Segment &s : pslg.segments)
    if (id(s.a) != id(s.b))
      cdt.insert_constraint(handle.at(id(s.a)), handle.at(id(s.b)));

  Reference ref;
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
    f->info() = 0;
  std::vector<CDT::Face_handle> stack;
  auto spread = [&]() {
    while (!stack.empty()) {
      const CDT::Face_handle f = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const CDT::Face_handle g = f->neighbor(i);
        if (!cdt.is_infinite(g) && g->info() == 0 && !cdt.is_constrained({f, i})) {
          g->info() = 1;
          stack.push_back(g);
        }
      }
    }
  };
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) {
    if (!cdt.is_infinite(f))
      continue;
    const int i = f->index(cdt.infinite_vertex());
    const CDT::Face_handle g = f->neighbor(i);
    ref.hull.insert(edge(f->vertex((i + 1) % 3)->info(), f->vertex((i + 2) % 3)->info()));
    if (eat_exterior && !cdt.is_constrained({f, i}) && g->info() == 0) {
      g->info() = 1;
      stack.push_back(g);
    }
  }
  spread();
  if (eat_holes)
    for (const Point &h : pslg.holes) {
      const CDT::Face_handle f = cdt.locate(K::Point_2(h.x, h.y));
      if (f != CDT::Face_handle() && !cdt.is_infinite(f) && f->info() == 0) {
        f->info() = 1;
        stack.push_back(f);
        spread();
      }
    }
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    ++ref.whole_hull_triangles;
    if (f->info() == 0)
      ref.triangles.insert(
          canonical({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}));
  }
  for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e)
    if (cdt.is_constrained(*e))
      ref.constrained.insert(edge(e->first->vertex((e->second + 1) % 3)->info(),
                                  e->first->vertex((e->second + 2) % 3)->info()));
  return ref;
}

std::string triangles_text(const std::vector<Triangle> &list) {
  std::string text;
  for (std::size_t k = 0; k < list.size() && k < 5; ++k)
    text += " (" + std::to_string(list[k][0]) + "," + std::to_string(list[k][1]) + "," +
            std::to_string(list[k][2]) + ")";
  return list.size() > 5 ? text + " ..." : text;
}

void compare_with_cgal(const clmesh::Input &pslg, const clmesh::Options &options,
                       const clmesh::Mesh &result) {
  const Reference ref = cgal_cdt(pslg, !options.convex_hull, !options.ignore_holes);
  const std::set<Triangle> ours(result.triangles.begin(), result.triangles.end());
  std::vector<Triangle> only_ours, only_cgal;
  std::set_difference(ours.begin(), ours.end(), ref.triangles.begin(), ref.triangles.end(),
                      std::back_inserter(only_ours));
  std::set_difference(ref.triangles.begin(), ref.triangles.end(), ours.begin(), ours.end(),
                      std::back_inserter(only_cgal));
  INFO("clmesh " << ours.size() << " triangles, CGAL " << ref.triangles.size() << "; only clmesh "
                 << only_ours.size() << ":" << triangles_text(only_ours) << "; only CGAL "
                 << only_cgal.size() << ":" << triangles_text(only_cgal));
  CHECK(ours.size() == result.triangles.size());
  CHECK(only_ours.empty());
  CHECK(only_cgal.empty());
  // The segments as they stand in the mesh: CGAL's constrained edges (input segments split at
  // the vertices on them), plus the hull edges with -c.
  if (options.convex_hull && (options.ignore_holes || pslg.holes.empty())) {
    std::set<Edge> expected = ref.constrained, listed;
    expected.insert(ref.hull.begin(), ref.hull.end());
    for (const Segment &s : result.segments)
      listed.insert(edge(s.a, s.b));
    std::vector<Edge> missing, extra;
    std::set_difference(expected.begin(), expected.end(), listed.begin(), listed.end(),
                        std::back_inserter(missing));
    std::set_difference(listed.begin(), listed.end(), expected.begin(), expected.end(),
                        std::back_inserter(extra));
    INFO("result.segments: " << missing.size() << " constrained or hull edges missing, "
                             << extra.size() << " others listed"
                             << (missing.empty()
                                     ? ""
                                     : "; first missing " + std::to_string(missing[0].first) + "-" +
                                           std::to_string(missing[0].second)));
    CHECK(missing.empty());
    CHECK(extra.empty());
    CHECK(listed.size() == result.segments.size());
  }
}
#endif

// Convex hull edges (between the strict hull vertices, counter-clockwise) as segments: with
// -c and holes the mesh boundary is the hull and the hole boundaries.
std::vector<Segment> hull_segments(const std::vector<Point> &pts) {
  std::vector<int32_t> ids(pts.size());
  for (int32_t i = 0; i < static_cast<int32_t>(pts.size()); ++i)
    ids[i] = i;
  std::sort(ids.begin(), ids.end(), [&](int32_t a, int32_t b) { return lex_less(pts[a], pts[b]); });
  std::vector<int32_t> hull(2 * ids.size() + 1);
  std::size_t k = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    while (k >= 2 && orient(pts, hull[k - 2], hull[k - 1], ids[i]) <= 0)
      --k;
    hull[k++] = ids[i];
  }
  for (std::size_t i = ids.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && orient(pts, hull[k - 2], hull[k - 1], ids[i]) <= 0)
      --k;
    hull[k++] = ids[i];
  }
  std::vector<Segment> segments;
  for (std::size_t i = 0; i + 1 < k; ++i)
    segments.push_back({hull[i], hull[i + 1], 1});
  return segments;
}

// Runs the CDT and checks it: exact checker, canonical order, and CGAL's triangles.
clmesh::Mesh cdt_checked(const clmesh::Input &pslg, const clmesh::Options &options,
                         bool with_cgal = true) {
  REQUIRE(options.pslg);
  clmesh::Mesh result = clmesh::triangulate(device(), pslg, options);
  const clmesh::Mesh &mesh = result;
  // The input's points, none added (these PSLGs have no crossing segments).
  REQUIRE(mesh.input_points == static_cast<long>(pslg.points.size()));
  REQUIRE(mesh.points.size() == pslg.points.size());
  CHECK(test_support::starts_with(mesh.points, pslg.points));
  CHECK(mesh.statistics.constrained);
  CHECK(mesh.statistics.constraints.crossings == 0);
  const bool whole_hull = options.convex_hull && (options.ignore_holes || pslg.holes.empty());
  std::vector<Segment> boundary = pslg.segments;
  if (options.convex_hull && !whole_hull) {
    const auto hull = hull_segments(pslg.points);
    boundary.insert(boundary.end(), hull.begin(), hull.end());
  }
  const auto report = clmesh::check_constrained(pslg.points, mesh.triangles, mesh.neighbors,
                                                mesh.duplicate_of, boundary, whole_hull);
  INFO(problems(report));
  CHECK(report.ok);
  REQUIRE(mesh.duplicate_of.size() == pslg.points.size());
  // Canonical order: each triangle from its smallest vertex, the triangles of
  // a first vertex together and sorted by their other two vertices.
  bool canonical_order = true;
  std::set<int32_t> first_vertices_seen;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const Triangle &t = mesh.triangles[k];
    canonical_order = canonical_order && t[0] < t[1] && t[0] < t[2];
    if (k > 0 && mesh.triangles[k - 1][0] == t[0])
      canonical_order = canonical_order && mesh.triangles[k - 1] < t;
    else
      canonical_order = canonical_order && first_vertices_seen.insert(t[0]).second;
  }
  CHECK(canonical_order);
#ifdef CLMESH_HAVE_CGAL
  if (with_cgal)
    compare_with_cgal(pslg, options, result);
#else
  (void)with_cgal;
#endif
  return result;
}

// -p: the constrained Delaunay triangulation, exterior and holes eaten.
clmesh::Options cdt_options() { return clmesh::parse_switches("p"); }

// -pc: every triangle of the convex hull kept.
clmesh::Options whole_hull_options() { return clmesh::parse_switches("pc"); }

// The vertices added where segments cross (the mesh's points after the input's).
std::size_t added_points(const clmesh::Mesh &mesh) {
  return mesh.points.size() - static_cast<std::size_t>(mesh.input_points);
}

// Runs the CDT of a PSLG whose segments cross (-pc) and checks it exactly: the input's points
// first and unchanged, then the crossings; every segment as it stands in the mesh a mesh edge.
clmesh::Mesh crossings_checked(const clmesh::Input &pslg) {
  const clmesh::Mesh result = clmesh::triangulate(device(), pslg, whole_hull_options());
  REQUIRE(result.input_points == static_cast<long>(pslg.points.size()));
  REQUIRE(result.points.size() >= pslg.points.size());
  REQUIRE(result.duplicate_of.size() == result.points.size());
  CHECK(added_points(result) == static_cast<std::size_t>(result.statistics.constraints.crossings));
  CHECK(test_support::starts_with(result.points, pslg.points));
  for (std::size_t i = pslg.points.size(); i < result.points.size(); ++i)
    CHECK(result.duplicate_of[i] == -1);
  const auto report = clmesh::check_constrained(result.points, result.triangles, result.neighbors,
                                                result.duplicate_of, result.segments, true);
  INFO(problems(report));
  CHECK(report.ok);
  return result;
}

// Number of distinct, non-zero-length segments after mapping duplicate points.
long distinct_segments(const clmesh::Input &pslg) {
  std::map<std::pair<double, double>, int32_t> smallest;
  for (int32_t i = 0; i < static_cast<int32_t>(pslg.points.size()); ++i)
    smallest.emplace(std::make_pair(pslg.points[i].x, pslg.points[i].y), i);
  std::set<Edge> seen;
  for (const Segment &s : pslg.segments) {
    const int32_t a = smallest.at({pslg.points[s.a].x, pslg.points[s.a].y});
    const int32_t b = smallest.at({pslg.points[s.b].x, pslg.points[s.b].y});
    if (a != b)
      seen.insert(edge(a, b));
  }
  return static_cast<long>(seen.size());
}

// Triangle's .ele file: count and 0-based triangles (numbering from the first id).
std::vector<Triangle> read_ele(const std::string &path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::vector<std::vector<long>> rows;
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream fields(line);
    std::vector<long> row;
    long v;
    while (fields >> v)
      row.push_back(v);
    if (!row.empty())
      rows.push_back(row);
  }
  REQUIRE(!rows.empty());
  const long count = rows[0][0];
  REQUIRE(static_cast<long>(rows.size()) == count + 1);
  const long base = count > 0 ? rows[1][0] : 0;
  std::vector<Triangle> triangles;
  for (long k = 1; k <= count; ++k)
    triangles.push_back({static_cast<int32_t>(rows[k][1] - base),
                         static_cast<int32_t>(rows[k][2] - base),
                         static_cast<int32_t>(rows[k][3] - base)});
  return triangles;
}

clmesh::Input load_poly(const std::string &name) {
  return clmesh::read_input(std::string(CLMESH_SHARED_DATA) + "/triangle-examples/inputs/" + name +
                            ".poly");
}

} // namespace

TEST_CASE("cdt checker: accepts CGAL's constrained triangulations, rejects broken ones") {
#ifndef CLMESH_HAVE_CGAL
  MESSAGE("built without CGAL: skipped");
#else
  clmesh::Input pslg;
  pslg.points = fixtures::uniform(3000, 11);
  pslg.segments = random_segments(pslg.points, 600, 0.01, 1.0, 12);
  REQUIRE(pslg.segments.size() > 50);
  const std::vector<int32_t> no_duplicates(pslg.points.size(), -1);
  const Reference ref = cgal_cdt(pslg, false, false);
  std::vector<Triangle> triangles(ref.triangles.begin(), ref.triangles.end());
  const auto neighbors = neighbors_of(triangles);
  const auto accepted = clmesh::check_constrained(pslg.points, triangles, neighbors, no_duplicates,
                                                  pslg.segments, true);
  INFO(problems(accepted));
  CHECK(accepted.ok);
  // The local (eaten-mesh) checks reject it: its hull edges are not segments.
  const auto local = clmesh::check_constrained(pslg.points, triangles, neighbors, no_duplicates,
                                               pslg.segments, false);
  CHECK_FALSE(local.ok);

  SUBCASE("the plain Delaunay triangulation misses the segments") {
    const Reference dt = cgal_cdt(pslg_of(pslg.points, {}), false, false);
    std::vector<Triangle> plain(dt.triangles.begin(), dt.triangles.end());
    const auto report = clmesh::check_constrained(pslg.points, plain, neighbors_of(plain),
                                                  no_duplicates, pslg.segments, true);
    CHECK_FALSE(report.ok);
  }
  SUBCASE("a constrained edge that is not a segment is not locally Delaunay") {
    // Drop the longest segment: its edges are not Delaunay edges.
    auto fewer = pslg.segments;
    auto longest =
        std::max_element(fewer.begin(), fewer.end(), [&](const Segment &s, const Segment &t) {
          auto len = [&](const Segment &q) {
            return std::hypot(pslg.points[q.a].x - pslg.points[q.b].x,
                              pslg.points[q.a].y - pslg.points[q.b].y);
          };
          return len(s) < len(t);
        });
    fewer.erase(longest);
    const auto report =
        clmesh::check_constrained(pslg.points, triangles, neighbors, no_duplicates, fewer, true);
    CHECK_FALSE(report.ok);
  }
  SUBCASE("eaten meshes: a missing interior triangle leaves a boundary edge that is no segment") {
    clmesh::Input square =
        closed_polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, fixtures::uniform(200, 13), 1);
    const Reference eaten = cgal_cdt(square, true, true);
    std::vector<Triangle> inside(eaten.triangles.begin(), eaten.triangles.end());
    const std::vector<int32_t> none(square.points.size(), -1);
    const auto good = clmesh::check_constrained(square.points, inside, neighbors_of(inside), none,
                                                square.segments, false);
    INFO(problems(good));
    CHECK(good.ok);
    inside.erase(inside.begin() + inside.size() / 2);
    const auto bad = clmesh::check_constrained(square.points, inside, neighbors_of(inside), none,
                                               square.segments, false);
    CHECK_FALSE(bad.ok);
  }
  SUBCASE("eaten meshes: an overlapping fan is found") {
    // A fan around vertex 0 turning twice: 8 points on two turns of a "square" around it.
    std::vector<Point> p = {{0, 0},   {1, 0},   {0, 1},    {-1, 0},  {0, -1},
                            {2, 0.1}, {0.1, 2}, {-2, 0.1}, {0.1, -2}};
    std::vector<Triangle> fan = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5},
                                 {0, 5, 6}, {0, 6, 7}, {0, 7, 8}};
    std::vector<Segment> every_edge; // so that only the fan check can fail
    for (const Triangle &t : fan)
      every_edge.push_back({t[1], t[2], 1});
    for (int32_t v = 1; v <= 8; ++v)
      every_edge.push_back({0, v, 1});
    const auto report = clmesh::check_constrained(
        p, fan, neighbors_of(fan), std::vector<int32_t>(p.size(), -1), every_edge, false);
    INFO(problems(report));
    CHECK_FALSE(report.ok);
    CHECK(problems(report).find("turn 1 times (open fan)") != std::string::npos);
  }
#endif
}

TEST_CASE("cdt: random points with non-crossing segments of many lengths") {
  SUBCASE("20k uniform points, segments from one spacing to the whole square") {
    clmesh::Input pslg;
    pslg.points = fixtures::uniform(20000, 21);
    pslg.segments = random_segments(pslg.points, 4000, 0.002, 1.2, 22);
    // Some Delaunay-near segments (a point and its nearest neighbour) too.
    SegmentSet set{pslg.points, pslg.segments};
    const Buckets buckets(pslg.points, 100);
    for (int32_t i = 0; i < 20000; i += 37) {
      const Point &p = pslg.points[i];
      set.add(i, buckets.nearest({p.x + 1e-4, p.y}), 9);
    }
    pslg.segments = set.segments;
    MESSAGE(pslg.segments.size() << " segments");
    REQUIRE(pslg.segments.size() > 300);
    const auto result = cdt_checked(pslg, whole_hull_options());
    CHECK(result.statistics.constraints.segments == distinct_segments(pslg));
    CHECK(result.statistics.constraints.dropped_segments == 0);
    CHECK(result.statistics.constraints.split_segments == 0);
    CHECK(result.statistics.constraints.eaten_triangles == 0);
    CHECK(result.statistics.constraints.intersections > 0);
  }
  SUBCASE("gaussian points, short segments only") {
    clmesh::Input pslg;
    pslg.points = fixtures::gaussian(30000, 23);
    pslg.segments = random_segments(pslg.points, 6000, 0.005, 0.05, 24);
    REQUIRE(pslg.segments.size() > 1000);
    cdt_checked(pslg, whole_hull_options());
  }
  SUBCASE("the same mesh whatever the work-group size") {
    clmesh::Input pslg;
    pslg.points = fixtures::disk(5000, 25);
    pslg.segments = random_segments(pslg.points, 1000, 0.01, 2, 26);
    auto options = whole_hull_options();
    options.tuning.work_group = 1;
    const auto first = clmesh::triangulate(device(), pslg, options);
    options.tuning.work_group = 256;
    const auto second = clmesh::triangulate(device(), pslg, options);
    options.tuning.work_group = clmesh::max_work_group_size(device());
    const auto largest = clmesh::triangulate(device(), pslg, options);
    CHECK(first.triangles == second.triangles);
    CHECK(first.neighbors == second.neighbors);
    CHECK(first.triangles == largest.triangles);
  }
}

TEST_CASE("cdt: long segments crossing thousands of triangles") {
  // 100k points in a thin band [0, 1] x [0, 0.01]; the band is cut into 10 strips of height
  // 0.001 and in each strip the leftmost and the rightmost point are joined: segments lying in
  // disjoint strips cannot cross, and each crosses about 1 / spacing = 3000+ triangles.  Half
  // of the strips also get an x-monotone chain through a few of their points (segments with
  // disjoint x ranges), for medium lengths.
  clmesh::Input pslg;
  pslg.points = fixtures::uniform(100000, 31);
  for (auto &p : pslg.points)
    p.y *= 0.01;
  const int strips = 10;
  std::vector<std::vector<int32_t>> strip(strips);
  for (int32_t i = 0; i < static_cast<int32_t>(pslg.points.size()); ++i)
    strip[std::min(strips - 1, static_cast<int>(pslg.points[i].y / 0.001))].push_back(i);
  for (int s = 0; s < strips; ++s) {
    auto &ids = strip[s];
    std::sort(ids.begin(), ids.end(),
              [&](int32_t a, int32_t b) { return lex_less(pslg.points[a], pslg.points[b]); });
    if (s % 2 == 0) {
      pslg.segments.push_back({ids.front(), ids.back(), 3});
    } else {
      const std::size_t step = ids.size() / 7;
      for (std::size_t k = 0; k + step < ids.size(); k += step)
        pslg.segments.push_back({ids[k], ids[k + step], 4});
    }
  }
  const auto result = cdt_checked(pslg, whole_hull_options());
  MESSAGE("intersections " << result.statistics.constraints.intersections << ", constraint flips "
                           << result.statistics.constraints.constraint_flips
                           << ", outer iterations "
                           << result.statistics.constraints.outer_iterations);
  CHECK(result.statistics.constraints.intersections > 5 * 3000);
  CHECK(result.statistics.constraints.split_segments == 0);
}

TEST_CASE("cdt: dense parallel chains (runs of many constraints side by side)") {
  // 20k points cut into 1400 horizontal strips a tenth of a point spacing high, each joined by
  // an x-monotone chain of two segments (the benchmark's 'long' PSLG, smaller): every crossed
  // triangle is crossed by about ten constraints, so the inner loop's runs are short and
  // border on one another, and most of their edges are relinked across runs.
  clmesh::Input pslg;
  pslg.points = fixtures::uniform(20000, 41);
  const int strips = 1400;
  std::vector<std::vector<int32_t>> strip(strips);
  for (int32_t i = 0; i < static_cast<int32_t>(pslg.points.size()); ++i)
    strip[std::min(strips - 1, static_cast<int>(pslg.points[i].y * strips))].push_back(i);
  for (auto &ids : strip) {
    if (ids.size() < 3)
      continue;
    std::sort(ids.begin(), ids.end(),
              [&](int32_t a, int32_t b) { return lex_less(pslg.points[a], pslg.points[b]); });
    const std::size_t middle = ids.size() / 2;
    pslg.segments.push_back({ids.front(), ids[middle], 5});
    pslg.segments.push_back({ids[middle], ids.back(), 5});
  }
  auto options = whole_hull_options();
  const auto result = cdt_checked(pslg, options);
  MESSAGE(pslg.segments.size() << " segments, intersections "
                               << result.statistics.constraints.intersections
                               << ", constraint flips "
                               << result.statistics.constraints.constraint_flips
                               << ", outer iterations "
                               << result.statistics.constraints.outer_iterations);
  CHECK(result.statistics.constraints.intersections > 20 * static_cast<long>(pslg.segments.size()));
  CHECK(result.statistics.constraints.split_segments == 0);
  options.tuning.work_group = 1;
  const auto single = clmesh::triangulate(device(), pslg, options);
  CHECK(single.triangles == result.triangles);
  CHECK(single.neighbors == result.neighbors);
}

TEST_CASE("cdt: small PSLGs") {
  SUBCASE("a square with either diagonal") {
    const std::vector<Point> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const auto &[a, b] : {std::pair<int32_t, int32_t>{1, 3}, {0, 2}}) {
      const clmesh::Input pslg = pslg_of(square, {{a, b, 5}});
      const auto result = cdt_checked(pslg, whole_hull_options());
      const std::vector<Triangle> expected = a == 1 ? std::vector<Triangle>{{0, 1, 3}, {1, 2, 3}}
                                                    : std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}};
      CHECK(result.triangles == expected);
      // Without -c the only segment encloses nothing: everything is eaten (as Triangle does).
      const auto eaten = clmesh::triangulate(device(), pslg, cdt_options());
      CHECK(eaten.triangles.empty());
    }
  }
  SUBCASE("a star polygon among random points, with and without its exterior") {
    std::vector<Point> ring;
    for (int k = 0; k < 40; ++k) {
      const double r = k % 2 ? 0.35 : 1.0, a = 2 * M_PI * k / 40;
      ring.push_back({0.123 + r * std::cos(a), -0.456 + r * std::sin(a)});
    }
    auto extra = fixtures::uniform(3000, 41);
    for (auto &p : extra)
      p = {0.123 - 1.5 + 3 * p.x, -0.456 - 1.5 + 3 * p.y};
    const clmesh::Input pslg = closed_polygon(ring, extra, 1);
    const auto whole = cdt_checked(pslg, whole_hull_options());
    const auto eaten = cdt_checked(pslg, cdt_options());
    CHECK(eaten.statistics.constraints.eaten_triangles ==
          static_cast<long>(whole.triangles.size() - eaten.triangles.size()));
    const std::set<Triangle> all(whole.triangles.begin(), whole.triangles.end());
    for (const Triangle &t : eaten.triangles)
      CHECK(all.count(t) == 1);
    long double polygon = 0; // shoelace
    for (int k = 0; k < 40; ++k)
      polygon += (static_cast<long double>(ring[k].x) * ring[(k + 1) % 40].y -
                  static_cast<long double>(ring[(k + 1) % 40].x) * ring[k].y) /
                 2;
    CHECK(std::fabs(static_cast<double>(area_of(pslg.points, eaten.triangles) - polygon)) <
          1e-9 * static_cast<double>(polygon));
  }
  SUBCASE("a spiral polyline") {
    clmesh::Input pslg;
    for (int k = 0; k < 400; ++k) {
      const double a = 6 * M_PI * k / 400, r = 0.02 + 0.05 * a;
      pslg.points.push_back({r * std::cos(a), r * std::sin(a)});
      if (k > 0)
        pslg.segments.push_back({k - 1, k, 2});
    }
    auto extra = fixtures::uniform(4000, 42);
    for (auto &p : extra)
      pslg.points.push_back({-1 + 2 * p.x, -1 + 2 * p.y});
    cdt_checked(pslg, whole_hull_options());
  }
  SUBCASE("collinear segment chains and a segment through collinear vertices") {
    clmesh::Input pslg;
    for (int i = 0; i < 50; ++i) // on y = x / 2, exactly
      pslg.points.push_back({i * 0.25, i * 0.125});
    for (int i = 0; i < 20; ++i)
      pslg.segments.push_back({i, i + 1, 3});
    pslg.segments.push_back({20, 49, 4}); // through the 28 vertices 21..48
    for (int i = 0; i < 30; ++i) {        // a vertical chain at x = 3.3 (collinear, exact)
      pslg.points.push_back({3.3, -2 + i * 0.125});
      if (i > 0)
        pslg.segments.push_back({49 + i, 50 + i, 5});
    }
    auto extra = fixtures::uniform(2000, 43);
    for (auto &p : extra)
      pslg.points.push_back({-1 + 14 * p.x, -3 + 10 * p.y});
    const auto result = cdt_checked(pslg, whole_hull_options());
    CHECK(result.statistics.constraints.split_segments == 1);
    CHECK(result.statistics.constraints.segments == 20 + 1 + 29);
    // The long segment stands as 29 pieces with its marker.
    long pieces = 0;
    for (const Segment &s : result.segments)
      if (s.marker == 4) {
        ++pieces;
        CHECK(std::abs(s.a - s.b) == 1);
        CHECK(std::min(s.a, s.b) >= 20);
        CHECK(std::max(s.a, s.b) <= 49);
      }
    CHECK(pieces == 29);
  }
  SUBCASE("segments along the convex hull through hull vertices") {
    // The smallest case: the top row of a 3x3 lattice, (0, 2) to (2, 2) through (1, 2).
    const clmesh::Input top = pslg_of(fixtures::lattice(3), {{2, 8, 1}});
    cdt_checked(top, whole_hull_options());
    // Every side of a 5x5 lattice, whole and in part.
    for (const auto &[a, b] :
         {std::pair<int32_t, int32_t>{0, 20}, {4, 24}, {0, 4}, {20, 24}, {9, 19}, {1, 3}}) {
      INFO("segment " << a << "-" << b);
      cdt_checked(pslg_of(fixtures::lattice(5), {{a, b, 1}}), whole_hull_options());
    }
  }
  SUBCASE("overlapping collinear segments") {
    // Triangle accepts these: both are split at the vertices on them; the overlap is one chain.
    clmesh::Input pslg;
    for (int i = 0; i < 10; ++i)
      pslg.points.push_back({static_cast<double>(i), 0.0});
    pslg.segments = {{0, 6, 1}, {3, 9, 2}};
    auto extra = fixtures::uniform(300, 44);
    for (auto &p : extra)
      pslg.points.push_back({-1 + 11 * p.x, -3 + 6 * p.y});
    cdt_checked(pslg, whole_hull_options());
  }
  SUBCASE("vertices exactly on a segment, one just off it") {
    // Segment 0-1 from (0, 0) to (4, 0) has vertex 2 = (2, 0) on it, vertex 3 = (3, 1e-20) just
    // above it; segment 2-4 ends on it (a T junction).
    clmesh::Input pslg;
    pslg.points = {{0, 0}, {4, 0}, {2, 0}, {3, 1e-20}, {2, 3}, {2, -3}, {1, 1}, {3, -1}, {-1, 0.5}};
    pslg.segments = {{0, 1, 7}, {2, 4, 8}};
    const auto result = cdt_checked(pslg, whole_hull_options());
    CHECK(result.statistics.constraints.split_segments == 1);
    CHECK(result.statistics.constraints.segments == 2);
    std::set<std::pair<Edge, int>> listed;
    for (const Segment &s : result.segments)
      listed.insert({edge(s.a, s.b), s.marker});
    CHECK(listed.count({edge(0, 2), 7}) == 1);
    CHECK(listed.count({edge(2, 1), 7}) == 1);
    CHECK(listed.count({edge(2, 4), 8}) == 1);
    CHECK(listed.count({edge(0, 1), 7}) == 0);
    CHECK(listed.count({edge(3, 1), 7}) == 0);
  }
  SUBCASE("duplicate and zero-length segments are dropped") {
    clmesh::Input pslg;
    pslg.points = fixtures::uniform(500, 45);
    pslg.segments = random_segments(pslg.points, 150, 0.05, 0.8, 46);
    const long kept = static_cast<long>(pslg.segments.size());
    REQUIRE(kept > 20);
    for (int i = 0; i < 5; ++i) // duplicate points 500..504 of 0..4
      pslg.points.push_back(pslg.points[i]);
    const Segment s0 = pslg.segments[0], s1 = pslg.segments[1];
    pslg.segments.push_back(s0);              // repeated
    pslg.segments.push_back({s0.b, s0.a, 9}); // reversed
    pslg.segments.push_back({s1.a, s1.a, 0}); // zero length
    pslg.segments.push_back({3, 503, 0});     // zero length through a duplicate point
    // A segment given once with the original, once with the duplicate endpoint.
    SegmentSet set{pslg.points,
                   std::vector<Segment>(pslg.segments.begin(), pslg.segments.begin() + kept)};
    int32_t with_duplicate = -1;
    for (int32_t other = 5; other < 500 && with_duplicate < 0; ++other)
      if (set.add(2, other))
        with_duplicate = other;
    REQUIRE(with_duplicate >= 0);
    pslg.segments.push_back({2, with_duplicate, 0});
    pslg.segments.push_back({with_duplicate, 502, 0});
    const auto result = cdt_checked(pslg, whole_hull_options());
    CHECK(result.statistics.constraints.segments == kept + 1);
    CHECK(result.statistics.constraints.dropped_segments == 5);
    CHECK(result.statistics.constraints.segments == distinct_segments(pslg));
  }
}

TEST_CASE("cdt: segments on a lattice (cocircular points)") {
  // Every lattice quad is cocircular: the result is unique only by the perturbation of the
  // in-circle test, which clmesh and CGAL share.  Segments between random lattice points (some
  // through other lattice points, split there) and the diagonals of a block of cells.
  clmesh::Input pslg;
  pslg.points = fixtures::lattice(40, 0.5, {-3, 7});
  SegmentSet set{pslg.points, {}};
  for (int i = 5; i < 15; ++i)
    for (int j = 5; j < 15; ++j)
      set.add(i * 40 + j, (i + 1) * 40 + j + 1, 6); // the diagonals of the cells of a block
  std::mt19937_64 rng(51);
  std::uniform_int_distribution<int32_t> pick(0, 40 * 40 - 1);
  for (int k = 0; k < 3000; ++k)
    set.add(pick(rng), pick(rng), 7);
  pslg.segments = set.segments;
  MESSAGE(pslg.segments.size() << " lattice segments");
  const auto result = cdt_checked(pslg, whole_hull_options());
  CHECK(result.statistics.constraints.split_segments > 0);
  CHECK(result.triangles.size() == 2u * 39 * 39);
}

TEST_CASE("cdt: Triangle's example PSLGs") {
  // Triangle's counts and areas: A, face and double_hex from their reference .1.ele (made with
  // `triangle -p`), box's -pc from box.1.ele (made with `triangle -pc`); the others from
  // Triangle 1.6 (the PyPI package `triangle`, triangulate(load(name), switches)); la's
  // reference .1.ele was made with -pqa (refined) and is not usable here.  Triangle eats the
  // holes with -c too; only -cO keeps the whole convex hull.  box's outer square has a segment
  // on one side only, so without -c Triangle eats everything.
  struct Expected {
    const char *name;
    long p, pc, pcO;
    double area_p;
  };
  const Expected cases[] = {{"A", 29, 47, 48, 0},
                            {"face", 36, 38, 44, 0},
                            {"double_hex", 98, 98, 118, 0},
                            {"box", 0, 8, 10, 0},
                            {"la", 265, 265, 265, 479.32669310999995},
                            {"square_circle_hole", 1517, 1517, 1538, 44.898168028466}};
  const std::string reference =
      std::string(CLMESH_SHARED_DATA) + "/triangle-examples/reference-outputs/";
  for (const Expected &e : cases) {
    INFO(std::string(e.name));
    const clmesh::Input pslg = load_poly(e.name);
    double area_p = e.area_p;
    if (std::string(e.name) == "A" || std::string(e.name) == "face" ||
        std::string(e.name) == "double_hex") {
      const auto ele = read_ele(reference + e.name + ".1.ele");
      CHECK(static_cast<long>(ele.size()) == e.p);
      area_p = static_cast<double>(area_of(pslg.points, ele));
    }
    const clmesh::Options p = clmesh::parse_switches("p"), pc = clmesh::parse_switches("pc"),
                          pcO = clmesh::parse_switches("pcO");
    const auto whole = cdt_checked(pslg, pcO);
    CHECK(static_cast<long>(whole.triangles.size()) == e.pcO);
    const std::set<Triangle> all(whole.triangles.begin(), whole.triangles.end());
    for (const auto *options : {&p, &pc}) {
      const auto result = cdt_checked(pslg, *options);
      const long expected = options == &p ? e.p : e.pc;
      CHECK(static_cast<long>(result.triangles.size()) == expected);
      CHECK(result.statistics.constraints.eaten_triangles == e.pcO - expected);
      for (const Triangle &t : result.triangles)
        CHECK(all.count(t) == 1);
      if (options == &p && expected > 0)
        CHECK(std::fabs(static_cast<double>(area_of(pslg.points, result.triangles)) - area_p) <=
              1e-9 * area_p);
    }
    if (std::string(e.name) == "box") {
      const auto ele = read_ele(reference + "box.1.ele");
      CHECK(static_cast<long>(ele.size()) == e.pc);
      const auto result = clmesh::triangulate(device(), pslg, pc);
      CHECK(std::fabs(static_cast<double>(area_of(pslg.points, result.triangles) -
                                          area_of(pslg.points, ele))) < 1e-9);
    }
  }
}

TEST_CASE("cdt: bad segments are refused with a typed error") {
  const std::vector<Point> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.3, 0.6}};
  SUBCASE("endpoint out of range") {
    CHECK_THROWS_AS(clmesh::triangulate(device(), pslg_of(square, {{0, 5, 0}}), cdt_options()),
                    clmesh::InputError);
    CHECK_THROWS_AS(clmesh::triangulate(device(), pslg_of(square, {{-1, 2, 0}}), cdt_options()),
                    clmesh::InputError);
  }
  SUBCASE("crossing segments") {
    // Split at a new vertex where they cross, numbered after the input (Triangle's behaviour).
    auto crossing_checked = [](const clmesh::Input &pslg, std::size_t crossings) {
      const auto result = crossings_checked(pslg);
      CHECK(added_points(result) == crossings);
      CHECK(result.statistics.constraints.crossings == static_cast<long>(crossings));
      return result;
    };
    const auto diagonals = crossing_checked(pslg_of(square, {{0, 2, 0}, {1, 3, 0}}), 1);
    REQUIRE(diagonals.points.size() == square.size() + 1);
    CHECK(diagonals.points[square.size()].x == 0.5);
    CHECK(diagonals.points[square.size()].y == 0.5);
    CHECK(diagonals.statistics.constraints.split_segments == 2);
    // A crossing close to an endpoint, by a tiny margin, is still a crossing.
    crossing_checked(pslg_of({{0, 0}, {1, 0}, {0.5, 1e-12}, {0.5, -1}, {0.5, 2}, {0.2, 0.7}},
                             {{0, 1, 0}, {2, 3, 0}}),
                     1);
  }
}

TEST_CASE("cdt: a grid of crossing segments among random points") {
  clmesh::Input pslg;
  pslg.points = fixtures::uniform(3000, 61);
  std::mt19937_64 rng(62);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  const int lines = 25;
  for (int k = 0; k < lines; ++k) {
    const auto a = static_cast<int32_t>(pslg.points.size());
    const double y = u(rng), x = u(rng);
    pslg.points.push_back({-0.1, y});
    pslg.points.push_back({1.1, y + 0.05 * u(rng)});
    pslg.points.push_back({x, -0.1});
    pslg.points.push_back({x + 0.05 * u(rng), 1.1});
    pslg.segments.push_back({a, a + 1, 5});
    pslg.segments.push_back({a + 2, a + 3, 6});
  }
  const auto result = crossings_checked(pslg);
  // Every horizontal line crosses every vertical one (near-horizontal lines may also cross).
  CHECK(result.statistics.constraints.crossings >= lines * lines);
  // Each input segment is a chain through its crossing vertices: n + 1 pieces for n crossings.
  CHECK(result.segments.size() >=
        pslg.segments.size() + 2 * static_cast<std::size_t>(lines * lines));
}

// Issue 32: crossings beyond the first room made for them (1024 and one per
// segment) grow the mesh's arrays, as refinement's do, instead of being
// refused. Each mesh is checked exactly (every input segment a chain of mesh
// edges through its crossings), equals CGAL's CDT of its own points and
// segments, and is the same at two work-group sizes.
TEST_CASE("cdt: thousands of crossings grow the mesh (issue 32)") {
  auto checked = [](const clmesh::Input &pslg) {
    auto options = whole_hull_options();
    options.tuning.work_group = 16;
    const clmesh::Mesh small_groups = clmesh::triangulate(device(), pslg, options);
    options.tuning.work_group = 64;
    const clmesh::Mesh mesh = clmesh::triangulate(device(), pslg, options);
    test_support::check_same_mesh(small_groups, mesh);
    CHECK(test_support::starts_with(mesh.points, pslg.points));
    CHECK(added_points(mesh) == static_cast<std::size_t>(mesh.statistics.constraints.crossings));
    const auto report = clmesh::check_mesh(pslg, mesh, options);
    INFO(problems(report));
    CHECK(report.ok);
#ifdef CLMESH_HAVE_CGAL
    // CGAL's CDT of clmesh's own rounded crossings and pieces: the same mesh.
    compare_with_cgal(pslg_of(mesh.points, mesh.segments), options, mesh);
#endif
    return mesh;
  };
  SUBCASE("400 random segments among 200 points") {
    clmesh::Input pslg;
    pslg.points = fixtures::uniform(200, 71);
    std::mt19937_64 rng(72);
    std::uniform_int_distribution<int32_t> pick(0, 199);
    while (pslg.segments.size() < 400) {
      const int32_t a = pick(rng), b = pick(rng);
      if (a != b)
        pslg.segments.push_back({a, b, 2});
    }
    const auto mesh = checked(pslg);
    CHECK(mesh.statistics.constraints.crossings > 1024 + 400);
  }
  SUBCASE("a star of 1000 spokes through one point, and its ring") {
    // Spoke k from p_k to -p_k: all pass exactly through the origin.
    const int spokes = 1000;
    clmesh::Input pslg;
    for (int k = 0; k < spokes; ++k)
      pslg.points.push_back({std::cos(M_PI * k / spokes), std::sin(M_PI * k / spokes)});
    for (int k = 0; k < spokes; ++k)
      pslg.points.push_back({-pslg.points[k].x, -pslg.points[k].y});
    for (int32_t k = 0; k < spokes; ++k)
      pslg.segments.push_back({k, k + spokes, 3});
    for (int32_t k = 0; k < 2 * spokes; ++k)
      pslg.segments.push_back({k, (k + 1) % (2 * spokes), 1});
    const auto mesh = checked(pslg);
    // One vertex at the centre, every spoke split there.
    REQUIRE(added_points(mesh) == 1);
    CHECK(mesh.points.back().x == 0.0);
    CHECK(mesh.points.back().y == 0.0);
    CHECK(mesh.segments.size() == 4 * static_cast<std::size_t>(spokes));
    CHECK(mesh.triangles.size() == 2 * static_cast<std::size_t>(spokes)); // a sector each
  }
}

// Issue 32: a hole or region seed lying exactly on a segment or at one of
// its vertices starts on neither side of it; it is ignored (and counted), not
// flooded from whichever triangle the walk stopped in. Exact: a seed one ulp
// off the segment is on a side.
TEST_CASE("cdt: hole and region seeds on a segment are ignored (issue 32)") {
  // A square in a square: the ring between them and the inner square.
  clmesh::Input pslg = pslg_of(
      {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {1, 1}, {3, 1}, {3, 3}, {1, 3}},
      {{0, 1, 1}, {1, 2, 1}, {2, 3, 1}, {3, 0, 1}, {4, 5, 2}, {5, 6, 2}, {6, 7, 2}, {7, 4, 2}});
  const clmesh::Mesh whole = clmesh::triangulate(device(), pslg, cdt_options());
  const clmesh::Mesh inner_removed = [&] {
    clmesh::Input with_hole = pslg;
    with_hole.holes = {{2, 2}};
    return clmesh::triangulate(device(), with_hole, cdt_options());
  }();
  REQUIRE(whole.triangles.size() == 10);
  REQUIRE(inner_removed.triangles.size() == 8);
  auto with_holes = [&](std::vector<Point> holes, const char *switches = "p") {
    clmesh::Input input = pslg;
    input.holes = std::move(holes);
    return clmesh::triangulate(device(), input, switches);
  };
  SUBCASE("on a segment, at a segment's vertex, on the outer boundary: the domain is kept") {
    for (const Point hole : {Point{2, 1}, Point{1, 1}, Point{2, 0}, Point{0, 4}, Point{4, 2.5}}) {
      CAPTURE(hole.x);
      CAPTURE(hole.y);
      const clmesh::Mesh mesh = with_holes({hole});
      CHECK(mesh.triangles == whole.triangles);
      CHECK(mesh.statistics.constraints.ignored_holes == 1);
      CHECK(mesh.statistics.constraints.eaten_triangles == 0);
    }
  }
  SUBCASE("beside holes that are not on a segment") {
    const clmesh::Mesh mesh = with_holes({{3, 2}, {2, 2}});
    CHECK(mesh.triangles == inner_removed.triangles);
    CHECK(mesh.statistics.constraints.ignored_holes == 1);
  }
  SUBCASE("one ulp off the segment: on a side") {
    CHECK(with_holes({{2, std::nextafter(1.0, 2.0)}}).triangles == inner_removed.triangles);
    const clmesh::Mesh below = with_holes({{2, std::nextafter(1.0, 0.0)}});
    CHECK(below.triangles.size() == 2); // the ring eaten
    CHECK(below.statistics.constraints.ignored_holes == 0);
  }
  SUBCASE("-O: the holes are not looked at") {
    CHECK(with_holes({{2, 1}}, "pO").statistics.constraints.ignored_holes == 0);
  }
  SUBCASE("a region seed on a segment labels nothing") {
    clmesh::Input input = pslg;
    input.regions = {{{3, 2}, 5, -1}, {{2, 2}, 7, -1}};
    const clmesh::Mesh mesh = clmesh::triangulate(device(), input, "pA");
    REQUIRE(mesh.triangle_attributes.size() == whole.triangles.size());
    CHECK(std::count(mesh.triangle_attributes.begin(), mesh.triangle_attributes.end(), 7.0) == 2);
    CHECK(std::count(mesh.triangle_attributes.begin(), mesh.triangle_attributes.end(), 0.0) == 8);
    CHECK(mesh.statistics.constraints.ignored_regions == 1);
    CHECK(mesh.statistics.constraints.ignored_holes == 0);
  }
}
