// Device arrays (host/device_mesh.hpp, Device::allocate): a large array on a
// CPU device lives in host memory the device uses in place, a mapping of its
// own that goes with it (or, when small, serves the next array of its
// length); its contents survive kernels, growth and the
// release of its owner; fills set exactly their range; the scans and the
// removal of duplicates give the exact results at every length.
#include <doctest/doctest.h>

#include "runtime/device_mesh.hpp"
#include "runtime/host_memory.hpp"
#include "runtime/opencl_context.hpp"
#include "runtime/prefix_scan.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <numeric>
#include <optional>
#include <thread>
#include <vector>

#include <sys/mman.h>

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
    if (dev.cpu_paths())
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

namespace {

// Whether the page at `memory` (a released array's) is unmapped once the
// queue finished: the driver may let go of the buffer a little after it.
bool unmapped_soon(Device &dev, void *memory) {
  dev.queue().finish();
  unsigned char resident[1];
  for (int tries = 0; tries < 500; ++tries) {
    if (mincore(memory, 1, resident) == -1 && errno == ENOMEM)
      return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

} // namespace

TEST_CASE("device arrays: on a CPU device one over 1 MiB is unmapped as it goes") {
  // From the heap its pages would stay in the process after it went.
  Device &dev = device();
  if (!dev.cpu_paths())
    return;
  // 1 MiB and a page, and 12 MiB: whole huge pages and a tail (with and
  // without them).
  for (const std::size_t n : {(std::size_t{1} << 18) + 1024, std::size_t{3} << 20})
    for (const bool huge_pages : {false, true}) {
      CAPTURE(n);
      CAPTURE(huge_pages);
      void *memory = nullptr;
      unsigned char resident[1];
      {
        DeviceArray<cl_int> array(dev, n, huge_pages);
        REQUIRE((array.buffer().getInfo<CL_MEM_FLAGS>() & CL_MEM_USE_HOST_PTR) != 0);
        memory = array.buffer().getInfo<CL_MEM_HOST_PTR>();
        array.fill(dev, 7, n);
        CHECK(array.read(dev, n - 1) == 7);
        CHECK(mincore(memory, 1, resident) == 0); // mapped
      }
      CHECK(unmapped_soon(dev, memory));
    }
}

TEST_CASE("device arrays: on a CPU device a small one's mapping serves the next, zeroed") {
  // A batch allocates the same lengths input after input: the mapping of a
  // released array of 64 KiB to 1 MiB is kept for the next array of its
  // length, which starts as zeros as a fresh mapping does.
  Device &dev = device();
  if (!dev.cpu_paths())
    return;
  const std::size_t n = (std::size_t{17} << 10) + 3 * 1024; // a length no other test uses
  void *memory = nullptr;
  {
    DeviceArray<cl_int> array(dev, n);
    memory = array.buffer().getInfo<CL_MEM_HOST_PTR>();
    array.fill(dev, 7, n);
    CHECK(array.read(dev, n - 1) == 7);
  }
  dev.queue().finish();
  bool reused = false;
  for (int tries = 0; tries < 500 && !reused; ++tries) {
    DeviceArray<cl_int> next(dev, n);
    reused = next.buffer().getInfo<CL_MEM_HOST_PTR>() == memory;
    if (reused) {
      const std::vector<cl_int> contents = next.download(dev, n);
      CHECK(std::all_of(contents.begin(), contents.end(), [](cl_int v) { return v == 0; }));
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  CHECK(reused);
}

TEST_CASE("device arrays: beside a large mesh a small one's mapping goes with it") {
  // With more than 64 MiB in buffers of their own (a large mesh), released
  // mappings are not kept: they would add to the mesh's peak memory.
  Device &dev = device();
  if (!dev.cpu_paths())
    return;
  const DeviceArray<cl_int> large(dev, std::size_t{17} << 20); // 68 MiB, never written
  const std::size_t n = (std::size_t{17} << 10) + 5 * 1024;    // a length no other test uses
  void *memory = nullptr;
  {
    DeviceArray<cl_int> small(dev, n);
    memory = small.buffer().getInfo<CL_MEM_HOST_PTR>();
    small.fill(dev, 7, n);
  }
  CHECK(unmapped_soon(dev, memory));
}

TEST_CASE("device arrays: both scan methods give the exact prefix sums at every length") {
  // Blocks (GPUs) and runs (CPUs): one block or run, several levels of
  // blocks, several runs with a short last one.
  Device &dev = device();
  const std::size_t lengths[] = {1, 7, 255, 256, 2049, 16384, 16385, 100003, 1000000};
  std::vector<cl_int> counts(1000001); // one more: the entry past the end stays unwritten
  for (std::size_t i = 0; i < counts.size(); ++i)
    counts[i] = static_cast<cl_int>((i * 7919) % 5);
  DeviceArray<cl_int> device_counts(dev, counts.size()), offsets(dev, counts.size());
  // (counts[n] is in the array but not in the scan)
  device_counts.upload(dev, counts);
  for (const auto method : {PrefixScan::Method::blocks, PrefixScan::Method::runs}) {
    PrefixScan scan(dev, method);
    for (const std::size_t n : lengths) {
      CAPTURE(n);
      offsets.fill(dev, -1, counts.size());
      const int total = scan.exclusive_scan(device_counts, offsets, n, "test");
      std::vector<cl_int> expected(n + 1);
      std::exclusive_scan(counts.begin(), counts.begin() + n + 1, expected.begin(), 0);
      CHECK(total == expected[n]);
      const std::vector<cl_int> got = offsets.download(dev, n + 1);
      CHECK(std::equal(got.begin(), got.begin() + n, expected.begin()));
      CHECK(got[n] == -1); // nothing written past the end
    }
  }
}

TEST_CASE("device arrays: unique keeps each slot's first entry, short lists and long ones") {
  // Short lists go in one launch by one work-group (unique_in_group), long
  // ones by four launches: the same list either way, in list order,
  // without negative entries, and the marks all clear again.
  Device &dev = device();
  const std::size_t slots = 3000, longest = 20000;
  std::vector<cl_int> list(longest);
  for (std::size_t i = 0; i < longest; ++i)
    list[i] = i % 11 == 3 ? -1 : static_cast<cl_int>((i * 7919 + i / 5) % slots);
  DeviceArray<cl_int> device_list(dev, longest), marks(dev, slots), keep(dev, longest),
      offsets(dev, longest), out(dev, longest);
  device_list.upload(dev, list);
  marks.fill(dev, -1, slots);
  for (const auto method : {PrefixScan::Method::blocks, PrefixScan::Method::runs}) {
    PrefixScan scan(dev, method);
    for (const std::size_t n :
         {std::size_t{1}, std::size_t{100}, std::size_t{4096}, std::size_t{4097}, longest}) {
      CAPTURE(n);
      std::vector<cl_int> expected;
      std::vector<char> seen(slots, 0);
      for (std::size_t i = 0; i < n; ++i)
        if (list[i] >= 0 && !seen[static_cast<std::size_t>(list[i])]) {
          seen[static_cast<std::size_t>(list[i])] = 1;
          expected.push_back(list[i]);
        }
      const int kept = scan.unique(device_list, n, marks, keep, offsets, out, "test");
      REQUIRE(kept == static_cast<int>(expected.size()));
      CHECK(out.download(dev, expected.size()) == expected);
      const std::vector<cl_int> clear = marks.download(dev, slots);
      CHECK(std::all_of(clear.begin(), clear.end(), [](cl_int m) { return m == -1; }));
    }
  }
}

TEST_CASE("device arrays: fills set exactly their range, for 4-, 8- and 16-byte elements") {
  // Device::fill runs a kernel (cl/fill.cl) for these sizes: the pattern
  // must line up with the elements, also when the range starts inside.
  Device &dev = device();
  const std::size_t n = 100003, first = 777;
  DeviceArray<cl_int> ints(dev, n);
  ints.upload(dev, std::vector<cl_int>(n, 5));
  ints.fill(dev, -3, n - 1); // the last entry stays
  const std::vector<cl_int> got_ints = ints.download(dev, n);
  CHECK(std::all_of(got_ints.begin(), got_ints.end() - 1, [](cl_int v) { return v == -3; }));
  CHECK(got_ints.back() == 5);

  const DeviceArray<cl_double> doubles =
      DeviceArray<cl_double>(dev, first).grown(dev, n, -1.0 / 3.0);
  const std::vector<cl_double> got_doubles = doubles.download(dev, n - first, first);
  CHECK(std::all_of(got_doubles.begin(), got_doubles.end(),
                    [](cl_double v) { return v == -1.0 / 3.0; }));

  DeviceArray<cl_double2> pairs(dev, first);
  pairs.upload(dev, std::vector<cl_double2>(first, cl_double2{{7, 8}}));
  const DeviceArray<cl_double2> grown_pairs = pairs.grown(dev, n, cl_double2{{0.25, -2.5}});
  const std::vector<cl_double2> got_pairs = grown_pairs.download(dev, n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = i < first ? 7 : 0.25, y = i < first ? 8 : -2.5;
    if (got_pairs[i].s[0] != x || got_pairs[i].s[1] != y) {
      FAIL_CHECK("pair " << i << " is (" << got_pairs[i].s[0] << ", " << got_pairs[i].s[1] << ")");
      break;
    }
  }
}

TEST_CASE("device arrays: a covered array sets its value as far as it is used, and keeps it") {
  // CoveredArray: cover(n) sets the entries below n (and kFillAhead beyond)
  // that were not set, never those set before (written by kernels since);
  // grow() keeps them.
  Device &dev = device();
  const std::size_t size = 4 * kFillAhead, first = 1000, second = kFillAhead + 5000;
  CoveredArray<cl_int> array(dev, size, -7);
  array.cover(dev, first, "test");
  CHECK(array.covered == first + kFillAhead);
  array.array.fill_range(dev, 3, 0, 10, "test"); // a kernel's writes
  array.cover(dev, second, "test");
  CHECK(array.covered == second + kFillAhead);
  array.grow(dev, 2 * size);
  CHECK(array.array.size() == 2 * size);
  array.cover(dev, 2 * size - 1, "test"); // up to the end at most
  CHECK(array.covered == 2 * size);
  const std::vector<cl_int> got = array.array.download(dev, 2 * size);
  CHECK(std::all_of(got.begin(), got.begin() + 10, [](cl_int v) { return v == 3; }));
  CHECK(std::all_of(got.begin() + 10, got.end(), [](cl_int v) { return v == -7; }));
}

TEST_CASE("device arrays: slab pieces never overlap, and a piece released serves again") {
  Device &dev = device();
  BufferSlabs slabs(dev.context(), 128, std::size_t{128} << 20);
  // Sizes across the classes (about 50 MiB in all), each piece filled with
  // its own number.
  std::vector<std::size_t> sizes;
  for (std::size_t k = 0; k < 300; ++k)
    sizes.push_back(k % 9 == 0 ? BufferSlabs::kLargest : 4 * (1 + (k * 7919) % (16384 >> k % 7)));
  std::vector<cl::Buffer> pieces(sizes.size());
  auto take = [&](std::size_t k) {
    pieces[k] = slabs.take(sizes[k]);
    REQUIRE(pieces[k]());
    dev.queue().enqueueFillBuffer(pieces[k], static_cast<cl_int>(k), 0, sizes[k]);
  };
  auto check = [&](std::size_t k) {
    std::vector<cl_int> got(sizes[k] / 4);
    dev.queue().enqueueReadBuffer(pieces[k], CL_TRUE, 0, sizes[k], got.data());
    CHECK(
        std::all_of(got.begin(), got.end(), [&](cl_int v) { return v == static_cast<cl_int>(k); }));
  };
  for (std::size_t k = 0; k < sizes.size(); ++k)
    take(k);
  for (std::size_t k = 0; k < sizes.size(); ++k)
    check(k);
  // Every other piece goes back and is taken again (from the free lists);
  // the pieces kept still hold their numbers.
  for (std::size_t k = 0; k < sizes.size(); k += 2)
    pieces[k] = cl::Buffer();
  dev.wait("test");
  for (std::size_t k = 0; k < sizes.size(); k += 2)
    take(k);
  for (std::size_t k = 0; k < sizes.size(); ++k)
    check(k);
  // Beyond its bound the slabs give null buffers (the driver's then).
  BufferSlabs one(dev.context(), 128, std::size_t{16} << 20);
  std::vector<cl::Buffer> held;
  for (int k = 0; k < 16; ++k)
    held.push_back(one.take(BufferSlabs::kLargest));
  CHECK(std::all_of(held.begin(), held.end(), [](const cl::Buffer &b) { return b() != nullptr; }));
  CHECK(one.take(4)() == nullptr);
}

TEST_CASE("device memory: a CPU device counts no more than this process could hold") {
  Device &dev = device();
  const auto reported =
      dev.context().getInfo<CL_CONTEXT_DEVICES>().front().getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  CHECK(dev.global_memory() <= reported);
  const std::optional<std::size_t> host = host_memory_for_process();
  REQUIRE(host.has_value()); // Linux says
  CHECK(*host > 0);
  if ((dev.context().getInfo<CL_CONTEXT_DEVICES>().front().getInfo<CL_DEVICE_TYPE>() &
       CL_DEVICE_TYPE_CPU) != 0)
    // Other processes may free memory between the two readings: 1% slack.
    CHECK(static_cast<double>(dev.global_memory()) <= 1.01 * static_cast<double>(*host));
}
