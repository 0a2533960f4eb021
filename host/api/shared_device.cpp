// clmesh — the process's shared devices (see shared_device.hpp).
#include "api/shared_device.hpp"

#include "api/device_choice.hpp"

#include <map>
#include <utility>

namespace clmesh {

std::shared_ptr<SharedDevice> shared_device(const std::string &spec) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<SharedDevice>> by_spec;
  static std::map<std::pair<int, int>, std::shared_ptr<SharedDevice>> by_device;
  std::lock_guard<std::mutex> lock(mutex);
  std::shared_ptr<SharedDevice> &slot = by_spec[spec];
  if (!slot) {
    const DeviceDescription found = find_device(spec);
    std::shared_ptr<SharedDevice> &device = by_device[{found.platform_index, found.device_index}];
    if (!device) {
      auto opened = std::make_shared<SharedDevice>();
      opened->device = open_device(std::to_string(found.platform_index) + ":" +
                                   std::to_string(found.device_index));
      device = opened;
    }
    slot = device;
  }
  return slot;
}

std::shared_ptr<SharedDevice> shared_device_for(const Input &input, const Options &options,
                                                Meshing meshing) {
  static std::mutex mutex;
  static std::map<std::pair<std::string, Meshing>, DeviceSpecs> specs_of;
  DeviceSpecs specs;
  {
    std::lock_guard<std::mutex> lock(mutex);
    const std::pair<std::string, Meshing> key{options.device, meshing};
    auto found = specs_of.find(key);
    if (found == specs_of.end()) {
      offer_pocl_drivers(options.device);
      found = specs_of.emplace(key, device_specs(options.device, meshing)).first;
    }
    specs = found->second;
  }
  return shared_device(specs.for_size(input_size(input, options)));
}

} // namespace clmesh
