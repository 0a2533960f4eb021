#include "refine/offcenter_insertion.hpp"

#include "election.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace clmesh {

namespace {
const char *kFile = "offcenter_insertion.cl";
} // namespace

std::vector<std::size_t> OffcenterInsertion::scratch_lists(const DeviceMesh &mesh) {
  const std::size_t slots = mesh.triangle_capacity;
  // In the order of List.
  std::vector<std::size_t> bytes{slots * sizeof(cl_double2), slots * sizeof(cl_double)};
  bytes.resize(kPriority + 1, slots * sizeof(cl_int));
  return bytes;
}

OffcenterInsertion::OffcenterInsertion(
    Device &device, DeviceMesh &mesh, const ScratchPool &pool, TriangleClaims &tie_marks,
    double min_angle, double max_area, int filter_rings, int filter_distance_rings,
    double filter_near, bool parallel_midpoints, int election_rings, bool carry_verdicts,
    std::size_t group_step_limit, bool conforming, int protected_segments, bool inward,
    const std::vector<double> &region_areas, const DeviceArray<cl_double> *size_bound)
    : device_(device), mesh_(mesh), max_area_(max_area), filter_rings_(filter_rings),
      filter_distance_rings_(filter_distance_rings),
      filter_near2_(filter_near > 0 ? filter_near * filter_near : INFINITY),
      parallel_midpoints_(parallel_midpoints), election_rings_(election_rings),
      carry_verdicts_(carry_verdicts), group_step_limit_(group_step_limit), conforming_(conforming),
      protected_segments_(protected_segments), inward_(inward),
      flag_hull_(device.kernel(kFile, "flag_hull_vertices", kPhase)),
      count_unfixable_(device.kernel(kFile, "count_unfixable_triangles", kPhase)),
      flag_unsettled_(device.kernel(kFile, "flag_unsettled", kPhase)),
      find_bad_(device.kernel(kFile, "find_bad_triangles", kPhase)),
      gather_bad_(device.kernel(kFile, "gather_bad_triangles", kPhase)),
      elect_(device.kernel(kFile, "elect_candidates", kPhase)),
      settle_elected_(device.kernel(kFile, "settle_elected", kPhase)),
      retire_blocked_(device.kernel(kFile, "retire_blocked", kPhase)),
      elect_again_(device.kernel(kFile, "elect_again", kPhase)),
      gather_elected_(device.kernel(kFile, "gather_elected", kPhase)),
      locate_(device.kernel(kFile, "locate_candidates", kPhase)),
      mark_(device.kernel(kFile, "mark_candidate_containers", kPhase)),
      ties_(device.kernel(kFile, "mark_candidate_ties", kPhase)),
      filter_(device.kernel(kFile, "insertion_filter", kPhase)),
      clear_(device.kernel(kFile, "clear_candidate_marks", kPhase)),
      append_(device.kernel(kFile, "append_survivors", kPhase)),
      step_one_in_group_(device.kernel(kFile, "step_one_in_group", kPhase)),
      place_in_group_(device.kernel(kFile, "place_candidates_in_group", kPhase)),
      candidate_(pool.list<cl_double2>(kCandidate)), bad_list_(device, mesh.triangle_capacity),
      bad_mark_(device, election_rings > 0 ? mesh.triangle_capacity : 1),
      origin_(pool.list<cl_int>(kOrigin)), container_(pool.list<cl_int>(kContainer)),
      split_edge_(pool.list<cl_int>(kSplitEdge)), survive_(pool.list<cl_int>(kSurvive)),
      keep_(pool.list<cl_int>(kKeep)), offset_(pool.list<cl_int>(kOffset)), tie_mark_(tie_marks),
      listed_(pool.list<cl_int>(kListed)), priority_(pool.list<cl_uint>(kPriority)),
      last_container_(device, mesh.triangle_capacity), radius2_(pool.list<cl_double>(kRadius2)),
      stuck_count_(device, 1), notes_(device, mesh.triangle_capacity),
      region_area_(device, region_areas.size()), size_bound_(size_bound), search_counts_(device, 5),
      pooled_keep_(pool.list<cl_int>(kCandidate)), pooled_offset_(pool.list<cl_int>(kRadius2)),
      search_group_(device.single_group(step_one_in_group_, kPhase)), place_counts_(device, 2),
      place_group_(device.single_group(place_in_group_, kPhase)) {
  std::vector<cl_double> areas(region_areas.begin(), region_areas.end());
  region_area_.upload(device_, areas);
  // The election's second round takes triangles bad by their area alone:
  // without an area bound of any kind there are none.
  second_round_ = max_area_ > 0 || size_bound_ != nullptr ||
                  std::any_of(areas.begin(), areas.end(), [](double a) { return a > 0; });
  stuck_count_.fill(device_, 0, 1);
  const double pi = 3.14159265358979323846, angle = min_angle * pi / 180;
  cos_bound_ = std::cos(angle);
  // R / l > 1 / (2 sin(angle)) exactly when the smallest angle is below `angle`.
  ratio_bound_squared_ = min_angle > 0 ? 1.0 / (4 * std::sin(angle) * std::sin(angle)) : 0.0;
  // Triangle's diametral lens: a hull edge is encroached by a point that sees
  // it at an angle whose cosine is at most -cos(2 angle).
  // With -D, the diametral circle (every point that sees it at an obtuse
  // angle).
  lens_ = conforming ? 0.0 : std::cos(2 * angle) * std::cos(2 * angle);
  // Üngör's off-center distance, as Triangle computes it.
  offconstant_ =
      min_angle > 0 ? 0.475 * std::sqrt((1 + std::cos(angle)) / (1 - std::cos(angle))) : 1e300;
}

void OffcenterInsertion::fill_new_slots() {
  const std::size_t slots = mesh_.triangle_count;
  if (slots <= filled_slots_)
    return;
  const std::size_t first = filled_slots_,
                    count = fill_ahead(slots, mesh_.triangle_capacity) - first;
  tie_mark_.cover(slots, kPhase);
  last_container_.fill_range(device_, -1, first, count, kPhase);
  notes_.fill_range(device_, 0, first, count, kPhase);
  filled_slots_ = first + count;
}

std::size_t OffcenterInsertion::flag_hull_vertices() {
  fill_new_slots();
  const std::size_t slots = mesh_.triangle_count;
  DeviceArray<cl_int> flagged(device_, 1);
  flagged.fill(device_, 0, 1);
  set_args_from(flag_hull_, mesh_.bind(flag_hull_, 0),
                static_cast<cl_int>(ratio_bound_squared_ > 0), cos_bound_, flagged.buffer(),
                static_cast<cl_int>(slots));
  launch(device_, flag_hull_, slots, kPhase);
  return static_cast<std::size_t>(flagged.read(device_, 0));
}

std::size_t OffcenterInsertion::count_unfixable() {
  fill_new_slots();
  const std::size_t slots = mesh_.triangle_count;
  DeviceArray<cl_int> count(device_, 1);
  count.fill(device_, 0, 1);
  set_args_from(count_unfixable_, mesh_.bind(count_unfixable_, 0), ratio_bound_squared_, max_area_,
                region_area_.buffer(), size_bound_buffer(),
                static_cast<cl_int>(size_bound_ != nullptr), offconstant_,
                static_cast<cl_int>(conforming_), static_cast<cl_int>(protected_segments_),
                static_cast<cl_int>(inward_), notes_.buffer(), located_stamp_, count.buffer(),
                static_cast<cl_int>(slots));
  launch(device_, count_unfixable_, slots, kPhase);
  return static_cast<std::size_t>(count.read(device_, 0));
}

std::size_t OffcenterInsertion::find_bad_triangles(PrefixScan &scan,
                                                   const DeviceList<cl_int> *changed, int stamp,
                                                   std::size_t room,
                                                   const DeviceArray<cl_int> *new_points) {
  fill_new_slots();
  // The first search sweeps every slot; the later ones only the last bad
  // triangles and the changed ones, without duplicates: the last bad ones
  // first, in their order (each slot at its first place), carried.
  const bool use_list = searched_ && changed != nullptr;
  const auto carried = static_cast<cl_int>(use_list && carry_verdicts_ ? bad_ : 0);
  const std::size_t listed = use_list ? bad_ + changed->size : 0;
  elected_ = false;
  placed_ = false;
  // A short search (group_step_limit_ entries at most, before duplicates
  // go) runs whole in one launch by one work-group, with the placement when
  // it can (step_one_in_group): on a small mesh the thirteen launches and
  // four reads of the kernels' way cost more than their work.
  if ((use_list ? listed : mesh_.triangle_count) <= group_step_limit_ &&
      listed <= std::min(pooled_keep_.size(), pooled_offset_.size()))
    return step_one_in_group(use_list ? changed : nullptr, carried, stamp, room, new_points);
  std::size_t entries = mesh_.triangle_count;
  if (use_list) {
    search_.size = 0;
    search_.append(device_, bad_list_, bad_);
    if (changed->size > 0)
      search_.append(device_, changed->items, changed->size);
    // The scan's scratch: two lists of the pool that hold candidates only
    // later, when they are long enough (they nearly always are), else lists
    // of its own.
    const bool pooled = search_.size <= std::min(pooled_keep_.size(), pooled_offset_.size());
    if (!pooled && search_keep_.size() < search_.size) {
      search_keep_ = DeviceArray<cl_int>(device_, search_.items.size());
      search_offset_ = DeviceArray<cl_int>(device_, search_.items.size());
    }
    entries = static_cast<std::size_t>(scan.unique(
        search_.items, search_.size, mesh_.tri_mark, pooled ? pooled_keep_ : search_keep_,
        pooled ? pooled_offset_ : search_offset_, listed_, kPhase));
    // The pages past this search's entries go back to the system (the next
    // search, of about the same size, writes those it keeps again).
    for (const DeviceArray<cl_int> *list : {&search_.items, &search_keep_, &search_offset_})
      list->discard(device_, search_.size, kPhase);
  }
  searched_ = true;
  searched_entries_ = entries;
  const auto items = static_cast<cl_int>(entries);
  const auto election = static_cast<cl_int>(election_rings_ > 0);
  set_args_from(find_bad_, search_args(find_bad_, use_list, carried), items);
  launch(device_, find_bad_, entries, kPhase);
  searched_stamp_ = stamp;
  bad_ = static_cast<std::size_t>(scan.exclusive_scan(keep_, offset_, entries, kPhase));
  candidates_ = 0;
  if (bad_ == 0)
    return 0;
  set_args(gather_bad_, keep_.buffer(), offset_.buffer(), listed_.buffer(),
           static_cast<cl_int>(use_list), mesh_.tri_mark.buffer(), election, bad_list_.buffer(),
           bad_mark_.buffer(), items);
  launch(device_, gather_bad_, entries, kPhase);
  return bad_;
}

void OffcenterInsertion::flag_unsettled(const DeviceList<cl_int> &changed,
                                        const DeviceArray<cl_int> &flags) {
  // A location sets a stuck bit and counts it in stuck_count_: with none
  // counted, no note holds one and the notes need no reading.
  const bool any_stuck = stuck_count_.read(device_, 0) > 0;
  const std::size_t noted = any_stuck ? std::min(filled_slots_, mesh_.triangle_count) : 0;
  const std::size_t n = std::max({bad_, changed.size, noted});
  set_args(flag_unsettled_, bad_list_.buffer(), static_cast<cl_int>(bad_),
           changed.size > 0 ? changed.items.buffer() : bad_list_.buffer(),
           static_cast<cl_int>(changed.size), notes_.buffer(), static_cast<cl_int>(noted),
           flags.buffer(), static_cast<cl_int>(n));
  launch(device_, flag_unsettled_, n, kPhase);
}

cl_uint OffcenterInsertion::search_args(cl::Kernel &kernel, bool use_list, cl_int carried) {
  return set_args_from(kernel, mesh_.bind(kernel, 0), listed_.buffer(),
                       static_cast<cl_int>(use_list), carried, searched_stamp_, bad_mark_.buffer(),
                       ratio_bound_squared_, max_area_, region_area_.buffer(), size_bound_buffer(),
                       static_cast<cl_int>(size_bound_ != nullptr), offconstant_,
                       static_cast<cl_int>(conforming_), static_cast<cl_int>(protected_segments_),
                       static_cast<cl_int>(inward_), located_stamp_, keep_.buffer(),
                       static_cast<cl_int>(election_rings_ > 0), lens_, notes_.buffer());
}

std::size_t OffcenterInsertion::step_one_in_group(const DeviceList<cl_int> *changed, cl_int carried,
                                                  int stamp, std::size_t room,
                                                  const DeviceArray<cl_int> *new_points) {
  const std::size_t last_bad = changed ? bad_ : 0, changed_count = changed ? changed->size : 0;
  search_.size = 0;
  search_.reserve(device_, std::max<std::size_t>(last_bad + changed_count, 1));
  const cl::Buffer &changed_list = changed_count > 0 ? changed->items.buffer() : keep_.buffer();
  // The candidates are at most the entries: room for that many points.
  const std::size_t entries_bound = changed ? last_bad + changed_count : mesh_.triangle_count;
  const Slots slots = point_slots_for(new_points ? std::min(entries_bound, room) : 0);
  const cl_int place_room = new_points ? clamped(room) : -1;
  set_args_from(step_one_in_group_, search_args(step_one_in_group_, changed != nullptr, carried),
                bad_list_.buffer(), static_cast<cl_int>(last_bad), changed_list,
                static_cast<cl_int>(changed_count), search_.items.buffer(), pooled_keep_.buffer(),
                pooled_offset_.buffer(), offset_.buffer(), static_cast<cl_int>(election_rings_),
                static_cast<cl_int>(second_round_), last_container_.buffer(), origin_.buffer(),
                cl::Local(sizeof(cl_int) * search_group_), search_counts_.buffer(),
                static_cast<cl_int>(mesh_.triangle_count), candidate_.buffer(), container_.buffer(),
                split_edge_.buffer(), priority_.buffer(), radius2_.buffer(),
                static_cast<cl_int>(stamp), stuck_count_.buffer(),
                static_cast<cl_int>(mesh_.triangle_count + 8), tie_mark_.buffer(),
                static_cast<cl_int>(filter_rings_), static_cast<cl_int>(filter_distance_rings_),
                filter_near2_, static_cast<cl_int>(parallel_midpoints_), survive_.buffer(),
                slots.free_list, slots.free_first, slots.free_count, slots.first_new,
                new_points ? new_points->buffer() : offset_.buffer(), place_room, place_room);
  launch(device_, step_one_in_group_, search_group_, kPhase, search_group_);
  const std::vector<cl_int> counts = search_counts_.download(device_, 5);
  searched_ = true;
  searched_stamp_ = stamp;
  searched_entries_ = static_cast<std::size_t>(counts[0]);
  bad_ = static_cast<std::size_t>(counts[1]);
  candidates_ = static_cast<std::size_t>(counts[2]);
  elected_ = true;
  // The pages past this search's entries go back to the system, as in the
  // kernels' way.
  if (changed)
    search_.items.discard(device_, last_bad + changed_count, kPhase);
  if (bad_ > 0 && static_cast<cl_int>(candidates_) <= place_room) {
    placed_ = true;
    appended_ = take_point_slots(&counts[3], room, stamp);
  }
  return bad_;
}

cl_int OffcenterInsertion::clamped(std::size_t count) {
  return static_cast<cl_int>(std::min<std::size_t>(count, INT32_MAX));
}

OffcenterInsertion::Slots OffcenterInsertion::point_slots_for(std::size_t most) {
  // The slots of the most points that can be appended are filled ahead (with
  // the values they would get when used); the host takes the free ones after
  // the read (take_point_slots), as append_survivors does before its launch.
  DeviceMesh::FreeList &free = mesh_.free_points;
  mesh_.fill_point_slots(device_, mesh_.point_count + most - std::min(most, free.count));
  return Slots{free.slots.size() ? free.slots.buffer() : offset_.buffer(),
               static_cast<cl_int>(free.first), static_cast<cl_int>(free.count),
               static_cast<cl_int>(mesh_.point_count)};
}

std::size_t OffcenterInsertion::take_point_slots(const cl_int *counts, std::size_t room,
                                                 int stamp) {
  located_stamp_ = stamp;
  stuck_total_ = static_cast<std::size_t>(counts[1]);
  stuck_known_ = true;
  const std::size_t count = std::min(static_cast<std::size_t>(counts[0]), room);
  mesh_.point_count += mesh_.free_points.take(count);
  return count;
}

std::size_t OffcenterInsertion::elect_candidates(PrefixScan &scan) {
  if (elected_)
    return candidates_; // by step_one_in_group
  candidates_ = bad_;
  if (bad_ == 0 || election_rings_ == 0)
    return candidates_;
  const auto bad = static_cast<cl_int>(bad_);
  set_args(elect_, bad_list_.buffer(), mesh_.tri_neighbor.buffer(), mesh_.tri_mark.buffer(),
           static_cast<cl_int>(election_rings_), notes_.buffer(), keep_.buffer(), bad);
  launch(device_, elect_, bad_, kPhase);
  candidates_ = static_cast<std::size_t>(scan.exclusive_scan(keep_, offset_, bad_, kPhase));
  if (second_round_ && CLM_SECOND_ROUND_SHARE * candidates_ < bad_) { // cl/election.h
    set_args(settle_elected_, bad_list_.buffer(), keep_.buffer(), mesh_.tri_mark.buffer(), bad);
    launch(device_, settle_elected_, bad_, kPhase);
    const auto rings = static_cast<cl_int>(election_rings_);
    set_args(retire_blocked_, bad_list_.buffer(), mesh_.tri_neighbor.buffer(),
             mesh_.tri_mark.buffer(), rings, notes_.buffer(), keep_.buffer(), bad);
    launch(device_, retire_blocked_, bad_, kPhase);
    set_args(elect_again_, bad_list_.buffer(), mesh_.tri_neighbor.buffer(), mesh_.tri_mark.buffer(),
             rings, notes_.buffer(), keep_.buffer(), bad);
    launch(device_, elect_again_, bad_, kPhase);
    candidates_ = static_cast<std::size_t>(scan.exclusive_scan(keep_, offset_, bad_, kPhase));
  }
  set_args(gather_elected_, bad_list_.buffer(), keep_.buffer(), offset_.buffer(),
           mesh_.tri_mark.buffer(), last_container_.buffer(), origin_.buffer(), bad);
  launch(device_, gather_elected_, bad_, kPhase);
  return candidates_;
}

std::size_t OffcenterInsertion::place_candidates(int stamp, std::size_t room, PrefixScan &scan,
                                                 const DeviceArray<cl_int> &new_points) {
  if (placed_) {
    placed_ = false;
    return appended_; // by step_one_in_group
  }
  if (candidates_ == 0)
    return 0;
  // A short placement (group_step_limit_ candidates at most) runs whole in
  // one launch by one work-group (place_candidates_in_group): six launches and a read
  // become one launch and its read.
  if (candidates_ > group_step_limit_) {
    locate_candidates(stamp);
    filter_candidates();
    return append_survivors(room, scan, new_points);
  }
  const Slots slots = point_slots_for(std::min(candidates_, room));
  set_args_from(place_in_group_, locate_args(place_in_group_, stamp), tie_mark_.buffer(),
                static_cast<cl_int>(filter_rings_), static_cast<cl_int>(filter_distance_rings_),
                filter_near2_, static_cast<cl_int>(parallel_midpoints_), survive_.buffer(),
                offset_.buffer(), slots.free_list, slots.free_first, slots.free_count,
                slots.first_new, new_points.buffer(), clamped(room),
                cl::Local(sizeof(cl_int) * place_group_), place_counts_.buffer(),
                static_cast<cl_int>(candidates_));
  launch(device_, place_in_group_, place_group_, kPhase, place_group_);
  const std::vector<cl_int> counts = place_counts_.download(device_, 2);
  return take_point_slots(counts.data(), room, stamp);
}

cl_uint OffcenterInsertion::locate_args(cl::Kernel &kernel, int stamp) {
  // Each candidate's bad triangle: the elected ones, or every bad one.
  const DeviceArray<cl_int> &origin = election_rings_ > 0 ? origin_ : bad_list_;
  return set_args_from(kernel, mesh_.bind(kernel, 0), last_container_.buffer(), located_stamp_,
                       ratio_bound_squared_, max_area_, region_area_.buffer(), size_bound_buffer(),
                       static_cast<cl_int>(size_bound_ != nullptr), offconstant_,
                       static_cast<cl_int>(conforming_), static_cast<cl_int>(protected_segments_),
                       candidate_.buffer(), container_.buffer(), split_edge_.buffer(),
                       origin.buffer(), priority_.buffer(), radius2_.buffer(), lens_,
                       static_cast<cl_int>(inward_), static_cast<cl_int>(stamp), notes_.buffer(),
                       stuck_count_.buffer(), static_cast<cl_int>(mesh_.triangle_count + 8));
}

void OffcenterInsertion::locate_candidates(int stamp) {
  set_args_from(locate_, locate_args(locate_, stamp), static_cast<cl_int>(candidates_));
  launch(device_, locate_, candidates_, kPhase);
  located_stamp_ = stamp;
  stuck_known_ = false;
}

bool OffcenterInsertion::stuck_since_last_asked() {
  const std::size_t total =
      stuck_known_ ? stuck_total_ : static_cast<std::size_t>(stuck_count_.read(device_, 0));
  const bool more = total > stuck_seen_;
  stuck_seen_ = total;
  return more;
}

void OffcenterInsertion::filter_candidates() {
  const auto n = static_cast<cl_int>(candidates_);
  set_args(mark_, container_.buffer(), split_edge_.buffer(), mesh_.tri_neighbor.buffer(),
           priority_.buffer(), mesh_.tri_mark.buffer(), n);
  launch(device_, mark_, candidates_, kPhase);
  set_args(ties_, container_.buffer(), split_edge_.buffer(), mesh_.tri_neighbor.buffer(),
           priority_.buffer(), mesh_.tri_mark.buffer(), tie_mark_.buffer(), n);
  launch(device_, ties_, candidates_, kPhase);
  set_args_from(filter_, mesh_.bind(filter_, 0), container_.buffer(), split_edge_.buffer(),
                priority_.buffer(), tie_mark_.buffer(), candidate_.buffer(), radius2_.buffer(),
                static_cast<cl_int>(filter_rings_), static_cast<cl_int>(filter_distance_rings_),
                filter_near2_, static_cast<cl_int>(parallel_midpoints_), survive_.buffer(), n);
  launch(device_, filter_, candidates_, kPhase);
}

void OffcenterInsertion::clear_candidate_marks() {
  set_args(clear_, container_.buffer(), split_edge_.buffer(), mesh_.tri_neighbor.buffer(),
           mesh_.tri_mark.buffer(), tie_mark_.buffer(), static_cast<cl_int>(candidates_));
  launch(device_, clear_, candidates_, kPhase);
}

std::size_t OffcenterInsertion::append_survivors(std::size_t room, PrefixScan &scan,
                                                 const DeviceArray<cl_int> &new_points) {
  if (candidates_ == 0)
    return 0;
  const auto n = static_cast<cl_int>(candidates_);
  const auto survivors =
      static_cast<std::size_t>(scan.exclusive_scan(survive_, offset_, candidates_, kPhase));
  const std::size_t count = std::min(survivors, room); // the first ones when there is less room
  if (count == 0) {
    clear_candidate_marks(); // else append_survivors clears them
    return 0;
  }
  DeviceMesh::FreeList &free = mesh_.free_points;
  const auto free_first = static_cast<cl_int>(free.first),
             free_count = static_cast<cl_int>(free.count);
  const std::size_t new_slots = free.take(count);
  mesh_.fill_point_slots(device_, mesh_.point_count + new_slots);
  const cl::Buffer &free_list = free.slots.size() ? free.slots.buffer() : offset_.buffer();
  set_args_from(append_, mesh_.bind(append_, 0), candidate_.buffer(), container_.buffer(),
                split_edge_.buffer(), radius2_.buffer(), priority_.buffer(), survive_.buffer(),
                offset_.buffer(), free_list, free_first, free_count,
                static_cast<cl_int>(mesh_.point_count), new_points.buffer(), tie_mark_.buffer(),
                static_cast<cl_int>(count), n);
  launch(device_, append_, candidates_, kPhase);
  mesh_.point_count += new_slots;
  return count;
}

} // namespace clmesh
