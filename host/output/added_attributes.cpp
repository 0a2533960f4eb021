#include "output/added_attributes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace clmesh {

std::vector<double> interpolate_along(const std::vector<Point> &ends,
                                      const std::vector<double> &attributes, int count,
                                      const std::vector<Segment> &segments,
                                      const std::vector<Point> &points) {
  const auto k = static_cast<std::size_t>(count);
  std::vector<double> result;
  result.reserve(points.size() * k);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto a = static_cast<std::size_t>(segments[i].a),
               b = static_cast<std::size_t>(segments[i].b);
    const double dx = ends[b].x - ends[a].x, dy = ends[b].y - ends[a].y,
                 length2 = dx * dx + dy * dy;
    const double t =
        length2 > 0 ? std::clamp(((points[i].x - ends[a].x) * dx + (points[i].y - ends[a].y) * dy) /
                                     length2,
                                 0.0, 1.0)
                    : 0.0;
    for (std::size_t j = 0; j < k; ++j)
      result.push_back(attributes[k * a + j] + t * (attributes[k * b + j] - attributes[k * a + j]));
  }
  return result;
}

namespace {

double orientation(const Point &a, const Point &b, const Point &c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// The triangles of a field bucketed by the grid cells their bounding boxes
// meet, about one triangle a cell (compressed rows).
class TriangleGrid {
public:
  explicit TriangleGrid(const AttributeField &field) : field_(field) {
    low_ = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    Point high{-low_.x, -low_.y};
    for (const Triangle &t : field.triangles)
      for (const int32_t v : t) {
        const Point &p = field.points[static_cast<std::size_t>(v)];
        low_ = {std::min(low_.x, p.x), std::min(low_.y, p.y)};
        high = {std::max(high.x, p.x), std::max(high.y, p.y)};
      }
    side_ = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(field.triangles.size()))), 1,
                       4096);
    cell_ = {(high.x - low_.x) / side_, (high.y - low_.y) / side_};
    start_.assign(static_cast<std::size_t>(side_) * side_ + 1, 0);
    for_each_cover([&](std::size_t cell, std::size_t) { ++start_[cell + 1]; });
    for (std::size_t c = 1; c < start_.size(); ++c)
      start_[c] += start_[c - 1];
    entries_.resize(start_.back());
    std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
    for_each_cover([&](std::size_t cell, std::size_t t) { entries_[next[cell]++] = t; });
  }

  // The triangle holding p and its barycentric coordinates (clamped to the
  // triangle when p lies outside every one: the nearest by the smallest
  // coordinate); false when the field has no usable triangle.
  bool locate(const Point &p, std::size_t &triangle, double weights[3]) const {
    if (field_.triangles.empty())
      return false;
    const int ci = cell_of(p.x, low_.x, cell_.x), cj = cell_of(p.y, low_.y, cell_.y);
    double best = -std::numeric_limits<double>::infinity();
    for (int ring = 0; ring <= side_; ++ring) {
      for (int j = cj - ring; j <= cj + ring; ++j)
        for (int i = ci - ring; i <= ci + ring; ++i) {
          const bool on_ring = std::max(std::abs(i - ci), std::abs(j - cj)) == ring;
          if (!on_ring || i < 0 || j < 0 || i >= side_ || j >= side_)
            continue;
          const std::size_t cell = static_cast<std::size_t>(j) * side_ + i;
          for (std::size_t e = start_[cell]; e < start_[cell + 1]; ++e) {
            double w[3];
            const double smallest = barycentric(entries_[e], p, w);
            if (smallest > best) {
              best = smallest;
              triangle = entries_[e];
              std::copy(w, w + 3, weights);
            }
          }
        }
      if (best >= -1e-9) // inside (up to rounding): no farther cell holds it better
        break;
    }
    if (best == -std::numeric_limits<double>::infinity())
      return false;
    double sum = 0;
    for (int i = 0; i < 3; ++i)
      sum += weights[i] = std::max(weights[i], 0.0);
    for (int i = 0; i < 3; ++i)
      weights[i] /= sum;
    return true;
  }

private:
  int cell_of(double x, double low, double size) const {
    if (!(size > 0))
      return 0;
    return std::clamp(static_cast<int>(std::floor((x - low) / size)), 0, side_ - 1);
  }
  template <typename Visit> void for_each_cover(Visit visit) const {
    for (std::size_t t = 0; t < field_.triangles.size(); ++t) {
      const Triangle &tri = field_.triangles[t];
      const Point &a = field_.points[static_cast<std::size_t>(tri[0])],
                  &b = field_.points[static_cast<std::size_t>(tri[1])],
                  &c = field_.points[static_cast<std::size_t>(tri[2])];
      const int i0 = cell_of(std::min({a.x, b.x, c.x}), low_.x, cell_.x),
                i1 = cell_of(std::max({a.x, b.x, c.x}), low_.x, cell_.x),
                j0 = cell_of(std::min({a.y, b.y, c.y}), low_.y, cell_.y),
                j1 = cell_of(std::max({a.y, b.y, c.y}), low_.y, cell_.y);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
          visit(static_cast<std::size_t>(j) * side_ + i, t);
    }
  }
  // The barycentric coordinates of p in triangle t, and the smallest of them
  // (-infinity for a flat triangle).
  double barycentric(std::size_t t, const Point &p, double w[3]) const {
    const Triangle &tri = field_.triangles[t];
    const Point &a = field_.points[static_cast<std::size_t>(tri[0])],
                &b = field_.points[static_cast<std::size_t>(tri[1])],
                &c = field_.points[static_cast<std::size_t>(tri[2])];
    const double area = orientation(a, b, c);
    if (area == 0 || !std::isfinite(area))
      return -std::numeric_limits<double>::infinity();
    w[0] = orientation(p, b, c) / area;
    w[1] = orientation(a, p, c) / area;
    w[2] = 1 - w[0] - w[1];
    return std::min({w[0], w[1], w[2]});
  }

  const AttributeField &field_;
  Point low_{};
  Point cell_{};
  int side_ = 1;
  std::vector<std::size_t> start_, entries_;
};

} // namespace

std::vector<double> interpolate_attributes(const AttributeField &field, int count,
                                           const std::vector<Point> &queries) {
  const auto k = static_cast<std::size_t>(count);
  std::vector<double> result(queries.size() * k, 0.0);
  if (k == 0 || queries.empty())
    return result;
  const TriangleGrid grid(field);
  for (std::size_t q = 0; q < queries.size(); ++q) {
    std::size_t t = 0;
    double w[3];
    if (!grid.locate(queries[q], t, w))
      continue;
    for (int c = 0; c < 3; ++c) {
      const auto v = static_cast<std::size_t>(field.triangles[t][c]);
      for (std::size_t i = 0; i < k; ++i)
        result[q * k + i] += w[c] * field.attributes[v * k + i];
    }
  }
  return result;
}

} // namespace clmesh
