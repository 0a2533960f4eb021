// clmesh — the GPU-DT scheduler (thesis §4.1.2): runs the phases on one
// device, keeping the mesh resident from the upload of the points to the
// download of the triangles; between kernels only small counters come back.
#include "dt/delaunay_scheduler.hpp"

#include "dt/shifting.hpp"
#include "dt/simple_loop.hpp"
#include "dt/triangulation_construction.hpp"
#include "predicates.h"
#include "runtime/host_memory.hpp"
#include "runtime/host_threads.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

namespace clmesh {

namespace {

// first: the number of points[0]; added: they were computed (where segments cross).
void check_coordinates(const std::vector<Point> &points, std::size_t first = 0,
                       bool added = false) {
  for (std::size_t i = 0; i < points.size(); ++i)
    for (const double value : {points[i].x, points[i].y}) {
      const double magnitude = std::fabs(value);
      if (!std::isfinite(value) || magnitude > kMaxCoordinate ||
          (value != 0 && magnitude < kMinCoordinate)) {
        char text[64];
        std::snprintf(text, sizeof text, "%.17g", value);
        throw InputError("point " + std::to_string(first + i), 0,
                         std::string("coordinate ") + text +
                             (added ? " (where segments cross)" : "") +
                             " is outside what exact arithmetic carries (non-zero magnitudes "
                             "from 1e-50 to 1e50)");
      }
    }
}

bool lexicographically_less(const Point &a, const Point &b) {
  return a.x < b.x || (a.x == b.x && a.y < b.y);
}

int orient(const Point &a, const Point &b, const Point &c) {
  return clm_orient2d(a.x, a.y, b.x, b.y, c.x, c.y);
}

// orient(a, b, p) > 0, exactly: a rounded determinant beyond its error bound
// (a larger one than Shewchuk's first stage) tells at once, as it does for
// nearly every point of a hull test; orient() decides the rest.
bool strictly_left(const Point &a, const Point &b, const Point &p) {
  const double left = (b.x - a.x) * (p.y - a.y), right = (b.y - a.y) * (p.x - a.x);
  const double bound =
      4 * std::numeric_limits<double>::epsilon() * (std::abs(left) + std::abs(right));
  return left - right > bound || (left - right >= -bound && orient(a, b, p) > 0);
}

// Duplicates of a point set with no triangle (all points collinear).
std::vector<int32_t> duplicates_on_host(const std::vector<Point> &points) {
  std::vector<int32_t> order(points.size()), duplicate_of(points.size(), -1);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
    return lexicographically_less(points[a], points[b]);
  });
  for (std::size_t i = 1; i < order.size(); ++i) {
    const Point &p = points[order[i]], &q = points[order[i - 1]];
    if (p.x == q.x && p.y == q.y)
      duplicate_of[order[i]] =
          duplicate_of[order[i - 1]] >= 0 ? duplicate_of[order[i - 1]] : order[i - 1];
  }
  return duplicate_of;
}

// The Hilbert curve on a 2^16 x 2^16 grid, four bits of x and y at a time:
// for each orientation of the curve (x and y swapped, both complemented) and
// each 4x4-bit input, the eight bits of curve position it contributes and the
// orientation that follows.
struct HilbertTable {
  std::array<std::array<uint8_t, 256>, 4> digits{}, next{};
  HilbertTable() {
    for (uint32_t orientation = 0; orientation < 4; ++orientation)
      for (uint32_t in = 0; in < 256; ++in) {
        uint32_t swapped = orientation & 1, complemented = orientation >> 1, d = 0;
        for (int b = 3; b >= 0; --b) {
          const uint32_t bx = (in >> (4 + b)) & 1, by = (in >> b) & 1;
          const uint32_t x = (swapped ? by : bx) ^ complemented,
                         y = (swapped ? bx : by) ^ complemented;
          d = (d << 2) | ((3 * x) ^ y); // quadrants 0, 1, 2, 3 along the curve
          if (y == 0) {                 // lower quadrants turn the curve
            complemented ^= x;
            swapped ^= 1;
          }
        }
        digits[orientation][in] = static_cast<uint8_t>(d);
        next[orientation][in] = static_cast<uint8_t>(swapped | (complemented << 1));
      }
  }
};

// Position along the Hilbert curve of a point quantized to the 2^16 x 2^16 grid.
uint32_t hilbert_index(uint32_t x, uint32_t y) {
  static const HilbertTable table;
  uint32_t d = 0, orientation = 0;
  for (int b = 12; b >= 0; b -= 4) {
    const uint32_t in = (((x >> b) & 15) << 4) | ((y >> b) & 15);
    d = (d << 8) | table.digits[orientation][in];
    orientation = table.next[orientation][in];
  }
  return d;
}

// (key << 32) | index of point p for the Hilbert curve over the square of
// side 65535 / scale from `low`.
uint64_t hilbert_entry(const Point &p, Point low, double scale, std::size_t index) {
  const auto qx = static_cast<uint32_t>(std::min(65535.0, (p.x - low.x) * scale));
  const auto qy = static_cast<uint32_t>(std::min(65535.0, (p.y - low.y) * scale));
  return (static_cast<uint64_t>(hilbert_index(qx, qy)) << 32) | index;
}

// Runs of more than this many points in one cell of the 2^16 x 2^16 grid
// (a cluster far smaller than the input's extent) are ordered again inside
// the cell, to at most kMostRefinements levels of cells in cells.
constexpr std::size_t kCrowdedCell = 32;
constexpr int kMostRefinements = 4;

// The runs [i, j) of more than kCrowdedCell equal keys in the sorted
// entry[first .. last).
std::vector<std::pair<std::size_t, std::size_t>> crowded_runs(const std::vector<uint64_t> &entry,
                                                              std::size_t first, std::size_t last) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  for (std::size_t i = first; i < last;) {
    std::size_t j = i + 1;
    while (j < last && entry[j] >> 32 == entry[i] >> 32)
      ++j;
    if (j - i > kCrowdedCell)
      runs.emplace_back(i, j);
    i = j;
  }
  return runs;
}

// Orders the crowded run entry[first .. last) ((key << 32) | index, of one
// key: in the input's order, which inside a cluster is no spatial order at
// all) again, along a Hilbert curve over its own points' bounding square;
// then its own crowded runs likewise, `depth` counting the levels.
void order_cell_again(const std::vector<Point> &points, std::vector<uint64_t> &entry,
                      std::size_t first, std::size_t last, int depth) {
  const auto point = [&](std::size_t k) { return points[entry[k] & 0xffffffffu]; };
  Point low = point(first), high = point(first);
  for (std::size_t k = first + 1; k < last; ++k) {
    low = {std::min(low.x, point(k).x), std::min(low.y, point(k).y)};
    high = {std::max(high.x, point(k).x), std::max(high.y, point(k).y)};
  }
  const double span = std::max(high.x - low.x, high.y - low.y);
  if (!(span > 0 && std::isfinite(span)))
    return; // all one point
  for (std::size_t k = first; k < last; ++k)
    entry[k] = hilbert_entry(point(k), low, 65535.0 / span, entry[k] & 0xffffffffu);
  std::sort(entry.begin() + static_cast<std::ptrdiff_t>(first),
            entry.begin() + static_cast<std::ptrdiff_t>(last));
  if (depth + 1 < kMostRefinements)
    for (const auto &[i, j] : crowded_runs(entry, first, last))
      order_cell_again(points, entry, i, j, depth + 1);
}

// Input indices sorted along a Hilbert curve (stable, so ties keep input
// order), crowded cells ordered again (order_cell_again).
std::vector<int32_t> spatial_order(const std::vector<Point> &points) {
  const auto [low, span] = bounding_square(points);
  const double scale = span > 0 && std::isfinite(span) ? 65535.0 / span : 0.0;
  const std::size_t n = points.size();
  const int parts = host_threads(n);
  // (key, index) pairs, sorted by three stable counting passes of 11 bits
  // over the key (the index in the low half keeps ties in input order).
  std::vector<uint64_t> entry(n), buffer(n);
  run_parts(parts, [&](int part, int) {
    const auto [first, end] = part_range(n, part, parts);
    for (std::size_t i = first; i < end; ++i)
      entry[i] = hilbert_entry(points[i], low, scale, i);
  });
  constexpr int kDigitBits = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;
  for (int shift = 32; shift < 64; shift += kDigitBits) {
    // Each part counts its entries' digits; in each bucket, a part's
    // entries follow those of the parts before it, as one pass would place them.
    std::vector<std::array<std::size_t, kBuckets>> start(static_cast<std::size_t>(parts));
    const auto digit = [shift](uint64_t e) { return (e >> shift) & (kBuckets - 1); };
    run_parts(parts, [&](int part, int) {
      std::array<std::size_t, kBuckets> &count = start[static_cast<std::size_t>(part)];
      count.fill(0);
      const auto [first, end] = part_range(n, part, parts);
      for (std::size_t i = first; i < end; ++i)
        ++count[digit(entry[i])];
    });
    std::size_t placed = 0;
    for (std::size_t b = 0; b < kBuckets; ++b)
      for (std::array<std::size_t, kBuckets> &count : start) {
        const std::size_t here = count[b];
        count[b] = placed;
        placed += here;
      }
    run_parts(parts, [&](int part, int) {
      std::array<std::size_t, kBuckets> &cursor = start[static_cast<std::size_t>(part)];
      const auto [first, end] = part_range(n, part, parts);
      for (std::size_t i = first; i < end; ++i)
        buffer[cursor[digit(entry[i])]++] = entry[i];
    });
    entry.swap(buffer);
  }
  // The crowded cells, each ordered again on its own (on two threads when
  // they hold many points: each writes its own runs).
  const auto crowded = crowded_runs(entry, 0, n);
  std::size_t crowded_points = 0;
  for (const auto &[i, j] : crowded)
    crowded_points += j - i;
  const int crowded_parts = host_threads(crowded_points);
  run_parts(crowded_parts, [&](int part, int) {
    const auto [first, end] = part_range(crowded.size(), part, crowded_parts);
    for (std::size_t k = first; k < end; ++k)
      order_cell_again(points, entry, crowded[k].first, crowded[k].second, 0);
  });
  std::vector<int32_t> order(n);
  for (std::size_t k = 0; k < n; ++k)
    order[k] = static_cast<int32_t>(entry[k] & 0xffffffffu);
  return order;
}

// Quickhull's elimination (Eddy; Barber, Dobkin and Huhdanpaa) as a filter:
// of the points `outside` (none strictly left of hull chord a -> b), drops
// those strictly inside the triangle of a, b and the farthest of them, f, and
// goes on with the points beyond a -> f and f -> b, until a group is small;
// appends what is left to `kept`. The farthest is chosen in rounded
// arithmetic; what is dropped is decided exactly, so that no hull vertex is
// ever dropped (the monotone chain sorts out the rest). A thin ring keeps
// all its points outside the octagon: this leaves about the hull.
void drop_inside_chords(const std::vector<Point> &points, int32_t a, int32_t b,
                        std::vector<int32_t> outside, std::vector<int32_t> &kept) {
  constexpr std::size_t kSmall = 64; // sorted as they are
  struct Group {
    int32_t a, b;
    std::vector<int32_t> members;
  };
  std::vector<Group> stack;
  stack.push_back({a, b, std::move(outside)});
  while (!stack.empty()) {
    Group group = std::move(stack.back());
    stack.pop_back();
    const Point &pa = points[group.a], &pb = points[group.b];
    int32_t far = -1;
    double farthest = 0;
    for (const int32_t v : group.members) {
      // Twice the area of (a, v, b): how far v lies beyond a -> b, rounded.
      const Point &p = points[v];
      const double d = (pb.x - pa.x) * (pa.y - p.y) - (pb.y - pa.y) * (pa.x - p.x);
      if (d > farthest) {
        farthest = d;
        far = v;
      }
    }
    if (group.members.size() <= kSmall || far < 0) {
      kept.insert(kept.end(), group.members.begin(), group.members.end());
      continue;
    }
    const Point &pf = points[far];
    Group before{group.a, far, {}}, after{far, group.b, {}};
    for (const int32_t v : group.members) {
      if (v == far)
        continue;
      if (!strictly_left(pa, pf, points[v]))
        before.members.push_back(v);
      else if (!strictly_left(pf, pb, points[v]))
        after.members.push_back(v);
    }
    kept.push_back(far);
    stack.push_back(std::move(after));
    stack.push_back(std::move(before));
  }
}

// Vertices of the convex hull, counter-clockwise, without collinear points
// (Andrew's monotone chain with the exact orientation predicate).
// Points strictly inside the octagon of the extreme points in eight
// directions are dropped first (Akl-Toussaint), which leaves few points to
// sort (a quadrilateral of four keeps half a square's points), then those
// inside chords of the hull (drop_inside_chords). A thin ring keeps nearly
// all its points through both: its halves and its octants go to two
// threads.
std::vector<int32_t> convex_hull(const std::vector<Point> &points) {
  // Extremes counter-clockwise: min y, max x-y, max x, max x+y, max y,
  // max y-x, min x, min x+y (the first point on a tie). Rounded sums only
  // choose which points; the octagon's corners are input points either way.
  const auto keys = [](const Point &p) {
    return std::array<double, 8>{-p.y, p.x - p.y, p.x, p.x + p.y, p.y, p.y - p.x, -p.x, -p.x - p.y};
  };
  std::array<int32_t, 8> extreme{};
  std::array<double, 8> best = keys(points[0]);
  for (int32_t i = 1; i < static_cast<int32_t>(points.size()); ++i) {
    const std::array<double, 8> key = keys(points[i]);
    for (int k = 0; k < 8; ++k)
      if (key[k] > best[k]) {
        best[k] = key[k];
        extreme[k] = i;
      }
  }
  // Each point outside the octagon goes with the first side it is not
  // strictly inside of, in input order (each half of the input apart, then
  // joined).
  std::array<std::array<std::vector<int32_t>, 8>, 2> outside_of_half;
  run_parts(host_threads(points.size()), [&](int half, int halves) {
    std::array<std::vector<int32_t>, 8> &outside = outside_of_half[static_cast<std::size_t>(half)];
    const auto [first, end] = part_range(points.size(), half, halves);
    for (auto i = static_cast<int32_t>(first); i < static_cast<int32_t>(end); ++i)
      for (int k = 0; k < 8; ++k) {
        const Point &a = points[extreme[k]], &b = points[extreme[(k + 1) % 8]];
        if ((a.x != b.x || a.y != b.y) && !strictly_left(a, b, points[i])) { // corners may repeat
          outside[k].push_back(i);
          break;
        }
      }
  });
  std::array<std::vector<int32_t>, 8> outside, kept;
  std::size_t outside_total = 0;
  for (int k = 0; k < 8; ++k) {
    outside[k] = std::move(outside_of_half[0][k]);
    outside[k].insert(outside[k].end(), outside_of_half[1][k].begin(), outside_of_half[1][k].end());
    outside_total += outside[k].size();
  }
  run_parts(host_threads(outside_total), [&](int share, int shares) {
    for (int k = share; k < 8; k += shares)
      drop_inside_chords(points, extreme[k], extreme[(k + 1) % 8], std::move(outside[k]), kept[k]);
  });
  std::vector<int32_t> order;
  for (const std::vector<int32_t> &part : kept)
    order.insert(order.end(), part.begin(), part.end());
  std::sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
    return lexicographically_less(points[a], points[b]) ||
           (!lexicographically_less(points[b], points[a]) && a < b);
  });
  std::vector<int32_t> hull(2 * order.size() + 1);
  std::size_t k = 0;
  auto push = [&](int32_t v, std::size_t floor) {
    while (k >= floor + 2 && orient(points[hull[k - 2]], points[hull[k - 1]], points[v]) <= 0)
      --k;
    hull[k++] = v;
  };
  for (const int32_t v : order)
    push(v, 0);
  const std::size_t lower = k - 1;
  for (auto it = order.rbegin() + 1; it != order.rend(); ++it)
    push(*it, lower);
  hull.resize(k > 1 ? k - 1 : k);
  return hull;
}

// Whether every point lies on one line (no triangle at all).
bool all_collinear(const std::vector<Point> &points) {
  std::size_t second = 1;
  while (second < points.size() && points[second].x == points[0].x &&
         points[second].y == points[0].y)
    ++second;
  for (std::size_t i = second + 1; i < points.size(); ++i)
    if (orient(points[0], points[second], points[i]) != 0)
      return false;
  return true;
}

// The hull polygon fanned from its first vertex, closed by one ghost triangle
// per hull edge; links are (triangle << 2) | edge.
struct HullFan {
  std::vector<cl_int> vertices, neighbors;
};

HullFan hull_fan(const std::vector<int32_t> &hull) {
  const int h = static_cast<int>(hull.size()), real = h - 2;
  HullFan fan;
  fan.vertices.resize(3 * (real + h));
  fan.neighbors.resize(3 * (real + h));
  auto set = [&](int t, int i, int vertex, int neighbor, int neighbor_edge) {
    fan.vertices[3 * t + i] = vertex;
    fan.neighbors[3 * t + i] = (neighbor << 2) | neighbor_edge;
  };
  // Ghost g (slot real + g) stands on hull edge hull[g] -> hull[g+1]:
  // vertices (hull[g+1], hull[g], infinite).
  auto ghost = [&](int g) { return real + (g % h); };
  // Real triangle k (1 <= k+1 < h-1) = (hull[0], hull[k+1], hull[k+2]).
  for (int k = 0; k < real; ++k) {
    // Opposite hull[0]: edge hull[k+1] -> hull[k+2] is hull edge k+1.
    set(k, 0, hull[0], ghost(k + 1), 2);
    // Opposite hull[k+1]: edge hull[k+2] -> hull[0]: next fan triangle or hull edge h-1.
    if (k + 1 < real)
      set(k, 1, hull[k + 1], k + 1, 2);
    else
      set(k, 1, hull[k + 1], ghost(h - 1), 2);
    // Opposite hull[k+2]: edge hull[0] -> hull[k+1]: previous fan triangle or hull edge 0.
    if (k > 0)
      set(k, 2, hull[k + 2], k - 1, 1);
    else
      set(k, 2, hull[k + 2], ghost(0), 2);
  }
  for (int g = 0; g < h; ++g) {
    const int t = ghost(g);
    // Real triangle holding hull edge g: edge 0 of fan triangle g-1 for
    // 1 <= g <= h-2, edge 2 of triangle 0 for g = 0, edge 1 of the last for g = h-1.
    const int real_t = g == 0 ? 0 : (g == h - 1 ? real - 1 : g - 1);
    const int real_e = g == 0 ? 2 : (g == h - 1 ? 1 : 0);
    // (hull[g+1], hull[g], inf): opposite hull[g+1] is edge hull[g] -> inf,
    // shared with the previous ghost's edge inf -> hull[g] (its edge 1).
    set(t, 0, hull[(g + 1) % h], ghost(g + h - 1), 1);
    // Opposite hull[g] is edge inf -> hull[g+1], shared with the next ghost's edge 0.
    set(t, 1, hull[g], ghost(g + 1), 0);
    set(t, 2, -1, real_t, real_e);
  }
  return fan;
}

// Whether the first triangulation of n points comes from the digital Voronoi
// diagram (the choice depends on the input alone: the same on every device).
// A grid named by --grid asks for the diagram.
bool uses_voronoi(const Tuning &tuning, std::size_t n) {
  switch (tuning.construction) {
  case Construction::voronoi:
    return true;
  case Construction::fan:
    return false;
  case Construction::automatic:
    break;
  }
  return n >= Tuning::kFanBelow || tuning.grid.has_value();
}

} // namespace

bool packable(const std::vector<Point> &points, std::size_t largest) {
  return points.size() >= 3 && points.size() <= largest && !all_collinear(points);
}

std::pair<Point, double> bounding_square(const std::vector<Point> &points) {
  const auto [low_x, high_x] = std::minmax_element(
      points.begin(), points.end(), [](const Point &a, const Point &b) { return a.x < b.x; });
  const auto [low_y, high_y] = std::minmax_element(
      points.begin(), points.end(), [](const Point &a, const Point &b) { return a.y < b.y; });
  return {{low_x->x, low_y->y}, std::max(high_x->x - low_x->x, high_y->y - low_y->y)};
}

void PhaseTimer::charge(const std::string &name) {
  {
    const ProfiledCall timed("phase timer");
    device_.queue().finish();
  }
  const auto now = Clock::now();
  const double seconds = std::chrono::duration<double>(now - last_).count();
  last_ = now;
  add_phase_time(stats_, name, seconds);
}

void add_phase_time(DelaunayStats &stats, const std::string &name, double seconds) {
  for (auto &phase : stats.phases)
    if (phase.name == name) {
      phase.seconds += seconds;
      return;
    }
  stats.phases.push_back({name, seconds});
}

DelaunayScheduler::DelaunayScheduler(Device &device, const std::vector<Point> &points,
                                     const DelaunayOptions &options, DelaunayStats &stats,
                                     std::size_t extra_points, std::vector<std::size_t> part_starts)
    : device_(device), points_(points), options_(options), extra_points_(extra_points),
      stats_(stats), part_starts_(std::move(part_starts)) {
  if (part_starts_.empty())
    part_starts_ = {0, points.size()};
  if (part_starts_.front() != 0 || part_starts_.back() != points.size() ||
      !std::is_sorted(part_starts_.begin(), part_starts_.end()))
    throw InternalError("packed triangulation: the parts do not cover the points in order");
  if (points.size() < 3)
    throw InputError("input", 0, "fewer than three points");
  if (points.size() > (std::size_t{1} << 28))
    throw InputError("input", 0, "more than 2^28 points");
  check_coordinates(points);
  // Before any program of this mesh.
  device.fit_prefetching(points.size() + extra_points, options.tuning.prefetch_from);
  // A shared device keeps no size from an earlier run.
  device.set_work_group(options.tuning.work_group.value_or(device.default_work_group()));
  stats.device = describe(device);
  stats.input_points = static_cast<long>(points.size());
  // Build every program before the clock starts; those of Phases 1-3 only
  // when they may run (a small input is fanned: loading them would cost a
  // small run more than its meshing).
  for (const char *file :
       {"scan.cl", "missing_point_insertion.cl", "flipping.cl", "mesh_output.cl", "fill.cl"})
    device.program(file, "setup");
  if ((!packed() && uses_voronoi(options.tuning, points.size())) || options.want_voronoi_image)
    for (const char *file : {"voronoi_banding.cl", "triangulation_construction.cl", "shifting.cl"})
      device.program(file, "setup");
  start_ = Clock::now();
}

DelaunayScheduler::~DelaunayScheduler() = default;

template <class Visit> void DelaunayScheduler::for_each_part(const Visit &visit) const {
  if (!packed()) {
    visit(std::size_t{0}, points_);
    return;
  }
  for (std::size_t k = 0; k + 1 < part_starts_.size(); ++k) {
    const auto first = points_.begin() + static_cast<std::ptrdiff_t>(part_starts_[k]),
               last = points_.begin() + static_cast<std::ptrdiff_t>(part_starts_[k + 1]);
    visit(part_starts_[k], std::vector<Point>(first, last));
  }
}

bool DelaunayScheduler::worth_levels(std::size_t points, std::size_t triangles) {
  return points / kLevelRatio >= std::max(kCoarsestLevel, triangles);
}

DelaunayScheduler::PointLevels DelaunayScheduler::point_levels(std::vector<cl_int> points,
                                                               std::size_t triangles) {
  // Level j takes the points at the multiples of kLevelRatio^j in the list,
  // but those of a coarser level; the coarsest (the largest such stride,
  // kLevelRatio^top) has at least as many points as the mesh has triangles,
  // and kCoarsestLevel at least.
  const std::size_t m = points.size(), coarsest = std::max(kCoarsestLevel, triangles);
  std::size_t top = 1;
  while (top <= m / coarsest / kLevelRatio)
    top *= kLevelRatio;
  PointLevels levels;
  for (std::size_t stride = top;; stride /= kLevelRatio) {
    PointLevel level;
    for (std::size_t i = 0; i < m; i += stride)
      if (stride == top || i % (stride * kLevelRatio) != 0) {
        level.points.push_back(points[i]);
        if (stride != top) // the coarser point before it on the Hilbert curve
          level.anchors.push_back(points[i - i % (stride * kLevelRatio)]);
      }
    levels.push_back(std::move(level));
    if (stride == 1)
      return levels;
  }
}

void DelaunayScheduler::upload_points() {
  const std::vector<Point> &points = points_;
  const std::size_t n = points.size();
  mesh_ = std::make_unique<DeviceMesh>(device_, n, extra_points_);
  scan_ = std::make_unique<PrefixScan>(device_);
  Device &device = device_;
  DeviceMesh &mesh = *mesh_;
  // Device points follow a Hilbert curve (each part's its own, in the part's
  // range), so that neighbouring work-items touch neighbouring memory; the
  // output goes back to the input numbering.
  original_id_.clear();
  original_id_.reserve(n);
  for_each_part([&](std::size_t first, const std::vector<Point> &part) {
    for (const int32_t i : spatial_order(part))
      original_id_.push_back(static_cast<int32_t>(first) + i);
  });
  const std::vector<int32_t> &original_id = original_id_;
  device_id_.assign(n, 0);
  std::vector<cl_double2> coordinates(n);
  const int parts = host_threads(n);
  run_parts(parts, [&](int part, int) { // original_id is a permutation: no write meets another
    const auto [first, end] = part_range(n, part, parts);
    for (std::size_t k = first; k < end; ++k) {
      device_id_[original_id[k]] = static_cast<int32_t>(k);
      coordinates[k] = {{points[original_id[k]].x, points[original_id[k]].y}};
    }
  });
  mesh.points.upload(device, coordinates);
  std::vector<cl_double2>().swap(coordinates); // the host copy is not needed any more
  mesh.original_id.upload(device, original_id);
  mesh.clear_triangle_slots(); // marks and stamps set as the slots come into use
  mesh.fill_point_slots(device, mesh.point_count);
  mesh.location.fill(device, 0, mesh.point_count); // added points come with theirs
  timer_->charge("upload");
}

bool DelaunayScheduler::take_triangles(const std::vector<Triangle> &triangles,
                                       const std::vector<cl_int> &links) {
  timer_ = std::make_unique<PhaseTimer>(device_, stats_);
  const std::size_t real = triangles.size();
  // The boundary edges a -> b, each of real triangle t opposite its corner
  // i, and which one leaves each vertex.
  struct BoundaryEdge {
    int32_t a, b, t, i;
  };
  std::vector<BoundaryEdge> boundary;
  std::vector<cl_int> leaving(points_.size(), -1);
  for (std::size_t t = 0; t < real; ++t)
    for (int i = 0; i < 3; ++i)
      if (links[3 * t + static_cast<std::size_t>(i)] < 0) {
        const int32_t a = triangles[t][(i + 1) % 3], b = triangles[t][(i + 2) % 3];
        cl_int &from_a = leaving[static_cast<std::size_t>(a)];
        if (from_a >= 0)
          return false; // two boundary edges leave a vertex
        from_a = static_cast<cl_int>(boundary.size());
        boundary.push_back({a, b, static_cast<int32_t>(t), i});
      }
  // The triangles (counter-clockwise, no edge twice in one direction:
  // validate) must tile a region of the plane, as the Delaunay
  // triangulation's triangles found by matching do. Enough for that: the
  // boundary edges form loops that are simple polygons, none meeting
  // another, one turning counter-clockwise and the others clockwise. The
  // triangles covering a point (each covers it positively) are as many as
  // the loops wind around it: at most one, the outer loop's turn less those
  // of the holes it lies in (and never fewer than none). The slots with the
  // ghosts are then 2 n - 2 + 2 h for h holes; they must fit the mesh's
  // room (DeviceMesh: 2 slots a point and 2 more). Anything else (a
  // boundary that touches itself or another loop, pieces apart, overlaps)
  // is triangulated (false).
  const std::size_t m = boundary.size(), slots = real + m;
  if (m == 0 || points_.size() < 3 || slots > 2 * (points_.size() + extra_points_) + 2)
    return false;
  // The boundary edges loop by loop (order; the loops start at
  // loop_start), each loop from its first edge in the order found.
  std::vector<cl_int> order;
  std::vector<int32_t> corners;
  std::vector<std::size_t> loop_start;
  std::vector<char> taken(m, 0);
  for (std::size_t first = 0; first < m; ++first) {
    if (taken[first])
      continue;
    loop_start.push_back(order.size());
    auto e = static_cast<cl_int>(first);
    do {
      if (e < 0 || taken[static_cast<std::size_t>(e)])
        return false; // a chain that ends, or joins another loop midway
      taken[static_cast<std::size_t>(e)] = 1;
      order.push_back(e);
      corners.push_back(boundary[static_cast<std::size_t>(e)].a);
      e = leaving[static_cast<std::size_t>(boundary[static_cast<std::size_t>(e)].b)];
    } while (e != static_cast<cl_int>(first));
  }
  const std::size_t loops = loop_start.size();
  loop_start.push_back(m);
  if (slots != 2 * points_.size() - 2 + 2 * (loops - 1) ||
      !are_simple_loops(points_, corners, loop_start))
    return false;
  std::size_t outer = 0;
  for (std::size_t l = 0; l < loops; ++l)
    outer += loop_turn(points_, corners, loop_start[l], loop_start[l + 1]) > 0;
  if (outer != 1)
    return false;
  // The points first: the arrays take their device numbers. Ghost e (slot
  // real + e) stands on boundary edge e, a -> b: vertices (b, a, infinite),
  // as the hull fan's; its edge 2 faces the real triangle, edge 0 the ghost
  // before it on its loop, edge 1 the ghost after it. The real triangles in
  // two parts (each writes its own slots).
  upload_points();
  const std::vector<int32_t> &device_id = device_id_;
  std::vector<cl_int> vertices(3 * slots), neighbors(3 * slots);
  const int parts = host_threads(3 * real);
  run_parts(parts, [&](int part, int) {
    const auto [first, end] = part_range(real, part, parts);
    for (std::size_t t = first; t < end; ++t)
      for (std::size_t i = 0; i < 3; ++i) {
        vertices[3 * t + i] = device_id[static_cast<std::size_t>(triangles[t][i])];
        neighbors[3 * t + i] = links[3 * t + i];
      }
  });
  for (std::size_t l = 0; l < loops; ++l) {
    const std::size_t first = loop_start[l], size = loop_start[l + 1] - first;
    const auto ghost = [&](std::size_t at) {
      return static_cast<cl_int>(real) + order[first + at % size];
    };
    for (std::size_t k = 0; k < size; ++k) {
      const BoundaryEdge &edge = boundary[static_cast<std::size_t>(order[first + k])];
      const cl_int slot = ghost(k), before = ghost(k + size - 1), after = ghost(k + 1);
      cl_int *vertex = &vertices[3 * static_cast<std::size_t>(slot)];
      cl_int *link = &neighbors[3 * static_cast<std::size_t>(slot)];
      vertex[0] = device_id[static_cast<std::size_t>(edge.b)];
      vertex[1] = device_id[static_cast<std::size_t>(edge.a)];
      vertex[2] = -1; // CLM_INFINITE
      link[0] = (before << 2) | 1;
      link[1] = (after << 2) | 0;
      link[2] = (edge.t << 2) | 2;
      neighbors[3 * static_cast<std::size_t>(edge.t) + static_cast<std::size_t>(edge.i)] =
          (slot << 2) | 2;
    }
  }
  DeviceMesh &mesh = *mesh_;
  mesh.tri_vertex.upload(device_, vertices);
  mesh.tri_neighbor.upload(device_, neighbors);
  mesh.triangle_count = slots;
  mesh.fill_triangle_slots(device_, slots);
  stats_.construction = "given_mesh";
  timer_->charge("upload");
  return true;
}

bool DelaunayScheduler::triangulate() {
  const std::vector<Point> &points = points_;
  const std::size_t n = points.size();
  timer_ = std::make_unique<PhaseTimer>(device_, stats_);
  if (all_collinear(points))
    return false; // no triangle

  upload_points();
  MissingPointInsertion insertion(device_, *mesh_, *scan_);
  Device &device = device_;
  DeviceMesh &mesh = *mesh_;

  // Phases 1-3 build the first triangulation and list the missing points;
  // when their result cannot be used, the hull is fanned instead.
  const bool from_voronoi = !packed() && uses_voronoi(options_.tuning, n);
  if (!from_voronoi && options_.want_voronoi_image) {
    const auto [low, span] = bounding_square(points);
    stats_.grid = texture_side(low, span);
    VoronoiBanding banding(device, mesh, *scan_);
    stats_.pixel_collisions = static_cast<long>(banding.run(stats_.grid, low, span));
    voronoi_ = banding.download_image();
    timer_->charge(VoronoiBanding::kPhase);
  }
  // The missing points when they go in levels (point_levels): the first in
  // `insertion`, the others here.
  PointLevels levels;
  if (!from_voronoi || !construct_from_voronoi(insertion, levels)) {
    // The hull only now: the Voronoi construction does without it. Each
    // part's hull is fanned in slots of its own, and its points start their
    // walks in its first fan triangle: the parts never meet.
    HullFan fans;
    std::vector<cl_int> start_triangle(n, 0);
    std::vector<char> in_mesh(n, 0);
    for_each_part([&](std::size_t first, const std::vector<Point> &part) {
      const std::vector<int32_t> hull = convex_hull(part);
      std::vector<int32_t> device_hull(hull.size());
      for (std::size_t i = 0; i < hull.size(); ++i) {
        device_hull[i] = device_id_[first + hull[i]];
        in_mesh[device_hull[i]] = 1;
      }
      const HullFan fan = hull_fan(device_hull);
      const auto slot = static_cast<cl_int>(fans.vertices.size() / 3);
      fans.vertices.insert(fans.vertices.end(), fan.vertices.begin(), fan.vertices.end());
      for (const cl_int link : fan.neighbors)
        fans.neighbors.push_back(link + (slot << 2));
      // The part's device points are its input range (spatial_order above).
      std::fill(start_triangle.begin() + static_cast<std::ptrdiff_t>(first),
                start_triangle.begin() + static_cast<std::ptrdiff_t>(first + part.size()), slot);
    });
    timer_->charge("upload");
    mesh.tri_vertex.upload(device, fans.vertices);
    mesh.tri_neighbor.upload(device, fans.neighbors);
    mesh.triangle_count = fans.vertices.size() / 3;
    mesh.clear_triangle_slots();
    mesh.fill_triangle_slots(device, mesh.triangle_count);
    mesh.location.upload(device, start_triangle);
    std::vector<cl_int> missing;
    for (std::size_t i = 0; i < n; ++i)
      if (!in_mesh[i])
        missing.push_back(static_cast<cl_int>(i));
    // A packed batch's small parts all at once (a level's anchors would
    // cross from part to part).
    if (!packed() && worth_levels(missing.size(), mesh.triangle_count)) {
      levels = point_levels(std::move(missing), mesh.triangle_count);
      insertion.set_points(levels.front().points);
    } else {
      insertion.set_points(missing);
    }
    stats_.construction = "hull_fan";
    flips_ = FlipCounts{};
    // The fan is a triangulation, not yet a Delaunay one: flip it first.
    flip_all(flips_);
  }
  stats_.missing_points = static_cast<long>(insertion.pending());
  for (std::size_t k = 1; k < levels.size(); ++k)
    stats_.missing_points += static_cast<long>(levels[k].points.size());

  stats_.insertion_levels = static_cast<long>(std::max<std::size_t>(1, levels.size()));
  stats_.insertion_rounds += insert_in_rounds(insertion);
  for (std::size_t k = 1; k < levels.size(); ++k) {
    insertion.set_points_near(levels[k].points, levels[k].anchors);
    PointLevel().swap(levels[k]);
    stats_.insertion_rounds += insert_in_rounds(insertion);
  }
  stats_.duplicates = static_cast<long>(insertion.duplicates());
  stats_.flips = flips_.flips;
  stats_.flip_passes = flips_.passes;
  stats_.exact_predicate_calls = flips_.exact_checks;
  return true;
}

int DelaunayScheduler::texture_side(Point low, double span) const {
  return options_.tuning.grid ? *options_.tuning.grid
                              : VoronoiBanding::choose_grid(points_, low, span);
}

bool DelaunayScheduler::construct_from_voronoi(MissingPointInsertion &insertion,
                                               PointLevels &levels) {
  const std::vector<Point> &points = points_;
  const std::size_t n = points.size();
  DeviceMesh &mesh = *mesh_;
  const auto [low, span] = bounding_square(points);
  stats_.grid = texture_side(low, span);
  VoronoiBanding banding(device_, mesh, *scan_);
  TriangulationConstruction construction(device_, mesh, *scan_);
  Shifting shifting(device_, mesh, *scan_);
  DeviceArray<cl_int> site_state(device_, n), bad(device_, n);
  site_state.fill(device_, 0, n); // CLM_SITE (cl/common.h)
  bad.fill(device_, 0, n);
  TriangulationConstruction::Built built;
  bool settled = false;
  long left_out_before = 0, left_out_two_before = 0;
  stats_.dropped_sites = 0;
  stats_.untangling_flips = 0;
  for (int round = 0; round < kConstructionRounds && !settled; ++round) {
    // Phase 1: the digital Voronoi diagram of the sites not left out.
    const std::size_t not_sites = banding.run(stats_.grid, low, span, &site_state);
    if (round == 0) {
      stats_.pixel_collisions = static_cast<long>(not_sites);
      if (options_.want_voronoi_image) // the diagram of every point
        voronoi_ = banding.download_image();
    }
    ++stats_.construction_rounds;
    timer_->charge(VoronoiBanding::kPhase);
    // Phase 2: triangles from its vertices, ghosts along the border, links.
    built = construction.run(banding.diagram(), stats_.grid, bad);
    timer_->charge(TriangulationConstruction::kPhase);
    if (!built.fits)
      break;
    // Phase 3: at the real coordinates, turned-over triangles are untangled
    // by flips where they can be; the sites of the others and of unmatched
    // triangles are left out of the next diagram, with their pixels' points.
    const long untangled = shifting.untangle(built.real, built.real + built.ghosts, bad, stamp_);
    stats_.untangling_flips += untangled;
    // The flips assume the tangle is local; where it was not, a link that no
    // longer pairs up leaves its sites out as well.
    if (untangled > 0)
      construction.check_links(built.real + built.ghosts, bad);
    const long left_out =
        shifting.leave_out_flagged(bad, site_state, banding.diagram(), banding.pixel_of());
    stats_.dropped_sites += left_out;
    timer_->charge(Shifting::kPhase);
    settled = left_out == 0;
    // Each round should fix a good part of what is left (a dense hull turns
    // over layer after layer, a few sites fewer each time), and every two
    // rounds a quarter of it even when little is left (the few sites that a
    // clustered input leaves out again and again); when they do not, the
    // hull fan is cheaper than more rounds.
    if (round >= 2 && ((left_out > kStalledSites && 4 * left_out > 3 * left_out_before) ||
                       4 * left_out > 3 * left_out_two_before))
      break;
    left_out_two_before = left_out_before;
    left_out_before = left_out;
  }
  if (!settled)
    return false;
  stats_.constructed_triangles = static_cast<long>(built.real);
  mesh.triangle_count = built.real + built.ghosts;
  mesh.fill_triangle_slots(device_, mesh.triangle_count); // the construction sets no marks

  // Phase 5 on the whole construction: the ghost flips make the outer cycle
  // convex. A structure that is no triangulation may flip on and on: a bound
  // on the passes, then the check that the cycle winds around once.
  flips_ = FlipCounts{};
  const long max_passes = 64 + 4 * static_cast<long>(std::sqrt(static_cast<double>(n)));
  const bool flipped = flip_all(flips_, Flipping::kPhase, max_passes);
  if (!flipped || !shifting.boundary_winds_once())
    return false;
  DeviceArray<cl_int> missing(device_, n);
  const std::size_t count =
      shifting.collect_missing(banding.diagram(), banding.pixel_of(), missing);
  // Few sites (a clustered input): the missing points in levels.
  if (worth_levels(count, mesh.triangle_count)) {
    levels = point_levels(missing.download(device_, count), mesh.triangle_count);
    insertion.set_points(levels.front().points);
  } else {
    insertion.set_points(missing, count);
  }
  timer_->charge(Shifting::kPhase);
  stats_.construction = "voronoi";
  return true;
}

std::vector<int32_t> DelaunayScheduler::insert_points(const std::vector<Point> &added,
                                                      const std::vector<int32_t> &start_triangles) {
  DeviceMesh &mesh = *mesh_;
  check_coordinates(added, mesh.point_count, true);
  // Short of room: the arrays grow by half at least, as refinement's do.
  if (mesh.point_count + added.size() > mesh.point_capacity)
    grow(std::max(added.size(), mesh.point_capacity / 2));
  const auto first = static_cast<int32_t>(mesh.point_count);
  std::vector<cl_double2> coordinates;
  std::vector<cl_int> ids;
  for (std::size_t i = 0; i < added.size(); ++i) {
    coordinates.push_back({{added[i].x, added[i].y}});
    ids.push_back(first + static_cast<cl_int>(i)); // numbered after the input
  }
  mesh.points.upload(device_, coordinates, first);
  mesh.original_id.upload(device_, ids, first);
  mesh.location.upload(device_, std::vector<cl_int>(start_triangles.begin(), start_triangles.end()),
                       first);
  insert_appended(added.size());
  const auto duplicates = mesh.duplicate_of.download(device_, added.size(), first);
  std::vector<int32_t> result(added.size());
  for (std::size_t i = 0; i < added.size(); ++i)
    result[i] = duplicates[i] >= 0 ? duplicates[i] : ids[i];
  return result;
}

long DelaunayScheduler::insert_in_rounds(MissingPointInsertion &insertion) {
  long rounds = 0;
  while (insertion.pending() > 0) {
    const std::size_t inserted = insertion.run_round(stamp_++);
    ++rounds;
    timer_->charge(MissingPointInsertion::kPhase);
    if (inserted == 0 && insertion.pending() > 0)
      throw InternalError("point insertion made no progress");
    flipping().run(insertion.changed(), 4 * inserted, stamp_, flips_);
    // The first rounds' long lists give their pages back: the mesh grows
    // into that memory in the rounds after.
    insertion.trim_lists();
    flipping().trim_lists();
    timer_->charge(Flipping::kPhase);
  }
  return rounds;
}

std::size_t DelaunayScheduler::insert_appended(std::size_t count) {
  DeviceMesh &mesh = *mesh_;
  const auto first = static_cast<int32_t>(mesh.point_count);
  std::vector<cl_int> ids(count);
  for (std::size_t i = 0; i < count; ++i) {
    ids[i] = first + static_cast<cl_int>(i);
    original_id_.push_back(ids[i]);
  }
  mesh.fill_point_slots(device_, mesh.point_count + count);
  mesh.point_count += count;
  MissingPointInsertion insertion(device_, mesh, *scan_);
  insertion.set_points(ids);
  insert_in_rounds(insertion);
  stats_.flips = flips_.flips;
  stats_.flip_passes = flips_.passes;
  stats_.exact_predicate_calls = flips_.exact_checks;
  return insertion.duplicates();
}

void DelaunayScheduler::fix_boundary() {
  fixed_boundary_ = true;
  if (flipping_)
    flipping_->set_fixed_boundary(true);
}

Flipping &DelaunayScheduler::flipping() {
  if (!flipping_) {
    flipping_ = std::make_unique<Flipping>(device_, *mesh_, options_.tuning.group_pass_limit);
    flipping_->set_fixed_boundary(fixed_boundary_);
  }
  return *flipping_;
}

void DelaunayScheduler::grow(std::size_t extra_points) {
  mesh_->grow(device_, extra_points);
  flipping_.reset(); // sized by the mesh: built again for the next flips
}

bool DelaunayScheduler::flip_all(FlipCounts &counts, const std::string &phase, long max_passes) {
  std::vector<cl_int> every_triangle(mesh_->triangle_count);
  std::iota(every_triangle.begin(), every_triangle.end(), 0);
  DeviceArray<cl_int> active(device_, every_triangle.size());
  active.upload(device_, every_triangle);
  const bool done = flipping().run(active, every_triangle.size(), stamp_, counts, max_passes);
  timer_->charge(phase);
  return done;
}

void DelaunayScheduler::flip_flagged(const DeviceArray<cl_int> &flags, FlipCounts &counts,
                                     const std::string &phase) {
  const std::size_t slots = mesh_->triangle_count;
  DeviceArray<cl_int> offsets(device_, slots), active(device_, slots);
  const auto n =
      static_cast<std::size_t>(scan_->compact_indices(flags, offsets, active, slots, phase));
  flipping().run(active, n, stamp_, counts);
  timer_->charge(phase);
}

void DelaunayScheduler::download(DelaunayResult &result, const DeviceArray<cl_int> *removed,
                                 const DeviceArray<cl_int> *label, std::vector<int32_t> *labels) {
  flipping_.reset(); // its lists are not needed any more: room for the output's
  release_free_heap();
  MeshOutput(device_, *mesh_, *scan_)
      .download(result.triangles, result.neighbors, result.duplicate_of, removed, label, labels);
  // The last use of the mesh: its memory goes before the host works on the result.
  mesh_.reset();
  result.voronoi = std::move(voronoi_);
  timer_->charge(MeshOutput::kPhase);
  stats_.triangles = static_cast<long>(result.triangles.size());
  stats_.compute_seconds = seconds_since(start_);
}

void DelaunayScheduler::download_collinear(DelaunayResult &result) {
  result.duplicate_of = duplicates_on_host(points_);
  stats_.duplicates = std::count_if(result.duplicate_of.begin(), result.duplicate_of.end(),
                                    [](int32_t d) { return d >= 0; });
  stats_.compute_seconds = seconds_since(start_);
}

} // namespace clmesh
