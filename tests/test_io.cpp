// Tests of Triangle's file formats (clmesh/io.hpp): reading, writing, batches.
#include "clmesh/errors.hpp"
#include "clmesh/io.hpp"
#include "io/directed_edges.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace clmesh;

namespace {

const fs::path kExamples = fs::path(CLMESH_SHARED_DATA) / "triangle-examples";

// A fresh directory, removed with everything in it at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    static int counter = 0;
    std::random_device seed;
    path = fs::temp_directory_path() /
           ("clmesh_test_io_" + std::to_string(seed()) + "_" + std::to_string(counter++));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  std::string file(const std::string &name) const { return (path / name).string(); }
  std::vector<std::string> names() const {
    std::vector<std::string> found;
    for (const auto &entry : fs::directory_iterator(path))
      found.push_back(entry.path().filename().string());
    std::sort(found.begin(), found.end());
    return found;
  }
};

void write_file(const std::string &path, const std::string &text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string read_file(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// `call` must throw an InputError naming `path` and `line`, with `words` in its message.
template <typename Call>
void expect_file_error(Call call, const std::string &path, long line, const std::string &words) {
  bool thrown = false;
  try {
    call();
  } catch (const InputError &error) {
    thrown = true;
    const std::string message = error.what();
    CAPTURE(message);
    CHECK(error.file() == path);
    CHECK(error.line() == line);
    CHECK(message.find(path + (line > 0 ? ":" + std::to_string(line) + ": " : ": ")) == 0);
    CHECK(message.find(words) != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  }
  CHECK(thrown);
}

// read_node on `text` must fail on `line` with a message containing `words`.
void expect_input_error(const std::string &text, long line, const std::string &words) {
  TempDir dir;
  const std::string path = dir.file("bad.node");
  write_file(path, text);
  CAPTURE(text);
  expect_file_error([&] { read_node(path); }, path, line, words);
}

PointSet read_text(const std::string &text) {
  TempDir dir;
  write_file(dir.file("in.node"), text);
  return read_node(dir.file("in.node"));
}

// Neighbours of a triangle list (opposite vertex i), -1 on the boundary.
std::vector<std::array<int32_t, 3>> neighbors_of(const std::vector<Triangle> &triangles) {
  std::map<std::pair<int32_t, int32_t>, int32_t> owner; // directed edge -> triangle
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int i = 0; i < 3; ++i)
      owner[{triangles[t][(i + 1) % 3], triangles[t][(i + 2) % 3]}] = static_cast<int32_t>(t);
  std::vector<std::array<int32_t, 3>> neighbors(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      auto it = owner.find({triangles[t][(i + 2) % 3], triangles[t][(i + 1) % 3]});
      neighbors[t][i] = it == owner.end() ? -1 : it->second;
    }
  return neighbors;
}

// Triangles of a Triangle .ele file, 0-based (a minimal reader for the tests).
std::vector<Triangle> read_ele(const std::string &path, int first_index) {
  std::istringstream in(read_file(path));
  std::string line;
  std::vector<Triangle> triangles;
  long count = -1;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream fields(line);
    if (count < 0) {
      if (fields >> count)
        triangles.reserve(static_cast<std::size_t>(count));
      continue;
    }
    long id;
    Triangle t;
    if (fields >> id >> t[0] >> t[1] >> t[2]) {
      for (auto &v : t)
        v -= first_index;
      triangles.push_back(t);
    }
  }
  REQUIRE(static_cast<long>(triangles.size()) == count);
  return triangles;
}

std::vector<std::string> lines_of(const std::string &text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

// read_poly on `text` (as bad.poly, beside the given extra files) must fail
// on `line` of `file` (bad.poly unless given) with a message holding `words`.
void expect_poly_error(const std::string &text, long line, const std::string &words,
                       const std::map<std::string, std::string> &extra = {},
                       const std::string &file = "bad.poly") {
  TempDir dir;
  const std::string path = dir.file("bad.poly");
  write_file(path, text);
  for (const auto &other : extra)
    write_file(dir.file(other.first), other.second);
  CAPTURE(text);
  bool thrown = false;
  try {
    read_poly(path);
  } catch (const InputError &error) {
    thrown = true;
    const std::string message = error.what();
    CAPTURE(message);
    CHECK(error.file() == dir.file(file));
    CHECK(error.line() == line);
    CHECK(message.find(dir.file(file)) == 0);
    if (line > 0)
      CHECK(message.find(":" + std::to_string(line) + ": ") != std::string::npos);
    CHECK(message.find(words) != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  }
  CHECK(thrown);
}

// The .poly text of `path` with its vertex section replaced by "0 2 0 1": the
// first `vertices` + 1 lines holding fields are dropped, comments are kept.
std::string without_vertices(const std::string &path, int vertices) {
  std::string out = "0  2  0  1\n";
  int fields_lines = 0;
  for (const std::string &line : lines_of(read_file(path))) {
    const std::string data = line.substr(0, line.find('#'));
    const bool has_fields = data.find_first_not_of(" \t\r") != std::string::npos;
    if (has_fields && fields_lines++ <= vertices)
      continue;
    out += line + "\n";
  }
  return out;
}

// Endpoints as an unordered pair.
std::pair<int32_t, int32_t> ends_of(const Segment &s) {
  return {std::min(s.a, s.b), std::max(s.a, s.b)};
}

} // namespace

// ---------------------------------------------------------------------------
// read_node
// ---------------------------------------------------------------------------

TEST_CASE("read_node reads every .node file of the Triangle examples") {
  const std::map<std::string, std::pair<std::size_t, bool>> expected = {
      {"spiral.node", {15, false}},      {"dots.node", {100, false}},
      {"greenland.node", {33343, true}}, {"diamond_02_00009.node", {9, false}},
      {"double_hex3.node", {16, true}},  {"ell.node", {21, true}},
      {"bbox.1.node", {12, true}},
  };
  int files = 0;
  for (const char *folder : {"inputs", "reference-outputs"}) {
    for (const auto &entry : fs::directory_iterator(kExamples / folder)) {
      if (entry.path().extension() != ".node")
        continue;
      const std::string name = entry.path().filename().string();
      CAPTURE(name);
      PointSet set;
      REQUIRE_NOTHROW(set = read_node(entry.path().string()));
      ++files;
      CHECK(set.points.size() >= 3);
      CHECK(set.first_index == 1);
      CHECK(set.attributes.size() == set.points.size() * set.attribute_count);
      CHECK(set.markers.size() == (set.has_markers ? set.points.size() : 0));
      for (const Point &p : set.points)
        CHECK((std::isfinite(p.x) && std::isfinite(p.y)));
      if (std::string(folder) == "inputs") {
        auto known = expected.find(name);
        if (known != expected.end()) {
          CHECK(set.points.size() == known->second.first);
          CHECK(set.has_markers == known->second.second);
        }
      }
    }
  }
  CHECK(files >= 7);

  const PointSet spiral = read_node((kExamples / "inputs" / "spiral.node").string());
  CHECK(spiral.points[0].x == 0.0);
  CHECK(spiral.points[1].x == -0.416);
  CHECK(spiral.points[14].y == 3.49);
  const PointSet a = read_node((kExamples / "reference-outputs" / "A.1.node").string());
  CHECK(a.attribute_count == 1);
  CHECK(a.points.size() == 29);
  CHECK(a.attributes[0] == -0.56999999999999995);
}

TEST_CASE("read_node: comments, blank lines, numbering, attributes, markers") {
  SUBCASE("comments and blank lines anywhere, 1-based") {
    const PointSet set = read_text("# a comment\n\n   \t\n4 2 0 0 # header comment\n"
                                   "# between\n1 0 0\n\n2 1.5 -2e3   # trailing\n"
                                   "  3\t0x1p-2\t+7\r\n#\n4 .5 5.\n# end\n");
    REQUIRE(set.points.size() == 4);
    CHECK(set.first_index == 1);
    CHECK(set.points[1].x == 1.5);
    CHECK(set.points[1].y == -2000.0);
    CHECK(set.points[2].x == 0.25);
    CHECK(set.points[2].y == 7.0);
    CHECK(set.points[3].x == 0.5);
    CHECK(set.points[3].y == 5.0);
    CHECK(set.attribute_count == 0);
    CHECK_FALSE(set.has_markers);
    CHECK(set.markers.empty());
  }
  SUBCASE("0-based") {
    const PointSet set = read_text("3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n");
    CHECK(set.first_index == 0);
    CHECK(set.points.size() == 3);
    CHECK(set.points[2].y == 1.0);
  }
  SUBCASE("attributes and markers") {
    const PointSet set = read_text("3 2 2 1\n1 0 0 10 11 5\n2 1 0 20 21 0\n3 0 1 30 31 -7\n");
    REQUIRE(set.points.size() == 3);
    CHECK(set.attribute_count == 2);
    CHECK(set.attributes == std::vector<double>{10, 11, 20, 21, 30, 31});
    CHECK(set.has_markers);
    CHECK(set.markers == std::vector<int>{5, 0, -7});
  }
  SUBCASE("short header defaults as in Triangle") {
    const PointSet set = read_text("3\n1 0 0\n2 1 0\n3 0 1\n");
    CHECK(set.points.size() == 3);
    CHECK(set.attribute_count == 0);
    CHECK_FALSE(set.has_markers);
  }
  SUBCASE("fields beyond the declared ones are ignored, as Triangle does") {
    const PointSet set = read_text("3 2 0 0\n1 0 0 9\n2 1 0 9\n3 0 1 9\n");
    CHECK(set.points.size() == 3);
    CHECK_FALSE(set.has_markers);
  }
  SUBCASE("fewer than three vertices is the caller's business") {
    CHECK(read_text("0 2 0 0\n").points.empty());
    CHECK(read_text("1 2 0 0\n1 5 5\n").points.size() == 1);
  }
}

TEST_CASE("read_node errors name the file and the line") {
  SUBCASE("missing file") {
    TempDir dir;
    const std::string path = dir.file("absent.node");
    try {
      read_node(path);
      FAIL("no error");
    } catch (const InputError &error) {
      CHECK(error.file() == path);
      CHECK(error.line() == 0);
      CHECK(std::string(error.what()).find(path) == 0);
    }
  }
  SUBCASE("directory") {
    TempDir dir;
    CHECK_THROWS_AS(read_node(dir.path.string()), InputError);
  }
  expect_input_error("", 1, "missing header");
  expect_input_error("# only a comment\n\n", 3, "missing header");
  expect_input_error("abc 2 0 0\n", 1, "malformed header");
  expect_input_error("# c\n\n-3 2 0 0\n", 3, "malformed header");
  expect_input_error("3 2.5 0 0\n", 1, "dimension");
  expect_input_error("3 3 0 0\n1 0 0 0\n", 1, "dimension must be 2");
  expect_input_error("3 2 x 0\n", 1, "attribute count");
  expect_input_error("3 2 0 2\n", 1, "must be 0 or 1");
  expect_input_error("3 2 0 0\n1 0 0\n2 1\n3 0 1\n", 3, "expected 3");
  expect_input_error("3 2 1 1\n1 0 0 5 1\n2 1 0 5\n", 3, "expected 5");
  expect_input_error("3 2 0 0\n1 0 0\n2 1 abc\n3 0 1\n", 3, "'abc'");
  expect_input_error("3 2 0 0\n1 0 0\n2 1 1.5x\n3 0 1\n", 3, "not a number");
  expect_input_error("3 2 0 0\n1 0 0\n2 1 0\n\n3 nan 1\n", 5, "not finite");
  expect_input_error("3 2 0 0\n1 0 0\n2 -inf 0\n3 0 1\n", 3, "not finite");
  expect_input_error("3 2 0 0\n1 0 0\n2 1e999 0\n3 0 1\n", 3, "not finite");
  expect_input_error("3 2 1 0\n1 0 0 1\n2 1 0 zz\n3 0 1 1\n", 3, "attribute");
  expect_input_error("3 2 0 1\n1 0 0 1\n2 1 0 1.5\n3 0 1 1\n", 3, "boundary marker");
  expect_input_error("3 2 0 1\n1 0 0 1\n2 1 0\n3 0 1 1\n", 3, "expected 4");
  expect_input_error("3 2 1 0\n1 0 0 1\n2 1 0 nan\n3 0 1 1\n", 3,
                     "attribute 'nan' of vertex 2 is not finite");
  expect_input_error("3 2 0 0\n1.0 0 0\n", 2, "not an integer");
  expect_input_error("3 2 0 0\n2 0 0\n", 2, "first vertex id must be 0 or 1");
  expect_input_error("3 2 0 0\n1 0 0\n3 1 0\n2 0 1\n", 3, "out of sequence");
  expect_input_error("3 2 0 0\n0 0 0\n1 1 0\n1 0 1\n", 4, "out of sequence");
  expect_input_error("4 2 0 0\n1 0 0\n2 1 0\n3 0 1\n", 5, "3 of 4 vertices");
  expect_input_error("4 2 0 0\n1 0 0\n2 1 0\n3 0 1", 4, "3 of 4 vertices");
  expect_input_error("4 2 0 0\n1 0 0\n# gone\n", 4, "1 of 4 vertices");
}

TEST_CASE("messages show input text escaped and whole") {
  SUBCASE("printable and quote") {
    CHECK(printable("plain 1.5e3 -x") == "plain 1.5e3 -x");
    CHECK(printable(std::string("a\0b", 3)) == "a\\x00b");
    CHECK(printable("\x1b[31mred\n\t\x7f") == "\\x1b[31mred\\x0a\\x09\\x7f");
    CHECK(printable("caf\xc3\xa9 \xe2\x88\x9e") == "caf\xc3\xa9 \xe2\x88\x9e"); // UTF-8 kept
    CHECK(printable("\xc2\x9b"
                    "2J") == "\\xc2\\x9b"
                             "2J");               // C1 control (CSI)
    CHECK(printable("\xff\xc3") == "\\xff\\xc3"); // not UTF-8
    CHECK(printable("\xc0\x80") == "\\xc0\\x80"); // overlong NUL
    CHECK(printable(printable("\x1b\\x1b")) == printable("\x1b\\x1b"));
    CHECK(quote(std::string("1\0", 2)) == "'1\\x00'");
    const std::string quoted_long = quote(std::string(10000, '7'));
    CHECK(quoted_long == "'" + std::string(256, '7') + "'...");
  }
  SUBCASE("an escape sequence in a coordinate") {
    expect_input_error("3 2 0 0\n1 0 0\n2 1\x1b[2J 0\n3 0 1\n", 3,
                       "x coordinate '1\\x1b[2J' of vertex 2 is not a number");
  }
  SUBCASE("a NUL byte neither ends a line nor the message") {
    expect_input_error(std::string("3 2 0 0\n1 0 0\n2 1 0\0\x01\n3 0 1\n", 28), 3,
                       "the line holds a NUL byte");
    expect_input_error(std::string("3 2 0 0\n1 0 0\n2 1 0\n3\0 0 1\n", 27), 4,
                       "the line holds a NUL byte");
    expect_input_error(std::string("3 2 0 0 # \0\n", 13), 1, "the line holds a NUL byte");
  }
  SUBCASE("a file name with control bytes") {
    TempDir dir;
    const std::string path = dir.file("bad\x1b[1m.node");
    write_file(path, "x\n");
    CHECK_THROWS_WITH_AS(read_node(path),
                         doctest::Contains("bad\\x1b[1m.node:1: malformed header: 'x'"),
                         InputError);
  }
}

TEST_CASE("read_node reads as it parses: endless, binary and huge inputs") {
  SUBCASE("lines across the reader's 4 MiB chunks") {
    TempDir dir;
    const int count = 300000; // about 9 MB
    std::string text = "# many\n" + std::to_string(count) + " 2 0 1\n";
    for (int i = 0; i < count; ++i)
      text += std::to_string(i + 1) + " " + std::to_string(i * 0.5) + " " +
              std::to_string(i % 977) + " " + std::to_string(i % 3) + "\n";
    write_file(dir.file("many.node"), text);
    const PointSet set = read_node(dir.file("many.node"));
    REQUIRE(set.points.size() == static_cast<std::size_t>(count));
    for (int i : {0, 1, 139810, 139811, count / 2, count - 1}) {
      CHECK(set.points[i].x == doctest::Approx(i * 0.5));
      CHECK(set.points[i].y == i % 977);
      CHECK(set.markers[i] == i % 3);
    }
  }
  SUBCASE("a line with many attributes may be longer than 1 MiB") {
    TempDir dir;
    const int attributes = 60000;
    std::string values;
    for (int a = 0; a < attributes; ++a)
      values += " 0.12345678901234567890";
    std::string text = "3 2 " + std::to_string(attributes) + " 0\n";
    for (int i = 1; i <= 3; ++i)
      text += std::to_string(i) + " " + std::to_string(i % 2) + " " + std::to_string(i / 2) +
              values + "\n";
    write_file(dir.file("wide.node"), text);
    const PointSet set = read_node(dir.file("wide.node"));
    CHECK(set.attributes.size() == 3u * attributes);
  }
  SUBCASE("a line longer than a section can hold") {
    expect_input_error("3 2 0 0\n" + std::string(3 << 20, '7') + "\n", 2, "longer than");
    expect_input_error(std::string(3 << 20, 'y'), 1, "longer than");
  }
  SUBCASE("a vertex count that the file cannot hold fails at its end") {
    expect_input_error("2000000000 2 0 0\n1 0 0\n2 1 0\n3 0 1\n", 5,
                       "after 3 of 2000000000 vertices");
    expect_input_error("1000000000000 2 0 0\n1 0 0\n", 1, "not a vertex count");
  }
  SUBCASE("device files") {
    TempDir dir;
    std::error_code error;
    fs::create_symlink("/dev/zero", dir.file("zero.node"), error);
    if (!error && fs::exists("/dev/zero"))
      CHECK_THROWS_WITH_AS(read_node(dir.file("zero.node")),
                           doctest::Contains("zero.node:1: the line holds a NUL byte"), InputError);
    fs::create_symlink("/dev/urandom", dir.file("random.node"), error);
    if (!error && fs::exists("/dev/urandom"))
      CHECK_THROWS_AS(read_node(dir.file("random.node")), InputError);
  }
}

// ---------------------------------------------------------------------------
// read_poly
// ---------------------------------------------------------------------------

TEST_CASE("read_poly reads every .poly file of the Triangle examples") {
  struct Expected {
    std::size_t points;
    int attributes;
    bool point_markers;
    std::size_t segments;
    bool segment_markers;
    std::size_t holes, regions;
  };
  const std::map<std::string, Expected> expected = {
      {"A.poly", {29, 1, false, 29, false, 1, 0}},
      {"box.poly", {8, 0, true, 5, true, 1, 0}},
      {"face.poly", {26, 0, true, 22, true, 3, 0}},
      {"la.poly", {141, 0, true, 148, true, 0, 6}},
      {"double_hex.poly", {96, 0, true, 96, true, 2, 0}},
      {"double_hex2.poly", {48, 0, true, 48, true, 2, 0}},
      {"double_hex3.poly", {16, 0, true, 16, true, 2, 0}},
      {"square_circle_hole.poly", {826, 0, true, 135, true, 1, 0}},
      // Triangle's outputs: 0 vertices, read from the .1.node beside them.
      {"A.1.poly", {29, 1, true, 29, true, 1, 0}},
      {"box.1.poly", {8, 0, true, 8, true, 1, 0}},
      {"face.1.poly", {26, 0, true, 22, true, 3, 0}},
      {"la.1.poly", {860, 0, true, 499, true, 0, 6}},
      {"double_hex.1.poly", {96, 0, true, 96, true, 2, 0}},
  };
  std::size_t files = 0;
  for (const char *folder : {"inputs", "reference-outputs"}) {
    for (const auto &entry : fs::directory_iterator(kExamples / folder)) {
      if (entry.path().extension() != ".poly")
        continue;
      const std::string name = entry.path().filename().string();
      CAPTURE(name);
      PolyFile poly;
      REQUIRE_NOTHROW(poly = read_poly(entry.path().string()));
      ++files;
      auto known = expected.find(name);
      REQUIRE(known != expected.end());
      const Expected &want = known->second;
      CHECK(poly.points.points.size() == want.points);
      CHECK(poly.points.attribute_count == want.attributes);
      CHECK(poly.points.has_markers == want.point_markers);
      CHECK(poly.points.first_index == 1);
      CHECK(poly.segments.size() == want.segments);
      CHECK(poly.segment_lines.size() == want.segments);
      CHECK(poly.segment_markers == want.segment_markers);
      CHECK(poly.holes.size() == want.holes);
      CHECK(poly.regions.size() == want.regions);
      CHECK(poly.node_path.empty() == (std::string(folder) == "inputs"));
      for (const Segment &segment : poly.segments) {
        CHECK(segment.a >= 0);
        CHECK(segment.b >= 0);
        CHECK(static_cast<std::size_t>(segment.a) < poly.points.points.size());
        CHECK(static_cast<std::size_t>(segment.b) < poly.points.points.size());
      }
      CHECK(std::is_sorted(poly.segment_lines.begin(), poly.segment_lines.end()));
    }
  }
  CHECK(files == expected.size());

  const std::string inputs = (kExamples / "inputs").string();
  const PolyFile a = read_poly(inputs + "/A.poly");
  CHECK(a.points.attributes[0] == -0.57);
  CHECK(a.segments[0].a == 28); // "1 29 1", numbered from 1
  CHECK(a.segments[0].b == 0);
  CHECK(a.segments[0].marker == 0);
  CHECK(a.segment_lines[0] == 32);
  CHECK(a.segment_lines[28] == 60);
  CHECK(a.holes[0].x == 0.47);
  CHECK(a.holes[0].y == -0.5);
  const PolyFile box = read_poly(inputs + "/box.poly");
  CHECK(box.points.markers[3] == 33);
  CHECK(box.segments[0].marker == 5);
  CHECK(box.segments[3].a == 7);
  CHECK(box.segments[3].b == 5);
  CHECK(box.segments[3].marker == 10);
  CHECK(box.segment_lines[0] == 24);
  CHECK(box.holes[0].x == 1.5);
  const PolyFile la = read_poly(inputs + "/la.poly");
  // "1 6 -0.2 0.05": no maximum area, so Triangle takes the attribute as one.
  CHECK(la.regions[0].seed.x == 6);
  CHECK(la.regions[0].seed.y == -0.2);
  CHECK(la.regions[0].attribute == 0.05);
  CHECK(la.regions[0].max_area == 0.05);
  CHECK(la.regions[5].seed.x == 5);
  CHECK(la.regions[5].attribute == 3);
  CHECK(la.segments.back().marker == 0);
}

TEST_CASE("read_poly: a vertex count of 0 reads the .node file beside the .poly") {
  const fs::path inputs = kExamples / "inputs";
  const PolyFile original = read_poly((inputs / "double_hex3.poly").string());
  TempDir dir;
  fs::copy_file(inputs / "double_hex3.node", dir.path / "double_hex3.node");
  write_file(dir.file("double_hex3.poly"),
             without_vertices((inputs / "double_hex3.poly").string(), 16));
  const PolyFile poly = read_poly(dir.file("double_hex3.poly"));
  CHECK(poly.node_path == dir.file("double_hex3.node"));
  const PointSet node = read_node((inputs / "double_hex3.node").string());
  REQUIRE(poly.points.points.size() == 16);
  for (std::size_t i = 0; i < 16; ++i) {
    CHECK(poly.points.points[i].x == node.points[i].x);
    CHECK(poly.points.points[i].y == node.points[i].y);
  }
  CHECK(poly.points.markers == node.markers);
  REQUIRE(poly.segments.size() == original.segments.size());
  for (std::size_t i = 0; i < poly.segments.size(); ++i) {
    CHECK(poly.segments[i].a == original.segments[i].a);
    CHECK(poly.segments[i].b == original.segments[i].b);
    CHECK(poly.segments[i].marker == original.segments[i].marker);
  }
  CHECK(poly.holes.size() == 2);
  CHECK(poly.holes[1].x == 0.6);

  SUBCASE("numbering follows the .node file") {
    TempDir zero;
    write_file(zero.file("z.node"), "3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n");
    write_file(zero.file("z.poly"), "0 2 0 0\n3 0\n0 0 1\n1 1 2\n2 2 0\n0\n");
    const PolyFile z = read_poly(zero.file("z.poly"));
    CHECK(z.points.first_index == 0);
    REQUIRE(z.segments.size() == 3);
    CHECK(z.segments[1].a == 1);
    CHECK(z.segments[1].b == 2);
    // The same .poly beside a 1-based .node: endpoint 0 is out of range.
    write_file(zero.file("z.node"), "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n");
    CHECK_THROWS_WITH_AS(read_poly(zero.file("z.poly")),
                         doctest::Contains("endpoint 0 of segment 0 is out of range"), InputError);
  }
  SUBCASE("no .node beside it: the error names the .node file and the header line") {
    expect_poly_error("# vertices elsewhere\n0 2 0 0\n0 0\n0\n", 2, "bad.node");
    expect_poly_error("0 2 0 0\n0 0\n0\n", 1, "cannot be opened");
  }
  SUBCASE("errors in the .node file name the .node file and its line") {
    expect_poly_error("0 2 0 0\n0 0\n0\n", 4, "'oops'",
                      {{"bad.node", "3\n1 0 0\n2 1 0\n3 oops 1\n"}}, "bad.node");
  }
}

TEST_CASE("read_poly: comments, optional fields, regions") {
  TempDir dir;
  write_file(dir.file("p.poly"), "# square with a hole\n4 2 0 1 # header\n"
                                 "0 0 0 3\n1 1 0 0\n2 1 1 0\n3 0 1 0\n"
                                 "\n4 1\n0 0 1 7\n1 1 2 0\n2 2 3 -1 extra\n3 3 0 0\n"
                                 "1\n0 0.5 0.5\n"
                                 "3\n0 0.1 0.1 5 0.25\n1 0.2 0.2 6\n2 0.3 0.3 7 -1\n");
  const PolyFile poly = read_poly(dir.file("p.poly"));
  CHECK(poly.points.first_index == 0);
  CHECK(poly.points.markers == std::vector<int>{3, 0, 0, 0});
  REQUIRE(poly.segments.size() == 4);
  CHECK(poly.segment_markers);
  CHECK(poly.segments[0].marker == 7);
  CHECK(poly.segments[1].marker == 0);
  CHECK(poly.segments[2].marker == -1);
  CHECK(poly.segment_lines == std::vector<long>{9, 10, 11, 12});
  REQUIRE(poly.regions.size() == 3);
  CHECK(poly.regions[0].max_area == 0.25);
  CHECK(poly.regions[1].max_area == 6);
  CHECK(poly.regions[2].max_area == -1);

  SUBCASE("no region section; segment markers off") {
    write_file(dir.file("q.poly"), "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n3 0\n1 1 2 9\n2 2 3\n3 3 1\n0\n");
    const PolyFile q = read_poly(dir.file("q.poly"));
    CHECK_FALSE(q.segment_markers);
    CHECK(q.segments[0].marker == 0); // the flag says no markers: the 9 is ignored
    CHECK(q.holes.empty());
    CHECK(q.regions.empty());
  }
}

TEST_CASE("read_poly errors name the file and the line") {
  const std::string tri = "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n"; // lines 1-4
  SUBCASE("missing file") {
    TempDir dir;
    CHECK_THROWS_WITH_AS(read_poly(dir.file("absent.poly")), doctest::Contains("absent.poly"),
                         InputError);
  }
  // Vertex section (shared with read_node).
  expect_poly_error("", 1, "missing header");
  expect_poly_error("abc 2 0 0\n", 1, "malformed header");
  expect_poly_error("3 2 0 0\n1 0 0\n2 x 0\n", 3, "'x'");
  // Segments.
  expect_poly_error(tri, 5, "before the segment section");
  expect_poly_error(tri + "x 1\n", 5, "malformed header");
  expect_poly_error(tri + "-2 0\n", 5, "malformed header");
  expect_poly_error(tri + "1 2\n", 5, "must be 0 or 1");
  expect_poly_error(tri + "2 0\n1 1 2\n", 7, "after 1 of 2 segments");
  expect_poly_error(tri + "1 0\n\n1\n", 7, "no endpoints");
  expect_poly_error(tri + "1 0\n1 2\n", 6, "only one endpoint");
  expect_poly_error(tri + "1 0\n1 2 b\n", 6, "'b'");
  expect_poly_error(tri + "1 0\n1 2 3.5\n", 6, "not an integer");
  expect_poly_error(tri + "1 0\nx 2 3\n", 6, "segment id 'x'");
  expect_poly_error(tri + "2 0\n1 1 2\n2 3 4\n", 7, "endpoint 4 of segment 2 is out of range");
  expect_poly_error(tri + "1 0\n7 0 2\n", 6, "endpoint 0 of segment 7 is out of range");
  expect_poly_error(tri + "1 0\n1 1 5\n", 6, "numbered 1 to 3");
  expect_poly_error(tri + "1 1\n1 1 2 m\n", 6, "boundary marker 'm'");
  // A marker that the header announces is required, as in a .node file.
  expect_poly_error(tri + "2 1\n1 1 2 5\n2 2 3\n", 7,
                    "segment 2 has no boundary marker (the section header announces one");
  expect_poly_error(tri + "2 1\n1 1 2\n2 2 3 4\n", 6, "segment 1 has no boundary marker");
  // Holes.
  const std::string segs = tri + "1 1\n1 1 2 0\n"; // lines 5-6
  expect_poly_error(segs, 7, "before the hole section");
  expect_poly_error(segs + "one\n", 7, "malformed header");
  expect_poly_error(segs + "2\n1 0.5 0.5\n", 9, "after 1 of 2 holes");
  expect_poly_error(segs + "1\n1\n", 8, "hole 1 has no coordinates");
  expect_poly_error(segs + "1\n1 0.5\n", 8, "hole 1 has no y coordinate");
  expect_poly_error(segs + "1\n1 0.5 y\n", 8, "'y'");
  expect_poly_error(segs + "1\n1 nan 0.5\n", 8, "not finite");
  // Regions.
  const std::string holes = segs + "0\n"; // line 7
  expect_poly_error(holes + "r\n", 8, "malformed header");
  expect_poly_error(holes + "2\n1 0.2 0.2 1 1\n", 10, "after 1 of 2 regions");
  expect_poly_error(holes + "1\n1 0.2 0.2\n", 9, "expected at least 3");
  expect_poly_error(holes + "1\n1 0.2 0.2 a\n", 9, "attribute 'a' of region 1");
  expect_poly_error(holes + "1\n1 0.2 0.2 1 big\n", 9, "maximum area 'big'");
  // The .node beside a .poly: the same rules as any .node file.
  const std::map<std::string, std::string> no_marker = {
      {"bad.node", "3 2 0 1\n1 0 0 1\n2 1 0\n3 0 1 1\n"}};
  expect_poly_error("0 2 0 0\n1 0\n1 1 2\n0\n", 3, "expected 4", no_marker, "bad.node");
  CHECK_NOTHROW(read_text(tri)); // (the same vertices are a valid .node)
}

// ---------------------------------------------------------------------------
// Meshes to refine (-r): .ele and .area files
// ---------------------------------------------------------------------------

TEST_CASE("read_ele reads Triangle's meshes: corners, six nodes, attributes, numbering") {
  const fs::path inputs = kExamples / "inputs";
  SUBCASE("the examples bbox.1 and ell, against their own text") {
    for (const std::string name : {"bbox.1", "ell"}) {
      CAPTURE(name);
      const PointSet points = read_node((inputs / (name + ".node")).string());
      const std::string path = (inputs / (name + ".ele")).string();
      const EleFile ele = read_ele(path, static_cast<long>(points.points.size()), 1);
      // Independent: the minimal reader of these tests.
      CHECK(ele.triangles == read_ele(path, 1));
      CHECK(ele.first_index == 1);
      CHECK(ele.attribute_count == 0);
      CHECK(ele.attributes.empty());
      REQUIRE(ele.lines.size() == ele.triangles.size());
      CHECK(ele.lines.front() == 2);
    }
  }
  SUBCASE("comments, blank lines, 0-based, attributes, six nodes") {
    TempDir dir;
    write_file(dir.file("m.ele"), "# a mesh\n2 6 2\n\n0 0 1 2 3 4 5 1.5 -2 # first\n"
                                  "1 2 1 3 6 7 8 0 1e3\n");
    const EleFile ele = read_ele(dir.file("m.ele"), 9, 0);
    CHECK(ele.triangles == std::vector<Triangle>{{0, 1, 2}, {2, 1, 3}});
    CHECK(ele.first_index == 0);
    CHECK(ele.attribute_count == 2);
    CHECK(ele.attributes == std::vector<double>{1.5, -2, 0, 1000});
    CHECK(ele.lines == std::vector<long>{4, 5});
  }
  SUBCASE("a header of one count: three nodes, no attributes") {
    TempDir dir;
    write_file(dir.file("m.ele"), "1\n1 3 2 1\n");
    const EleFile ele = read_ele(dir.file("m.ele"), 3, 1);
    CHECK(ele.triangles == std::vector<Triangle>{{2, 1, 0}});
  }
}

TEST_CASE("read_ele and read_area errors name the file and the line") {
  TempDir dir;
  const std::string ele = dir.file("m.ele");
  auto ele_error = [&](const std::string &text, long line, const std::string &words) {
    CAPTURE(text);
    write_file(ele, text);
    expect_file_error([&] { read_ele(ele, 4, 1); }, ele, line, words);
  };
  expect_file_error([&] { read_ele(dir.file("absent.ele"), 4, 1); }, dir.file("absent.ele"), 0,
                    "cannot open");
  ele_error("", 1, "before the header");
  ele_error("two 3 0\n", 1, "malformed header");
  ele_error("1 2 0\n", 1, "at least 3 nodes");
  ele_error("1 3 x\n", 1, "attribute count");
  ele_error("2 3 0\n1 1 2 3\n", 3, "after 1 of 2 triangles");
  ele_error("1 3 0\n1 1 2\n", 2, "expected 4 (id, 3 nodes)");
  ele_error("1 3 1\n1 1 2 3\n", 2, "expected 5 (id, 3 nodes, 1 attribute(s))");
  ele_error("1 6 0\n1 1 2 3 4\n", 2, "expected 7");
  ele_error("1 3 0\n1 1 2 c\n", 2, "corner 'c' of triangle 1 is not an integer");
  ele_error("1 3 0\n1 1 2 5\n", 2,
            "corner 5 of triangle 1 is not a vertex (vertices are "
            "numbered 1 to 4)");
  ele_error("1 3 0\n1 0 2 3\n", 2, "corner 0 of triangle 1 is not a vertex");
  ele_error("2 3 0\n1 1 2 3\n3 2 3 4\n", 3, "triangle id 3 out of sequence (expected 2)");
  ele_error("1 3 0\n2 1 2 3\n", 2, "first triangle id must be 0 or 1");
  ele_error("1 3 1\n1 1 2 3 nan\n", 2, "attribute 'nan' of triangle 1 is not finite");
  ele_error("1 3 1\n1 1 2 3 big\n", 2, "attribute 'big' of triangle 1 is not a number");

  const std::string area = dir.file("m.area");
  auto area_error = [&](const std::string &text, long line, const std::string &words) {
    CAPTURE(text);
    write_file(area, text);
    expect_file_error([&] { read_area(area, 2); }, area, line, words);
  };
  expect_file_error([&] { read_area(dir.file("absent.area"), 2); }, dir.file("absent.area"), 0,
                    "cannot open");
  area_error("", 1, "before the header");
  area_error("3\n1 1\n2 1\n3 1\n", 1, "the header announces 3 triangles, the .ele file has 2");
  area_error("x\n", 1, "malformed header");
  area_error("2\n1 0.5\n", 3, "after 1 of 2 triangles");
  area_error("2\n1 0.5\n2\n", 3, "triangle 2 has no maximum area");
  area_error("2\n1 0.5\n2 small\n", 3, "maximum area 'small' of triangle 2 is not a number");
  area_error("2\n1 0.5\n4 1\n", 3, "out of sequence");
  write_file(area, "# areas\n2\n0 -1\n1 0.25 # second\n");
  CHECK(read_area(area, 2) == std::vector<double>{-1, 0.25});
}

TEST_CASE("read_mesh reads -r's files as Triangle does") {
  TempDir dir;
  const std::string square = "4 2 0 1\n1 0 0 1\n2 1 0 2\n3 1 1 0\n4 0 1 0\n";
  write_file(dir.file("sq.1.node"), square);
  write_file(dir.file("sq.1.ele"), "2 3 1\n1 1 2 3 7\n2 1 3 4 8\n");
  write_file(dir.file("sq.1.area"), "2\n1 0.1\n2 -1\n");
  const std::string base = dir.file("sq.1");
  SUBCASE(".node and .ele") {
    std::vector<std::string> opened;
    const Input input = read_mesh(base, false, false, &opened);
    CHECK(opened == std::vector<std::string>{base + ".node", base + ".ele"});
    CHECK(input.points.size() == 4);
    CHECK(input.point_markers == std::vector<int>{1, 2, 0, 0});
    CHECK(input.first_index == 1);
    CHECK(input.triangles == std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}});
    CHECK(input.triangle_attribute_count == 1);
    CHECK(input.triangle_attributes == std::vector<double>{7, 8});
    CHECK(input.triangle_max_area.empty());
    CHECK(input.source == base + ".node");
    CHECK(input.triangles_source == base + ".ele");
    CHECK(input.triangle_lines == std::vector<long>{2, 3});
    CHECK(input.segments.empty());
    CHECK_NOTHROW(validate(input));
  }
  SUBCASE("with the .area file") {
    std::vector<std::string> opened;
    const Input input = read_mesh(base, false, true, &opened);
    CHECK(opened.back() == base + ".area");
    CHECK(input.triangle_max_area == std::vector<double>{0.1, -1});
  }
  SUBCASE("-p: segments and holes of the .poly, vertices from the .node beside it") {
    write_file(dir.file("sq.1.poly"), "0 2 0 1\n1 1\n1 1 3 5\n1\n1 5 5\n1\n1 0.5 0.5 3 0.1\n");
    std::vector<std::string> opened;
    const Input input = read_mesh(base, true, false, &opened);
    CHECK(opened == std::vector<std::string>{base + ".poly", base + ".node", base + ".ele"});
    REQUIRE(input.segments.size() == 1);
    CHECK(input.segments[0].a == 0);
    CHECK(input.segments[0].b == 2);
    CHECK(input.segments[0].marker == 5);
    CHECK(input.holes.size() == 1);
    CHECK(input.regions.empty()); // Triangle reads no regions with -r
    CHECK(input.points.size() == 4);
    CHECK(input.source == base + ".poly");
  }
  SUBCASE("-p: a .poly that lists vertices: those, not the .node's") {
    write_file(dir.file("sq.1.poly"), "4 2 0 0\n1 0 0\n2 2 0\n3 2 2\n4 0 2\n0 0\n0\n");
    write_file(dir.file("sq.1.node"), "not a node file\n");
    std::vector<std::string> opened;
    const Input input = read_mesh(base, true, false, &opened);
    CHECK(opened == std::vector<std::string>{base + ".poly", base + ".ele"});
    CHECK(input.points[2].x == 2);
  }
  SUBCASE("errors name the file") {
    expect_file_error([&] { read_mesh(dir.file("none"), false, false); }, dir.file("none.node"), 0,
                      "cannot open");
    write_file(dir.file("nomesh.node"), square);
    expect_file_error([&] { read_mesh(dir.file("nomesh"), false, false); }, dir.file("nomesh.ele"),
                      0, "cannot open");
    expect_file_error([&] { read_mesh(dir.file("sq.1"), true, false); }, dir.file("sq.1.poly"), 0,
                      "cannot open");
    std::remove(dir.file("sq.1.area").c_str());
    expect_file_error([&] { read_mesh(base, false, true); }, base + ".area", 0, "cannot open");
    // validate() names the .ele's line: a clockwise triangle on line 3.
    write_file(dir.file("sq.1.ele"), "2 3 0\n1 1 2 3\n2 1 4 3\n");
    const Input clockwise = read_mesh(base, false, false);
    expect_file_error([&] { validate(clockwise); }, base + ".ele", 3,
                      "triangle 2: its corners "
                      "are in clockwise order");
  }
}

// ---------------------------------------------------------------------------
// Writers
// ---------------------------------------------------------------------------

TEST_CASE("writers reproduce Triangle's reference output byte for byte") {
  struct Case {
    const char *input, *reference, *command;
  };
  for (const Case &c :
       {Case{"spiral.node", "spiral.1", "triangle spiral"},
        Case{"diamond_02_00009.node", "diamond_02_00009.1", "triangle -v diamond_02_00009.node"}}) {
    CAPTURE(c.input);
    const PointSet input = read_node((kExamples / "inputs" / c.input).string());
    const std::string reference = (kExamples / "reference-outputs" / c.reference).string();
    const std::vector<Triangle> triangles = read_ele(reference + ".ele", 1);
    const auto neighbors = neighbors_of(triangles);
    MeshView mesh;
    mesh.set_points(input);
    mesh.triangles = &triangles;
    mesh.neighbors = &neighbors;
    WriteOptions options;
    options.first_index = input.first_index;
    options.command_line = c.command;
    TempDir dir;
    OutputBatch batch;
    batch.write_node(dir.file("out.node"), mesh, options);
    batch.write_ele(dir.file("out.ele"), mesh, options);
    batch.commit();
    CHECK(read_file(dir.file("out.node")) == read_file(reference + ".node"));
    CHECK(read_file(dir.file("out.ele")) == read_file(reference + ".ele"));
  }
}

TEST_CASE("write_node then read_node gives the same points") {
  std::mt19937_64 random(12345);
  std::uniform_real_distribution<double> coordinate(-1e6, 1e6);
  PointSet set;
  set.attribute_count = 2;
  set.has_markers = true;
  for (int i = 0; i < 500; ++i) {
    set.points.push_back(Point{coordinate(random), coordinate(random) * 1e-9});
    set.attributes.push_back(coordinate(random));
    set.attributes.push_back(i * 0.1);
    set.markers.push_back(i % 7 - 3);
  }
  set.points.push_back(Point{0.1, -0.0});
  // The extremes read_node accepts (what the exact predicates carry), with 17 digits.
  set.points.push_back(Point{1.0000000000000001e-50 * 3.141592653589793, -9.999999999999999e49});
  for (int i = 0; i < 2; ++i) {
    set.attributes.insert(set.attributes.end(), {1.0 / 3, -2.5});
    set.markers.push_back(0);
  }
  for (int first : {0, 1}) {
    CAPTURE(first);
    MeshView mesh;
    mesh.set_points(set);
    WriteOptions options;
    options.first_index = first;
    TempDir dir;
    OutputBatch batch;
    batch.write_node(dir.file("p.node"), mesh, options);
    batch.commit();
    const PointSet back = read_node(dir.file("p.node"));
    CHECK(back.first_index == first);
    REQUIRE(back.points.size() == set.points.size());
    for (std::size_t i = 0; i < set.points.size(); ++i) {
      CHECK(back.points[i].x == set.points[i].x);
      CHECK(back.points[i].y == set.points[i].y);
    }
    CHECK(back.attribute_count == 2);
    CHECK(back.attributes == set.attributes);
    CHECK(back.has_markers);
    CHECK(back.markers == set.markers);
    CHECK(read_file(dir.file("p.node")).find("# Generated by") == std::string::npos);
  }
}

TEST_CASE("writers: formats, hull markers, numbering") {
  // Unit square split along 0-2, plus an interior-free layout.
  PointSet set;
  set.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}};
  const std::vector<std::array<int32_t, 3>> neighbors = {{-1, 1, -1}, {-1, -1, 0}};
  CHECK(neighbors == neighbors_of(triangles));
  MeshView mesh;
  mesh.set_points(set);
  mesh.triangles = &triangles;
  mesh.neighbors = &neighbors;

  SUBCASE("mesh_edges: each edge once, by triangle then edge, marker 1 on the hull") {
    const std::vector<Edge> edges = mesh_edges(triangles, neighbors);
    REQUIRE(edges.size() == 5);
    const std::vector<std::array<int, 3>> expected = {
        {1, 2, 1}, {2, 0, 0}, {0, 1, 1}, {2, 3, 1}, {3, 0, 1}};
    for (std::size_t e = 0; e < edges.size(); ++e) {
      CHECK(edges[e].a == expected[e][0]);
      CHECK(edges[e].b == expected[e][1]);
      CHECK(edges[e].marker == expected[e][2]);
    }
    CHECK_THROWS_AS(mesh_edges(triangles, {}), Error);
  }

  for (int first : {0, 1}) {
    CAPTURE(first);
    WriteOptions options;
    options.first_index = first;
    options.command_line = "clmesh -en square";
    TempDir dir;
    OutputBatch batch;
    batch.write_node(dir.file("s.node"), mesh, options);
    batch.write_ele(dir.file("s.ele"), mesh, options);
    batch.write_edge(dir.file("s.edge"), mesh, options);
    batch.write_neigh(dir.file("s.neigh"), mesh, options);
    batch.commit();
    const std::string f = std::to_string(first), g = std::to_string(first + 1);
    auto id = [&](int k) { return std::to_string(k + first); };
    const auto node = lines_of(read_file(dir.file("s.node")));
    REQUIRE(node.size() == 6);
    CHECK(node[0] == "4  2  0  1");
    CHECK(node[1] == "   " + id(0) + "    0  0    1"); // hull vertex: marker 1
    CHECK(node[3] == "   " + id(2) + "    1  1    1");
    CHECK(node[5] == "# Generated by clmesh -en square");
    const auto ele = lines_of(read_file(dir.file("s.ele")));
    REQUIRE(ele.size() == 4);
    CHECK(ele[0] == "2  3  0");
    CHECK(ele[1] == "   " + id(0) + "       " + id(0) + "     " + id(1) + "     " + id(2));
    CHECK(ele[3] == "# Generated by clmesh -en square");
    const auto edge = lines_of(read_file(dir.file("s.edge")));
    REQUIRE(edge.size() == 7);
    CHECK(edge[0] == "5  1");
    CHECK(edge[1] == "   " + id(0) + "   " + id(1) + "  " + id(2) + "  1");
    CHECK(edge[2] == "   " + id(1) + "   " + id(2) + "  " + id(0) + "  0");
    const auto neigh = lines_of(read_file(dir.file("s.neigh")));
    REQUIRE(neigh.size() == 4);
    CHECK(neigh[0] == "2  3");
    CHECK(neigh[1] == "   " + id(0) + "    -1  " + id(1) + "  -1");
    CHECK(neigh[2] == "   " + id(1) + "    -1  -1  " + id(0));
  }

  SUBCASE("input markers are kept; only zero markers on the hull become 1") {
    PointSet marked = set;
    marked.points.push_back({0.5, 0.25});
    marked.has_markers = true;
    marked.markers = {0, 7, 0, -2, 0};
    const std::vector<Triangle> fan = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    const auto fan_neighbors = neighbors_of(fan);
    MeshView view;
    view.set_points(marked);
    view.triangles = &fan;
    view.neighbors = &fan_neighbors;
    TempDir dir;
    OutputBatch batch;
    batch.write_node(dir.file("m.node"), view, WriteOptions{});
    batch.commit();
    const PointSet back = read_node(dir.file("m.node"));
    CHECK(back.markers == std::vector<int>{1, 7, 1, -2, 0});
  }
}

// The '# Generated by' command of a Triangle output file.
std::string generated_by(const std::string &path) {
  const std::string text = read_file(path);
  const std::string mark = "# Generated by ";
  const std::size_t at = text.rfind(mark);
  REQUIRE(at != std::string::npos);
  std::string command = text.substr(at + mark.size());
  while (!command.empty() && (command.back() == '\n' || command.back() == '\r'))
    command.pop_back();
  return command;
}

TEST_CASE("-p writers reproduce Triangle's reference output byte for byte") {
  const fs::path inputs = kExamples / "inputs", references = kExamples / "reference-outputs";
  SUBCASE("from the input .poly, the segments and triangles of Triangle's mesh") {
    // The segments in Triangle's order, with the input markers: the writers
    // give them and the vertices Triangle's -p markers.
    for (const char *name : {"A", "box", "face", "double_hex"}) {
      CAPTURE(name);
      const PolyFile input = read_poly((inputs / (std::string(name) + ".poly")).string());
      const std::string reference = (references / (std::string(name) + ".1")).string();
      const PolyFile output = read_poly(reference + ".poly");
      std::map<std::pair<int32_t, int32_t>, int> input_marker;
      for (const Segment &segment : input.segments)
        input_marker.emplace(ends_of(segment), segment.marker);
      std::vector<Segment> segments = output.segments;
      for (Segment &segment : segments) {
        auto found = input_marker.find(ends_of(segment));
        segment.marker = found != input_marker.end() ? found->second : 1; // -c: hull edge, 1
      }
      const std::vector<Triangle> triangles = read_ele(reference + ".ele", 1);
      const auto neighbors = neighbors_of(triangles);
      MeshView mesh;
      mesh.set_points(input.points);
      mesh.triangles = &triangles;
      mesh.neighbors = &neighbors;
      mesh.segments = &segments;
      WriteOptions options;
      options.first_index = input.points.first_index;
      options.command_line = generated_by(reference + ".node");
      TempDir dir;
      OutputBatch batch;
      batch.write_node(dir.file("out.node"), mesh, options);
      batch.write_ele(dir.file("out.ele"), mesh, options);
      batch.write_poly(dir.file("out.poly"), mesh, input.holes, input.regions, options);
      batch.commit();
      CHECK(read_file(dir.file("out.node")) == read_file(reference + ".node"));
      CHECK(read_file(dir.file("out.ele")) == read_file(reference + ".ele"));
      CHECK(read_file(dir.file("out.poly")) == read_file(reference + ".poly"));
    }
  }
  SUBCASE("rewriting Triangle's outputs gives them back (regions included)") {
    for (const char *name : {"A", "box", "face", "double_hex", "la"}) {
      CAPTURE(name);
      const std::string reference = (references / (std::string(name) + ".1")).string();
      const PolyFile output = read_poly(reference + ".poly");
      const std::vector<Triangle> triangles = read_ele(reference + ".ele", 1);
      const auto neighbors = neighbors_of(triangles);
      MeshView mesh;
      mesh.set_points(output.points);
      mesh.triangles = &triangles;
      mesh.neighbors = &neighbors;
      mesh.segments = &output.segments;
      WriteOptions options;
      options.command_line = generated_by(reference + ".poly");
      TempDir dir;
      OutputBatch batch;
      batch.write_node(dir.file("out.node"), mesh, options);
      batch.write_poly(dir.file("out.poly"), mesh, output.holes, output.regions, options);
      batch.commit();
      CHECK(read_file(dir.file("out.node")) == read_file(reference + ".node"));
      CHECK(read_file(dir.file("out.poly")) == read_file(reference + ".poly"));
    }
  }
}

TEST_CASE("-p writers: markers, -B, -A, -j, eaten segments") {
  // A square 0-1-2-3 with a centre vertex 4 and a vertex 5 in an eaten corner
  // region outside the mesh; triangles fan around 4.
  PointSet set;
  set.points = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 1}, {3, 3}};
  set.has_markers = true;
  set.markers = {0, 0, 0, 9, 0, 0};
  const std::vector<Triangle> triangles = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  const auto neighbors = neighbors_of(triangles);
  // Segments: bottom (marker 0: on the boundary, becomes 1), right (5), top
  // (0, becomes 1), left (0), an interior one 0-4 with marker 0 and one 2-4
  // with marker 6, and one 2-5 that is no edge of the mesh (eaten).
  const std::vector<Segment> segments = {{0, 1, 0}, {1, 2, 5}, {2, 3, 0}, {3, 0, 0},
                                         {0, 4, 0}, {4, 2, 6}, {2, 5, 4}};
  const std::vector<double> attributes = {1.5, 2, -3, 0.1};
  MeshView mesh;
  mesh.set_points(set);
  mesh.triangles = &triangles;
  mesh.neighbors = &neighbors;
  mesh.segments = &segments;

  // Vertex 1: first non-zero segment marker (5); 2: 5 (segment 1-2 comes
  // first); 3: its own 9; 0: boundary, 1; 4: interior, from segment 4-2: 6;
  // 5: from the eaten segment 2-5, as Triangle marks before carving.
  CHECK(output_vertex_markers(mesh) == std::vector<int>{1, 5, 5, 9, 6, 4});

  const std::vector<Edge> edges = mesh_edges(triangles, neighbors, segments);
  REQUIRE(edges.size() == 8);
  std::map<std::pair<int32_t, int32_t>, int> marker;
  for (const Edge &edge : edges)
    marker[{std::min(edge.a, edge.b), std::max(edge.a, edge.b)}] = edge.marker;
  CHECK(marker[{0, 1}] == 1); // segment with marker 0 on the boundary
  CHECK(marker[{1, 2}] == 5);
  CHECK(marker[{2, 3}] == 1);
  CHECK(marker[{0, 3}] == 1);
  CHECK(marker[{0, 4}] == 0); // interior segment with marker 0
  CHECK(marker[{2, 4}] == 6);
  CHECK(marker[{1, 4}] == 0); // interior, no segment
  CHECK(marker[{3, 4}] == 0);
  {
    // Without segments in the list, boundary edges get 1.
    const std::vector<Edge> plain = mesh_edges(triangles, neighbors, {});
    for (std::size_t e = 0; e < plain.size(); ++e)
      CHECK(plain[e].marker == mesh_edges(triangles, neighbors)[e].marker);
  }

  SUBCASE("the .poly leaves out segments that are no edge of the mesh") {
    TempDir dir;
    OutputBatch batch;
    WriteOptions options;
    options.command_line = "clmesh -p square";
    batch.write_poly(dir.file("s.poly"), mesh, {{2.5, 2.5}}, {{{1, 0.5}, 4, -1}}, options);
    batch.commit();
    const auto lines = lines_of(read_file(dir.file("s.poly")));
    REQUIRE(lines.size() == 13);
    CHECK(lines[0] == "0  2  0  1");
    CHECK(lines[1] == "6  1");
    CHECK(lines[2] == "   1       1     2       1");
    CHECK(lines[3] == "   2       2     3       5");
    CHECK(lines[6] == "   5       1     5       0");
    CHECK(lines[7] == "   6       5     3       6");
    CHECK(lines[8] == "1");
    CHECK(lines[9] == "   1   2.5  2.5");
    CHECK(lines[10] == "1");
    CHECK(lines[11] == "   1   1  0.5  4  -1");
    CHECK(lines[12] == "# Generated by clmesh -p square");
  }
  SUBCASE("-B: no marker column anywhere") {
    TempDir dir;
    OutputBatch batch;
    WriteOptions options;
    options.boundary_markers = false;
    options.first_index = 0;
    batch.write_node(dir.file("b.node"), mesh, options);
    batch.write_edge(dir.file("b.edge"), mesh, options);
    batch.write_poly(dir.file("b.poly"), mesh, {}, {}, options);
    batch.commit();
    const auto node = lines_of(read_file(dir.file("b.node")));
    CHECK(node[0] == "6  2  0  0");
    CHECK(node[1] == "   0    0  0");
    const PointSet back = read_node(dir.file("b.node"));
    CHECK_FALSE(back.has_markers);
    const auto edge = lines_of(read_file(dir.file("b.edge")));
    CHECK(edge[0] == "8  0");
    CHECK(edge[1] == "   0   1  4");
    const auto poly = lines_of(read_file(dir.file("b.poly")));
    CHECK(poly[0] == "0  2  0  0");
    CHECK(poly[1] == "6  0");
    CHECK(poly[2] == "   0       0     1");
    CHECK(poly[8] == "0");
    CHECK(poly.size() == 9);
  }
  SUBCASE("-A: an attribute column in .ele") {
    MeshView with = mesh;
    with.triangle_attribute_count = 1;
    with.triangle_attributes = &attributes;
    TempDir dir;
    OutputBatch batch;
    batch.write_ele(dir.file("a.ele"), with, WriteOptions{});
    const std::vector<double> short_list = {1};
    MeshView wrong = mesh;
    wrong.triangle_attribute_count = 1;
    wrong.triangle_attributes = &short_list;
    CHECK_THROWS_AS(batch.write_ele(dir.file("w.ele"), wrong, WriteOptions{}), InternalError);
    batch.commit();
    const auto ele = lines_of(read_file(dir.file("a.ele")));
    REQUIRE(ele.size() == 5);
    CHECK(ele[0] == "4  3  1");
    CHECK(ele[1] == "   1       1     2     5  1.5");
    CHECK(ele[3] == "   3       3     4     5  -3");
    CHECK(ele[4] == "   4       4     1     5  0.10000000000000001");
  }
  SUBCASE("-r: several attribute columns in .ele and .vtu") {
    const std::vector<double> columns = {1, -1, 2, -2, 3, -3, 4, -4};
    MeshView with = mesh;
    with.triangle_attribute_count = 2;
    with.triangle_attributes = &columns;
    TempDir dir;
    OutputBatch batch;
    batch.write_ele(dir.file("r.ele"), with, WriteOptions{});
    batch.write_vtu(dir.file("r.vtu"), with, WriteOptions{});
    MeshView wrong = with;
    wrong.triangle_attribute_count = 3;
    CHECK_THROWS_AS(batch.write_ele(dir.file("w.ele"), wrong, WriteOptions{}), InternalError);
    batch.commit();
    const auto ele = lines_of(read_file(dir.file("r.ele")));
    REQUIRE(ele.size() == 5);
    CHECK(ele[0] == "4  3  2");
    CHECK(ele[2] == "   2       2     3     5  2  -2");
    // Read back: the attributes by column, row-major.
    const EleFile back = read_ele(dir.file("r.ele"), 6, 1);
    CHECK(back.attributes == columns);
    const std::string vtu = read_file(dir.file("r.vtu"));
    CHECK(vtu.find("Name=\"attribute2\"") != std::string::npos);
    CHECK(vtu.find("Name=\"attribute3\"") == std::string::npos);
  }
  SUBCASE("-j also drops the vertices in no triangle") {
    WriteOptions jettison;
    jettison.jettison_duplicates = true;
    CHECK(output_vertex_numbers(mesh, jettison) == std::vector<int32_t>{0, 1, 2, 3, 4, -1});
    MeshView without = mesh;
    without.segments = nullptr; // without -p, only duplicates go
    CHECK(output_vertex_numbers(without, jettison) == std::vector<int32_t>{0, 1, 2, 3, 4, 5});
    TempDir dir;
    OutputBatch batch;
    batch.write_node(dir.file("j.node"), mesh, jettison);
    batch.write_poly(dir.file("j.poly"), mesh, {}, {}, jettison);
    batch.commit();
    CHECK(read_node(dir.file("j.node")).points.size() == 5);
    CHECK(read_poly(dir.file("j.poly")).segments.size() == 6);
  }
  SUBCASE("write_poly needs the segments") {
    MeshView without = mesh;
    without.segments = nullptr;
    OutputBatch batch;
    TempDir dir;
    CHECK_THROWS_AS(batch.write_poly(dir.file("x.poly"), without, {}, {}, WriteOptions{}),
                    InternalError);
  }
}

TEST_CASE("write_poly and write_node, then read_poly, give the same PSLG") {
  const PolyFile input = read_poly((kExamples / "inputs" / "double_hex2.poly").string()); // 2 holes
  // A fan of triangles through every segment is not needed: give each segment
  // a triangle of its own so that it is an edge of the "mesh".
  std::vector<Triangle> triangles;
  PointSet points = input.points;
  for (const Segment &segment : input.segments) {
    points.points.push_back({0, 0});
    points.markers.push_back(0);
    triangles.push_back({segment.a, segment.b, static_cast<int32_t>(points.points.size() - 1)});
  }
  const auto neighbors = neighbors_of(triangles);
  const std::vector<Region> regions = {{{0.5, 0.5}, 2.5, 0.01}, {{0.9, 0.1}, -1, -1}};
  MeshView mesh;
  mesh.set_points(points);
  mesh.triangles = &triangles;
  mesh.neighbors = &neighbors;
  mesh.segments = &input.segments;
  for (int first : {0, 1}) {
    CAPTURE(first);
    WriteOptions options;
    options.first_index = first;
    TempDir dir;
    OutputBatch batch;
    batch.write_node(dir.file("rt.node"), mesh, options);
    batch.write_poly(dir.file("rt.poly"), mesh, input.holes, regions, options);
    batch.commit();
    const PolyFile back = read_poly(dir.file("rt.poly"));
    CHECK(back.node_path == dir.file("rt.node"));
    CHECK(back.points.first_index == first);
    CHECK(back.points.points.size() == points.points.size());
    REQUIRE(back.segments.size() == input.segments.size());
    for (std::size_t i = 0; i < back.segments.size(); ++i) {
      CHECK(back.segments[i].a == input.segments[i].a);
      CHECK(back.segments[i].b == input.segments[i].b);
      CHECK(back.segments[i].marker == input.segments[i].marker); // all non-zero
    }
    REQUIRE(back.holes.size() == 2);
    CHECK(back.holes[1].x == input.holes[1].x);
    CHECK(back.holes[1].y == input.holes[1].y);
    REQUIRE(back.regions.size() == 2);
    CHECK(back.regions[0].seed.x == 0.5);
    CHECK(back.regions[0].attribute == 2.5);
    CHECK(back.regions[0].max_area == 0.01);
    CHECK(back.regions[1].max_area == -1);
  }
}

TEST_CASE("-j drops duplicate vertices and renumbers the rest") {
  PointSet set;
  set.points = {{0, 0}, {1, 0}, {0, 0}, {1, 1}, {1, 0}, {0, 1}};
  set.has_markers = true;
  set.markers = {0, 0, 4, 0, 0, 0};
  const std::vector<int32_t> duplicate_of = {-1, -1, 0, -1, 1, -1};
  const std::vector<Triangle> triangles = {{0, 1, 3}, {0, 3, 5}};
  const auto neighbors = neighbors_of(triangles);
  MeshView mesh;
  mesh.set_points(set);
  mesh.triangles = &triangles;
  mesh.neighbors = &neighbors;
  mesh.duplicate_of = &duplicate_of;

  WriteOptions keep;
  CHECK(output_vertex_numbers(mesh, keep) == std::vector<int32_t>{0, 1, 2, 3, 4, 5});
  WriteOptions jettison;
  jettison.jettison_duplicates = true;
  CHECK(output_vertex_numbers(mesh, jettison) == std::vector<int32_t>{0, 1, -1, 2, -1, 3});
  MeshView no_duplicates = mesh;
  no_duplicates.duplicate_of = nullptr;
  CHECK(output_vertex_numbers(no_duplicates, jettison) == std::vector<int32_t>{0, 1, 2, 3, 4, 5});

  for (int first : {0, 1}) {
    CAPTURE(first);
    jettison.first_index = first;
    TempDir dir;
    OutputBatch batch;
    batch.write_node(dir.file("j.node"), mesh, jettison);
    batch.write_ele(dir.file("j.ele"), mesh, jettison);
    batch.write_edge(dir.file("j.edge"), mesh, jettison);
    batch.commit();
    const PointSet back = read_node(dir.file("j.node"));
    REQUIRE(back.points.size() == 4);
    CHECK(back.first_index == first);
    CHECK(back.points[2].x == 1.0);
    CHECK(back.points[2].y == 1.0);
    CHECK(back.points[3].y == 1.0);
    const std::vector<Triangle> ele = read_ele(dir.file("j.ele"), first);
    CHECK(ele == std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}});
    const auto edge = lines_of(read_file(dir.file("j.edge")));
    CHECK(edge[0] == "5  1");
    for (std::size_t i = 1; i < 6; ++i) {
      std::istringstream fields(edge[i]);
      long id, a, b, marker;
      REQUIRE(static_cast<bool>(fields >> id >> a >> b >> marker));
      CHECK(a - first < 4);
      CHECK(b - first < 4);
    }
  }

  SUBCASE("without -j every vertex is written, duplicates keep their markers") {
    TempDir dir;
    OutputBatch batch;
    batch.write_node(dir.file("k.node"), mesh, keep);
    batch.commit();
    const PointSet back = read_node(dir.file("k.node"));
    CHECK(back.points.size() == 6);
    CHECK(back.markers == std::vector<int>{1, 1, 4, 1, 0, 1});
  }
}

// ---------------------------------------------------------------------------
// OutputBatch
// ---------------------------------------------------------------------------

// A mesh of one triangle, for the batch tests.
struct OneTriangle {
  PointSet set;
  const std::vector<Triangle> triangles = {{0, 1, 2}};
  const std::vector<std::array<int32_t, 3>> neighbors = {{-1, -1, -1}};
  MeshView mesh;
  OneTriangle() {
    set.points = {{0, 0}, {1, 0}, {0, 1}};
    mesh.set_points(set);
    mesh.triangles = &triangles;
    mesh.neighbors = &neighbors;
  }
};

TEST_CASE_FIXTURE(OneTriangle, "OutputBatch writes all files on commit, none without it") {
  SUBCASE("not committed: nothing is left") {
    TempDir dir;
    {
      OutputBatch batch;
      batch.write_node(dir.file("a.node"), mesh, WriteOptions{});
      batch.write_ele(dir.file("a.ele"), mesh, WriteOptions{});
      batch.write_text(dir.file("a.json"), "{}\n");
      CHECK_FALSE(fs::exists(dir.file("a.node")));
    }
    CHECK(dir.names().empty());
  }
  SUBCASE("committed: the files and no temporaries") {
    TempDir dir;
    {
      OutputBatch batch;
      batch.write_node(dir.file("a.node"), mesh, WriteOptions{});
      batch.write_edge(dir.file("a.edge"), mesh, WriteOptions{});
      batch.write_neigh(dir.file("a.neigh"), mesh, WriteOptions{});
      batch.write_text(dir.file("a.json"), "{}\n");
      batch.write_text(dir.file("a.json"), "{\"again\": 1}\n");
      batch.commit();
    }
    CHECK(dir.names() == std::vector<std::string>{"a.edge", "a.json", "a.neigh", "a.node"});
    CHECK(read_file(dir.file("a.json")) == "{\"again\": 1}\n");
    CHECK(read_node(dir.file("a.node")).points.size() == 3);
  }
  SUBCASE("committing replaces an existing file") {
    TempDir dir;
    write_file(dir.file("a.ele"), "old");
    OutputBatch batch;
    batch.write_ele(dir.file("a.ele"), mesh, WriteOptions{});
    CHECK(read_file(dir.file("a.ele")) == "old");
    batch.commit();
    CHECK(read_file(dir.file("a.ele")).rfind("1  3  0\n", 0) == 0);
  }
  SUBCASE("a failed write names the file and leaves nothing behind") {
    TempDir dir;
    const std::string bad = dir.file("no-such-dir/a.ele");
    {
      OutputBatch batch;
      batch.write_node(dir.file("a.node"), mesh, WriteOptions{});
      try {
        batch.write_ele(bad, mesh, WriteOptions{});
        FAIL("no error");
      } catch (const InputError &error) {
        CHECK(error.file() == bad);
        CHECK(std::string(error.what()).find(bad) == 0);
      }
    }
    CHECK(dir.names().empty());
  }
}

TEST_CASE_FIXTURE(OneTriangle, "OutputBatch commits all or nothing") {
  SUBCASE("an output name taken by a directory is refused before writing") {
    TempDir dir;
    fs::create_directory(dir.file("a.ele"));
    {
      OutputBatch batch;
      batch.write_node(dir.file("a.node"), mesh, WriteOptions{});
      const std::string words = dir.file("a.ele") + ": cannot write";
      CHECK_THROWS_WITH_AS(batch.write_ele(dir.file("a.ele"), mesh, WriteOptions{}),
                           doctest::Contains(words.c_str()), InputError);
    }
    CHECK(dir.names() == std::vector<std::string>{"a.ele"});
    CHECK(fs::is_directory(dir.file("a.ele")));
  }
  SUBCASE("a directory appearing before the commit: nothing is moved") {
    TempDir dir;
    write_file(dir.file("a.node"), "old node");
    {
      OutputBatch batch;
      batch.write_node(dir.file("a.node"), mesh, WriteOptions{});
      batch.write_ele(dir.file("a.ele"), mesh, WriteOptions{});
      batch.write_text(dir.file("a.json"), "{}\n");
      fs::create_directory(dir.file("a.json"));
      const std::string words = dir.file("a.json");
      CHECK_THROWS_WITH_AS(batch.commit(), doctest::Contains(words.c_str()), InputError);
    }
    CHECK(dir.names() == std::vector<std::string>{"a.json", "a.node"});
    CHECK(read_file(dir.file("a.node")) == "old node");
  }
  SUBCASE("a rename failing midway: placed files removed, replaced ones restored") {
    TempDir dir;
    write_file(dir.file("a.node"), "old node");
    write_file(dir.file("a.neigh"), "old neigh");
    {
      OutputBatch batch;
      batch.write_node(dir.file("a.node"), mesh, WriteOptions{});
      batch.write_ele(dir.file("a.ele"), mesh, WriteOptions{});
      batch.write_neigh(dir.file("a.neigh"), mesh, WriteOptions{});
      batch.write_edge(dir.file("a.edge"), mesh, WriteOptions{});
      // The .neigh's temporary vanishes: its rename fails after two others.
      for (const std::string &name : dir.names())
        if (name.rfind("a.neigh.tmp", 0) == 0)
          fs::remove(dir.file(name));
      const std::string words = dir.file("a.neigh");
      CHECK_THROWS_WITH_AS(batch.commit(), doctest::Contains(words.c_str()), InputError);
    }
    CHECK(dir.names() == std::vector<std::string>{"a.neigh", "a.node"});
    CHECK(read_file(dir.file("a.node")) == "old node");
    CHECK(read_file(dir.file("a.neigh")) == "old neigh");
  }
  SUBCASE("files with the temporary's or the backup's name are left alone") {
    TempDir dir;
    write_file(dir.file("a.node"), "old node");
    write_file(dir.file("a.node.tmp-clmesh"), "mine");
    write_file(dir.file("a.node.old-clmesh"), "mine too");
    {
      OutputBatch batch;
      batch.write_node(dir.file("a.node"), mesh, WriteOptions{});
      batch.commit();
    }
    CHECK(dir.names() ==
          std::vector<std::string>{"a.node", "a.node.old-clmesh", "a.node.tmp-clmesh"});
    CHECK(read_file(dir.file("a.node.tmp-clmesh")) == "mine");
    CHECK(read_file(dir.file("a.node.old-clmesh")) == "mine too");
    CHECK(read_node(dir.file("a.node")).points.size() == 3);
  }
}

// ---------------------------------------------------------------------------
// Pictures
// ---------------------------------------------------------------------------

TEST_CASE("mesh_svg draws the triangles and, when few, the points") {
  const std::vector<Point> points = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}};
  const std::string svg = mesh_svg(points, triangles);
  CHECK(svg.rfind("<?xml", 0) == 0);
  CHECK(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 ") != std::string::npos);
  CHECK(svg.find("</svg>") != std::string::npos);
  auto count = [](const std::string &text, const std::string &word) {
    std::size_t n = 0;
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
      ++n;
    return n;
  };
  CHECK(count(svg, "<path") == 1);
  CHECK(count(svg, "Z") == 2);
  CHECK(count(svg, "<circle") == 4);
  CHECK(svg.find("nan") == std::string::npos);

  std::vector<Point> many(6000);
  for (std::size_t i = 0; i < many.size(); ++i)
    many[i] = {double(i % 100), double(i / 100)};
  CHECK(count(mesh_svg(many, {}), "<circle") == 0);
  // Degenerate extents do not give a zero or invalid view box.
  const std::string flat = mesh_svg({{1, 1}, {1, 1}, {1, 1}}, {});
  CHECK(flat.find("viewBox=\"0 0 0 0\"") == std::string::npos);
  CHECK(mesh_svg({}, {}).find("</svg>") != std::string::npos);
}

TEST_CASE("mesh_svg draws the segments over the triangles") {
  const std::vector<Point> points = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}};
  const std::vector<Segment> segments = {{0, 1, 1}, {2, 0, 0}, {3, 9, 0}}; // the last is invalid
  const std::string svg = mesh_svg(points, triangles, &segments);
  const std::size_t mesh_path = svg.find("<path");
  const std::size_t segment_path = svg.find("<path", mesh_path + 1);
  REQUIRE(segment_path != std::string::npos);
  const std::string segment_part =
      svg.substr(segment_path, svg.find("/>", segment_path) - segment_path);
  CHECK(segment_part.find("stroke-width=\"2\"") != std::string::npos);
  CHECK(std::count(segment_part.begin(), segment_part.end(), 'M') == 2);
  CHECK(mesh_svg(points, triangles, nullptr) == mesh_svg(points, triangles));
  const std::vector<Segment> none;
  CHECK(mesh_svg(points, triangles, &none) == mesh_svg(points, triangles));
}

TEST_CASE("voronoi_pgm writes a binary grey map") {
  const int grid = 4;
  std::vector<int32_t> sites(grid * grid, 0);
  for (int i = 0; i < grid * grid; ++i)
    sites[i] = i % 3 - 1; // -1, 0, 1, ...
  const std::string pgm = voronoi_pgm(sites, grid);
  const std::string header = "P5\n4 4\n255\n";
  REQUIRE(pgm.size() == header.size() + 16);
  CHECK(pgm.compare(0, header.size(), header) == 0);
  // Row 0 of the grid is the bottom row of the picture.
  for (int y = 0; y < grid; ++y)
    for (int x = 0; x < grid; ++x) {
      const unsigned char grey = pgm[header.size() + (grid - 1 - y) * grid + x];
      const int32_t site = sites[y * grid + x];
      if (site < 0)
        CHECK(grey == 0);
      else
        CHECK(grey >= 40);
    }
  // Same site, same grey.
  CHECK(voronoi_pgm(std::vector<int32_t>(4, 7), 2).substr(11) ==
        std::string(4, voronoi_pgm({7}, 1).back()));
  CHECK_THROWS_AS(voronoi_pgm(sites, 3), Error);
}

TEST_CASE("DirectedEdges::reverses finds each edge's other side as triangle_of does") {
  // Random triangles over a few vertices: edges taken once, twice or more,
  // in one direction or both, some vertices with no edge at all. The last
  // set has edges enough for the work to run in two parts (host_threads).
  std::mt19937 random(7);
  for (const auto &[vertices, count] : {std::pair{3, 200}, {10, 200}, {60, 200}, {2000, 40000}}) {
    std::uniform_int_distribution<int32_t> corner(0, vertices - 1);
    std::vector<Triangle> triangles;
    while (triangles.size() < static_cast<std::size_t>(count)) {
      const Triangle t{corner(random), corner(random), corner(random)};
      if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
        triangles.push_back(t);
    }
    const DirectedEdges directed(triangles, static_cast<std::size_t>(vertices) + 5);
    const std::vector<DirectedEdges::Edge> &edges = directed.edges();
    const std::vector<int64_t> reverse = directed.reverses();
    REQUIRE(reverse.size() == edges.size());
    std::size_t paired = 0;
    for (std::size_t a = 0; a < directed.vertices(); ++a)
      for (std::size_t e = directed.first(a); e < directed.first(a + 1); ++e) {
        const int32_t b = edges[e].head;
        // In increasing b, then increasing triangle.
        if (e > directed.first(a)) {
          const DirectedEdges::Edge &before = edges[e - 1];
          CHECK((before.head < b || (before.head == b && before.triangle < edges[e].triangle)));
        }
        // The edge a -> b leaves its triangle's corner `corner`.
        const Triangle &own = triangles[edges[e].triangle];
        CHECK(own[edges[e].corner] == static_cast<int32_t>(a));
        CHECK(own[(edges[e].corner + 1) % 3] == b);
        const int64_t other = directed.triangle_of(b, static_cast<int32_t>(a));
        if (other < 0) {
          CHECK(reverse[e] == -1);
          continue;
        }
        ++paired;
        REQUIRE(reverse[e] >= 0);
        const auto r = static_cast<std::size_t>(reverse[e]);
        CHECK(r >= directed.first(static_cast<std::size_t>(b)));
        CHECK(r < directed.first(static_cast<std::size_t>(b) + 1));
        CHECK(edges[r].head == static_cast<int32_t>(a));
        CHECK(edges[r].triangle == static_cast<uint32_t>(other));
      }
    CHECK(paired > 0);
  }
}
