#include "cdt/constraint_insertion.hpp"

#include "priority.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <numeric>
#include <utility>

namespace clmesh {

namespace {
const char *kFile = "constraint_marking.cl";
constexpr int kPresent = 1, kSplit = 2, kCrossing = 3;
constexpr std::size_t kCounters = 3;    // see mark_constraint_triangles
constexpr std::size_t kRunCounters = 3; // see find_run_starts
// Where segments a-b and p-q cross: a + t (b - a) on line p-q, in extended
// precision, rounded once. A segment far longer than the crossing's distance
// from its nearer endpoint (a coordinate of 1e16 among ones near 1) loses
// the crossing in the rounding of t (b - a): the point lands off the other
// segment, or off both. It is then taken from the endpoint, of either
// segment, whose offset to it is the smallest, the best conditioned of the
// four: whenever a + t (b - a) lands outside either segment's box, or its
// offset is over 1024 times the best one (ten bits lost).
// `noise`: how near another point is indistinguishable from the crossing.
// `along`: the same along the segments, where the crossing of two segments
// at an angle theta is uncertain by noise / sin(theta).
struct Crossing {
  Point point;
  double noise, along;
};

Crossing crossing_point(const Point &a, const Point &b, const Point &p, const Point &q) {
  using Real = long double;
  auto cross = [](Real ux, Real uy, Real vx, Real vy) { return ux * vy - uy * vx; };
  const Real dx = static_cast<Real>(b.x) - a.x, dy = static_cast<Real>(b.y) - a.y;
  const Real ex = static_cast<Real>(q.x) - p.x, ey = static_cast<Real>(q.y) - p.y;
  const Real d_cross_e = cross(dx, dy, ex, ey);
  const Real t =
      cross(static_cast<Real>(p.x) - a.x, static_cast<Real>(p.y) - a.y, ex, ey) / d_cross_e;
  const Point point{static_cast<double>(a.x + t * dx), static_cast<double>(a.y + t * dy)};
  auto in_box = [&](const Point &u, const Point &w) {
    return point.x >= std::min(u.x, w.x) && point.x <= std::max(u.x, w.x) &&
           point.y >= std::min(u.y, w.y) && point.y <= std::max(u.y, w.y);
  };
  struct From {
    Point base;
    Real along, ux, uy; // the point is base + along (ux, uy)
  };
  const From from[] = {
      {a, t, dx, dy},
      {b, cross(static_cast<Real>(b.x) - p.x, static_cast<Real>(b.y) - p.y, ex, ey) / d_cross_e,
       -dx, -dy},
      {p, cross(static_cast<Real>(p.x) - a.x, static_cast<Real>(p.y) - a.y, dx, dy) / d_cross_e, ex,
       ey},
      {q, cross(static_cast<Real>(a.x) - q.x, static_cast<Real>(a.y) - q.y, dx, dy) / d_cross_e,
       -ex, -ey}};
  auto offset = [](const From &f) { return std::abs(f.along) * (std::abs(f.ux) + std::abs(f.uy)); };
  const From &best =
      *std::min_element(std::begin(from), std::end(from),
                        [&](const From &u, const From &w) { return offset(u) < offset(w); });
  const Point chosen = in_box(a, b) && in_box(p, q) && offset(from[0]) <= 1024 * offset(best)
                           ? point
                           : Point{static_cast<double>(best.base.x + best.along * best.ux),
                                   static_cast<double>(best.base.y + best.along * best.uy)};
  // Four units in the last place of the point, or of the shorter segment's
  // length: the rounding of crossings earlier on these segments bent them by
  // about that much.
  const double shorter = static_cast<double>(
      std::min(std::max(std::abs(dx), std::abs(dy)), std::max(std::abs(ex), std::abs(ey))));
  const double noise = 4 * std::numeric_limits<double>::epsilon() *
                       std::max({std::abs(chosen.x), std::abs(chosen.y), shorter});
  const Real sine = std::abs(d_cross_e) / (std::hypot(dx, dy) * std::hypot(ex, ey));
  return {chosen, noise,
          sine > 0 ? std::max(noise, static_cast<double>(noise / sine))
                   : std::numeric_limits<double>::infinity()};
}

} // namespace

ConstraintInsertion::ConstraintInsertion(Device &device, DeviceMesh &mesh)
    : device_(device), mesh_(mesh),
      resolve_duplicates_(device.kernel(kFile, "resolve_duplicate_endpoints", kPhase)),
      record_vertex_triangles_(device.kernel(kFile, "record_vertex_triangles", kPhase)),
      mark_(device.kernel(kFile, "mark_constraint_triangles", kPhase)),
      find_run_starts_(device.kernel(kFile, "find_run_starts", kPhase)),
      claim_runs_(device.kernel(kFile, "claim_runs", kPhase)),
      flip_along_runs_(device.kernel(kFile, "flip_along_runs", kPhase)),
      relink_run_boundaries_(device.kernel(kFile, "relink_run_boundaries", kPhase)),
      counters_(device, kCounters), constraint_mark_(device, mesh.triangle_capacity),
      run_start_(device, mesh.triangle_capacity), run_of_(device, mesh.triangle_capacity),
      boundary_log_(device, kLogPerTriangle * mesh.triangle_capacity),
      run_counters_(device, kRunCounters), touched_(device, mesh.triangle_capacity) {}

std::vector<char> first_occurrences(std::vector<Segment> &segments) {
  // Sorting (edge, position) pairs: one flat array, far cheaper than a std::set of edges.
  // Each edge's repeats then follow its first occurrence in input order.
  std::vector<std::pair<std::pair<int32_t, int32_t>, std::size_t>> keyed(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i)
    keyed[i] = {std::minmax(segments[i].a, segments[i].b), i};
  std::sort(keyed.begin(), keyed.end());
  std::vector<char> first(segments.size(), 0);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    const std::size_t i = keyed[k].second;
    first[i] = k == 0 || keyed[k].first != keyed[k - 1].first;
    if (first[i])
      kept = i;
    else if (segments[kept].marker == 0)
      segments[kept].marker = segments[i].marker;
  }
  return first;
}

std::vector<cl_int> ConstraintInsertion::download_by_segment(const DeviceArray<cl_int> &array) {
  const std::size_t m = segments_.size();
  const auto by_priority = array.download(device_, m);
  std::vector<cl_int> by_segment(m);
  for (std::size_t d = 0; d < m; ++d)
    by_segment[priority_order_[d]] = by_priority[d];
  return by_segment;
}

std::vector<Segment> ConstraintInsertion::resolve_duplicates(const std::vector<Segment> &segments) {
  const std::size_t m = segments.size();
  if (m == 0)
    return {};
  std::vector<cl_int> a(m), b(m);
  for (std::size_t i = 0; i < m; ++i) {
    a[i] = segments[i].a;
    b[i] = segments[i].b;
  }
  DeviceArray<cl_int> device_a(device_, m), device_b(device_, m);
  device_a.upload(device_, a);
  device_b.upload(device_, b);
  set_args(resolve_duplicates_, mesh_.duplicate_of.buffer(), device_a.buffer(), device_b.buffer(),
           static_cast<cl_int>(m));
  launch(device_, resolve_duplicates_, m, kPhase);
  a = device_a.download(device_, m);
  b = device_b.download(device_, m);
  std::vector<Segment> resolved(segments);
  for (std::size_t i = 0; i < m; ++i) {
    resolved[i].a = a[i];
    resolved[i].b = b[i];
  }
  return resolved;
}

void ConstraintInsertion::set_constraints(std::vector<Segment> pieces) {
  // Overlapping collinear segments split at each other's vertices repeat pieces.
  const std::vector<char> distinct = first_occurrences(pieces);
  std::vector<Segment> segments;
  std::vector<int32_t> origin;
  const bool first = origin_.empty();
  for (std::size_t i = 0; i < pieces.size(); ++i)
    if (distinct[i]) {
      segments.push_back(pieces[i]);
      origin.push_back(first ? static_cast<int32_t>(i) : origin_[i]);
    }
  if (first)
    split_origin_.assign(pieces.size(), 0);
  if (segments.size() >= (std::size_t{1} << 27))
    throw InputError("segments", 0, "more than 2^27 segments (a triangle's mark holds 27 bits)");
  segments_ = segments;
  origin_ = origin;
  const std::size_t m = segments.size();
  std::vector<cl_int> a(m), b(m);
  // Marks keep the constraint of smallest device index. Input files list
  // segments along chains and contours, so neighbouring constraints would
  // have neighbouring priorities and each would wait for the one beside it:
  // the device holds them in a scrambled (fixed) order instead.
  std::vector<std::pair<unsigned, int32_t>> keyed(m); // a bijection: keys are distinct
  for (std::size_t i = 0; i < m; ++i)
    keyed[i] = {clm_priority_of(static_cast<unsigned>(i)), static_cast<int32_t>(i)};
  std::sort(keyed.begin(), keyed.end());
  // The marking walks run in the order of the segments' first endpoints (the
  // device numbers points along a Hilbert curve), so that neighbouring walks
  // read the same triangles: walk_order[k] is the device index of the k-th.
  priority_order_.resize(m);
  std::vector<cl_int> device_index(m);
  for (std::size_t d = 0; d < m; ++d) {
    priority_order_[d] = keyed[d].second;
    a[d] = segments[priority_order_[d]].a;
    b[d] = segments[priority_order_[d]].b;
    device_index[priority_order_[d]] = static_cast<cl_int>(d);
  }
  std::vector<cl_int> walk_order(m);
  std::iota(walk_order.begin(), walk_order.end(), 0);
  std::sort(walk_order.begin(), walk_order.end(), [&](cl_int i, cl_int j) {
    return std::make_pair(segments[i].a, segments[i].b) <
           std::make_pair(segments[j].a, segments[j].b);
  });
  for (cl_int &i : walk_order)
    i = device_index[i];
  mesh_.set_constraint_rows(device_, segments);
  segment_a_ = DeviceArray<cl_int>(device_, m);
  segment_b_ = DeviceArray<cl_int>(device_, m);
  segment_state_ = DeviceArray<cl_int>(device_, m);
  walk_order_ = DeviceArray<cl_int>(device_, m);
  walk_order_.upload(device_, walk_order);
  split_vertex_ = DeviceArray<cl_int>(device_, m);
  crossed_vertex_ = DeviceArray<cl_int>(device_, m);
  crossed_triangle_ = DeviceArray<cl_int>(device_, m);
  segment_a_.upload(device_, a);
  segment_b_.upload(device_, b);
  segment_state_.fill(device_, 0, m);
}

long ConstraintInsertion::mark(ConstrainedStats &stats, bool first,
                               const PointInserter &insert_points) {
  const std::size_t slots = mesh_.triangle_count, m = segments_.size();
  if (!vertex_triangles_recorded_) {
    // Afterwards the flips keep vertex_triangle up to date.
    set_args(record_vertex_triangles_, mesh_.tri_vertex.buffer(), mesh_.vertex_triangle.buffer(),
             static_cast<cl_int>(slots));
    launch(device_, record_vertex_triangles_, slots, kPhase);
    vertex_triangles_recorded_ = true;
  }
  constraint_mark_.fill(device_, 0x7fffffff, slots);
  counters_.fill(device_, 0, kCounters);
  set_args_from(mark_, mesh_.bind_triangulation(mark_, 0), walk_order_.buffer(),
                segment_a_.buffer(), segment_b_.buffer(), segment_state_.buffer(),
                split_vertex_.buffer(), crossed_vertex_.buffer(), crossed_triangle_.buffer(),
                constraint_mark_.buffer(), counters_.buffer(), static_cast<cl_int>(slots + 8),
                static_cast<cl_int>(m));
  launch(device_, mark_, m, kPhase);
  const auto counters = counters_.download(device_, kCounters);
  if (first)
    stats.intersections = counters[1];
  if (counters[2] == 0)
    return counters[0];
  // Splits and crossings are rare: only then is the segment state read back.
  const auto state = download_by_segment(segment_state_);
  const auto vertex = download_by_segment(split_vertex_);
  if (std::find(state.begin(), state.end(), kCrossing) != state.end()) {
    split_crossings(state, vertex, stats, insert_points);
    return -1;
  }
  std::vector<Segment> pieces;
  std::vector<int32_t> origin; // input segment of each piece
  for (std::size_t i = 0; i < m; ++i) {
    const Segment &s = segments_[i];
    if (state[i] == kSplit) {
      pieces.push_back({s.a, vertex[i], s.marker});
      pieces.push_back({vertex[i], s.b, s.marker});
      origin.insert(origin.end(), 2, origin_[i]);
      if (!split_origin_[origin_[i]]) {
        split_origin_[origin_[i]] = 1;
        ++stats.split_segments;
      }
    } else if (state[i] != 0 && state[i] != kPresent) {
      throw InternalError("constraint marking: a walk along a segment did not end");
    } else {
      pieces.push_back(s);
      origin.push_back(origin_[i]);
    }
  }
  origin_ = origin;
  set_constraints(pieces);
  return -1;
}

void ConstraintInsertion::split_crossings(const std::vector<cl_int> &state,
                                          const std::vector<cl_int> &vertex,
                                          ConstrainedStats &stats,
                                          const PointInserter &insert_points) {
  const std::size_t m = segments_.size();
  const auto other = download_by_segment(crossed_vertex_);
  const auto triangle = download_by_segment(crossed_triangle_);
  // (ends, index) of every piece, sorted: the piece a walk met, by binary
  // search.
  using Ends = std::pair<int32_t, int32_t>;
  std::vector<std::pair<Ends, std::size_t>> piece_of(m);
  for (std::size_t i = 0; i < m; ++i)
    piece_of[i] = {std::minmax(segments_[i].a, segments_[i].b), i};
  std::sort(piece_of.begin(), piece_of.end());
  // One download, not a read per endpoint: a round may split thousands.
  const std::vector<cl_double2> points = mesh_.points.download(device_, mesh_.point_count);
  auto coordinates = [&](int32_t v) {
    const cl_double2 &p = points[static_cast<std::size_t>(v)];
    return Point{p.s[0], p.s[1]};
  };
  // Each crossing splits two segments: s (walking) and the piece p-q it met.
  std::vector<char> busy(m, 0);
  std::vector<std::pair<std::size_t, std::size_t>> crossings; // (s, piece)
  std::vector<Point> where;
  std::vector<int32_t> near, at_vertex; // at_vertex: see `at` below
  std::vector<int32_t> where_origin;    // added_origins() of the new points
  std::multimap<double, std::pair<Point, int32_t>>
      new_vertices; // this round's, as crossing_vertices_
  for (std::size_t s = 0; s < m; ++s) {
    if (state[s] != kCrossing)
      continue;
    const Ends ends = std::minmax(vertex[s], other[s]);
    const auto found =
        std::lower_bound(piece_of.begin(), piece_of.end(), std::make_pair(ends, std::size_t{0}));
    if (found == piece_of.end() || found->first != ends)
      throw InternalError("constraint marking: a crossed constraint edge is no constraint");
    const std::size_t piece = found->second;
    if (busy[s] || busy[piece])
      continue; // split in a later round
    busy[s] = busy[piece] = 1;
    const Point a = coordinates(segments_[s].a), b = coordinates(segments_[s].b);
    const Point p = coordinates(segments_[piece].a), q = coordinates(segments_[piece].b);
    const Crossing crossing = crossing_point(a, b, p, q);
    const Point &point = crossing.point;
    // A crossing within its rounding noise of an endpoint of either segment
    // (one passes within rounding of the other's end), or of the vertex of an
    // earlier crossing, is that vertex, the nearest: no new point. Crossings
    // of many segments at one spot (a star of diameters) then meet at one
    // vertex, instead of making a cluster of points a hair apart whose pieces
    // cross again and again. Nearly parallel segments (overlapping ones a
    // hair from collinear) cross where rounding decides: an endpoint within
    // that uncertainty along them is the crossing, or their pieces would
    // cross again without end. A vertex qualifies only within the extent of
    // each segment it splits. at: a vertex, or -2 - k for the k-th new point.
    int32_t at = -1;
    double nearest = std::numeric_limits<double>::infinity();
    // Strictly between u and w along u-w, each end's side measured from that
    // end (a far end's coordinates leave the near one's digits alone).
    auto inside = [&](const Point &v, const Point &u, const Point &w) {
      const double ux = w.x - u.x, uy = w.y - u.y;
      return (v.x == u.x && v.y == u.y) || (v.x == w.x && v.y == w.y) ||
             ((v.x - u.x) * ux + (v.y - u.y) * uy > 0 && (w.x - v.x) * ux + (w.y - v.y) * uy > 0);
    };
    auto consider = [&](const Point &there, int32_t id, double reach) {
      const double distance = std::max(std::abs(there.x - point.x), std::abs(there.y - point.y));
      if (distance <= reach && distance < nearest && inside(there, a, b) && inside(there, p, q)) {
        at = id;
        nearest = distance;
      }
    };
    for (const int32_t v : {segments_[s].a, segments_[s].b, segments_[piece].a, segments_[piece].b})
      consider(coordinates(v), v, crossing.along);
    for (const auto *index : {&crossing_vertices_, &new_vertices})
      for (auto it = index->lower_bound(point.x - crossing.noise);
           it != index->end() && it->first <= point.x + crossing.noise; ++it)
        consider(it->second.first, it->second.second, crossing.noise);
    const int32_t origin = std::min(origin_[s], origin_[piece]);
    if (at == -1) {
      at = -2 - static_cast<int32_t>(where.size());
      new_vertices.emplace(point.x, std::make_pair(point, at));
      where.push_back(point);
      near.push_back(triangle[s]);
      where_origin.push_back(origin);
    } else if (at < -1) {
      where_origin[-2 - at] = std::min(where_origin[-2 - at], origin);
    }
    crossings.emplace_back(s, piece);
    at_vertex.push_back(at);
  }
  const std::vector<int32_t> added = insert_points(where, near);
  vertex_triangles_recorded_ = false;
  fit_to_mesh();
  added_points_.insert(added_points_.end(), where.begin(), where.end());
  added_origins_.insert(added_origins_.end(), where_origin.begin(), where_origin.end());
  for (std::size_t k = 0; k < where.size(); ++k)
    crossing_vertices_.emplace(where[k].x, std::make_pair(where[k], added[k]));
  stats.crossings += static_cast<long>(where.size());
  stats.crossings_at_vertices += static_cast<long>(crossings.size() - where.size());
  std::vector<Segment> pieces;
  std::vector<int32_t> origin;
  std::vector<int32_t> split_at(m, -1);
  for (std::size_t k = 0; k < crossings.size(); ++k)
    split_at[crossings[k].first] = split_at[crossings[k].second] =
        at_vertex[k] >= 0 ? at_vertex[k] : added[-2 - at_vertex[k]];
  for (std::size_t i = 0; i < m; ++i) {
    const Segment &s = segments_[i];
    if (split_at[i] < 0) {
      pieces.push_back(s);
      origin.push_back(origin_[i]);
      continue;
    }
    for (const Segment &piece :
         {Segment{s.a, split_at[i], s.marker}, Segment{split_at[i], s.b, s.marker}})
      if (piece.a != piece.b) { // the new vertex may coincide with an endpoint
        pieces.push_back(piece);
        origin.push_back(origin_[i]);
      }
    if (!split_origin_[origin_[i]]) {
      split_origin_[origin_[i]] = 1;
      ++stats.split_segments;
    }
  }
  origin_ = origin;
  set_constraints(pieces);
}

void ConstraintInsertion::fit_to_mesh() {
  const std::size_t slots = mesh_.triangle_capacity;
  touched_.grow(device_, slots);
  touched_.cover(device_, mesh_.triangle_count, kPhase);
  if (constraint_mark_.size() >= slots)
    return;
  // The others are rewritten before each use.
  constraint_mark_ = DeviceArray<cl_int>(device_, slots);
  run_start_ = DeviceArray<cl_int>(device_, slots);
  run_of_ = DeviceArray<cl_int>(device_, slots);
  boundary_log_ = DeviceArray<cl_int>(device_, kLogPerTriangle * slots);
}

ConstraintInsertion::RunPass ConstraintInsertion::flip_runs() {
  const std::size_t slots = mesh_.triangle_count;
  const auto max_steps = static_cast<cl_int>(4 * slots + 64);
  run_counters_.fill(device_, 0, kRunCounters);
  run_of_.fill(device_, -1, slots);
  set_args(find_run_starts_, constraint_mark_.buffer(), mesh_.tri_neighbor.buffer(),
           run_start_.buffer(), run_counters_.buffer(), static_cast<cl_int>(slots));
  launch(device_, find_run_starts_, slots, kPhase);
  const auto runs = static_cast<std::size_t>(run_counters_.read(device_, 0));
  set_args(claim_runs_, run_start_.buffer(), mesh_.tri_neighbor.buffer(), constraint_mark_.buffer(),
           run_of_.buffer(), max_steps, static_cast<cl_int>(runs));
  launch(device_, claim_runs_, runs, kPhase);
  const auto log_capacity = static_cast<cl_int>(boundary_log_.size());
  set_args_from(flip_along_runs_, mesh_.bind_triangulation(flip_along_runs_, 0),
                run_start_.buffer(), constraint_mark_.buffer(), segment_a_.buffer(),
                segment_b_.buffer(), run_of_.buffer(), boundary_log_.buffer(),
                run_counters_.buffer(), touched_.array.buffer(), log_capacity, max_steps,
                static_cast<cl_int>(runs));
  launch(device_, flip_along_runs_, runs, kPhase);
  const auto counts = run_counters_.download(device_, kRunCounters);
  const std::size_t logged =
      std::min<std::size_t>(static_cast<std::size_t>(counts[1]), boundary_log_.size());
  if (logged > 0) {
    std::size_t table = 1;
    while (table < 2 * logged)
      table *= 2;
    if (edge_table_.size() < table)
      edge_table_ = DeviceArray<cl_int>(device_, table);
    edge_table_.fill(device_, -1, table);
    set_args(relink_run_boundaries_, boundary_log_.buffer(), mesh_.tri_vertex.buffer(),
             mesh_.tri_neighbor.buffer(), run_of_.buffer(), edge_table_.buffer(),
             static_cast<cl_uint>(table - 1), static_cast<cl_int>(logged));
    launch(device_, relink_run_boundaries_, logged, kPhase);
  }
  return {static_cast<long>(runs), counts[2]};
}

void ConstraintInsertion::run(ConstrainedStats &stats, const PointInserter &insert_points) {
  fit_to_mesh();
  bool first = true;
  // Each outer iteration either inserts a segment, splits one, or flips; the
  // bound (of the pieces and triangles so far: crossings add both) only
  // turns a bug into an error instead of a hang.
  auto max_outer = [&] {
    return 64 + 4 * static_cast<long>(segments_.size() + mesh_.triangle_count);
  };
  for (long outer = 0; outer < max_outer(); ++outer) {
    const long pending = mark(stats, first, insert_points);
    first = false;
    if (pending < 0)
      continue; // segments were split: mark again
    if (pending == 0)
      return;
    ++stats.outer_iterations;
    const RunPass pass = flip_runs();
    stats.inner_iterations += pass.runs;
    stats.constraint_flips += pass.flips;
    if (pass.flips == 0)
      throw InternalError("constraint insertion made no progress");
  }
  throw InternalError("constraint insertion did not finish");
}

} // namespace clmesh
