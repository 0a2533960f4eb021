// clmesh — each triangle slot's own area bound, from a sizing field the
// device evaluates or a user's callback the host runs (Options::size_field,
// Options::unsuitable). Kernels: cl/size_bound.cl.
#pragma once

#include "runtime/device_mesh.hpp"

#include "clmesh/size_field.hpp"

namespace clmesh {

class SizeBound {
public:
  static constexpr const char *kPhase = "size_bound";

  // field, unsuitable: either may be null, not both.
  SizeBound(Device &device, DeviceMesh &mesh, const SizeField *field, const Unsuitable *unsuitable);

  // Room for every triangle slot of the mesh (after it grew).
  void fit();
  // The bounds of the slots in `changed` (null: of every slot in use).
  // Rethrows what the callback throws.
  void update(const DeviceList<cl_int> *changed);
  // Per triangle slot: its area bound (<= 0: none).
  const DeviceArray<cl_double> &bounds() const { return bound_; }

private:
  // The background mesh's grid of cells (see cl/size_bound.cl).
  void build_grid(const SizeField &field);

  Device &device_;
  DeviceMesh &mesh_;
  const SizeField *field_;
  const Unsuitable *unsuitable_;
  cl::Kernel evaluate_, gather_, scatter_;
  DeviceArray<cl_double> bound_;
  DeviceArray<cl_int> no_list_; // the list argument when every slot is updated
  DeviceArray<cl_double2> field_points_;
  DeviceArray<cl_double> field_area_;
  DeviceArray<cl_int> field_triangles_, cell_start_, cell_entry_;
  cl_double4 grid_{};
  int columns_ = 1, rows_ = 1;
};

} // namespace clmesh
