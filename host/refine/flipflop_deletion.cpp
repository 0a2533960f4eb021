#include "refine/flipflop_deletion.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace clmesh {

namespace {
const char *kFile = "flipflop_deletion.cl";
// A pass deletes a redundant point or flips; far more passes than any mesh
// needs means a bug, reported instead of a hang.
constexpr long kMaxPasses = 100000;
} // namespace

FlipflopDeletion::FlipflopDeletion(Device &device, DeviceMesh &mesh, PrefixScan &scan,
                                   bool orthogonal_test, double lens, std::size_t group_pass_limit)
    : device_(device), mesh_(mesh), scan_(scan), orthogonal_test_(orthogonal_test ? 1 : 0),
      lens_(lens), group_pass_limit_(group_pass_limit),
      mark_encroaching_(device.kernel(kFile, "mark_encroaching_points", kPhase)),
      clear_claims_(device.kernel(kFile, "clear_encroaching_claims", kPhase)),
      propose_(device.kernel(kFile, "flipflop_propose", kPhase)),
      propose_exact_(device.kernel(kFile, "flipflop_propose_exact", kPhase)),
      apply_(device.kernel(kFile, "flipflop_apply", kPhase)),
      relink_(device.kernel(kFile, "flipflop_relink", kPhase)),
      gather_next_(device.kernel(kFile, "flipflop_gather_next", kPhase)),
      track_(device.kernel(kFile, "track_redundant_points", kPhase)),
      emit_(device.kernel(kFile, "emit_redundant_stars", kPhase)),
      finish_(device.kernel(kFile, "finish_iteration", kPhase)),
      keep_stuck_(device.kernel(kFile, "keep_stuck_points", kPhase)),
      flag_dead_(device.kernel(kFile, "flag_dead_triangles", kPhase)),
      flag_deleted_(device.kernel(kFile, "flag_deleted_points", kPhase)),
      number_(device.kernel(kFile, "number_steiner_points", kPhase)),
      triangle_cells_(device.kernel(kFile, "triangle_cells", kPhase)),
      point_cells_(device.kernel(kFile, "steiner_point_cells", kPhase)),
      move_points_(device.kernel(kFile, "move_steiner_points", kPhase)),
      renumber_vertices_(device.kernel(kFile, "renumber_steiner_vertices", kPhase)),
      sort_cells_(device.kernel(kFile, "sort_cells", kPhase)),
      move_triangles_(device.kernel(kFile, "move_triangles", kPhase)),
      pass_in_group_(device.kernel(kFile, "flipflop_pass_in_group", kPhase)),
      log_deleted_(device.kernel(kFile, "log_deleted_points", kPhase)),
      // The next list holds the pass's results and the redundant stars before
      // duplicates are dropped; an active list has distinct live triangles.
      active_(device, 2 * mesh.list_capacity), next_active_(device, 2 * mesh.list_capacity),
      exact_list_(device, mesh.list_capacity), operation_(device, mesh.list_capacity),
      proposal_(device, mesh.list_capacity), star_(device, 4 * mesh.list_capacity),
      applied_(device, mesh.list_capacity), count_(device, 2 * mesh.list_capacity),
      offset_(device, 2 * mesh.list_capacity), redundant_mark_(device, mesh.point_capacity),
      redundant_anchor_(device, mesh.point_capacity), star_size_(device, mesh.point_capacity),
      star_offset_(device, mesh.point_capacity), tracked_(device, mesh.point_capacity),
      encroach_claim_(device, mesh.point_capacity), marked_count_(device, 1),
      exact_count_(device, 1), flip_counts_(device, 3), failures_(device, 1), midpoints_(device, 1),
      kept_(device, 1), logged_(device, 1), pass_result_(device, 5) {
  pass_group_limit_ = guarded(kPhase, "querying the work-group size", [&] {
    return pass_in_group_.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device.cl_device());
  });
  redundant_mark_.fill(device_, 0, mesh.point_capacity);
  encroach_claim_.fill(device_, 0x7fffffff, mesh.point_capacity);
  failures_.fill(device_, 0, 1);
}

void FlipflopDeletion::run(const DeviceArray<cl_int> &changed, std::size_t n,
                           const DeviceArray<cl_int> &new_points, std::size_t m, int &stamp,
                           DeviceList<cl_int> &rewritten, DeletionLog &deleted,
                           FlipflopCounts &counts) {
  if (n > mesh_.list_capacity)
    throw InternalError("flip-flop: the active list is longer than its arrays");
  if (n > 0)
    guarded(kPhase, "copying the active list", [&] {
      device_.queue().enqueueCopyBuffer(changed.buffer(), active_.buffer(), 0, 0,
                                        n * sizeof(cl_int));
    });
  flip_counts_.fill(device_, 0, 3);
  kept_.fill(device_, 0, 1);
  // The points to follow: this iteration's, then the old ones that encroach
  // a hull edge split in this iteration (thesis §3.4.1).
  if (m > 0)
    guarded(kPhase, "copying the new points", [&] {
      device_.queue().enqueueCopyBuffer(new_points.buffer(), tracked_.buffer(), 0, 0,
                                        m * sizeof(cl_int));
    });
  tracked_n_ = m;
  if (m > 0) {
    const auto items = static_cast<cl_int>(m);
    auto encroaching = [&](int step) {
      set_args(mark_encroaching_, new_points.buffer(), mesh_.points.buffer(),
               mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(),
               mesh_.vertex_triangle.buffer(), mesh_.point_state.buffer(), lens_,
               static_cast<cl_int>(step), encroach_claim_.buffer(), redundant_mark_.buffer(),
               redundant_anchor_.buffer(), star_size_.buffer(), star_offset_.buffer(),
               tracked_.buffer(), items, items);
      launch(device_, mark_encroaching_, m, kPhase);
    };
    encroaching(0); // claim
    encroaching(1); // count, into star_size_
    const auto old =
        static_cast<std::size_t>(scan_.exclusive_scan(star_size_, star_offset_, m, kPhase));
    if (old > 0) {
      encroaching(2); // write
      tracked_n_ += old;
    }
    set_args(clear_claims_, tracked_.buffer(), encroach_claim_.buffer(),
             static_cast<cl_int>(tracked_n_));
    launch(device_, clear_claims_, tracked_n_, kPhase);
  }
  redundant_left_ = true; // marks of the boundary routine: tracked in the first pass
  for (long pass = 0; n > 0; ++pass) {
    if (pass == kMaxPasses)
      throw InternalError("flip-flop did not converge in " + std::to_string(kMaxPasses) +
                          " passes");
    const auto pass_stamp = static_cast<cl_int>(stamp++);
    const auto any_redundant = static_cast<cl_int>(redundant_left_ && pass > 0);
    const PassResult result = n <= group_pass_limit_ && tracked_n_ <= kTrackedInGroup
                                  ? pass_in_group(n, any_redundant, pass_stamp, counts)
                                  : pass_by_kernels(n, any_redundant, pass_stamp, counts);
    rewritten.append(device_, next_active_, result.next); // the pass's results (and losers)
    ++counts.passes;
    if (result.looked_for_stars) {
      redundant_left_ = result.stars > 0;
      n = result.length;
      if (n > mesh_.list_capacity)
        throw InternalError("flip-flop: the active list is longer than its arrays");
      if (result.next == 0 && result.marked == 0 && redundant_left_) {
        // Stalled: what is left cannot be deleted. Their stars are listed.
        set_args(keep_stuck_, tracked_.buffer(), mesh_.point_state.buffer(), kept_.buffer(),
                 static_cast<cl_int>(tracked_n_));
        launch(device_, keep_stuck_, tracked_n_, kPhase);
        redundant_left_ = false;
      }
    } else {
      std::swap(active_, next_active_);
      n = result.next;
    }
  }
  // Checked once per iteration: a lost star only leaves its point undeleted
  // until then.
  if (failures_.read(device_, 0) != 0)
    throw InternalError("flip-flop lost the star of a redundant point");
  const std::vector<cl_int> flips = flip_counts_.download(device_, 3);
  counts.delaunay_flips += flips[0];
  counts.non_delaunay_flips += flips[1] + flips[2];
  counts.deleted += flips[2]; // each removal deletes one point
  if (flips[2] > 0) {
    DeviceList<cl_double2> &log = deleted.coordinates;
    log.reserve(device_, static_cast<std::size_t>(flips[2]));
    logged_.fill(device_, 0, 1);
    set_args(log_deleted_, tracked_.buffer(), mesh_.point_state.buffer(), mesh_.points.buffer(),
             log.items.buffer(), static_cast<cl_int>(log.size), logged_.buffer(),
             static_cast<cl_int>(tracked_n_));
    launch(device_, log_deleted_, tracked_n_, kPhase);
    log.size += static_cast<std::size_t>(flips[2]);
  }
  midpoints_.fill(device_, 0, 1);
  if (m > 0) {
    set_args(finish_, new_points.buffer(), mesh_.point_state.buffer(), midpoints_.buffer(),
             static_cast<cl_int>(m));
    launch(device_, finish_, m, kPhase);
  }
  counts.midpoints += midpoints_.read(device_, 0);
  counts.kept_redundant += kept_.read(device_, 0);
}

FlipflopDeletion::PassResult FlipflopDeletion::pass_by_kernels(std::size_t n, cl_int any_redundant,
                                                               cl_int stamp,
                                                               FlipflopCounts &counts) {
  const auto items = static_cast<cl_int>(n);
  marked_count_.fill(device_, 0, 1);
  counts.exact_checks += propose(items, any_redundant);
  set_args(apply_, active_.buffer(), operation_.buffer(), proposal_.buffer(), star_.buffer(),
           mesh_.tri_mark.buffer(), mesh_.points.buffer(), mesh_.tri_vertex.buffer(),
           mesh_.tri_neighbor.buffer(), mesh_.modified_stamp.buffer(), mesh_.children.buffer(),
           mesh_.point_state.buffer(), applied_.buffer(), flip_counts_.buffer(), stamp, items);
  launch(device_, apply_, n, kPhase);
  set_args(relink_, active_.buffer(), operation_.buffer(), proposal_.buffer(), star_.buffer(),
           applied_.buffer(), mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(),
           mesh_.modified_stamp.buffer(), mesh_.children.buffer(), mesh_.tri_mark.buffer(),
           count_.buffer(), stamp, items);
  launch(device_, relink_, n, kPhase);
  PassResult result;
  result.next = static_cast<std::size_t>(scan_.exclusive_scan(count_, offset_, n, kPhase));
  set_args(gather_next_, active_.buffer(), proposal_.buffer(), operation_.buffer(), star_.buffer(),
           applied_.buffer(), count_.buffer(), offset_.buffer(), next_active_.buffer(), items);
  launch(device_, gather_next_, n, kPhase);
  result.marked = marked_count_.read(device_, 0);
  result.looked_for_stars = result.marked > 0 || redundant_left_;
  if (result.looked_for_stars)
    result.length = find_stars(stamp, result.next, &result.stars);
  return result;
}

FlipflopDeletion::PassResult FlipflopDeletion::pass_in_group(std::size_t n, cl_int any_redundant,
                                                             cl_int stamp, FlipflopCounts &counts) {
  // The group may have to be smaller for this large kernel than for the others.
  const std::size_t group = std::min(device_.work_group(), pass_group_limit_);
  set_args(pass_in_group_, active_.buffer(), mesh_.points.buffer(), mesh_.tri_vertex.buffer(),
           mesh_.tri_neighbor.buffer(), mesh_.constraint_start.buffer(),
           mesh_.constraint_adjacent.buffer(), static_cast<cl_int>(mesh_.has_constraints),
           mesh_.point_state.buffer(), mesh_.insertion_radius2.buffer(),
           mesh_.point_priority.buffer(), orthogonal_test_, any_redundant, redundant_mark_.buffer(),
           redundant_anchor_.buffer(), marked_count_.buffer(), mesh_.tri_mark.buffer(),
           operation_.buffer(), proposal_.buffer(), star_.buffer(), mesh_.modified_stamp.buffer(),
           mesh_.children.buffer(), applied_.buffer(), flip_counts_.buffer(), count_.buffer(),
           offset_.buffer(), next_active_.buffer(), static_cast<cl_int>(next_active_.size()),
           tracked_.buffer(), static_cast<cl_int>(tracked_n_), static_cast<cl_int>(redundant_left_),
           star_size_.buffer(), star_offset_.buffer(), failures_.buffer(),
           cl::Local(sizeof(cl_int) * group), pass_result_.buffer(), stamp, static_cast<cl_int>(n));
  launch(device_, pass_in_group_, group, kPhase, group);
  const std::vector<cl_int> values = pass_result_.download(device_, 5);
  if (values[2] == -2)
    throw InternalError("flip-flop: the active list is longer than its arrays");
  PassResult result;
  result.next = static_cast<std::size_t>(values[0]);
  result.marked = values[1];
  result.looked_for_stars = values[2] >= 0;
  result.stars = result.looked_for_stars ? static_cast<std::size_t>(values[2]) : 0;
  result.length = static_cast<std::size_t>(values[3]);
  counts.exact_checks += values[4];
  return result;
}

// Every active triangle proposes its operation: the filter's kernel, then the
// exact one for the triangles it could not decide. Returns how many those were.
long FlipflopDeletion::propose(cl_int items, cl_int any_redundant) {
  const auto constrained = static_cast<cl_int>(mesh_.has_constraints);
  exact_count_.fill(device_, 0, 1);
  set_args(propose_, active_.buffer(), mesh_.points.buffer(), mesh_.tri_vertex.buffer(),
           mesh_.tri_neighbor.buffer(), mesh_.constraint_start.buffer(),
           mesh_.constraint_adjacent.buffer(), constrained, mesh_.point_state.buffer(),
           mesh_.insertion_radius2.buffer(), mesh_.point_priority.buffer(), orthogonal_test_,
           any_redundant, redundant_mark_.buffer(), redundant_anchor_.buffer(),
           marked_count_.buffer(), mesh_.tri_mark.buffer(), operation_.buffer(), proposal_.buffer(),
           star_.buffer(), exact_list_.buffer(), exact_count_.buffer(), items);
  launch(device_, propose_, static_cast<std::size_t>(items), kPhase);
  const int uncertain = exact_count_.read(device_, 0);
  if (uncertain > 0) {
    set_args(propose_exact_, exact_list_.buffer(), active_.buffer(), mesh_.points.buffer(),
             mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(),
             mesh_.constraint_start.buffer(), mesh_.constraint_adjacent.buffer(), constrained,
             mesh_.point_state.buffer(), mesh_.insertion_radius2.buffer(),
             mesh_.point_priority.buffer(), orthogonal_test_, any_redundant,
             redundant_mark_.buffer(), redundant_anchor_.buffer(), marked_count_.buffer(),
             mesh_.tri_mark.buffer(), operation_.buffer(), proposal_.buffer(), star_.buffer(),
             static_cast<cl_int>(uncertain));
    launch(device_, propose_exact_, static_cast<std::size_t>(uncertain), kPhase);
  }
  return uncertain;
}

// Marked points become redundant, and the stars of the redundant ones join the
// next list (next_active_[0 .. next)), which goes without duplicates to active_.
std::size_t FlipflopDeletion::find_stars(int stamp, std::size_t next, std::size_t *stars_found) {
  const std::size_t m = tracked_n_;
  const auto points = static_cast<cl_int>(m);
  set_args(track_, tracked_.buffer(), mesh_.point_state.buffer(), redundant_mark_.buffer(),
           redundant_anchor_.buffer(), mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(),
           mesh_.modified_stamp.buffer(), mesh_.children.buffer(), star_size_.buffer(),
           failures_.buffer(), static_cast<cl_int>(stamp), points);
  launch(device_, track_, m, kPhase);
  const auto stars =
      static_cast<std::size_t>(scan_.exclusive_scan(star_size_, star_offset_, m, kPhase));
  *stars_found = stars;
  if (next + stars > next_active_.size())
    throw InternalError("flip-flop: the active list is longer than its arrays");
  if (stars > 0) {
    // The stars go after the pass's results, from `next` on.
    set_args(emit_, tracked_.buffer(), redundant_anchor_.buffer(), mesh_.tri_vertex.buffer(),
             mesh_.tri_neighbor.buffer(), star_size_.buffer(), star_offset_.buffer(),
             next_active_.buffer(), static_cast<cl_int>(next), points);
    launch(device_, emit_, m, kPhase);
  }
  return static_cast<std::size_t>(
      scan_.unique(next_active_, next + stars, mesh_.tri_mark, count_, offset_, active_, kPhase));
}

void FlipflopDeletion::collect_free_slots() {
  DeviceMesh::FreeList &triangles = mesh_.free_triangles, &points = mesh_.free_points;
  if (triangles.slots.size() < mesh_.triangle_capacity)
    triangles.slots = DeviceArray<cl_int>(device_, mesh_.triangle_capacity);
  if (points.slots.size() < mesh_.point_capacity)
    points.slots = DeviceArray<cl_int>(device_, mesh_.point_capacity);
  // count_ and offset_ (2 list_capacity > triangle_capacity) serve as scratch.
  const std::size_t slots = mesh_.triangle_count;
  set_args(flag_dead_, mesh_.tri_vertex.buffer(), count_.buffer(), static_cast<cl_int>(slots));
  launch(device_, flag_dead_, slots, kPhase);
  triangles.first = 0;
  triangles.count = static_cast<std::size_t>(
      scan_.compact_indices(count_, offset_, triangles.slots, slots, kPhase));
  const std::size_t point_slots = mesh_.point_count;
  set_args(flag_deleted_, mesh_.point_state.buffer(), cl_int{1}, count_.buffer(), cl_int{0},
           static_cast<cl_int>(point_slots));
  launch(device_, flag_deleted_, point_slots, kPhase);
  points.first = 0;
  points.count = static_cast<std::size_t>(
      scan_.compact_indices(count_, offset_, points.slots, point_slots, kPhase));
}

FlipflopDeletion::ZGrid FlipflopDeletion::z_grid(Point low, double side, std::size_t items,
                                                 std::size_t per_cell) {
  int bits = 1;
  while (bits < 15 && (std::size_t{1} << (2 * bits)) * per_cell < items)
    ++bits;
  const double scale =
      side > 0 && std::isfinite(side) ? static_cast<double>(std::size_t{1} << bits) / side : 0.0;
  return {cl_double2{{low.x, low.y}}, scale, bits, std::size_t{1} << (2 * bits)};
}

std::size_t FlipflopDeletion::z_order(const ZGrid &grid, const DeviceArray<cl_int> &cell,
                                      const DeviceArray<cl_ulong> &key, bool rotated,
                                      std::size_t items, const DeviceArray<cl_int> &order,
                                      const DeviceArray<cl_int> &new_slot) {
  DeviceArray<cl_int> cell_size(device_, grid.cells), cell_start(device_, grid.cells),
      cursor(device_, grid.cells);
  const auto placed = static_cast<std::size_t>(
      scan_.bucket(cell, items, grid.cells, cell_size, cell_start, cursor, order, kPhase));
  set_args(sort_cells_, cell_start.buffer(), cell_size.buffer(), key.buffer(),
           static_cast<cl_int>(rotated), order.buffer(), new_slot.buffer(),
           static_cast<cl_int>(grid.cells));
  launch(device_, sort_cells_, grid.cells, kPhase);
  return placed;
}

void FlipflopDeletion::compact(Point low, double side, std::size_t first) {
  compact_triangles(low, side);
  compact_steiner_points(low, side, first);
}

void FlipflopDeletion::compact_triangles(Point low, double side) {
  const std::size_t slots = mesh_.triangle_count;
  const ZGrid grid = z_grid(low, side, slots, 8);
  // The marks (none are set between iterations) hold the cells, the stamps
  // the new slots, the children the moved vertices: all are reset after.
  const DeviceArray<cl_int> &cell = mesh_.tri_mark, &new_slot = mesh_.modified_stamp;
  DeviceArray<cl_int> order(device_, slots);
  std::size_t live = 0;
  {
    DeviceArray<cl_ulong> key(device_, slots);
    set_args(triangle_cells_, mesh_.points.buffer(), mesh_.tri_vertex.buffer(), grid.low,
             grid.scale, static_cast<cl_int>(grid.bits), cell.buffer(), key.buffer(),
             static_cast<cl_int>(slots));
    launch(device_, triangle_cells_, slots, kPhase);
    live = z_order(grid, cell, key, true, slots, order, new_slot);
  }
  {
    DeviceArray<cl_int> moved_neighbor(device_, 3 * mesh_.triangle_capacity);
    set_args(move_triangles_, order.buffer(), new_slot.buffer(), mesh_.tri_vertex.buffer(),
             mesh_.tri_neighbor.buffer(), mesh_.children.buffer(), moved_neighbor.buffer(),
             static_cast<cl_int>(live));
    launch(device_, move_triangles_, live, kPhase);
    std::swap(mesh_.tri_vertex, mesh_.children);
    std::swap(mesh_.tri_neighbor, moved_neighbor);
  }
  // Past the old slots the marks and stamps were never written since filled.
  mesh_.tri_mark.fill(device_, -1, slots); // no mark
  mesh_.modified_stamp.fill(device_, 0, slots);
  mesh_.triangle_count = live;
  mesh_.free_triangles.first = mesh_.free_triangles.count = 0;
}

void FlipflopDeletion::compact_steiner_points(Point low, double side, std::size_t first) {
  const std::size_t slots = mesh_.point_count - first;
  if (slots == 0)
    return;
  const ZGrid grid = z_grid(low, side, slots, 4);
  // Scratch: the flip-flop's per-point arrays, reset between iterations.
  const DeviceArray<cl_int> &cell = star_size_, &new_slot = star_offset_, &order = tracked_;
  std::size_t live = 0;
  {
    DeviceArray<cl_ulong> key(device_, slots);
    set_args(point_cells_, mesh_.points.buffer(), mesh_.point_state.buffer(), grid.low, grid.scale,
             static_cast<cl_int>(grid.bits), cell.buffer(), key.buffer(),
             static_cast<cl_int>(first), static_cast<cl_int>(slots));
    launch(device_, point_cells_, slots, kPhase);
    live = z_order(grid, cell, key, false, slots, order, new_slot);
  }
  const std::size_t capacity = mesh_.point_capacity;
  DeviceArray<cl_double2> points(device_, capacity);
  DeviceArray<cl_int> state(device_, capacity);
  DeviceArray<cl_double> radius2(device_, capacity);
  DeviceArray<cl_uint> priority(device_, capacity);
  set_args(move_points_, order.buffer(), mesh_.points.buffer(), mesh_.point_state.buffer(),
           mesh_.insertion_radius2.buffer(), mesh_.point_priority.buffer(), points.buffer(),
           state.buffer(), radius2.buffer(), priority.buffer(), mesh_.original_id.buffer(),
           static_cast<cl_int>(first), static_cast<cl_int>(first + live));
  launch(device_, move_points_, first + live, kPhase);
  set_args(renumber_vertices_, new_slot.buffer(), mesh_.tri_vertex.buffer(),
           static_cast<cl_int>(first), static_cast<cl_int>(3 * mesh_.triangle_count));
  launch(device_, renumber_vertices_, 3 * mesh_.triangle_count, kPhase);
  std::swap(mesh_.points, points);
  std::swap(mesh_.point_state, state);
  std::swap(mesh_.insertion_radius2, radius2);
  std::swap(mesh_.point_priority, priority);
  mesh_.point_count = first + live;
  mesh_.free_points.first = mesh_.free_points.count = 0;
}

std::vector<Point> FlipflopDeletion::steiner_points(std::size_t first) {
  const std::size_t n = mesh_.point_count - first;
  std::vector<Point> result;
  if (n == 0)
    return result;
  set_args(flag_deleted_, mesh_.point_state.buffer(), cl_int{0}, count_.buffer(),
           static_cast<cl_int>(first), static_cast<cl_int>(n));
  launch(device_, flag_deleted_, n, kPhase);
  const int survivors = scan_.exclusive_scan(count_, offset_, n, kPhase);
  set_args(number_, mesh_.point_state.buffer(), offset_.buffer(), static_cast<cl_int>(survivors),
           mesh_.original_id.buffer(), static_cast<cl_int>(first), static_cast<cl_int>(n));
  launch(device_, number_, n, kPhase);
  // The final download: the coordinates of the survivors, in slot order.
  const std::vector<cl_double2> points = mesh_.points.download(device_, n, first);
  const std::vector<cl_int> keep = count_.download(device_, n);
  result.reserve(static_cast<std::size_t>(survivors));
  for (std::size_t k = 0; k < n; ++k)
    if (keep[k])
      result.push_back({points[k].s[0], points[k].s[1]});
  return result;
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
