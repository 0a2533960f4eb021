// clmesh — how much of the host's memory a run may use (Linux's /proc and
// control groups), and the heap's free pages given back.
#include "runtime/host_memory.hpp"

#include <algorithm>
#include <fstream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace clmesh {

namespace {

// The number after `key` in a file of "key value" lines (/proc/meminfo,
// memory.stat).
std::optional<std::size_t> keyed_value(const std::string &path, const std::string &key) {
  std::ifstream file(path);
  std::string name, rest;
  std::size_t value = 0;
  while (file >> name >> value) {
    std::getline(file, rest);
    if (name == key)
      return value;
  }
  return std::nullopt;
}

// The first number in a file (memory.limit_in_bytes, memory.current...);
// empty when there is none (v2's "max": no limit).
std::optional<std::size_t> number_in(const std::string &path) {
  std::ifstream file(path);
  std::size_t value = 0;
  if (file >> value)
    return value;
  return std::nullopt;
}

// This process's resident set (the second field of /proc/self/statm, in
// pages), in bytes.
std::size_t resident_memory(const std::string &root) {
  std::ifstream statm(root + "/proc/self/statm");
  std::size_t size = 0, resident = 0;
  if (!(statm >> size >> resident))
    return 0;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

bool has_token(const std::string &list, const std::string &token) {
  std::istringstream items(list);
  std::string item;
  while (std::getline(items, item, ','))
    if (item == token)
      return true;
  return false;
}

// A memory controller's hierarchy as this process sees it: where it is
// mounted, and the folder of the process's own group in it.
struct MemoryHierarchy {
  bool v2 = false;
  std::string mount_point, group;
};

// The memory hierarchies of the process (a v1 memory controller, the v2
// unified hierarchy, or both on a hybrid system), from /proc/self/cgroup
// (lines "id:controllers:path") and /proc/self/mountinfo (fields: id,
// parent, device, root, mount point, options, optional fields, "-", type,
// source, super options).
std::vector<MemoryHierarchy> memory_hierarchies(const std::string &root) {
  std::string v1_path, v2_path;
  bool v1 = false, v2 = false;
  std::ifstream cgroups(root + "/proc/self/cgroup");
  for (std::string line; std::getline(cgroups, line);) {
    const std::size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos)
      continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    if (line.compare(0, first, "0") == 0 && controllers.empty()) {
      v2 = true;
      v2_path = line.substr(second + 1);
    } else if (has_token(controllers, "memory")) {
      v1 = true;
      v1_path = line.substr(second + 1);
    }
  }
  std::vector<MemoryHierarchy> found;
  std::ifstream mounts(root + "/proc/self/mountinfo");
  for (std::string line; std::getline(mounts, line);) {
    std::istringstream fields(line);
    std::string id, parent, device, mount_root, mount_point, field;
    fields >> id >> parent >> device >> mount_root >> mount_point;
    while (fields >> field && field != "-") {
    }
    std::string type, source, options;
    fields >> type >> source >> options;
    const bool is_v2 = type == "cgroup2" && v2;
    if (!is_v2 && !(type == "cgroup" && v1 && has_token(options, "memory")))
      continue;
    // The group's path is from the hierarchy's root; the mount shows the
    // hierarchy from mount_root down (a container's view may start lower).
    std::string path = is_v2 ? v2_path : v1_path;
    if (mount_root != "/" && path.compare(0, mount_root.size(), mount_root) == 0)
      path.erase(0, mount_root.size());
    else if (mount_root != "/")
      path.clear();
    found.push_back({is_v2, root + mount_point, root + mount_point + path});
  }
  return found;
}

// What the limits of the group at `folder` and of the groups above it, up
// to the hierarchy's mount point, leave to grow into; empty without limits.
std::optional<std::size_t> room_under_limits(const MemoryHierarchy &hierarchy) {
  std::optional<std::size_t> room;
  std::string folder = hierarchy.group;
  while (folder.size() > hierarchy.mount_point.size() && folder.back() == '/')
    folder.pop_back();
  while (folder.size() >= hierarchy.mount_point.size()) {
    const std::optional<std::size_t> limit =
        number_in(folder + (hierarchy.v2 ? "/memory.max" : "/memory.limit_in_bytes"));
    // v1 writes "no limit" as the largest multiple of the page size.
    if (limit && *limit < (std::size_t{1} << 62)) {
      const std::size_t usage =
          number_in(folder + (hierarchy.v2 ? "/memory.current" : "/memory.usage_in_bytes"))
              .value_or(0);
      const std::size_t cache = keyed_value(folder + "/memory.stat",
                                            hierarchy.v2 ? "inactive_file" : "total_inactive_file")
                                    .value_or(0);
      const std::size_t used = usage - std::min(usage, cache);
      const std::size_t left = *limit - std::min(*limit, used);
      room = room ? std::min(*room, left) : left;
    }
    const std::size_t slash = folder.find_last_of('/');
    if (folder.size() == hierarchy.mount_point.size() || slash == std::string::npos ||
        slash < hierarchy.mount_point.size())
      break;
    folder.erase(slash);
  }
  return room;
}

} // namespace

std::optional<std::size_t> host_memory_for_process(const std::string &root) {
  const std::optional<std::size_t> available_kib =
      keyed_value(root + "/proc/meminfo", "MemAvailable:");
  if (!available_kib)
    return std::nullopt;
  std::size_t room = *available_kib * 1024;
  // The process's own groups do not change while it runs (a batch asks for
  // every input): found once; a test's root is read every time.
  static const std::vector<MemoryHierarchy> own = memory_hierarchies("");
  for (const MemoryHierarchy &hierarchy : root.empty() ? own : memory_hierarchies(root))
    if (const std::optional<std::size_t> limited = room_under_limits(hierarchy))
      room = std::min(room, *limited);
  return room + resident_memory(root);
}

void release_free_heap() {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  // The walk over the heap pays only where much of it is free (a large
  // mesh's set-up); each small mesh of a batch would pay it for little.
  constexpr std::size_t kWorthIt = std::size_t{16} << 20;
  if (mallinfo2().fordblks >= kWorthIt)
    malloc_trim(0);
#endif
}

} // namespace clmesh
