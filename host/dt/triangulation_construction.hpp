// clmesh — Phase 2 of GPU-DT: triangulation construction from the digital
// Voronoi vertices (thesis §4.1.2). Kernels: cl/triangulation_construction.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

namespace clmesh {

class TriangulationConstruction {
public:
  static constexpr const char *kPhase = "triangulation_construction";

  TriangulationConstruction(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  struct Built {
    bool fits = false;      // the triangles fit in the mesh's slots
    std::size_t real = 0;   // triangles in slots [0, real)
    std::size_t ghosts = 0; // ghost triangles in slots [real, real + ghosts)
  };

  // Writes the triangles dual to the digital Voronoi vertices of `diagram`
  // (grid x grid device point numbers) into the mesh, closes the border cycle
  // with ghost triangles and links neighbours. Sites whose triangles do not
  // fit together are flagged in `bad` (1 per point).
  Built run(const DeviceArray<cl_int> &diagram, int grid, const DeviceArray<cl_int> &bad);

  // Flags in `bad` the sites of every edge of slots [0, slots) whose link is
  // missing, not returned or not the edge reversed.
  void check_links(std::size_t slots, const DeviceArray<cl_int> &bad);

private:
  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel count_blocks_, emit_blocks_, border_sites_, emit_ghosts_, count_visits_,
      flag_repeated_, link_, check_links_;
};

} // namespace clmesh
