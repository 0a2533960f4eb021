// clmesh — GPU-DT entry point (thesis §4.1.2).
#include "dt/delaunay.hpp"

#include "dt/delaunay_scheduler.hpp"

#include <algorithm>

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

std::vector<DelaunayResult> delaunay_packed(Device &device,
                                            const std::vector<const std::vector<Point> *> &sets,
                                            const DelaunayOptions &options) {
  std::vector<Point> points;
  std::vector<std::size_t> starts{0};
  for (const std::vector<Point> *set : sets) {
    points.insert(points.end(), set->begin(), set->end());
    starts.push_back(points.size());
  }
  DelaunayResult pack;
  DelaunayScheduler scheduler(device, points, options, pack.stats, 0, starts);
  if (!scheduler.triangulate())
    throw InternalError("packed triangulation: a point set is collinear");
  scheduler.download(pack);
  // Each triangle's vertices are of one set; the canonical order (by the
  // smallest vertex) keeps each set's triangles in the order of its own.
  std::vector<DelaunayResult> results(sets.size());
  auto set_of = [&](int32_t vertex) {
    return static_cast<std::size_t>(
        std::upper_bound(starts.begin(), starts.end(), static_cast<std::size_t>(vertex)) -
        starts.begin() - 1);
  };
  std::vector<int32_t> local(pack.triangles.size());
  for (std::size_t t = 0; t < pack.triangles.size(); ++t) {
    const std::size_t k = set_of(pack.triangles[t][0]);
    const auto first = static_cast<int32_t>(starts[k]);
    Triangle triangle = pack.triangles[t];
    for (int32_t &v : triangle) {
      if (set_of(v) != k)
        throw InternalError("packed triangulation: a triangle joins two point sets");
      v -= first;
    }
    local[t] = static_cast<int32_t>(results[k].triangles.size());
    results[k].triangles.push_back(triangle);
  }
  for (DelaunayResult &result : results)
    result.neighbors.reserve(result.triangles.size());
  for (std::size_t t = 0; t < pack.triangles.size(); ++t) {
    std::array<int32_t, 3> across = pack.neighbors[t];
    for (int32_t &u : across)
      if (u >= 0)
        u = local[static_cast<std::size_t>(u)];
    results[set_of(pack.triangles[t][0])].neighbors.push_back(across);
  }
  for (std::size_t k = 0; k < sets.size(); ++k) {
    DelaunayResult &result = results[k];
    const auto first = static_cast<int32_t>(starts[k]);
    result.duplicate_of.assign(pack.duplicate_of.begin() + first,
                               pack.duplicate_of.begin() +
                                   static_cast<std::ptrdiff_t>(starts[k + 1]));
    for (int32_t &d : result.duplicate_of)
      if (d >= 0)
        d -= first;
    result.stats = pack.stats;
    result.stats.construction = "packed";
    result.stats.input_points = static_cast<long>(sets[k]->size());
    result.stats.duplicates = std::count_if(result.duplicate_of.begin(), result.duplicate_of.end(),
                                            [](int32_t d) { return d >= 0; });
    result.stats.triangles = static_cast<long>(result.triangles.size());
  }
  return results;
}

} // namespace clmesh
