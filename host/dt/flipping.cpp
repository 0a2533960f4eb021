#include "dt/flipping.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace clmesh {

namespace {
const char *kFile = "flipping.cl";
}

Flipping::Flipping(Device &device, DeviceMesh &mesh, std::size_t group_pass_limit)
    : device_(device), mesh_(mesh), group_pass_limit_(group_pass_limit),
      mark_active_(device.kernel(kFile, "flip_mark_active", kPhase)),
      check_fast_(device.kernel(kFile, "flip_check_fast", kPhase)),
      check_exact_(device.kernel(kFile, "flip_check_exact", kPhase)),
      apply_(device.kernel(kFile, "flip_apply", kPhase)),
      relink_and_collect_(device.kernel(kFile, "flip_relink_and_collect", kPhase)),
      passes_in_group_(device.kernel(kFile, "flip_passes_in_group", kPhase)),
      active_(device, mesh.list_capacity), next_active_(device, mesh.list_capacity),
      exact_list_(device, mesh.list_capacity), proposal_(device, mesh.list_capacity),
      exact_count_(device, 1), flags_(device, mesh.list_capacity), pass_counts_(device, 2),
      active_round_(device, mesh.triangle_capacity), group_result_(device, 4) {
  passes_group_limit_ = guarded(kPhase, "querying the work-group size", [&] {
    return passes_in_group_.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device.cl_device());
  });
}

void Flipping::mark_active(const DeviceArray<cl_int> &active, std::size_t n) {
  set_args(mark_active_, active.buffer(), active_round_.array.buffer(), ++round_,
           static_cast<cl_int>(n));
  launch(device_, mark_active_, n, kPhase);
}

void Flipping::propose(std::size_t n, cl_int *uncertain) {
  const auto items = static_cast<cl_int>(n);
  exact_count_.fill(device_, 0, 1);
  set_args_from(check_fast_, mesh_.bind_triangulation(check_fast_, 0), active_.buffer(),
                static_cast<cl_int>(fixed_boundary_), active_round_.array.buffer(), round_,
                flags_.buffer(), exact_list_.buffer(), exact_count_.buffer(), proposal_.buffer(),
                items);
  launch(device_, check_fast_, n, kPhase);
  exact_count_.download_later(device_, uncertain, 1);
  set_args_from(check_exact_, mesh_.bind_triangulation(check_exact_, 0), exact_list_.buffer(),
                active_.buffer(), flags_.buffer(), proposal_.buffer(), exact_count_.buffer());
  launch(device_, check_exact_, sharing_items(device_, n), kPhase);
}

void Flipping::trim_lists() {
  for (const DeviceArray<cl_int> *list :
       {&active_, &next_active_, &exact_list_, &proposal_, &flags_})
    list->discard(device_, 0, kPhase);
}

bool Flipping::run(const DeviceArray<cl_int> &active, std::size_t n, int &stamp, FlipCounts &counts,
                   long max_passes) {
  if (n == 0)
    return true;
  active_round_.cover(device_, mesh_.triangle_count, kPhase);
  guarded(kPhase, "copying the active list", [&] {
    device_.queue().enqueueCopyBuffer(active.buffer(), active_.buffer(), 0, 0, n * sizeof(cl_int));
  });
  mark_active(active_, n); // later lists are marked as they are collected
  for (long pass = 0; n > 0; ++pass) {
    if (pass == max_passes)
      return false;
    // The next list may be twice as long: both lists must hold it.
    const std::size_t limit = std::min(group_pass_limit_, active_.size() / 2);
    if (n <= limit) {
      const std::size_t group = std::min(device_.work_group(), passes_group_limit_);
      const long left = max_passes < 0 ? std::numeric_limits<cl_int>::max() : max_passes - pass;
      set_args_from(passes_in_group_, mesh_.bind_triangulation(passes_in_group_, 0),
                    active_.buffer(), next_active_.buffer(), static_cast<cl_int>(n),
                    static_cast<cl_int>(fixed_boundary_), active_round_.array.buffer(), round_,
                    proposal_.buffer(), flags_.buffer(), static_cast<cl_int>(stamp),
                    static_cast<cl_int>(limit), static_cast<cl_int>(left), group_result_.buffer());
      launch(device_, passes_in_group_, group, kPhase, group);
      const std::vector<cl_int> result = group_result_.download(device_, 4);
      stamp += result[0];
      round_ += result[0];
      pass += result[0] - 1; // the loop adds the last one
      counts.passes += result[0];
      counts.flips += result[1];
      counts.exact_checks += result[3];
      if (result[0] % 2)
        std::swap(active_, next_active_);
      n = static_cast<std::size_t>(result[2]);
      continue;
    }
    const auto items = static_cast<cl_int>(n);
    const auto pass_stamp = static_cast<cl_int>(stamp++);
    pass_counts_.fill(device_, 0, 2);
    cl_int uncertain = 0;
    propose(n, &uncertain);
    set_args_from(apply_, mesh_.bind_triangulation(apply_, 0), active_.buffer(), proposal_.buffer(),
                  flags_.buffer(), pass_counts_.buffer(), pass_stamp, items);
    launch(device_, apply_, n, kPhase);
    set_args_from(relink_and_collect_, mesh_.bind_triangulation(relink_and_collect_, 0),
                  active_.buffer(), proposal_.buffer(), flags_.buffer(), pass_stamp,
                  next_active_.buffer(), active_round_.array.buffer(), round_ + 1,
                  pass_counts_.buffer(), items);
    launch(device_, relink_and_collect_, n, kPhase);
    const std::vector<cl_int> pass_counts = pass_counts_.download(device_, 2);
    counts.exact_checks += uncertain;
    ++round_;
    counts.flips += pass_counts[0];
    ++counts.passes;
    std::swap(active_, next_active_);
    n = static_cast<std::size_t>(pass_counts[1]);
  }
  return true;
}

} // namespace clmesh
