#include "cdt/exterior_removal.hpp"

#include <algorithm>
#include <utility>

namespace clmesh {

namespace {
const char *kFile = "exterior_removal.cl";
}

ExteriorRemoval::ExteriorRemoval(Device &device, DeviceMesh &mesh)
    : device_(device), mesh_(mesh), seed_from_hull_(device.kernel(kFile, "seed_from_hull", kPhase)),
      seed_from_points_(device.kernel(kFile, "seed_from_points", kPhase)),
      spread_(device.kernel(kFile, "spread_flood", kPhase)),
      flood_in_group_(device.kernel(kFile, "flood_in_group", kPhase)),
      seed_label_(device.kernel(kFile, "seed_label", kPhase)),
      remove_unlabelled_(device.kernel(kFile, "remove_unlabelled", kPhase)),
      seed_thick_pockets_(device.kernel(kFile, "seed_thick_pockets", kPhase)),
      remove_flat_pockets_(device.kernel(kFile, "remove_flat_pockets", kPhase)),
      count_flat_(device.kernel(kFile, "count_flat_triangles", kPhase)),
      removed_(device, mesh.triangle_capacity), label_(device, 1),
      frontier_(device, mesh.triangle_capacity), next_frontier_(device, mesh.triangle_capacity),
      count_(device, 1), flood_result_(device, 3),
      flood_group_(device.single_group(flood_in_group_, kPhase)) {}

std::size_t ExteriorRemoval::slots() {
  removed_.cover(device_, mesh_.triangle_count, kPhase);
  return mesh_.triangle_count;
}

long ExteriorRemoval::run(bool from_hull, const std::vector<Point> &holes) {
  const std::size_t slots = this->slots();
  count_.fill(device_, 0, 1);
  seeds_on_segments_ = 0;
  if (from_hull)
    seed_from_hull(slots);
  if (!holes.empty()) {
    std::vector<cl_double2> seeds;
    for (const Point &p : holes)
      seeds.push_back({{p.x, p.y}});
    DeviceArray<cl_double2> seed_buffer(device_, seeds.size());
    seed_buffer.upload(device_, seeds);
    DeviceArray<cl_int> on_segment(device_, seeds.size());
    set_args_from(seed_from_points_, mesh_.bind_triangulation(seed_from_points_, 0),
                  seed_buffer.buffer(), static_cast<cl_int>(0), static_cast<cl_int>(slots + 8),
                  removed_.array.buffer(), frontier_.buffer(), count_.buffer(), on_segment.buffer(),
                  static_cast<cl_int>(seeds.size()));
    launch(device_, seed_from_points_, seeds.size(), kPhase);
    count_seeds_on_segments(on_segment, seeds.size());
  }
  const long removed = flood(-1);
  removed_any_ = removed_any_ || removed > 0;
  return removed;
}

void ExteriorRemoval::seed_from_hull(std::size_t slots) {
  set_args_from(seed_from_hull_, mesh_.bind_triangulation(seed_from_hull_, 0),
                removed_.array.buffer(), frontier_.buffer(), count_.buffer(),
                static_cast<cl_int>(slots));
  launch(device_, seed_from_hull_, slots, kPhase);
}

long ExteriorRemoval::remove_flat_pockets() {
  if (count_flat(true) == 0)
    return 0; // no flat triangle: no flat pocket (the usual case, one sweep)
  const std::size_t slots = this->slots(), capacity = mesh_.triangle_capacity;
  // The pockets: what a removal from the hull would eat (into removed_ for
  // the flood, swapped out after).
  CoveredArray<cl_int> pocket(device_, capacity);
  pocket.cover(device_, slots, kPhase);
  std::swap(removed_, pocket);
  count_.fill(device_, 0, 1);
  seed_from_hull(slots);
  flood(-1);
  std::swap(removed_, pocket);
  // The pockets with a triangle that is not flat, labelled 0 by a flood
  // closed outside the pockets.
  CoveredArray<cl_int> outside(device_, capacity);
  outside.covered = slots; // seed_thick_pockets sets every slot in use
  label_ = DeviceArray<cl_int>(device_, capacity);
  count_.fill(device_, 0, 1);
  set_args_from(seed_thick_pockets_, mesh_.bind_triangulation(seed_thick_pockets_, 0),
                pocket.array.buffer(), outside.array.buffer(), label_.buffer(), frontier_.buffer(),
                count_.buffer(), static_cast<cl_int>(slots));
  launch(device_, seed_thick_pockets_, slots, kPhase);
  std::swap(removed_, outside);
  flood(0);
  std::swap(removed_, outside);
  count_.fill(device_, 0, 1);
  set_args(remove_flat_pockets_, pocket.array.buffer(), label_.buffer(), removed_.array.buffer(),
           count_.buffer(), static_cast<cl_int>(slots));
  launch(device_, remove_flat_pockets_, slots, kPhase);
  const long removed = count_.read(device_, 0);
  removed_any_ = removed_any_ || removed > 0;
  return removed;
}

long ExteriorRemoval::count_flat(bool every) {
  const std::size_t slots = this->slots();
  count_.fill(device_, 0, 1);
  set_args_from(count_flat_, mesh_.bind_triangulation(count_flat_, 0), removed_.array.buffer(),
                static_cast<cl_int>(every), count_.buffer(), static_cast<cl_int>(slots));
  launch(device_, count_flat_, slots, kPhase);
  return count_.read(device_, 0);
}

void ExteriorRemoval::remove_unlabelled(const DeviceArray<cl_int> &label) {
  const std::size_t slots = this->slots();
  count_.fill(device_, 0, 1);
  set_args_from(remove_unlabelled_, mesh_.bind_triangulation(remove_unlabelled_, 0), label.buffer(),
                removed_.array.buffer(), count_.buffer(), static_cast<cl_int>(slots));
  launch(device_, remove_unlabelled_, slots, kPhase);
  removed_any_ = removed_any_ || count_.read(device_, 0) > 0;
}

void ExteriorRemoval::count_seeds_on_segments(const DeviceArray<cl_int> &on_segment,
                                              std::size_t count) {
  const std::vector<cl_int> flags = on_segment.download(device_, count);
  seeds_on_segments_ = static_cast<long>(std::count(flags.begin(), flags.end(), 1));
}

long ExteriorRemoval::flood(int region) {
  long reached = 0;
  for (int front = count_.read(device_, 0); front > 0;) {
    if (front <= kInGroup) {
      set_args_from(flood_in_group_, mesh_.bind_triangulation(flood_in_group_, 0),
                    frontier_.buffer(), removed_.array.buffer(), static_cast<cl_int>(region),
                    label_.buffer(), next_frontier_.buffer(), static_cast<cl_int>(front),
                    static_cast<cl_int>(kInGroup), flood_result_.buffer());
      launch(device_, flood_in_group_, flood_group_, kPhase, flood_group_);
      const std::vector<cl_int> result = flood_result_.download(device_, 3);
      if (result[2] % 2)
        std::swap(frontier_, next_frontier_);
      reached += result[1];
      front = result[0];
      if (front == 0)
        break;
    } // the front outgrew one group: waves by launches
    reached += front;
    count_.fill(device_, 0, 1);
    set_args_from(spread_, mesh_.bind_triangulation(spread_, 0), frontier_.buffer(),
                  removed_.array.buffer(), static_cast<cl_int>(region), label_.buffer(),
                  next_frontier_.buffer(), count_.buffer(), static_cast<cl_int>(front));
    launch(device_, spread_, static_cast<std::size_t>(front), kPhase);
    std::swap(frontier_, next_frontier_);
    front = count_.read(device_, 0);
  }
  return reached;
}

const DeviceArray<cl_int> &ExteriorRemoval::label_regions(const std::vector<Point> &seeds) {
  const std::size_t slots = this->slots();
  label_ = DeviceArray<cl_int>(device_, mesh_.triangle_capacity);
  label_.fill(device_, -1, fill_ahead(slots, mesh_.triangle_capacity));
  DeviceArray<cl_int> on_segment(device_, seeds.size());
  for (std::size_t r = 0; r < seeds.size(); ++r) {
    count_.fill(device_, 0, 1);
    set_args_from(seed_label_, mesh_.bind_triangulation(seed_label_, 0), removed_.array.buffer(),
                  cl_double2{{seeds[r].x, seeds[r].y}}, static_cast<cl_int>(0),
                  static_cast<cl_int>(slots + 8), static_cast<cl_int>(r), label_.buffer(),
                  frontier_.buffer(), count_.buffer(), on_segment.buffer());
    launch(device_, seed_label_, 1, kPhase);
    flood(static_cast<int>(r));
  }
  count_seeds_on_segments(on_segment, seeds.size());
  return label_;
}

} // namespace clmesh
