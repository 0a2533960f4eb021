// clmesh — the GPU-DT scheduler (thesis §4.1.2): runs the phases on one
// device, keeping the mesh resident from the upload of the points to the
// download of the triangles; between kernels only small counters come back.
#include "clmesh/delaunay.hpp"

#include "flipping.hpp"
#include "mesh_output.hpp"
#include "missing_point_insertion.hpp"
#include "voronoi_banding.hpp"
#include "predicates.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

namespace clmesh {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

class PhaseTimer {
public:
  PhaseTimer(Device &device, DelaunayStats &stats) : device_(device), stats_(stats) {}
  // Waits for the device, then charges the time since the last call to `name`.
  void charge(const std::string &name) {
    device_.queue().finish();
    const auto now = Clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    for (auto &phase : stats_.phases)
      if (phase.name == name) {
        phase.seconds += seconds;
        return;
      }
    stats_.phases.push_back({name, seconds});
  }

private:
  Device &device_;
  DelaunayStats &stats_;
  Clock::time_point last_ = Clock::now();
};

void check_coordinates(const std::vector<Point> &points) {
  for (std::size_t i = 0; i < points.size(); ++i)
    for (const double value : {points[i].x, points[i].y}) {
      const double magnitude = std::fabs(value);
      if (!std::isfinite(value) || magnitude > kMaxCoordinate ||
          (value != 0 && magnitude < kMinCoordinate))
        throw InputError("point " + std::to_string(i), 0,
                         "coordinate " + std::to_string(value) +
                             " is outside what exact arithmetic carries (non-zero magnitudes "
                             "from 1e-50 to 1e50)");
    }
}

bool lexicographically_less(const Point &a, const Point &b) {
  return a.x < b.x || (a.x == b.x && a.y < b.y);
}

int orient(const Point &a, const Point &b, const Point &c) {
  return clm_orient2d(a.x, a.y, b.x, b.y, c.x, c.y);
}

// Rotates each triangle to start at its smallest vertex and sorts the list,
// so the output depends only on the mesh, not on how it was computed.
void canonical_order(std::vector<Triangle> &triangles,
                     std::vector<std::array<int32_t, 3>> &neighbors) {
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    auto &tri = triangles[t];
    const int r = tri[0] < tri[1] ? (tri[0] < tri[2] ? 0 : 2) : (tri[1] < tri[2] ? 1 : 2);
    std::rotate(tri.begin(), tri.begin() + r, tri.end());
    std::rotate(neighbors[t].begin(), neighbors[t].begin() + r, neighbors[t].end());
  }
  std::vector<int32_t> order(triangles.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int32_t a, int32_t b) { return triangles[a] < triangles[b]; });
  std::vector<int32_t> new_index(triangles.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    new_index[order[i]] = static_cast<int32_t>(i);
  std::vector<Triangle> sorted(triangles.size());
  std::vector<std::array<int32_t, 3>> sorted_neighbors(triangles.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    sorted[i] = triangles[order[i]];
    for (int k = 0; k < 3; ++k) {
      const int32_t n = neighbors[order[i]][k];
      sorted_neighbors[i][k] = n < 0 ? -1 : new_index[n];
    }
  }
  triangles.swap(sorted);
  neighbors.swap(sorted_neighbors);
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
      duplicate_of[order[i]] = duplicate_of[order[i - 1]] >= 0 ? duplicate_of[order[i - 1]]
                                                               : order[i - 1];
  }
  return duplicate_of;
}

// Position along a Hilbert curve of a point quantized to a 2^16 x 2^16 grid.
uint32_t hilbert_index(uint32_t x, uint32_t y) {
  uint32_t d = 0;
  for (uint32_t s = 1u << 15; s > 0; s >>= 1) {
    const uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry);
    if (ry == 0) { // rotate the quadrant
      if (rx == 1) {
        x = s - 1 - (x & (s - 1)) + (x & ~(s - 1));
        y = s - 1 - (y & (s - 1)) + (y & ~(s - 1));
      }
      std::swap(x, y);
    }
  }
  return d;
}

// Input indices sorted along a Hilbert curve (stable, so ties keep input order).
std::vector<int32_t> spatial_order(const std::vector<Point> &points) {
  double min_x = points[0].x, max_x = min_x, min_y = points[0].y, max_y = min_y;
  for (const Point &p : points) {
    min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
    min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
  }
  const double span = std::max(max_x - min_x, max_y - min_y);
  const double scale = span > 0 && std::isfinite(span) ? 65535.0 / span : 0.0;
  std::vector<uint32_t> key(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto qx = static_cast<uint32_t>(std::min(65535.0, (points[i].x - min_x) * scale));
    const auto qy = static_cast<uint32_t>(std::min(65535.0, (points[i].y - min_y) * scale));
    key[i] = hilbert_index(qx, qy);
  }
  // Two stable counting-sort passes of 16 bits each.
  std::vector<int32_t> order(points.size()), buffer(points.size());
  std::iota(order.begin(), order.end(), 0);
  for (int shift = 0; shift < 32; shift += 16) {
    std::vector<std::size_t> start(65537, 0);
    for (const int32_t i : order)
      ++start[((key[i] >> shift) & 0xffff) + 1];
    for (std::size_t b = 1; b < start.size(); ++b)
      start[b] += start[b - 1];
    for (const int32_t i : order)
      buffer[start[(key[i] >> shift) & 0xffff]++] = i;
    order.swap(buffer);
  }
  return order;
}

// Vertices of the convex hull, counter-clockwise, without collinear points
// (Andrew's monotone chain with the exact orientation predicate).
std::vector<int32_t> convex_hull(const std::vector<Point> &points) {
  std::vector<int32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
    return lexicographically_less(points[a], points[b]) ||
           (!lexicographically_less(points[b], points[a]) && a < b);
  });
  std::vector<int32_t> hull(2 * points.size() + 1);
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

} // namespace

DelaunayResult delaunay(Device &device, const std::vector<Point> &points,
                        const DelaunayOptions &options) {
  if (points.size() < 3)
    throw InputError("input", 0, "fewer than three points");
  if (points.size() > (std::size_t{1} << 28))
    throw InputError("input", 0, "more than 2^28 points");
  check_coordinates(points);
  if (options.work_group)
    device.set_work_group(options.work_group);

  DelaunayResult result;
  DelaunayStats &stats = result.stats;
  stats.device = describe(device);
  stats.input_points = static_cast<long>(points.size());
  const std::size_t n = points.size();

  // Build every program before the clock starts.
  for (const char *file : {"scan.cl", "voronoi_banding.cl", "missing_point_insertion.cl",
                           "flipping.cl", "mesh_output.cl"})
    device.program(file, "setup");

  const auto start = Clock::now();
  const std::vector<int32_t> hull = convex_hull(points);
  if (hull.size() < 3) { // all points collinear: no triangle
    result.duplicate_of = duplicates_on_host(points);
    stats.duplicates = std::count_if(result.duplicate_of.begin(), result.duplicate_of.end(),
                                     [](int32_t d) { return d >= 0; });
    stats.compute_seconds = seconds_since(start);
    return result;
  }

  PhaseTimer timer(device, stats);
  DeviceMesh mesh(device, n);
  PrefixScan scan(device);
  MissingPointInsertion insertion(device, mesh, scan);
  Flipping flipping(device, mesh, scan);
  MeshOutput output(device, mesh, scan);

  // Device points follow a Hilbert curve, so that neighbouring work-items
  // touch neighbouring memory; the output goes back to the input numbering.
  const std::vector<int32_t> original_id = spatial_order(points);
  std::vector<int32_t> device_id(n);
  std::vector<cl_double2> coordinates(n);
  for (std::size_t k = 0; k < n; ++k) {
    device_id[original_id[k]] = static_cast<int32_t>(k);
    coordinates[k] = {{points[original_id[k]].x, points[original_id[k]].y}};
  }
  mesh.points.upload(device, coordinates);
  mesh.original_id.upload(device, original_id);
  std::vector<int32_t> device_hull(hull.size());
  for (std::size_t i = 0; i < hull.size(); ++i)
    device_hull[i] = device_id[hull[i]];
  const HullFan fan = hull_fan(device_hull);
  mesh.tri_vertex.upload(device, fan.vertices);
  mesh.tri_neighbor.upload(device, fan.neighbors);
  mesh.triangle_count = fan.vertices.size() / 3;
  mesh.tri_mark.fill(device, 0xffffffffu, mesh.triangle_capacity);
  mesh.modified_stamp.fill(device, 0, mesh.triangle_capacity);
  mesh.duplicate_of.fill(device, -1, n);
  mesh.location.fill(device, 0, n);
  std::vector<char> in_mesh(n, 0);
  for (const int32_t v : device_hull) {
    in_mesh[v] = 1;
    mesh.vertex_triangle.upload(device, std::vector<cl_int>{0}, v);
  }
  std::vector<cl_int> missing;
  missing.reserve(n - hull.size());
  for (std::size_t i = 0; i < n; ++i)
    if (!in_mesh[i])
      missing.push_back(static_cast<cl_int>(i));
  insertion.set_points(missing);
  stats.missing_points = static_cast<long>(missing.size());
  timer.charge("upload");

  // Phase 1. Phases 2 and 3 (triangulation construction from the digital
  // Voronoi vertices, shifting) are not built yet, so the diagram serves the
  // picture only and every point is placed by Phase 4: the run is skipped
  // unless the picture is wanted.
  if (options.want_voronoi_image) {
    stats.grid = options.grid > 0 ? options.grid : VoronoiBanding::default_grid(n);
    VoronoiBanding banding(device, mesh, scan);
    const auto [low_x, high_x] = std::minmax_element(
        points.begin(), points.end(), [](const Point &a, const Point &b) { return a.x < b.x; });
    const auto [low_y, high_y] = std::minmax_element(
        points.begin(), points.end(), [](const Point &a, const Point &b) { return a.y < b.y; });
    const double span = std::max(high_x->x - low_x->x, high_y->y - low_y->y);
    stats.pixel_collisions = static_cast<long>(banding.run(stats.grid, {low_x->x, low_y->y}, span));
    result.voronoi = banding.download_image();
    timer.charge(VoronoiBanding::kPhase);
  }

  // The fan is a triangulation, not yet a Delaunay one: flip it first.
  int stamp = 1;
  FlipCounts flips;
  {
    std::vector<cl_int> every_triangle(mesh.triangle_count);
    std::iota(every_triangle.begin(), every_triangle.end(), 0);
    DeviceArray<cl_int> active(device, every_triangle.size());
    active.upload(device, every_triangle);
    flipping.run(active, every_triangle.size(), stamp, flips);
    timer.charge(Flipping::kPhase);
  }

  // Phase 4 in conflict-free rounds, each followed by Phase 5 flipping so that
  // the next round's walks run in a Delaunay triangulation.
  while (insertion.pending() > 0) {
    const std::size_t inserted = insertion.run_round(stamp++);
    ++stats.insertion_rounds;
    timer.charge(MissingPointInsertion::kPhase);
    if (inserted == 0 && insertion.pending() > 0)
      throw InternalError("missing-point insertion made no progress");
    flipping.run(insertion.changed(), 4 * inserted, stamp, flips);
    timer.charge(Flipping::kPhase);
  }
  stats.duplicates = static_cast<long>(insertion.duplicates());
  stats.flips = flips.flips;
  stats.flip_passes = flips.passes;
  stats.exact_predicate_calls = flips.exact_checks;

  output.download(result.triangles, result.neighbors, result.duplicate_of);
  canonical_order(result.triangles, result.neighbors);
  timer.charge(MeshOutput::kPhase);
  stats.triangles = static_cast<long>(result.triangles.size());
  stats.compute_seconds = seconds_since(start);
  return result;
}

} // namespace clmesh
