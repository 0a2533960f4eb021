// clmesh — each triangle slot's own area bound, from a sizing field the
// device evaluates (Options::size_field), the maximum areas of a refined
// mesh's triangles (-r's .area file: each bounds the triangles whose
// centroid it holds), or a user's callback the host runs
// (Options::unsuitable); the tightest. Kernels: cl/size_bound.cl.
#pragma once

#include "runtime/device_mesh.hpp"

#include "clmesh/size_field.hpp"

namespace clmesh {

class SizeBound {
public:
  static constexpr const char *kPhase = "size_bound";

  // Any of them may be null, not all; `areas`: a mesh with one maximum area
  // per triangle (<= 0: none), in SizeField's shape. With `areas`, the
  // mesh's regions (DeviceMesh::tri_region), when it has them, are the
  // triangles of `areas` its slots descend from: tried first, and unless
  // `keep_regions` (the slots take those triangles' attributes) replaced by
  // the triangle that holds the slot's centroid, where a walk finds one.
  // `areas_across`: the triangles of `areas` across the edge opposite each
  // corner (-1 on the boundary), as the walk takes them.
  SizeBound(Device &device, DeviceMesh &mesh, const SizeField *field, const SizeField *areas,
            const std::vector<cl_int> *areas_across, const Unsuitable *unsuitable,
            bool keep_regions);

  // Room for every triangle slot of the mesh (after it grew).
  void fit();
  // The bounds of the slots in `changed` (null: of every slot in use).
  // Rethrows what the callback throws.
  void update(const DeviceList<cl_int> *changed);
  // Per triangle slot: its area bound (<= 0: none).
  const DeviceArray<cl_double> &bounds() const { return bound_; }
  // The same, for a compaction to move with the slots (ZOrderCompaction):
  // each slot's bound stays right for its triangle.
  DeviceArray<cl_double> &bounds_to_move() { return bound_; }

private:
  // A background mesh on the device, with its grid of cells (see
  // cl/size_bound.cl): values per vertex (interpolated) or per triangle.
  struct Background {
    // `neighbours` (a mesh with values per triangle): its triangles across
    // their edges, as `across` holds them.
    Background(Device &device, const SizeField &mesh, const std::vector<cl_int> *neighbours);
    bool per_triangle;
    DeviceArray<cl_double2> points;
    DeviceArray<cl_double> value;
    DeviceArray<cl_int> triangles, cell_start, cell_entry;
    // Per triangle (per_triangle only): the triangle across the edge
    // opposite each corner, -1 on the boundary.
    DeviceArray<cl_int> across;
    cl_double4 grid{};
    int columns = 1, rows = 1;
    // The smallest positive value (0: none): a triangle smaller than it is
    // within its bound wherever it lies, and is not looked up.
    double least = 0;
  };
  // bound[t] of the listed slots from `background`, the tighter of it and
  // the bound already there when `combine`.
  void evaluate(const Background &background, const cl::Buffer &list, bool use_list, std::size_t n,
                bool combine);

  Device &device_;
  DeviceMesh &mesh_;
  const Unsuitable *unsuitable_;
  bool keep_regions_;
  std::vector<Background> backgrounds_;
  cl::Kernel evaluate_, gather_, scatter_;
  DeviceArray<cl_double> bound_;
  DeviceArray<cl_int> no_list_; // the list argument when every slot is updated
};

} // namespace clmesh
