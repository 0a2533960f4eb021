// clmesh — how much of the host's memory a run may use, and giving back
// what it has freed.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace clmesh {

// The memory this process could hold now: what it holds (its resident set)
// plus what is left for it, the least of
// - what the system has available (MemAvailable of /proc/meminfo);
// - under each memory limit of the process's control groups (cgroup v1's
//   memory.limit_in_bytes, v2's memory.max, of its own group and every group
//   above it): the limit less the group's usage, its inactive file cache
//   (which the kernel reclaims first) not counted as used.
// A container or a batch job's allocation (Slurm, systemd) sets such limits;
// MemAvailable does not see them, and a process over them is killed.
// Empty where the system does not say (not Linux).
//
// `root`: a folder that stands for `/` (/proc and /sys/fs/cgroup are read
// under it), for tests; empty for the system itself.
std::optional<std::size_t> host_memory_for_process(const std::string &root = "");

// Gives the free pages of the heap back to the system (glibc's malloc_trim;
// nothing elsewhere). A run's set-up frees much more than it keeps (the
// readers' lines, a given mesh's edge lists, the size field's grid), in
// blocks scattered among those still in use, and the allocator keeps those
// pages otherwise: the phases after would add their memory to them. Only
// when 16 MiB or more are free: a small mesh's few pages are not worth the
// walk.
void release_free_heap();

} // namespace clmesh
