// clmesh — the mesh as a VTK XML unstructured grid (.vtu, ASCII), for ParaView.
#include "clmesh/io.hpp"

#include "io/text_file.hpp"
#include "io/view_access.hpp"

namespace clmesh {

void OutputBatch::write_vtu(const std::string &path, const MeshView &mesh,
                            const WriteOptions &options) {
  const std::vector<Point> &points = points_of(mesh);
  const std::vector<Triangle> &triangles = triangles_of(mesh);
  const std::vector<Point> &midpoints = midpoints_of(mesh);
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  const std::size_t written = written_count(numbers), attributes = attributes_of(mesh);
  const bool six_nodes = !midpoints.empty();
  WriteOptions from_zero = options; // VTK numbers its points from 0
  from_zero.first_index = 0;
  TextFile file(temporary_for(path), path);
  file.text("<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
            "<UnstructuredGrid>\n");
  file.format("<Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n", written + midpoints.size(),
              triangles.size());
  // Every written point (vertices, then middle nodes) through `value`.
  auto point_values = [&](auto value) {
    for (std::size_t i = 0; i < points.size(); ++i)
      if (numbers[i] >= 0)
        value(i, false);
    for (std::size_t k = 0; k < midpoints.size(); ++k)
      value(k, true);
  };
  file.text("<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
            "format=\"ascii\">\n");
  point_values([&](std::size_t i, bool midpoint) {
    const Point &p = midpoint ? midpoints[i] : points[i];
    file.real(p.x);
    file.text(" ");
    file.real(p.y);
    file.text(" 0");
    file.end_line();
  });
  file.text("</DataArray>\n</Points>\n<Cells>\n"
            "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      file.integer(written_vertex(numbers, triangles[t][k], from_zero));
      file.text(" ");
    }
    // VTK's quadratic triangle: corners, then the middles of edges 01, 12, 20
    // (opposite corners 2, 0, 1).
    for (int k : {2, 0, 1})
      if (six_nodes) {
        file.integer(static_cast<long>(written) + (*mesh.triangle_midpoints)[t][k]);
        file.text(" ");
      }
    file.end_line();
  }
  file.text("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    file.integer(static_cast<long>((t + 1) * (six_nodes ? 6 : 3)));
    file.end_line();
  }
  file.text("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    file.integer(six_nodes ? 22 : 5); // VTK_QUADRATIC_TRIANGLE, VTK_TRIANGLE
    file.end_line();
  }
  file.text("</DataArray>\n</Cells>\n<PointData>\n");
  if (options.boundary_markers) {
    const std::vector<int> markers = output_vertex_markers(mesh);
    file.text("<DataArray type=\"Int32\" Name=\"marker\" format=\"ascii\">\n");
    point_values([&](std::size_t i, bool midpoint) {
      file.integer(midpoint ? (*mesh.edge_midpoint_markers)[i] : markers[i]);
      file.end_line();
    });
    file.text("</DataArray>\n");
  }
  for (std::size_t a = 0; a < attributes; ++a) {
    file.format("<DataArray type=\"Float64\" Name=\"attribute%zu\" format=\"ascii\">\n", a + 1);
    point_values([&](std::size_t i, bool midpoint) {
      file.real(midpoint ? (*mesh.edge_midpoint_attributes)[i * attributes + a]
                         : (*mesh.point_attributes)[i * attributes + a]);
      file.end_line();
    });
    file.text("</DataArray>\n");
  }
  file.text("</PointData>\n<CellData>\n");
  const std::size_t columns = triangle_attributes_of(mesh);
  for (std::size_t a = 0; a < columns; ++a) {
    file.format("<DataArray type=\"Float64\" Name=\"attribute%zu\" format=\"ascii\">\n", a + 1);
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      file.real((*mesh.triangle_attributes)[t * columns + a]);
      file.end_line();
    }
    file.text("</DataArray>\n");
  }
  file.text("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
  file.close();
}

} // namespace clmesh
