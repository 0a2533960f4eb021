// clmesh CLI — the devices a clmesh process meshes on: one for its small
// inputs, one for its large ones, as the library chooses them when nothing
// names a device (api/device_choice.hpp: on PoCL, its in-thread and
// multi-threaded drivers); otherwise the chosen device serves every input.
#pragma once

#include "clmesh/device.hpp"

#include <cstddef>
#include <memory>
#include <string>

namespace cli {

class DevicePool {
public:
  // Call before any OpenCL call. spec: --device's value ("" for none).
  explicit DevicePool(const std::string &spec);

  // Throws DeviceError when the chosen device does not exist or lacks fp64;
  // opens nothing.
  void check() const;

  // The device for an input of `size` (clmesh::input_size()), opened on
  // first use; `opened_seconds`: the time that choosing and opening it took
  // now (0 when it was open already).
  struct Lease {
    clmesh::Device &device;
    double opened_seconds;
  };
  Lease lease(std::size_t size);

private:
  std::string spec_;
  bool resolved_ = false;
  std::string small_spec_, large_spec_;
  std::shared_ptr<clmesh::Device> small_, large_;
};

} // namespace cli
