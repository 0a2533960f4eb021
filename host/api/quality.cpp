// clmesh — Triangle's -V mesh quality statistics, so that meshes compare side
// by side with Triangle's.
#include "clmesh/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace clmesh {

namespace {

// Upper ends of the aspect ratio histogram's bins (the last bin is open).
constexpr double kRatioBins[] = {1.5, 2,  2.5, 3,   4,    6,     10,    15,
                                 25,  50, 100, 300, 1000, 10000, 100000};
constexpr int kRatioCount = sizeof kRatioBins / sizeof kRatioBins[0] + 1;
constexpr double kPi = 3.14159265358979323846;

} // namespace

QualityStatistics quality_statistics(const Mesh &mesh) {
  QualityStatistics q;
  q.triangles = static_cast<long>(mesh.triangles.size());
  if (mesh.triangles.empty())
    return q;
  q.smallest_area = HUGE_VAL, q.shortest_edge = HUGE_VAL, q.shortest_altitude = HUGE_VAL;
  q.smallest_angle = 180;
  const std::vector<Point> &p = mesh.points;
  for (const Triangle &t : mesh.triangles) {
    double length[3];
    for (int i = 0; i < 3; ++i) {
      const Point &a = p[t[(i + 1) % 3]], &b = p[t[(i + 2) % 3]];
      length[i] = std::hypot(b.x - a.x, b.y - a.y);
    }
    const Point &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
    const double area = 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    const double edge_max = std::max({length[0], length[1], length[2]});
    const double edge_min = std::min({length[0], length[1], length[2]});
    const double altitude = 2 * area / edge_max;
    const double ratio = altitude > 0 ? edge_max / altitude : HUGE_VAL;
    q.smallest_area = std::min(q.smallest_area, area);
    q.largest_area = std::max(q.largest_area, area);
    q.shortest_edge = std::min(q.shortest_edge, edge_min);
    q.longest_edge = std::max(q.longest_edge, edge_max);
    q.shortest_altitude = std::min(q.shortest_altitude, altitude);
    q.largest_aspect_ratio = std::max(q.largest_aspect_ratio, ratio);
    int bin = 0;
    while (bin < kRatioCount - 1 && ratio >= kRatioBins[bin])
      ++bin;
    ++q.aspect_ratio_histogram[bin];
    for (int i = 0; i < 3; ++i) { // angle at vertex i, opposite edge i
      const double u = length[(i + 1) % 3], v = length[(i + 2) % 3], w = length[i];
      const double cosine = std::clamp((u * u + v * v - w * w) / (2 * u * v), -1.0, 1.0);
      const double angle = std::acos(cosine) * 180 / kPi;
      q.smallest_angle = std::min(q.smallest_angle, angle);
      q.largest_angle = std::max(q.largest_angle, angle);
      ++q.angle_histogram[std::min(17, static_cast<int>(angle / 10))];
    }
  }
  return q;
}

std::string format_quality(const QualityStatistics &q) {
  if (q.triangles == 0)
    return "";
  std::string out;
  char line[160];
  auto add = [&](const char *format, auto... values) {
    std::snprintf(line, sizeof line, format, values...);
    out += line;
  };
  add("\nMesh quality statistics:\n\n");
  add("  Smallest area: %16.5g   |  Largest area: %16.5g\n", q.smallest_area, q.largest_area);
  add("  Shortest edge: %16.5g   |  Longest edge: %16.5g\n", q.shortest_edge, q.longest_edge);
  add("  Shortest altitude: %12.5g   |  Largest aspect ratio: %8.5g\n\n", q.shortest_altitude,
      q.largest_aspect_ratio);
  add("  Triangle aspect ratio histogram:\n");
  for (int row = 0; row < 8; ++row) {
    const int left = row, right = row + 8;
    char upper[16] = "";
    if (right < kRatioCount - 1)
      std::snprintf(upper, sizeof upper, "%g", kRatioBins[right]);
    add("  %6.6g - %-6.6g    :  %8ld    | %6.6g - %-6s     :  %8ld\n",
        left == 0 ? 1.1547 : kRatioBins[left - 1], kRatioBins[left], q.aspect_ratio_histogram[left],
        kRatioBins[right - 1], upper, q.aspect_ratio_histogram[right]);
  }
  add("  (Aspect ratio is longest edge divided by shortest altitude)\n\n");
  add("  Smallest angle: %15.5g   |  Largest angle: %15.5g\n\n", q.smallest_angle, q.largest_angle);
  add("  Angle histogram:\n");
  for (int row = 0; row < 9; ++row)
    add("    %3d - %3d degrees:  %8ld    |    %3d - %3d degrees:  %8ld\n", row * 10, row * 10 + 10,
        q.angle_histogram[row], row * 10 + 90, row * 10 + 100, q.angle_histogram[row + 9]);
  return out;
}

} // namespace clmesh
