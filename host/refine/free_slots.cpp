#include "refine/free_slots.hpp"

#include <algorithm>

namespace clmesh {

namespace {
const char *kFile = "free_slots.cl";
} // namespace

FreeSlots::FreeSlots(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      flag_dead_(device.kernel(kFile, "flag_dead_triangles", kPhase)),
      flag_deleted_(device.kernel(kFile, "flag_deleted_points", kPhase)) {}

void FreeSlots::collect() {
  DeviceMesh::FreeList &triangles = mesh_.free_triangles, &points = mesh_.free_points;
  if (triangles.slots.size() < mesh_.triangle_capacity)
    triangles.slots = DeviceArray<cl_int>(device_, mesh_.triangle_capacity);
  if (points.slots.size() < mesh_.point_capacity)
    points.slots = DeviceArray<cl_int>(device_, mesh_.point_capacity);
  const std::size_t slots = mesh_.triangle_count, point_slots = mesh_.point_count;
  const std::size_t scratch = std::max(slots, point_slots);
  DeviceArray<cl_int> flag(device_, scratch), offset(device_, scratch);
  set_args(flag_dead_, mesh_.tri_vertex.buffer(), flag.buffer(), static_cast<cl_int>(slots));
  launch(device_, flag_dead_, slots, kPhase);
  triangles.first = 0;
  triangles.count =
      static_cast<std::size_t>(scan_.compact_indices(flag, offset, triangles.slots, slots, kPhase));
  set_args(flag_deleted_, mesh_.point_state.buffer(), cl_int{1}, flag.buffer(), cl_int{0},
           static_cast<cl_int>(point_slots));
  launch(device_, flag_deleted_, point_slots, kPhase);
  points.first = 0;
  points.count = static_cast<std::size_t>(
      scan_.compact_indices(flag, offset, points.slots, point_slots, kPhase));
}

} // namespace clmesh
