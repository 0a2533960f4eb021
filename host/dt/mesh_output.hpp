// clmesh — the mesh in canonical order, downloaded (thesis §3.6.1).
// Kernels: cl/mesh_output.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

#include "clmesh/geometry.hpp"

#include <array>
#include <vector>

namespace clmesh {

class MeshOutput {
public:
  static constexpr const char *kPhase = "download";

  MeshOutput(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // Consumes the mesh (its arrays hold intermediate results): the last step.
  // Real triangles (ghosts dropped) in canonical order (each from its smallest
  // vertex, sorted) with neighbour links, -1 on the hull, the per-slot
  // `label` of each (when given) in `labels`, and
  // for each point the point that stands for it (-1: itself), the smallest
  // index of each group of identical points standing for the group.
  void download(std::vector<Triangle> &triangles, std::vector<std::array<int32_t, 3>> &neighbors,
                std::vector<int32_t> &duplicate_of, const DeviceArray<cl_int> *removed = nullptr,
                const DeviceArray<cl_int> *label = nullptr, std::vector<int32_t> *labels = nullptr);

private:
  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel flag_real_, smallest_representative_, redirect_duplicates_, fill_identity_,
      restore_numbering_, invert_numbering_, name_points_, canonical_, sort_buckets_, write_sorted_;
};

} // namespace clmesh
