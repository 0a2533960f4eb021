#include "refine/size_bound.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace clmesh {

namespace {
const char *kFile = "size_bound.cl";
// Background triangles per cell of a grid that only the walks' misses read
// (-r's .area): a coarser grid costs less to build (each triangle is listed
// in fewer cells) and finds the same triangle, the one holding the point.
constexpr double kTrianglesPerWalkedCell = 4;
} // namespace

SizeBound::SizeBound(Device &device, DeviceMesh &mesh, const SizeField *field,
                     const SizeField *areas, const std::vector<cl_int> *areas_across,
                     const Unsuitable *unsuitable, bool keep_regions)
    : device_(device), mesh_(mesh), unsuitable_(unsuitable), keep_regions_(keep_regions),
      evaluate_(device.kernel(kFile, "evaluate_size_field", kPhase)),
      gather_(device.kernel(kFile, "gather_corners", kPhase)),
      scatter_(device.kernel(kFile, "scatter_bounds", kPhase)),
      bound_(device, mesh.triangle_capacity), no_list_(device, 1) {
  // The bounds of the slots that come into use are set before any search
  // reads them (update): the pages past those in use stay untouched.
  bound_.fill(device_, -1, fill_ahead(mesh.triangle_count, mesh.triangle_capacity));
  if (field)
    backgrounds_.emplace_back(device_, *field, nullptr);
  if (areas)
    backgrounds_.emplace_back(device_, *areas, areas_across);
}

SizeBound::Background::Background(Device &device, const SizeField &field,
                                  const std::vector<cl_int> *neighbours)
    : per_triangle(neighbours != nullptr) {
  std::vector<cl_double2> points;
  double low_x = HUGE_VAL, low_y = HUGE_VAL, high_x = -HUGE_VAL, high_y = -HUGE_VAL;
  for (const Point &p : field.points) {
    points.push_back({{p.x, p.y}});
    low_x = std::min(low_x, p.x);
    low_y = std::min(low_y, p.y);
    high_x = std::max(high_x, p.x);
    high_y = std::max(high_y, p.y);
  }
  // About one cell per background triangle; with walks, which find most
  // triangles before any cell is read, one per kTrianglesPerWalkedCell.
  const double per_cell = neighbours ? kTrianglesPerWalkedCell : 1.0;
  const auto side = static_cast<int>(std::clamp(
      std::ceil(std::sqrt(static_cast<double>(field.triangles.size()) / per_cell)), 1.0, 2048.0));
  columns = rows = side;
  const double width = high_x > low_x ? high_x - low_x : 1,
               height = high_y > low_y ? high_y - low_y : 1;
  grid = {{low_x, low_y, columns / width, rows / height}};
  auto column = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - low_x) * grid.s[2])), 0, columns - 1);
  };
  auto row = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - low_y) * grid.s[3])), 0, rows - 1);
  };
  // Each cell's triangles: those whose box meets it, in order, in rows
  // (own_start, own): counted, then placed.
  const std::size_t cells = static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
  // Each triangle's box in cells (first and last row and column; at most
  // 2048 of each), from one pass over its corners.
  struct CellBox {
    uint16_t row0, row1, column0, column1;
  };
  std::vector<CellBox> boxes(field.triangles.size());
  for (std::size_t k = 0; k < field.triangles.size(); ++k) {
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
    for (int32_t v : field.triangles[k]) {
      x0 = std::min(x0, field.points[v].x);
      y0 = std::min(y0, field.points[v].y);
      x1 = std::max(x1, field.points[v].x);
      y1 = std::max(y1, field.points[v].y);
    }
    boxes[k] = {static_cast<uint16_t>(row(y0)), static_cast<uint16_t>(row(y1)),
                static_cast<uint16_t>(column(x0)), static_cast<uint16_t>(column(x1))};
  }
  auto for_each_cell = [&](const CellBox &box, auto &&visit) {
    for (std::size_t r = box.row0; r <= box.row1; ++r)
      for (std::size_t c = box.column0; c <= box.column1; ++c)
        visit(r * static_cast<std::size_t>(columns) + c);
  };
  std::vector<cl_int> own_start(cells + 1, 0);
  for (const CellBox &box : boxes)
    for_each_cell(box, [&](std::size_t cell) { ++own_start[cell + 1]; });
  for (std::size_t c = 0; c < cells; ++c)
    own_start[c + 1] += own_start[c];
  std::vector<cl_int> own(static_cast<std::size_t>(own_start[cells])), cursor(own_start);
  for (std::size_t k = 0; k < boxes.size(); ++k)
    for_each_cell(boxes[k], [&](std::size_t cell) {
      own[static_cast<std::size_t>(cursor[cell]++)] = static_cast<cl_int>(k);
    });
  std::vector<CellBox>().swap(boxes);
  std::vector<cl_int> corners;
  corners.reserve(3 * field.triangles.size());
  for (const Triangle &t : field.triangles)
    corners.insert(corners.end(), t.begin(), t.end());
  std::vector<cl_int>().swap(cursor);
  // An empty cell takes the triangles of the nearest cell that has some
  // (breadth first over the grid, in cell order).
  std::vector<long> source(cells, -1);
  std::deque<long> queue;
  for (std::size_t c = 0; c < cells; ++c)
    if (own_start[c + 1] > own_start[c]) {
      source[c] = static_cast<long>(c);
      queue.push_back(static_cast<long>(c));
    }
  while (!queue.empty()) {
    const long c = queue.front();
    queue.pop_front();
    const long r = c / columns, k = c % columns;
    const long around[4][2] = {{r - 1, k}, {r + 1, k}, {r, k - 1}, {r, k + 1}};
    for (const auto &[rr, kk] : around)
      if (rr >= 0 && rr < rows && kk >= 0 && kk < columns) {
        const long next = rr * columns + kk;
        if (source[static_cast<std::size_t>(next)] < 0) {
          source[static_cast<std::size_t>(next)] = source[static_cast<std::size_t>(c)];
          queue.push_back(next);
        }
      }
  }
  std::vector<cl_int> start(cells + 1, 0), entries;
  entries.reserve(own.size());
  for (std::size_t c = 0; c < cells; ++c) {
    const auto from = static_cast<std::size_t>(source[c]);
    entries.insert(entries.end(), own.begin() + own_start[from], own.begin() + own_start[from + 1]);
    start[c + 1] = static_cast<cl_int>(entries.size());
  }
  const std::vector<double> &values = field.area;
  for (const double v : values)
    if (v > 0 && (least == 0 || v < least))
      least = v;
  this->points = DeviceArray<cl_double2>(device, points.size());
  this->points.upload(device, points);
  value = DeviceArray<cl_double>(device, values.size());
  value.upload(device, std::vector<cl_double>(values.begin(), values.end()));
  triangles = DeviceArray<cl_int>(device, corners.size());
  triangles.upload(device, corners);
  std::vector<cl_int>().swap(corners);
  if (neighbours) { // a walk from the given triangle a slot descends from
    across = DeviceArray<cl_int>(device, neighbours->size());
    across.upload(device, *neighbours);
  } else {
    across = DeviceArray<cl_int>(device, 1);
  }
  cell_start = DeviceArray<cl_int>(device, start.size());
  cell_start.upload(device, start);
  cell_entry = DeviceArray<cl_int>(device, entries.size());
  cell_entry.upload(device, entries);
}

void SizeBound::fit() {
  if (bound_.size() < mesh_.triangle_capacity)
    bound_ = bound_.grown(device_, mesh_.triangle_capacity, -1);
}

void SizeBound::update(const DeviceList<cl_int> *changed) {
  const bool use_list = changed != nullptr;
  const std::size_t n = use_list ? changed->size : mesh_.triangle_count;
  if (n == 0)
    return;
  const cl::Buffer &list = use_list ? changed->items.buffer() : no_list_.buffer();
  for (std::size_t b = 0; b < backgrounds_.size(); ++b)
    evaluate(backgrounds_[b], list, use_list, n, b > 0);
  if (!unsuitable_)
    return;
  DeviceArray<cl_double2> corners(device_, 3 * n);
  set_args(gather_, mesh_.points.buffer(), mesh_.tri_vertex.buffer(), list,
           static_cast<cl_int>(use_list), corners.buffer(), static_cast<cl_int>(n));
  launch(device_, gather_, n, kPhase);
  const std::vector<cl_double2> at = corners.download(device_, 3 * n);
  std::vector<cl_double> value(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const Point a{at[3 * i].s[0], at[3 * i].s[1]}, b{at[3 * i + 1].s[0], at[3 * i + 1].s[1]},
        c{at[3 * i + 2].s[0], at[3 * i + 2].s[1]};
    if (std::isnan(a.x))
      continue;
    const double area = std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / 2;
    if ((*unsuitable_)(a, b, c, area))
      value[i] = area / 2;
  }
  DeviceArray<cl_double> values(device_, n);
  values.upload(device_, value);
  set_args(scatter_, list, static_cast<cl_int>(use_list), values.buffer(),
           static_cast<cl_int>(!backgrounds_.empty()), bound_.buffer(), static_cast<cl_int>(n));
  launch(device_, scatter_, n, kPhase);
}

void SizeBound::evaluate(const Background &background, const cl::Buffer &list, bool use_list,
                         std::size_t n, bool combine) {
  const bool hinted = background.per_triangle && mesh_.has_regions;
  set_args(evaluate_, mesh_.points.buffer(), mesh_.tri_vertex.buffer(), list,
           static_cast<cl_int>(use_list), background.points.buffer(), background.value.buffer(),
           static_cast<cl_int>(background.per_triangle), background.triangles.buffer(),
           background.across.buffer(), background.cell_start.buffer(),
           background.cell_entry.buffer(), background.grid, static_cast<cl_int>(background.columns),
           static_cast<cl_int>(background.rows), mesh_.tri_region.buffer(),
           static_cast<cl_int>(hinted), static_cast<cl_int>(hinted && !keep_regions_),
           static_cast<cl_int>(combine), background.least, bound_.buffer(), static_cast<cl_int>(n));
  launch(device_, evaluate_, n, kPhase);
}

} // namespace clmesh
