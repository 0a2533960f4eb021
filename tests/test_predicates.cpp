// Host-side tests of the exact predicates of cl/predicates.h against CGAL's exact predicates.
#include <doctest/doctest.h>

#include "predicates.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#ifdef CLMESH_HAVE_CGAL
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#endif

namespace {

struct Pt {
  double x, y;
};

bool operator==(const Pt &p, const Pt &q) { return p.x == q.x && p.y == q.y; }

std::string text(const Pt &p) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", p.x, p.y);
  return buf;
}

int orient(const Pt &a, const Pt &b, const Pt &c) {
  return clm_orient2d(a.x, a.y, b.x, b.y, c.x, c.y);
}
int orient_exact(const Pt &a, const Pt &b, const Pt &c) {
  return clm_orient2d_exact(a.x, a.y, b.x, b.y, c.x, c.y);
}
int orient_filter(const Pt &a, const Pt &b, const Pt &c) {
  return clm_orient2d_filter(a.x, a.y, b.x, b.y, c.x, c.y);
}
int incircle(const Pt &a, const Pt &b, const Pt &c, const Pt &d) {
  return clm_incircle(a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y);
}
int incircle_exact(const Pt &a, const Pt &b, const Pt &c, const Pt &d) {
  return clm_incircle_exact(a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y);
}
int incircle_filter(const Pt &a, const Pt &b, const Pt &c, const Pt &d) {
  return clm_incircle_filter(a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y);
}
int incircle_translated(const Pt &a, const Pt &b, const Pt &c, const Pt &d) {
  return clm_incircle_translated(a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y);
}
int sos(const Pt &a, const Pt &b, const Pt &c, const Pt &d) {
  return clm_incircle_sos(a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y);
}
int sos_exact(const Pt &a, const Pt &b, const Pt &c, const Pt &d) {
  return clm_incircle_sos_exact(a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y);
}

// Moves x by k units in the last place.
double nudge(double x, int k) {
  for (; k > 0; --k)
    x = std::nextafter(x, HUGE_VAL);
  for (; k < 0; ++k)
    x = std::nextafter(x, -HUGE_VAL);
  return x;
}

// Counts disagreements and keeps the first one for the failure message.
struct Tally {
  long cases = 0, mismatches = 0, uncertain = 0, zeros = 0;
  long translated = 0; // in-circle cases the translated stage decided
  std::string first;
  void expect(bool good, const std::function<std::string()> &describe) {
    ++cases;
    if (!good && mismatches++ == 0)
      first = describe();
  }
};

// A family of point sets: coordinates x * scale + offset of unit-range values.
struct Family {
  const char *name;
  double scale, offset;
};

const Family kFamilies[] = {
    {"unit", 1.0, 0.0},       {"offset 1e15", 1.0, 1e15},      {"tiny 1e-40", 1e-40, 0.0},
    {"huge 1e40", 1e40, 0.0}, {"offset 1e15 wide", 1e3, 1e15}, {"tiny offset", 1e-40, 3e-38},
};

// A unit-range value, with zero for what would fall under 1e-9 (keeps |x * 1e-40| >= 1e-49).
double unit(std::mt19937_64 &rng) {
  double v = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
  return std::fabs(v) < 1e-9 ? 0.0 : v;
}

Pt random_point(std::mt19937_64 &rng, const Family &f) {
  return {unit(rng) * f.scale + f.offset, unit(rng) * f.scale + f.offset};
}

// A point on the segment ab (rounded), moved by up to `spread` ulps per coordinate.
Pt near_segment(std::mt19937_64 &rng, const Pt &a, const Pt &b, int spread) {
  const double t = std::uniform_real_distribution<double>(-0.5, 1.5)(rng);
  std::uniform_int_distribution<int> k(-spread, spread);
  return {nudge(a.x + t * (b.x - a.x), k(rng)), nudge(a.y + t * (b.y - a.y), k(rng))};
}

// A point on the circle (rounded), moved by up to `spread` ulps per coordinate.
Pt near_circle(std::mt19937_64 &rng, const Pt &center, double radius, int spread) {
  const double angle = std::uniform_real_distribution<double>(0.0, 6.283185307179586)(rng);
  std::uniform_int_distribution<int> k(-spread, spread);
  return {nudge(center.x + radius * std::cos(angle), k(rng)),
          nudge(center.y + radius * std::sin(angle), k(rng))};
}

// Lattice points of x^2 + y^2 == r^2, counter-clockwise from the positive x axis.
std::vector<Pt> lattice_circle(int r) {
  std::vector<Pt> pts;
  for (int x = -r; x <= r; ++x)
    for (int y = -r; y <= r; ++y)
      if (x * x + y * y == r * r)
        pts.push_back({double(x), double(y)});
  std::sort(pts.begin(), pts.end(),
            [](const Pt &p, const Pt &q) { return std::atan2(p.y, p.x) < std::atan2(q.y, q.x); });
  return pts;
}

// Exactly representable affine images (power-of-two scale, integer offsets) of a point set.
std::vector<Pt> transformed(const std::vector<Pt> &pts, int exponent, double offset) {
  std::vector<Pt> out;
  for (const Pt &p : pts)
    out.push_back({std::ldexp(p.x, exponent) + offset, std::ldexp(p.y, exponent) + offset});
  return out;
}

// The perturbation rule written out independently: leading point of the lexicographic order
// decides (see clm_incircle_perturbed).
int rule_sos(const Pt &a, const Pt &b, const Pt &c, const Pt &d) {
  const int s = incircle_exact(a, b, c, d);
  if (s != 0)
    return s;
  const Pt *pts[4] = {&a, &b, &c, &d};
  std::sort(pts, pts + 4,
            [](const Pt *p, const Pt *q) { return p->x < q->x || (p->x == q->x && p->y < q->y); });
  for (int i = 3; i > 0; --i) {
    int o = 0;
    if (pts[i] == &d)
      return -1;
    if (pts[i] == &c)
      o = orient_exact(a, b, d);
    if (pts[i] == &b)
      o = orient_exact(a, d, c);
    if (pts[i] == &a)
      o = orient_exact(d, b, c);
    if (o != 0)
      return o;
  }
  return -1;
}

#ifdef CLMESH_HAVE_CGAL
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using KP = K::Point_2;
KP kp(const Pt &p) { return KP(p.x, p.y); }
int cgal_orient(const Pt &a, const Pt &b, const Pt &c) {
  return static_cast<int>(CGAL::orientation(kp(a), kp(b), kp(c)));
}
int cgal_incircle(const Pt &a, const Pt &b, const Pt &c, const Pt &d) {
  return static_cast<int>(CGAL::side_of_oriented_circle(kp(a), kp(b), kp(c), kp(d)));
}
int cgal_sos(const Pt &a, const Pt &b, const Pt &c, const Pt &d) {
  static const CGAL::Delaunay_triangulation_2<K> dt;
  return static_cast<int>(dt.side_of_oriented_circle(kp(a), kp(b), kp(c), kp(d), true));
}

// Checks every orientation entry point on one case against CGAL.
void check_orient_case(Tally &tally, const Pt &a, const Pt &b, const Pt &c) {
  const int ref = cgal_orient(a, b, c);
  const int exact = orient_exact(a, b, c), full = orient(a, b, c), filter = orient_filter(a, b, c);
  tally.uncertain += filter == CLM_UNCERTAIN;
  tally.zeros += ref == 0;
  tally.expect(exact == ref && full == ref && (filter == CLM_UNCERTAIN || filter == ref) &&
                   orient_exact(b, c, a) == ref && orient_exact(b, a, c) == -ref,
               [&] {
                 return "orient " + text(a) + text(b) + text(c) + ": CGAL " + std::to_string(ref) +
                        ", exact " + std::to_string(exact) + ", full " + std::to_string(full) +
                        ", filter " + std::to_string(filter);
               });
}

// Checks every in-circle entry point on one case against CGAL.
void check_incircle_case(Tally &tally, const Pt &a, const Pt &b, const Pt &c, const Pt &d) {
  const int ref = cgal_incircle(a, b, c, d);
  const int exact = incircle_exact(a, b, c, d), full = incircle(a, b, c, d);
  const int filter = incircle_filter(a, b, c, d), translated = incircle_translated(a, b, c, d);
  tally.uncertain += filter == CLM_UNCERTAIN;
  tally.zeros += ref == 0;
  tally.translated += translated != CLM_UNCERTAIN;
  bool good = exact == ref && full == ref && (filter == CLM_UNCERTAIN || filter == ref) &&
              (translated == CLM_UNCERTAIN || translated == ref) &&
              incircle_exact(b, c, a, d) == ref && incircle_exact(b, a, c, d) == -ref;
  int s = 0, se = 0, sref = 0;
  const bool sos_applies = orient_exact(a, b, c) > 0 && !(d == a) && !(d == b) && !(d == c);
  if (sos_applies) {
    s = sos(a, b, c, d);
    se = sos_exact(a, b, c, d);
    sref = cgal_sos(a, b, c, d);
    good = good && s == sref && se == sref && (ref == 0 || s == ref);
  }
  tally.expect(good, [&] {
    return "incircle " + text(a) + text(b) + text(c) + text(d) + ": CGAL " + std::to_string(ref) +
           ", exact " + std::to_string(exact) + ", full " + std::to_string(full) + ", filter " +
           std::to_string(filter) + ", translated " + std::to_string(translated) + ", sos " +
           std::to_string(s) + "/" + std::to_string(se) + " CGAL sos " + std::to_string(sref);
  });
}

void report(const std::string &what, const Tally &tally) {
  INFO(what << ": " << tally.cases << " cases, " << tally.uncertain << " uncertain filter, "
            << tally.zeros << " exact zeros; first mismatch: " << tally.first);
  CHECK(tally.mismatches == 0);
  MESSAGE(what << ": " << tally.cases << " cases, " << tally.uncertain
               << " needed the exact stage, " << tally.zeros << " exactly degenerate, "
               << tally.translated << " decided on exact differences");
}
#endif

} // namespace

TEST_CASE("predicates: simple signs") {
  const Pt o{0, 0}, x{1, 0}, y{0, 1}, xy{1, 1};
  CHECK(orient(o, x, y) == 1);
  CHECK(orient(o, y, x) == -1);
  CHECK(orient(o, x, Pt{2, 0}) == 0);
  CHECK(orient_filter(o, x, Pt{2, 0}) == 0); // certain zero: both products exactly zero
  CHECK(orient_exact(o, x, Pt{2, 0}) == 0);
  CHECK(incircle(o, x, y, Pt{0.5, 0.5}) == 1);
  CHECK(incircle(o, x, y, Pt{2, 2}) == -1);
  CHECK(incircle(o, x, y, xy) == 0);
  CHECK(incircle_exact(o, x, y, xy) == 0);
  CHECK(incircle_filter(o, x, y, xy) == CLM_UNCERTAIN);
  CHECK(incircle(o, y, x, Pt{0.5, 0.5}) == -1); // clockwise triangle: sign flips
  // Zero coordinates everywhere.
  CHECK(orient_exact(o, o, o) == 0);
  CHECK(incircle_exact(o, o, o, o) == 0);
  // The square is split along (1,0)-(0,1): (0,1) is outside the circle of (0,0),(1,0),(1,1)
  // under the perturbation, and (1,1) outside that of (0,0),(1,0),(0,1).
  CHECK(sos(o, x, xy, y) == 1);
  CHECK(sos(o, x, y, xy) == -1);
  CHECK(sos_exact(o, x, xy, y) == 1);
  CHECK(sos_exact(o, x, y, xy) == -1);
}

TEST_CASE("predicates: Shewchuk's near-collinear grid") {
  // a walks a 64 x 64 grid of ulps around (0.5, 0.5); b, c on the line y = x.
  const double u = std::ldexp(1.0, -53);
  const Pt b{12, 12}, c{24, 24};
  long positive = 0, negative = 0, zero = 0, wrong_filter = 0;
#ifdef CLMESH_HAVE_CGAL
  Tally tally;
#endif
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const Pt a{0.5 + i * u, 0.5 + j * u};
      const int s = orient(a, b, c);
      // Exactly: sign of (a - c) x (b - c) = 12 * ((ay - 24) - (ax - 24)) = 12 (j - i) u.
      CHECK(s == (j > i) - (j < i));
      positive += s > 0, negative += s < 0, zero += s == 0;
      const int f = orient_filter(a, b, c);
      wrong_filter += f != CLM_UNCERTAIN && f != s;
#ifdef CLMESH_HAVE_CGAL
      check_orient_case(tally, a, b, c);
#endif
    }
  CHECK(zero == 64);
  CHECK(wrong_filter == 0);
#ifdef CLMESH_HAVE_CGAL
  report("near-collinear grid", tally);
#endif
}

#ifdef CLMESH_HAVE_CGAL
TEST_CASE("predicates: orient2d agrees with CGAL on hard families") {
  std::mt19937_64 rng(20240601);
  for (const Family &f : kFamilies) {
    Tally tally;
    for (int k = 0; k < 4000; ++k) {
      const Pt a = random_point(rng, f), c = random_point(rng, f);
      const Pt b = near_segment(rng, a, c, k % 5); // exact zeros likely with spread 0
      switch (k % 3) {
      case 0:
        check_orient_case(tally, a, b, c);
        break;
      case 1:
        check_orient_case(tally, b, c, a);
        break;
      default:
        check_orient_case(tally, c, b, a);
        break;
      }
    }
    report(std::string("orient2d near-collinear, ") + f.name, tally);
  }
}

TEST_CASE("predicates: orient2d agrees with CGAL on zeros and mixed magnitudes") {
  std::mt19937_64 rng(7);
  const double values[] = {0.0, 1.0, -1.0, 2.0, 0.5, -3.0, 1e-40, -1e-40, 1e40, 3e-50, 1e50};
  std::uniform_int_distribution<int> pick(0, sizeof values / sizeof values[0] - 1);
  Tally tally;
  for (int k = 0; k < 20000; ++k) {
    Pt p[3];
    for (Pt &q : p)
      q = {values[pick(rng)], values[pick(rng)]};
    check_orient_case(tally, p[0], p[1], p[2]);
  }
  // Mixed magnitudes with full mantissas.
  std::uniform_real_distribution<double> mant(0.5, 1.0);
  const double scales[] = {0.0, 1e-45, 1e-20, 1.0, 1e20, 1e45};
  std::uniform_int_distribution<int> pick_scale(0, 5);
  for (int k = 0; k < 20000; ++k) {
    Pt p[3];
    for (Pt &q : p)
      q = {mant(rng) * scales[pick_scale(rng)] * (k & 1 ? 1 : -1),
           mant(rng) * scales[pick_scale(rng)]};
    check_orient_case(tally, p[0], p[1], p[2]);
  }
  report("orient2d zeros and mixed magnitudes", tally);
}

TEST_CASE("predicates: incircle agrees with CGAL on hard families") {
  std::mt19937_64 rng(1997);
  for (const Family &f : kFamilies) {
    Tally tally;
    for (int k = 0; k < 4000; ++k) {
      const Pt center = random_point(rng, f);
      const double radius = (0.25 + 0.5 * std::fabs(unit(rng))) * f.scale;
      const int spread = k % 4; // spread 0: on the circle up to rounding
      Pt a = near_circle(rng, center, radius, spread), b = near_circle(rng, center, radius, spread);
      Pt c = near_circle(rng, center, radius, spread), d = near_circle(rng, center, radius, spread);
      if (orient_exact(a, b, c) < 0)
        std::swap(a, b); // mostly counter-clockwise, so that the perturbed test applies
      check_incircle_case(tally, a, b, c, d);
    }
    report(std::string("incircle near-cocircular, ") + f.name, tally);
  }
  // Near-collinear triangles (huge circumcircles) with a fourth point near the line.
  Tally tally;
  for (const Family &f : kFamilies) {
    for (int k = 0; k < 1000; ++k) {
      const Pt a = random_point(rng, f), c = random_point(rng, f);
      const Pt b = near_segment(rng, a, c, 3), d = near_segment(rng, a, c, 3);
      check_incircle_case(tally, a, b, c, d);
    }
  }
  report("incircle near-collinear", tally);
}

TEST_CASE("predicates: incircle agrees with CGAL on zeros and mixed magnitudes") {
  std::mt19937_64 rng(11);
  const double values[] = {0.0, 1.0, -1.0, 2.0, 0.5, -3.0, 1e-40, -1e-40, 1e40, 3e-50, 1e50};
  std::uniform_int_distribution<int> pick(0, sizeof values / sizeof values[0] - 1);
  Tally tally;
  for (int k = 0; k < 20000; ++k) {
    Pt p[4];
    for (Pt &q : p)
      q = {values[pick(rng)], values[pick(rng)]};
    check_incircle_case(tally, p[0], p[1], p[2], p[3]);
  }
  std::uniform_real_distribution<double> mant(0.5, 1.0);
  const double scales[] = {0.0, 1e-45, 1e-20, 1.0, 1e20, 1e45};
  std::uniform_int_distribution<int> pick_scale(0, 5);
  for (int k = 0; k < 20000; ++k) {
    Pt p[4];
    for (Pt &q : p)
      q = {mant(rng) * scales[pick_scale(rng)] * (k & 1 ? 1 : -1),
           mant(rng) * scales[pick_scale(rng)]};
    check_incircle_case(tally, p[0], p[1], p[2], p[3]);
  }
  report("incircle zeros and mixed magnitudes", tally);
}

TEST_CASE("predicates: perturbed incircle on cocircular and grid sets") {
  // Exactly cocircular lattice points (radius 5: 12 points, 25: 20 points), small integer
  // grids (many cocircular and collinear subsets), and exact images of them far from the
  // origin, tiny and huge.
  std::vector<std::vector<Pt>> sets = {lattice_circle(5), lattice_circle(25)};
  std::vector<Pt> grid;
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      grid.push_back({double(x), double(y)});
  sets.push_back(grid);
  const std::size_t base = sets.size();
  for (std::size_t s = 0; s < base; ++s) {
    sets.push_back(transformed(sets[s], 0, 1e15));
    sets.push_back(transformed(sets[s], -140, 0));   // ~1e-42
    sets.push_back(transformed(sets[s], 130, 0));    // ~1e39
    sets.push_back(transformed(sets[s], -3, -1e12)); // fractions, negative offset
  }
  Tally tally;
  long zero_det = 0;
  for (const std::vector<Pt> &pts : sets) {
    const std::size_t m = pts.size();
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = 0; j < m; ++j)
        for (std::size_t k = 0; k < m; ++k) {
          if (orient_exact(pts[i], pts[j], pts[k]) <= 0)
            continue;
          for (std::size_t l = 0; l < m; ++l) {
            if (l == i || l == j || l == k)
              continue;
            const Pt &a = pts[i], &b = pts[j], &c = pts[k], &d = pts[l];
            const int s = sos(a, b, c, d), se = sos_exact(a, b, c, d);
            const int ref = cgal_sos(a, b, c, d), rule = rule_sos(a, b, c, d);
            const bool zero = incircle_exact(a, b, c, d) == 0;
            zero_det += zero;
            tally.zeros += zero;
            tally.uncertain += incircle_filter(a, b, c, d) == CLM_UNCERTAIN;
            // Rotating the triangle keeps the perturbed determinant.
            const int rotated = sos(b, c, a, d);
            tally.expect(s != 0 && s == se && s == ref && s == rule && rotated == s, [&] {
              return "sos " + text(a) + text(b) + text(c) + text(d) + ": " + std::to_string(s) +
                     "/" + std::to_string(se) + ", rotated " + std::to_string(rotated) + ", CGAL " +
                     std::to_string(ref) + ", rule " + std::to_string(rule);
            });
          }
        }
  }
  CHECK(zero_det > 10000);
  report("perturbed incircle, cocircular sets", tally);
}
#endif

TEST_CASE("predicates: perturbed incircle picks exactly one diagonal of a cocircular quad") {
  // For a convex quadrilateral a, b, c, d (counter-clockwise) on one circle, diagonal ac is
  // kept when d is outside the perturbed circle of abc; seen from the other triangle c, d, a
  // the test must agree (an even permutation of the determinant's rows), and diagonal bd is
  // kept when a is outside the circle of bcd: the opposite answer (an odd permutation).  So
  // exactly one diagonal is locally Delaunay and the flip algorithm cannot cycle.
  std::vector<std::vector<Pt>> circles = {lattice_circle(5), lattice_circle(25),
                                          lattice_circle(65)};
  const std::size_t base = circles.size();
  for (std::size_t s = 0; s < base; ++s) {
    circles.push_back(transformed(circles[s], 0, 1e15));
    circles.push_back(transformed(circles[s], -150, 0));
    circles.push_back(transformed(circles[s], 140, 0));
  }
  // Axis-aligned rectangles: the most common cocircular quads (grids).
  circles.push_back({{2, 1}, {0, 1}, {0, 0}, {2, 0}});
  circles.push_back({{1e15 + 2, 7}, {1e15, 7}, {1e15, 3}, {1e15 + 2, 3}});
  long quads = 0, bad = 0, ac_kept = 0;
  std::string first;
  for (const std::vector<Pt> &pts : circles) {
    const std::size_t m = pts.size();
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = i + 1; j < m; ++j)
        for (std::size_t k = j + 1; k < m; ++k)
          for (std::size_t l = k + 1; l < m; ++l) {
            const Pt &a = pts[i], &b = pts[j], &c = pts[k], &d = pts[l];
            REQUIRE(incircle_exact(a, b, c, d) == 0);
            const int ac1 = sos(a, b, c, d), ac2 = sos(c, d, a, b);
            const int bd1 = sos(b, c, d, a), bd2 = sos(d, a, b, c);
            ++quads;
            ac_kept += ac1 < 0;
            if (!(ac1 == ac2 && bd1 == bd2 && ac1 == -bd1 && ac1 != 0) && bad++ == 0)
              first = text(a) + text(b) + text(c) + text(d);
          }
  }
  INFO("first inconsistent quad: " << first);
  CHECK(bad == 0);
  CHECK(ac_kept > 0);
  CHECK(ac_kept < quads);
  MESSAGE(quads << " cocircular quads, diagonal ac kept in " << ac_kept);
}

TEST_CASE("predicates: filters never certify a wrong sign") {
  // Random near-degenerate inputs at every scale; the exact stage is the reference.
  std::mt19937_64 rng(42);
  long orient_certain = 0, incircle_certain = 0, wrong = 0;
  for (const Family &f : kFamilies) {
    for (int k = 0; k < 20000; ++k) {
      const Pt a = random_point(rng, f), c = random_point(rng, f);
      const Pt b = near_segment(rng, a, c, 8);
      const int fo = orient_filter(a, b, c), eo = orient_exact(a, b, c);
      if (fo != CLM_UNCERTAIN) {
        ++orient_certain;
        wrong += fo != eo;
      }
      const Pt center = random_point(rng, f);
      const double radius = 0.5 * f.scale;
      const Pt p = near_circle(rng, center, radius, 8), q = near_circle(rng, center, radius, 8);
      const Pt r = near_circle(rng, center, radius, 8), s = near_circle(rng, center, radius, 8);
      const int fi = incircle_filter(p, q, r, s), ei = incircle_exact(p, q, r, s);
      if (fi != CLM_UNCERTAIN) {
        ++incircle_certain;
        wrong += fi != ei;
      }
      CHECK(fi != 0); // the in-circle filter only certifies non-zero signs
    }
  }
  CHECK(wrong == 0);
  CHECK(orient_certain > 0);
  CHECK(incircle_certain > 0);
}

TEST_CASE("predicates: the in-circle stage in doubles answers only with the exact sign") {
  // Lattice points (small integers, dyadic fractions, far from the origin,
  // tiny and huge scales), cocircular or nearly so, and points a few ulps off
  // the lattice: whenever the stage answers, its sign (zero included) is the
  // exact determinant's.
  std::mt19937_64 rng(11);
  long answered = 0, zeros = 0, wrong = 0;
  for (const double scale : {1.0, 0.0078125, 1024.0, 0x1p-150, 0x1p140}) {
    for (const double origin : {0.0, 3.0, 1e6, -12345.0}) {
      std::uniform_int_distribution<int> coordinate(-40, 40);
      for (int k = 0; k < 20000; ++k) {
        auto lattice = [&] {
          return Pt{origin + scale * coordinate(rng), origin + scale * coordinate(rng)};
        };
        Pt p[4] = {lattice(), lattice(), lattice(), lattice()};
        if (k % 3 == 1) { // a square's corners: cocircular
          const double x = origin + scale * coordinate(rng), y = origin + scale * coordinate(rng);
          const double side = scale * (1 + (coordinate(rng) & 7));
          p[0] = {x, y}, p[1] = {x + side, y}, p[2] = {x + side, y + side}, p[3] = {x, y + side};
        }
        if (k % 5 == 2) // one point a few ulps off
          p[k % 4].x = std::nextafter(std::nextafter(p[k % 4].x, 1e300), 1e300);
        const int stage =
            clm_incircle_in_doubles(p[0].x, p[0].y, p[1].x, p[1].y, p[2].x, p[2].y, p[3].x, p[3].y);
        if (stage == CLM_UNCERTAIN)
          continue;
        ++answered;
        zeros += stage == 0;
        const int exact =
            clm_incircle_exact(p[0].x, p[0].y, p[1].x, p[1].y, p[2].x, p[2].y, p[3].x, p[3].y);
        if (stage != exact) {
          ++wrong;
          INFO(text(p[0]) << " " << text(p[1]) << " " << text(p[2]) << " " << text(p[3]));
          CHECK(stage == exact);
        }
      }
    }
  }
  CHECK(wrong == 0);
  CHECK(answered > 100000); // lattices are its case
  CHECK(zeros > 10000);
  // Rounded differences, or factors of more than 26 bits: the expansions decide.
  CHECK(clm_incircle_in_doubles(0.1, 0.2, 0.3, 0.5, 0.7, 0.11, 0.13, 0.17) == CLM_UNCERTAIN);
  CHECK(clm_incircle_in_doubles(0, 0, 1 + 0x1p-40, 0, 1, 1, 0, 1) == CLM_UNCERTAIN);
}

TEST_CASE("predicates: expansion arithmetic keeps exact values") {
  // (2^60 + 1) * (2^60 - 1) = 2^120 - 1 needs three doubles: check sign of the difference
  // with 2^120 through the exact minor, and a sum that cancels to zero.
  const double big = std::ldexp(1.0, 60);
  double p[CLM_LEN_MINOR];
  // (big + 1) rounds to big in double, so use exactly representable factors.
  const double a = std::ldexp(1.0, 52) + 1, b = std::ldexp(1.0, 52) - 1; // product 2^104 - 1
  int n = clm_minor2(a, 1.0, std::ldexp(1.0, 104), b, p);                // a*b - 1*2^104 = -1
  CHECK(clm_expansion_sign(n, p) == -1);
  double sum = 0;
  for (int i = 0; i < n; ++i)
    sum += p[i];
  CHECK(sum == -1.0);
  n = clm_minor2(big, big, big, big, p); // exactly zero
  CHECK(n == 1);
  CHECK(p[0] == 0.0);
  // Scaling by zero and summing zeros give the one-component zero expansion.
  double e[2] = {1.0, big}, h[4];
  CHECK(clm_scale_expansion(2, e, 0.0, h) == 1);
  CHECK(h[0] == 0.0);
  double z[1] = {0.0};
  CHECK(clm_expansion_sum(1, z, 1, z, h) == 1);
  CHECK(h[0] == 0.0);
}
