// clmesh — host loops over many items (a large input's points, a given
// mesh's edges) cut into parts that run at once, where the device waits
// for them: two parts on two threads when there is a second core. Each part
// writes where the others do not, so the results never depend on the cut.
#pragma once

#include <cstddef>
#include <exception>
#include <thread>
#include <utility>

namespace clmesh {

// Loops over fewer items than this run on one thread: a thread's start costs
// more than it saves.
constexpr std::size_t kManyItems = std::size_t{1} << 16;

// The parts a loop over `items` takes: 2 for many items and a second core, else 1.
inline int host_threads(std::size_t items) {
  return items > kManyItems && std::thread::hardware_concurrency() > 1 ? 2 : 1;
}

// work(part, parts) for part 0 .. parts - 1 (parts 1 or 2) at once, part 0
// on this thread; what a part throws is thrown here once both are done.
template <class Work> void run_parts(int parts, const Work &work) {
  if (parts < 2) {
    work(0, 1);
    return;
  }
  std::exception_ptr failure;
  std::thread helper([&] {
    try {
      work(1, 2);
    } catch (...) {
      failure = std::current_exception();
    }
  });
  try {
    work(0, 2);
  } catch (...) {
    helper.join();
    throw;
  }
  helper.join();
  if (failure)
    std::rethrow_exception(failure);
}

// The items [first, end) of part `part` of n items cut into `parts`.
inline std::pair<std::size_t, std::size_t> part_range(std::size_t n, int part, int parts) {
  const std::size_t size = n / static_cast<std::size_t>(parts),
                    first = size * static_cast<std::size_t>(part);
  return {first, part + 1 == parts ? n : first + size};
}

} // namespace clmesh
