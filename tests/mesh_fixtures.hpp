// Point sets for the tests: the thesis distributions and harder cases.
#pragma once

#include "clmesh/geometry.hpp"

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace fixtures {

using clmesh::Point;

inline std::vector<Point> uniform(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point> p(n);
  for (auto &q : p)
    q = {u(rng), u(rng)};
  return p;
}

inline std::vector<Point> gaussian(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::vector<Point> p(n);
  for (auto &q : p)
    q = {g(rng), g(rng)};
  return p;
}

inline std::vector<Point> disk(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Point> p;
  while (static_cast<int>(p.size()) < n) {
    const double x = u(rng), y = u(rng);
    if (x * x + y * y <= 1)
      p.push_back({x, y});
  }
  return p;
}

// Points on the unit circle (as rounded by floating point), the thesis's
// "circle" distribution: nearly every point is on the hull, many are cocircular.
inline std::vector<Point> circle(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 2 * M_PI);
  std::vector<Point> p(n);
  for (auto &q : p) {
    const double a = u(rng);
    q = {std::cos(a), std::sin(a)};
  }
  return p;
}

// The benchmark's thin circle: radii uniform in [1 - thickness / 2,
// 1 + thickness / 2), a band only a few points wide.
inline std::vector<Point> ring(int n, double thickness, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), jitter(-0.5, 0.5);
  std::vector<Point> p(n);
  for (auto &q : p) {
    const double a = angle(rng), r = 1 + thickness * jitter(rng);
    q = {r * std::cos(a), r * std::sin(a)};
  }
  return p;
}

// `clusters` Gaussian clusters of standard deviation `spread` around
// uniform centres in the unit square, `n` points in all, dealt in turn: with
// a tiny spread, each cluster lies in one cell of a fine grid over the square.
inline std::vector<Point> clusters(int n, int clusters, double spread, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g(0, spread);
  std::vector<Point> centre(static_cast<std::size_t>(clusters));
  for (auto &c : centre)
    c = {u(rng), u(rng)};
  std::vector<Point> p(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point &c = centre[i % centre.size()];
    p[i] = {c.x + g(rng), c.y + g(rng)};
  }
  return p;
}

// Hard for the digital Voronoi construction: uniform points, a ring of
// points on one circle, and a run along one line with every other point a
// hair (1e-12) above it.
inline std::vector<Point> rings_and_hairs(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point> p(n);
  for (auto &q : p) {
    const double kind = u(rng), t = u(rng);
    if (kind < 0.3)
      q = {t, u(rng)};
    else if (kind < 0.6)
      q = {0.5 + 0.4 * std::cos(2 * M_PI * t), 0.5 + 0.4 * std::sin(2 * M_PI * t)};
    else
      q = {t, 0.5 + (u(rng) < 0.5 ? 1e-12 : 0.0)};
  }
  return p;
}

// Points on four circles, two of them 1e-7 apart.
inline std::vector<Point> concentric_rings(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI);
  const double radii[4] = {1, 1 + 1e-7, 2, 3};
  std::vector<Point> p(n);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double a = angle(rng), r = radii[i % 4];
    p[i] = {r * std::cos(a), r * std::sin(a)};
  }
  return p;
}

// A third as many points as asked, each repeated up to three times, some
// copies moved by 1e-15.
inline std::vector<Point> near_duplicates(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point> base(static_cast<std::size_t>(n / 3 + 1));
  for (auto &q : base)
    q = {u(rng), u(rng)};
  std::uniform_int_distribution<std::size_t> pick(0, base.size() - 1);
  const double nudge[3] = {0, 1e-15, -1e-15};
  std::vector<Point> p(n);
  for (auto &q : p) {
    const Point b = base[pick(rng)];
    q = {b.x + nudge[pick(rng) % 3], b.y + nudge[pick(rng) % 2]};
  }
  return p;
}

inline std::vector<Point> lattice(int side, double spacing = 1, Point origin = {0, 0}) {
  std::vector<Point> p;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      p.push_back({origin.x + i * spacing, origin.y + j * spacing});
  return p;
}

// Reads the [[x, y], ...] arrays of the delaunator fixtures.
inline std::vector<Point> json_points(const std::string &path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  for (char &c : s)
    if (c == '[' || c == ']' || c == ',')
      c = ' ';
  std::istringstream numbers(s);
  std::vector<Point> p;
  double x, y;
  while (numbers >> x >> y)
    p.push_back({x, y});
  return p;
}

} // namespace fixtures
