// clmesh — compaction of the triangle and Steiner point arrays into Z-order
// (thesis §3.6.1 compacts the arrays to drop their empty slots; the live
// triangles and points also move into spatial order, so that neighbours
// share cache lines). Kernels: cl/zorder_compaction.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

#include "clmesh/geometry.hpp"

namespace clmesh {

class ZOrderCompaction {
public:
  static constexpr const char *kPhase = "zorder_compaction";

  ZOrderCompaction(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // Moves the live triangles to the front, in the order of a Z-order curve
  // over the square of side `side` from `low` (the points' bounding box),
  // then the live Steiner points (slots `first` ..) likewise, and empties
  // both free lists. Every triangle and Steiner slot number changes: lists
  // of them kept elsewhere are void. With slot_flags (one per triangle slot),
  // each triangle's flag moves with it: the array then holds one per new slot.
  // With slot_values (one per triangle slot), each triangle's value moves
  // with it, the array keeping its length.
  void compact(Point low, double side, std::size_t first, DeviceArray<cl_int> *slot_flags = nullptr,
               DeviceArray<cl_double> *slot_values = nullptr);

private:
  // A Z-order grid over the bounding box with about `per_cell` of `items`
  // in each cell.
  struct ZGrid {
    cl_double2 low;
    double scale; // cells per unit
    int bits;     // 2^bits cells a side
    std::size_t cells;
  };
  static ZGrid z_grid(Point low, double side, std::size_t items, std::size_t per_cell);
  // From the cells of `items` (-1: left out): order[k], the item that goes
  // to place k, and new_slot[item], its place, cell by cell, in the order of
  // key[item] inside a cell; `rotated` (triangles): new_slot[item] is the
  // link (place, rotation in key's low two bits). Returns how many are placed.
  std::size_t z_order(const ZGrid &grid, const DeviceArray<cl_int> &cell,
                      const DeviceArray<cl_ulong> &key, bool rotated, std::size_t items,
                      const DeviceArray<cl_int> &order, const DeviceArray<cl_int> &new_slot);
  void compact_triangles(Point low, double side, DeviceArray<cl_int> *slot_flags,
                         DeviceArray<cl_double> *slot_values);
  void compact_steiner_points(Point low, double side, std::size_t first);

  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel triangle_cells_, point_cells_, sort_cells_, move_triangles_, move_points_,
      renumber_vertices_;
};

} // namespace clmesh
