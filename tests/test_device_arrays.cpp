// Device arrays (host/device_mesh.hpp, Device::allocate): a large array on a
// CPU device lives in host memory the device uses in place; its contents
// survive kernels, growth and the release of its owner.
#include <doctest/doctest.h>

#include "device_mesh.hpp"
#include "opencl_context.hpp"
#include "prefix_scan.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

using namespace clmesh;
using test_support::device;

TEST_CASE("device arrays: large arrays keep their contents through kernels and growth") {
  Device &dev = device();
  const std::size_t n = std::size_t{3} << 20; // 12 MiB of ints: whole huge pages and a tail
  std::vector<cl_int> counts(n);
  for (std::size_t i = 0; i < n; ++i)
    counts[i] = static_cast<cl_int>(i % 3);
  DeviceArray<cl_int> offsets(dev, n);
  {
    DeviceArray<cl_int> device_counts(dev, n);
    const bool cpu = dev.cl_device().getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU;
    if (cpu)
      CHECK((device_counts.buffer().getInfo<CL_MEM_FLAGS>() & CL_MEM_USE_HOST_PTR) != 0);
    device_counts.upload(dev, counts);
    PrefixScan scan(dev);
    const int total = scan.exclusive_scan(device_counts, offsets, n, "test");
    CHECK(total == static_cast<int>(n / 3 * 3)); // 0 + 1 + 2 per three entries
    // The owner goes while the queue may still hold the buffer.
  }
  std::vector<cl_int> expected(n);
  std::exclusive_scan(counts.begin(), counts.end(), expected.begin(), 0);
  CHECK(offsets.download(dev, n) == expected);
  const DeviceArray<cl_int> bigger = offsets.grown(dev, n + (1 << 20) + 5, -7);
  const std::vector<cl_int> grown = bigger.download(dev, n + (1 << 20) + 5);
  CHECK(std::equal(expected.begin(), expected.end(), grown.begin()));
  CHECK(std::all_of(grown.begin() + n, grown.end(), [](cl_int v) { return v == -7; }));
}
