// clmesh — when a phase's scratch lists give their memory back to the system.
#pragma once

#include <algorithm>
#include <cstddef>

namespace clmesh {

// A phase's lists, sized for the largest use, hold memory only in the pages
// written (a CPU device's memory comes when first written), and keep it:
// after the long lists of the first iterations of refinement, the pages of
// every phase's lists would add up to the peak. A phase counts the entries
// each use of its lists takes (its work); once a use takes less than half of
// the most taken since the lists were last discarded, they are discarded
// (DeviceArray::discard). While the uses shrink, memory goes back in a
// few steps, and the pages written again cost about as much as the last
// use wrote.
class ScratchWatermark {
public:
  // After a use of `work` entries: whether the lists are to be discarded now.
  bool discard_after(std::size_t work) {
    high_ = std::max(high_, work);
    if (2 * work >= high_)
      return false;
    high_ = 0;
    return true;
  }

private:
  std::size_t high_ = 0; // the most entries a use took since the last discard
};

} // namespace clmesh
