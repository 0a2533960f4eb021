#include "dt/triangulation_construction.hpp"

namespace clmesh {

namespace {
const char *kFile = "triangulation_construction.cl";
}

TriangulationConstruction::TriangulationConstruction(Device &device, DeviceMesh &mesh,
                                                     PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      count_blocks_(device.kernel(kFile, "count_block_triangles", kPhase)),
      emit_blocks_(device.kernel(kFile, "emit_block_triangles", kPhase)),
      border_sites_(device.kernel(kFile, "border_sites", kPhase)),
      emit_ghosts_(device.kernel(kFile, "emit_ghosts", kPhase)),
      count_visits_(device.kernel(kFile, "count_border_visits", kPhase)),
      flag_repeated_(device.kernel(kFile, "flag_repeated_border_sites", kPhase)),
      link_(device.kernel(kFile, "link_block_triangles", kPhase)),
      check_links_(device.kernel(kFile, "check_links", kPhase)) {}

TriangulationConstruction::Built TriangulationConstruction::run(const DeviceArray<cl_int> &diagram,
                                                                int grid,
                                                                const DeviceArray<cl_int> &bad) {
  Built built;
  const auto g = static_cast<cl_int>(grid);
  const std::size_t blocks = static_cast<std::size_t>(grid - 1) * (grid - 1);
  const std::size_t n = mesh_.point_count;
  DeviceArray<cl_int> counts(device_, blocks), offsets(device_, blocks);
  set_args(count_blocks_, diagram.buffer(), counts.buffer(), g);
  launch(device_, count_blocks_, blocks, kPhase);
  built.real = static_cast<std::size_t>(scan_.exclusive_scan(counts, offsets, blocks, kPhase));
  counts = DeviceArray<cl_int>();

  // The border cycle, one ghost per edge.
  const std::size_t length = 4 * static_cast<std::size_t>(grid - 1);
  DeviceArray<cl_int> site(device_, length), starts(device_, length),
      border_offsets(device_, length), cycle(device_, length);
  set_args(border_sites_, diagram.buffer(), site.buffer(), starts.buffer(), g);
  launch(device_, border_sites_, length, kPhase);
  built.ghosts =
      static_cast<std::size_t>(scan_.compact(site, starts, border_offsets, cycle, length, kPhase));
  if (built.real == 0 || built.ghosts < 3 || built.real + built.ghosts > mesh_.triangle_capacity)
    return built;

  DeviceArray<cl_int> block_of(device_, built.real);
  set_args(emit_blocks_, mesh_.points.buffer(), diagram.buffer(), offsets.buffer(),
           mesh_.tri_vertex.buffer(), block_of.buffer(), g);
  launch(device_, emit_blocks_, blocks, kPhase);
  const auto m = static_cast<cl_int>(built.ghosts);
  const auto real = static_cast<cl_int>(built.real);
  set_args(emit_ghosts_, cycle.buffer(), mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(),
           real, m);
  launch(device_, emit_ghosts_, built.ghosts, kPhase);
  DeviceArray<cl_int> visits(device_, n);
  visits.fill(device_, 0, n);
  set_args(count_visits_, cycle.buffer(), visits.buffer(), m);
  launch(device_, count_visits_, built.ghosts, kPhase);
  set_args(flag_repeated_, cycle.buffer(), visits.buffer(), bad.buffer(), m);
  launch(device_, flag_repeated_, built.ghosts, kPhase);

  // Neighbour links along the Voronoi edges, then the check that they pair up.
  set_args(link_, diagram.buffer(), offsets.buffer(), block_of.buffer(), mesh_.tri_vertex.buffer(),
           mesh_.tri_neighbor.buffer(), border_offsets.buffer(), real, m, real, g);
  launch(device_, link_, built.real, kPhase);
  check_links(built.real + built.ghosts, bad);
  built.fits = true;
  return built;
}

void TriangulationConstruction::check_links(std::size_t slots, const DeviceArray<cl_int> &bad) {
  set_args(check_links_, mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(), bad.buffer(),
           static_cast<cl_int>(slots));
  launch(device_, check_links_, slots, kPhase);
}

} // namespace clmesh
