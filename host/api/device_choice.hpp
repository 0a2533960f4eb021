// clmesh — which device meshes an input when the caller chose none.
//
// When nothing chose the device (no spec, neither CLMESH_DEVICE nor
// POCL_DEVICES set), clmesh asks PoCL, before the process's first OpenCL
// call, for its multi-threaded CPU driver ("pthread") and its in-thread
// driver ("basic"). If PoCL then gives the default device, small inputs
// run on the in-thread device: the kernels run in the thread that launches
// them, so the hundreds of launches of a small mesh cost no hand-offs to
// PoCL's threads (a 500-vertex coastline with -pq30 meshes about 5x
// faster). Larger inputs run on the multi-threaded device. In a batch, whose
// worker processes keep every CPU busy, an input is small below
// kLargeInBatch; meshed alone, below kLargeAlone, about where the
// multi-threaded device overtakes on two CPUs (a coastline of 20,000
// vertices, -pq30) and sooner on more.
//
// In a batch, if a GPU gives the default device and PoCL is there too, small
// inputs run on PoCL's in-thread device and larger ones on the GPU: a small
// mesh's hundreds of launches and reads each cost a round trip to the GPU's
// driver (on an H200, 2000 coastlines took 17 times the native Triangle's
// time), while a batch's worker processes mesh small inputs on every CPU at
// once. An input meshed alone keeps the GPU: PoCL's in-thread device would
// give it one core, and where that beats the GPU is not measured.
//
// Every device gives the same mesh. Otherwise (another CPU platform first, a
// device or POCL_DEVICES chosen, or OpenCL already started without the
// request) the default device serves every input.
#pragma once

#include "clmesh/device.hpp"
#include "clmesh/input.hpp"
#include "clmesh/options.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace clmesh {

// Inputs of at least this size (input_size) run on the large inputs' device.
constexpr std::size_t kLargeInBatch = 100000, kLargeAlone = 30000;

// An input's size as the choice weighs it: points, segments and triangles,
// and with -a about the points the area bound asks for (the bounding box's
// area over the bound).
std::size_t input_size(const Input &input, const Options &options);

// Sets POCL_DEVICES to "pthread basic" when `spec` is "" and neither
// CLMESH_DEVICE nor POCL_DEVICES is set. PoCL reads it at the process's first
// OpenCL call: afterwards it changes nothing.
void offer_pocl_drivers(const std::string &spec);

// What the devices are chosen for: one input at a time, or a batch of them.
enum class Meshing { one_input, batch };

// The specs (as open_device() takes them) of the devices for small and large
// inputs: when `spec` is "", CLMESH_DEVICE is unset and POCL_DEVICES is
// "pthread basic", choose_devices() over the devices found; else `spec` for
// both. Throws DeviceError as find_device().
struct DeviceSpecs {
  std::string small_inputs, large_inputs;
  std::size_t large_from = kLargeInBatch; // the size from which an input is large
  bool large(std::size_t size) const { return size >= large_from; }
  const std::string &for_size(std::size_t size) const {
    return large(size) ? large_inputs : small_inputs;
  }
};
DeviceSpecs device_specs(const std::string &spec, Meshing meshing);

// The choice itself, `chosen` being the default device among `devices`:
// PoCL's in-thread and multi-threaded devices when PoCL gives the default
// device; for a batch, PoCL's in-thread device and `spec` when a device that
// is not a CPU does; else `spec` for both (also when PoCL lacks one of its
// devices).
DeviceSpecs choose_devices(const std::vector<DeviceDescription> &devices,
                           const DeviceDescription &chosen, const std::string &spec,
                           Meshing meshing);

// Whether processes would only take turns on the device a batch's small
// inputs get (device_specs), or with every_input_large (a batch on streams
// puts every input on the large inputs' device) on that one: any device but
// a CPU (a GPU runs one process's kernels at a time, switching between
// them), or any device with CLMESH_DEVICE_PATHS=gpu. A batch on such a
// device is meshed by one worker process (cli). Throws DeviceError as
// find_device().
bool device_taken_in_turns(const std::string &spec, bool every_input_large);

} // namespace clmesh
