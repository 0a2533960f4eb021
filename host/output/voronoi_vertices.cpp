#include "output/voronoi_vertices.hpp"

#include "runtime/device_mesh.hpp"

#include <cmath>

namespace clmesh {

VoronoiVertices::VoronoiVertices(Device &device)
    : device_(device), vertices_(device.kernel("voronoi_vertices.cl", "voronoi_vertices", kPhase)) {
}

void VoronoiVertices::compute(const std::vector<Point> &points,
                              const std::vector<double> &attributes, int attribute_count,
                              const std::vector<Triangle> &triangles, std::vector<Point> &centers,
                              std::vector<double> &center_attributes) {
  static_assert(sizeof(Point) == 2 * sizeof(double));
  static_assert(sizeof(Triangle) == 3 * sizeof(cl_int));
  const std::size_t n = triangles.size(), k = static_cast<std::size_t>(attribute_count);
  centers.assign(n, Point{});
  center_attributes.assign(n * k, 0.0);
  if (n == 0)
    return;
  if (attributes.size() < points.size() * k)
    throw InternalError("voronoi_vertices: fewer point attributes than the count says");
  DeviceArray<Point> device_points(device_, points.size());
  DeviceArray<cl_int> device_triangles(device_, 3 * n);
  DeviceArray<double> device_attributes(device_, points.size() * k);
  DeviceArray<Point> device_centers(device_, n);
  DeviceArray<double> device_center_attributes(device_, n * k);
  device_points.upload(device_, points);
  guarded(kPhase, "uploading the triangles", [&] {
    device_.queue().enqueueWriteBuffer(device_triangles.buffer(), CL_TRUE, 0,
                                       3 * n * sizeof(cl_int), triangles.data());
  });
  if (k > 0)
    device_attributes.upload(device_, attributes);
  set_args(vertices_, device_points.buffer(), device_triangles.buffer(), device_attributes.buffer(),
           static_cast<cl_int>(attribute_count), device_centers.buffer(),
           device_center_attributes.buffer(), static_cast<cl_int>(n));
  launch(device_, vertices_, n, kPhase);
  centers = device_centers.download(device_, n);
  if (k > 0)
    center_attributes = device_center_attributes.download(device_, n * k);
  for (std::size_t t = 0; t < n; ++t)
    if (!std::isfinite(centers[t].x) || !std::isfinite(centers[t].y))
      throw InternalError("voronoi_vertices: triangle " + std::to_string(t) +
                          " has collinear corners and no circumcentre");
}

} // namespace clmesh
