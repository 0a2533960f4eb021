#include "mesh_output.hpp"

namespace clmesh {

namespace {
const char *kFile = "mesh_output.cl";
}

MeshOutput::MeshOutput(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      flag_real_(device.kernel(kFile, "flag_real_triangles", kPhase)),
      write_real_(device.kernel(kFile, "write_real_triangles", kPhase)),
      smallest_representative_(device.kernel(kFile, "smallest_representative", kPhase)),
      redirect_duplicates_(device.kernel(kFile, "redirect_duplicates", kPhase)),
      rename_vertices_(device.kernel(kFile, "rename_vertices", kPhase)),
      fill_identity_(device.kernel(kFile, "fill_identity", kPhase)),
      restore_numbering_(device.kernel(kFile, "restore_input_numbering", kPhase)) {}

void MeshOutput::download(std::vector<Triangle> &triangles,
                          std::vector<std::array<int32_t, 3>> &neighbors,
                          std::vector<int32_t> &duplicate_of) {
  const std::size_t slots = mesh_.triangle_count;
  DeviceArray<cl_int> is_real(device_, slots), new_index(device_, slots);
  set_args(flag_real_, mesh_.tri_vertex.buffer(), is_real.buffer(), static_cast<cl_int>(slots));
  launch(device_, flag_real_, slots, kPhase);
  const auto count = static_cast<std::size_t>(scan_.exclusive_scan(is_real, new_index, slots, kPhase));
  DeviceArray<cl_int> out_vertex(device_, 3 * count), out_neighbor(device_, 3 * count);
  set_args(write_real_, mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(), is_real.buffer(),
           new_index.buffer(), out_vertex.buffer(), out_neighbor.buffer(),
           static_cast<cl_int>(slots));
  launch(device_, write_real_, slots, kPhase);
  const std::size_t points = mesh_.point_capacity;
  const auto point_count = static_cast<cl_int>(points);
  DeviceArray<cl_int> input_duplicate_of(device_, points), representative(device_, points);
  set_args(restore_numbering_, mesh_.duplicate_of.buffer(), mesh_.original_id.buffer(),
           input_duplicate_of.buffer(), point_count);
  launch(device_, restore_numbering_, points, kPhase);
  set_args(fill_identity_, representative.buffer(), point_count);
  launch(device_, fill_identity_, points, kPhase);
  set_args(smallest_representative_, input_duplicate_of.buffer(), representative.buffer(),
           point_count);
  launch(device_, smallest_representative_, points, kPhase);
  set_args(redirect_duplicates_, input_duplicate_of.buffer(), representative.buffer(),
           point_count);
  launch(device_, redirect_duplicates_, points, kPhase);
  set_args(rename_vertices_, out_vertex.buffer(), mesh_.original_id.buffer(),
           representative.buffer(), static_cast<cl_int>(3 * count));
  launch(device_, rename_vertices_, 3 * count, kPhase);
  duplicate_of = input_duplicate_of.download(device_, points);
  const auto vertices = out_vertex.download(device_, 3 * count);
  const auto links = out_neighbor.download(device_, 3 * count);
  triangles.resize(count);
  neighbors.resize(count);
  for (std::size_t t = 0; t < count; ++t)
    for (int i = 0; i < 3; ++i) {
      triangles[t][i] = vertices[3 * t + i];
      neighbors[t][i] = links[3 * t + i];
    }
}

} // namespace clmesh
