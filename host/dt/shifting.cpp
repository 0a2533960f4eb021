#include "dt/shifting.hpp"

#include <climits>

namespace clmesh {

namespace {
const char *kFile = "shifting.cl";
}

Shifting::Shifting(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      list_turned_(device.kernel(kFile, "list_turned_triangles", kPhase)),
      claim_flips_(device.kernel(kFile, "claim_untangling_flips", kPhase)),
      apply_flips_(device.kernel(kFile, "apply_untangling_flips", kPhase)),
      relink_(device.kernel(kFile, "relink_untangled", kPhase)),
      flag_turned_(device.kernel(kFile, "flag_turned_sites", kPhase)),
      leave_out_(device.kernel(kFile, "leave_out_flagged_pixels", kPhase)),

      count_lowest_(device.kernel(kFile, "count_lowest_boundary_vertices", kPhase)),
      record_triangles_(device.kernel(kFile, "record_vertex_triangles", kPhase)),
      flag_missing_(device.kernel(kFile, "flag_missing_points", kPhase)), counter_(device, 1) {}

long Shifting::untangle(std::size_t real, std::size_t slots, const DeviceArray<cl_int> &bad,
                        int &stamp) {
  // Sized for the largest round; pages come as written, a few for a short list.
  if (turned_.size() < real)
    turned_ = DeviceArray<cl_int>(device_, real);
  if (claim_.size() < slots)
    claim_ = DeviceArray<cl_int>(device_, slots);
  counter_.fill(device_, 0, 1);
  set_args(list_turned_, mesh_.points.buffer(), mesh_.tri_vertex.buffer(), turned_.buffer(),
           counter_.buffer(), static_cast<cl_int>(real));
  launch(device_, list_turned_, real, kPhase);
  const long turned = counter_.read(device_, 0);
  long flips = 0;
  if (turned == 0)
    return flips;
  const auto count = static_cast<cl_int>(turned);
  // relink_edge tells a flipped neighbour by its stamp: every slot gets one.
  mesh_.fill_triangle_slots(device_, slots);
  const cl::Buffer &points = mesh_.points.buffer(), &vertices = mesh_.tri_vertex.buffer(),
                   &neighbors = mesh_.tri_neighbor.buffer(),
                   &stamps = mesh_.modified_stamp.buffer(), &children = mesh_.children.buffer();
  // A flip can only make room for another (a claim lost, a neighbour's turn).
  for (int pass = 0; pass < kUntanglingPasses; ++pass) {
    for (const cl_int reset : {1, 0}) {
      set_args(claim_flips_, points, vertices, neighbors, turned_.buffer(), claim_.buffer(), reset,
               count);
      launch(device_, claim_flips_, turned, kPhase);
    }
    const auto pass_stamp = static_cast<cl_int>(stamp++);
    counter_.fill(device_, 0, 1);
    set_args(apply_flips_, points, vertices, neighbors, stamps, children, turned_.buffer(),
             claim_.buffer(), counter_.buffer(), pass_stamp, count);
    launch(device_, apply_flips_, turned, kPhase);
    set_args(relink_, vertices, neighbors, stamps, children, turned_.buffer(), claim_.buffer(),
             pass_stamp, count);
    launch(device_, relink_, turned, kPhase);
    const long flipped = counter_.read(device_, 0);
    flips += flipped;
    if (flipped == 0)
      break;
  }
  set_args(flag_turned_, points, vertices, turned_.buffer(), bad.buffer(), count);
  launch(device_, flag_turned_, turned, kPhase);
  return flips;
}

long Shifting::leave_out_flagged(const DeviceArray<cl_int> &bad,
                                 const DeviceArray<cl_int> &site_state,
                                 const DeviceArray<cl_int> &diagram,
                                 const DeviceArray<cl_int> &pixel_of) {
  counter_.fill(device_, 0, 1);
  set_args(leave_out_, bad.buffer(), site_state.buffer(), diagram.buffer(), pixel_of.buffer(),
           counter_.buffer(), static_cast<cl_int>(mesh_.point_count));
  launch(device_, leave_out_, mesh_.point_count, kPhase);
  const long flagged = counter_.read(device_, 0);
  if (flagged > 0)
    bad.fill(device_, 0, mesh_.point_count);
  return flagged;
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
