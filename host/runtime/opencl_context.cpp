// clmesh — device selection, program building and error naming.
#include "runtime/opencl_context.hpp"

#include "runtime/host_memory.hpp"
#include "runtime/predicate_check.hpp"
#include "runtime/program_cache.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

#include <sys/mman.h>

namespace clmesh {

const char *opencl_error_name(int code) {
  switch (code) {
#define CLMESH_NAME(c)                                                                             \
  case c:                                                                                          \
    return #c;
    CLMESH_NAME(CL_SUCCESS)
    CLMESH_NAME(CL_DEVICE_NOT_FOUND)
    CLMESH_NAME(CL_DEVICE_NOT_AVAILABLE)
    CLMESH_NAME(CL_COMPILER_NOT_AVAILABLE)
    CLMESH_NAME(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    CLMESH_NAME(CL_OUT_OF_RESOURCES)
    CLMESH_NAME(CL_OUT_OF_HOST_MEMORY)
    CLMESH_NAME(CL_PROFILING_INFO_NOT_AVAILABLE)
    CLMESH_NAME(CL_MEM_COPY_OVERLAP)
    CLMESH_NAME(CL_IMAGE_FORMAT_MISMATCH)
    CLMESH_NAME(CL_IMAGE_FORMAT_NOT_SUPPORTED)
    CLMESH_NAME(CL_BUILD_PROGRAM_FAILURE)
    CLMESH_NAME(CL_MAP_FAILURE)
    CLMESH_NAME(CL_MISALIGNED_SUB_BUFFER_OFFSET)
    CLMESH_NAME(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
    CLMESH_NAME(CL_COMPILE_PROGRAM_FAILURE)
    CLMESH_NAME(CL_LINKER_NOT_AVAILABLE)
    CLMESH_NAME(CL_LINK_PROGRAM_FAILURE)
    CLMESH_NAME(CL_DEVICE_PARTITION_FAILED)
    CLMESH_NAME(CL_KERNEL_ARG_INFO_NOT_AVAILABLE)
    CLMESH_NAME(CL_INVALID_VALUE)
    CLMESH_NAME(CL_INVALID_DEVICE_TYPE)
    CLMESH_NAME(CL_INVALID_PLATFORM)
    CLMESH_NAME(CL_INVALID_DEVICE)
    CLMESH_NAME(CL_INVALID_CONTEXT)
    CLMESH_NAME(CL_INVALID_QUEUE_PROPERTIES)
    CLMESH_NAME(CL_INVALID_COMMAND_QUEUE)
    CLMESH_NAME(CL_INVALID_HOST_PTR)
    CLMESH_NAME(CL_INVALID_MEM_OBJECT)
    CLMESH_NAME(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR)
    CLMESH_NAME(CL_INVALID_IMAGE_SIZE)
    CLMESH_NAME(CL_INVALID_SAMPLER)
    CLMESH_NAME(CL_INVALID_BINARY)
    CLMESH_NAME(CL_INVALID_BUILD_OPTIONS)
    CLMESH_NAME(CL_INVALID_PROGRAM)
    CLMESH_NAME(CL_INVALID_PROGRAM_EXECUTABLE)
    CLMESH_NAME(CL_INVALID_KERNEL_NAME)
    CLMESH_NAME(CL_INVALID_KERNEL_DEFINITION)
    CLMESH_NAME(CL_INVALID_KERNEL)
    CLMESH_NAME(CL_INVALID_ARG_INDEX)
    CLMESH_NAME(CL_INVALID_ARG_VALUE)
    CLMESH_NAME(CL_INVALID_ARG_SIZE)
    CLMESH_NAME(CL_INVALID_KERNEL_ARGS)
    CLMESH_NAME(CL_INVALID_WORK_DIMENSION)
    CLMESH_NAME(CL_INVALID_WORK_GROUP_SIZE)
    CLMESH_NAME(CL_INVALID_WORK_ITEM_SIZE)
    CLMESH_NAME(CL_INVALID_GLOBAL_OFFSET)
    CLMESH_NAME(CL_INVALID_EVENT_WAIT_LIST)
    CLMESH_NAME(CL_INVALID_EVENT)
    CLMESH_NAME(CL_INVALID_OPERATION)
    CLMESH_NAME(CL_INVALID_GL_OBJECT)
    CLMESH_NAME(CL_INVALID_BUFFER_SIZE)
    CLMESH_NAME(CL_INVALID_MIP_LEVEL)
    CLMESH_NAME(CL_INVALID_GLOBAL_WORK_SIZE)
    CLMESH_NAME(CL_INVALID_PROPERTY)
    CLMESH_NAME(CL_INVALID_IMAGE_DESCRIPTOR)
    CLMESH_NAME(CL_INVALID_COMPILER_OPTIONS)
    CLMESH_NAME(CL_INVALID_LINKER_OPTIONS)
    CLMESH_NAME(CL_INVALID_DEVICE_PARTITION_COUNT)
    CLMESH_NAME(CL_PLATFORM_NOT_FOUND_KHR)
#undef CLMESH_NAME
  default:
    return "CL_UNKNOWN_ERROR";
  }
}

OpenCLError::OpenCLError(int code, const std::string &what_failed, const std::string &phase,
                         const std::string &kernel)
    : Error(std::string(opencl_error_name(code)) + " in " + what_failed + " (phase " + phase +
            (kernel.empty() ? std::string() : ", kernel " + kernel) + ")"),
      code_(code) {}

namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

struct FoundDevice {
  cl::Device device;
  DeviceDescription description;
};

std::vector<FoundDevice> find_devices() {
  std::vector<FoundDevice> found;
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error &) {
    return found; // no ICD or no platform: an empty list
  }
  for (std::size_t p = 0; p < platforms.size(); ++p) {
    std::vector<cl::Device> devices;
    try {
      platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error &) {
      continue;
    }
    for (std::size_t d = 0; d < devices.size(); ++d) {
      DeviceDescription description;
      description.platform_index = static_cast<int>(p);
      description.device_index = static_cast<int>(d);
      description.platform_name = platforms[p].getInfo<CL_PLATFORM_NAME>();
      description.device_name = devices[d].getInfo<CL_DEVICE_NAME>();
      description.version = devices[d].getInfo<CL_DEVICE_VERSION>();
      const std::string extensions = devices[d].getInfo<CL_DEVICE_EXTENSIONS>();
      description.has_fp64 = extensions.find("cl_khr_fp64") != std::string::npos ||
                             devices[d].getInfo<CL_DEVICE_DOUBLE_FP_CONFIG>() != 0;
      description.is_cpu = (devices[d].getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU) != 0;
      found.push_back({devices[d], description});
    }
  }
  return found;
}

bool is_number(const std::string &text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); });
}

bool matches(const FoundDevice &found, const std::string &spec, std::size_t list_position) {
  const auto colon = spec.find(':');
  if (colon != std::string::npos && is_number(spec.substr(0, colon)) &&
      is_number(spec.substr(colon + 1)))
    return found.description.platform_index == std::stoi(spec.substr(0, colon)) &&
           found.description.device_index == std::stoi(spec.substr(colon + 1));
  if (is_number(spec))
    return list_position == std::stoul(spec);
  const std::string haystack =
      lower(found.description.platform_name + " " + found.description.device_name);
  return haystack.find(lower(spec)) != std::string::npos;
}

std::string read_kernel_file(const std::string &name) {
  if (const char *dir = std::getenv("CLMESH_KERNEL_DIR"); dir && *dir) {
    std::ifstream in(std::string(dir) + "/" + name);
    if (!in)
      throw DeviceError("kernel source " + std::string(dir) + "/" + name +
                        " not found (CLMESH_KERNEL_DIR is set)");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  const char *text = detail::embedded_source(name.c_str());
  if (!text)
    throw InternalError("kernel source " + name + " is not embedded in this build");
  return text;
}

void expand_includes(const std::string &name, std::set<std::string> &included, std::string &out) {
  if (!included.insert(name).second)
    return; // every header once
  std::istringstream in(read_kernel_file(name));
  std::string line;
  int number = 0;
  out += "#line 1 \"" + name + "\"\n";
  while (std::getline(in, line)) {
    ++number;
    const auto first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
      const auto open = line.find('"'), close = line.rfind('"');
      if (open != std::string::npos && close > open) {
        expand_includes(line.substr(open + 1, close - open - 1), included, out);
        out += "#line " + std::to_string(number + 1) + " \"" + name + "\"\n";
        continue;
      }
    }
    out += line;
    out += '\n';
  }
}

} // namespace

std::string kernel_source(const std::string &file) {
  std::set<std::string> included;
  std::string out;
  expand_includes(file, included, out);
  return out;
}

std::vector<DeviceDescription> list_devices() {
  std::vector<DeviceDescription> descriptions;
  for (const auto &found : find_devices())
    descriptions.push_back(found.description);
  return descriptions;
}

namespace {

// The device a spec names (see open_device()).
FoundDevice select_device(const std::string &requested) {
  std::string spec = requested;
  if (spec.empty())
    if (const char *env = std::getenv("CLMESH_DEVICE"))
      spec = env;
  const auto found = find_devices();
  if (found.empty())
    throw DeviceError("no OpenCL device found (is an ICD such as pocl-opencl-icd installed?)");
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (spec.empty() ? !found[i].description.has_fp64 : !matches(found[i], spec, i))
      continue;
    if (!found[i].description.has_fp64)
      throw DeviceError("device '" + found[i].description.device_name +
                        "' lacks double precision (cl_khr_fp64), which clmesh's exact "
                        "predicates require");
    return found[i];
  }
  if (spec.empty())
    throw DeviceError("no OpenCL device with double precision (cl_khr_fp64) found");
  throw DeviceError("no OpenCL device matches '" + spec + "' (see clmesh --list-devices)");
}

} // namespace

DeviceDescription find_device(const std::string &spec) { return select_device(spec).description; }

std::shared_ptr<Device> open_device(const std::string &spec) {
  FoundDevice found = select_device(spec);
  return std::make_shared<Device>(found.device, found.description);
}

std::string describe(const Device &device) {
  return device.description().device_name + " (" + device.description().platform_name + ")";
}

std::size_t max_work_group_size(const Device &device) { return device.max_work_group(); }

DevicePaths device_paths_from_environment() {
  // CLMESH_DEVICE_PATHS=gpu runs the GPU code paths on any device (no
  // prefetching kernels, no host-memory buffers, scans by blocks), =cpu the
  // CPU ones; unset, empty or "auto": the device's type decides. Read here
  // only (device_taken_in_turns() also asks, for a batch's workers). The meshes never depend on it:
  // the test suite runs its mesh tests both ways on PoCL's CPU device (tests/CMakeLists.txt).
  const char *env = std::getenv("CLMESH_DEVICE_PATHS");
  const std::string value = env ? lower(env) : std::string();
  if (value.empty() || value == "auto")
    return DevicePaths::by_type;
  if (value == "gpu")
    return DevicePaths::gpu;
  if (value == "cpu")
    return DevicePaths::cpu;
  throw OptionError("CLMESH_DEVICE_PATHS must be 'gpu', 'cpu' or 'auto', not '" + std::string(env) +
                    "'");
}

Device::Device(cl::Device device, DeviceDescription description, DevicePaths paths)
    : device_(device), description_(std::move(description)),
      programs_(std::make_shared<BuiltPrograms>()), mapping_pool_(std::make_shared<MappingPool>()) {
  guarded("setup", "creating the context", [&] {
    context_ = cl::Context(device_);
    queue_ = cl::CommandQueue(context_, device_);
    const cl::Platform platform(device_.getInfo<CL_DEVICE_PLATFORM>());
    build_identity_ =
        platform.getInfo<CL_PLATFORM_NAME>() + "\n" + platform.getInfo<CL_PLATFORM_VERSION>() +
        "\n" + device_.getInfo<CL_DEVICE_NAME>() + "\n" + device_.getInfo<CL_DEVICE_VERSION>() +
        "\n" + device_.getInfo<CL_DRIVER_VERSION>();
    cpu_paths_ = paths == DevicePaths::by_type
                     ? (device_.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU) != 0
                     : paths == DevicePaths::cpu;
    // The kernels that share a list take runs of it there (cl/common.h share_of).
    if (cpu_paths_)
      build_options_ += " -DCLM_ITEMS_IN_TURN";
    // A CPU runs a work-group's work-items in turn: they can prefetch for
    // the ones after them (cl/prefetch.h), with a builtin of PoCL's compiler.
    can_prefetch_ =
        cpu_paths_ && platform.getInfo<CL_PLATFORM_NAME>() == "Portable Computing Language";
    if (platform.getInfo<CL_PLATFORM_NAME>() == "Portable Computing Language")
      turns_ = std::make_shared<std::mutex>();
    // The exact predicate stages stay out of line on a CPU device, inlined on
    // others (cl/predicates.h): a CPU's stack, a GPU's compiler.
    if ((device_.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU) != 0)
      build_options_ += " -DCLM_EXACT_OUT_OF_LINE";
  });
  // CLMESH_BUILD_OPTIONS (a developer's aid): more OpenCL build options, to
  // study a device's compiler (say -cl-opt-disable). Options that relax IEEE
  // arithmetic are refused: the exact predicates need it.
  if (const char *extra = std::getenv("CLMESH_BUILD_OPTIONS"); extra && *extra) {
    for (const char *relaxing : {"fast-relaxed-math", "mad-enable", "unsafe-math", "finite-math",
                                 "no-signed-zeros", "denorms-are-zero"})
      if (std::strstr(extra, relaxing))
        throw OptionError(std::string("CLMESH_BUILD_OPTIONS '") + extra +
                          "' relaxes IEEE arithmetic, which the exact predicates need");
    build_options_ += " " + std::string(extra);
  }
  if (const char *env = std::getenv("CLMESH_WORK_GROUP"); env && *env)
    set_work_group(std::strtoul(env, nullptr, 10));
  default_work_group_ = work_group_;
  // Slabs only with CLMESH_SLABS=on (for comparison): on an H100, NVIDIA's
  // driver meshed a batch of small inputs faster with every array a buffer
  // of its own (docs/algorithm.md).
  const char *slabs = std::getenv("CLMESH_SLABS");
  if (!cpu_paths_ && slabs && std::strcmp(slabs, "on") == 0) {
    const auto align_bits = guarded("setup", "querying the device", [&] {
      return device_.getInfo<CL_DEVICE_MEM_BASE_ADDR_ALIGN>();
    });
    slab_alignment_ = align_bits / 8;
    slab_bytes_ = std::min<std::size_t>(std::size_t{256} << 20, global_memory() / 16);
    slabs_ = std::make_shared<BufferSlabs>(context_, slab_alignment_, slab_bytes_);
  }
}

namespace {

// PoCL's in-thread driver ('basic'): kernels run on the thread that waits
// for them.
bool runs_on_calling_thread(const DeviceDescription &description) {
  return description.platform_name == "Portable Computing Language" &&
         description.device_name.rfind("basic", 0) == 0;
}

} // namespace

Device::Device(Stream, Device &device)
    : device_(device.device_), description_(device.description_), context_(device.context_),
      work_group_(device.work_group_), default_work_group_(device.default_work_group_),
      programs_(device.programs_), turns_(device.turns_), build_identity_(device.build_identity_),
      cpu_paths_(device.cpu_paths_), can_prefetch_(device.can_prefetch_),
      prefetching_(device.prefetching_), build_options_(device.build_options_),
      mapping_pool_(std::make_shared<MappingPool>()) {
  if (!device.takes_streams())
    throw DeviceError("device '" + description_.device_name +
                      "' runs kernels on the calling thread, and PoCL's cache of loaded "
                      "kernels is not safe for two threads at once: no streams on it (its "
                      "'pthread' device takes them)");
  guarded("setup", "creating a command queue",
          [&] { queue_ = cl::CommandQueue(context_, device_); });
  if (device.slabs_)
    slabs_ = std::make_shared<BufferSlabs>(context_, device.slab_alignment_, device.slab_bytes_);
}

bool Device::takes_streams() const { return !runs_on_calling_thread(description_); }

std::shared_ptr<Device> open_stream(Device &device) {
  return std::make_shared<Device>(Device::Stream{}, device);
}

namespace {

// A mapping of its own for a device buffer: released to the system as the
// buffer goes (from the heap, a freed buffer's pages would stay in the
// process, raising the peak memory of every later phase), or, in a small
// mesh, kept in the device's MappingPool for the next buffer of its length.
struct Mapping {
  void *start;
  std::size_t length;
  std::shared_ptr<MappingPool> pool;
};

} // namespace

// Small mappings of released buffers, by length, for later buffers of the
// same length: a batch of small meshes allocates the same lengths input
// after input, and a fresh mapping costs two system calls and a page fault
// a page. Kept only while the buffers in mappings of their own hold at most
// kSmallMesh bytes (a large mesh's peak stays as it was) and at most
// kMostBytes of them; each leaves as the pool goes.
class MappingPool {
public:
  ~MappingPool() { unmap_kept(); }
  // A kept mapping of `length` bytes, zeroed as a fresh one, or nullptr.
  void *take(std::size_t length) {
    void *start = nullptr;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      const auto it = kept_.find(length);
      if (it == kept_.end())
        return nullptr;
      start = it->second;
      kept_.erase(it);
      kept_bytes_ -= length;
    }
    std::memset(start, 0, length);
    return start;
  }
  // A buffer of `length` bytes now holds a mapping (kept or fresh).
  void count_in_use(std::size_t length) {
    const std::lock_guard<std::mutex> lock(mutex_);
    live_bytes_ += length;
    if (live_bytes_ > kSmallMesh)
      unmap_kept();
  }
  // The buffer went: its mapping is kept, or unmapped.
  void give(void *start, std::size_t length) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      live_bytes_ -= std::min(live_bytes_, length);
      if (length <= kLongest && live_bytes_ <= kSmallMesh && kept_bytes_ + length <= kMostBytes) {
        kept_.emplace(length, start);
        kept_bytes_ += length;
        return;
      }
    }
    munmap(start, length);
  }

private:
  static constexpr std::size_t kLongest = std::size_t{1} << 20, kMostBytes = std::size_t{16} << 20,
                               kSmallMesh = std::size_t{64} << 20;
  std::mutex mutex_; // buffers may be released on a driver's thread
  std::multimap<std::size_t, void *> kept_;
  std::size_t kept_bytes_ = 0;
  std::size_t live_bytes_ = 0; // in buffers now

  void unmap_kept() {
    for (const auto &[length, start] : kept_)
      munmap(start, length);
    kept_.clear();
    kept_bytes_ = 0;
  }
};

cl::Buffer Device::allocate(std::size_t bytes, bool huge_pages) {
  const ProfiledCall timed("buffer creation");
  // Smaller buffers come from the driver: a mapping each would cost more
  // system calls than the memory it gives back.
  constexpr std::size_t own_mapping = std::size_t{64} << 10;
  if (cpu_paths_ && bytes >= own_mapping) {
    constexpr std::size_t page = 4096, huge_page = std::size_t{2} << 20;
    const std::size_t length = (bytes + page - 1) / page * page;
    // Huge pages: aligned to one, mapped with room to align, the slack
    // before and after unmapped again.
    const bool huge = huge_pages && bytes >= huge_page;
    const std::size_t align = huge ? huge_page : page;
    void *kept = huge ? nullptr : mapping_pool_->take(length);
    void *mapped = kept ? kept
                        : mmap(nullptr, length + align - page, PROT_READ | PROT_WRITE,
                               MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped != MAP_FAILED) {
      const auto first = reinterpret_cast<std::uintptr_t>(mapped);
      const std::uintptr_t aligned = (first + align - 1) / align * align;
      if (aligned > first)
        munmap(mapped, aligned - first);
      if (first + align - page > aligned)
        munmap(reinterpret_cast<void *>(aligned + length), first + align - page - aligned);
      void *memory = reinterpret_cast<void *>(aligned);
#ifdef MADV_HUGEPAGE
      // Advice only, for the whole huge pages (a partial last one would be
      // committed whole): the kernel may not follow it.
      if (huge)
        madvise(memory, bytes / huge_page * huge_page, MADV_HUGEPAGE);
#endif
      cl_int error = CL_SUCCESS;
      cl_mem buffer = clCreateBuffer(context_(), CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, bytes,
                                     memory, &error);
      // The memory goes with the buffer (kernels may hold it longer than its owner).
      auto *mapping = new Mapping{memory, length, mapping_pool_};
      auto release = [](cl_mem, void *user_data) {
        const auto *owned = static_cast<Mapping *>(user_data);
        owned->pool->give(owned->start, owned->length);
        delete owned;
      };
      if (error == CL_SUCCESS &&
          clSetMemObjectDestructorCallback(buffer, release, mapping) == CL_SUCCESS) {
        mapping_pool_->count_in_use(length);
        return cl::Buffer(buffer);
      }
      if (error == CL_SUCCESS)
        clReleaseMemObject(buffer);
      munmap(memory, length);
      delete mapping; // then the driver's own memory
    }
  }
  cl::Buffer buffer;
  if (slabs_ && bytes <= BufferSlabs::kLargest)
    buffer = slabs_->take(bytes);
  if (!buffer())
    buffer = cl::Buffer(context_, CL_MEM_READ_WRITE, bytes);
  // CLMESH_POISON_BUFFERS=B (a byte, 0-255; a check): every buffer from the
  // driver starts as bytes B, as a GPU's may hold anything. The meshes must
  // not change: no kernel reads what nothing wrote.
  if (const char *poison = std::getenv("CLMESH_POISON_BUFFERS"); poison && *poison) {
    const auto byte = static_cast<cl_uchar>(std::strtoul(poison, nullptr, 0));
    guarded("setup", "poisoning a buffer",
            [&] { queue_.enqueueFillBuffer(buffer, byte, 0, bytes); });
  }
  return buffer;
}

std::size_t Device::compute_units() const {
  return std::max<std::size_t>(1, device_.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>());
}

std::size_t Device::max_work_group() const {
  return device_.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
}

std::size_t Device::max_allocation() const {
  return static_cast<std::size_t>(device_.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>());
}

std::size_t Device::global_memory() const {
  const auto global = static_cast<std::size_t>(device_.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>());
  const bool host_memory = (device_.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU) != 0 ||
                           device_.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>() != CL_FALSE;
  if (!host_memory)
    return global;
  const std::optional<std::size_t> host = host_memory_for_process();
  return host ? std::min(global, *host) : global;
}

std::size_t Device::single_group(const cl::Kernel &kernel, const std::string &phase) const {
  return cpu_paths_ ? 1 : fitting_group(kernel, phase);
}

std::size_t Device::fitting_group(const cl::Kernel &kernel, const std::string &phase) const {
  return std::min(work_group_, guarded(phase, "querying the work-group size", [&] {
                    return kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device_);
                  }));
}

void Device::set_work_group(std::size_t size) {
  const std::size_t max_size = max_work_group();
  if (size == 0 || size > max_size)
    throw OptionError("work-group size must be between 1 and " + std::to_string(max_size));
  work_group_ = size;
}

void Device::fit_prefetching(std::size_t points, std::size_t from) {
  prefetching_ = points >= from;
}

std::string Device::options_now() const {
  // No -cl-fast-relaxed-math, no -cl-mad-enable: the exact predicates need
  // IEEE arithmetic without contraction (the sources also say FP_CONTRACT OFF).
  return build_options_ + (can_prefetch_ && prefetching_ ? " -DCLM_PREFETCH" : "");
}

ProgramCache Device::result_cache(const std::string &file, const std::string &question) const {
  return ProgramCache(kernel_source(file) + "\n" + question,
                      options_now() + "\n" + build_identity_);
}

cl::Program &Device::program(const std::string &file, const std::string &phase) {
  const bool prefetch = can_prefetch_ && prefetching_;
  const std::string key = prefetch ? file + " (prefetching)" : file;
  const std::lock_guard<std::recursive_mutex> lock(programs_->mutex);
  std::map<std::string, cl::Program> &programs = programs_->by_key;
  auto it = programs.find(key);
  if (it != programs.end())
    return it->second;
  if (!programs_->predicates_checked) { // before any other program: the check builds its own
    programs_->predicates_checked = true;
    check_device_predicates(*this);
  }
  const std::string source = kernel_source(file);
  const std::string options = options_now();
  const ProgramCache cache(source, options + "\n" + build_identity_);
  if (const auto binary = cache.load()) {
    try {
      cl::Program program(context_, {device_}, cl::Program::Binaries{*binary});
      program.build(std::vector<cl::Device>{device_}, options.c_str());
      return programs.insert_or_assign(key, program).first->second;
    } catch (const cl::Error &) {
      // A binary the driver no longer takes (CL_INVALID_BINARY, a failed
      // build): built again from the source, and its entry replaced below.
    }
  }
  cl::Program program(context_, source);
  try {
    program.build(std::vector<cl::Device>{device_}, options.c_str());
  } catch (const cl::Error &error) {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_);
    } catch (const cl::Error &) {
    }
    throw OpenCLError(error.err(), "building " + file + ":\n" + log, phase, "");
  }
  try {
    const auto binaries = program.getInfo<CL_PROGRAM_BINARIES>();
    if (binaries.size() == 1)
      cache.store(binaries.front());
  } catch (const cl::Error &) {
    // No binary to keep: the next run builds from the source again.
  }
  return programs.insert_or_assign(key, program).first->second;
}

cl::Kernel Device::kernel(const std::string &file, const std::string &name,
                          const std::string &phase) {
  cl::Program &built = program(file, phase);
  const ProfiledCall timed("kernel creation");
  return guarded(phase, "creating kernel", [&] { return cl::Kernel(built, name.c_str()); });
}

void Device::wait(const std::string &phase) {
  const ProfiledCall timed("finish");
  guarded(phase, "waiting for the device", [&] { queue_.finish(); });
}

void Device::fill(const cl::Buffer &buffer, const void *pattern, std::size_t pattern_size,
                  std::size_t offset, std::size_t bytes, const std::string &phase) {
  if (bytes == 0)
    return;
  const std::size_t word = sizeof(cl_uint);
  if ((pattern_size != 4 && pattern_size != 8 && pattern_size != 16) ||
      offset % pattern_size != 0 || bytes % pattern_size != 0)
    throw InternalError("a device fill takes whole elements of 4, 8 or 16 bytes, not " +
                        std::to_string(pattern_size));
  if (!fill_words_())
    fill_words_ = kernel("fill.cl", "fill_words", phase);
  cl_uint4 words{};
  std::memcpy(&words, pattern, pattern_size);
  set_args(fill_words_, buffer, words, static_cast<cl_uint>(pattern_size / word),
           static_cast<cl_ulong>(offset / word), static_cast<cl_ulong>(bytes / word));
  launch(*this, fill_words_, bytes / word, phase);
}

void Device::discard(const cl::Buffer &buffer, std::size_t offset, std::size_t bytes,
                     const std::string &phase) {
  constexpr std::size_t page = 4096;
  // Fewer pages are not worth the wait for the device (and the faults
  // that bring them back when written again).
  constexpr std::size_t least = std::size_t{1} << 20;
  if (!cpu_paths_ || bytes < least)
    return;
  auto *host = static_cast<char *>(
      guarded(phase, "querying a buffer", [&] { return buffer.getInfo<CL_MEM_HOST_PTR>(); }));
  if (host == nullptr)
    return;
  const auto start = reinterpret_cast<std::uintptr_t>(host) + offset;
  const std::uintptr_t first = (start + page - 1) / page * page,
                       last = (start + bytes) / page * page;
  if (last < first + least)
    return;
  // No kernel writes the pages while they go.
  const ProfiledCall timed("discard");
  guarded(phase, "waiting for the device", [&] { queue_.finish(); });
  madvise(reinterpret_cast<void *>(first), last - first, MADV_DONTNEED);
}

std::size_t sharing_items(const Device &device, std::size_t most) {
  return device.cpu_paths() ? std::min(most, 64 * device.compute_units()) : most;
}

void launch(Device &device, cl::Kernel &kernel, std::size_t items, const std::string &phase) {
  launch(device, kernel, items, phase, device.fitting_group(kernel, phase));
}

namespace {

// CLMESH_PROFILE=1 (development aid): per kernel its seconds (each launch
// waited for), launches and work-items, and the host's calls into the driver
// by cause (ProfiledCall) with their seconds, on stderr at exit.
// CLMESH_PROFILE=phases counts each kernel apart in each phase (phase/kernel).
const char *const profile_setting = std::getenv("CLMESH_PROFILE");
const bool profile = profile_setting != nullptr;
const bool profile_by_phase = profile && std::string(profile_setting) == "phases";

struct ProfileTotal {
  double seconds = 0;
  long launches = 0;
  double items = 0;
};

struct Profile {
  std::map<std::string, ProfileTotal> kernels;
  std::map<std::string, ProfileTotal> calls;
  ~Profile() {
    for (const auto &[name, total] : kernels)
      std::fprintf(stderr, "%-32s %9.4f s %7ld launches %12.0f items\n", name.c_str(),
                   total.seconds, total.launches, total.items);
    for (const auto &[cause, total] : calls)
      std::fprintf(stderr, "host: %-26s %9.6f s %7ld calls\n", cause.c_str(), total.seconds,
                   total.launches);
  }
};

Profile &profile_totals() {
  static Profile totals;
  return totals;
}

// Streams (open_stream) count from several threads.
std::mutex &profile_mutex() {
  static std::mutex mutex;
  return mutex;
}

} // namespace

ProfiledCall::ProfiledCall(const char *cause) : cause_(cause) {
  if (profile)
    start_ = std::chrono::steady_clock::now();
}

ProfiledCall::~ProfiledCall() {
  if (!profile)
    return;
  const std::lock_guard<std::mutex> lock(profile_mutex());
  ProfileTotal &total = profile_totals().calls[cause_];
  total.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  ++total.launches;
}

void launch(Device &device, cl::Kernel &kernel, std::size_t items, const std::string &phase,
            std::size_t group) {
  if (items == 0)
    return;
  const std::size_t global = (items + group - 1) / group * group;
  const auto start = std::chrono::steady_clock::now();
  try {
    device.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global),
                                        cl::NDRange(group));
    if (profile)
      device.queue().finish();
  } catch (const cl::Error &error) {
    throw OpenCLError(error.err(), "launching", phase, kernel.getInfo<CL_KERNEL_FUNCTION_NAME>());
  }
  if (profile) {
    const std::lock_guard<std::mutex> lock(profile_mutex());
    const std::string name = kernel.getInfo<CL_KERNEL_FUNCTION_NAME>();
    ProfileTotal &total = profile_totals().kernels[profile_by_phase ? phase + "/" + name : name];
    total.seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++total.launches;
    total.items += static_cast<double>(items);
  }
}

} // namespace clmesh
