// clmesh CLI — the devices of a clmesh process (device_pool.hpp).
#include "device_pool.hpp"

#include <chrono>
#include <cstdlib>

namespace cli {
namespace {

bool starts_with(const std::string &text, const char *prefix) { return text.rfind(prefix, 0) == 0; }

std::string platform_and_device(const clmesh::DeviceDescription &description) {
  return std::to_string(description.platform_index) + ":" +
         std::to_string(description.device_index);
}

} // namespace

DevicePool::DevicePool(const std::string &spec) : spec_(spec) {
  const char *chosen = std::getenv("CLMESH_DEVICE");
  if (spec_.empty() && !(chosen && *chosen) && !std::getenv("POCL_DEVICES"))
    pocl_drivers_ = ::setenv("POCL_DEVICES", "pthread basic", 0) == 0;
}

void DevicePool::check() const { clmesh::find_device(spec_); }

void DevicePool::resolve() {
  resolved_ = true;
  small_spec_ = large_spec_ = spec_;
  if (!pocl_drivers_)
    return;
  const clmesh::DeviceDescription chosen = clmesh::find_device(spec_);
  if (chosen.platform_name != "Portable Computing Language")
    return; // a GPU (or another CPU platform) comes first: it serves every input
  std::string in_thread, multi_threaded;
  for (const clmesh::DeviceDescription &device : clmesh::list_devices()) {
    if (device.platform_index != chosen.platform_index || !device.has_fp64)
      continue;
    if (starts_with(device.device_name, "basic") && in_thread.empty())
      in_thread = platform_and_device(device);
    else if (starts_with(device.device_name, "pthread") && multi_threaded.empty())
      multi_threaded = platform_and_device(device);
  }
  if (!in_thread.empty() && !multi_threaded.empty()) {
    small_spec_ = in_thread;
    large_spec_ = multi_threaded;
  }
}

DevicePool::Lease DevicePool::lease(std::size_t size) {
  const auto start = std::chrono::steady_clock::now();
  if (!resolved_)
    resolve();
  // One device for every input: no second copy of it.
  const bool small = size < kLargeInput || large_spec_ == small_spec_;
  std::shared_ptr<clmesh::Device> &device = small ? small_ : large_;
  if (device)
    return {*device, 0};
  device = clmesh::open_device(small ? small_spec_ : large_spec_);
  return {*device, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

} // namespace cli
