// clmesh — Triangle's file formats (.node .poly .ele .area .edge .neigh, .v.node
// .v.edge, .off), VTK's .vtu, SVG and PGM pictures.
//
// Readers accept '#' comments anywhere on a line, blank lines, and 0- or
// 1-based numbering (decided by the first id). Every problem is reported as
// an InputError naming the file and line, the input text it quotes escaped
// (clmesh::quote). They parse as they read, a few MiB at a time, and stop at
// the first bad line: a line holding a NUL byte or longer than a section can
// hold is one, so that an endless or binary input (a FIFO, /dev/zero) ends
// at once, and memory follows the data accepted, never a header's count.
#pragma once

#include "clmesh/geometry.hpp"
#include "clmesh/input.hpp"
#include "clmesh/mesh.hpp"
#include "clmesh/size_field.hpp"

#include <array>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace clmesh {

// Reads a .node file. Throws InputError (missing file, malformed header or
// line, non-numeric or non-finite coordinate, ids out of sequence).
PointSet read_node(const std::string &path);

// A Triangle .poly file (a PSLG).
struct PolyFile {
  // The vertices: the .poly's node section, or, when it declares 0 vertices,
  // the .node file beside it (same base name), whose numbering then applies.
  PointSet points;
  std::string node_path; // that .node file; empty when the vertices are in the .poly
  // Segments with 0-based endpoints (the file's numbering removed); markers
  // are 0 when the file has none (segment_markers false). As in a .node file,
  // a line without the marker that its section header announces is an error
  // (Triangle reads 0); the only optional field is a region's maximum area.
  std::vector<Segment> segments;
  bool segment_markers = false;
  std::vector<long> segment_lines; // line of each segment in the .poly, for messages
  std::vector<Point> holes;
  // Optional last section. As in Triangle, a region line without a maximum
  // area gets its attribute as maximum area; a negative one means none.
  std::vector<Region> regions;
};

// Reads a .poly file. Throws InputError naming the file and line (malformed
// section header, missing or non-numeric fields, segment endpoint out of
// range, premature end of file; a vertex count of 0 without a readable .node
// beside the .poly), or the .node file's own errors.
PolyFile read_poly(const std::string &path);

// Reads a mesher's input: name.poly (a PSLG; its vertices may come from the
// .node file beside it, whose path then goes to *node_path) or name.node (a
// point set). Throws InputError as read_poly() and read_node() do.
Input read_input(const std::string &path, std::string *node_path = nullptr);

// A Triangle .ele file: the triangles of a mesh to refine (-r).
struct EleFile {
  // 0-based corners, as the file gives them (validate() checks their
  // orientation); of a six-node triangle the first three, as Triangle reads it.
  std::vector<Triangle> triangles;
  int attribute_count = 0;        // attributes per triangle
  std::vector<double> attributes; // triangles.size() * attribute_count, row-major
  std::vector<long> lines;        // line of each triangle in the file, for messages
  int first_index = 0;            // numbering of the triangles (0 or 1, from the first id)
};

// Reads a .ele file ("<#triangles> <nodes per triangle> <#attributes>", then
// "<id> <corner> <corner> <corner> [more nodes] [attributes]") over
// `vertex_count` vertices numbered from `first_vertex`. Throws InputError
// naming the file and line (malformed header, fewer than 3 nodes per
// triangle, a missing corner or attribute, a corner that is no integer or
// out of range, a non-finite attribute, ids out of sequence, premature end).
EleFile read_ele(const std::string &path, long vertex_count, int first_vertex);

// Reads a .area file ("<#triangles>", then "<id> <maximum area>"): one
// maximum area per triangle of the mesh (<= 0: none), for the
// `triangle_count` triangles of its .ele file. Throws InputError naming the
// file and line (a count that differs from triangle_count, a missing or
// non-numeric area, ids out of sequence, premature end).
std::vector<double> read_area(const std::string &path, std::size_t triangle_count);

// Reads a mesh to refine (-r), as Triangle does: the vertices of base.node,
// or with `pslg` those of base.poly (or, when it lists none, of the base.node
// beside it) with its segments and holes (its regions are not read, as
// Triangle reads none with -r); the triangles of base.ele, with their
// attributes; with `areas` (-a without a number) the maximum areas of
// base.area. Input::source is the vertices' file, Input::triangles_source
// the .ele. Every file read is appended to *opened (when given), in order.
// Throws InputError as the readers above do.
Input read_mesh(const std::string &base, bool pslg, bool areas,
                std::vector<std::string> *opened = nullptr);

// Reads a sizing field (--size-field): base.node, whose first vertex
// attribute is the target area at the vertex, and base.ele, its triangles.
// Throws InputError naming the file and line (no attribute, a target area
// that is not positive, a triangle not counter-clockwise, no triangle), or
// those of read_node() and read_ele().
SizeField read_size_field(const std::string &base);

// What the writers need of the mesh.
struct MeshView {
  const std::vector<Point> *points = nullptr; // vertices written to .node
  int attribute_count = 0;
  const std::vector<double> *point_attributes = nullptr; // points * attribute_count, row-major
  const std::vector<int> *point_markers = nullptr;       // the points' own markers, or none
  const std::vector<Triangle> *triangles = nullptr;
  const std::vector<std::array<int32_t, 3>> *neighbors = nullptr; // -1 on the hull
  const std::vector<int32_t> *duplicate_of = nullptr;             // optional, for -j
  // -p: the segments as they stand in the mesh (ConstrainedResult::segments).
  // They set the boundary markers of .node, .edge and .poly as Triangle's -p
  // does, and -j then also drops vertices that no triangle uses.
  const std::vector<Segment> *segments = nullptr;
  // Triangle attributes (-A: the region's; -r: the refined triangle's),
  // triangle_attribute_count per triangle (row-major), written as the .ele
  // attribute columns.
  int triangle_attribute_count = 0;
  const std::vector<double> *triangle_attributes = nullptr;
  // -o2 (Mesh's fields of the same names): middle nodes, written after the
  // vertices with their attributes and markers, and each triangle's three.
  const std::vector<Point> *edge_midpoints = nullptr;
  const std::vector<double> *edge_midpoint_attributes = nullptr;
  const std::vector<int> *edge_midpoint_markers = nullptr;
  const std::vector<std::array<int32_t, 3>> *triangle_midpoints = nullptr;
  // -v (Mesh's fields of the same names).
  const std::vector<Point> *voronoi_points = nullptr;
  const std::vector<double> *voronoi_point_attributes = nullptr;
  const std::vector<VoronoiEdge> *voronoi_edges = nullptr;

  // The points, attributes and markers of a point set.
  void set_points(const PointSet &set);
};

// The view of a whole mesh (segments, triangle attributes, middle nodes and
// the Voronoi diagram when it has them).
MeshView view_of(const Mesh &mesh);

struct WriteOptions {
  int first_index = 1;              // numbering of the output (Triangle: the input's; -z: 0)
  bool jettison_duplicates = false; // -j: drop duplicate vertices from .node
  bool boundary_markers = true;     // false (-B): no marker column in .node, .edge, .poly
  std::string command_line;         // written as a trailing '# Generated by' comment
};

// Edges of the mesh, each once, in Triangle's order (by triangle, then edge),
// with boundary markers: 1 on the convex hull, 0 inside.
std::vector<Edge> mesh_edges(const std::vector<Triangle> &triangles,
                             const std::vector<std::array<int32_t, 3>> &neighbors);
// The same edges with Triangle's -p markers: an edge that is a segment gets the
// segment's marker (0 promoted to 1 when it lies on the mesh boundary), any
// other edge 1 on the mesh boundary, else 0.
std::vector<Edge> mesh_edges(const std::vector<Triangle> &triangles,
                             const std::vector<std::array<int32_t, 3>> &neighbors,
                             const std::vector<Segment> &segments);

// Boundary marker of every vertex as written to .node: its input marker when
// non-zero; else (with mesh.segments) the marker of the first segment with a
// non-zero marker ending at it; else 1 on the boundary of the mesh; else 0.
std::vector<int> output_vertex_markers(const MeshView &mesh);

// Number (0-based, before first_index is added) that each input vertex gets in
// the output files: the identity, except with jettison_duplicates (-j), where
// vertices with duplicate_of[i] != -1 (and, with mesh.segments, vertices that no
// triangle uses, e.g. eaten with a hole) get -1 (not written) and the others
// are renumbered consecutively in input order, as Triangle's -j does.
std::vector<int32_t> output_vertex_numbers(const MeshView &mesh, const WriteOptions &options);

// -p: the segments of mesh.segments that are edges of the mesh (those eaten
// with a hole or the exterior are left out, as Triangle deletes them), with
// their output markers (a segment's own, else 1 on the mesh boundary, else
// 0), in input numbering: what the output .poly lists.
std::vector<Segment> output_segments(const MeshView &mesh);

// Output files are first written beside their final name (under a name no
// file has) and renamed into place only when every file of the batch was
// written, so a failure never leaves a partial file behind. Writing to a name
// that a directory has is refused at once (InputError naming it). The write_*
// calls of different paths may run at once on several threads; commit() after
// they have all returned.
class OutputBatch {
public:
  OutputBatch() = default;
  OutputBatch(const OutputBatch &) = delete;
  OutputBatch &operator=(const OutputBatch &) = delete;
  ~OutputBatch(); // removes temporaries of an uncommitted batch

  void write_node(const std::string &path, const MeshView &mesh, const WriteOptions &options);
  void write_ele(const std::string &path, const MeshView &mesh, const WriteOptions &options);
  void write_edge(const std::string &path, const MeshView &mesh, const WriteOptions &options);
  void write_neigh(const std::string &path, const MeshView &mesh, const WriteOptions &options);
  // Triangle's -v files: name.v.node (the circumcentres, numbered as the
  // triangles, with their interpolated attributes, no markers) and
  // name.v.edge (finite edges "a b", rays "a -1 dx dy", no markers).
  void write_voronoi_node(const std::string &path, const MeshView &mesh,
                          const WriteOptions &options);
  void write_voronoi_edge(const std::string &path, const MeshView &mesh,
                          const WriteOptions &options);
  // Triangle's -g file: the mesh in Object File Format (vertices, middle
  // nodes included, with z = 0; the triangles' corners, numbered from 0).
  void write_off(const std::string &path, const MeshView &mesh, const WriteOptions &options);
  // A VTK XML unstructured grid (.vtu, ASCII) for ParaView: the written
  // vertices (and middle nodes) with z = 0, the triangles (six-node
  // quadratic triangles with -o2), the point data "marker" (unless -B) and
  // "attribute1".. and the cell data "attribute1".. of the triangle attributes.
  void write_vtu(const std::string &path, const MeshView &mesh, const WriteOptions &options);
  // Triangle's output .poly: no vertices (they are in the .node), the segments
  // of mesh.segments that are edges of the mesh (segments eaten with a hole
  // are left out, as Triangle deletes them) with their -p markers, the holes,
  // and the regions when there are any.
  void write_poly(const std::string &path, const MeshView &mesh, const std::vector<Point> &holes,
                  const std::vector<Region> &regions, const WriteOptions &options);
  void write_text(const std::string &path, const std::string &contents);
  // Renames every temporary into place, all or nothing: every target is
  // checked first, a replaced file is kept aside until the end, and when a
  // rename fails the files already placed are removed and the replaced ones
  // restored before the InputError (naming the file) is thrown.
  void commit();

private:
  std::string temporary_for(const std::string &path);
  std::mutex files_mutex_;                                 // guards files_ while writes run at once
  std::vector<std::pair<std::string, std::string>> files_; // temporary, final
};

// SVG picture of the mesh (triangles; input points when few enough; segments,
// when given, drawn thicker in another colour over the triangles).
std::string mesh_svg(const std::vector<Point> &points, const std::vector<Triangle> &triangles,
                     const std::vector<Segment> *segments = nullptr);
// Binary PGM (P5) of a digital Voronoi diagram: each site's region in a grey.
std::string voronoi_pgm(const std::vector<int32_t> &sites, int grid);

} // namespace clmesh
