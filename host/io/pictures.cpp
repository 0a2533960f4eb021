// clmesh — SVG pictures of meshes and PGM pictures of digital Voronoi diagrams.
#include "clmesh/io.hpp"

#include "clmesh/errors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace clmesh {

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
