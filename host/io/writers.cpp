// clmesh — writing Triangle's files (.node .ele .edge .neigh .poly, .v.node
// .v.edge, .off): the edges and markers Triangle reports, and the
// all-or-nothing batch of output files (see clmesh/io.hpp).
#include "clmesh/io.hpp"

#include "clmesh/errors.hpp"
#include "io/edge_order.hpp"
#include "io/system_error.hpp"
#include "io/text_file.hpp"
#include "io/view_access.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string_view>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace clmesh {

// ---------------------------------------------------------------------------
// Mesh helpers
// ---------------------------------------------------------------------------

namespace {

void check_neighbors(const std::vector<Triangle> &triangles,
                     const std::vector<std::array<int32_t, 3>> &neighbors, const char *caller) {
  if (neighbors.size() != triangles.size())
    throw InternalError(std::string(caller) + ": " + std::to_string(triangles.size()) +
                        " triangles but " + std::to_string(neighbors.size()) +
                        " neighbour entries");
}

// The segments by their ends: the indices of the segments {a, b}, found in
// constant time from the smaller end's row (compressed rows, in index order).
// Hashing every mesh edge instead costs more than writing the files.
class SegmentsByEnd {
public:
  explicit SegmentsByEnd(const std::vector<Segment> &segments) {
    std::size_t rows = 0;
    for (const Segment &segment : segments)
      if (std::min(segment.a, segment.b) >= 0)
        rows = std::max(rows, static_cast<std::size_t>(std::min(segment.a, segment.b)) + 1);
    first_.assign(rows + 1, 0);
    for (const Segment &segment : segments)
      if (std::min(segment.a, segment.b) >= 0)
        ++first_[static_cast<std::size_t>(std::min(segment.a, segment.b)) + 1];
    for (std::size_t row = 0; row < rows; ++row)
      first_[row + 1] += first_[row];
    std::vector<std::size_t> next(first_.begin(), first_.end() - 1);
    entries_.resize(first_[rows]);
    for (std::size_t s = 0; s < segments.size(); ++s) {
      const int32_t low = std::min(segments[s].a, segments[s].b);
      if (low >= 0)
        entries_[next[static_cast<std::size_t>(low)]++] = {std::max(segments[s].a, segments[s].b),
                                                           s};
    }
  }
  // Calls found(s) for every segment s that joins a and b, in index order.
  template <typename Found> void visit(int32_t a, int32_t b, Found found) const {
    const int32_t low = std::min(a, b), high = std::max(a, b);
    if (low < 0 || static_cast<std::size_t>(low) + 1 >= first_.size())
      return;
    for (std::size_t k = first_[static_cast<std::size_t>(low)];
         k < first_[static_cast<std::size_t>(low) + 1]; ++k)
      if (entries_[k].first == high)
        found(entries_[k].second);
  }

private:
  std::vector<std::size_t> first_; // row v: entries first_[v] to first_[v + 1]
  std::vector<std::pair<int32_t, std::size_t>> entries_; // the larger end and the segment
};

// Triangle's -p marker of a segment in the mesh: its own when non-zero, else 1
// when it lies on the mesh boundary (Triangle marks the subsegments that
// become boundary when it carves holes and the exterior), else 0.
int segment_marker(const Segment &segment, bool on_boundary) {
  return segment.marker != 0 ? segment.marker : on_boundary ? 1 : 0;
}

} // namespace

std::vector<Edge> mesh_edges(const std::vector<Triangle> &triangles,
                             const std::vector<std::array<int32_t, 3>> &neighbors) {
  check_neighbors(triangles, neighbors, "mesh_edges");
  std::vector<Edge> edges;
  edges.reserve(triangles.size() * 3 / 2 + 3);
  visit_edges(triangles, neighbors, [&](std::size_t t, int i, int32_t other) {
    edges.push_back(Edge{triangles[t][(i + 1) % 3], triangles[t][(i + 2) % 3], other == -1});
  });
  return edges;
}

std::vector<Edge> mesh_edges(const std::vector<Triangle> &triangles,
                             const std::vector<std::array<int32_t, 3>> &neighbors,
                             const std::vector<Segment> &segments) {
  std::vector<Edge> edges = mesh_edges(triangles, neighbors);
  const SegmentsByEnd by_end(segments);
  for (Edge &edge : edges) {
    std::size_t first = segments.size(); // the first segment on the edge gives its marker
    by_end.visit(edge.a, edge.b, [&](std::size_t s) { first = std::min(first, s); });
    if (first < segments.size())
      edge.marker =
          segment_marker(Segment{edge.a, edge.b, segments[first].marker}, edge.marker == 1);
  }
  return edges;
}

void MeshView::set_points(const PointSet &set) {
  points = &set.points;
  attribute_count = set.attribute_count;
  point_attributes = &set.attributes;
  point_markers = set.has_markers ? &set.markers : nullptr;
}

MeshView view_of(const Mesh &mesh) {
  MeshView view;
  view.points = &mesh.points;
  view.attribute_count = mesh.attribute_count;
  view.point_attributes = &mesh.point_attributes;
  view.point_markers = &mesh.point_markers;
  view.triangles = &mesh.triangles;
  view.neighbors = &mesh.neighbors;
  view.duplicate_of = &mesh.duplicate_of;
  // -p, and -r: the mesh's boundary edges and the .poly's segments.
  if (mesh.statistics.constrained || !mesh.segments.empty())
    view.segments = &mesh.segments;
  if (mesh.triangle_attribute_count > 0) {
    view.triangle_attribute_count = mesh.triangle_attribute_count;
    view.triangle_attributes = &mesh.triangle_attributes;
  }
  if (!mesh.triangle_midpoints.empty() || !mesh.edge_midpoints.empty()) {
    view.edge_midpoints = &mesh.edge_midpoints;
    view.edge_midpoint_attributes = &mesh.edge_midpoint_attributes;
    view.edge_midpoint_markers = &mesh.edge_midpoint_markers;
    view.triangle_midpoints = &mesh.triangle_midpoints;
  }
  view.voronoi_points = &mesh.voronoi_points;
  view.voronoi_point_attributes = &mesh.voronoi_point_attributes;
  view.voronoi_edges = &mesh.voronoi_edges;
  return view;
}

std::vector<int> output_vertex_markers(const MeshView &mesh) {
  const std::size_t n = mesh.points ? mesh.points->size() : 0;
  std::vector<int> markers(n, 0);
  if (mesh.point_markers && mesh.point_markers->size() == n)
    markers = *mesh.point_markers;
  auto in_range = [n](int32_t v) { return v >= 0 && static_cast<std::size_t>(v) < n; };
  // As Triangle inserts the segments in order: an endpoint whose marker is
  // still 0 takes the segment's.
  if (mesh.segments)
    for (const Segment &segment : *mesh.segments)
      for (int32_t v : {segment.a, segment.b})
        if (in_range(v) && markers[v] == 0)
          markers[v] = segment.marker;
  // Vertices on the mesh boundary (the convex hull without -p) whose marker is 0 get 1.
  if (mesh.triangles && mesh.neighbors && mesh.neighbors->size() == mesh.triangles->size()) {
    for (std::size_t t = 0; t < mesh.triangles->size(); ++t)
      for (int i = 0; i < 3; ++i)
        if ((*mesh.neighbors)[t][i] == -1)
          for (int k = 1; k <= 2; ++k) {
            int32_t v = (*mesh.triangles)[t][(i + k) % 3];
            if (in_range(v) && markers[v] == 0)
              markers[v] = 1;
          }
  }
  return markers;
}

std::vector<int32_t> output_vertex_numbers(const MeshView &mesh, const WriteOptions &options) {
  std::size_t n = mesh.points ? mesh.points->size() : 0;
  std::vector<char> dropped(n, 0);
  if (options.jettison_duplicates) {
    const std::vector<int32_t> *duplicates = mesh.duplicate_of;
    if (duplicates && duplicates->size() == n)
      for (std::size_t i = 0; i < n; ++i)
        dropped[i] = (*duplicates)[i] != -1;
    // -p: Triangle's -j also drops the vertices that are in no triangle.
    if (mesh.segments && mesh.triangles) {
      std::vector<char> used(n, 0);
      for (const Triangle &t : *mesh.triangles)
        for (int32_t v : t)
          if (v >= 0 && static_cast<std::size_t>(v) < n)
            used[v] = 1;
      for (std::size_t i = 0; i < n; ++i)
        dropped[i] = dropped[i] || !used[i];
    }
  }
  std::vector<int32_t> numbers(n);
  int32_t next = 0;
  for (std::size_t i = 0; i < n; ++i)
    numbers[i] = dropped[i] ? -1 : next++;
  return numbers;
}

// ---------------------------------------------------------------------------
// Writing
// ---------------------------------------------------------------------------

std::vector<Segment> output_segments(const MeshView &mesh) {
  if (!mesh.segments)
    throw InternalError("output_segments called without segments");
  const std::vector<Triangle> &triangles = triangles_of(mesh);
  const std::vector<std::array<int32_t, 3>> &neighbors = neighbors_of(mesh);
  // Each segment's edge in the mesh: whether the first triangle (in order)
  // that has it has no neighbour across it; -1 when no triangle has it.
  std::vector<signed char> on_boundary(mesh.segments->size(), -1);
  const SegmentsByEnd by_end(*mesh.segments);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int i = 0; i < 3; ++i)
      by_end.visit(triangles[t][(i + 1) % 3], triangles[t][(i + 2) % 3], [&](std::size_t s) {
        if (on_boundary[s] < 0)
          on_boundary[s] = neighbors[t][i] == -1;
      });
  std::vector<Segment> segments;
  segments.reserve(mesh.segments->size());
  for (std::size_t s = 0; s < mesh.segments->size(); ++s) {
    if (on_boundary[s] < 0)
      continue; // no edge of the mesh: eaten with a hole or the exterior
    const Segment &segment = (*mesh.segments)[s];
    segments.push_back(Segment{segment.a, segment.b, segment_marker(segment, on_boundary[s] == 1)});
  }
  return segments;
}

OutputBatch::~OutputBatch() {
  for (const auto &file : files_)
    std::remove(file.first.c_str());
}

namespace {

namespace fs = std::filesystem;

// Whether anything (a file, a directory, a link, even a dangling one) has that name.
bool name_taken(const std::string &path) {
  std::error_code error;
  return fs::symlink_status(path, error).type() != fs::file_type::not_found && !error;
}

// `stem`, or `stem` followed by ".1", ".2"... : the first name nothing has.
std::string free_name(const std::string &stem) {
  std::string name = stem;
  for (int k = 1; name_taken(name); ++k)
    name = stem + "." + std::to_string(k);
  return name;
}

// An output file can replace a file or a link, never a directory.
void check_target(const std::string &path) {
  std::error_code error;
  if (fs::symlink_status(path, error).type() == fs::file_type::directory)
    throw InputError(path, 0, "cannot write: a directory has that name");
}

} // namespace

std::string OutputBatch::temporary_for(const std::string &path) {
  check_target(path);
  const std::lock_guard<std::mutex> lock(files_mutex_);
  // Written again: the earlier temporary is dropped, the new one replaces it.
  for (auto file = files_.begin(); file != files_.end(); ++file)
    if (file->second == path) {
      std::remove(file->first.c_str());
      files_.erase(file);
      break;
    }
  // A name no file has, so that no file of the user's is ever overwritten
  // (TextFile creates it exclusively).
  std::string temporary = free_name(path + ".tmp-clmesh");
  files_.emplace_back(temporary, path);
  return temporary;
}

namespace {

// One line of a .node file: "%4ld    %.17g  %.17g", then "  %.17g" per
// attribute, then "    %d" when there is a marker.
void node_line(TextFile &file, long number, const Point &point, const double *attributes,
               std::size_t attribute_count, const int *marker) {
  file.integer(number, 4);
  file.text("    ");
  file.real(point.x);
  file.text("  ");
  file.real(point.y);
  for (std::size_t a = 0; a < attribute_count; ++a) {
    file.text("  ");
    file.real(attributes[a]);
  }
  if (marker) {
    file.text("    ");
    file.integer(*marker);
  }
  file.end_line();
}

} // namespace

void OutputBatch::write_node(const std::string &path, const MeshView &mesh,
                             const WriteOptions &options) {
  const std::vector<Point> &points = points_of(mesh);
  const std::size_t n = points.size();
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  const std::size_t written = written_count(numbers);
  const std::vector<Point> &midpoints = midpoints_of(mesh);
  const std::vector<int> markers =
      options.boundary_markers ? output_vertex_markers(mesh) : std::vector<int>();

  const std::size_t attributes = attributes_of(mesh);
  if (attributes > 0 && (!mesh.point_attributes || mesh.point_attributes->size() < n * attributes))
    throw InternalError("point set holds fewer attributes than its attribute count says");
  TextFile file(temporary_for(path), path);
  file.format("%zu  2  %zu  %d\n", written + midpoints.size(), attributes,
              options.boundary_markers ? 1 : 0);
  for (std::size_t i = 0; i < n; ++i)
    if (numbers[i] >= 0)
      node_line(file, static_cast<long>(numbers[i]) + options.first_index, points[i],
                attributes ? &(*mesh.point_attributes)[i * attributes] : nullptr, attributes,
                options.boundary_markers ? &markers[i] : nullptr);
  for (std::size_t k = 0; k < midpoints.size(); ++k)
    node_line(file, static_cast<long>(written + k) + options.first_index, midpoints[k],
              attributes ? &(*mesh.edge_midpoint_attributes)[k * attributes] : nullptr, attributes,
              options.boundary_markers ? &(*mesh.edge_midpoint_markers)[k] : nullptr);
  file.footer(options);
  file.close();
}

void OutputBatch::write_ele(const std::string &path, const MeshView &mesh,
                            const WriteOptions &options) {
  const std::vector<Triangle> &triangles = triangles_of(mesh);
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  const std::size_t columns = triangle_attributes_of(mesh);
  const bool six_nodes = !midpoints_of(mesh).empty();
  const long first_midpoint = static_cast<long>(written_count(numbers)) + options.first_index;
  TextFile file(temporary_for(path), path);
  file.format("%zu  %d  %zu\n", triangles.size(), six_nodes ? 6 : 3, columns);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    // "%4ld    %4d  %4d  %4d" (and "  %4d" per middle node), then "  %.17g" per attribute
    file.integer(static_cast<long>(t) + options.first_index, 4);
    for (int k = 0; k < 3; ++k) {
      file.text(k == 0 ? "    " : "  ");
      file.integer(written_vertex(numbers, triangles[t][k], options), 4);
    }
    for (int k = 0; six_nodes && k < 3; ++k) {
      file.text("  ");
      file.integer(first_midpoint + (*mesh.triangle_midpoints)[t][k], 4);
    }
    for (std::size_t a = 0; a < columns; ++a) {
      file.text("  ");
      file.real((*mesh.triangle_attributes)[t * columns + a]);
    }
    file.end_line();
  }
  file.footer(options);
  file.close();
}

void OutputBatch::write_edge(const std::string &path, const MeshView &mesh,
                             const WriteOptions &options) {
  const std::vector<Edge> edges =
      mesh.segments ? mesh_edges(triangles_of(mesh), neighbors_of(mesh), *mesh.segments)
                    : mesh_edges(triangles_of(mesh), neighbors_of(mesh));
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  TextFile file(temporary_for(path), path);
  file.format("%zu  %d\n", edges.size(), options.boundary_markers ? 1 : 0);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    // "%4ld   %d  %d  %d" ("%4ld   %d  %d" with -B)
    file.integer(static_cast<long>(e) + options.first_index, 4);
    file.text("   ");
    file.integer(written_vertex(numbers, edges[e].a, options));
    file.text("  ");
    file.integer(written_vertex(numbers, edges[e].b, options));
    if (options.boundary_markers) {
      file.text("  ");
      file.integer(edges[e].marker);
    }
    file.end_line();
  }
  file.footer(options);
  file.close();
}

void OutputBatch::write_poly(const std::string &path, const MeshView &mesh,
                             const std::vector<Point> &holes, const std::vector<Region> &regions,
                             const WriteOptions &options) {
  if (!mesh.segments)
    throw InternalError("write_poly called without segments");
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  std::vector<Segment> segments = output_segments(mesh);
  for (Segment &segment : segments) {
    segment.a = written_vertex(numbers, segment.a, options);
    segment.b = written_vertex(numbers, segment.b, options);
  }
  const int flag = options.boundary_markers ? 1 : 0;
  TextFile file(temporary_for(path), path);
  // The vertices are in the .node file: 0 of them here.
  file.format("0  2  %d  %d\n", std::max(mesh.attribute_count, 0), flag);
  file.format("%zu  %d\n", segments.size(), flag);
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const long id = static_cast<long>(s) + options.first_index;
    if (options.boundary_markers)
      file.format("%4ld    %4d  %4d    %4d\n", id, segments[s].a, segments[s].b,
                  segments[s].marker);
    else
      file.format("%4ld    %4d  %4d\n", id, segments[s].a, segments[s].b);
  }
  file.format("%zu\n", holes.size());
  for (std::size_t h = 0; h < holes.size(); ++h)
    file.format("%4ld   %.17g  %.17g\n", static_cast<long>(h) + options.first_index, holes[h].x,
                holes[h].y);
  if (!regions.empty()) {
    file.format("%zu\n", regions.size());
    for (std::size_t r = 0; r < regions.size(); ++r)
      file.format("%4ld   %.17g  %.17g  %.17g  %.17g\n", static_cast<long>(r) + options.first_index,
                  regions[r].seed.x, regions[r].seed.y, regions[r].attribute, regions[r].max_area);
  }
  file.footer(options);
  file.close();
}

void OutputBatch::write_neigh(const std::string &path, const MeshView &mesh,
                              const WriteOptions &options) {
  const std::vector<std::array<int32_t, 3>> &neighbors = neighbors_of(mesh);
  auto number = [&](int32_t t) { return t < 0 ? -1 : t + options.first_index; };
  TextFile file(temporary_for(path), path);
  file.format("%zu  3\n", neighbors.size());
  for (std::size_t t = 0; t < neighbors.size(); ++t) {
    // "%4ld    %d  %d  %d"
    file.integer(static_cast<long>(t) + options.first_index, 4);
    for (int k = 0; k < 3; ++k) {
      file.text(k == 0 ? "    " : "  ");
      file.integer(number(neighbors[t][k]));
    }
    file.end_line();
  }
  file.footer(options);
  file.close();
}

void OutputBatch::write_voronoi_node(const std::string &path, const MeshView &mesh,
                                     const WriteOptions &options) {
  if (!mesh.voronoi_points || !mesh.voronoi_point_attributes)
    throw InternalError("write_voronoi_node called without a Voronoi diagram");
  const std::vector<Point> &centers = *mesh.voronoi_points;
  const std::size_t attributes = attributes_of(mesh);
  if (mesh.voronoi_point_attributes->size() != centers.size() * attributes)
    throw InternalError("write_voronoi_node: attributes do not match the Voronoi vertices");
  TextFile file(temporary_for(path), path);
  file.format("%zu  2  %zu  0\n", centers.size(), attributes);
  for (std::size_t t = 0; t < centers.size(); ++t)
    node_line(file, static_cast<long>(t) + options.first_index, centers[t],
              attributes ? &(*mesh.voronoi_point_attributes)[t * attributes] : nullptr, attributes,
              nullptr);
  file.footer(options);
  file.close();
}

void OutputBatch::write_voronoi_edge(const std::string &path, const MeshView &mesh,
                                     const WriteOptions &options) {
  if (!mesh.voronoi_edges)
    throw InternalError("write_voronoi_edge called without a Voronoi diagram");
  const std::vector<VoronoiEdge> &edges = *mesh.voronoi_edges;
  TextFile file(temporary_for(path), path);
  file.format("%zu  0\n", edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    // "%4ld   %d  %d", or for a ray "%4ld   %d  -1   %.17g  %.17g"
    file.integer(static_cast<long>(e) + options.first_index, 4);
    file.text("   ");
    file.integer(static_cast<long>(edges[e].a) + options.first_index);
    file.text("  ");
    if (edges[e].b >= 0) {
      file.integer(static_cast<long>(edges[e].b) + options.first_index);
    } else {
      file.text("-1   ");
      file.real(edges[e].direction.x);
      file.text("  ");
      file.real(edges[e].direction.y);
    }
    file.end_line();
  }
  file.footer(options);
  file.close();
}

void OutputBatch::write_off(const std::string &path, const MeshView &mesh,
                            const WriteOptions &options) {
  const std::vector<Point> &points = points_of(mesh);
  const std::vector<Triangle> &triangles = triangles_of(mesh);
  const std::vector<std::array<int32_t, 3>> &neighbors = neighbors_of(mesh);
  const std::vector<Point> &midpoints = midpoints_of(mesh);
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  std::size_t hull = 0;
  for (const auto &across : neighbors)
    for (int32_t other : across)
      hull += other == -1;
  WriteOptions from_zero = options; // .off numbers its vertices from 0
  from_zero.first_index = 0;
  TextFile file(temporary_for(path), path);
  file.format("OFF\n%zu  %zu  %zu\n", written_count(numbers) + midpoints.size(), triangles.size(),
              (3 * triangles.size() + hull) / 2);
  auto vertex_line = [&file](const Point &point) {
    file.text(" ");
    file.real(point.x);
    file.text("  ");
    file.real(point.y);
    file.text("  0");
    file.end_line();
  };
  for (std::size_t i = 0; i < points.size(); ++i)
    if (numbers[i] >= 0)
      vertex_line(points[i]);
  for (const Point &midpoint : midpoints)
    vertex_line(midpoint);
  for (const Triangle &triangle : triangles) {
    // " 3   %4d  %4d  %4d"
    file.text(" 3   ");
    for (int k = 0; k < 3; ++k) {
      if (k > 0)
        file.text("  ");
      file.integer(written_vertex(numbers, triangle[k], from_zero), 4);
    }
    file.end_line();
  }
  file.footer(options);
  file.close();
}

void OutputBatch::write_text(const std::string &path, const std::string &contents) {
  TextFile file(temporary_for(path), path);
  file.append(contents);
  file.close();
}

void OutputBatch::commit() {
  // Every target is checked before the first rename, so that the usual
  // failure (a directory with an output's name) moves nothing.
  for (const auto &file : files_)
    check_target(file.second);
  // Each file that is replaced is first renamed aside, so that a failure
  // further on can put it back: a failed commit leaves no new file and
  // changes no existing one.
  struct Step {
    std::string path, backup; // backup: the replaced file's name meanwhile, empty if none
    bool placed = false;      // the new file is at path
  };
  std::vector<Step> steps;
  // Undoes the steps so far, last first; says which replaced file could not
  // be put back, and where it is.
  auto roll_back = [&steps]() {
    std::string kept;
    for (auto step = steps.rbegin(); step != steps.rend(); ++step) {
      if (step->placed)
        std::remove(step->path.c_str());
      if (!step->backup.empty() && std::rename(step->backup.c_str(), step->path.c_str()) != 0)
        kept += "; the file it replaced is kept as " + printable(step->backup);
    }
    return kept;
  };
  for (const auto &file : files_) {
    const std::string &path = file.second;
    steps.push_back(Step{path, "", false});
    Step &step = steps.back();
    const char *problem = nullptr;
    if (name_taken(path)) {
      const std::string backup = free_name(path + ".old-clmesh");
      if (std::rename(path.c_str(), backup.c_str()) != 0)
        problem = "cannot replace the existing file: ";
      else
        step.backup = backup;
    }
    if (!problem && std::rename(file.first.c_str(), path.c_str()) != 0)
      problem = "cannot move the finished file into place: ";
    if (problem) {
      const int error = errno;
      throw InputError(path, 0, problem + describe_errno(error) + roll_back());
    }
    step.placed = true;
  }
  for (const Step &step : steps)
    if (!step.backup.empty())
      std::remove(step.backup.c_str());
  files_.clear();
}

} // namespace clmesh
