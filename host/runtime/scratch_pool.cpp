#include "runtime/scratch_pool.hpp"

#include <algorithm>
#include <cmath>

namespace clmesh {

ScratchPool::ScratchPool(Device &device, std::initializer_list<std::vector<std::size_t>> users)
    : device_(device) {
  std::vector<std::size_t> bytes;
  for (const std::vector<std::size_t> &user : users) {
    bytes.resize(std::max(bytes.size(), user.size()), 0);
    for (std::size_t k = 0; k < user.size(); ++k)
      bytes[k] = std::max(bytes[k], user[k]);
  }
  // Whole entries of every type a list may hold (up to 16 bytes).
  constexpr std::size_t largest = 16;
  for (const std::size_t size : bytes)
    lists_.emplace_back(device, (size + largest - 1) / largest * largest / sizeof(cl_int));
}

void ScratchPool::trim(std::size_t work, std::size_t capacity, const char *phase) {
  const double share = std::min(1.0, static_cast<double>(work) / static_cast<double>(capacity));
  for (const DeviceArray<cl_int> &list : lists_)
    list.discard(device_,
                 static_cast<std::size_t>(std::ceil(share * static_cast<double>(list.size()))),
                 phase);
}

} // namespace clmesh
