#include "refine/domain_boundary.hpp"

#include "clmesh/errors.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace clmesh {

namespace {
const char *kFile = "domain_boundary.cl";
constexpr cl_int kInfinite = -1; // CLM_INFINITE (cl/common.h): a ghost's vertex
} // namespace

DomainBoundary::DomainBoundary(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      count_(device.kernel(kFile, "count_boundary_edges", kPhase)),
      make_ghosts_(device.kernel(kFile, "make_ghosts", kPhase)),
      link_kept_(device.kernel(kFile, "link_kept_triangles", kPhase)),
      retire_(device.kernel(kFile, "retire_exterior", kPhase)),
      point_at_(device.kernel(kFile, "point_at_kept_triangles", kPhase)) {}

std::size_t DomainBoundary::room_needed(const DeviceArray<cl_int> &removed) {
  const std::size_t slots = mesh_.triangle_count;
  boundary_edges_ = DeviceArray<cl_int>(device_, slots);
  offset_ = DeviceArray<cl_int>(device_, slots);
  set_args_from(count_, mesh_.bind_triangulation(count_, 0), removed.buffer(),
                boundary_edges_.buffer(), static_cast<cl_int>(slots));
  launch(device_, count_, slots, kPhase);
  counted_ =
      static_cast<std::size_t>(scan_.exclusive_scan(boundary_edges_, offset_, slots, kPhase));
  return counted_;
}

std::size_t DomainBoundary::close(const DeviceArray<cl_int> &removed) {
  const std::size_t slots = mesh_.triangle_count;
  // The counts of room_needed, when it counted these slots (growing the
  // arrays for the ghosts moves no triangle).
  const std::size_t ghosts = offset_.size() == slots ? counted_ : room_needed(removed);
  if (slots + ghosts > mesh_.triangle_capacity)
    throw InternalError("no room for the ghosts of the domain's boundary");
  const auto first_ghost = static_cast<cl_int>(slots);
  mesh_.fill_triangle_slots(device_, slots + ghosts);
  DeviceArray<cl_int> lost(device_, 1);
  lost.fill(device_, 0, 1);
  set_args_from(make_ghosts_, mesh_.bind_triangulation(make_ghosts_, 0), removed.buffer(),
                offset_.buffer(), first_ghost, static_cast<cl_int>(slots + 8), lost.buffer(),
                static_cast<cl_int>(slots));
  launch(device_, make_ghosts_, slots, kPhase);
  if (lost.read(device_, 0) != 0)
    throw InternalError("a boundary loop of the domain could not be followed");
  set_args_from(link_kept_, mesh_.bind_triangulation(link_kept_, 0), removed.buffer(),
                offset_.buffer(), first_ghost, static_cast<cl_int>(slots));
  launch(device_, link_kept_, slots, kPhase);
  retire(removed, false);
  mesh_.triangle_count = slots + ghosts;
  boundary_edges_ = {};
  offset_ = {};
  first_ghost_ = slots;
  ghosts_ = ghosts;
  kept_hull_ = false;
  return ghosts;
}

void DomainBoundary::keep_hull(const DeviceArray<cl_int> &removed) {
  retire(removed, true);
  kept_hull_ = true;
}

void DomainBoundary::retire(const DeviceArray<cl_int> &removed, bool keep_ghosts) {
  const std::size_t slots = mesh_.triangle_count;
  DeviceArray<cl_int> owner(device_, mesh_.point_count);
  owner.fill(device_, 0x7fffffff, mesh_.point_count);
  set_args_from(retire_, mesh_.bind_triangulation(retire_, 0), removed.buffer(),
                static_cast<cl_int>(keep_ghosts), owner.buffer(), static_cast<cl_int>(slots));
  launch(device_, retire_, slots, kPhase);
  set_args_from(point_at_, mesh_.bind_triangulation(point_at_, 0), owner.buffer(),
                static_cast<cl_int>(mesh_.point_count));
  launch(device_, point_at_, mesh_.point_count, kPhase);
}

std::vector<Segment> DomainBoundary::edges() const {
  // The ghosts (infinity, q, p) on edges p -> q, in any rotation.
  std::vector<Segment> by_start;
  const auto add_ghost = [&](const cl_int *corners) {
    for (int k = 0; k < 3; ++k)
      if (corners[k] == kInfinite)
        by_start.push_back({corners[(k + 2) % 3], corners[(k + 1) % 3], 1});
  };
  if (kept_hull_) {
    const std::vector<cl_int> corners =
        mesh_.tri_vertex.download(device_, 3 * mesh_.triangle_count);
    for (std::size_t t = 0; t < mesh_.triangle_count; ++t)
      add_ghost(&corners[3 * t]);
  } else {
    const std::vector<cl_int> corners =
        mesh_.tri_vertex.download(device_, 3 * ghosts_, 3 * first_ghost_);
    by_start.reserve(ghosts_);
    for (std::size_t g = 0; g < ghosts_; ++g)
      add_ghost(&corners[3 * g]);
  }
  // The ghosts' slots follow the triangulation's history; the loops, each
  // from its lowest vertex (the lowest edge out of a vertex the loop passes
  // twice), follow the input alone.
  const auto lower = [](const Segment &x, const Segment &y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  };
  std::sort(by_start.begin(), by_start.end(), lower);
  std::vector<char> used(by_start.size(), 0);
  std::vector<Segment> edges;
  edges.reserve(by_start.size());
  for (std::size_t first = 0; first < by_start.size(); ++first) {
    for (std::size_t e = first; !used[e];) {
      used[e] = 1;
      edges.push_back(by_start[e]);
      const Segment from{by_start[e].b, std::numeric_limits<int32_t>::min(), 0};
      e = static_cast<std::size_t>(std::lower_bound(by_start.begin(), by_start.end(), from, lower) -
                                   by_start.begin());
      while (e < by_start.size() && by_start[e].a == from.a && used[e])
        ++e;
      if (e == by_start.size() || by_start[e].a != from.a)
        break;
    }
  }
  return edges;
}

} // namespace clmesh
