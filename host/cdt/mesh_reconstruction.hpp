// clmesh — a mesh given to refine (Triangle's -r) found in the CDT of its
// vertices and edges: each CDT triangle labelled with the input triangle it
// is, or -1 outside the mesh. Kernels: cl/mesh_reconstruction.cl.
#pragma once

#include "runtime/device_mesh.hpp"

#include <vector>

namespace clmesh {

class MeshReconstruction {
public:
  static constexpr const char *kPhase = "mesh_reconstruction";

  // `triangles`: the input's, counter-clockwise, corners in device numbering.
  MeshReconstruction(Device &device, DeviceMesh &mesh, const std::vector<Triangle> &triangles);

  // Labels every triangle slot of the mesh with the input triangle it is
  // (-1: none). Returns -1 when every input triangle is in the mesh, else
  // the first one that is not (it overlaps another one or holds a vertex).
  long label();
  // Per triangle slot, after label().
  const DeviceArray<cl_int> &labels() const { return label_; }

private:
  Device &device_;
  DeviceMesh &mesh_;
  std::size_t triangle_count_;
  cl::Kernel match_;
  DeviceArray<cl_int> row_start_;
  DeviceArray<cl_int4> row_entry_;
  DeviceArray<cl_int> label_;
};

} // namespace clmesh
