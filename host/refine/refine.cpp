// clmesh — GPU-QM and GPU-QM-V entry point (thesis chapter 3): GPU-DT, then
// iterations of three steps until no triangle is bad: (1) off-centers of the
// bad triangles and the insertion filter, (2) their insertion, in place, in
// one round of 1-3 and 2-4 (1-2 on the hull) flips, (3) flip-flop: Delaunay
// flips together with the deletion of redundant points.
#include "refine/refine.hpp"

#include "dt/delaunay_scheduler.hpp"
#include "dt/missing_point_insertion.hpp"
#include "refine/flip_flop.hpp"
#include "refine/free_slots.hpp"
#include "refine/offcenter_insertion.hpp"
#include "refine/steiner_renumbering.hpp"
#include "refine/zorder_compaction.hpp"

#include <algorithm>
#include <limits>
#include <memory>

namespace clmesh {

namespace {

// Can the device hold the refinement's arrays for `points` points? About 600
// bytes per point in all; the largest array (flip-flop's stars, 4 entries
// per list entry) takes 16 x 8/3 bytes per point.
bool device_holds(const Device &device, std::size_t points) {
  const double per_point = 600, largest_per_point = 16.0 * 8 / 3;
  return per_point * static_cast<double>(points) <
             0.9 * static_cast<double>(device.global_memory()) &&
         largest_per_point * static_cast<double>(points) <
             static_cast<double>(device.max_allocation());
}

// First room for Steiner points (thesis §3.6.1: the arrays grow when it runs
// out). A growth copies every array and builds the steps again, and the
// search after it sweeps every slot, so the first room is what refinement to
// the angle bound usually takes: point sets gain about 0.6 n Steiner points
// at 20 degrees and 1.8 n at 30 (uniform, Gaussian, disk; a thin circle up to
// 3.4 n), and deleted points hold their slots for a while. A growth adds
// half the room at least, so that few follow.
std::size_t first_room(const Device &device, std::size_t n, const RefineOptions &options) {
  const double bound = std::min(options.min_angle, 30.0) / 30.0;
  auto room = static_cast<std::size_t>(static_cast<double>(n) * std::max(1.0, 2.2 * bound * bound));
  if (options.max_steiner)
    room = std::min(room, std::max(n, static_cast<std::size_t>(*options.max_steiner)));
  if (!device_holds(device, n + room + 4096))
    room = n;
  return room + 4096;
}

// The phase objects of the three steps, sized by the mesh: built again when
// the mesh grows.
struct RefinementSteps {
  RefinementSteps(DelaunayScheduler &scheduler, const RefineOptions &options)
      : offcenter(scheduler.device(), scheduler.mesh(), options.min_angle,
                  options.max_area.value_or(-1), options.delaunay.tuning.filter_rings,
                  options.delaunay.tuning.filter_distance_rings,
                  options.delaunay.tuning.filter_near, options.delaunay.tuning.parallel_midpoints,
                  options.delaunay.tuning.election_rings),
        insertion(scheduler.device(), scheduler.mesh(), scheduler.scan()),
        flipflop(scheduler.device(), scheduler.mesh(), scheduler.scan(),
                 options.delaunay.tuning.algorithm == RefineAlgorithm::qmv, offcenter.lens(),
                 options.delaunay.tuning.group_pass_limit),
        free_slots(scheduler.device(), scheduler.mesh(), scheduler.scan()),
        compaction(scheduler.device(), scheduler.mesh(), scheduler.scan()),
        renumbering(scheduler.device(), scheduler.mesh(), scheduler.scan()),
        new_points(scheduler.device(), scheduler.mesh().point_capacity) {}
  OffcenterInsertion offcenter;
  MissingPointInsertion insertion;
  FlipFlop flipflop;
  FreeSlots free_slots;
  ZOrderCompaction compaction;
  SteinerRenumbering renumbering;
  DeviceArray<cl_int> new_points; // the points inserted in this iteration
};

} // namespace

RefineResult refine_delaunay(Device &device, const std::vector<Point> &points,
                             const RefineOptions &options) {
  RefineResult result;
  const std::size_t n = points.size();
  // Refinement breaks ties by triangle slot; its first compaction gives
  // the triangles a layout that depends on them alone, whichever
  // construction (and grid) built them.
  DelaunayScheduler scheduler(device, points, options.delaunay, result.mesh.stats,
                              first_room(device, n, options));
  device.program("offcenter_insertion.cl", "setup");
  for (const char *file : {"flip_flop.cl", "hull_encroachment.cl", "free_slots.cl",
                           "zorder_compaction.cl", "steiner_renumbering.cl"})
    device.program(file, "setup");
  if (!scheduler.triangulate()) {
    scheduler.download_collinear(result.mesh);
    return result;
  }
  DeviceMesh &mesh = scheduler.mesh();
  mesh.enable_refinement(device);
  scheduler.flipping().set_fixed_boundary(true);
  auto steps = std::make_unique<RefinementSteps>(scheduler, options);
  const std::size_t acute_hull_vertices = steps->offcenter.flag_hull_vertices();
  RefineStats &stats = result.stats;
  FlipFlopCounts flips;
  const std::size_t limit = options.max_steiner ? static_cast<std::size_t>(*options.max_steiner)
                                                : std::numeric_limits<std::size_t>::max();
  DeletionLog deletion_log;
  DeviceList<cl_int> changed; // the triangles rewritten since the last search
  std::size_t steiner = 0;    // Steiner points in the mesh now
  bool deleted_since_collection = false;
  // Point and triangle slots for `wanted` more points: the free ones, then the
  // ones past the used ranges.
  auto room = [&mesh] {
    return std::min(mesh.point_capacity - mesh.point_count + mesh.free_points.count,
                    (mesh.triangle_capacity - mesh.triangle_count + mesh.free_triangles.count) / 2);
  };
  // Termination is guaranteed for angles up to about 30 degrees away from
  // small hull angles; the bound on iterations turns anything else into
  // remaining bad triangles, reported, instead of a hang.
  const long max_iterations = 1000;
  const auto [low, side] = bounding_square(points); // for the spatial order of the triangles
  // Triangles move into spatial order at the start, then whenever their
  // slots grew by half while much work remains: at least one triangle in 16
  // bad at the last search. Later, the move and the search over every slot
  // that follows it cost more than the order saves (1M Gaussian q20: the
  // second move came at 2% bad, 3.75 -> 3.40 s without it, 5 alternating
  // pairs; q30: 5.7% bad, 7.85 -> 6.9 s, 3 pairs; at 34% bad the move pays).
  std::size_t compacted_slots = 0, last_bad = 0;
  for (long iteration = 0;; ++iteration) {
    if (iteration == 0 || (mesh.triangle_count >= compacted_slots + compacted_slots / 2 &&
                           16 * last_bad >= mesh.triangle_count)) {
      steps->compaction.compact(low, side, n);
      steps->offcenter.forget_triangles();
      changed.size = 0;
      deleted_since_collection = false;
      compacted_slots = mesh.triangle_count;
      scheduler.timer().charge(FlipFlop::kPhase);
    }
    const std::size_t bad = steps->offcenter.find(scheduler.scan(), &changed, scheduler.stamp());
    changed.size = 0;
    scheduler.timer().charge(OffcenterInsertion::kPhase);
    stats.remaining_bad = static_cast<long>(bad);
    last_bad = bad;
    if (bad == 0 || iteration == max_iterations || steiner >= limit)
      break;
    // Room for every candidate first: the empty slots when they run short,
    // then larger arrays (growing invalidates the candidates: found again).
    const std::size_t candidates = steps->offcenter.candidates();
    if (room() < candidates && deleted_since_collection) {
      steps->free_slots.collect();
      deleted_since_collection = false;
    }
    if (room() < candidates && steiner + candidates <= limit) {
      const std::size_t extra = std::max(candidates, mesh.point_capacity / 2);
      if (!device_holds(device, scheduler.mesh().point_capacity + extra)) {
        stats.out_of_memory = true;
        break; // reported with the bad triangles left (angles above about 33 degrees may not end)
      }
      steps.reset(); // before the mesh grows: a lower peak
      scheduler.grow(extra);
      ++stats.growths;
      steps = std::make_unique<RefinementSteps>(scheduler, options);
      continue;
    }
    ++stats.iterations;
    stats.candidates += static_cast<long>(candidates);
    std::size_t wanted = 0;
    const std::size_t added = steps->offcenter.append(std::min(room(), limit - steiner),
                                                      scheduler.scan(), steps->new_points, &wanted);
    scheduler.timer().charge(OffcenterInsertion::kPhase);
    if (added == 0)
      break; // the -S limit, or every candidate fell on a vertex
    MissingPointInsertion &insertion = steps->insertion;
    insertion.set_points(steps->new_points, added);
    const std::size_t inserted = insertion.run_round(scheduler.stamp()++, false);
    if (insertion.pending() > 0)
      throw InternalError("Steiner points placed in place were not all inserted in one round");
    scheduler.timer().charge(MissingPointInsertion::kPhase);
    const long deleted_before = flips.deleted;
    changed.append(device, insertion.changed(), 4 * inserted);
    steps->flipflop.run(insertion.changed(), 4 * inserted, steps->new_points, added,
                        scheduler.stamp(), changed, deletion_log, flips);
    scheduler.timer().charge(FlipFlop::kPhase);
    const auto deleted = static_cast<std::size_t>(flips.deleted - deleted_before);
    deleted_since_collection = deleted_since_collection || deleted > 0;
    stats.insertions += static_cast<long>(added);
    steiner += added - deleted;
  }
  if (acute_hull_vertices > 0)
    stats.remaining_bad += static_cast<long>(steps->offcenter.count_unfixable());
  stats.deleted = flips.deleted;
  stats.kept_redundant = flips.kept_redundant;
  stats.boundary_splits = flips.midpoints;
  stats.delaunay_flips = flips.delaunay_flips;
  stats.non_delaunay_flips = flips.non_delaunay_flips;
  DelaunayStats &mesh_stats = result.mesh.stats;
  mesh_stats.flips += flips.delaunay_flips + flips.non_delaunay_flips;
  mesh_stats.flip_passes += flips.passes;
  mesh_stats.exact_predicate_calls += flips.exact_checks;

  // Surviving Steiner points follow the input points, in slot order.
  result.added_points = steps->renumbering.number(n);
  const std::size_t survivors = result.added_points.size();
  stats.inserted = static_cast<long>(survivors);
  steps.reset();
  scheduler.download(result.mesh);
  result.mesh.duplicate_of.resize(n + survivors);
  stats.inserted_more_than_once =
      deletion_log.points_inserted_more_than_once(device, result.added_points);
  return result;
}

} // namespace clmesh
