// clmesh — GPU-DT entry point (thesis §4.1.2).
#include "dt/delaunay.hpp"

#include "dt/delaunay_scheduler.hpp"

namespace clmesh {

DelaunayResult delaunay(Device &device, const std::vector<Point> &points,
                        const DelaunayOptions &options) {
  DelaunayResult result;
  DelaunayScheduler scheduler(device, points, options, result.stats);
  if (scheduler.triangulate())
    scheduler.download(result);
  else
    scheduler.download_collinear(result);
  return result;
}

} // namespace clmesh
