// clmesh — the device for an input when the caller chose none
// (device_choice.hpp).
#include "api/device_choice.hpp"

#include "clmesh/device.hpp"
#include "runtime/opencl_context.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace clmesh {
namespace {

constexpr const char *kPoclDrivers = "pthread basic";
constexpr const char *kPocl = "Portable Computing Language";

bool device_chosen(const std::string &spec) {
  const char *chosen = std::getenv("CLMESH_DEVICE");
  return !spec.empty() || (chosen && *chosen);
}

bool starts_with(const std::string &text, const char *prefix) { return text.rfind(prefix, 0) == 0; }

std::string platform_and_device(const DeviceDescription &description) {
  return std::to_string(description.platform_index) + ":" +
         std::to_string(description.device_index);
}

} // namespace

std::size_t input_size(const Input &input, const Options &options) {
  double size =
      static_cast<double>(input.points.size() + input.segments.size() + input.triangles.size());
  if (options.max_area && *options.max_area > 0 && !input.points.empty()) {
    Point low = input.points[0], high = input.points[0];
    for (const Point &p : input.points) {
      low = {std::min(low.x, p.x), std::min(low.y, p.y)};
      high = {std::max(high.x, p.x), std::max(high.y, p.y)};
    }
    size += (high.x - low.x) * (high.y - low.y) / *options.max_area;
  }
  return size < 1e18 ? static_cast<std::size_t>(size) : static_cast<std::size_t>(1e18);
}

void offer_pocl_drivers(const std::string &spec) {
  if (!device_chosen(spec) && !std::getenv("POCL_DEVICES"))
    ::setenv("POCL_DEVICES", kPoclDrivers, 0);
}

DeviceSpecs choose_devices(const std::vector<DeviceDescription> &devices,
                           const DeviceDescription &chosen, const std::string &spec,
                           Meshing meshing) {
  // PoCL's CPU drivers by their devices' names: "basic" and "pthread" up to
  // PoCL 4, "cpu-minimal" and "cpu" since.
  std::string in_thread, multi_threaded;
  for (const DeviceDescription &device : devices) {
    if (device.platform_name != kPocl || !device.is_cpu || !device.has_fp64)
      continue;
    const bool minimal =
        starts_with(device.device_name, "basic") || starts_with(device.device_name, "cpu-minimal");
    const bool threaded = !minimal && (starts_with(device.device_name, "pthread") ||
                                       starts_with(device.device_name, "cpu"));
    if (minimal && in_thread.empty())
      in_thread = platform_and_device(device);
    else if (threaded && multi_threaded.empty())
      multi_threaded = platform_and_device(device);
  }
  const std::size_t large_from = meshing == Meshing::batch ? kLargeInBatch : kLargeAlone;
  if (chosen.platform_name == kPocl) {
    if (in_thread.empty() || multi_threaded.empty())
      return {spec, spec}; // OpenCL started before the request
    return {in_thread, multi_threaded, large_from};
  }
  // A GPU first, in a batch: small inputs on the CPU's in-thread device,
  // whose kernels run without a round trip to the GPU's driver each.
  if (meshing == Meshing::batch && !chosen.is_cpu && !in_thread.empty())
    return {in_thread, spec, large_from};
  return {spec, spec}; // the default device serves every input
}

DeviceSpecs device_specs(const std::string &spec, Meshing meshing) {
  const char *drivers = std::getenv("POCL_DEVICES");
  if (device_chosen(spec) || !drivers || std::strcmp(drivers, kPoclDrivers) != 0)
    return {spec, spec};
  return choose_devices(list_devices(), find_device(spec), spec, meshing);
}

bool device_taken_in_turns(const std::string &spec, bool every_input_large) {
  switch (device_paths_from_environment()) {
  case DevicePaths::gpu:
    return true;
  case DevicePaths::cpu:
    return false;
  case DevicePaths::by_type:
    break;
  }
  // Small inputs on a CPU (choose_devices) take the CPU's workers.
  const DeviceSpecs specs = device_specs(spec, Meshing::batch);
  return !find_device(every_input_large ? specs.large_inputs : specs.small_inputs).is_cpu;
}

} // namespace clmesh
