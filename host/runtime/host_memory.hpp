// clmesh — how much of the host's memory a run may use.
#pragma once

#include <cstddef>
#include <optional>

namespace clmesh {

// The memory this process could hold now: what it holds (its resident set)
// plus what the system has available for it (MemAvailable of
// /proc/meminfo). Empty where the system does not say (not Linux).
std::optional<std::size_t> host_memory_for_process();

} // namespace clmesh
