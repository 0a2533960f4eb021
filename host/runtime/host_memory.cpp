// clmesh — how much of the host's memory a run may use (Linux's /proc).
#include "runtime/host_memory.hpp"

#include <fstream>
#include <string>
#include <unistd.h>

namespace clmesh {

namespace {

// MemAvailable of /proc/meminfo, in bytes.
std::optional<std::size_t> memory_available() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  std::size_t kib = 0;
  while (meminfo >> key >> kib) {
    std::getline(meminfo, unit);
    if (key == "MemAvailable:")
      return kib * 1024;
  }
  return std::nullopt;
}

// This process's resident set (the second field of /proc/self/statm, in
// pages), in bytes.
std::size_t resident_memory() {
  std::ifstream statm("/proc/self/statm");
  std::size_t size = 0, resident = 0;
  if (!(statm >> size >> resident))
    return 0;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

} // namespace

std::optional<std::size_t> host_memory_for_process() {
  const std::optional<std::size_t> available = memory_available();
  if (!available)
    return std::nullopt;
  return *available + resident_memory();
}

} // namespace clmesh
