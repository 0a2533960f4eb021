#include "flipping.hpp"

#include <utility>

namespace clmesh {

namespace {
const char *kFile = "flipping.cl";
}

Flipping::Flipping(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      mark_active_(device.kernel(kFile, "flip_mark_active", kPhase)),
      check_fast_(device.kernel(kFile, "flip_check_fast", kPhase)),
      check_exact_(device.kernel(kFile, "flip_check_exact", kPhase)),
      propose_(device.kernel(kFile, "flip_propose", kPhase)),
      apply_(device.kernel(kFile, "flip_apply", kPhase)),
      relink_(device.kernel(kFile, "flip_relink", kPhase)),
      count_next_(device.kernel(kFile, "flip_count_next", kPhase)),
      clear_marks_(device.kernel(kFile, "flip_clear_marks", kPhase)),
      gather_next_(device.kernel(kFile, "flip_gather_next", kPhase)),
      active_(device, mesh.list_capacity), next_active_(device, mesh.list_capacity),
      flags_(device, mesh.list_capacity), exact_list_(device, mesh.list_capacity),
      proposal_(device, mesh.list_capacity), flipped_(device, mesh.list_capacity),
      count_(device, mesh.list_capacity), offset_(device, mesh.list_capacity),
      exact_count_(device, 1), flip_count_(device, 1),
      active_round_(device, mesh.triangle_capacity) {
  flip_count_.fill(device_, 0, 1);
  active_round_.fill(device_, 0, mesh.triangle_capacity);
}

void Flipping::check(const DeviceArray<cl_int> &active, std::size_t n,
                     const DeviceArray<cl_int> &flags, FlipCounts &counts) {
  const auto items = static_cast<cl_int>(n);
  exact_count_.fill(device_, 0, 1);
  const cl_int round = ++round_;
  set_args(mark_active_, active.buffer(), active_round_.buffer(), round, items);
  launch(device_, mark_active_, n, kPhase);
  set_args(check_fast_, active.buffer(), mesh_.points.buffer(), mesh_.tri_vertex.buffer(),
           mesh_.tri_neighbor.buffer(), mesh_.constraint_start.buffer(),
           mesh_.constraint_adjacent.buffer(), static_cast<cl_int>(mesh_.has_constraints),
           static_cast<cl_int>(fixed_boundary_), active_round_.buffer(), round, flags.buffer(),
           exact_list_.buffer(), exact_count_.buffer(), items);
  launch(device_, check_fast_, n, kPhase);
  const int uncertain = exact_count_.read(device_, 0);
  if (uncertain > 0) {
    counts.exact_checks += uncertain;
    set_args(check_exact_, exact_list_.buffer(), active.buffer(), mesh_.points.buffer(),
             mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(), flags.buffer(),
             static_cast<cl_int>(uncertain));
    launch(device_, check_exact_, static_cast<std::size_t>(uncertain), kPhase);
  }
}

bool Flipping::run(const DeviceArray<cl_int> &active, std::size_t n, int &stamp, FlipCounts &counts,
                   long max_passes) {
  if (n == 0)
    return true;
  guarded(kPhase, "copying the active list", [&] {
    device_.queue().enqueueCopyBuffer(active.buffer(), active_.buffer(), 0, 0, n * sizeof(cl_int));
  });
  for (long pass = 0; n > 0; ++pass) {
    if (pass == max_passes)
      return false;
    const auto items = static_cast<cl_int>(n);
    const auto pass_stamp = static_cast<cl_int>(stamp++);
    check(active_, n, flags_, counts);
    set_args(propose_, active_.buffer(), flags_.buffer(), mesh_.tri_neighbor.buffer(),
             mesh_.tri_mark.buffer(), proposal_.buffer(), items);
    launch(device_, propose_, n, kPhase);
    set_args(apply_, active_.buffer(), proposal_.buffer(), mesh_.tri_mark.buffer(),
             mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(), mesh_.modified_stamp.buffer(),
             mesh_.children.buffer(), flipped_.buffer(), flip_count_.buffer(), pass_stamp, items);
    launch(device_, apply_, n, kPhase);
    set_args(relink_, active_.buffer(), proposal_.buffer(), flipped_.buffer(),
             mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(), mesh_.modified_stamp.buffer(),
             mesh_.children.buffer(), pass_stamp, items);
    launch(device_, relink_, n, kPhase);
    set_args(count_next_, active_.buffer(), proposal_.buffer(), flipped_.buffer(),
             mesh_.modified_stamp.buffer(), count_.buffer(), pass_stamp, items);
    launch(device_, count_next_, n, kPhase);
    set_args(clear_marks_, active_.buffer(), proposal_.buffer(), mesh_.tri_mark.buffer(), items);
    launch(device_, clear_marks_, n, kPhase);
    const int next = scan_.exclusive_scan(count_, offset_, n, kPhase);
    set_args(gather_next_, active_.buffer(), proposal_.buffer(), flipped_.buffer(), count_.buffer(),
             offset_.buffer(), next_active_.buffer(), items);
    launch(device_, gather_next_, n, kPhase);
    counts.flips += flip_count_.read(device_, 0);
    flip_count_.fill(device_, 0, 1);
    ++counts.passes;
    std::swap(active_, next_active_);
    n = static_cast<std::size_t>(next);
  }
  return true;
}

} // namespace clmesh
