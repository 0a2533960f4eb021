// clmesh — exclusive scan and stream compaction on the device (cl/scan.cl).
#pragma once

#include "runtime/device_mesh.hpp"

#include <map>
#include <string>

namespace clmesh {

class PrefixScan {
public:
  // How exclusive_scan works: blocks of a work-group each, scanned with
  // barriers and added up level by level (for GPUs), or runs of consecutive
  // entries, a work-item each, scanned by plain loops (for CPUs, where a
  // work-group's work-items run one after another). The result is the same.
  // device_default: runs on a device taking the CPU paths (Device::cpu_paths).
  enum class Method { device_default, blocks, runs };
  explicit PrefixScan(Device &device, Method method = Method::device_default);
  bool by_runs() const { return by_runs_; }

  // offsets = exclusive scan of counts[0..n); returns the total (one small read-back).
  int exclusive_scan(const DeviceArray<cl_int> &counts, const DeviceArray<cl_int> &offsets,
                     std::size_t n, const std::string &phase);
  // out[offset[i]] = list[i] for every i with keep[i]; returns how many were kept.
  int compact(const DeviceArray<cl_int> &list, const DeviceArray<cl_int> &keep,
              const DeviceArray<cl_int> &offsets, const DeviceArray<cl_int> &out, std::size_t n,
              const std::string &phase);

  // out[offset[i]] = i for every i with keep[i]; returns how many were kept.
  int compact_indices(const DeviceArray<cl_int> &keep, const DeviceArray<cl_int> &offsets,
                      const DeviceArray<cl_int> &out, std::size_t n, const std::string &phase);

  // out = list[0 .. n) without duplicates and negative entries, each slot at
  // its first position; marks: a per-slot array holding 0xffffffff (restored).
  // keep and offsets: scratch of n entries. Returns the length of out. A
  // short list takes one launch (one work-group), a longer one four.
  int unique(const DeviceArray<cl_int> &list, std::size_t n, const DeviceArray<cl_int> &marks,
             const DeviceArray<cl_int> &keep, const DeviceArray<cl_int> &offsets,
             const DeviceArray<cl_int> &out, const std::string &phase);

  // order = 0 .. n) grouped by key (buckets keys, negative ones left out),
  // bucket b at order[start[b] .. start[b] + size[b]); the order inside a
  // bucket is arbitrary. cursor: scratch of `buckets` entries. Returns how
  // many were placed.
  int bucket(const DeviceArray<cl_int> &key, std::size_t n, std::size_t buckets,
             const DeviceArray<cl_int> &size, const DeviceArray<cl_int> &start,
             const DeviceArray<cl_int> &cursor, const DeviceArray<cl_int> &order,
             const std::string &phase);

private:
  // Scans n entries of `in` into `out` (exclusive); returns the array whose
  // first entry is their total (the top level's block sums).
  const DeviceArray<cl_int> &scan_level(const cl::Buffer &in, const cl::Buffer &out, std::size_t n,
                                        int level, const std::string &phase);
  const DeviceArray<cl_int> &block_sums(int level, std::size_t size);
  int scan_by_runs(const cl::Buffer &in, const cl::Buffer &out, std::size_t n,
                   const std::string &phase);

  Device &device_;
  cl::Kernel scan_blocks_, add_offsets_, compact_, compact_indices_, unique_mark_, unique_keep_,
      unique_compact_, unique_in_group_, count_keys_, scatter_by_key_, sum_runs_, scan_runs_;
  std::size_t group_; // the scan's own work-group size (its result never depends on it)
  bool by_runs_;      // Method::runs
  std::size_t max_runs_;
  DeviceArray<cl_int> run_sums_, run_total_;
  DeviceArray<cl_int> unique_length_; // unique_in_group's result
  std::size_t unique_group_;          // its work-group size
  std::map<int, std::pair<DeviceArray<cl_int>, DeviceArray<cl_int>>> levels_; // sums, scanned
};

} // namespace clmesh
