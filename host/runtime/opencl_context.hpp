// clmesh — the OpenCL device: context, queue, program building and launching.
#pragma once

#include "clmesh/device.hpp"
#include "clmesh/errors.hpp"
#include "runtime/buffer_slabs.hpp"
#include "runtime/program_cache.hpp"

#include <CL/opencl.hpp>

#include <chrono>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace clmesh {

namespace detail {
// Kernel sources embedded at build time (cmake/embed_kernels.cmake).
const char *embedded_source(const char *name);
} // namespace detail

// Which device-type-specific code paths a Device takes: a CPU's (kernels
// that prefetch, large buffers in host memory the device uses in place,
// scans by runs) or a GPU's (none of these). by_type: the device's own type.
// The meshes are the same either way; forcing them tests the GPU paths on a
// CPU device (and the other way round).
enum class DevicePaths { by_type, cpu, gpu };

// The paths asked for by the CLMESH_DEVICE_PATHS environment variable:
// "gpu", "cpu", or unset/empty/"auto" for by_type. Throws OptionError for
// anything else.
DevicePaths device_paths_from_environment();

class MappingPool; // small mappings kept for reuse (opencl_context.cpp)

// The programs built for one context, shared by the Devices on it (its
// streams): each program is built once, whichever stream asks first.
struct BuiltPrograms {
  std::recursive_mutex mutex; // the predicate check builds within a build
  std::map<std::string, cl::Program> by_key;
  bool predicates_checked = false; // check_device_predicates() has run
};

class Device {
public:
  // paths: by default from CLMESH_DEVICE_PATHS (open_device() takes that).
  Device(cl::Device device, DeviceDescription description,
         DevicePaths paths = device_paths_from_environment());
  // A stream of `device` (open_stream()): its own command queue on the same
  // context, sharing its built programs and settings; its own kernels, fill
  // kernel and kept mappings, so that each is used by one thread.
  struct Stream {};
  Device(Stream, Device &device);

  const DeviceDescription &description() const { return description_; }
  cl::Context &context() { return context_; }
  const cl::Device &cl_device() const { return device_; }
  cl::CommandQueue &queue() { return queue_; }
  // Waits until the device has done everything queued (`phase` names a failure).
  void wait(const std::string &phase);

  // Builds (once per device) the program made of `file` with its
  // `#include "x.h"` lines expanded, without fast-math or mad options.
  // Sources come from CLMESH_KERNEL_DIR when set, else from the embedded copies.
  // Binaries are kept between runs (program_cache.hpp).
  cl::Program &program(const std::string &file, const std::string &phase);
  // The program cache's entry for a result that `file`'s program, as this
  // device builds it now, gives for `question` (the predicate check's
  // verdict): keyed by the source, the build options, the device and driver.
  ProgramCache result_cache(const std::string &file, const std::string &question) const;
  cl::Kernel kernel(const std::string &file, const std::string &name, const std::string &phase);

  // Software prefetching (cl/prefetch.h, PoCL's CPU devices) pays only once
  // a mesh outgrows the caches; below that its loads cost more than the
  // misses they save. Programs (and kernels) made after this call are built
  // with prefetching when `points`, the mesh's point capacity, reaches
  // `from` (Tuning::prefetch_from); each variant is built and cached apart.
  void fit_prefetching(std::size_t points, std::size_t from);

  // A read-write buffer of `bytes`. On the CPU paths one of 64 KiB or more
  // lives in a mapping of its own that the device uses in place, unmapped
  // when the buffer goes. With `huge_pages` (the mesh's arrays, read at
  // random all along), one of 2 MiB or more is aligned to 2 MiB with
  // transparent huge pages asked for: the random accesses then miss the TLB
  // far less often. Lists and scratch arrays go without: used in part, a
  // huge page would hold 2 MiB for the few entries written in it. On the
  // GPU paths one of at most 1 MiB is a piece of a slab (buffer_slabs.hpp).
  cl::Buffer allocate(std::size_t bytes, bool huge_pages = false);
  // Sets `bytes` bytes of `buffer` from byte `offset` on to copies of the
  // `pattern_size`-byte `pattern` (4, 8 or 16 bytes; offset and bytes whole
  // elements), in parallel (cl/fill.cl); the pattern repeats from the
  // buffer's start.
  void fill(const cl::Buffer &buffer, const void *pattern, std::size_t pattern_size,
            std::size_t offset, std::size_t bytes, const std::string &phase);
  // Gives the pages of bytes [offset, offset + bytes) of `buffer` back to the
  // system, once the device is done with everything queued: a scratch list's
  // contents are lost, and its memory comes back (zeroed) when written
  // again. Only for a buffer in a mapping of its own (allocate, on the CPU
  // paths), only whole pages, and only 1 MiB of them or more (fewer are not
  // worth a wait); elsewhere nothing happens.
  void discard(const cl::Buffer &buffer, std::size_t offset, std::size_t bytes,
               const std::string &phase);

  // Work-group size used for every launch (results never depend on it).
  std::size_t work_group() const { return work_group_; }
  // The size a run gets when its options name none: 64, or CLMESH_WORK_GROUP.
  std::size_t default_work_group() const { return default_work_group_; }
  // work_group() within `kernel`'s own limit (CL_KERNEL_WORK_GROUP_SIZE: a
  // GPU refuses a group whose registers its multiprocessor cannot hold).
  std::size_t fitting_group(const cl::Kernel &kernel, const std::string &phase) const;
  // The work-group size of `kernel` launched as one work-group (a short
  // step in one launch, barriers between its parts): one work-item on the
  // CPU paths, whose work-items run in turn (each barrier would cost a loop
  // over the group for nothing), else work_group() within the kernel's own
  // limit. Results never depend on it.
  std::size_t single_group(const cl::Kernel &kernel, const std::string &phase) const;
  void set_work_group(std::size_t size);
  std::size_t max_work_group() const;
  std::size_t compute_units() const;
  // Whether this device takes the CPU paths (DevicePaths): true for a CPU
  // device unless CLMESH_DEVICE_PATHS or the constructor said otherwise.
  bool cpu_paths() const { return cpu_paths_; }
  // Whether open_stream() takes this device: all but PoCL's in-thread
  // driver, whose kernels run on the waiting thread.
  bool takes_streams() const;
  // Held while a mesh is made on this device or one of its streams, where
  // the streams take turns: on PoCL, whose cache of loaded kernels is not
  // safe for two threads submitting at once (PoCL 3.1 aborts in
  // pocl_release_dlhandle_cache); elsewhere an empty lock (the streams
  // overlap).
  std::unique_lock<std::mutex> take_turn() const {
    return turns_ ? std::unique_lock<std::mutex>(*turns_) : std::unique_lock<std::mutex>();
  }
  // CL_DEVICE_MAX_MEM_ALLOC_SIZE, in bytes.
  std::size_t max_allocation() const;
  // CL_DEVICE_GLOBAL_MEM_SIZE, in bytes; for a device whose memory is the
  // host's (a CPU, an integrated GPU) no more than this process could hold
  // now (host_memory_for_process()), which other processes' use lowers.
  std::size_t global_memory() const;

private:
  // The options programs are built with now (prefetching or not).
  std::string options_now() const;

  cl::Device device_;
  DeviceDescription description_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::size_t work_group_ = 64;
  std::size_t default_work_group_ = 64;
  std::shared_ptr<BuiltPrograms> programs_;
  std::shared_ptr<std::mutex> turns_; // take_turn(): PoCL's devices only, shared with the streams
  cl::Kernel fill_words_;             // created on the first fill
  std::string build_identity_;        // platform, device and driver, for the program cache
  bool cpu_paths_ = false;
  bool can_prefetch_ = false; // a CPU device of PoCL's (cl/prefetch.h)
  bool prefetching_ = true;   // programs made now prefetch (when they can)
  std::string build_options_ = "-cl-std=CL1.2";
  std::shared_ptr<MappingPool> mapping_pool_;
  // The GPU paths' small buffers (null on the CPU paths): each stream has
  // its own slabs, whose pieces only its queue uses.
  std::shared_ptr<BufferSlabs> slabs_;
  std::size_t slab_alignment_ = 0, slab_bytes_ = 0;
};

// Source text of a kernel file with its includes expanded.
std::string kernel_source(const std::string &file);

// Work-items for a kernel that shares a list whose length only the device
// knows (at most `most` entries), each work-item taking its share of it
// (cl/common.h share_of): saves the round trip that reading the length would
// cost. On the GPU paths one an entry (those past the length stop at once),
// on the CPU paths a few a compute unit (each loops over its run of entries).
std::size_t sharing_items(const Device &device, std::size_t most);

// Launches `kernel` over `items` work-items (rounded up to the work-group
// size; kernels guard their index). OpenCL failures become OpenCLError
// naming the phase and the kernel.
void launch(Device &device, cl::Kernel &kernel, std::size_t items, const std::string &phase);
// The same with an explicit work-group size (kernels that use local memory).
void launch(Device &device, cl::Kernel &kernel, std::size_t items, const std::string &phase,
            std::size_t group);

// With CLMESH_PROFILE set (see launch), counts a host call into the driver
// (a blocking transfer, a finish, a buffer or kernel made) under `cause`, with
// the seconds from its construction to its end; otherwise does nothing.
class ProfiledCall {
public:
  explicit ProfiledCall(const char *cause);
  ~ProfiledCall();
  ProfiledCall(const ProfiledCall &) = delete;
  ProfiledCall &operator=(const ProfiledCall &) = delete;

private:
  const char *cause_;
  std::chrono::steady_clock::time_point start_;
};

// Sets kernel arguments in order from index `first`; returns the index after
// the last one set.
template <typename... Args>
cl_uint set_args_from(cl::Kernel &kernel, cl_uint first, const Args &...args) {
  cl_uint index = first;
  try {
    (kernel.setArg(index++, args), ...);
  } catch (const cl::Error &error) {
    throw OpenCLError(error.err(),
                      std::string(error.what()) + " (argument " + std::to_string(index - 1) + ")",
                      "setting kernel arguments", kernel.getInfo<CL_KERNEL_FUNCTION_NAME>());
  }
  return index;
}

// Sets kernel arguments in order.
template <typename... Args> void set_args(cl::Kernel &kernel, const Args &...args) {
  set_args_from(kernel, 0, args...);
}

// Runs `body`, turning a cl::Error into an OpenCLError for `phase`.
template <typename Body>
auto guarded(const std::string &phase, const std::string &what, Body body) {
  try {
    return body();
  } catch (const cl::Error &error) {
    throw OpenCLError(error.err(), error.what(), phase, what);
  }
}

} // namespace clmesh
