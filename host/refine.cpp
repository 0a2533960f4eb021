// clmesh — GPU-QM entry point (thesis chapter 3): GPU-DT, then rounds of
// off-center insertion (bad triangles, insertion filter, point insertion and
// Delaunay flipping) until no triangle is bad.
#include "clmesh/refine.hpp"

#include "delaunay_scheduler.hpp"
#include "offcenter_insertion.hpp"

#include <algorithm>
#include <cmath>

namespace clmesh {

namespace {

// Room for Steiner points: enough for the usual refinement of a point set,
// plus the triangles an area bound asks for, at most about 10 million
// (beyond, refinement stops and reports the triangles still bad).
std::size_t steiner_room(const std::vector<Point> &points, const RefineOptions &options) {
  std::size_t room = 4 * points.size() + 4096;
  if (options.max_area > 0) {
    double min_x = points[0].x, max_x = min_x, min_y = points[0].y, max_y = min_y;
    for (const Point &p : points) {
      min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
      min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
    }
    const double box = (max_x - min_x) * (max_y - min_y);
    room += static_cast<std::size_t>(std::min(1e7, 2 * box / options.max_area));
  }
  if (options.max_steiner >= 0)
    room = std::min(room, static_cast<std::size_t>(options.max_steiner));
  return room;
}

} // namespace

RefineResult refine_delaunay(Device &device, const std::vector<Point> &points,
                             const RefineOptions &options) {
  if (options.min_angle < 0 || options.min_angle > 45)
    throw UsageError("the minimum angle (-q) must be between 0 and 45 degrees");
  RefineResult result;
  const std::size_t room = steiner_room(points, options);
  DelaunayScheduler scheduler(device, points, options.delaunay, result.mesh.stats, room);
  device.program("offcenter_insertion.cl", "setup");
  if (!scheduler.triangulate()) {
    scheduler.download_collinear(result.mesh);
    return result;
  }
  DeviceMesh &mesh = scheduler.mesh();
  const std::size_t n = points.size();
  OffcenterInsertion offcenter(device, mesh, options.min_angle, options.max_area);
  RefineStats &stats = result.stats;
  scheduler.flipping().set_fixed_boundary(true);
  // Termination is guaranteed for angles up to about 30 degrees away from
  // small hull angles; the bound on iterations turns anything else into
  // remaining bad triangles, reported, instead of a hang.
  const long max_iterations = 1000;
  for (long iteration = 0;; ++iteration) {
    const std::size_t bad = offcenter.find(scheduler.scan());
    scheduler.timer().charge(OffcenterInsertion::kPhase);
    stats.remaining_bad = static_cast<long>(bad);
    if (bad == 0 || iteration == max_iterations)
      break;
    ++stats.iterations;
    stats.candidates += static_cast<long>(bad);
    // Hull splits first, each on its edge, then the points inside.
    const std::size_t splits =
        offcenter.append(true, mesh.point_capacity - mesh.point_count, scheduler.scan());
    if (splits > 0)
      scheduler.insert_appended(splits, true);
    stats.boundary_splits += static_cast<long>(splits);
    const std::size_t inside =
        offcenter.append(false, mesh.point_capacity - mesh.point_count, scheduler.scan());
    const std::size_t coinciding = inside > 0 ? scheduler.insert_appended(inside) : 0;
    if (splits + inside - coinciding == 0)
      break; // nothing new: no room left, or every candidate fell on a vertex
  }
  stats.inserted = static_cast<long>(mesh.point_count - n);
  std::vector<cl_double2> added = mesh.points.download(device, mesh.point_count - n, n);
  for (const cl_double2 &p : added)
    result.added_points.push_back({p.s[0], p.s[1]});
  scheduler.download(result.mesh);
  return result;
}

} // namespace clmesh
