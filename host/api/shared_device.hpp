// clmesh — the process's shared devices: each OpenCL device opened once, on
// the first call that names it, and used by one call at a time.
#pragma once

#include "api/device_choice.hpp"
#include "clmesh/device.hpp"
#include "clmesh/input.hpp"
#include "clmesh/options.hpp"

#include <memory>
#include <mutex>
#include <string>

namespace clmesh {

// A device every call naming it shares; `busy` is held while one meshes on it.
struct SharedDevice {
  std::shared_ptr<Device> device;
  std::mutex busy;
};

// The shared device `spec` names (as open_device(spec) would find it), opened
// on first use; two specs naming the same device share it. Throws DeviceError.
std::shared_ptr<SharedDevice> shared_device(const std::string &spec);

// The shared device for `input` meshed with `options`: of the devices
// device_specs(options.device, meshing) gives, the one for its size
// (device_choice.hpp). The process's first call asks PoCL for its drivers.
std::shared_ptr<SharedDevice> shared_device_for(const Input &input, const Options &options,
                                                Meshing meshing);

} // namespace clmesh
