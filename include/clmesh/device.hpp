// clmesh — choosing an OpenCL device.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace clmesh {

struct DeviceDescription {
  int platform_index = 0;
  int device_index = 0;
  std::string platform_name;
  std::string device_name;
  std::string version;
  bool has_fp64 = false;
  bool is_cpu = false; // CL_DEVICE_TYPE_CPU
};

// Every OpenCL device visible through the ICD loader.
std::vector<DeviceDescription> list_devices();

class Device;
// Opens a device. spec: "" (the CLMESH_DEVICE environment variable, else the
// first device with fp64), "P:D" (platform and device index), "N" (the N-th
// device in list order) or a case-insensitive substring of "platform device".
// Throws DeviceError when nothing matches or the device lacks cl_khr_fp64.
std::shared_ptr<Device> open_device(const std::string &spec = "");
// A stream of an open device: a second command queue on its context,
// sharing its built programs. Two threads may mesh at once, each on a stream
// of its own (a Device is used by one thread at a time); on a GPU their
// launches then overlap, as those of two processes (two contexts, which the
// GPU takes in turns) do not. On PoCL the streams take turns, one mesh at
// a time: its cache of loaded kernels is not safe for two threads
// submitting at once. Throws DeviceError for PoCL's in-thread driver
// ('basic'), whose kernels run on the waiting thread.
std::shared_ptr<Device> open_stream(Device &device);
// The device open_device(spec) opens, without opening it. Throws DeviceError
// as open_device() does.
DeviceDescription find_device(const std::string &spec = "");

// Human-readable "device name (platform name)".
std::string describe(const Device &device);

// The largest work-group size the device accepts (DelaunayOptions::work_group).
std::size_t max_work_group_size(const Device &device);

} // namespace clmesh
