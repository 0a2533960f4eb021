#include "dt/shifting.hpp"

#include <climits>

namespace clmesh {

namespace {
const char *kFile = "shifting.cl";
}

Shifting::Shifting(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      flag_inverted_(device.kernel(kFile, "flag_inverted_triangles", kPhase)),
      leave_out_(device.kernel(kFile, "leave_out_flagged_sites", kPhase)),

      count_lowest_(device.kernel(kFile, "count_lowest_boundary_vertices", kPhase)),
      record_triangles_(device.kernel(kFile, "record_vertex_triangles", kPhase)),
      flag_missing_(device.kernel(kFile, "flag_missing_points", kPhase)), counter_(device, 1) {}

void Shifting::flag_inverted(std::size_t real, const DeviceArray<cl_int> &bad) {
  set_args(flag_inverted_, mesh_.points.buffer(), mesh_.tri_vertex.buffer(), bad.buffer(),
           static_cast<cl_int>(real));
  launch(device_, flag_inverted_, real, kPhase);
}

long Shifting::leave_out_flagged(const DeviceArray<cl_int> &bad,
                                 const DeviceArray<cl_int> &site_state) {
  counter_.fill(device_, 0, 1);
  set_args(leave_out_, bad.buffer(), site_state.buffer(), counter_.buffer(),
           static_cast<cl_int>(mesh_.point_count));
  launch(device_, leave_out_, mesh_.point_count, kPhase);
  return counter_.read(device_, 0);
}

bool Shifting::boundary_winds_once() {
  counter_.fill(device_, 0, 1);
  set_args(count_lowest_, mesh_.points.buffer(), mesh_.tri_vertex.buffer(),
           mesh_.tri_neighbor.buffer(), counter_.buffer(),
           static_cast<cl_int>(mesh_.triangle_count));
  launch(device_, count_lowest_, mesh_.triangle_count, kPhase);
  return counter_.read(device_, 0) == 1;
}

std::size_t Shifting::collect_missing(const DeviceArray<cl_int> &diagram,
                                      const DeviceArray<cl_int> &pixel_of,
                                      const DeviceArray<cl_int> &missing) {
  const std::size_t n = mesh_.point_count;
  mesh_.vertex_triangle.fill(device_, INT_MAX, n);
  set_args(record_triangles_, mesh_.tri_vertex.buffer(), mesh_.vertex_triangle.buffer(),
           static_cast<cl_int>(mesh_.triangle_count));
  launch(device_, record_triangles_, mesh_.triangle_count, kPhase);
  DeviceArray<cl_int> flags(device_, n), offsets(device_, n);
  set_args(flag_missing_, mesh_.vertex_triangle.buffer(), pixel_of.buffer(), diagram.buffer(),
           mesh_.location.buffer(), flags.buffer(), static_cast<cl_int>(n));
  launch(device_, flag_missing_, n, kPhase);
  return static_cast<std::size_t>(scan_.compact_indices(flags, offsets, missing, n, kPhase));
}

} // namespace clmesh
