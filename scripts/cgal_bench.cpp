// cgal_bench: CGAL reference timings for scripts/bench.py.
//
//   cgal_bench [MODE] FILE.node
//   cgal_bench cdt FILE.poly
//   cgal_bench mesh ANGLE FILE.node
//   cgal_bench pslgmesh ANGLE [hull] FILE.poly
//
// MODE (default dt):
//   dt    Delaunay triangulation of the points: times only the construction of
//         CGAL::Delaunay_triangulation_2<Epick> from the point range (the range
//         insert spatially sorts the points first), not the file reading.
//   cdt   Constrained Delaunay triangulation of a .poly (the whole convex hull,
//         like Triangle's -pc; holes and regions are ignored): times the
//         construction of CGAL::Constrained_Delaunay_triangulation_2<Epick>:
//         the points inserted as a range (spatially sorted, each tagged with its
//         index), the vertex handle of every index looked up, then every
//         segment inserted with insert_constraint(handle, handle).  Segments
//         must not cross (CGAL's default intersection tag throws).
//   mesh  Quality mesh of the points' convex hull with minimum angle ANGLE
//         degrees (like Triangle's -qANGLE on a .node): a
//         CGAL::Constrained_Delaunay_triangulation_2<Epick> with the mesher's
//         Delaunay_mesh_vertex_base_2 and Delaunay_mesh_face_base_2; the points
//         inserted as a range, then every convex hull edge (between consecutive
//         hull vertices, collinear ones included: the finite edges of the
//         infinite faces) made a constraint, then
//         CGAL::refine_Delaunay_mesh_2 with Delaunay_mesh_criteria_2(b),
//         b = sin^2(ANGLE) (CGAL's bound on the squared sine of a good
//         triangle's smallest angle; no size bound).  Times from the point
//         insertion to the end of the refinement, not the file reading.  CGAL
//         guarantees termination only up to about 20.7 degrees (b <= 0.125).
//   pslgmesh  Quality mesh of a .poly with minimum angle ANGLE degrees (like
//         Triangle's -pqANGLE, or -pcqANGLE with the word `hull` before the
//         file): the MeshCDT of `mesh`, its points inserted one by one in
//         CGAL::spatial_sort order (each with the previous vertex as hint, so
//         that every index keeps its vertex handle), every segment inserted
//         with insert_constraint, with `hull` every convex hull edge made a
//         constraint too, then CGAL::refine_Delaunay_mesh_2 with the .poly's
//         holes as seeds (seeds mark the components not to mesh; the
//         component of the infinite face is never meshed, as Triangle's -p
//         eats the triangles outside the outer boundary) and
//         Delaunay_mesh_criteria_2(sin^2 ANGLE).  The criteria's b is the
//         bound on the squared sine of the smallest angle: CGAL documents it
//         as the radius-edge bound B = sqrt(1 / (4 b)), and sin(angle) =
//         1 / (2 B).  Times from the point insertion to the end of the
//         refinement.  Regional attributes and area bounds are ignored.  Also
//         reports the mesh's smallest angle in degrees and how many of its
//         triangles have an angle below ANGLE (computed in double precision
//         from the vertex coordinates, with 1e-9 relative tolerance on the
//         squared sine).
//
// Prints one line of JSON on stdout:
//   {"mode": "dt", "seconds": s, "triangles": n, "vertices": n}
// where triangles counts the finite faces and vertices the distinct vertices.
// With mesh, vertices are the input points plus the Steiner points, and
// triangles only the faces in the mesh's domain: a hull edge split at a
// rounded midpoint slightly inside the hull leaves a sliver between the
// constrained subsegments and the hull, a finite face outside the domain.
//
// The readers are deliberately simple: '#' comments, a header
// "<#vertices> <dim> <#attributes> <#markers>", then "<id> <x> <y> ..." lines
// whose ids may start at 0 or 1 (points keep file order).  A .poly must hold
// its vertices (node section count > 0); its segment section
// "<#segments> <#markers>" follows, with "<id> <a> <b> [marker]" lines whose
// endpoints use the numbering of the first vertex id.

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Delaunay_mesh_criteria_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using DT = CGAL::Delaunay_triangulation_2<Kernel>;
using CdtVb = CGAL::Triangulation_vertex_base_with_info_2<long, Kernel>;
using CdtFb = CGAL::Constrained_triangulation_face_base_2<Kernel>;
using CdtTds = CGAL::Triangulation_data_structure_2<CdtVb, CdtFb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<Kernel, CdtTds>;
using MeshVb = CGAL::Delaunay_mesh_vertex_base_2<Kernel>;
using MeshFb = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using MeshTds = CGAL::Triangulation_data_structure_2<MeshVb, MeshFb>;
using MeshCDT = CGAL::Constrained_Delaunay_triangulation_2<Kernel, MeshTds>;

// Splits the file into the whitespace-separated tokens of its non-comment
// parts, one vector of tokens per non-empty line.
class NodeReader {
public:
  explicit NodeReader(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
      throw std::runtime_error("cannot open " + path);
    std::ostringstream ss;
    ss << in.rdbuf();
    text_ = ss.str();
    pos_ = 0;
  }

  // Fills `tok` with the tokens of the next line that has any; false at EOF.
  bool next_line(std::vector<const char *> &tok) {
    tok.clear();
    while (pos_ < text_.size()) {
      size_t end = text_.find('\n', pos_);
      if (end == std::string::npos)
        end = text_.size();
      const void *hash = std::memchr(&text_[pos_], '#', end - pos_);
      size_t stop =
          hash ? static_cast<size_t>(static_cast<const char *>(hash) - text_.data()) : end;
      for (size_t i = pos_; i < stop; ++i) {
        char c = text_[i];
        if (c == ' ' || c == '\t' || c == '\r') {
          text_[i] = '\0';
        } else if (i == pos_ || text_[i - 1] == '\0') {
          tok.push_back(&text_[i]);
        }
      }
      if (stop < text_.size())
        text_[stop] = '\0';
      pos_ = end + 1;
      if (!tok.empty())
        return true;
    }
    return false;
  }

private:
  std::string text_;
  size_t pos_;
};

double to_double(const char *s, const std::string &what) {
  char *end = nullptr;
  double v = std::strtod(s, &end);
  if (end == s || *end != '\0')
    throw std::runtime_error("bad number '" + std::string(s) + "' in " + what);
  return v;
}

std::vector<Point> read_node(const std::string &path) {
  NodeReader r(path);
  std::vector<const char *> tok;
  if (!r.next_line(tok))
    throw std::runtime_error(path + ": empty file");
  long n = std::strtol(tok[0], nullptr, 10);
  if (n <= 0)
    throw std::runtime_error(path +
                             ": no vertices in the header (a .poly that refers to a .node?)");
  if (tok.size() >= 2 && std::strtol(tok[1], nullptr, 10) != 2)
    throw std::runtime_error(path + ": dimension must be 2");
  std::vector<Point> pts;
  pts.reserve(static_cast<size_t>(n));
  for (long i = 0; i < n; ++i) {
    if (!r.next_line(tok))
      throw std::runtime_error(path + ": expected " + std::to_string(n) + " vertices, got " +
                               std::to_string(i));
    if (tok.size() < 3)
      throw std::runtime_error(path + ": short vertex line " + std::to_string(i + 1));
    pts.emplace_back(to_double(tok[1], path), to_double(tok[2], path));
  }
  return pts;
}

// The node section, the segments (0-based endpoints) and the holes of a .poly.
struct Poly {
  std::vector<Point> points;
  std::vector<std::pair<long, long>> segments;
  std::vector<Point> holes;
};

Poly read_poly(const std::string &path) {
  NodeReader r(path);
  std::vector<const char *> tok;
  if (!r.next_line(tok))
    throw std::runtime_error(path + ": empty file");
  const long n = std::strtol(tok[0], nullptr, 10);
  if (n <= 0)
    throw std::runtime_error(path + ": the node section must hold the vertices (count > 0)");
  if (tok.size() >= 2 && std::strtol(tok[1], nullptr, 10) != 2)
    throw std::runtime_error(path + ": dimension must be 2");
  Poly poly;
  poly.points.reserve(static_cast<size_t>(n));
  long base = 0;
  for (long i = 0; i < n; ++i) {
    if (!r.next_line(tok) || tok.size() < 3)
      throw std::runtime_error(path + ": short or missing vertex line " + std::to_string(i + 1));
    if (i == 0)
      base = std::strtol(tok[0], nullptr, 10);
    poly.points.emplace_back(to_double(tok[1], path), to_double(tok[2], path));
  }
  if (!r.next_line(tok))
    throw std::runtime_error(path + ": no segment section");
  const long m = std::strtol(tok[0], nullptr, 10);
  poly.segments.reserve(static_cast<size_t>(std::max(0L, m)));
  for (long i = 0; i < m; ++i) {
    if (!r.next_line(tok) || tok.size() < 3)
      throw std::runtime_error(path + ": short or missing segment line " + std::to_string(i + 1));
    const long a = std::strtol(tok[1], nullptr, 10) - base,
               b = std::strtol(tok[2], nullptr, 10) - base;
    if (a < 0 || a >= n || b < 0 || b >= n)
      throw std::runtime_error(path + ": segment " + std::to_string(i + 1) + " out of range");
    poly.segments.emplace_back(a, b);
  }
  if (r.next_line(tok)) { // the optional hole section
    const long h = std::strtol(tok[0], nullptr, 10);
    for (long i = 0; i < h; ++i) {
      if (!r.next_line(tok) || tok.size() < 3)
        throw std::runtime_error(path + ": short or missing hole line " + std::to_string(i + 1));
      poly.holes.emplace_back(to_double(tok[1], path), to_double(tok[2], path));
    }
  }
  return poly;
}

// Times CGAL's CDT of the .poly; returns the seconds.
double time_cdt(const Poly &poly, CDT &cdt) {
  const size_t n = poly.points.size();
  std::vector<std::pair<Point, long>> input;
  input.reserve(n);
  for (size_t i = 0; i < n; ++i)
    input.emplace_back(poly.points[i], static_cast<long>(i));

  auto t0 = std::chrono::steady_clock::now();
  cdt.insert(input.begin(), input.end());
  // Vertex of every index; a duplicate point's index gets the vertex that stands for it.
  std::vector<CDT::Vertex_handle> vertex(n);
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
    vertex[v->info()] = v;
  std::map<std::pair<double, double>, CDT::Vertex_handle> by_point;
  for (size_t i = 0; i < n; ++i)
    if (vertex[i] == CDT::Vertex_handle()) {
      if (by_point.empty())
        for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
          by_point[{v->point().x(), v->point().y()}] = v;
      vertex[i] = by_point.at({poly.points[i].x(), poly.points[i].y()});
    }
  for (const auto &s : poly.segments)
    if (vertex[s.first] != vertex[s.second])
      cdt.insert_constraint(vertex[s.first], vertex[s.second]);
  auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double>(t1 - t0).count();
}

// The convex hull edges of a triangulation, between consecutive hull vertices (collinear ones
// too): the finite edge of every infinite face.
std::vector<std::pair<MeshCDT::Vertex_handle, MeshCDT::Vertex_handle>>
hull_edges(const MeshCDT &cdt) {
  std::vector<std::pair<MeshCDT::Vertex_handle, MeshCDT::Vertex_handle>> hull;
  const MeshCDT::Vertex_handle inf = cdt.infinite_vertex();
  MeshCDT::Face_circulator f = cdt.incident_faces(inf), done = f;
  do {
    const int i = f->index(inf);
    hull.emplace_back(f->vertex(MeshCDT::ccw(i)), f->vertex(MeshCDT::cw(i)));
  } while (++f != done);
  return hull;
}

// Times CGAL's quality mesh of the points' convex hull (see the top of the file); returns the
// seconds.
double time_mesh(const std::vector<Point> &pts, double angle_degrees, MeshCDT &cdt) {
  const double pi = std::acos(-1.0);
  const double sine = std::sin(angle_degrees * pi / 180.0);
  auto t0 = std::chrono::steady_clock::now();
  cdt.insert(pts.begin(), pts.end());
  if (cdt.dimension() < 2)
    throw std::runtime_error("the points are collinear: nothing to mesh");
  // The hull edges collected first, then constrained.
  for (const auto &e : hull_edges(cdt))
    cdt.insert_constraint(e.first, e.second);
  CGAL::refine_Delaunay_mesh_2(cdt, CGAL::Delaunay_mesh_criteria_2<MeshCDT>(sine * sine));
  auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double>(t1 - t0).count();
}

// Times CGAL's quality mesh of the .poly (see pslgmesh at the top of the file); returns the
// seconds.
double time_pslg_mesh(const Poly &poly, double angle_degrees, bool convex_hull, MeshCDT &cdt) {
  const double pi = std::acos(-1.0);
  const double sine = std::sin(angle_degrees * pi / 180.0);
  const size_t n = poly.points.size();
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i)
    order[i] = i;
  using SortTraits =
      CGAL::Spatial_sort_traits_adapter_2<Kernel, CGAL::Pointer_property_map<Point>::const_type>;

  auto t0 = std::chrono::steady_clock::now();
  CGAL::spatial_sort(order.begin(), order.end(), SortTraits(CGAL::make_property_map(poly.points)));
  std::vector<MeshCDT::Vertex_handle> vertex(n);
  MeshCDT::Vertex_handle hint;
  for (const size_t i : order)
    hint = vertex[i] = cdt.insert(
        poly.points[i], hint == MeshCDT::Vertex_handle() ? MeshCDT::Face_handle() : hint->face());
  if (cdt.dimension() < 2)
    throw std::runtime_error("the points are collinear: nothing to mesh");
  for (const auto &s : poly.segments)
    if (vertex[s.first] != vertex[s.second])
      cdt.insert_constraint(vertex[s.first], vertex[s.second]);
  if (convex_hull)
    for (const auto &e : hull_edges(cdt))
      cdt.insert_constraint(e.first, e.second);
  CGAL::refine_Delaunay_mesh_2(cdt, poly.holes.begin(), poly.holes.end(),
                               CGAL::Delaunay_mesh_criteria_2<MeshCDT>(sine * sine));
  auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double>(t1 - t0).count();
}

// The squared sine of a triangle's smallest angle: 4 area^2 over the product of the squared
// lengths of the two longer edges (the sides of that angle).
double smallest_angle_sine_squared(const Point &a, const Point &b, const Point &c) {
  const double twice_area = CGAL::to_double(CGAL::area(a, b, c)) * 2.0;
  double e[3] = {CGAL::to_double(CGAL::squared_distance(b, c)),
                 CGAL::to_double(CGAL::squared_distance(c, a)),
                 CGAL::to_double(CGAL::squared_distance(a, b))};
  std::sort(e, e + 3);
  return twice_area * twice_area / (e[1] * e[2]);
}

int usage() {
  std::fprintf(stderr, "usage: cgal_bench [dt] FILE.node | cgal_bench cdt FILE.poly | "
                       "cgal_bench mesh ANGLE FILE.node | "
                       "cgal_bench pslgmesh ANGLE [hull] FILE.poly\n");
  return 2;
}

} // namespace

int main(int argc, char **argv) {
  std::string mode = "dt";
  std::string path;
  double angle = 0;
  bool convex_hull = false;
  const bool with_angle =
      argc >= 4 && (std::strcmp(argv[1], "mesh") == 0 || std::strcmp(argv[1], "pslgmesh") == 0);
  if (argc == 2) {
    path = argv[1];
  } else if (argc == 3) {
    mode = argv[1];
    path = argv[2];
  } else if (with_angle) {
    mode = argv[1];
    char *end = nullptr;
    angle = std::strtod(argv[2], &end);
    if (end == argv[2] || *end != '\0' || !(angle > 0 && angle < 60)) {
      std::fprintf(stderr, "cgal_bench: bad angle '%s' (degrees, between 0 and 60)\n", argv[2]);
      return 2;
    }
    path = argv[argc - 1];
    if (argc == 5 && mode == "pslgmesh" && std::strcmp(argv[3], "hull") == 0)
      convex_hull = true;
    else if (argc != 4)
      return usage();
  } else {
    return usage();
  }
  if (mode != "dt" && mode != "cdt" && !(with_angle && (mode == "mesh" || mode == "pslgmesh")))
    return usage();

  try {
    if (mode == "pslgmesh") {
      const Poly poly = read_poly(path);
      MeshCDT cdt;
      const double seconds = time_pslg_mesh(poly, angle, convex_hull, cdt);
      const double pi = std::acos(-1.0);
      const double sine = std::sin(angle * pi / 180.0);
      const double bad_below = sine * sine * (1.0 - 1e-9);
      size_t triangles = 0, bad = 0;
      double smallest = 1.0; // squared sine
      for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (!f->is_in_domain())
          continue;
        ++triangles;
        const double q = smallest_angle_sine_squared(f->vertex(0)->point(), f->vertex(1)->point(),
                                                     f->vertex(2)->point());
        smallest = std::min(smallest, q);
        bad += q < bad_below ? 1 : 0;
      }
      // Vertices of the mesh: those with a face in the domain (the hole's and the outside's
      // vertices that only bound removed faces are not part of it; CGAL keeps them).
      size_t vertices = 0;
      for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
        MeshCDT::Face_circulator f = cdt.incident_faces(v), done = f;
        bool in_domain = false;
        do
          in_domain = in_domain || (!cdt.is_infinite(f) && f->is_in_domain());
        while (!in_domain && ++f != done);
        vertices += in_domain ? 1 : 0;
      }
      std::printf("{\"mode\": \"pslgmesh\", \"seconds\": %.9g, \"triangles\": %zu, "
                  "\"vertices\": %zu, \"bad_triangles\": %zu, \"min_angle\": %.6f}\n",
                  seconds, triangles, vertices, bad, std::asin(std::sqrt(smallest)) * 180.0 / pi);
      return 0;
    }
    if (mode == "cdt") {
      const Poly poly = read_poly(path);
      CDT cdt;
      const double seconds = time_cdt(poly, cdt);
      std::printf("{\"mode\": \"cdt\", \"seconds\": %.9g, \"triangles\": %zu, \"vertices\": %zu}\n",
                  seconds, static_cast<size_t>(cdt.number_of_faces()),
                  static_cast<size_t>(cdt.number_of_vertices()));
      return 0;
    }

    std::vector<Point> pts = read_node(path);
    if (mode == "mesh") {
      MeshCDT cdt;
      const double seconds = time_mesh(pts, angle, cdt);
      // Only the mesh's faces: the rounded midpoints of split hull edges leave slivers between
      // the constrained subsegments and the convex hull, outside the domain.
      size_t triangles = 0;
      for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
        triangles += f->is_in_domain() ? 1 : 0;
      std::printf(
          "{\"mode\": \"mesh\", \"seconds\": %.9g, \"triangles\": %zu, \"vertices\": %zu}\n",
          seconds, triangles, static_cast<size_t>(cdt.number_of_vertices()));
      return 0;
    }

    auto t0 = std::chrono::steady_clock::now();
    DT dt;
    dt.insert(pts.begin(), pts.end());
    auto t1 = std::chrono::steady_clock::now();
    double seconds = std::chrono::duration<double>(t1 - t0).count();

    std::printf("{\"mode\": \"%s\", \"seconds\": %.9g, \"triangles\": %zu, \"vertices\": %zu}\n",
                mode.c_str(), seconds, static_cast<size_t>(dt.number_of_faces()),
                static_cast<size_t>(dt.number_of_vertices()));
  } catch (const std::exception &e) {
    std::fprintf(stderr, "cgal_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
