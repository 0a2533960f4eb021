#include "runtime/device_mesh.hpp"

#include <algorithm>

namespace clmesh {

DeviceMesh::DeviceMesh(Device &device, std::size_t input_points, std::size_t extra_points)
    : point_capacity(input_points + extra_points), point_count(input_points),
      triangle_capacity(2 * point_capacity + 2),
      // Each winner of an insertion round owns a triangle and adds two, so the
      // 4 entries per winner stay below 4/3 of the triangle slots.
      list_capacity(4 * triangle_capacity / 3 + 16), points(device, point_capacity, kHugePages),
      original_id(device, point_capacity, kHugePages),
      tri_vertex(device, 3 * triangle_capacity, kHugePages),
      tri_neighbor(device, 3 * triangle_capacity, kHugePages),
      tri_mark(device, triangle_capacity, kHugePages),
      modified_stamp(device, triangle_capacity, kHugePages),
      children(device, 3 * triangle_capacity, kHugePages),
      vertex_triangle(device, point_capacity, kHugePages),
      duplicate_of(device, point_capacity, kHugePages),
      location(device, point_capacity, kHugePages),
      location_edge(device, point_capacity, kHugePages), constraint_start(device, 1),
      constraint_adjacent(device, 1), constraint_segment(device, 1), tri_region(device, 1) {}

void DeviceMesh::grow(Device &device, std::size_t extra_points) {
  const std::size_t points_now = point_capacity + extra_points;
  const std::size_t triangles_now = 2 * points_now + 2;
  // Each array keeps its contents; past them its entries are written before
  // they are read, as in a new mesh's arrays, and are not touched (so not
  // resident on a CPU device) until then. Past triangles_filled and
  // points_filled the marks, stamps, duplicates and constraint rows are set
  // when used (fill_triangle_slots, fill_point_slots).
  auto keep = [&](auto &array, std::size_t size) {
    array = array.enlarged(device, size, array.size());
  };
  keep(points, points_now);
  keep(original_id, points_now);
  keep(tri_vertex, 3 * triangles_now);
  keep(tri_neighbor, 3 * triangles_now);
  tri_mark = tri_mark.enlarged(device, triangles_now, triangles_filled);
  modified_stamp = modified_stamp.enlarged(device, triangles_now, triangles_filled);
  keep(children, 3 * triangles_now);
  keep(vertex_triangle, points_now);
  duplicate_of = duplicate_of.enlarged(device, points_now, points_filled);
  keep(location, points_now);
  keep(location_edge, points_now);
  if (has_constraint_rows())
    constraint_start = constraint_start.enlarged(device, points_now + 1, points_filled + 1);
  if (has_regions)
    keep(tri_region, triangles_now);
  if (point_state.size() > 0) {
    keep(point_state, points_now);
    keep(insertion_radius2, points_now);
    keep(point_priority, points_now);
    keep(point_segment, points_now);
  }
  // Past the end of the old ranges there is room again: the free lists start over.
  free_triangles = FreeList{};
  free_points = FreeList{};
  point_capacity = points_now;
  triangle_capacity = triangles_now;
  list_capacity = 4 * triangle_capacity / 3 + 16;
}

void DeviceMesh::discard_except(Device &device,
                                std::initializer_list<const DeviceArray<cl_int> *> kept) {
  const char *phase = "download";
  for (const DeviceArray<cl_int> *array :
       {&original_id, &tri_vertex, &tri_neighbor, &tri_mark, &modified_stamp, &children,
        &vertex_triangle, &duplicate_of, &location, &location_edge, &constraint_start,
        &constraint_adjacent, &constraint_segment, &tri_region, &free_triangles.slots,
        &free_points.slots, &point_state, &point_segment, &segment_end})
    if (std::find(kept.begin(), kept.end(), array) == kept.end())
      array->discard(device, 0, phase);
  points.discard(device, 0, phase);
  insertion_radius2.discard(device, 0, phase);
  point_priority.discard(device, 0, phase);
}

void DeviceMesh::fill_point_slots(Device &device, std::size_t count) {
  if (count <= points_filled)
    return;
  const std::size_t first = points_filled, added = fill_ahead(count, point_capacity) - first;
  duplicate_of.fill_range(device, -1, first, added, "setup");
  // A point's row ends where the next one starts: empty rows end with the last.
  if (has_constraint_rows())
    constraint_start.fill_range(device, constraint_entries, first + 1, added, "setup");
  points_filled += added;
}

void DeviceMesh::fill_triangle_slots(Device &device, std::size_t slots) {
  if (slots <= triangles_filled)
    return;
  const std::size_t count = fill_ahead(slots, triangle_capacity) - triangles_filled;
  tri_mark.fill_range(device, -1, triangles_filled, count, "setup"); // no mark: all bits set
  modified_stamp.fill_range(device, 0, triangles_filled, count, "setup");
  triangles_filled += count;
}

std::size_t DeviceMesh::FreeList::take(std::size_t wanted) {
  const std::size_t reused = std::min(wanted, count);
  first += reused;
  count -= reused;
  return wanted - reused;
}

cl_uint DeviceMesh::bind_triangulation(cl::Kernel &kernel, cl_uint first) const {
  return set_args_from(
      kernel, first, points.buffer(), tri_vertex.buffer(), tri_neighbor.buffer(), tri_mark.buffer(),
      modified_stamp.buffer(), children.buffer(), vertex_triangle.buffer(),
      constraint_start.buffer(), constraint_adjacent.buffer(), static_cast<cl_int>(has_constraints),
      original_id.buffer(), duplicate_of.buffer(), location.buffer(), location_edge.buffer(),
      tri_region.buffer(), static_cast<cl_int>(has_regions));
}

cl_uint DeviceMesh::bind(cl::Kernel &kernel, cl_uint first) const {
  return set_args_from(kernel, bind_triangulation(kernel, first), point_state.buffer(),
                       insertion_radius2.buffer(), point_priority.buffer(), point_segment.buffer(),
                       segment_end.buffer(), constraint_segment.buffer());
}

void DeviceMesh::set_constraint_rows(Device &device, const std::vector<Segment> &segments) {
  // The rows of the points in use (the others end where the last one does).
  const std::size_t n = points_filled, m = segments.size();
  std::vector<cl_int> start(n + 1, 0), adjacent(2 * m), segment(2 * m);
  for (const Segment &s : segments) {
    ++start[s.a + 1];
    ++start[s.b + 1];
  }
  for (std::size_t v = 0; v < n; ++v)
    start[v + 1] += start[v];
  std::vector<cl_int> cursor(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < m; ++i) {
    const Segment &s = segments[i];
    segment[cursor[s.a]] = static_cast<cl_int>(i);
    adjacent[cursor[s.a]++] = s.b;
    segment[cursor[s.b]] = static_cast<cl_int>(i);
    adjacent[cursor[s.b]++] = s.a;
  }
  constraint_start = DeviceArray<cl_int>(device, point_capacity + 1, kHugePages);
  constraint_start.upload(device, start);
  constraint_entries = static_cast<cl_int>(adjacent.size());
  constraint_adjacent = DeviceArray<cl_int>(device, adjacent.size());
  constraint_adjacent.upload(device, adjacent);
  constraint_segment = DeviceArray<cl_int>(device, segment.size());
  constraint_segment.upload(device, segment);
  has_constraints = !adjacent.empty();
}

void DeviceMesh::enable_refinement(Device &device) {
  point_state = DeviceArray<cl_int>(device, point_capacity, kHugePages);
  insertion_radius2 = DeviceArray<cl_double>(device, point_capacity, kHugePages);
  point_priority = DeviceArray<cl_uint>(device, point_capacity, kHugePages);
  point_segment = DeviceArray<cl_int>(device, point_capacity, kHugePages);
  segment_end = DeviceArray<cl_int>(device, 2);
  // Every point so far is an input point, on no segment (CLM_NO_SEGMENT);
  // the ones added later set theirs.
  point_state.fill(device, 0, point_count);
  point_segment.fill(device, -1, point_count);
}

void DeviceMesh::set_segments(Device &device, const std::vector<Segment> &segments) {
  set_constraint_rows(device, segments);
  std::vector<cl_int> ends(2 * segments.size() + 2, -1);
  std::vector<int> meeting(point_count, 0);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    ends[2 * i] = segments[i].a;
    ends[2 * i + 1] = segments[i].b;
    ++meeting[static_cast<std::size_t>(segments[i].a)];
    ++meeting[static_cast<std::size_t>(segments[i].b)];
  }
  segment_end = DeviceArray<cl_int>(device, ends.size());
  segment_end.upload(device, ends);
  std::vector<cl_int> on_segment(point_count);
  for (std::size_t v = 0; v < point_count; ++v)
    on_segment[v] = meeting[v] >= 2 ? -2 : -1; // CLM_SEGMENT_JOINT, CLM_NO_SEGMENT
  point_segment.upload(device, on_segment);
}

} // namespace clmesh
