#include "cdt/mesh_reconstruction.hpp"

#include <algorithm>

namespace clmesh {

namespace {
const char *kFile = "mesh_reconstruction.cl";
}

MeshReconstruction::MeshReconstruction(Device &device, DeviceMesh &mesh,
                                       const std::vector<Triangle> &triangles)
    : device_(device), mesh_(mesh), triangle_count_(triangles.size()),
      match_(device.kernel(kFile, "match_input_triangles", kPhase)),
      row_start_(device, mesh.point_count + 1), row_entry_(device, triangles.size()) {
  // Rows by smallest corner, the other two in the triangle's order.
  std::vector<cl_int> start(mesh.point_count + 1, 0);
  auto smallest = [](const Triangle &t) {
    return static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
  };
  for (const Triangle &t : triangles)
    ++start[static_cast<std::size_t>(t[smallest(t)]) + 1];
  for (std::size_t v = 0; v < mesh.point_count; ++v)
    start[v + 1] += start[v];
  std::vector<cl_int> cursor(start.begin(), start.end() - 1);
  std::vector<cl_int4> entries(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle &t = triangles[i];
    const int k = smallest(t);
    entries[static_cast<std::size_t>(cursor[t[k]]++)] = {
        {t[(k + 1) % 3], t[(k + 2) % 3], static_cast<cl_int>(i), 0}};
  }
  row_start_.upload(device_, start);
  row_entry_.upload(device_, entries);
}

long MeshReconstruction::label() {
  const std::size_t slots = mesh_.triangle_count;
  // Slots that come into use later take their parents' labels (as the
  // exterior removal's labels, fill_ahead): the pages past those in use stay
  // untouched.
  label_ = DeviceArray<cl_int>(device_, mesh_.triangle_capacity);
  label_.fill(device_, -1, fill_ahead(slots, mesh_.triangle_capacity));
  DeviceArray<cl_int> found(device_, triangle_count_), matched(device_, 1);
  found.fill(device_, 0, triangle_count_);
  matched.fill(device_, 0, 1);
  set_args(match_, mesh_.tri_vertex.buffer(), row_start_.buffer(), row_entry_.buffer(),
           label_.buffer(), found.buffer(), matched.buffer(),
           static_cast<cl_int>(row_start_.size() - 1), static_cast<cl_int>(slots));
  launch(device_, match_, slots, kPhase);
  if (static_cast<std::size_t>(matched.read(device_, 0)) == triangle_count_)
    return -1;
  // An input that is no triangulation: one download to name the triangle.
  const std::vector<cl_int> flags = found.download(device_, triangle_count_);
  return static_cast<long>(std::find(flags.begin(), flags.end(), 0) - flags.begin());
}

} // namespace clmesh
