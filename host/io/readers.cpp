// clmesh — reading Triangle's .node, .poly, .ele and .area files as they stream in
// (see clmesh/io.hpp).
#include "clmesh/io.hpp"

#include "clmesh/errors.hpp"
#include "io/system_error.hpp"

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
  // The common decimal forms by from_chars (correctly rounded, as strtod);
  // the rest (a sign '+', hexadecimal, out of range) by strtod.
  const char *last = token.data() + token.size();
  if (const auto [stop, error] = std::from_chars(token.data(), last, value);
      error == std::errc() && stop == last && !token.empty())
    return true;
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
  // Plain digits by from_chars; the rest (a sign '+', overflow) by strtol.
  const char *last = token.data() + token.size();
  if (const auto [stop, error] = std::from_chars(token.data(), last, value, 10);
      error == std::errc() && stop == last && !token.empty())
    return true;
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
// What a number belongs to, named in messages ("of triangle 7"): built only
// when one is written, not for every line read.
struct Owner {
  const char *kind;
  long id;
  std::string text() const { return std::string("of ") + kind + " " + std::to_string(id); }
};

double read_number(FieldReader &reader, std::string_view token, const char *what,
                   const Owner &owner) {
  double value = 0;
  if (!parse_double(token, value))
    reader.fail(std::string(what) + " " + quote(token) + " " + owner.text() + " is not a number");
  if (!std::isfinite(value))
    reader.fail(std::string(what) + " " + quote(token) + " " + owner.text() + " is not finite");
  return value;
}

// The id of the i-th item of a section, numbered from 0 or 1 as its first
// id says (*first is set from it); `item` names the items in messages.
void check_id(FieldReader &reader, std::string_view token, long i, long *first, const char *item) {
  long id = 0;
  if (!parse_long(token, id))
    reader.fail(std::string(item) + " id " + quote(token) + " is not an integer");
  if (i == 0) {
    if (id != 0 && id != 1)
      reader.fail("first " + std::string(item) + " id must be 0 or 1, got " + std::to_string(id));
    *first = id;
  } else if (id != *first + i) {
    reader.fail(std::string(item) + " id " + std::to_string(id) + " out of sequence (expected " +
                std::to_string(*first + i) + ")");
  }
}

// Next line of a section, or an InputError at the end of the file.
void next_line(FieldReader &reader, const std::string &path, std::vector<std::string_view> &fields,
               const std::string &missing) {
  if (!reader.next(fields))
    throw InputError(path, reader.eof_line(), "file ends " + missing);
}

// Next line of a section's `count` items, `done` read: at the end of the
// file an InputError "file ends after n of m <items>".
void next_item(FieldReader &reader, const std::string &path, std::vector<std::string_view> &fields,
               long done, long count, const char *items) {
  if (!reader.next(fields))
    throw InputError(path, reader.eof_line(),
                     "file ends after " + std::to_string(done) + " of " + std::to_string(count) +
                         " " + items);
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
    next_item(reader, path, fields, i, count, "vertices");
    if (fields.size() < wanted) {
      std::string shape = "id, x, y";
      if (attributes > 0)
        shape += ", " + std::to_string(attributes) + " attribute(s)";
      if (set.has_markers)
        shape += ", boundary marker";
      reader.fail("vertex line has " + std::to_string(fields.size()) + " field(s), expected " +
                  std::to_string(wanted) + " (" + shape + ")");
    }
    long first = set.first_index;
    check_id(reader, fields[0], i, &first, "vertex");
    set.first_index = static_cast<int>(first);
    const long id = first + i;
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
                                           "attribute", Owner{"vertex", id}));
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
    next_item(reader, path, fields, i, segment_count, "segments");
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
    next_item(reader, path, fields, i, hole_count, "holes");
    long id = 0;
    if (!parse_long(fields[0], id))
      reader.fail("hole id " + quote(fields[0]) + " is not an integer");
    if (fields.size() < 3)
      reader.fail("hole " + std::to_string(id) + " has " +
                  (fields.size() == 1 ? "no coordinates" : "no y coordinate") +
                  " (expected id, x, y)");
    const Owner name{"hole", id};
    const double x = read_number(reader, fields[1], "x coordinate", name);
    const double y = read_number(reader, fields[2], "y coordinate", name);
    poly.holes.push_back(Point{x, y});
  }

  // Regions: an optional last section.
  if (!reader.next(fields))
    return poly;
  const long region_count = read_count(reader, fields[0], "<#regions>");
  for (long i = 0; i < region_count; ++i) {
    next_item(reader, path, fields, i, region_count, "regions");
    long id = 0;
    if (!parse_long(fields[0], id))
      reader.fail("region id " + quote(fields[0]) + " is not an integer");
    if (fields.size() < 4)
      reader.fail("region " + std::to_string(id) + " has " + std::to_string(fields.size() - 1) +
                  " number(s), expected at least 3 (x, y, attribute[, maximum area])");
    const Owner name{"region", id};
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

namespace {

// The vertices of `points` (attributes, markers, numbering) into `input`.
void take_points(Input &input, PointSet &&points) {
  input.points = std::move(points.points);
  input.attribute_count = points.attribute_count;
  input.point_attributes = std::move(points.attributes);
  if (points.has_markers)
    input.point_markers = std::move(points.markers);
  input.first_index = points.first_index;
}

} // namespace

Input read_input(const std::string &path, std::string *node_path) {
  Input input;
  input.source = path;
  const bool pslg = path.size() >= 5 && path.compare(path.size() - 5, 5, ".poly") == 0;
  if (pslg) {
    PolyFile file = read_poly(path);
    if (node_path)
      *node_path = file.node_path;
    take_points(input, std::move(file.points));
    input.segments = std::move(file.segments);
    input.holes = std::move(file.holes);
    input.regions = std::move(file.regions);
  } else {
    take_points(input, read_node(path));
  }
  return input;
}

EleFile read_ele(const std::string &path, long vertex_count, int first_vertex) {
  FieldReader reader(path);
  std::vector<std::string_view> fields;
  const std::string shape = "<#triangles> <nodes per triangle> <#attributes>";
  next_line(reader, path, fields, "before the header (expected '" + shape + "')");
  const long count = read_count(reader, fields[0], shape);
  long nodes = 3, attributes = 0;
  if (fields.size() > 1 && !parse_long(fields[1], nodes))
    reader.fail("malformed header: nodes per triangle " + quote(fields[1]) + " is not an integer");
  if (nodes < 3 || nodes > 1000)
    reader.fail("malformed header: a triangle has at least 3 nodes (3, or 6 for second-order "
                "triangles), not " +
                std::to_string(nodes));
  if (fields.size() > 2 &&
      (!parse_long(fields[2], attributes) || attributes < 0 || attributes > 1000000))
    reader.fail("malformed header: " + quote(fields[2]) + " is not an attribute count");

  EleFile ele;
  ele.attribute_count = static_cast<int>(attributes);
  // Do not trust the header for the allocation: a triangle line is at least 8 bytes.
  const std::size_t reserve =
      std::min<std::size_t>(static_cast<std::size_t>(count), reader.size_bound() / 8);
  ele.triangles.reserve(reserve);
  ele.lines.reserve(reserve);
  ele.attributes.reserve(reserve * static_cast<std::size_t>(attributes));
  const std::size_t wanted = 1 + static_cast<std::size_t>(nodes + attributes);
  reader.expect_fields(wanted);
  long first = 0;
  for (long i = 0; i < count; ++i) {
    next_item(reader, path, fields, i, count, "triangles");
    check_id(reader, fields[0], i, &first, "triangle");
    const Owner name{"triangle", first + i};
    if (fields.size() < wanted)
      reader.fail("triangle line has " + std::to_string(fields.size()) + " field(s), expected " +
                  std::to_string(wanted) + " (id, " + std::to_string(nodes) + " nodes" +
                  (attributes > 0 ? ", " + std::to_string(attributes) + " attribute(s))" : ")"));
    Triangle triangle{};
    for (int k = 0; k < 3; ++k) {
      long corner = 0;
      if (!parse_long(fields[1 + k], corner))
        reader.fail("corner " + quote(fields[1 + k]) + " " + name.text() + " is not an integer");
      if (corner < first_vertex || corner >= first_vertex + vertex_count)
        reader.fail("corner " + std::to_string(corner) + " " + name.text() +
                    " is not a vertex (vertices are numbered " + std::to_string(first_vertex) +
                    " to " + std::to_string(first_vertex + vertex_count - 1) + ")");
      triangle[k] = static_cast<int32_t>(corner - first_vertex);
    }
    ele.triangles.push_back(triangle);
    ele.lines.push_back(reader.line());
    for (long a = 0; a < attributes; ++a)
      ele.attributes.push_back(
          read_number(reader, fields[1 + static_cast<std::size_t>(nodes + a)], "attribute", name));
  }
  ele.first_index = static_cast<int>(first);
  return ele;
}

std::vector<double> read_area(const std::string &path, std::size_t triangle_count) {
  FieldReader reader(path);
  std::vector<std::string_view> fields;
  next_line(reader, path, fields, "before the header (expected '<#triangles>')");
  const long count = read_count(reader, fields[0], "<#triangles>");
  if (static_cast<std::size_t>(count) != triangle_count)
    reader.fail("the header announces " + std::to_string(count) + " triangles, the .ele file has " +
                std::to_string(triangle_count));
  std::vector<double> areas;
  areas.reserve(triangle_count);
  long first = 0;
  for (long i = 0; i < count; ++i) {
    next_item(reader, path, fields, i, count, "triangles");
    check_id(reader, fields[0], i, &first, "triangle");
    if (fields.size() < 2)
      reader.fail("triangle " + std::to_string(first + i) +
                  " has no maximum area (expected id, maximum area)");
    areas.push_back(read_number(reader, fields[1], "maximum area", Owner{"triangle", first + i}));
  }
  return areas;
}

Input read_mesh(const std::string &base, bool pslg, bool areas, std::vector<std::string> *opened) {
  auto open = [opened](const std::string &path) {
    if (opened)
      opened->push_back(path);
    return path;
  };
  Input input;
  if (pslg) {
    input.source = open(base + ".poly");
    PolyFile file = read_poly(input.source);
    if (!file.node_path.empty())
      open(file.node_path);
    take_points(input, std::move(file.points));
    input.segments = std::move(file.segments);
    input.holes = std::move(file.holes);
  } else {
    input.source = open(base + ".node");
    take_points(input, read_node(input.source));
  }
  input.triangles_source = open(base + ".ele");
  EleFile ele =
      read_ele(input.triangles_source, static_cast<long>(input.points.size()), input.first_index);
  input.triangles = std::move(ele.triangles);
  input.triangle_attribute_count = ele.attribute_count;
  input.triangle_attributes = std::move(ele.attributes);
  input.triangle_lines = std::move(ele.lines);
  if (areas)
    input.triangle_max_area = read_area(open(base + ".area"), input.triangles.size());
  return input;
}

} // namespace clmesh
