// clmesh — Triangle's file formats, SVG and PGM pictures (see clmesh/io.hpp).
#include "clmesh/io.hpp"

#include "clmesh/errors.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

namespace clmesh {

// ---------------------------------------------------------------------------
// Reading
// ---------------------------------------------------------------------------
namespace {

std::string describe_errno(int error) { return error != 0 ? std::strerror(error) : "I/O error"; }

std::string read_whole_file(const std::string &path) {
  std::FILE *file = std::fopen(path.c_str(), "rb");
  if (!file) {
    int error = errno;
    throw InputError(path, 0, "cannot open: " + describe_errno(error));
  }
  std::string data;
  char buffer[1 << 16];
  for (;;) {
    std::size_t got = std::fread(buffer, 1, sizeof buffer, file);
    data.append(buffer, got);
    if (got < sizeof buffer)
      break;
  }
  bool failed = std::ferror(file) != 0;
  int error = errno;
  std::fclose(file);
  if (failed)
    throw InputError(path, 0, "cannot read: " + describe_errno(error));
  return data;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Splits a file into lines of whitespace-separated fields; '#' starts a
// comment that runs to the end of the line; lines without fields are skipped.
class FieldReader {
public:
  FieldReader(std::string path, std::string data)
      : path_(std::move(path)), data_(std::move(data)) {}

  // Next line holding at least one field; false at the end of the file.
  bool next(std::vector<std::string_view> &fields) {
    while (pos_ < data_.size()) {
      std::size_t end = data_.find('\n', pos_);
      if (end == std::string::npos)
        end = data_.size();
      ++line_;
      std::string_view text(data_.data() + pos_, end - pos_);
      pos_ = end + 1;
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
  long eof_line() const {
    return static_cast<long>(std::count(data_.begin(), data_.end(), '\n')) + 1;
  }
  [[noreturn]] void fail(const std::string &problem) const {
    throw InputError(path_, line_, problem);
  }
  std::size_t size() const { return data_.size(); }

private:
  std::string path_;
  std::string data_;
  std::size_t pos_ = 0;
  long line_ = 0;
};

std::string quoted(std::string_view token) { return "'" + std::string(token) + "'"; }

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
  return end != text && *end == '\0';
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
  return end != small && *end == '\0' && errno != ERANGE;
}

} // namespace

PointSet read_node(const std::string &path) {
  FieldReader reader(path, read_whole_file(path));
  std::vector<std::string_view> fields;

  const char *header_shape = "<#vertices> <dimension> <#attributes> <#boundary markers>";
  if (!reader.next(fields))
    throw InputError(path, reader.eof_line(),
                     std::string("missing header line (expected '") + header_shape + "')");
  // Triangle lets trailing header fields default to 2, 0, 0.
  long count = 0, dimension = 2, attributes = 0, markers = 0;
  if (!parse_long(fields[0], count) || count < 0 || count > INT32_MAX)
    reader.fail("malformed header: " + quoted(fields[0]) + " is not a vertex count (expected '" +
                header_shape + "')");
  if (fields.size() > 1 && !parse_long(fields[1], dimension))
    reader.fail("malformed header: dimension " + quoted(fields[1]) + " is not an integer");
  if (dimension != 2)
    reader.fail("dimension must be 2, got " + std::to_string(dimension));
  if (fields.size() > 2 &&
      (!parse_long(fields[2], attributes) || attributes < 0 || attributes > 1000000))
    reader.fail("malformed header: " + quoted(fields[2]) + " is not an attribute count");
  if (fields.size() > 3 && (!parse_long(fields[3], markers) || (markers != 0 && markers != 1)))
    reader.fail("malformed header: boundary marker flag " + quoted(fields[3]) + " must be 0 or 1");

  PointSet set;
  set.attribute_count = static_cast<int>(attributes);
  set.has_markers = markers == 1;
  // Do not trust the header for the allocation: a vertex line is at least 6 bytes.
  std::size_t reserve = std::min<std::size_t>(static_cast<std::size_t>(count), reader.size() / 6);
  set.points.reserve(reserve);
  set.attributes.reserve(reserve * static_cast<std::size_t>(attributes));
  if (set.has_markers)
    set.markers.reserve(reserve);

  const std::size_t wanted = 3 + static_cast<std::size_t>(attributes) + (set.has_markers ? 1 : 0);
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
      reader.fail("vertex id " + quoted(fields[0]) + " is not an integer");
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
        reader.fail(std::string(axis) + " coordinate " + quoted(fields[1 + k]) + " of vertex " +
                    std::to_string(id) + " is not a number");
      if (!std::isfinite(xy[k]))
        reader.fail(std::string(axis) + " coordinate " + quoted(fields[1 + k]) + " of vertex " +
                    std::to_string(id) + " is not finite");
    }
    set.points.push_back(Point{xy[0], xy[1]});
    for (long a = 0; a < attributes; ++a) {
      double value = 0;
      std::string_view token = fields[3 + static_cast<std::size_t>(a)];
      if (!parse_double(token, value))
        reader.fail("attribute " + quoted(token) + " of vertex " + std::to_string(id) +
                    " is not a number");
      set.attributes.push_back(value);
    }
    if (set.has_markers) {
      long marker = 0;
      std::string_view token = fields[wanted - 1];
      if (!parse_long(token, marker) || marker < INT_MIN || marker > INT_MAX)
        reader.fail("boundary marker " + quoted(token) + " of vertex " + std::to_string(id) +
                    " is not an integer");
      set.markers.push_back(static_cast<int>(marker));
    }
  }
  return set;
}

// ---------------------------------------------------------------------------
// Mesh helpers
// ---------------------------------------------------------------------------

std::vector<Edge> mesh_edges(const std::vector<Triangle> &triangles,
                             const std::vector<std::array<int32_t, 3>> &neighbors) {
  if (neighbors.size() != triangles.size())
    throw InternalError("mesh_edges: " + std::to_string(triangles.size()) + " triangles but " +
                        std::to_string(neighbors.size()) + " neighbour entries");
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

std::vector<int32_t> output_vertex_numbers(const MeshView &mesh, const WriteOptions &options) {
  std::size_t n = mesh.points ? mesh.points->points.size() : 0;
  std::vector<int32_t> numbers(n);
  const std::vector<int32_t> *duplicates = mesh.duplicate_of;
  bool jettison = options.jettison_duplicates && duplicates && duplicates->size() == n;
  int32_t next = 0;
  for (std::size_t i = 0; i < n; ++i)
    numbers[i] = jettison && (*duplicates)[i] != -1 ? -1 : next++;
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
    file_ = std::fopen(temporary.c_str(), "wb");
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
    int count = 0;
    unsigned long magnitude =
        value < 0 ? 0UL - static_cast<unsigned long>(value) : static_cast<unsigned long>(value);
    do {
      digits[count++] = static_cast<char>('0' + magnitude % 10);
      magnitude /= 10;
    } while (magnitude != 0);
    if (value < 0)
      digits[count++] = '-';
    if (width > count)
      buffer_.append(static_cast<std::size_t>(width - count), ' ');
    while (count > 0)
      buffer_ += digits[--count];
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

const PointSet &points_of(const MeshView &mesh) {
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

std::string OutputBatch::temporary_for(const std::string &path) {
  std::string temporary = path + ".tmp-clmesh";
  for (const auto &file : files_)
    if (file.second == path)
      return temporary; // written again: replaces the earlier one
  files_.emplace_back(temporary, path);
  return temporary;
}

void OutputBatch::write_node(const std::string &path, const MeshView &mesh,
                             const WriteOptions &options) {
  const PointSet &set = points_of(mesh);
  const std::size_t n = set.points.size();
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  std::size_t written = 0;
  for (int32_t number : numbers)
    written += number >= 0;

  // As Triangle without -p: vertices on the convex hull whose marker is 0 get 1.
  std::vector<int> markers(n, 0);
  if (set.has_markers && set.markers.size() == n)
    markers = set.markers;
  if (mesh.triangles && mesh.neighbors && mesh.neighbors->size() == mesh.triangles->size()) {
    for (std::size_t t = 0; t < mesh.triangles->size(); ++t)
      for (int i = 0; i < 3; ++i)
        if ((*mesh.neighbors)[t][i] == -1)
          for (int k = 1; k <= 2; ++k) {
            int32_t v = (*mesh.triangles)[t][(i + k) % 3];
            if (v >= 0 && static_cast<std::size_t>(v) < n && markers[v] == 0)
              markers[v] = 1;
          }
  }

  const std::size_t attributes = static_cast<std::size_t>(std::max(set.attribute_count, 0));
  if (set.attributes.size() < n * attributes)
    throw InternalError("point set holds fewer attributes than its attribute count says");
  TextFile file(temporary_for(path), path);
  file.format("%zu  2  %zu  1\n", written, attributes);
  for (std::size_t i = 0; i < n; ++i) {
    if (numbers[i] < 0)
      continue;
    file.format("%4ld    %.17g  %.17g", static_cast<long>(numbers[i]) + options.first_index,
                set.points[i].x, set.points[i].y);
    for (std::size_t a = 0; a < attributes; ++a)
      file.format("  %.17g", set.attributes[i * attributes + a]);
    file.format("    %d\n", markers[i]);
  }
  file.footer(options);
  file.close();
}

void OutputBatch::write_ele(const std::string &path, const MeshView &mesh,
                            const WriteOptions &options) {
  const std::vector<Triangle> &triangles = triangles_of(mesh);
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  TextFile file(temporary_for(path), path);
  file.format("%zu  3  0\n", triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    // "%4ld    %4d  %4d  %4d"
    file.integer(static_cast<long>(t) + options.first_index, 4);
    for (int k = 0; k < 3; ++k) {
      file.text(k == 0 ? "    " : "  ");
      file.integer(written_vertex(numbers, triangles[t][k], options), 4);
    }
    file.end_line();
  }
  file.footer(options);
  file.close();
}

void OutputBatch::write_edge(const std::string &path, const MeshView &mesh,
                             const WriteOptions &options) {
  const std::vector<Edge> edges = mesh_edges(triangles_of(mesh), neighbors_of(mesh));
  const std::vector<int32_t> numbers = output_vertex_numbers(mesh, options);
  TextFile file(temporary_for(path), path);
  file.format("%zu  1\n", edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    // "%4ld   %d  %d  %d"
    file.integer(static_cast<long>(e) + options.first_index, 4);
    file.text("   ");
    file.integer(written_vertex(numbers, edges[e].a, options));
    file.text("  ");
    file.integer(written_vertex(numbers, edges[e].b, options));
    file.text("  ");
    file.integer(edges[e].marker);
    file.end_line();
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
  while (!files_.empty()) {
    const auto &file = files_.front();
    if (std::rename(file.first.c_str(), file.second.c_str()) != 0) {
      int error = errno;
      throw InputError(file.second, 0,
                       "cannot move the finished file into place: " + describe_errno(error));
    }
    files_.erase(files_.begin());
  }
}

// ---------------------------------------------------------------------------
// Pictures
// ---------------------------------------------------------------------------

std::string mesh_svg(const std::vector<Point> &points, const std::vector<Triangle> &triangles) {
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
