// clmesh CLI — the devices a clmesh process meshes on: one for its small
// inputs, one for its large ones.
//
// When the user chose neither a device (--device, CLMESH_DEVICE) nor PoCL's
// drivers (POCL_DEVICES), clmesh asks PoCL for its multi-threaded CPU driver
// ("pthread") and its in-thread driver ("basic"), before any OpenCL call.
// If PoCL then gives the default device, small inputs run on the in-thread
// device: the kernels run in the thread that launches them, so the hundreds
// of launches of a small mesh cost no hand-offs to PoCL's threads (a
// 500-vertex coastline with -pq30 meshes about 5x faster). Large inputs run
// on the multi-threaded device. Every device gives the same mesh.
// Otherwise (a GPU first, or the user's choice) the chosen device serves all.
#pragma once

#include "clmesh/device.hpp"

#include <cstddef>
#include <memory>
#include <string>

namespace cli {

// Inputs of at least this size (points, segments and triangles read, and
// with -a about the points the area bound asks for) run on the
// multi-threaded device.
constexpr std::size_t kLargeInput = 100000;

class DevicePool {
public:
  // Call before any OpenCL call. spec: --device's value ("" for none).
  explicit DevicePool(const std::string &spec);

  // Throws DeviceError when the chosen device does not exist or lacks fp64;
  // opens nothing.
  void check() const;

  // The device for an input of `size`; `opened_seconds`: the time that
  // opening it took now (0 when it was open already).
  struct Lease {
    clmesh::Device &device;
    double opened_seconds;
  };
  Lease lease(std::size_t size);

private:
  void resolve();

  std::string spec_;
  bool pocl_drivers_ = false; // POCL_DEVICES was set by clmesh
  bool resolved_ = false;
  // The specs of the two devices, equal unless PoCL gives the default device.
  std::string small_spec_, large_spec_;
  std::shared_ptr<clmesh::Device> small_, large_;
};

} // namespace cli
