#include "refine/zorder_compaction.hpp"

#include <cmath>
#include <utility>

namespace clmesh {

namespace {
const char *kFile = "zorder_compaction.cl";
} // namespace

ZOrderCompaction::ZOrderCompaction(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      triangle_cells_(device.kernel(kFile, "triangle_cells", kPhase)),
      point_cells_(device.kernel(kFile, "steiner_point_cells", kPhase)),
      sort_cells_(device.kernel(kFile, "sort_cells", kPhase)),
      move_triangles_(device.kernel(kFile, "move_triangles", kPhase)),
      move_points_(device.kernel(kFile, "move_steiner_points", kPhase)),
      renumber_vertices_(device.kernel(kFile, "renumber_steiner_vertices", kPhase)) {}

ZOrderCompaction::ZGrid ZOrderCompaction::z_grid(Point low, double side, std::size_t items,
                                                 std::size_t per_cell) {
  int bits = 1;
  while (bits < 15 && (std::size_t{1} << (2 * bits)) * per_cell < items)
    ++bits;
  const double scale =
      side > 0 && std::isfinite(side) ? static_cast<double>(std::size_t{1} << bits) / side : 0.0;
  return {cl_double2{{low.x, low.y}}, scale, bits, std::size_t{1} << (2 * bits)};
}

std::size_t ZOrderCompaction::z_order(const ZGrid &grid, const DeviceArray<cl_int> &cell,
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

void ZOrderCompaction::compact(Point low, double side, std::size_t first,
                               DeviceArray<cl_int> *slot_flags,
                               DeviceArray<cl_double> *slot_values) {
  compact_triangles(low, side, slot_flags, slot_values);
  compact_steiner_points(low, side, first);
}

void ZOrderCompaction::compact_triangles(Point low, double side, DeviceArray<cl_int> *slot_flags,
                                         DeviceArray<cl_double> *slot_values) {
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
    // The moved arrays take the place of the mesh's.
    DeviceArray<cl_int> moved_neighbor(device_, 3 * mesh_.triangle_capacity,
                                       DeviceMesh::kHugePages);
    DeviceArray<cl_int> moved_region(device_, mesh_.has_regions ? mesh_.triangle_capacity : 1,
                                     DeviceMesh::kHugePages);
    DeviceArray<cl_int> moved_flags(device_, slot_flags ? live : 1);
    const DeviceArray<cl_int> &flags = slot_flags ? *slot_flags : moved_flags;
    DeviceArray<cl_double> moved_values(device_, slot_values ? slot_values->size() : 1);
    const DeviceArray<cl_double> &values = slot_values ? *slot_values : moved_values;
    set_args(move_triangles_, order.buffer(), new_slot.buffer(), mesh_.tri_vertex.buffer(),
             mesh_.tri_neighbor.buffer(), mesh_.tri_region.buffer(),
             static_cast<cl_int>(mesh_.has_regions), flags.buffer(),
             static_cast<cl_int>(slot_flags != nullptr), values.buffer(),
             static_cast<cl_int>(slot_values != nullptr), mesh_.children.buffer(),
             moved_neighbor.buffer(), moved_region.buffer(), moved_flags.buffer(),
             moved_values.buffer(), static_cast<cl_int>(live));
    launch(device_, move_triangles_, live, kPhase);
    if (slot_flags)
      *slot_flags = std::move(moved_flags);
    if (slot_values)
      *slot_values = std::move(moved_values);
    std::swap(mesh_.tri_vertex, mesh_.children);
    std::swap(mesh_.tri_neighbor, moved_neighbor);
    if (mesh_.has_regions) // the slots past the live ones get theirs when filled
      std::swap(mesh_.tri_region, moved_region);
  }
  // Past the old slots the marks and stamps were never written since filled.
  mesh_.tri_mark.fill(device_, -1, slots); // no mark
  mesh_.modified_stamp.fill(device_, 0, slots);
  mesh_.triangle_count = live;
  mesh_.free_triangles.first = mesh_.free_triangles.count = 0;
}

void ZOrderCompaction::compact_steiner_points(Point low, double side, std::size_t first) {
  const std::size_t slots = mesh_.point_count - first;
  if (slots == 0)
    return;
  const ZGrid grid = z_grid(low, side, slots, 4);
  DeviceArray<cl_int> cell(device_, slots), new_slot(device_, slots), order(device_, slots);
  std::size_t live = 0;
  {
    DeviceArray<cl_ulong> key(device_, slots);
    set_args(point_cells_, mesh_.points.buffer(), mesh_.point_state.buffer(), grid.low, grid.scale,
             static_cast<cl_int>(grid.bits), cell.buffer(), key.buffer(),
             static_cast<cl_int>(first), static_cast<cl_int>(slots));
    launch(device_, point_cells_, slots, kPhase);
    live = z_order(grid, cell, key, false, slots, order, new_slot);
  }
  // The moved arrays take the place of the mesh's.
  const std::size_t capacity = mesh_.point_capacity;
  constexpr bool huge = DeviceMesh::kHugePages;
  DeviceArray<cl_double2> points(device_, capacity, huge);
  DeviceArray<cl_int> state(device_, capacity, huge);
  DeviceArray<cl_double> radius2(device_, capacity, huge);
  DeviceArray<cl_uint> priority(device_, capacity, huge);
  DeviceArray<cl_int> segment(device_, capacity, huge);
  set_args_from(move_points_, mesh_.bind(move_points_, 0), order.buffer(), points.buffer(),
                state.buffer(), radius2.buffer(), priority.buffer(), segment.buffer(),
                static_cast<cl_int>(first), static_cast<cl_int>(first + live));
  launch(device_, move_points_, first + live, kPhase);
  set_args(renumber_vertices_, new_slot.buffer(), mesh_.tri_vertex.buffer(),
           static_cast<cl_int>(first), static_cast<cl_int>(3 * mesh_.triangle_count));
  launch(device_, renumber_vertices_, 3 * mesh_.triangle_count, kPhase);
  std::swap(mesh_.points, points);
  std::swap(mesh_.point_state, state);
  std::swap(mesh_.insertion_radius2, radius2);
  std::swap(mesh_.point_priority, priority);
  std::swap(mesh_.point_segment, segment);
  mesh_.point_count = first + live;
  mesh_.free_points.first = mesh_.free_points.count = 0;
}

} // namespace clmesh
