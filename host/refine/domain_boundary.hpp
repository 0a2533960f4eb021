// clmesh — the domain of a PSLG as refinement's boundary: after GPU-CDT has
// flagged the exterior and the holes, each boundary edge of the domain gets
// its own ghost triangle and the flagged triangles die, so that refinement
// treats the domain's boundary as it treats a convex hull (thesis §3.4.1).
// Kernels: cl/domain_boundary.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

namespace clmesh {

class DomainBoundary {
public:
  static constexpr const char *kPhase = "domain_boundary";

  DomainBoundary(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // Closes the domain left by `removed` (per triangle slot, 1: outside it)
  // with ghosts. The mesh must have room for one more triangle per boundary
  // edge (room_needed). Returns the number of boundary edges.
  std::size_t close(const DeviceArray<cl_int> &removed);

  // The triangle slots closing the domain takes beyond the ones in use; the
  // counts are kept for close(), which must follow with the same `removed`.
  std::size_t room_needed(const DeviceArray<cl_int> &removed);

  // When `removed` flags no triangle (the domain is the convex hull): the
  // hull's ghosts close the domain as they are, and close()'s new ghosts,
  // the same triangles in other slots, are not made. Each vertex points at
  // a kept triangle, as close() leaves it.
  void keep_hull(const DeviceArray<cl_int> &removed);

  // The boundary edges the last close() or keep_hull() found, each with the
  // domain on its left, marker 1 (read from its ghosts: one small download
  // after close(), the whole triangle list after keep_hull()), loop after
  // loop in an order that depends on the input alone.
  std::vector<Segment> edges() const;

private:
  // The removed triangles (and the ghosts unless `keep_ghosts`) die; each
  // vertex points at its smallest kept triangle.
  void retire(const DeviceArray<cl_int> &removed, bool keep_ghosts);

  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel count_, make_ghosts_, link_kept_, retire_, point_at_;
  DeviceArray<cl_int> boundary_edges_, offset_; // per slot, from room_needed
  std::size_t counted_ = 0;                     // their total
  std::size_t first_ghost_ = 0, ghosts_ = 0;    // the ghosts of the last close()
  bool kept_hull_ = false;                      // keep_hull() came last
};

} // namespace clmesh
