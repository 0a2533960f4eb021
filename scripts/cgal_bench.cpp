// cgal_bench: CGAL reference timings for scripts/bench.py.
//
//   cgal_bench [MODE] FILE.node
//
// MODE (default dt):
//   dt    Delaunay triangulation of the points: times only the construction of
//         CGAL::Delaunay_triangulation_2<Epick> from the point range (the range
//         insert spatially sorts the points first), not the file reading.
//   (cdt and mesh are reserved for the constrained triangulation and the
//    refinement benchmarks.)
//
// Prints one line of JSON on stdout:
//   {"mode": "dt", "seconds": s, "triangles": n, "vertices": n}
// where triangles counts the finite faces and vertices the distinct vertices.
//
// The .node reader is deliberately simple: '#' comments, a header
// "<#vertices> <dim> <#attributes> <#markers>", then "<id> <x> <y> ..." lines
// whose ids may start at 0 or 1 (they are not used: points keep file order).

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using DT = CGAL::Delaunay_triangulation_2<Kernel>;

// Splits the file into the whitespace-separated tokens of its non-comment
// parts, one vector of tokens per non-empty line.
class NodeReader {
 public:
  explicit NodeReader(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::ostringstream ss;
    ss << in.rdbuf();
    text_ = ss.str();
    pos_ = 0;
  }

  // Fills `tok` with the tokens of the next line that has any; false at EOF.
  bool next_line(std::vector<const char*>& tok) {
    tok.clear();
    while (pos_ < text_.size()) {
      size_t end = text_.find('\n', pos_);
      if (end == std::string::npos) end = text_.size();
      const void* hash = std::memchr(&text_[pos_], '#', end - pos_);
      size_t stop = hash ? static_cast<size_t>(static_cast<const char*>(hash) - text_.data()) : end;
      for (size_t i = pos_; i < stop; ++i) {
        char c = text_[i];
        if (c == ' ' || c == '\t' || c == '\r') {
          text_[i] = '\0';
        } else if (i == pos_ || text_[i - 1] == '\0') {
          tok.push_back(&text_[i]);
        }
      }
      if (stop < text_.size()) text_[stop] = '\0';
      pos_ = end + 1;
      if (!tok.empty()) return true;
    }
    return false;
  }

 private:
  std::string text_;
  size_t pos_;
};

double to_double(const char* s, const std::string& what) {
  char* end = nullptr;
  double v = std::strtod(s, &end);
  if (end == s || *end != '\0') throw std::runtime_error("bad number '" + std::string(s) + "' in " + what);
  return v;
}

std::vector<Point> read_node(const std::string& path) {
  NodeReader r(path);
  std::vector<const char*> tok;
  if (!r.next_line(tok)) throw std::runtime_error(path + ": empty file");
  long n = std::strtol(tok[0], nullptr, 10);
  if (n <= 0) throw std::runtime_error(path + ": no vertices in the header (a .poly that refers to a .node?)");
  if (tok.size() >= 2 && std::strtol(tok[1], nullptr, 10) != 2)
    throw std::runtime_error(path + ": dimension must be 2");
  std::vector<Point> pts;
  pts.reserve(static_cast<size_t>(n));
  for (long i = 0; i < n; ++i) {
    if (!r.next_line(tok)) throw std::runtime_error(path + ": expected " + std::to_string(n) + " vertices, got " + std::to_string(i));
    if (tok.size() < 3) throw std::runtime_error(path + ": short vertex line " + std::to_string(i + 1));
    pts.emplace_back(to_double(tok[1], path), to_double(tok[2], path));
  }
  return pts;
}

int usage() {
  std::fprintf(stderr, "usage: cgal_bench [dt] FILE.node   (cdt and mesh are not implemented yet)\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mode = "dt";
  std::string path;
  if (argc == 2) {
    path = argv[1];
  } else if (argc == 3) {
    mode = argv[1];
    path = argv[2];
  } else {
    return usage();
  }
  if (mode == "cdt" || mode == "mesh") {
    std::fprintf(stderr, "cgal_bench: mode '%s' is not implemented yet\n", mode.c_str());
    return 2;
  }
  if (mode != "dt") return usage();

  try {
    std::vector<Point> pts = read_node(path);

    auto t0 = std::chrono::steady_clock::now();
    DT dt;
    dt.insert(pts.begin(), pts.end());
    auto t1 = std::chrono::steady_clock::now();
    double seconds = std::chrono::duration<double>(t1 - t0).count();

    std::printf("{\"mode\": \"%s\", \"seconds\": %.9g, \"triangles\": %zu, \"vertices\": %zu}\n", mode.c_str(),
                seconds, static_cast<size_t>(dt.number_of_faces()), static_cast<size_t>(dt.number_of_vertices()));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cgal_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
