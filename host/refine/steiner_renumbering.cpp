#include "refine/steiner_renumbering.hpp"

namespace clmesh {

SteinerRenumbering::SteinerRenumbering(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      flag_deleted_(device.kernel("free_slots.cl", "flag_deleted_points", kPhase)),
      number_(device.kernel("steiner_renumbering.cl", "number_steiner_points", kPhase)) {}

std::vector<Point> SteinerRenumbering::number(std::size_t first, std::vector<int32_t> *segments) {
  const std::size_t n = mesh_.point_count - first;
  std::vector<Point> result;
  if (n == 0)
    return result;
  DeviceArray<cl_int> survives(device_, n), offset(device_, n);
  set_args(flag_deleted_, mesh_.point_state.buffer(), cl_int{0}, survives.buffer(),
           static_cast<cl_int>(first), static_cast<cl_int>(n));
  launch(device_, flag_deleted_, n, kPhase);
  const int survivors = scan_.exclusive_scan(survives, offset, n, kPhase);
  set_args(number_, mesh_.point_state.buffer(), offset.buffer(), static_cast<cl_int>(survivors),
           mesh_.original_id.buffer(), static_cast<cl_int>(first), static_cast<cl_int>(n));
  launch(device_, number_, n, kPhase);
  // The final download: the coordinates of the survivors, in slot order.
  const std::vector<cl_double2> points = mesh_.points.download(device_, n, first);
  const std::vector<cl_int> keep = survives.download(device_, n);
  const std::vector<cl_int> on_segment =
      segments ? mesh_.point_segment.download(device_, n, first) : std::vector<cl_int>();
  result.reserve(static_cast<std::size_t>(survivors));
  for (std::size_t k = 0; k < n; ++k)
    if (keep[k]) {
      result.push_back({points[k].s[0], points[k].s[1]});
      if (segments)
        segments->push_back(on_segment[k]);
    }
  return result;
}

} // namespace clmesh
