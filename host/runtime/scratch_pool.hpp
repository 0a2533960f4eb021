// clmesh — scratch lists shared by phases that never run at the same time.
#pragma once

#include "runtime/device_mesh.hpp"

#include <cstddef>
#include <initializer_list>
#include <vector>

namespace clmesh {

// The lists of several users (phases of one iteration, one running at a
// time, each list's contents not needed once its user's step is over), kept
// once: list k of every user is the same memory, as large as the largest
// user's list k. A CPU device's memory comes when first written and stays,
// so the pages that one step wrote serve the next step's lists instead of
// adding to them; on a GPU the lists take the largest user's room, not the
// sum.
class ScratchPool {
public:
  // users: for each user, the size in bytes of each of its lists.
  ScratchPool(Device &device, std::initializer_list<std::vector<std::size_t>> users);

  // List k, as many entries of T as it holds (its user's size or more).
  // Its contents are whatever the last user wrote.
  template <typename T> DeviceArray<T> list(std::size_t k) const {
    return DeviceArray<T>::view(lists_.at(k).buffer(),
                                lists_[k].size() * sizeof(cl_int) / sizeof(T));
  }

  // After an iteration whose steps took at most `work` of `capacity`
  // entries per list: each list keeps the pages of that share of its
  // memory, which the next iteration (of about the same size) writes again,
  // and gives the rest back to the system (DeviceArray::discard).
  void trim(std::size_t work, std::size_t capacity, const char *phase);

private:
  Device &device_;
  std::vector<DeviceArray<cl_int>> lists_;
};

} // namespace clmesh
