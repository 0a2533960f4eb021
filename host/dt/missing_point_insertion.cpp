#include "dt/missing_point_insertion.hpp"

#include "clmesh/errors.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace clmesh {

namespace {
const char *kFile = "missing_point_insertion.cl";
}

namespace {
// List k of `pool`, or a list of its own (a point's entry each).
DeviceArray<cl_int> point_list(Device &device, const DeviceMesh &mesh, const ScratchPool *pool,
                               std::size_t k) {
  return pool ? pool->list<cl_int>(k) : DeviceArray<cl_int>(device, mesh.point_capacity);
}
} // namespace

std::vector<std::size_t> MissingPointInsertion::scratch_lists(const DeviceMesh &mesh) {
  return std::vector<std::size_t>(kLists, mesh.point_capacity * sizeof(cl_int));
}

MissingPointInsertion::MissingPointInsertion(Device &device, DeviceMesh &mesh, PrefixScan &scan,
                                             const ScratchPool *pool)
    : device_(device), mesh_(mesh), scan_(scan),
      locate_(device.kernel(kFile, "locate_points", kPhase)),
      mark_(device.kernel(kFile, "mark_containers", kPhase)),
      select_(device.kernel(kFile, "select_winners", kPhase)),
      clear_marks_(device.kernel(kFile, "clear_container_marks", kPhase)),
      split_(device.kernel(kFile, "split_triangles", kPhase)),
      relink_(device.kernel(kFile, "relink_split_children", kPhase)),
      count_remaining_(device.kernel(kFile, "count_remaining", kPhase)),
      round_in_group_(device.kernel(kFile, "insert_round_in_group", kPhase)),
      start_at_anchors_(device.kernel(kFile, "start_at_anchors", kPhase)),
      remaining_(point_list(device, mesh, pool, kRemaining)),
      remaining_next_(point_list(device, mesh, pool, kRemainingNext)),
      status_(point_list(device, mesh, pool, kStatus)),
      winner_(point_list(device, mesh, pool, kWinner)),
      offset_(point_list(device, mesh, pool, kOffset)),
      keep_(point_list(device, mesh, pool, kKeep)), changed_(device, mesh.list_capacity),
      counters_(device, kCounters), pooled_(pool != nullptr) {
  counters_.fill(device_, 0, kCounters);
  group_ = device.single_group(round_in_group_, kPhase);
}

void MissingPointInsertion::set_points(const std::vector<cl_int> &points) {
  remaining_.upload(device_, points);
  pending_ = points.size();
}

void MissingPointInsertion::set_points_near(const std::vector<cl_int> &points,
                                            const std::vector<cl_int> &anchors) {
  if (pending_ > 0)
    throw InternalError("missing-point insertion: a level set while points are pending");
  set_points(points);
  keep_.upload(device_, anchors); // free between rounds
  set_args(start_at_anchors_, remaining_.buffer(), keep_.buffer(), mesh_.location.buffer(),
           static_cast<cl_int>(pending_));
  launch(device_, start_at_anchors_, pending_, kPhase);
  // Their start triangles may be as old as any: every point walks.
  located_since_ = 0;
}

void MissingPointInsertion::set_points(const DeviceArray<cl_int> &points, std::size_t count) {
  if (count > 0)
    guarded(kPhase, "copying the point list", [&] {
      device_.queue().enqueueCopyBuffer(points.buffer(), remaining_.buffer(), 0, 0,
                                        count * sizeof(cl_int));
    });
  pending_ = count;
}

void MissingPointInsertion::trim_lists() {
  changed_.discard(device_, 4 * round_points_, kPhase); // 4 entries per insertion
  if (!pooled_)                                         // else the pool's owner trims them
    for (const DeviceArray<cl_int> *list :
         {&remaining_, &remaining_next_, &status_, &winner_, &offset_, &keep_})
      list->discard(device_, round_points_, kPhase);
}

std::size_t MissingPointInsertion::run_round(int stamp, bool walk) {
  const auto n = static_cast<cl_int>(pending_);
  // The bits of the point numbers (the ties of insertion_priority).
  cl_int index_bits = 1;
  while (index_bits < 32 && (std::size_t{1} << index_bits) < mesh_.point_capacity)
    ++index_bits;
  if (n == 0)
    return 0;
  round_points_ = pending_;
  // Any walk in a Delaunay triangulation visits each triangle at most once.
  const auto max_steps = static_cast<cl_int>(mesh_.triangle_count + 8);
  if (walk) {
    set_args_from(locate_, mesh_.bind_triangulation(locate_, 0),
                  static_cast<cl_int>(located_since_), remaining_.buffer(), status_.buffer(),
                  max_steps, n);
    launch(device_, locate_, pending_, kPhase);
    located_since_ = stamp; // this round's changes and later ones move points
  }
  // The new triangles' slots: the free ones first, then from first_slot on.
  const auto first_slot = static_cast<cl_int>(mesh_.triangle_count);
  DeviceMesh::FreeList &free = mesh_.free_triangles;
  const auto free_first = static_cast<cl_int>(free.first),
             free_count = static_cast<cl_int>(free.count);
  const cl::Buffer &free_list = free.slots.size() ? free.slots.buffer() : mesh_.tri_mark.buffer();
  // Without a walk mark_containers sets every status to pending.
  std::array<cl_int, kCounters> counters{};
  std::size_t winners = 0;
  if (pending_ <= kInGroup && mesh_.triangle_count + 2 * pending_ <= mesh_.triangle_capacity &&
      4 * pending_ <= mesh_.list_capacity) {
    // Room for every point to win: the whole round in one launch.
    mesh_.fill_triangle_slots(device_, mesh_.triangle_count + 2 * pending_);
    set_args_from(round_in_group_, mesh_.bind_triangulation(round_in_group_, 0),
                  remaining_.buffer(), status_.buffer(), winner_.buffer(), offset_.buffer(),
                  keep_.buffer(), counters_.buffer(), cl::Local(sizeof(cl_int) * group_),
                  static_cast<cl_int>(!walk), index_bits, changed_.buffer(),
                  static_cast<cl_int>(stamp), free_list, free_first, free_count, first_slot, n);
    launch(device_, round_in_group_, group_, kPhase, group_);
    const std::vector<cl_int> read = counters_.download(device_, kCounters);
    std::copy(read.begin(), read.end(), counters.begin());
    winners = static_cast<std::size_t>(counters[2]);
    mesh_.triangle_count += free.take(2 * winners);
  } else {
    set_args_from(mark_, mesh_.bind_triangulation(mark_, 0), remaining_.buffer(), status_.buffer(),
                  static_cast<cl_int>(!walk), index_bits, n);
    launch(device_, mark_, pending_, kPhase);
    set_args_from(select_, mesh_.bind_triangulation(select_, 0), remaining_.buffer(),
                  status_.buffer(), winner_.buffer(), index_bits, n);
    launch(device_, select_, pending_, kPhase);
    set_args_from(clear_marks_, mesh_.bind_triangulation(clear_marks_, 0), remaining_.buffer(),
                  status_.buffer(), n);
    launch(device_, clear_marks_, pending_, kPhase);
    set_args(count_remaining_, status_.buffer(), winner_.buffer(), keep_.buffer(),
             counters_.buffer(), n);
    launch(device_, count_remaining_, pending_, kPhase);
    // The counters come back with the winners' total: one wait.
    counters_.download_later(device_, counters.data(), 2);
    winners = static_cast<std::size_t>(scan_.exclusive_scan(winner_, offset_, pending_, kPhase));
    const std::size_t new_slots = free.take(2 * winners);
    if (mesh_.triangle_count + new_slots > mesh_.triangle_capacity ||
        4 * winners > mesh_.list_capacity)
      throw InternalError("missing-point insertion: triangle slots exhausted");
    mesh_.fill_triangle_slots(device_, mesh_.triangle_count + new_slots);
    set_args_from(split_, mesh_.bind_triangulation(split_, 0), remaining_.buffer(),
                  winner_.buffer(), offset_.buffer(), changed_.buffer(), static_cast<cl_int>(stamp),
                  free_list, free_first, free_count, first_slot, n);
    launch(device_, split_, pending_, kPhase);
    mesh_.triangle_count += new_slots;
    set_args_from(relink_, mesh_.bind_triangulation(relink_, 0), changed_.buffer(),
                  static_cast<cl_int>(stamp), static_cast<cl_int>(4 * winners));
    launch(device_, relink_, 4 * winners, kPhase);
  }
  if (counters[0] != 0)
    throw InternalError("missing-point insertion: a point location walk did not end");
  // The points still waiting: the running total less the last one (modulo
  // 2^32, as the device's counter wraps).
  const auto kept = static_cast<std::size_t>(static_cast<cl_uint>(counters[1]) - waiting_total_);
  waiting_total_ = static_cast<cl_uint>(counters[1]);

  if (kept > 0) { // after split_triangles, the last reader of offset_
    scan_.compact(remaining_, keep_, offset_, remaining_next_, pending_, kPhase);
    std::swap(remaining_, remaining_next_);
  }
  duplicates_ += pending_ - kept - winners;
  pending_ = kept;
  return winners;
}

} // namespace clmesh
