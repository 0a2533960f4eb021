// clmesh — the library's one entry point: the input and options go to the
// phase that meshes them (GPU-DT, GPU-CDT, GPU-QM/QM-V), and the result
// comes back as one Mesh with every point, marker and attribute in place.
#include "clmesh/triangulate.hpp"

#include "cdt/constrained.hpp"
#include "clmesh/errors.hpp"
#include "clmesh/io.hpp"
#include "dt/delaunay.hpp"
#include "refine/refine.hpp"

#include <map>
#include <memory>
#include <mutex>

namespace clmesh {

namespace {

// The points the run added (crossings, Steiner points) follow the input's,
// with zero attributes and markers, as in Triangle.
void take_points(Mesh &mesh, const Input &input, const std::vector<Point> &added) {
  mesh.points.reserve(input.points.size() + added.size());
  mesh.points = input.points;
  mesh.points.insert(mesh.points.end(), added.begin(), added.end());
  mesh.input_points = static_cast<long>(input.points.size());
  mesh.attribute_count = input.attribute_count;
  mesh.point_attributes = input.point_attributes;
  mesh.point_attributes.resize(mesh.points.size() * static_cast<std::size_t>(input.attribute_count),
                               0.0);
  if (!input.point_markers.empty()) {
    mesh.point_markers = input.point_markers;
    mesh.point_markers.resize(mesh.points.size(), 0);
  }
}

void take_triangulation(Mesh &mesh, DelaunayResult &&result) {
  mesh.triangles = std::move(result.triangles);
  mesh.neighbors = std::move(result.neighbors);
  mesh.duplicate_of = std::move(result.duplicate_of);
  mesh.voronoi_image = std::move(result.voronoi);
  mesh.statistics.delaunay = std::move(result.stats);
  // duplicate_of covers the input points; the added ones are never duplicates.
  mesh.duplicate_of.resize(mesh.points.size(), -1);
}

// Meshes a validated input with validated options.
Mesh mesh_of(Device &device, const Input &input, const Options &options);

} // namespace

Mesh triangulate(Device &device, const Input &input, const Options &options) {
  validate(options);
  validate(input);
  try {
    return mesh_of(device, input, options);
  } catch (const InputError &error) {
    // The phases name an item of the input ("point 7") or "input": in the
    // input's file when it came from one, as validate() does.
    if (input.source.empty())
      throw;
    const std::string &item = error.file();
    throw InputError(item == "input" ? input.source : input.source + ": " + item, error.line(),
                     error.problem());
  }
}

namespace {

Mesh mesh_of(Device &device, const Input &input, const Options &options) {
  DelaunayOptions delaunay_options;
  delaunay_options.tuning = options.tuning;
  delaunay_options.want_voronoi_image = options.voronoi_image;
  Mesh mesh;
  RefineOptions refine;
  refine.delaunay = delaunay_options;
  refine.min_angle = options.quality ? options.min_angle : 0;
  refine.max_area = options.max_area;
  refine.max_steiner = options.max_steiner;
  ConstrainedOptions constrained;
  constrained.delaunay = delaunay_options;
  constrained.keep_convex_hull = options.convex_hull;
  constrained.ignore_holes = options.ignore_holes;
  constrained.regional_attributes = options.regional_attributes;
  const bool refined = options.quality || options.max_area;
  if (options.pslg && refined) {
    RefineResult result =
        refine_constrained(device, Pslg{input.points, input.segments, input.holes, input.regions},
                           constrained, refine);
    take_points(mesh, input, result.added_points);
    take_triangulation(mesh, std::move(result.mesh));
    mesh.segments = std::move(result.segments);
    mesh.statistics.constrained = true;
    mesh.statistics.constraints = result.constraints;
    mesh.statistics.refined = true;
    mesh.statistics.refinement = result.stats;
  } else if (options.pslg) {
    ConstrainedResult result = constrained_delaunay(
        device, Pslg{input.points, input.segments, input.holes, input.regions}, constrained);
    take_points(mesh, input, result.added_points);
    take_triangulation(mesh, std::move(result.mesh));
    mesh.segments = std::move(result.segments);
    if (options.regional_attributes) {
      if (result.triangle_attributes.size() != mesh.triangles.size())
        throw InternalError("-A: " + std::to_string(result.triangle_attributes.size()) +
                            " regional attributes for " + std::to_string(mesh.triangles.size()) +
                            " triangles");
      mesh.triangle_attribute_count = 1;
      mesh.triangle_attributes = std::move(result.triangle_attributes);
    }
    mesh.statistics.constrained = true;
    mesh.statistics.constraints = result.stats;
  } else if (refined) {
    RefineResult result = refine_delaunay(device, input.points, refine);
    take_points(mesh, input, result.added_points);
    take_triangulation(mesh, std::move(result.mesh));
    mesh.statistics.refined = true;
    mesh.statistics.refinement = result.stats;
  } else {
    take_points(mesh, input, {});
    take_triangulation(mesh, delaunay(device, input.points, delaunay_options));
  }
  const MeshView view = view_of(mesh);
  mesh.point_markers = output_vertex_markers(view);
  if (options.edges)
    mesh.edges = mesh.statistics.constrained
                     ? mesh_edges(mesh.triangles, mesh.neighbors, mesh.segments)
                     : mesh_edges(mesh.triangles, mesh.neighbors);
  return mesh;
}

} // namespace

Mesh triangulate(Device &device, const Input &input, const std::string &switches) {
  return triangulate(device, input, parse_switches(switches));
}

Mesh triangulate(const Input &input, const Options &options) {
  // One device per process and name: its context and built programs serve
  // every later call, one call at a time.
  struct Shared {
    std::shared_ptr<Device> device;
    std::mutex busy;
  };
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<Shared>> devices;
  std::shared_ptr<Shared> shared;
  {
    std::lock_guard<std::mutex> lock(mutex);
    std::shared_ptr<Shared> &slot = devices[options.device];
    if (!slot) {
      auto opened = std::make_shared<Shared>();
      opened->device = open_device(options.device);
      slot = opened;
    }
    shared = slot;
  }
  std::lock_guard<std::mutex> lock(shared->busy);
  return triangulate(*shared->device, input, options);
}

} // namespace clmesh
