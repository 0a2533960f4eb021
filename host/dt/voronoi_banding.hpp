// clmesh — Phase 1 of GPU-DT: digital Voronoi diagram by parallel banding
// (thesis §4.1.2, [CTMT10]). Kernels: cl/voronoi_banding.cl.
#pragma once

#include "runtime/prefix_scan.hpp"

#include "clmesh/geometry.hpp"

#include <vector>

namespace clmesh {

class VoronoiBanding {
public:
  static constexpr const char *kPhase = "voronoi_banding";
  static constexpr int kMaxGrid = 8192;

  VoronoiBanding(Device &device, DeviceMesh &mesh, PrefixScan &scan);

  // A texture side suited to n points: the power of two nearest sqrt(n) / 2.5.
  static int default_grid(std::size_t n);
  // The grid for these points in the square [low, low + span]^2:
  // default_grid, or, when nearly every point has a pixel of its own at the
  // smallest power of two not below sqrt(n) (a lattice, or points as evenly
  // spread), that finer grid: Phases 1-3 then triangulate them all at once,
  // without the missing-point insertion whose flips a cocircular lattice
  // makes long.
  static int choose_grid(const std::vector<Point> &points, Point low, double span);

  // Maps the device points into a grid x grid texture over the square
  // [min, min + span]^2 and colours every pixel with its nearest site.
  // Points whose `site_state` is CLM_LEFT_OUT (cl/common.h) are no sites.
  // Returns how many points are not sites (missing points).
  std::size_t run(int grid, Point min, double span,
                  const DeviceArray<cl_int> *site_state = nullptr);

  // The diagram of the last run (grid * grid device point numbers) and the
  // pixel of every point.
  const DeviceArray<cl_int> &diagram() const { return voronoi_; }
  const DeviceArray<cl_int> &pixel_of() const { return pixel_of_; }

  // The diagram in the input numbering (-1: no site), for pictures.
  std::vector<int32_t> download_image();

private:
  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  cl::Kernel map_points_, claim_pixels_, clear_empty_, count_missing_, column_sweep_, row_colour_,
      renumber_;
  int grid_ = 0;
  DeviceArray<cl_int> site_of_pixel_, column_site_row_, stack_x_, stack_y_, voronoi_, pixel_of_,
      missing_, missing_offset_;
};

} // namespace clmesh
