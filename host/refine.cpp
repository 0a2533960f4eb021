// clmesh — GPU-QM entry point (thesis chapter 3): GPU-DT, then rounds of
// off-center insertion (bad triangles, insertion filter, point insertion and
// Delaunay flipping) until no triangle is bad.
#include "clmesh/refine.hpp"

#include "delaunay_scheduler.hpp"
#include "offcenter_insertion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace clmesh {

namespace {

// First room for Steiner points; the arrays grow by at least n when it runs
// out (thesis §3.6.1).
std::size_t first_room(std::size_t n) { return n + 4096; }

} // namespace

RefineResult refine_delaunay(Device &device, const std::vector<Point> &points,
                             const RefineOptions &options) {
  if (options.min_angle < 0 || options.min_angle > 45)
    throw UsageError("the minimum angle (-q) must be between 0 and 45 degrees");
  RefineResult result;
  const std::size_t n = points.size();
  DelaunayScheduler scheduler(device, points, options.delaunay, result.mesh.stats, first_room(n));
  device.program("offcenter_insertion.cl", "setup");
  if (!scheduler.triangulate()) {
    scheduler.download_collinear(result.mesh);
    return result;
  }
  auto offcenter = std::make_unique<OffcenterInsertion>(device, scheduler.mesh(), options.min_angle,
                                                        options.max_area);
  RefineStats &stats = result.stats;
  scheduler.flipping().set_fixed_boundary(true);
  const std::size_t limit = options.max_steiner >= 0 ? static_cast<std::size_t>(options.max_steiner)
                                                     : std::numeric_limits<std::size_t>::max();
  // Room for the next survivors: within the -S limit, growing the arrays when
  // the limit allows more than they hold. False when the limit is reached.
  auto make_room = [&](std::size_t wanted) {
    const DeviceMesh &mesh = scheduler.mesh();
    if (mesh.point_count - n + wanted > limit)
      return false;
    if (mesh.point_count + wanted > mesh.point_capacity) {
      scheduler.grow(std::max(wanted, n));
      offcenter = std::make_unique<OffcenterInsertion>(device, scheduler.mesh(), options.min_angle,
                                                       options.max_area);
    }
    return true;
  };
  // Termination is guaranteed for angles up to about 30 degrees away from
  // small hull angles; the bound on iterations turns anything else into
  // remaining bad triangles, reported, instead of a hang.
  const long max_iterations = 1000;
  for (long iteration = 0;; ++iteration) {
    const std::size_t bad = offcenter->find(scheduler.scan(), scheduler.stamp());
    scheduler.timer().charge(OffcenterInsertion::kPhase);
    stats.remaining_bad = static_cast<long>(bad);
    if (bad == 0 || iteration == max_iterations)
      break;
    // Room for every candidate first (growing invalidates the candidates:
    // they are found again).
    if (scheduler.mesh().point_count + bad > scheduler.mesh().point_capacity &&
        scheduler.mesh().point_count - n + bad <= limit) {
      make_room(bad);
      continue;
    }
    ++stats.iterations;
    stats.candidates += static_cast<long>(bad);
    const DeviceMesh &mesh = scheduler.mesh();
    const std::size_t room = std::min(mesh.point_capacity - mesh.point_count,
                                      limit - std::min(limit, mesh.point_count - n));
    // Hull splits first, each on its edge, then the points inside.
    std::size_t wanted = 0;
    const std::size_t splits = offcenter->append(true, room, scheduler.scan(), &wanted);
    if (splits > 0)
      scheduler.insert_appended(splits, true);
    stats.boundary_splits += static_cast<long>(splits);
    const std::size_t inside = offcenter->append(false, room - splits, scheduler.scan(), &wanted);
    const std::size_t coinciding = inside > 0 ? scheduler.insert_appended(inside) : 0;
    if (splits + inside - coinciding == 0)
      break; // nothing new: the -S limit, or every candidate fell on a vertex
  }
  const DeviceMesh &mesh = scheduler.mesh();
  stats.inserted = static_cast<long>(mesh.point_count - n);
  std::vector<cl_double2> added = mesh.points.download(device, mesh.point_count - n, n);
  for (const cl_double2 &p : added)
    result.added_points.push_back({p.s[0], p.s[1]});
  scheduler.download(result.mesh);
  return result;
}

} // namespace clmesh
