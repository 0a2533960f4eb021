#include "runtime/prefix_scan.hpp"

#include <algorithm>

namespace clmesh {

PrefixScan::PrefixScan(Device &device, Method method)
    : device_(device), scan_blocks_(device.kernel("scan.cl", "scan_blocks", "scan")),
      add_offsets_(device.kernel("scan.cl", "scan_add_offsets", "scan")),
      compact_(device.kernel("scan.cl", "compact_list", "scan")),
      compact_indices_(device.kernel("scan.cl", "compact_indices", "scan")),
      unique_mark_(device.kernel("scan.cl", "unique_mark", "scan")),
      unique_keep_(device.kernel("scan.cl", "unique_keep", "scan")),
      unique_compact_(device.kernel("scan.cl", "unique_compact", "scan")),
      unique_in_group_(device.kernel("scan.cl", "unique_in_group", "scan")),
      count_keys_(device.kernel("scan.cl", "count_keys", "scan")),
      scatter_by_key_(device.kernel("scan.cl", "scatter_by_key", "scan")),
      sum_runs_(device.kernel("scan.cl", "sum_runs", "scan")),
      scan_runs_(device.kernel("scan.cl", "scan_runs", "scan")),
      group_(std::min<std::size_t>(256, device.max_work_group())),
      by_runs_(method == Method::runs || (method == Method::device_default && device.cpu_paths())),
      max_runs_(4 * device.compute_units()), run_sums_(device, max_runs_), run_total_(device, 1),
      unique_length_(device, 1), unique_group_(device.single_group(unique_in_group_, "scan")) {}

const DeviceArray<cl_int> &PrefixScan::block_sums(int level, std::size_t size) {
  auto it = levels_.find(level);
  if (it == levels_.end() || it->second.first.size() < size)
    it = levels_
             .insert_or_assign(level, std::make_pair(DeviceArray<cl_int>(device_, size),
                                                     DeviceArray<cl_int>(device_, size)))
             .first;
  return it->second.first;
}

// Items per work-item of scan_blocks (CLM_SCAN_ITEMS in cl/scan.cl).
constexpr std::size_t kScanItems = 8;
constexpr std::size_t kSmallGroup = 32;

const DeviceArray<cl_int> &PrefixScan::scan_level(const cl::Buffer &in, const cl::Buffer &out,
                                                  std::size_t n, int level,
                                                  const std::string &phase) {
  // A short list (most of the flip-flop's passes) takes one small work-group:
  // PoCL pays for each barrier per work-item.
  const std::size_t group = n <= kSmallGroup * kScanItems ? std::min(kSmallGroup, group_) : group_;
  const std::size_t block = group * kScanItems;
  const std::size_t groups = (n + block - 1) / block;
  const auto &sums = block_sums(level, groups);
  set_args(scan_blocks_, in, out, sums.buffer(), cl::Local(sizeof(cl_int) * group),
           static_cast<cl_int>(n));
  launch(device_, scan_blocks_, groups * group, phase, group);
  if (groups == 1)
    return sums; // one block: its sum is the total
  const auto &scanned = levels_.at(level).second;
  const auto &total = scan_level(sums.buffer(), scanned.buffer(), groups, level + 1, phase);
  set_args(add_offsets_, out, scanned.buffer(), static_cast<cl_int>(block), static_cast<cl_int>(n));
  launch(device_, add_offsets_, n, phase);
  return total;
}

// Lists of at most this many entries lose their duplicates in one launch,
// by one work-group (unique_in_group): the four launches of the longer
// ones' way cost more than their work.
constexpr std::size_t kUniqueInGroup = 4096;

// Entries a run takes at least (shorter scans are one loop, one launch); at
// most four runs a compute unit.
constexpr std::size_t kMinRun = 16384;

int PrefixScan::scan_by_runs(const cl::Buffer &in, const cl::Buffer &out, std::size_t n,
                             const std::string &phase) {
  const std::size_t runs = std::min(max_runs_, (n + kMinRun - 1) / kMinRun);
  const auto run = static_cast<cl_int>((n + runs - 1) / runs), items = static_cast<cl_int>(n);
  if (runs > 1) {
    set_args(sum_runs_, in, run_sums_.buffer(), run, items);
    launch(device_, sum_runs_, runs, phase, 1);
  }
  set_args(scan_runs_, in, out, run_sums_.buffer(), run_total_.buffer(), run,
           static_cast<cl_int>(runs), items);
  launch(device_, scan_runs_, runs, phase, 1);
  return run_total_.read(device_, 0);
}

int PrefixScan::exclusive_scan(const DeviceArray<cl_int> &counts,
                               const DeviceArray<cl_int> &offsets, std::size_t n,
                               const std::string &phase) {
  if (n == 0)
    return 0;
  if (by_runs_)
    return scan_by_runs(counts.buffer(), offsets.buffer(), n, phase);
  return scan_level(counts.buffer(), offsets.buffer(), n, 0, phase).read(device_, 0);
}

int PrefixScan::compact(const DeviceArray<cl_int> &list, const DeviceArray<cl_int> &keep,
                        const DeviceArray<cl_int> &offsets, const DeviceArray<cl_int> &out,
                        std::size_t n, const std::string &phase) {
  const int kept = exclusive_scan(keep, offsets, n, phase);
  set_args(compact_, list.buffer(), keep.buffer(), offsets.buffer(), out.buffer(),
           static_cast<cl_int>(n));
  launch(device_, compact_, n, phase);
  return kept;
}

int PrefixScan::compact_indices(const DeviceArray<cl_int> &keep, const DeviceArray<cl_int> &offsets,
                                const DeviceArray<cl_int> &out, std::size_t n,
                                const std::string &phase) {
  const int kept = exclusive_scan(keep, offsets, n, phase);
  set_args(compact_indices_, keep.buffer(), offsets.buffer(), out.buffer(), static_cast<cl_int>(n));
  launch(device_, compact_indices_, n, phase);
  return kept;
}

int PrefixScan::unique(const DeviceArray<cl_int> &list, std::size_t n,
                       const DeviceArray<cl_int> &marks, const DeviceArray<cl_int> &keep,
                       const DeviceArray<cl_int> &offsets, const DeviceArray<cl_int> &out,
                       const std::string &phase) {
  if (n == 0)
    return 0;
  const auto items = static_cast<cl_int>(n);
  if (n <= kUniqueInGroup) {
    set_args(unique_in_group_, list.buffer(), marks.buffer(), keep.buffer(), offsets.buffer(),
             out.buffer(), cl::Local(sizeof(cl_int) * unique_group_), unique_length_.buffer(),
             items);
    launch(device_, unique_in_group_, unique_group_, phase, unique_group_);
    return unique_length_.read(device_, 0);
  }
  set_args(unique_mark_, list.buffer(), marks.buffer(), items);
  launch(device_, unique_mark_, n, phase);
  set_args(unique_keep_, list.buffer(), marks.buffer(), keep.buffer(), items);
  launch(device_, unique_keep_, n, phase);
  const int kept = exclusive_scan(keep, offsets, n, phase);
  set_args(unique_compact_, list.buffer(), keep.buffer(), offsets.buffer(), marks.buffer(),
           out.buffer(), items);
  launch(device_, unique_compact_, n, phase);
  return kept;
}

int PrefixScan::bucket(const DeviceArray<cl_int> &key, std::size_t n, std::size_t buckets,
                       const DeviceArray<cl_int> &size, const DeviceArray<cl_int> &start,
                       const DeviceArray<cl_int> &cursor, const DeviceArray<cl_int> &order,
                       const std::string &phase) {
  const auto items = static_cast<cl_int>(n);
  size.fill(device_, 0, buckets);
  set_args(count_keys_, key.buffer(), size.buffer(), items);
  launch(device_, count_keys_, n, phase);
  const int placed = exclusive_scan(size, start, buckets, phase);
  cursor.fill(device_, 0, buckets);
  set_args(scatter_by_key_, key.buffer(), start.buffer(), cursor.buffer(), order.buffer(), items);
  launch(device_, scatter_by_key_, n, phase);
  return placed;
}

} // namespace clmesh
