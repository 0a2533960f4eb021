// clmesh — the library's one entry point: the input and options go to the
// phase that meshes them (GPU-DT, GPU-CDT, GPU-QM/QM-V), and the result
// comes back as one Mesh with every point, marker and attribute in place.
#include "clmesh/triangulate.hpp"

#include "api/shared_device.hpp"
#include "api/triangle_error.hpp"
#include "api/triangulate_validated.hpp"
#include "cdt/constrained.hpp"
#include "clmesh/errors.hpp"
#include "clmesh/io.hpp"
#include "dt/delaunay.hpp"
#include "output/added_attributes.hpp"
#include "output/second_order.hpp"
#include "output/voronoi_diagram.hpp"
#include "refine/refine.hpp"

#include <algorithm>
#include <memory>
#include <mutex>
#include <utility>

namespace clmesh {

namespace {

// The points the run added (crossings, Steiner points) follow the input's,
// with markers 0 (as in Triangle) and attributes 0 until
// interpolate_added_attributes sets them.
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

// -A: each triangle's regional attribute, one column, when the input lists
// regions (not with -r, as in Triangle: the given triangles' attributes are
// inherited instead).
void take_attributes(Mesh &mesh, const Input &input, const Options &options,
                     std::vector<double> attributes) {
  if (!options.regional_attributes || options.refine || input.regions.empty())
    return;
  if (attributes.size() != mesh.triangles.size())
    throw InternalError("-A: " + std::to_string(attributes.size()) + " regional attributes for " +
                        std::to_string(mesh.triangles.size()) + " triangles");
  mesh.triangle_attribute_count = 1;
  mesh.triangle_attributes = std::move(attributes);
}

// -r: each triangle inherits the attributes of the input triangle it refines.
void take_origin_attributes(Mesh &mesh, const Input &input, const std::vector<int32_t> &origin) {
  const auto count = static_cast<std::size_t>(input.triangle_attribute_count);
  if (count == 0)
    return;
  if (origin.size() != mesh.triangles.size())
    throw InternalError("-r: " + std::to_string(origin.size()) + " origins for " +
                        std::to_string(mesh.triangles.size()) + " triangles");
  mesh.triangle_attribute_count = input.triangle_attribute_count;
  mesh.triangle_attributes.assign(mesh.triangles.size() * count, 0.0);
  for (std::size_t t = 0; t < origin.size(); ++t)
    if (origin[t] >= 0)
      std::copy_n(input.triangle_attributes.begin() +
                      static_cast<std::ptrdiff_t>(origin[t] * count),
                  count, mesh.triangle_attributes.begin() + static_cast<std::ptrdiff_t>(t * count));
}

// Meshes a validated input with validated options.
Mesh mesh_of(Device &device, const Input &input, const Options &options);

// Whether the options ask for refinement (Steiner points).
bool refines(const Options &options) {
  return options.quality || options.max_area || options.regional_areas ||
         options.conforming_delaunay || options.size_field || options.unsuitable;
}

DelaunayOptions delaunay_options_of(const Options &options) {
  DelaunayOptions delaunay_options;
  delaunay_options.tuning = options.tuning;
  delaunay_options.want_voronoi_image = options.voronoi_image;
  return delaunay_options;
}

// The attributes of the added points that lie where segments cross
// (crossed[i]: the input segment added point i was made on), along it; the
// others' stay as they are.
void interpolate_crossings(Mesh &mesh, const Input &input, const std::vector<Segment> &crossed) {
  const std::size_t n = input.points.size(), k = static_cast<std::size_t>(input.attribute_count);
  const std::vector<Point> crossings(mesh.points.begin() + static_cast<std::ptrdiff_t>(n),
                                     mesh.points.begin() +
                                         static_cast<std::ptrdiff_t>(n + crossed.size()));
  const std::vector<double> values = interpolate_along(input.points, input.point_attributes,
                                                       input.attribute_count, crossed, crossings);
  std::copy(values.begin(), values.end(),
            mesh.point_attributes.begin() + static_cast<std::ptrdiff_t>(n * k));
}

// The attributes of the Steiner points of a refinement (and of its segment
// crossings), from the triangulation it started from: output/added_attributes.hpp.
void interpolate_added_attributes(Device &device, Mesh &mesh, const Input &input,
                                  const Options &options) {
  const std::size_t n = input.points.size(), k = static_cast<std::size_t>(input.attribute_count);
  AttributeField field;
  field.points = input.points;
  field.attributes = input.point_attributes;
  if (options.refine) {
    field.triangles = input.triangles;
  } else if (options.pslg) {
    // The constrained Delaunay triangulation of the whole hull, its crossings
    // with their attributes along their segments.
    ConstrainedOptions hull;
    hull.delaunay = delaunay_options_of(options);
    hull.keep_convex_hull = true;
    hull.ignore_holes = true;
    ConstrainedResult cdt =
        constrained_delaunay(device, Pslg{input.points, input.segments, {}, {}}, hull);
    const std::vector<double> crossings =
        interpolate_along(input.points, input.point_attributes, input.attribute_count,
                          cdt.crossed_segments, cdt.added_points);
    field.attributes.insert(field.attributes.end(), crossings.begin(), crossings.end());
    field.points.insert(field.points.end(), cdt.added_points.begin(), cdt.added_points.end());
    field.triangles = std::move(cdt.mesh.triangles);
  } else {
    field.triangles = delaunay(device, input.points, delaunay_options_of(options)).triangles;
  }
  const std::vector<Point> added(mesh.points.begin() + static_cast<std::ptrdiff_t>(n),
                                 mesh.points.end());
  const std::vector<double> values = interpolate_attributes(field, input.attribute_count, added);
  std::copy(values.begin(), values.end(),
            mesh.point_attributes.begin() + static_cast<std::ptrdiff_t>(n * k));
}

// What the options add to a mesh: output markers, edges, the Voronoi
// diagram, second-order nodes.
void complete(Device &device, Mesh &mesh, const Options &options) {
  const MeshView view = view_of(mesh);
  mesh.point_markers = output_vertex_markers(view);
  if (options.edges)
    mesh.edges = mesh.statistics.constrained
                     ? mesh_edges(mesh.triangles, mesh.neighbors, mesh.segments)
                     : mesh_edges(mesh.triangles, mesh.neighbors);
  if (options.voronoi)
    add_voronoi_diagram(device, mesh);
  if (options.second_order)
    add_second_order_nodes(mesh);
}

} // namespace

Mesh triangulate(Device &device, const Input &input, const Options &options) {
  validate(options);
  validate(input);
  return triangulate_validated(device, input, options);
}

Mesh triangulate_validated(Device &device, const Input &input, const Options &options) {
  const std::unique_lock<std::mutex> turn = device.take_turn();
  try {
    return mesh_of(device, input, options);
  } catch (const InputError &error) {
    // The phases name an item of the input ("point 7") or "input": in the
    // input's file when it came from one, as validate() does.
    // An error about a triangle to refine names its own file already.
    if (input.source.empty() ||
        (!input.triangles_source.empty() && error.file() == input.triangles_source))
      throw;
    const std::string &item = error.file();
    throw InputError(item == "input" ? input.source : input.source + ": " + item, error.line(),
                     error.problem());
  }
}

bool options_pack(const Options &options) {
  return !options.pslg && !options.refine && !refines(options) && !options.voronoi_image;
}

bool input_packs(const Input &input) { return packable(input.points, kPackedLargest); }

std::vector<Mesh> triangulate_packed(Device &device, const std::vector<const Input *> &inputs,
                                     const Options &options) {
  const std::unique_lock<std::mutex> turn = device.take_turn();
  std::vector<const std::vector<Point> *> sets;
  for (const Input *input : inputs)
    sets.push_back(&input->points);
  std::vector<DelaunayResult> triangulations =
      delaunay_packed(device, sets, delaunay_options_of(options));
  std::vector<Mesh> meshes(inputs.size());
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    take_points(meshes[k], *inputs[k], {});
    take_triangulation(meshes[k], std::move(triangulations[k]));
    complete(device, meshes[k], options);
  }
  return meshes;
}

namespace {

Mesh mesh_of(Device &device, const Input &input, const Options &options) {
  const DelaunayOptions delaunay_options = delaunay_options_of(options);
  Mesh mesh;
  RefineOptions refine;
  refine.delaunay = delaunay_options;
  refine.min_angle = options.quality ? options.min_angle : 0;
  refine.max_area = options.max_area;
  refine.max_steiner = options.max_steiner;
  refine.conforming = options.conforming_delaunay;
  refine.regional_areas = options.regional_areas;
  refine.attributes = options.regional_attributes;
  refine.protected_segments = options.no_steiner_on_segments;
  refine.size_field = options.size_field.get();
  refine.unsuitable = options.unsuitable ? &options.unsuitable : nullptr;
  ConstrainedOptions constrained;
  constrained.delaunay = delaunay_options;
  constrained.keep_convex_hull = options.convex_hull;
  constrained.ignore_holes = options.ignore_holes;
  constrained.regional_attributes = options.regional_attributes;
  const bool refined = refines(options);
  // A PSLG's mesh: its points, triangles, segments, -A attributes and the
  // statistics of GPU-CDT.
  auto take_pslg = [&](const std::vector<Point> &added, DelaunayResult triangulation,
                       std::vector<Segment> segments, std::vector<double> attributes,
                       const ConstrainedStats &stats) {
    take_points(mesh, input, added);
    take_triangulation(mesh, std::move(triangulation));
    mesh.segments = std::move(segments);
    take_attributes(mesh, input, options, std::move(attributes));
    mesh.statistics.constrained = true;
    mesh.statistics.constraints = stats;
  };
  auto pslg = [&] { return Pslg{input.points, input.segments, input.holes, input.regions}; };
  if (options.refine) {
    if (input.triangles.empty())
      throw InputError("input", 0, "-r refines a mesh, and the input has no triangles");
    // The .poly's segments and holes come with -p only; its regions never
    // (Triangle's -r: the .area file's bounds and the triangles' attributes
    // take their place).
    const std::vector<Segment> no_segments;
    const std::vector<Point> no_holes;
    const std::vector<Region> no_regions;
    const Pslg given{input.points, options.pslg ? input.segments : no_segments,
                     options.pslg ? input.holes : no_holes, no_regions};
    refine.attributes = input.triangle_attribute_count > 0;
    constrained.keep_convex_hull = false;
    RefineResult result;
    try {
      result =
          refine_mesh(device, given, input.triangles, input.triangle_max_area, constrained, refine);
    } catch (const TriangleNotInMesh &bad) {
      throw_triangle_error(input, bad.triangle,
                           "it overlaps another triangle, a vertex lies inside it or a "
                           "segment crosses it: the triangles are no triangulation of the "
                           "vertices and segments");
    }
    take_pslg(result.added_points, std::move(result.mesh), std::move(result.segments), {},
              result.constraints);
    mesh.statistics.refined = true;
    mesh.statistics.refinement = result.stats;
    take_origin_attributes(mesh, input, result.triangle_origin);
  } else if (options.pslg && refined) {
    RefineResult result = refine_constrained(device, pslg(), constrained, refine);
    take_pslg(result.added_points, std::move(result.mesh), std::move(result.segments),
              std::move(result.triangle_attributes), result.constraints);
    mesh.statistics.refined = true;
    mesh.statistics.refinement = result.stats;
  } else if (options.pslg) {
    ConstrainedResult result = constrained_delaunay(device, pslg(), constrained);
    take_pslg(result.added_points, std::move(result.mesh), std::move(result.segments),
              std::move(result.triangle_attributes), result.stats);
    if (input.attribute_count > 0)
      interpolate_crossings(mesh, input, result.crossed_segments);
  } else if (refined) {
    RefineResult result = refine_delaunay(device, input.points, refine);
    take_points(mesh, input, result.added_points);
    take_triangulation(mesh, std::move(result.mesh));
    mesh.statistics.refined = true;
    mesh.statistics.refinement = result.stats;
  } else {
    // The mesh's copy of the points comes once the device's work is done.
    DelaunayResult triangulation = delaunay(device, input.points, delaunay_options);
    take_points(mesh, input, {});
    take_triangulation(mesh, std::move(triangulation));
  }
  if (refined && input.attribute_count > 0 && mesh.points.size() > input.points.size())
    interpolate_added_attributes(device, mesh, input, options);
  complete(device, mesh, options);
  return mesh;
}

} // namespace

Mesh triangulate(Device &device, const Input &input, const std::string &switches) {
  return triangulate(device, input, parse_switches(switches));
}

Mesh triangulate(const Input &input, const Options &options) {
  const std::shared_ptr<SharedDevice> shared =
      shared_device_for(input, options, Meshing::one_input);
  std::lock_guard<std::mutex> lock(shared->busy);
  return triangulate(*shared->device, input, options);
}

} // namespace clmesh
