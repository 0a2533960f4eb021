#include "refine/hull_encroachment.hpp"

namespace clmesh {

namespace {
const char *kFile = "hull_encroachment.cl";
constexpr cl_int kNoClaim = 0x7fffffff;
// The three steps of mark_encroaching_points (CLM_ENCROACH_*).
constexpr cl_int kClaim = 0, kCount = 1, kWrite = 2;
} // namespace

HullEncroachment::HullEncroachment(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      mark_(device.kernel(kFile, "mark_encroaching_points", kPhase)),
      clear_claims_(device.kernel(kFile, "clear_encroaching_claims", kPhase)),
      mark_in_group_(device.kernel(kFile, "mark_encroaching_in_group", kPhase)),
      claim_(device, mesh.point_capacity), owned_(device, mesh.point_capacity),
      offset_(device, mesh.point_capacity), appended_(device, 1),
      group_(device.single_group(mark_in_group_, kPhase)) {}

void HullEncroachment::trim_lists() {
  owned_.discard(device_, new_points_, kPhase);
  offset_.discard(device_, new_points_, kPhase);
}

std::optional<std::size_t> HullEncroachment::mark_encroaching(
    const DeviceArray<cl_int> &new_points, std::size_t m, const DeviceArray<cl_int> &redundant_mark,
    const DeviceArray<cl_int> &redundant_anchor, const DeviceArray<cl_int> &tracked) {
  new_points_ = m;
  if (m == 0)
    return 0;
  // The claims of the points that came since the last call start empty.
  if (mesh_.point_count > claims_filled_) {
    const std::size_t end = fill_ahead(mesh_.point_count, mesh_.point_capacity);
    claim_.fill_range(device_, kNoClaim, claims_filled_, end - claims_filled_, kPhase);
    claims_filled_ = end;
  }
  const auto items = static_cast<cl_int>(m);
  if (m <= kInGroup) {
    set_args_from(mark_in_group_, mesh_.bind(mark_in_group_, 0), new_points.buffer(),
                  claim_.buffer(), redundant_mark.buffer(), redundant_anchor.buffer(),
                  owned_.buffer(), offset_.buffer(), tracked.buffer(),
                  cl::Local(sizeof(cl_int) * group_), appended_.buffer(), items);
    launch(device_, mark_in_group_, group_, kPhase, group_);
    return std::nullopt;
  }
  guarded(kPhase, "copying the new points", [&] {
    device_.queue().enqueueCopyBuffer(new_points.buffer(), tracked.buffer(), 0, 0,
                                      m * sizeof(cl_int));
  });
  auto run_step = [&](cl_int step) {
    set_args_from(mark_, mesh_.bind(mark_, 0), new_points.buffer(), step, claim_.buffer(),
                  redundant_mark.buffer(), redundant_anchor.buffer(), owned_.buffer(),
                  offset_.buffer(), tracked.buffer(), items, items);
    launch(device_, mark_, m, kPhase);
  };
  run_step(kClaim);
  run_step(kCount);
  const auto old = static_cast<std::size_t>(scan_.exclusive_scan(owned_, offset_, m, kPhase));
  if (old > 0)
    run_step(kWrite);
  // The claims go back to empty: those of the new points and of the old ones.
  const std::size_t claimed = m + old;
  set_args(clear_claims_, tracked.buffer(), claim_.buffer(), static_cast<cl_int>(claimed));
  launch(device_, clear_claims_, claimed, kPhase);
  return old;
}

} // namespace clmesh
