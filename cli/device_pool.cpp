// clmesh CLI — the devices of a clmesh process (device_pool.hpp).
#include "device_pool.hpp"

#include "api/device_choice.hpp"

#include <chrono>

namespace cli {

DevicePool::DevicePool(const std::string &spec) : spec_(spec) { clmesh::offer_pocl_drivers(spec_); }

void DevicePool::check() const { clmesh::find_device(spec_); }

DevicePool::Lease DevicePool::lease(std::size_t size) {
  const auto start = std::chrono::steady_clock::now();
  if (!resolved_) {
    const clmesh::DeviceSpecs specs = clmesh::device_specs(spec_);
    small_spec_ = specs.small_inputs;
    large_spec_ = specs.large_inputs;
    resolved_ = true;
  }
  // One device for every input: no second copy of it.
  const bool small = size < clmesh::kLargeInput || large_spec_ == small_spec_;
  std::shared_ptr<clmesh::Device> &device = small ? small_ : large_;
  if (device)
    return {*device, 0};
  device = clmesh::open_device(small ? small_spec_ : large_spec_);
  return {*device, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

} // namespace cli
