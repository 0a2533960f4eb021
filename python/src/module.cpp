// clmesh._clmesh — the library for Python. Arrays come in already shaped
// and typed by clmesh/_input.py (this side checks the shapes again, so that no
// call can read out of bounds) and become an Input; a Run keeps the input,
// options and mesh of one triangulate() call, run with the GIL released on
// the process's shared device, and hands its parts out as new NumPy arrays.
// triangulate_many() meshes many Inputs through the library's batch, with the
// GIL released once, and returns a Run or an exception object for each. A
// SizeField is a checked sizing field (clmesh/_size_field.py builds it from a
// dict); an `unsuitable` callable runs with the GIL taken back.
#include <clmesh/clmesh.hpp>

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/unique_ptr.h>
#include <nanobind/stl/vector.h>

#include <array>
#include <cstdint>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <vector>

namespace nb = nanobind;

namespace {

template <class T> using In = nb::ndarray<const T, nb::ndim<2>, nb::c_contig, nb::device::cpu>;
template <class T> using Out = nb::ndarray<nb::numpy, T>;

// `values` as a new NumPy array of `rows` rows that owns them.
template <class T> Out<T> array(std::vector<T> &&values, std::size_t rows, std::size_t columns) {
  auto *owned = new std::vector<T>(std::move(values));
  nb::capsule owner(owned, [](void *p) noexcept { delete static_cast<std::vector<T> *>(p); });
  return Out<T>(owned->data(), {rows, columns}, owner);
}

// Rows of three indices (triangles, neighbours) as an int32 (N, 3) array.
Out<int32_t> index_rows(const std::vector<std::array<int32_t, 3>> &rows) {
  std::vector<int32_t> values;
  values.reserve(rows.size() * 3);
  for (const std::array<int32_t, 3> &row : rows)
    values.insert(values.end(), row.begin(), row.end());
  return array(std::move(values), rows.size(), 3);
}

// Edges or segments as their ends (int32 (N, 2)) and markers (int32 (N, 1)).
template <class Link> nb::tuple ends_and_markers(const std::vector<Link> &links) {
  std::vector<int32_t> ends, markers;
  for (const Link &link : links) {
    ends.insert(ends.end(), {link.a, link.b});
    markers.push_back(link.marker);
  }
  return nb::make_tuple(array(std::move(ends), links.size(), 2),
                        array(std::move(markers), links.size(), 1));
}

// An array given by Python must have `columns` columns (and, when rows >= 0,
// that many rows).
template <class T>
void require_shape(const In<T> &values, const char *name, std::size_t columns, long rows = -1) {
  if (values.shape(1) != columns || (rows >= 0 && values.shape(0) != static_cast<size_t>(rows)))
    throw clmesh::InputError("input", 0,
                             std::string(name) + " has shape (" + std::to_string(values.shape(0)) +
                                 ", " + std::to_string(values.shape(1)) + "), expected " +
                                 (rows >= 0 ? "(" + std::to_string(rows) : std::string("(N")) +
                                 ", " + std::to_string(columns) + ")");
}

// Points as a float64 (N, 2) array.
Out<double> xy_rows(const std::vector<clmesh::Point> &points) {
  std::vector<double> xy;
  xy.reserve(points.size() * 2);
  for (const clmesh::Point &p : points)
    xy.insert(xy.end(), {p.x, p.y});
  return array(std::move(xy), points.size(), 2);
}

// -v: the Voronoi edges as their ends (int32 (E, 2), -1 second end for a ray)
// and directions (float64 (E, 2), (0, 0) for a finite edge).
nb::tuple voronoi_edges(const std::vector<clmesh::VoronoiEdge> &links) {
  std::vector<int32_t> ends;
  std::vector<double> directions;
  ends.reserve(links.size() * 2);
  directions.reserve(links.size() * 2);
  for (const clmesh::VoronoiEdge &link : links) {
    ends.insert(ends.end(), {link.a, link.b});
    directions.insert(directions.end(), {link.direction.x, link.direction.y});
  }
  return nb::make_tuple(array(std::move(ends), links.size(), 2),
                        array(std::move(directions), links.size(), 2));
}

std::vector<clmesh::Point> points_of(const In<double> &xy, const char *name) {
  require_shape(xy, name, 2);
  std::vector<clmesh::Point> points(xy.shape(0));
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = {xy(i, 0), xy(i, 1)};
  return points;
}

// A sizing field from the arrays of clmesh/_size_field.py: points (N, 2),
// their target areas (N, 1), triangles (M, 3); checked by the library
// (InputError naming the point or triangle at fault).
clmesh::SizeField size_field(const In<double> &vertices, const In<double> &area,
                             const In<int32_t> &triangles) {
  clmesh::SizeField field;
  field.points = points_of(vertices, "size_field vertices");
  require_shape(area, "size_field area", 1, static_cast<long>(field.points.size()));
  field.area.assign(area.data(), area.data() + area.shape(0));
  require_shape(triangles, "size_field triangles", 3);
  field.triangles.resize(triangles.shape(0));
  for (std::size_t t = 0; t < field.triangles.size(); ++t)
    field.triangles[t] = {triangles(t, 0), triangles(t, 1), triangles(t, 2)};
  clmesh::validate(field);
  return field;
}

// A Python callable f(a, b, c, area) -> bool as the library's Unsuitable,
// the corners as (x, y) tuples of floats. The library calls it on the thread
// that released the GIL to mesh: each call takes the GIL back. What f raises
// (or the truth test of its answer) leaves as nb::python_error, through the
// library, and nanobind raises it again unchanged in the caller. `callable`
// is borrowed: it must outlive the run (it is an argument of triangulate()).
clmesh::Unsuitable unsuitable_of(nb::handle callable) {
  return [callable](clmesh::Point a, clmesh::Point b, clmesh::Point c, double area) {
    nb::gil_scoped_acquire locked;
    const nb::object answer = callable(nb::make_tuple(a.x, a.y), nb::make_tuple(b.x, b.y),
                                       nb::make_tuple(c.x, c.y), area);
    const int truth = PyObject_IsTrue(answer.ptr());
    if (truth < 0)
      throw nb::python_error();
    return truth == 1;
  };
}

// True while this thread meshes: an unsuitable function that calls
// triangulate() again would wait forever for the device its caller holds.
thread_local bool meshing = false;

// Marks this thread as meshing while it lives; refuses a nested call.
struct Meshing {
  Meshing() {
    if (meshing)
      throw clmesh::Error("triangulate() called from an unsuitable function: the device is "
                          "meshing for its caller, one call at a time");
    meshing = true;
  }
  ~Meshing() { meshing = false; }
  Meshing(const Meshing &) = delete;
  Meshing &operator=(const Meshing &) = delete;
};

// One triangulate() call: what went in, and what came out.
struct Run {
  std::shared_ptr<const clmesh::Input> input;
  clmesh::Options options;
  clmesh::Mesh mesh;

  clmesh::MeshView view() const { return clmesh::view_of(mesh); }
};

// -r: the mesh to refine, its triangles' attributes and (with -a alone)
// maximum areas into `input`; given without -r they are ignored, as Triangle
// ignores them. has_triangles / has_max_area: the dict had the key.
void take_mesh(clmesh::Input &input, const clmesh::Options &options, const In<int32_t> &triangles,
               bool has_triangles, const In<double> &triangle_attributes,
               const In<double> &triangle_max_area, bool has_max_area) {
  if (!options.refine)
    return;
  if (!has_triangles)
    throw clmesh::InputError("input", 0, "'triangles' is missing: -r refines the mesh they form");
  require_shape(triangles, "triangles", 3);
  const long t = static_cast<long>(triangles.shape(0));
  input.triangles.resize(triangles.shape(0));
  for (long k = 0; k < t; ++k)
    input.triangles[k] = {triangles(k, 0), triangles(k, 1), triangles(k, 2)};
  require_shape(triangle_attributes, "triangle_attributes", triangle_attributes.shape(1), t);
  input.triangle_attribute_count = static_cast<int>(triangle_attributes.shape(1));
  input.triangle_attributes.assign(triangle_attributes.data(),
                                   triangle_attributes.data() + triangle_attributes.size());
  if (!options.regional_areas)
    return;
  if (!has_max_area)
    throw clmesh::InputError("input", 0,
                             "'triangle_max_area' is missing: -r with -a without a number "
                             "takes each triangle's maximum area from it");
  require_shape(triangle_max_area, "triangle_max_area", 1, t);
  input.triangle_max_area.assign(triangle_max_area.data(), triangle_max_area.data() + t);
}

// The Input of the arrays of clmesh/_input.py; `switches` say whether the
// triangles to refine (-r) and their maximum areas (-ra) are taken.
std::shared_ptr<clmesh::Input>
input_of(const In<double> &vertices, const In<int32_t> &vertex_markers,
         const In<double> &vertex_attributes, const In<int32_t> &segments,
         const In<int32_t> &segment_markers, const In<double> &holes, const In<double> &regions,
         const In<int32_t> &triangles, bool has_triangles, const In<double> &triangle_attributes,
         const In<double> &triangle_max_area, bool has_triangle_max_area,
         const std::string &switches) {
  auto made = std::make_shared<clmesh::Input>();
  clmesh::Input &input = *made;
  input.points = points_of(vertices, "vertices");
  const long n = static_cast<long>(input.points.size());
  if (vertex_markers.shape(0) != 0) {
    require_shape(vertex_markers, "vertex_markers", 1, n);
    input.point_markers.assign(vertex_markers.data(), vertex_markers.data() + n);
  }
  if (vertex_attributes.shape(1) != 0) {
    require_shape(vertex_attributes, "vertex_attributes", vertex_attributes.shape(1), n);
    input.attribute_count = static_cast<int>(vertex_attributes.shape(1));
    input.point_attributes.assign(vertex_attributes.data(),
                                  vertex_attributes.data() + vertex_attributes.size());
  }
  require_shape(segments, "segments", 2);
  const long m = static_cast<long>(segments.shape(0));
  if (segment_markers.shape(0) != 0)
    require_shape(segment_markers, "segment_markers", 1, m);
  input.segments.resize(segments.shape(0));
  for (long s = 0; s < m; ++s)
    input.segments[s] = {segments(s, 0), segments(s, 1),
                         segment_markers.shape(0) != 0 ? segment_markers(s, 0) : 0};
  input.holes = points_of(holes, "holes");
  require_shape(regions, "regions", 4);
  for (std::size_t r = 0; r < regions.shape(0); ++r)
    input.regions.push_back({{regions(r, 0), regions(r, 1)}, regions(r, 2), regions(r, 3)});
  take_mesh(input, clmesh::parse_switches(switches), triangles, has_triangles, triangle_attributes,
            triangle_max_area, has_triangle_max_area);
  return made;
}

// The options of a call: the switches, zero-based numbering (as the triangle
// package, which always adds -z), the device, the field and the function.
clmesh::Options options_of(const std::string &switches, const std::string &device,
                           const clmesh::SizeField *field, nb::handle unsuitable) {
  clmesh::Options options = clmesh::parse_switches(switches);
  options.zero_based = true;
  options.device = device;
  if (field)
    options.size_field = std::make_shared<const clmesh::SizeField>(*field);
  if (!unsuitable.is_none()) {
    options.unsuitable = unsuitable_of(unsuitable);
    // A batch's inputs one at a time (no streams on a GPU): the function
    // then sees them in order, none after a failed one, and runs on the
    // meshing thread (which refuses a nested triangulate()).
    options.tuning.streams = 1;
  }
  return options;
}

// The Run of a meshed input. The options' unsuitable function borrows a
// Python callable that the Run does not keep: it is left out.
std::unique_ptr<Run> run_of(std::shared_ptr<const clmesh::Input> input,
                            const clmesh::Options &options, clmesh::Mesh &&mesh) {
  auto run = std::make_unique<Run>();
  run->input = std::move(input);
  run->options = options;
  run->options.unsuitable = nullptr;
  run->mesh = std::move(mesh);
  return run;
}

std::unique_ptr<Run> triangulate(std::shared_ptr<clmesh::Input> input, const std::string &switches,
                                 const std::string &device, const clmesh::SizeField *field,
                                 nb::handle unsuitable) {
  const clmesh::Options options = options_of(switches, device, field, unsuitable);
  clmesh::Mesh mesh;
  {
    Meshing on_this_thread;
    nb::gil_scoped_release unlocked;
    mesh = clmesh::triangulate(*input, options);
  }
  return run_of(std::move(input), options, std::move(mesh));
}

// The class of clmesh/_errors.py for a library error (nullptr for another).
const char *error_class_name(const std::exception &e) {
  if (dynamic_cast<const clmesh::InputError *>(&e))
    return "InputError";
  if (dynamic_cast<const clmesh::OptionError *>(&e))
    return "OptionError";
  if (dynamic_cast<const clmesh::DeviceError *>(&e))
    return "DeviceError";
  if (dynamic_cast<const clmesh::OpenCLError *>(&e))
    return "OpenCLError";
  if (dynamic_cast<const clmesh::InternalError *>(&e))
    return "InternalError";
  if (dynamic_cast<const clmesh::Error *>(&e))
    return "Error";
  return nullptr;
}

nb::object error_class(const char *name) {
  return nb::module_::import_("clmesh._errors").attr(name);
}

// An input's error in a batch as a Python exception object: the library's
// errors as the classes of clmesh/_errors.py; what an unsuitable function
// raised, the same object.
nb::object error_object(const std::exception_ptr &error) {
  try {
    std::rethrow_exception(error);
  } catch (const nb::python_error &e) {
    return nb::borrow(e.value());
  } catch (const std::bad_alloc &e) {
    return nb::borrow(PyExc_MemoryError)(e.what());
  } catch (const std::exception &e) {
    const char *name = error_class_name(e);
    return name ? error_class(name)(e.what()) : nb::borrow(PyExc_RuntimeError)(e.what());
  }
}

// Whether an input's error ends a batch: what Python raises that is no
// Exception (KeyboardInterrupt from Ctrl-C in an unsuitable function,
// SystemExit). Called without the GIL.
bool ends_batch(const std::exception_ptr &error) {
  try {
    std::rethrow_exception(error);
  } catch (const nb::python_error &e) {
    nb::gil_scoped_acquire locked;
    return !e.matches(PyExc_Exception);
  } catch (...) {
    return false;
  }
}

// Every input meshed through the library's triangulate_many on the shared
// device, in order, with the GIL released once (on `streams` streams, 0:
// the library's default): for each a Run, or the exception object of its
// error. The list ends early, after the failed
// input, with stop_at_error and when an input's error ends the batch.
nb::list triangulate_many(const std::vector<std::shared_ptr<clmesh::Input>> &inputs,
                          const std::string &switches, const std::string &device,
                          const clmesh::SizeField *field, nb::handle unsuitable, bool stop_at_error,
                          std::size_t streams) {
  clmesh::Options options = options_of(switches, device, field, unsuitable);
  if (streams > 0 && unsuitable.is_none())
    options.tuning.streams = streams;
  struct Stop {};
  std::vector<clmesh::BatchResult> results;
  results.reserve(inputs.size());
  {
    Meshing on_this_thread;
    nb::gil_scoped_release unlocked;
    try {
      clmesh::triangulate_many(
          inputs.size(), [&](std::size_t i) { return *inputs[i]; }, options,
          [&](std::size_t, clmesh::BatchResult &&result) {
            results.push_back(std::move(result));
            const std::exception_ptr &error = results.back().error;
            if (error && (stop_at_error || ends_batch(error)))
              throw Stop{};
          });
    } catch (const Stop &) {
    }
  }
  nb::list outcomes;
  for (std::size_t i = 0; i < results.size(); ++i)
    if (results[i].ok())
      outcomes.append(nb::cast(run_of(inputs[i], options, std::move(results[i].mesh))));
    else
      outcomes.append(error_object(results[i].error));
  return outcomes;
}

// Triangle files as the triangle package's load() gives them: the vertices
// of `poly` (or, when it lists none, of the .node beside it) or else of
// `node`, the segments, holes and regions of `poly`, the triangles of `ele`,
// the maximum areas of `area` (empty paths: no such file). Indices
// zero-based; the readers' InputError names the file and line at fault.
nb::dict read_files(const std::string &node, const std::string &poly, const std::string &ele,
                    const std::string &area) {
  nb::dict d;
  clmesh::PointSet points;
  clmesh::PolyFile pslg;
  if (!poly.empty()) {
    pslg = clmesh::read_poly(poly);
    points = pslg.points;
  } else if (!node.empty()) {
    points = clmesh::read_node(node);
  }
  if (!poly.empty() || !node.empty()) {
    d["vertices"] = xy_rows(points.points);
    const auto count = static_cast<std::size_t>(points.attribute_count);
    if (count > 0)
      d["vertex_attributes"] =
          array(std::vector<double>(points.attributes), points.points.size(), count);
    if (points.has_markers)
      d["vertex_markers"] =
          array(std::vector<int32_t>(points.markers.begin(), points.markers.end()),
                points.markers.size(), 1);
  }
  if (!poly.empty()) {
    if (!pslg.segments.empty()) {
      const nb::tuple ends = ends_and_markers(pslg.segments);
      d["segments"] = ends[0];
      if (pslg.segment_markers)
        d["segment_markers"] = ends[1];
    }
    if (!pslg.holes.empty())
      d["holes"] = xy_rows(pslg.holes);
    if (!pslg.regions.empty()) {
      std::vector<double> rows;
      for (const clmesh::Region &r : pslg.regions)
        rows.insert(rows.end(), {r.seed.x, r.seed.y, r.attribute, r.max_area});
      d["regions"] = array(std::move(rows), pslg.regions.size(), 4);
    }
  }
  if (!ele.empty()) {
    const clmesh::EleFile mesh =
        clmesh::read_ele(ele, static_cast<long>(points.points.size()), points.first_index);
    d["triangles"] = index_rows(mesh.triangles);
    const auto count = static_cast<std::size_t>(mesh.attribute_count);
    if (count > 0)
      d["triangle_attributes"] =
          array(std::vector<double>(mesh.attributes), mesh.triangles.size(), count);
    if (!area.empty()) {
      std::vector<double> bounds = clmesh::read_area(area, mesh.triangles.size());
      const std::size_t rows = bounds.size();
      d["triangle_max_area"] = array(std::move(bounds), rows, 1);
    }
  }
  return d;
}

nb::dict quality_dict(const clmesh::QualityStatistics &q) {
  nb::dict d;
  d["triangles"] = q.triangles;
  d["smallest_area"] = q.smallest_area;
  d["largest_area"] = q.largest_area;
  d["shortest_edge"] = q.shortest_edge;
  d["longest_edge"] = q.longest_edge;
  d["shortest_altitude"] = q.shortest_altitude;
  d["largest_aspect_ratio"] = q.largest_aspect_ratio;
  d["smallest_angle"] = q.smallest_angle;
  d["largest_angle"] = q.largest_angle;
  d["aspect_ratio_histogram"] =
      std::vector<long>(q.aspect_ratio_histogram.begin(), q.aspect_ratio_histogram.end());
  d["angle_histogram"] = std::vector<long>(q.angle_histogram.begin(), q.angle_histogram.end());
  return d;
}

// Triangle's quality statistics of any triangles over any vertices (a mesh
// from another mesher too).
nb::dict quality_of(const In<double> &vertices, const In<int32_t> &triangles) {
  clmesh::Mesh mesh;
  mesh.points = points_of(vertices, "vertices");
  require_shape(triangles, "triangles", 3);
  const auto n = static_cast<int32_t>(mesh.points.size());
  mesh.triangles.resize(triangles.shape(0));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int32_t v = triangles(t, i);
      if (v < 0 || v >= n)
        throw clmesh::InputError("input", 0,
                                 "triangle " + std::to_string(t) + ": vertex " + std::to_string(v) +
                                     " out of range (" + std::to_string(n) + " vertices)");
      mesh.triangles[t][i] = v;
    }
  return quality_dict(clmesh::quality_statistics(mesh));
}

// The switches that decide which arrays Python returns.
nb::dict options_dict(const clmesh::Options &o) {
  nb::dict d;
  d["pslg"] = o.pslg;
  d["refine"] = o.refine;
  d["convex_hull"] = o.convex_hull;
  d["regional_attributes"] = o.regional_attributes;
  d["edges"] = o.edges;
  d["neighbors"] = o.neighbors;
  d["jettison"] = o.jettison;
  d["no_boundary_markers"] = o.no_boundary_markers;
  d["no_node_file"] = o.no_node_file;
  d["no_ele_file"] = o.no_ele_file;
  d["check"] = o.check;
  d["voronoi"] = o.voronoi;
  d["second_order"] = o.second_order;
  return d;
}

nb::list devices() {
  nb::list list;
  for (const clmesh::DeviceDescription &d : clmesh::list_devices()) {
    nb::dict entry;
    entry["spec"] = std::to_string(d.platform_index) + ":" + std::to_string(d.device_index);
    entry["platform"] = d.platform_name;
    entry["name"] = d.device_name;
    entry["version"] = d.version;
    entry["fp64"] = d.has_fp64;
    entry["cpu"] = d.is_cpu;
    list.append(entry);
  }
  return list;
}

// The library's errors as the Python classes of clmesh/_errors.py.
void translate_error(const std::exception_ptr &error, void *) {
  try {
    std::rethrow_exception(error);
  } catch (const std::exception &e) {
    const char *name = error_class_name(e);
    if (!name)
      throw; // nanobind's own translation
    PyErr_SetString(error_class(name).ptr(), e.what());
  }
}

} // namespace

NB_MODULE(_clmesh, m) {
  m.doc() = "clmesh's compiled core; use the clmesh package.";
  nb::register_exception_translator(translate_error);
  m.attr("version") = CLMESH_VERSION_STRING;

  nb::class_<clmesh::SizeField>(m, "SizeField",
                                "A checked sizing field (clmesh.triangulate's size_field).");
  m.def("size_field", &size_field, nb::arg("vertices"), nb::arg("area"), nb::arg("triangles"));

  nb::class_<Run>(m, "Run")
      .def_prop_ro("options", [](const Run &r) { return options_dict(r.options); })
      .def("points", [](const Run &r) { return xy_rows(r.mesh.points); })
      .def("point_markers",
           [](const Run &r) {
             std::vector<int32_t> markers(r.mesh.point_markers.begin(), r.mesh.point_markers.end());
             return array(std::move(markers), r.mesh.point_markers.size(), 1);
           })
      .def("point_attributes",
           [](const Run &r) {
             return array(std::vector<double>(r.mesh.point_attributes), r.mesh.points.size(),
                          static_cast<std::size_t>(r.mesh.attribute_count));
           })
      .def("triangles", [](const Run &r) { return index_rows(r.mesh.triangles); })
      .def("triangle_attributes",
           [](const Run &r) {
             return array(std::vector<double>(r.mesh.triangle_attributes), r.mesh.triangles.size(),
                          static_cast<std::size_t>(r.mesh.triangle_attribute_count));
           })
      .def("neighbors", [](const Run &r) { return index_rows(r.mesh.neighbors); })
      .def("edges", [](const Run &r) { return ends_and_markers(r.mesh.edges); })
      .def(
          "segments",
          [](const Run &r) { return ends_and_markers(clmesh::output_segments(r.view())); },
          "The segments that are edges of the mesh (-p), with their output markers.")
      .def(
          "edge_midpoints", [](const Run &r) { return xy_rows(r.mesh.edge_midpoints); },
          "-o2: the node at the middle of every edge, numbered after the vertices.")
      .def("edge_midpoint_markers",
           [](const Run &r) {
             std::vector<int32_t> markers(r.mesh.edge_midpoint_markers.begin(),
                                          r.mesh.edge_midpoint_markers.end());
             const std::size_t count = markers.size();
             return array(std::move(markers), count, 1);
           })
      .def("edge_midpoint_attributes",
           [](const Run &r) {
             return array(std::vector<double>(r.mesh.edge_midpoint_attributes),
                          r.mesh.edge_midpoints.size(),
                          static_cast<std::size_t>(r.mesh.attribute_count));
           })
      .def(
          "triangle_midpoints", [](const Run &r) { return index_rows(r.mesh.triangle_midpoints); },
          "-o2: per triangle, the edge_midpoints index of the middle of the edge opposite each "
          "corner.")
      .def(
          "voronoi_points", [](const Run &r) { return xy_rows(r.mesh.voronoi_points); },
          "-v: the circumcentre of every triangle, numbered as the triangles.")
      .def(
          "voronoi_edges", [](const Run &r) { return voronoi_edges(r.mesh.voronoi_edges); },
          "-v: (ends, directions): one edge per mesh edge; a ray has second end -1.")
      .def(
          "vertex_numbers",
          [](const Run &r) {
            clmesh::WriteOptions jettison;
            jettison.jettison_duplicates = true;
            std::vector<int32_t> numbers = clmesh::output_vertex_numbers(r.view(), jettison);
            const std::size_t count = numbers.size();
            return array(std::move(numbers), count, 1);
          },
          "-j: each vertex's number in the output, -1 for one left out.")
      .def(
          "statistics_json",
          [](const Run &r) {
            clmesh::RunSeconds seconds;
            seconds.compute = r.mesh.statistics.delaunay.compute_seconds;
            return clmesh::statistics_json(r.mesh, seconds);
          },
          "The statistics as --stats-json writes them.")
      .def("quality_statistics",
           [](const Run &r) { return quality_dict(clmesh::quality_statistics(r.mesh)); })
      .def(
          "check",
          [](const Run &r) {
            nb::gil_scoped_release unlocked;
            return clmesh::check_mesh(*r.input, r.mesh, r.options).problems;
          },
          "The problems the exact check (-C) finds; empty for a valid mesh.");

  nb::class_<clmesh::Input>(m, "Input", "One input, checked and copied from its arrays.");
  m.def("input", &input_of, nb::arg("vertices"), nb::arg("vertex_markers"),
        nb::arg("vertex_attributes"), nb::arg("segments"), nb::arg("segment_markers"),
        nb::arg("holes"), nb::arg("regions"), nb::arg("triangles"), nb::arg("has_triangles"),
        nb::arg("triangle_attributes"), nb::arg("triangle_max_area"),
        nb::arg("has_triangle_max_area"), nb::arg("switches"));
  m.def("triangulate", &triangulate, nb::arg("input"), nb::arg("switches"), nb::arg("device"),
        nb::arg("size_field").none() = nb::none(), nb::arg("unsuitable").none() = nb::none());
  m.def("triangulate_many", &triangulate_many, nb::arg("inputs"), nb::arg("switches"),
        nb::arg("device"), nb::arg("size_field").none(), nb::arg("unsuitable").none(),
        nb::arg("stop_at_error"), nb::arg("streams"));
  m.def("quality_statistics", &quality_of, nb::arg("vertices"), nb::arg("triangles"));
  m.def("read_files", &read_files, nb::arg("node"), nb::arg("poly"), nb::arg("ele"),
        nb::arg("area"));
  m.def("devices", &devices);
  m.def(
      "parse_switches",
      [](const std::string &switches) {
        const clmesh::Options options = clmesh::parse_switches(switches);
        clmesh::validate(options);
        return options_dict(options);
      },
      nb::arg("switches"));
}
