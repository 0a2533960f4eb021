#include "dt/voronoi_banding.hpp"

#include <algorithm>
#include <cmath>

namespace clmesh {

namespace {
const char *kFile = "voronoi_banding.cl";
}

VoronoiBanding::VoronoiBanding(Device &device, DeviceMesh &mesh, PrefixScan &scan)
    : device_(device), mesh_(mesh), scan_(scan),
      map_points_(device.kernel(kFile, "map_points_to_pixels", kPhase)),
      claim_pixels_(device.kernel(kFile, "claim_pixels", kPhase)),
      clear_empty_(device.kernel(kFile, "clear_empty_pixels", kPhase)),
      count_missing_(device.kernel(kFile, "count_missing_points", kPhase)),
      column_sweep_(device.kernel(kFile, "column_sweep", kPhase)),
      row_colour_(device.kernel(kFile, "row_proximate_and_colour", kPhase)),
      renumber_(device.kernel(kFile, "voronoi_input_numbering", kPhase)) {}

int VoronoiBanding::default_grid(std::size_t n) {
  // Four to ten points per pixel: Phases 2 and 3 then build a coarse
  // triangulation of a fraction of the points in few rounds, and Phase 4
  // inserts the rest into it (on PoCL the fastest mix, from 100k to 10M
  // points): the power of two nearest to sqrt(n) / 2.5.
  const double target = std::log2(std::sqrt(static_cast<double>(n)) / 2.5);
  const int exponent = static_cast<int>(std::lround(std::max(4.0, target)));
  return std::min(kMaxGrid, 1 << std::min(exponent, 13));
}

int VoronoiBanding::choose_grid(const std::vector<Point> &points, Point low, double span) {
  const std::size_t n = points.size();
  const int coarse = default_grid(n);
  int fine = 2;
  while (fine < kMaxGrid && static_cast<double>(fine) * fine < static_cast<double>(n))
    fine *= 2;
  if (fine <= coarse || !(span > 0))
    return coarse;
  // The pixels of map_points_to_pixels (cl/voronoi_banding.cl); at most one
  // point in 64 may share its pixel.
  const double scale = fine / span;
  const std::size_t allowed = n / 64;
  std::vector<bool> taken(static_cast<std::size_t>(fine) * fine, false);
  std::size_t shared = 0;
  for (const Point &p : points) {
    const auto x = std::min(static_cast<int>((p.x - low.x) * scale), fine - 1);
    const auto y = std::min(static_cast<int>((p.y - low.y) * scale), fine - 1);
    const std::size_t pixel = static_cast<std::size_t>(y) * fine + x;
    if (taken[pixel] && ++shared > allowed)
      return coarse;
    taken[pixel] = true;
  }
  return fine;
}

std::size_t VoronoiBanding::run(int grid, Point min, double span,
                                const DeviceArray<cl_int> *site_state) {
  if (grid < 2 || grid > kMaxGrid)
    throw OptionError("--grid must be between 2 and " + std::to_string(kMaxGrid));
  const std::size_t pixels = static_cast<std::size_t>(grid) * grid;
  const std::size_t n = mesh_.point_count;
  if (grid != grid_) { // scratch kept between the rounds of Phases 2 and 3
    grid_ = grid;
    site_of_pixel_ = DeviceArray<cl_int>(device_, pixels);
    column_site_row_ = DeviceArray<cl_int>(device_, pixels);
    stack_x_ = DeviceArray<cl_int>(device_, pixels);
    stack_y_ = DeviceArray<cl_int>(device_, pixels);
    voronoi_ = DeviceArray<cl_int>(device_, pixels);
    pixel_of_ = DeviceArray<cl_int>(device_, n);
    missing_ = DeviceArray<cl_int>(device_, n);
    missing_offset_ = DeviceArray<cl_int>(device_, n);
  }
  const DeviceArray<cl_int> &site_of_pixel = site_of_pixel_, &column_site_row = column_site_row_,
                            &stack_x = stack_x_, &stack_y = stack_y_, &pixel_of = pixel_of_,
                            &missing = missing_, &missing_offset = missing_offset_;
  const DeviceArray<cl_int> &best_distance = column_site_row; // until the column sweep
  best_distance.fill(device_, 0x7fffffff, pixels);
  site_of_pixel.fill(device_, 0x7fffffff, pixels);
  const double scale = span > 0 ? grid / span : 0.0;
  const cl::Buffer &state = site_state ? site_state->buffer() : missing.buffer();
  const auto use_state = static_cast<cl_int>(site_state != nullptr);
  set_args(map_points_, mesh_.points.buffer(), state, use_state, pixel_of.buffer(),
           best_distance.buffer(), min.x, min.y, scale, static_cast<cl_int>(grid),
           static_cast<cl_int>(n));
  launch(device_, map_points_, n, kPhase);
  set_args(claim_pixels_, mesh_.points.buffer(), state, use_state, best_distance.buffer(),
           site_of_pixel.buffer(), min.x, min.y, scale, static_cast<cl_int>(grid),
           static_cast<cl_int>(n));
  launch(device_, claim_pixels_, n, kPhase);
  set_args(clear_empty_, site_of_pixel.buffer(), static_cast<cl_int>(pixels));
  launch(device_, clear_empty_, pixels, kPhase);
  set_args(count_missing_, pixel_of.buffer(), site_of_pixel.buffer(), missing.buffer(),
           static_cast<cl_int>(n));
  launch(device_, count_missing_, n, kPhase);
  const int missing_points = scan_.exclusive_scan(missing, missing_offset, n, kPhase);
  set_args(column_sweep_, site_of_pixel.buffer(), column_site_row.buffer(),
           static_cast<cl_int>(grid));
  launch(device_, column_sweep_, static_cast<std::size_t>(grid), kPhase);
  set_args(row_colour_, site_of_pixel.buffer(), column_site_row.buffer(), stack_x.buffer(),
           stack_y.buffer(), voronoi_.buffer(), static_cast<cl_int>(grid));
  launch(device_, row_colour_, static_cast<std::size_t>(grid), kPhase);
  return static_cast<std::size_t>(missing_points);
}

std::vector<int32_t> VoronoiBanding::download_image() {
  const std::size_t pixels = static_cast<std::size_t>(grid_) * grid_;
  DeviceArray<cl_int> image(device_, pixels);
  set_args(renumber_, voronoi_.buffer(), mesh_.original_id.buffer(), image.buffer(),
           static_cast<cl_int>(pixels));
  launch(device_, renumber_, pixels, kPhase);
  return image.download(device_, pixels);
}

} // namespace clmesh
