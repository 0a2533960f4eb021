// clmesh — Triangle's file formats, SVG and PGM pictures (see clmesh/io.hpp).
#include "clmesh/io.hpp"

#include "clmesh/errors.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string_view>
#include <unordered_map>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace clmesh {

// ---------------------------------------------------------------------------
// Reading
// ---------------------------------------------------------------------------
namespace {

std::string describe_errno(int error) { return error != 0 ? std::strerror(error) : "I/O error"; }

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Reads a file line by line through a buffer of a few MiB and splits each
// line into whitespace-separated fields; '#' starts a comment that runs to the
// end of the line; lines without fields are skipped. Nothing is read beyond
// what the caller asks for, so memory follows the data accepted and an
// endless or binary input (a FIFO, /dev/zero) stops at its first bad line: a
// NUL byte ends the reading with an error on its line as soon as it is read,
// and so does a line longer than the longest a section can hold.
class FieldReader {
public:
  explicit FieldReader(std::string path) : path_(std::move(path)) {
    descriptor_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    if (descriptor_ < 0) {
      int error = errno;
      throw InputError(path_, 0, "cannot open: " + describe_errno(error));
    }
    struct stat info;
    if (::fstat(descriptor_, &info) == 0 && S_ISREG(info.st_mode))
      file_size_ = static_cast<std::size_t>(info.st_size);
    buffer_.reset(new char[capacity_]);
  }
  FieldReader(const FieldReader &) = delete;
  FieldReader &operator=(const FieldReader &) = delete;
  ~FieldReader() { ::close(descriptor_); }

  // Next line holding at least one field; false at the end of the file.
  bool next(std::vector<std::string_view> &fields) {
    std::string_view text;
    while (next_line(text)) {
      fields.clear();
      std::size_t i = 0;
      while (i < text.size() && text[i] != '#') {
        if (is_space(text[i])) {
          ++i;
          continue;
        }
        std::size_t start = i;
        while (i < text.size() && !is_space(text[i]) && text[i] != '#')
          ++i;
        fields.push_back(text.substr(start, i - start));
      }
      if (!fields.empty())
        return true;
    }
    return false;
  }

  long line() const { return line_; }
  // Line on which the end of the file lies: the last line, or the empty line
  // after it when the file ends with a newline.
  long eof_line() const { return newlines_ + 1; }
  [[noreturn]] void fail(const std::string &problem) const {
    throw InputError(path_, line_, problem);
  }
  // Most bytes the file can hold: its size when it is a regular file, else 0
  // (unknown). Bounds what a header's count may reserve.
  std::size_t size_bound() const { return file_size_; }
  // Lets lines grow by 64 bytes for each of `fields` fields (a vertex line
  // with many attributes).
  void expect_fields(std::size_t fields) { longest_ = std::max(longest_, kLongest + 64 * fields); }

private:
  static constexpr std::size_t kChunk = std::size_t(4) << 20;   // bytes read at a time
  static constexpr std::size_t kLongest = std::size_t(1) << 20; // longest line by default

  // Next line, without its '\n'; false at the end of the file.
  bool next_line(std::string_view &text) {
    line_ = newlines_ + 1;
    for (;;) {
      // [begin_, scanned_) is known to hold neither '\n' nor NUL.
      const char *from = buffer_.get() + scanned_;
      const auto *newline = static_cast<const char *>(std::memchr(from, '\n', end_ - scanned_));
      const std::size_t stop = newline ? static_cast<std::size_t>(newline - buffer_.get()) : end_;
      if (std::memchr(from, '\0', stop - scanned_))
        fail("the line holds a NUL byte (not a text file?)");
      scanned_ = stop;
      if (scanned_ - begin_ > longest_)
        fail("the line is longer than " + std::to_string(longest_) + " bytes (not a " +
             "text file?)");
      if (newline) {
        text = std::string_view(buffer_.get() + begin_, stop - begin_);
        begin_ = scanned_ = stop + 1;
        ++newlines_;
        return true;
      }
      if (at_end_) {
        if (begin_ == end_)
          return false;
        text = std::string_view(buffer_.get() + begin_, end_ - begin_);
        begin_ = scanned_ = end_;
        return true;
      }
      fill();
    }
  }

  // Reads more after the line begun, which moves to the front of the buffer.
  void fill() {
    if (begin_ > 0) {
      std::memmove(buffer_.get(), buffer_.get() + begin_, end_ - begin_);
      end_ -= begin_;
      scanned_ -= begin_;
      begin_ = 0;
    }
    if (end_ == capacity_) { // a line longer than the buffer: twice the room
      std::unique_ptr<char[]> larger(new char[capacity_ * 2]);
      std::memcpy(larger.get(), buffer_.get(), end_);
      buffer_ = std::move(larger);
      capacity_ *= 2;
    }
    ssize_t got;
    do
      got = ::read(descriptor_, buffer_.get() + end_, capacity_ - end_);
    while (got < 0 && errno == EINTR);
    if (got < 0) {
      int error = errno;
      throw InputError(path_, 0, "cannot read: " + describe_errno(error));
    }
    end_ += static_cast<std::size_t>(got);
    at_end_ = got == 0;
  }

  std::string path_;
  int descriptor_ = -1;
  std::size_t file_size_ = 0;
  std::unique_ptr<char[]> buffer_;
  std::size_t capacity_ = kChunk;
  std::size_t begin_ = 0, scanned_ = 0, end_ = 0; // line begun, scanned up to, data up to
  bool at_end_ = false;
  long line_ = 0, newlines_ = 0;
  std::size_t longest_ = kLongest;
};

// Whole token as a double (strtod syntax); false when it is not one.
bool parse_double(std::string_view token, double &value) {
  char small[64];
  std::string large;
  const char *text;
  if (token.size() < sizeof small) {
    std::memcpy(small, token.data(), token.size());
    small[token.size()] = '\0';
    text = small;
  } else {
    large.assign(token);
    text = large.c_str();
  }
  char *end = nullptr;
  value = std::strtod(text, &end);
  return !token.empty() && end == text + token.size(); // a NUL byte inside is no number
}

// Whole token as a base-10 integer; false when it is not one or overflows.
bool parse_long(std::string_view token, long &value) {
  char small[64];
  if (token.empty() || token.size() >= sizeof small)
    return false;
  std::memcpy(small, token.data(), token.size());
  small[token.size()] = '\0';
  char *end = nullptr;
  errno = 0;
  value = std::strtol(small, &end, 10);
  return end == small + token.size() && errno != ERANGE; // a NUL byte inside is no number
}

// A finite number; `what` and `owner` name it ("x coordinate", "of hole 3").
double read_number(FieldReader &reader, std::string_view token, const char *what,
                   const std::string &owner) {
  double value = 0;
  if (!parse_double(token, value))
    reader.fail(std::string(what) + " " + quote(token) + " " + owner + " is not a number");
  if (!std::isfinite(value))
    reader.fail(std::string(what) + " " + quote(token) + " " + owner + " is not finite");
  return value;
}

// The vertex section of a .node or .poly file: header, then the vertices.
PointSet read_vertex_section(FieldReader &reader, const std::string &path) {
  std::vector<std::string_view> fields;

  const char *header_shape = "<#vertices> <dimension> <#attributes> <#boundary markers>";
  if (!reader.next(fields))
    throw InputError(path, reader.eof_line(),
                     std::string("missing header line (expected '") + header_shape + "')");
  // Triangle lets trailing header fields default to 2, 0, 0.
  long count = 0, dimension = 2, attributes = 0, markers = 0;
  if (!parse_long(fields[0], count) || count < 0 || count > INT32_MAX)
    reader.fail("malformed header: " + quote(fields[0]) + " is not a vertex count (expected '" +
                header_shape + "')");
  if (fields.size() > 1 && !parse_long(fields[1], dimension))
    reader.fail("malformed header: dimension " + quote(fields[1]) + " is not an integer");
  if (dimension != 2)
    reader.fail("dimension must be 2, got " + std::to_string(dimension));
  if (fields.size() > 2 &&
      (!parse_long(fields[2], attributes) || attributes < 0 || attributes > 1000000))
    reader.fail("malformed header: " + quote(fields[2]) + " is not an attribute count");
  if (fields.size() > 3 && (!parse_long(fields[3], markers) || (markers != 0 && markers != 1)))
    reader.fail("malformed header: boundary marker flag " + quote(fields[3]) + " must be 0 or 1");

  PointSet set;
  set.attribute_count = static_cast<int>(attributes);
  set.has_markers = markers == 1;
  // Do not trust the header for the allocation: a vertex line is at least 6 bytes.
  std::size_t reserve =
      std::min<std::size_t>(static_cast<std::size_t>(count), reader.size_bound() / 6);
  set.points.reserve(reserve);
  set.attributes.reserve(reserve * static_cast<std::size_t>(attributes));
  if (set.has_markers)
    set.markers.reserve(reserve);

  const std::size_t wanted = 3 + static_cast<std::size_t>(attributes) + (set.has_markers ? 1 : 0);
  reader.expect_fields(wanted);
  for (long i = 0; i < count; ++i) {
    if (!reader.next(fields))
      throw InputError(path, reader.eof_line(),
                       "file ends after " + std::to_string(i) + " of " + std::to_string(count) +
                           " vertices");
    if (fields.size() < wanted) {
      std::string shape = "id, x, y";
      if (attributes > 0)
        shape += ", " + std::to_string(attributes) + " attribute(s)";
      if (set.has_markers)
        shape += ", boundary marker";
      reader.fail("vertex line has " + std::to_string(fields.size()) + " field(s), expected " +
                  std::to_string(wanted) + " (" + shape + ")");
    }
    long id = 0;
    if (!parse_long(fields[0], id))
      reader.fail("vertex id " + quote(fields[0]) + " is not an integer");
    if (i == 0) {
      if (id != 0 && id != 1)
        reader.fail("first vertex id must be 0 or 1, got " + std::to_string(id));
      set.first_index = static_cast<int>(id);
    } else if (id != set.first_index + i) {
      reader.fail("vertex id " + std::to_string(id) + " out of sequence (expected " +
                  std::to_string(set.first_index + i) + ")");
    }
    double xy[2];
    for (int k = 0; k < 2; ++k) {
      const char *axis = k == 0 ? "x" : "y";
      if (!parse_double(fields[1 + k], xy[k]))
        reader.fail(std::string(axis) + " coordinate " + quote(fields[1 + k]) + " of vertex " +
                    std::to_string(id) + " is not a number");
      if (!std::isfinite(xy[k]))
        reader.fail(std::string(axis) + " coordinate " + quote(fields[1 + k]) + " of vertex " +
                    std::to_string(id) + " is not finite");
      const double magnitude = std::fabs(xy[k]);
      if (magnitude > kMaxCoordinate || (xy[k] != 0 && magnitude < kMinCoordinate))
        reader.fail(std::string(axis) + " coordinate " + quote(fields[1 + k]) + " of vertex " +
                    std::to_string(id) +
                    " is outside what exact arithmetic carries (non-zero magnitudes from 1e-50 "
                    "to 1e50)");
    }
    set.points.push_back(Point{xy[0], xy[1]});
    // Finite, as the attributes of regions are.
    for (long a = 0; a < attributes; ++a)
      set.attributes.push_back(read_number(reader, fields[3 + static_cast<std::size_t>(a)],
                                           "attribute", "of vertex " + std::to_string(id)));
    if (set.has_markers) {
      long marker = 0;
      std::string_view token = fields[wanted - 1];
      if (!parse_long(token, marker) || marker < INT_MIN || marker > INT_MAX)
        reader.fail("boundary marker " + quote(token) + " of vertex " + std::to_string(id) +
                    " is not an integer");
      set.markers.push_back(static_cast<int>(marker));
    }
  }
  return set;
}

// Numbers of a section header ("<count> [<flag>]"): the count must be a
// non-negative integer, a marker flag 0 or 1.
long read_count(FieldReader &reader, std::string_view token, const std::string &shape) {
  long count = 0;
  if (!parse_long(token, count) || count < 0 || count > INT32_MAX)
    reader.fail("malformed header: " + quote(token) + " is not a count (expected '" + shape + "')");
  return count;
}

// Next line of a section, or an InputError at the end of the file.
void next_line(FieldReader &reader, const std::string &path, std::vector<std::string_view> &fields,
               const std::string &missing) {
  if (!reader.next(fields))
    throw InputError(path, reader.eof_line(), "file ends " + missing);
}

// "n of m <items>" for premature ends of file.
std::string progress(long done, long count, const char *items) {
  return "after " + std::to_string(done) + " of " + std::to_string(count) + " " + items;
}

} // namespace

PointSet read_node(const std::string &path) {
  FieldReader reader(path);
  return read_vertex_section(reader, path);
}

PolyFile read_poly(const std::string &path) {
  FieldReader reader(path);
  std::vector<std::string_view> fields;
  PolyFile poly;

  // Vertices, or 0 and the .node file beside the .poly.
  poly.points = read_vertex_section(reader, path);
  if (poly.points.points.empty()) {
    const long header_line = reader.line();
    const std::string base = path.size() > 5 && path.compare(path.size() - 5, 5, ".poly") == 0
                                 ? path.substr(0, path.size() - 5)
                                 : path;
    poly.node_path = base + ".node";
    std::FILE *probe = std::fopen(poly.node_path.c_str(), "rb");
    if (!probe) {
      int error = errno;
      throw InputError(path, header_line,
                       "the vertex count is 0, so the vertices must be in " +
                           printable(poly.node_path) +
                           ", which cannot be opened: " + describe_errno(error));
    }
    std::fclose(probe);
    poly.points = read_node(poly.node_path);
  }
  const long n = static_cast<long>(poly.points.points.size());
  const long first = poly.points.first_index;

  // Segments.
  const std::string segment_shape = "<#segments> <#boundary markers>";
  next_line(reader, path, fields, "before the segment section (expected '" + segment_shape + "')");
  const long segment_count = read_count(reader, fields[0], segment_shape);
  if (fields.size() > 1) {
    long markers = 0;
    if (!parse_long(fields[1], markers) || (markers != 0 && markers != 1))
      reader.fail("malformed header: segment marker flag " + quote(fields[1]) + " must be 0 or 1");
    poly.segment_markers = markers == 1;
  }
  const std::size_t reserve =
      std::min<std::size_t>(static_cast<std::size_t>(segment_count), reader.size_bound() / 6);
  poly.segments.reserve(reserve);
  poly.segment_lines.reserve(reserve);
  for (long i = 0; i < segment_count; ++i) {
    next_line(reader, path, fields, progress(i, segment_count, "segments"));
    long id = 0;
    if (!parse_long(fields[0], id))
      reader.fail("segment id " + quote(fields[0]) + " is not an integer");
    if (fields.size() < 3)
      reader.fail(
          "segment " + std::to_string(id) + " has " +
          (fields.size() == 1 ? std::string("no endpoints") : std::string("only one endpoint")) +
          " (expected id, endpoint, endpoint" +
          (poly.segment_markers ? ", boundary marker)" : ")"));
    // As in a .node file, a marker that the section header announces must be there.
    if (poly.segment_markers && fields.size() < 4)
      reader.fail("segment " + std::to_string(id) +
                  " has no boundary marker (the section header announces one: expected id, "
                  "endpoint, endpoint, boundary marker)");
    long ends[2];
    for (int k = 0; k < 2; ++k) {
      if (!parse_long(fields[1 + k], ends[k]))
        reader.fail("endpoint " + quote(fields[1 + k]) + " of segment " + std::to_string(id) +
                    " is not an integer");
      if (ends[k] < first || ends[k] >= first + n)
        reader.fail("endpoint " + std::to_string(ends[k]) + " of segment " + std::to_string(id) +
                    " is out of range (vertices are numbered " + std::to_string(first) + " to " +
                    std::to_string(first + n - 1) + ")");
    }
    Segment segment;
    segment.a = static_cast<int32_t>(ends[0] - first);
    segment.b = static_cast<int32_t>(ends[1] - first);
    if (poly.segment_markers) {
      long marker = 0;
      if (!parse_long(fields[3], marker) || marker < INT_MIN || marker > INT_MAX)
        reader.fail("boundary marker " + quote(fields[3]) + " of segment " + std::to_string(id) +
                    " is not an integer");
      segment.marker = static_cast<int>(marker);
    }
    poly.segments.push_back(segment);
    poly.segment_lines.push_back(reader.line());
  }

  // Holes.
  next_line(reader, path, fields, "before the hole section (expected '<#holes>')");
  const long hole_count = read_count(reader, fields[0], "<#holes>");
  for (long i = 0; i < hole_count; ++i) {
    next_line(reader, path, fields, progress(i, hole_count, "holes"));
    long id = 0;
    if (!parse_long(fields[0], id))
      reader.fail("hole id " + quote(fields[0]) + " is not an integer");
    if (fields.size() < 3)
      reader.fail("hole " + std::to_string(id) + " has " +
                  (fields.size() == 1 ? "no coordinates" : "no y coordinate") +
                  " (expected id, x, y)");
    const std::string name = "of hole " + std::to_string(id);
    const double x = read_number(reader, fields[1], "x coordinate", name);
    const double y = read_number(reader, fields[2], "y coordinate", name);
    poly.holes.push_back(Point{x, y});
  }

  // Regions: an optional last section.
  if (!reader.next(fields))
    return poly;
  const long region_count = read_count(reader, fields[0], "<#regions>");
  for (long i = 0; i < region_count; ++i) {
    next_line(reader, path, fields, progress(i, region_count, "regions"));
    long id = 0;
    if (!parse_long(fields[0], id))
      reader.fail("region id " + quote(fields[0]) + " is not an integer");
    if (fields.size() < 4)
      reader.fail("region " + std::to_string(id) + " has " + std::to_string(fields.size() - 1) +
                  " number(s), expected at least 3 (x, y, attribute[, maximum area])");
    const std::string name = "of region " + std::to_string(id);
    Region region;
    region.seed.x = read_number(reader, fields[1], "x coordinate", name);
    region.seed.y = read_number(reader, fields[2], "y coordinate", name);
    region.attribute = read_number(reader, fields[3], "attribute", name);
    region.max_area = fields.size() > 4 ? read_number(reader, fields[4], "maximum area", name)
                                        : region.attribute; // as Triangle reads a line without one
    poly.regions.push_back(region);
  }
  return poly;
}

Input read_input(const std::string &path, std::string *node_path) {
  Input input;
  input.source = path;
  PointSet points;
  const bool pslg = path.size() >= 5 && path.compare(path.size() - 5, 5, ".poly") == 0;
  if (pslg) {
    PolyFile file = read_poly(path);
    if (node_path)
      *node_path = file.node_path;
    points = std::move(file.points);
    input.segments = std::move(file.segments);
    input.holes = std::move(file.holes);
    input.regions = std::move(file.regions);
  } else {
    points = read_node(path);
  }
  input.points = std::move(points.points);
  input.attribute_count = points.attribute_count;
  input.point_attributes = std::move(points.attributes);
  if (points.has_markers)
    input.point_markers = std::move(points.markers);
  input.first_index = points.first_index;
  return input;
}

// ---------------------------------------------------------------------------
// Mesh helpers
// ---------------------------------------------------------------------------

namespace {

// Key of the undirected edge {a, b}.
uint64_t edge_key(int32_t a, int32_t b) {
  const uint32_t lo = static_cast<uint32_t>(std::min(a, b)),
                 hi = static_cast<uint32_t>(std::max(a, b));
  return (static_cast<uint64_t>(lo) << 32) | hi;
}

void check_neighbors(const std::vector<Triangle> &triangles,
                     const std::vector<std::array<int32_t, 3>> &neighbors, const char *caller) {
  if (neighbors.size() != triangles.size())
    throw InternalError(std::string(caller) + ": " + std::to_string(triangles.size()) +
                        " triangles but " + std::to_string(neighbors.size()) +
                        " neighbour entries");
}

// Every edge of the mesh, mapped to whether it lies on the mesh boundary.
std::unordered_map<uint64_t, bool>
edges_on_boundary(const std::vector<Triangle> &triangles,
                  const std::vector<std::array<int32_t, 3>> &neighbors) {
  std::unordered_map<uint64_t, bool> edges;
  edges.reserve(triangles.size() * 2 + 4);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int i = 0; i < 3; ++i)
      edges.emplace(edge_key(triangles[t][(i + 1) % 3], triangles[t][(i + 2) % 3]),
                    neighbors[t][i] == -1);
  return edges;
}

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
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int i = 0; i < 3; ++i) {
      // Edge i lies opposite vertex i, from vertex i+1 to vertex i+2 (Triangle's
      // org/dest of orientation i); an interior edge is written by the triangle
      // with the smaller index.
      int32_t other = neighbors[t][i];
      if (other == -1 || static_cast<int64_t>(t) < other)
        edges.push_back(Edge{triangles[t][(i + 1) % 3], triangles[t][(i + 2) % 3], other == -1});
    }
  }
  return edges;
}

std::vector<Edge> mesh_edges(const std::vector<Triangle> &triangles,
                             const std::vector<std::array<int32_t, 3>> &neighbors,
                             const std::vector<Segment> &segments) {
  std::vector<Edge> edges = mesh_edges(triangles, neighbors);
  std::unordered_map<uint64_t, int> marker_of; // segment edge -> its marker (first one wins)
  marker_of.reserve(segments.size() * 2 + 1);
  for (const Segment &segment : segments)
    marker_of.emplace(edge_key(segment.a, segment.b), segment.marker);
  for (Edge &edge : edges) {
    auto found = marker_of.find(edge_key(edge.a, edge.b));
    if (found != marker_of.end())
      edge.marker = segment_marker(Segment{edge.a, edge.b, found->second}, edge.marker == 1);
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
  if (mesh.statistics.constrained)
    view.segments = &mesh.segments;
  if (mesh.triangle_attribute_count > 0)
    view.triangle_attributes = &mesh.triangle_attributes;
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
namespace {

// Buffered text output to a temporary file; errors name the final file.
class TextFile {
public:
  TextFile(const std::string &temporary, const std::string &final_path)
      : temporary_(temporary), final_(final_path) {
    file_ = std::fopen(temporary.c_str(), "wbx"); // exclusive: a new file or an error
    if (!file_) {
      int error = errno;
      throw InputError(final_, 0, "cannot write: " + describe_errno(error));
    }
    buffer_.reserve(kFlushAt + 4096);
  }
  TextFile(const TextFile &) = delete;
  TextFile &operator=(const TextFile &) = delete;
  ~TextFile() {
    if (file_)
      std::fclose(file_);
  }

  [[gnu::format(printf, 2, 3)]] void format(const char *pattern, ...) {
    char line[512];
    va_list args;
    va_start(args, pattern);
    int length = std::vsnprintf(line, sizeof line, pattern, args);
    va_end(args);
    if (length < 0)
      fail(EINVAL);
    if (static_cast<std::size_t>(length) < sizeof line) {
      buffer_.append(line, static_cast<std::size_t>(length));
    } else {
      std::string big(static_cast<std::size_t>(length) + 1, '\0');
      va_start(args, pattern);
      std::vsnprintf(&big[0], big.size(), pattern, args);
      va_end(args);
      buffer_.append(big.data(), static_cast<std::size_t>(length));
    }
    if (buffer_.size() >= kFlushAt)
      flush();
  }
  // Appends `value` right-aligned in `width` characters, as printf's "%*ld"
  // (the integer columns of .ele, .edge and .neigh are by far the bulk).
  void integer(long value, int width = 0) {
    char digits[24];
    const auto result = std::to_chars(digits, digits + sizeof digits, value);
    const auto count = static_cast<int>(result.ptr - digits);
    if (width > count)
      buffer_.append(static_cast<std::size_t>(width - count), ' ');
    buffer_.append(digits, result.ptr);
  }
  // Appends `value` as printf's "%.17g" does (std::to_chars promises the
  // same characters), without printf's cost: coordinates fill .node files.
  void real(double value) {
    char digits[32];
    const auto result =
        std::to_chars(digits, digits + sizeof digits, value, std::chars_format::general, 17);
    buffer_.append(digits, result.ptr);
  }
  void text(const char *words) { buffer_ += words; }
  void end_line() {
    buffer_ += '\n';
    if (buffer_.size() >= kFlushAt)
      flush();
  }
  void append(const std::string &text) {
    buffer_ += text;
    if (buffer_.size() >= kFlushAt)
      flush();
  }
  void footer(const WriteOptions &options) {
    if (!options.command_line.empty())
      append("# Generated by " + options.command_line + "\n");
  }
  void close() {
    flush();
    std::FILE *file = file_;
    file_ = nullptr;
    if (std::fclose(file) != 0)
      fail(errno);
  }

private:
  static constexpr std::size_t kFlushAt = 1 << 20;
  void flush() {
    if (!buffer_.empty() && std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size())
      fail(errno);
    buffer_.clear();
  }
  [[noreturn]] void fail(int error) {
    throw InputError(final_, 0, "cannot write: " + describe_errno(error));
  }
  std::string temporary_, final_;
  std::FILE *file_ = nullptr;
  std::string buffer_;
};

const std::vector<Point> &points_of(const MeshView &mesh) {
  if (!mesh.points)
    throw InternalError("output writer called without points");
  return *mesh.points;
}
const std::vector<Triangle> &triangles_of(const MeshView &mesh) {
  if (!mesh.triangles)
    throw InternalError("output writer called without triangles");
  return *mesh.triangles;
}
const std::vector<std::array<int32_t, 3>> &neighbors_of(const MeshView &mesh) {
  if (!mesh.neighbors || mesh.neighbors->size() != triangles_of(mesh).size())
    throw InternalError("output writer called without neighbours for every triangle");
  return *mesh.neighbors;
}

// Vertex number as written: renumbered for -j, then shifted to first_index.
int32_t written_vertex(const std::vector<int32_t> &numbers, int32_t vertex, const WriteOptions &o) {
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= numbers.size() || numbers[vertex] < 0)
    throw InternalError("mesh refers to vertex " + std::to_string(vertex) +
                        ", which is not written");
  return numbers[vertex] + o.first_index;
}

} // namespace

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

void OutputBatch::write_node(const std::string &path, const MeshView &mesh,
                             const WriteOptions &options) {
  const std::vector<Point> &points = points_of(mesh);
  const std::size_t n = points.size();
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  std::size_t written = 0;
  for (int32_t number : numbers)
    written += number >= 0;
  const std::vector<int> markers =
      options.boundary_markers ? output_vertex_markers(mesh) : std::vector<int>();

  const std::size_t attributes = static_cast<std::size_t>(std::max(mesh.attribute_count, 0));
  if (attributes > 0 && (!mesh.point_attributes || mesh.point_attributes->size() < n * attributes))
    throw InternalError("point set holds fewer attributes than its attribute count says");
  TextFile file(temporary_for(path), path);
  file.format("%zu  2  %zu  %d\n", written, attributes, options.boundary_markers ? 1 : 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (numbers[i] < 0)
      continue;
    // "%4ld    %.17g  %.17g", then "  %.17g" per attribute, then "    %d"
    file.integer(static_cast<long>(numbers[i]) + options.first_index, 4);
    file.text("    ");
    file.real(points[i].x);
    file.text("  ");
    file.real(points[i].y);
    for (std::size_t a = 0; a < attributes; ++a) {
      file.text("  ");
      file.real((*mesh.point_attributes)[i * attributes + a]);
    }
    if (options.boundary_markers) {
      file.text("    ");
      file.integer(markers[i]);
    }
    file.end_line();
  }
  file.footer(options);
  file.close();
}

void OutputBatch::write_ele(const std::string &path, const MeshView &mesh,
                            const WriteOptions &options) {
  const std::vector<Triangle> &triangles = triangles_of(mesh);
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  const std::vector<double> *attributes = mesh.triangle_attributes;
  if (attributes && attributes->size() != triangles.size())
    throw InternalError("output writer called with " + std::to_string(attributes->size()) +
                        " triangle attributes for " + std::to_string(triangles.size()) +
                        " triangles");
  TextFile file(temporary_for(path), path);
  file.format("%zu  3  %d\n", triangles.size(), attributes ? 1 : 0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    // "%4ld    %4d  %4d  %4d", then "  %.17g" per attribute
    file.integer(static_cast<long>(t) + options.first_index, 4);
    for (int k = 0; k < 3; ++k) {
      file.text(k == 0 ? "    " : "  ");
      file.integer(written_vertex(numbers, triangles[t][k], options), 4);
    }
    if (attributes) {
      file.text("  ");
      file.real((*attributes)[t]);
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
  const auto on_boundary = edges_on_boundary(triangles_of(mesh), neighbors_of(mesh));
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  struct Written {
    int32_t a, b;
    int marker;
  };
  std::vector<Written> segments;
  segments.reserve(mesh.segments->size());
  for (const Segment &segment : *mesh.segments) {
    auto edge = on_boundary.find(edge_key(segment.a, segment.b));
    if (edge == on_boundary.end())
      continue; // no edge of the mesh: eaten with a hole or the exterior
    segments.push_back(Written{written_vertex(numbers, segment.a, options),
                               written_vertex(numbers, segment.b, options),
                               segment_marker(segment, edge->second)});
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

// ---------------------------------------------------------------------------
// Pictures
// ---------------------------------------------------------------------------

std::string mesh_svg(const std::vector<Point> &points, const std::vector<Triangle> &triangles,
                     const std::vector<Segment> *segments) {
  double min_x = 0, max_x = 1, min_y = 0, max_y = 1;
  if (!points.empty()) {
    min_x = max_x = points[0].x;
    min_y = max_y = points[0].y;
    for (const Point &p : points) {
      min_x = std::min(min_x, p.x);
      max_x = std::max(max_x, p.x);
      min_y = std::min(min_y, p.y);
      max_y = std::max(max_y, p.y);
    }
  }
  double extent = std::max(max_x - min_x, max_y - min_y);
  if (!(extent > 0) || !std::isfinite(extent))
    extent = 1;
  const double margin = 0.03 * extent;
  const double width = (max_x - min_x) + 2 * margin, height = (max_y - min_y) + 2 * margin;
  // Shifted so that the picture starts at (0, 0), y flipped so that it points up.
  auto sx = [&](double x) { return x - min_x + margin; };
  auto sy = [&](double y) { return max_y - y + margin; };

  std::string svg;
  char buffer[256];
  auto add = [&](const char *format, auto... args) {
    int length = std::snprintf(buffer, sizeof buffer, format, args...);
    if (length > 0)
      svg.append(buffer, std::min<std::size_t>(length, sizeof buffer - 1));
  };
  const double pixels = 1000;
  add("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
  add("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 %.9g %.9g\" width=\"%.0f\" "
      "height=\"%.0f\">\n",
      width, height, width >= height ? pixels : std::max(1.0, pixels * width / height),
      height >= width ? pixels : std::max(1.0, pixels * height / width));
  add("<title>clmesh: %zu points, %zu triangles</title>\n", points.size(), triangles.size());
  add("<rect x=\"0\" y=\"0\" width=\"%.9g\" height=\"%.9g\" fill=\"white\"/>\n", width, height);
  svg += "<path fill=\"none\" stroke=\"#1f4e79\" stroke-width=\"0.6\" stroke-linejoin=\"round\" "
         "vector-effect=\"non-scaling-stroke\" d=\"";
  for (const Triangle &t : triangles) {
    bool valid = true;
    for (int32_t v : t)
      valid = valid && v >= 0 && static_cast<std::size_t>(v) < points.size();
    if (!valid)
      continue;
    const Point &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
    add("M%.8g %.8gL%.8g %.8gL%.8g %.8gZ", sx(a.x), sy(a.y), sx(b.x), sy(b.y), sx(c.x), sy(c.y));
  }
  svg += "\"/>\n";
  if (segments && !segments->empty()) {
    svg += "<path fill=\"none\" stroke=\"#e67e22\" stroke-width=\"2\" stroke-linecap=\"round\" "
           "vector-effect=\"non-scaling-stroke\" d=\"";
    for (const Segment &s : *segments) {
      if (s.a < 0 || s.b < 0 || static_cast<std::size_t>(s.a) >= points.size() ||
          static_cast<std::size_t>(s.b) >= points.size())
        continue;
      const Point &a = points[s.a], &b = points[s.b];
      add("M%.8g %.8gL%.8g %.8g", sx(a.x), sy(a.y), sx(b.x), sy(b.y));
    }
    svg += "\"/>\n";
  }
  if (points.size() <= 5000) {
    add("<g fill=\"#c0392b\" stroke=\"none\">\n");
    const double radius = 0.004 * extent;
    for (const Point &p : points)
      add("<circle cx=\"%.8g\" cy=\"%.8g\" r=\"%.4g\"/>\n", sx(p.x), sy(p.y), radius);
    svg += "</g>\n";
  }
  svg += "</svg>\n";
  return svg;
}

std::string voronoi_pgm(const std::vector<int32_t> &sites, int grid) {
  if (grid <= 0 || sites.size() != static_cast<std::size_t>(grid) * static_cast<std::size_t>(grid))
    throw InternalError("voronoi_pgm: " + std::to_string(sites.size()) +
                        " sites do not fill a grid of side " + std::to_string(grid));
  std::string image = "P5\n" + std::to_string(grid) + " " + std::to_string(grid) + "\n255\n";
  const std::size_t header = image.size();
  image.resize(header + sites.size());
  // Row 0 of the grid is the bottom (smallest y): the image's top row is the last.
  for (int row = 0; row < grid; ++row) {
    const int32_t *source = sites.data() + static_cast<std::size_t>(grid - 1 - row) * grid;
    char *target = &image[header + static_cast<std::size_t>(row) * grid];
    for (int column = 0; column < grid; ++column) {
      int32_t site = source[column];
      unsigned char grey = 0;
      if (site >= 0) {
        uint32_t h = static_cast<uint32_t>(site) * 0x9E3779B1u;
        h ^= h >> 16;
        h *= 0x85EBCA6Bu;
        h ^= h >> 13;
        grey = static_cast<unsigned char>(40 + h % 216);
      }
      target[column] = static_cast<char>(grey);
    }
  }
  return image;
}

} // namespace clmesh
