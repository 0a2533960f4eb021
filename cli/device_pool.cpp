// clmesh CLI — the devices of a clmesh process (device_pool.hpp).
#include "device_pool.hpp"

#include "api/device_choice.hpp"

#include <chrono>

namespace cli {

DevicePool::DevicePool(const std::string &spec, clmesh::Meshing meshing)
    : spec_(spec), meshing_(meshing) {
  clmesh::offer_pocl_drivers(spec_);
}

void DevicePool::check() const { clmesh::find_device(spec_); }

DevicePool::Lease DevicePool::lease(std::size_t size, unsigned stream) {
  const std::lock_guard<std::recursive_mutex> lock(mutex_);
  const auto start = std::chrono::steady_clock::now();
  if (!resolved_) {
    specs_ = clmesh::device_specs(spec_, meshing_);
    resolved_ = true;
  }
  // One device for every input: no second copy of it.
  const bool large =
      (specs_.large(size) || every_input_large_) && specs_.large_inputs != specs_.small_inputs;
  std::shared_ptr<clmesh::Device> &device = devices_[{large, stream}];
  if (device)
    return {*device, 0};
  if (stream == 0) {
    device = clmesh::open_device(large ? specs_.large_inputs : specs_.small_inputs);
  } else {
    const Lease opened = lease(size, 0); // the mutex is recursive
    device = clmesh::open_stream(opened.device);
  }
  return {*device, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

} // namespace cli
