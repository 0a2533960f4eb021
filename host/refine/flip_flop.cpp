#include "refine/flip_flop.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <utility>

namespace clmesh {

namespace {
const char *kFile = "flip_flop.cl";
// A pass deletes a redundant point or flips. A run may need a pass per
// triangle of a fan: a far vertex joined to a dense run of points split on a
// segment, where each Delaunay flip unsettles the next triangle of the fan
// (domains with parts a hair wide, refined toward the memory limit). Far
// more passes than that means a bug, reported instead of a hang.
long max_passes(std::size_t triangles) { return 100000 + 16 * static_cast<long>(triangles); }
} // namespace

std::vector<std::size_t> FlipFlop::scratch_lists(const DeviceMesh &mesh) {
  // The next list holds the pass's results and the redundant stars before
  // duplicates are dropped; an active list has distinct live triangles.
  const std::size_t list = mesh.list_capacity * sizeof(cl_int),
                    point = mesh.point_capacity * sizeof(cl_int);
  // In the order of List.
  return {4 * list, 2 * list, 2 * list, 2 * list, 2 * list, list,
          list,     list,     list,     point,    point,    point};
}

FlipFlop::FlipFlop(Device &device, DeviceMesh &mesh, PrefixScan &scan, const ScratchPool &pool,
                   TriangleClaims &removal_claims, bool orthogonal_test,
                   std::size_t group_pass_limit)
    : device_(device), mesh_(mesh), scan_(scan), encroachment_(device, mesh, scan),
      orthogonal_test_(orthogonal_test ? 1 : 0), group_pass_limit_(group_pass_limit),
      propose_(device.kernel(kFile, "flipflop_propose", kPhase)),
      propose_exact_(device.kernel(kFile, "flipflop_propose_exact", kPhase)),
      apply_(device.kernel(kFile, "flipflop_apply", kPhase)),
      relink_(device.kernel(kFile, "flipflop_relink", kPhase)),
      gather_next_(device.kernel(kFile, "flipflop_gather_next", kPhase)),
      track_(device.kernel(kFile, "track_redundant_points", kPhase)),
      emit_(device.kernel(kFile, "emit_redundant_stars", kPhase)),
      finish_(device.kernel(kFile, "finish_iteration", kPhase)),
      keep_stuck_(device.kernel(kFile, "keep_stuck_points", kPhase)),
      passes_in_group_(device.kernel(kFile, "flipflop_passes_in_group", kPhase)),
      log_deleted_(device.kernel(kFile, "log_deleted_points", kPhase)),
      active_(pool.list<cl_int>(kActive)), next_active_(pool.list<cl_int>(kNextActive)),
      exact_list_(pool.list<cl_int>(kExactList)), operation_(pool.list<cl_int>(kOperation)),
      proposal_(pool.list<cl_int>(kProposal)), star_(pool.list<cl_int>(kStar)),
      applied_(pool.list<cl_int>(kApplied)), count_(pool.list<cl_int>(kCount)),
      offset_(pool.list<cl_int>(kOffset)), redundant_mark_(device, mesh.point_capacity),
      redundant_anchor_(device, mesh.point_capacity), star_size_(pool.list<cl_int>(kStarSize)),
      star_offset_(pool.list<cl_int>(kStarOffset)), tracked_(pool.list<cl_int>(kTracked)),
      marked_count_(device, 1), exact_count_(device, 1), logged_(device, 1),
      pass_result_(device, kGroupResults), totals_(device, kTotals),
      removal_claim_(removal_claims) {
  pass_group_ = device.single_group(passes_in_group_, kPhase);
  // Running totals, never reset: each iteration takes the difference.
  totals_.fill(device_, 0, kTotals);
}

void FlipFlop::run(const DeviceArray<cl_int> &changed, std::size_t n,
                   const DeviceArray<cl_int> &new_points, std::size_t m, int &stamp,
                   DeviceList<cl_int> &rewritten, DeletionLog &deleted, FlipFlopCounts &counts) {
  if (n > mesh_.list_capacity)
    throw InternalError("flip-flop: the active list is longer than its arrays");
  if (n > 0)
    guarded(kPhase, "copying the active list", [&] {
      device_.queue().enqueueCopyBuffer(changed.buffer(), active_.buffer(), 0, 0,
                                        n * sizeof(cl_int));
    });
  removal_claim_.cover(mesh_.triangle_count, kPhase); // the slots that came since: unclaimed
  if (mesh_.point_count > marks_filled_) {            // the points that came since: not marked
    const std::size_t end = fill_ahead(mesh_.point_count, mesh_.point_capacity);
    redundant_mark_.fill_range(device_, 0, marks_filled_, end - marks_filled_, kPhase);
    marks_filled_ = end;
  }
  // The points to follow: this iteration's, then the old ones that encroach
  // a hull edge split in this iteration (thesis §3.4.1).
  // With few new points the old ones' count stays on the device for the
  // passes in group to read (tracked_known_ false until they bring it back).
  const std::optional<std::size_t> old =
      encroachment_.mark_encroaching(new_points, m, redundant_mark_, redundant_anchor_, tracked_);
  tracked_known_ = old.has_value();
  tracked_n_ = m + old.value_or(0);
  redundant_left_ = true; // marks of the boundary routine: tracked in the first pass
  run_entries_ = std::max(n, tracked_n_);
  finished_in_group_ = false;
  const long pass_limit = max_passes(mesh_.triangle_count);
  for (long pass = 0; n > 0;) {
    if (pass >= pass_limit)
      throw InternalError("flip-flop did not converge in " + std::to_string(pass_limit) +
                          " passes");
    if (n <= group_pass_limit_ && tracked_n_ <= kTrackedInGroup) {
      n = passes_in_group(n, pass, stamp, new_points, m, rewritten, counts);
      continue;
    }
    know_tracked(m);
    const auto pass_stamp = static_cast<cl_int>(stamp++);
    const auto any_redundant = static_cast<cl_int>(redundant_left_ && pass > 0);
    const PassResult result = pass_by_kernels(n, any_redundant, pass_stamp, rewritten, counts);
    run_entries_ = std::max({run_entries_, result.next, result.length});
    ++counts.passes;
    ++pass;
    if (result.looked_for_stars) {
      redundant_left_ = result.stars > 0;
      n = result.length;
      if (n > mesh_.list_capacity)
        throw InternalError("flip-flop: the active list is longer than its arrays");
      if (result.next == 0 && result.marked == 0 && redundant_left_) {
        // Stalled: what is left cannot be deleted. Their stars are listed.
        set_args(keep_stuck_, tracked_.buffer(), mesh_.point_state.buffer(), totals_.buffer(),
                 static_cast<cl_int>(tracked_n_));
        launch(device_, keep_stuck_, tracked_n_, kPhase);
        redundant_left_ = false;
      }
    } else {
      std::swap(active_, next_active_);
      n = result.next;
    }
  }
  know_tracked(m);
  // The iteration's counts, read at once (with the last passes' result
  // when they ended the run): the running totals less the last ones
  // (modulo 2^32, as the device's counters wrap).
  std::vector<cl_int> totals(group_totals_.begin(), group_totals_.end());
  if (!finished_in_group_) {
    if (m > 0) {
      set_args(finish_, new_points.buffer(), mesh_.point_state.buffer(), totals_.buffer(),
               static_cast<cl_int>(m));
      launch(device_, finish_, m, kPhase);
    }
    totals = totals_.download(device_, kTotals);
  }
  const cl_int failures = totals[kFailures];
  std::array<cl_int, kFailures> since{};
  for (std::size_t k = 0; k < kFailures; ++k) {
    since[k] = static_cast<cl_int>(static_cast<cl_uint>(totals[k]) -
                                   static_cast<cl_uint>(last_totals_[k]));
    last_totals_[k] = totals[k];
  }
  const cl_int *flips = &since[0], midpoints = since[3], kept = since[4];
  // Checked once per iteration: a lost star only leaves its point undeleted
  // until then.
  if (failures != 0)
    throw InternalError("flip-flop lost the star of a redundant point");
  counts.delaunay_flips += flips[0];
  counts.non_delaunay_flips += flips[1] + flips[2];
  counts.deleted += flips[2]; // each removal deletes one point
  counts.midpoints += midpoints;
  counts.kept_redundant += kept;
  if (flips[2] > 0) {
    // After finish_iteration, which leaves the deleted points' state alone.
    DeviceList<cl_double2> &log = deleted.coordinates;
    log.reserve(device_, static_cast<std::size_t>(flips[2]));
    if (logged_size_ != log.size) // set once for these steps: the kernel counts on
      logged_.fill(device_, static_cast<cl_int>(log.size), 1);
    set_args(log_deleted_, tracked_.buffer(), mesh_.point_state.buffer(), mesh_.points.buffer(),
             log.items.buffer(), logged_.buffer(), static_cast<cl_int>(tracked_n_));
    launch(device_, log_deleted_, tracked_n_, kPhase);
    log.size += static_cast<std::size_t>(flips[2]);
    logged_size_ = log.size;
  }
}

void FlipFlop::trim_lists() { encroachment_.trim_lists(); }

cl_uint FlipFlop::bind_lists(cl::Kernel &kernel, cl_uint first) const {
  return set_args_from(kernel, first, active_.buffer(), operation_.buffer(), proposal_.buffer(),
                       star_.buffer(), applied_.buffer(), count_.buffer(), offset_.buffer(),
                       next_active_.buffer(), exact_list_.buffer(), exact_count_.buffer(),
                       redundant_mark_.buffer(), redundant_anchor_.buffer(), marked_count_.buffer(),
                       tracked_.buffer(), star_size_.buffer(), star_offset_.buffer(),
                       totals_.buffer(), removal_claim_.buffer());
}

FlipFlop::PassResult FlipFlop::pass_by_kernels(std::size_t n, cl_int any_redundant, cl_int stamp,
                                               DeviceList<cl_int> &rewritten,
                                               FlipFlopCounts &counts) {
  const auto items = static_cast<cl_int>(n);
  marked_count_.fill(device_, 0, 1);
  cl_int uncertain = 0;
  propose(items, any_redundant, &uncertain);
  // The proposals have marked every point they mark: the count is read with
  // the scan's total below (the queue runs in order).
  cl_int marked = 0;
  marked_count_.download_later(device_, &marked, 1);
  bind(apply_, stamp, items);
  launch(device_, apply_, n, kPhase);
  bind(relink_, stamp, items);
  launch(device_, relink_, n, kPhase);
  PassResult result;
  result.next = static_cast<std::size_t>(scan_.exclusive_scan(count_, offset_, n, kPhase));
  set_args_from(gather_next_, bind_lists(gather_next_, 0), items);
  launch(device_, gather_next_, n, kPhase);
  rewritten.append(device_, next_active_, result.next); // the pass's results (and losers)
  result.marked = marked;
  counts.exact_checks += uncertain;
  result.looked_for_stars = result.marked > 0 || redundant_left_;
  if (result.looked_for_stars)
    result.length = find_stars(stamp, result.next, &result.stars);
  return result;
}

std::size_t FlipFlop::passes_in_group(std::size_t n, long &pass, int &stamp,
                                      const DeviceArray<cl_int> &new_points, std::size_t m,
                                      DeviceList<cl_int> &rewritten, FlipFlopCounts &counts) {
  const std::size_t group = pass_group_;
  rewritten.reserve(device_, 2 * n); // each entry passes on two at most
  bind(passes_in_group_, orthogonal_test_, static_cast<cl_int>(pass == 0),
       static_cast<cl_int>(next_active_.size()), static_cast<cl_int>(mesh_.list_capacity),
       static_cast<cl_int>(group_pass_limit_),
       static_cast<cl_int>(std::min<long>(max_passes(mesh_.triangle_count) - pass,
                                          std::numeric_limits<cl_int>::max())),
       static_cast<cl_int>(tracked_known_ ? tracked_n_ : -1), encroachment_.appended().buffer(),
       static_cast<cl_int>(kTrackedInGroup), static_cast<cl_int>(redundant_left_),
       rewritten.items.buffer(), static_cast<cl_int>(rewritten.size),
       static_cast<cl_int>(rewritten.items.size()), cl::Local(sizeof(cl_int) * group),
       pass_result_.buffer(), new_points.buffer(), static_cast<cl_int>(m),
       static_cast<cl_int>(stamp), static_cast<cl_int>(n));
  launch(device_, passes_in_group_, group, kPhase, group);
  const std::vector<cl_int> values = pass_result_.download(device_, kGroupResults);
  if (values[2] != 0)
    throw InternalError("flip-flop: the active list is longer than its arrays");
  pass += values[1];
  stamp += values[1];
  counts.passes += values[1];
  redundant_left_ = values[3] != 0;
  counts.exact_checks += values[4];
  if (values[5] != 0)
    std::swap(active_, next_active_);
  rewritten.size += static_cast<std::size_t>(values[6]);
  run_entries_ = std::max(run_entries_, static_cast<std::size_t>(values[7]));
  finished_in_group_ = values[8] != 0;
  std::copy(values.begin() + 9, values.begin() + 9 + kTotals, group_totals_.begin());
  tracked_n_ = static_cast<std::size_t>(values[9 + kTotals]);
  tracked_known_ = true;
  run_entries_ = std::max(run_entries_, tracked_n_);
  return static_cast<std::size_t>(values[0]);
}

void FlipFlop::know_tracked(std::size_t m) {
  if (tracked_known_)
    return;
  tracked_n_ = m + encroachment_.read_appended();
  tracked_known_ = true;
  run_entries_ = std::max(run_entries_, tracked_n_);
}

// Every active triangle proposes its operation: the filter's kernel, then the
// exact one for the triangles it could not decide, which reads how many they
// are itself. *uncertain gets that count once the queue has run this far
// (after the next blocking transfer).
void FlipFlop::propose(cl_int items, cl_int any_redundant, cl_int *uncertain) {
  exact_count_.fill(device_, 0, 1);
  bind(propose_, orthogonal_test_, any_redundant, items);
  launch(device_, propose_, static_cast<std::size_t>(items), kPhase);
  exact_count_.download_later(device_, uncertain, 1);
  bind(propose_exact_, orthogonal_test_, any_redundant);
  launch(device_, propose_exact_, sharing_items(device_, static_cast<std::size_t>(items)), kPhase);
}

// Marked points become redundant, and the stars of the redundant ones join the
// next list (next_active_[0 .. next)), which goes without duplicates to active_.
std::size_t FlipFlop::find_stars(int stamp, std::size_t next, std::size_t *stars_found) {
  const std::size_t m = tracked_n_;
  const auto points = static_cast<cl_int>(m);
  bind(track_, static_cast<cl_int>(stamp), points);
  launch(device_, track_, m, kPhase);
  const auto stars =
      static_cast<std::size_t>(scan_.exclusive_scan(star_size_, star_offset_, m, kPhase));
  *stars_found = stars;
  if (next + stars > next_active_.size())
    throw InternalError("flip-flop: the active list is longer than its arrays");
  if (stars > 0) {
    // The stars go after the pass's results, from `next` on.
    bind(emit_, static_cast<cl_int>(next), points);
    launch(device_, emit_, m, kPhase);
  }
  return static_cast<std::size_t>(
      scan_.unique(next_active_, next + stars, mesh_.tri_mark, count_, offset_, active_, kPhase));
}

long DeletionLog::points_inserted_more_than_once(Device &device,
                                                 const std::vector<Point> &survivors) const {
  if (coordinates.size == 0)
    return 0;
  const std::vector<cl_double2> deleted = coordinates.items.download(device, coordinates.size);
  std::vector<Point> sorted(deleted.size());
  std::transform(deleted.begin(), deleted.end(), sorted.begin(), [](const cl_double2 &c) {
    return Point{c.s[0], c.s[1]};
  });
  const auto less = [](const Point &a, const Point &b) {
    return a.x != b.x ? a.x < b.x : a.y < b.y;
  };
  const auto same = [](const Point &a, const Point &b) { return a.x == b.x && a.y == b.y; };
  std::sort(sorted.begin(), sorted.end(), less);
  // Each point deleted, once per point, and whether it came back.
  std::vector<Point> distinct;
  std::vector<char> back;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (i > 0 && same(sorted[i], sorted[i - 1])) {
      back.back() = 1; // deleted twice: inserted twice at least
      continue;
    }
    distinct.push_back(sorted[i]);
    back.push_back(0);
  }
  for (const Point &p : survivors) {
    const auto it = std::lower_bound(distinct.begin(), distinct.end(), p, less);
    if (it != distinct.end() && same(*it, p))
      back[static_cast<std::size_t>(it - distinct.begin())] = 1;
  }
  return static_cast<long>(std::count(back.begin(), back.end(), 1));
}

} // namespace clmesh
