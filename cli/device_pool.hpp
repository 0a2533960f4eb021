// clmesh CLI — the devices a clmesh process meshes on: one for its small
// inputs, one for its large ones, as the library chooses them when nothing
// names a device (api/device_choice.hpp: on PoCL, its in-thread and
// multi-threaded drivers; in a batch with a GPU first, PoCL's in-thread
// driver and the GPU); otherwise the chosen device serves every input.
// Each stream (a thread meshing inputs at once with others) has a command
// queue of its own on each device (clmesh::open_stream).
#pragma once

#include "api/device_choice.hpp"
#include "clmesh/device.hpp"

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

namespace cli {

class DevicePool {
public:
  // Call before any OpenCL call. spec: --device's value ("" for none);
  // meshing: one input or a batch (clmesh::device_specs).
  DevicePool(const std::string &spec, clmesh::Meshing meshing);

  // Throws DeviceError when the chosen device does not exist or lacks fp64;
  // opens nothing.
  void check() const;

  // The device for an input of `size` (clmesh::input_size()) as stream
  // `stream` has it, opened on first use; `opened_seconds`: the time that
  // choosing and opening it took now (0 when it was open already). Streams
  // may call it at once.
  struct Lease {
    clmesh::Device &device;
    double opened_seconds;
  };
  Lease lease(std::size_t size, unsigned stream = 0);

  // Before any lease: every input takes the device for large inputs. For
  // streams, which lease at once: PoCL's in-thread driver runs kernels on the
  // calling thread, and its cache of loaded kernels is not safe for two
  // threads at once. For packs: they are for the GPU that a batch's small
  // inputs would otherwise leave (device_specs). Where nothing chose two
  // devices, the two are one.
  void take_every_input_as_large() { every_input_large_ = true; }

private:
  std::string spec_;
  clmesh::Meshing meshing_;
  std::recursive_mutex mutex_;
  bool resolved_ = false;
  bool every_input_large_ = false;
  clmesh::DeviceSpecs specs_; // resolved on the first lease
  // By (large, stream): stream 0 the device as opened, the others its streams.
  std::map<std::pair<bool, unsigned>, std::shared_ptr<clmesh::Device>> devices_;
};

} // namespace cli
