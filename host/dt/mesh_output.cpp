#include "dt/mesh_output.hpp"

namespace clmesh {

namespace {
const char *kFile = "mesh_output.cl";
}

MeshOutput::MeshOutput(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      flag_real_(device.kernel(kFile, "flag_real_triangles", kPhase)),
      smallest_representative_(device.kernel(kFile, "smallest_representative", kPhase)),
      redirect_duplicates_(device.kernel(kFile, "redirect_duplicates", kPhase)),
      fill_identity_(device.kernel(kFile, "fill_identity", kPhase)),
      restore_numbering_(device.kernel(kFile, "restore_input_numbering", kPhase)),
      invert_numbering_(device.kernel(kFile, "invert_numbering", kPhase)),
      name_points_(device.kernel(kFile, "name_points", kPhase)),
      canonical_(device.kernel(kFile, "canonical_triangles", kPhase)),
      sort_buckets_(device.kernel(kFile, "sort_buckets", kPhase)),
      write_sorted_(device.kernel(kFile, "write_sorted", kPhase)) {}

void MeshOutput::download(std::vector<Triangle> &triangles,
                          std::vector<std::array<int32_t, 3>> &neighbors,
                          std::vector<int32_t> &duplicate_of, const DeviceArray<cl_int> *removed,
                          const DeviceArray<cl_int> *label, std::vector<int32_t> *labels) {
  const std::size_t slots = mesh_.triangle_count;
  // The output is the last use of the mesh: arrays it no longer needs hold
  // the output's intermediate results, and the others give their memory
  // back as soon as they are read for the last time, so the peak memory
  // stays low. The points and the refinement's arrays are not read.
  mesh_.discard_except(device_, {&mesh_.tri_vertex, &mesh_.tri_neighbor, &mesh_.tri_mark,
                                 &mesh_.modified_stamp, &mesh_.children, &mesh_.vertex_triangle,
                                 &mesh_.duplicate_of, &mesh_.location, &mesh_.location_edge,
                                 &mesh_.original_id, &mesh_.tri_region});
  const DeviceArray<cl_int> &is_real = mesh_.tri_mark;
  set_args(flag_real_, mesh_.tri_vertex.buffer(), removed ? removed->buffer() : is_real.buffer(),
           static_cast<cl_int>(removed != nullptr), is_real.buffer(), static_cast<cl_int>(slots));
  launch(device_, flag_real_, slots, kPhase);

  // Identical points: each group is named by its smallest input index
  // (representative, by input index); duplicate_of points the others to it.
  const std::size_t points = mesh_.point_count;
  const auto point_count = static_cast<cl_int>(points);
  const DeviceArray<cl_int> &representative = mesh_.location;
  {
    DeviceArray<cl_int> input_duplicate_of(device_, points);
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
    duplicate_of = input_duplicate_of.download(device_, points);
  }

  // The real triangles in canonical order (cl/mesh_output.cl): rewritten in
  // their slots with the points' names, bucketed by their first corner's
  // device slot, each bucket sorted, then written in that order.
  const DeviceArray<cl_int> &bucket_size = mesh_.location_edge,
                            &bucket_start = mesh_.vertex_triangle;
  const DeviceArray<cl_int> &device_of_input = bucket_size; // until the buckets are counted
  const DeviceArray<cl_int> &name = bucket_start, &home = mesh_.duplicate_of; // likewise
  const DeviceArray<cl_int> &first_slot = mesh_.modified_stamp;
  const DeviceArray<cl_int> &position = is_real; // once the triangles are rewritten
  const DeviceArray<cl_int> &sorted_vertex = mesh_.children;
  std::size_t count = 0;
  DeviceArray<cl_int> sorted_neighbor, sorted_label;
  {
    set_args(invert_numbering_, mesh_.original_id.buffer(), device_of_input.buffer(), point_count);
    launch(device_, invert_numbering_, points, kPhase);
    set_args(name_points_, mesh_.original_id.buffer(), representative.buffer(),
             device_of_input.buffer(), name.buffer(), home.buffer(), point_count);
    launch(device_, name_points_, points, kPhase);
    set_args(canonical_, mesh_.tri_vertex.buffer(), mesh_.tri_neighbor.buffer(), is_real.buffer(),
             name.buffer(), home.buffer(), first_slot.buffer(), static_cast<cl_int>(slots));
    launch(device_, canonical_, slots, kPhase);
    DeviceArray<cl_int> order(device_, slots); // the real ones fill its first entries
    // representative is reused as the buckets' cursors.
    count = static_cast<std::size_t>(scan_.bucket(first_slot, slots, points, bucket_size,
                                                  bucket_start, representative, order, kPhase));
    set_args(sort_buckets_, mesh_.tri_vertex.buffer(), bucket_start.buffer(), bucket_size.buffer(),
             order.buffer(), position.buffer(), point_count);
    launch(device_, sort_buckets_, points, kPhase);
    sorted_neighbor = DeviceArray<cl_int>(device_, 3 * count);
    sorted_label = DeviceArray<cl_int>(device_, label ? count : 1);
    const auto use_label = static_cast<cl_int>(label != nullptr);
    set_args(write_sorted_, order.buffer(), position.buffer(), mesh_.tri_vertex.buffer(),
             mesh_.tri_neighbor.buffer(), label ? label->buffer() : is_real.buffer(), use_label,
             sorted_vertex.buffer(), sorted_neighbor.buffer(), sorted_label.buffer(),
             static_cast<cl_int>(count));
    launch(device_, write_sorted_, count, kPhase);
    device_.wait(kPhase);
  }
  // Triangle and the neighbour triples are three packed ints, as on the device.
  static_assert(sizeof(Triangle) == 3 * sizeof(cl_int));
  static_assert(sizeof(std::array<int32_t, 3>) == 3 * sizeof(cl_int));
  // The host's copy comes as the device's goes: first every array but the
  // sorted ones, then each of these once downloaded.
  mesh_.discard_except(device_, {&sorted_vertex});
  auto download = [&](const DeviceArray<cl_int> &from, void *to) {
    if (count)
      guarded(kPhase, "downloading the mesh", [&] {
        device_.queue().enqueueReadBuffer(from.buffer(), CL_TRUE, 0, 3 * count * sizeof(cl_int),
                                          to);
      });
    from.discard(device_, 0, kPhase);
  };
  triangles.resize(count);
  download(sorted_vertex, triangles.data());
  neighbors.resize(count);
  download(sorted_neighbor, neighbors.data());
  if (label && labels)
    *labels = sorted_label.download(device_, count);
}

} // namespace clmesh
