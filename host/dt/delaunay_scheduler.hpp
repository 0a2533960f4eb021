// clmesh — the GPU-DT scheduler: owns the device mesh and the phase objects,
// runs Phases 1, 4 and 5, and hands the resident mesh to later phases (CDT).
#pragma once

#include "dt/flipping.hpp"
#include "dt/mesh_output.hpp"
#include "dt/missing_point_insertion.hpp"
#include "dt/voronoi_banding.hpp"

#include "dt/delaunay.hpp"

#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace clmesh {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Lower-left corner and side of the square around the points (non-empty):
// the digital Voronoi texture's, and the cells of refinement's triangle order.
std::pair<Point, double> bounding_square(const std::vector<Point> &points);

// Charges wall time to named phases, waiting for the device at each boundary.
// Adds `seconds` to phase `name` of `stats` (a new phase at the end).
void add_phase_time(DelaunayStats &stats, const std::string &name, double seconds);

class PhaseTimer {
public:
  PhaseTimer(Device &device, DelaunayStats &stats) : device_(device), stats_(stats) {}
  void charge(const std::string &name);

private:
  Device &device_;
  DelaunayStats &stats_;
  Clock::time_point last_ = Clock::now();
};

class DelaunayScheduler {
public:
  // Checks the points and builds the programs; the compute clock starts here.
  // extra_points: room for points added after the triangulation (insert_points).
  // part_starts (packed meshes, delaunay_packed): the points are several
  // point sets, part k from part_starts[k] to part_starts[k + 1] (the last
  // entry: points.size()), none of them collinear; each is triangulated
  // apart, in the same arrays and launches (empty: one set).
  DelaunayScheduler(Device &device, const std::vector<Point> &points,
                    const DelaunayOptions &options, DelaunayStats &stats,
                    std::size_t extra_points = 0, std::vector<std::size_t> part_starts = {});
  ~DelaunayScheduler();

  // Phases 1-5; false when all points are collinear (no triangle).
  bool triangulate();
  // In place of triangulate(), for a given mesh (-r) whose triangles use
  // every point: its triangles (input numbering, counter-clockwise) as the
  // first mesh, `links[3 t + i]` the link ((triangle << 2) | edge) across
  // the edge opposite corner i of triangle t, -1 on the boundary, where a
  // ghost closes each boundary edge. No flip: the mesh need not be
  // Delaunay. False, with nothing on the device, unless the mesh is a disk
  // whose outline is a simple polygon (the caller then triangulates).
  bool take_triangles(const std::vector<Triangle> &triangles, const std::vector<cl_int> &links);
  // Inserts new points (numbered after every earlier one, in the device and
  // in the output), each walking from the given triangle, and restores the
  // (constrained) Delaunay property; the mesh grows when its room runs short.
  // Returns their device numbers, or the number of the point already there
  // for one that coincides with it.
  std::vector<int32_t> insert_points(const std::vector<Point> &added,
                                     const std::vector<int32_t> &start_triangles);

  // Inserts the points point_count .. point_count + count - 1, already on the
  // device with their start triangles in location[], and restores the
  // Delaunay property. Returns how many coincided with a vertex already there.
  std::size_t insert_appended(std::size_t count);

  // Makes room for `extra_points` more points; the phase objects that size
  // their lists by the mesh are built again when next needed.
  void grow(std::size_t extra_points);

  // Flips every triangle until locally (constrained) Delaunay; false when
  // `max_passes` passes (-1: no limit) did not finish.
  bool flip_all(FlipCounts &counts, const std::string &phase = Flipping::kPhase,
                long max_passes = -1);

  // Flips the triangles whose slot is flagged (flags[t] != 0) until every
  // edge they reach is locally (constrained) Delaunay.
  void flip_flagged(const DeviceArray<cl_int> &flags, FlipCounts &counts, const std::string &phase);

  // Downloads the real triangles not flagged in `removed` (per slot), with
  // the per-slot `label` of each in `labels` when given; the device mesh is
  // released (mesh() is not to be used after).
  void download(DelaunayResult &result, const DeviceArray<cl_int> *removed = nullptr,
                const DeviceArray<cl_int> *label = nullptr, std::vector<int32_t> *labels = nullptr);
  void download_collinear(DelaunayResult &result);

  // Later flips keep the boundary fixed (Flipping::set_fixed_boundary).
  void fix_boundary();
  // Phase 5's lists go until a flip needs them again (refinement flips by
  // its own phase): memory for the phases that follow.
  void release_flipping() { flipping_.reset(); }

  Device &device() { return device_; }
  DeviceMesh &mesh() { return *mesh_; }
  PrefixScan &scan() { return *scan_; }
  PhaseTimer &timer() { return *timer_; }
  int &stamp() { return stamp_; }
  DelaunayStats &stats() { return stats_; }
  int32_t device_point(int32_t input_index) const { return device_id_[input_index]; }
  const std::vector<int32_t> &original_ids() const { return original_id_; }

private:
  // Rounds of Phases 1-3 before the hull fan is used instead.
  static constexpr int kConstructionRounds = 12;
  // Sites left out in a round that did not cut the previous round's count by
  // a quarter: more than this many, and the rounds stop (from the third on;
  // whatever their number when two rounds did not cut it by a quarter).
  static constexpr long kStalledSites = 64;

  // The Voronoi texture's side: --grid, else VoronoiBanding::choose_grid.
  int texture_side(Point low, double span) const;

  // The missing points of a first triangulation with few triangles (a hull
  // fan, a clustered input's few sites), inserted level after level, each
  // about kLevelRatio times the points of the one before (a biased
  // randomized insertion order, by their Hilbert order): a coarse level's
  // points spread over the few large triangles, and each later point starts
  // its walk near where a coarser one was inserted (its anchor). Inserted
  // all at once, every round would move every point still waiting from the
  // triangle just split to one of its children, round after round.
  struct PointLevel {
    std::vector<cl_int> points, anchors; // anchors: none in the first level
    void swap(PointLevel &other) {
      points.swap(other.points);
      anchors.swap(other.anchors);
    }
  };
  using PointLevels = std::vector<PointLevel>;
  static constexpr std::size_t kLevelRatio = 16, kCoarsestLevel = 4096;
  // Whether `points` missing from a mesh of `triangles` go in levels.
  static bool worth_levels(std::size_t points, std::size_t triangles);
  // `points` (ascending, so in Hilbert order) as levels, coarsest first.
  static PointLevels point_levels(std::vector<cl_int> points, std::size_t triangles);
  // Phases 1-3: the first triangulation from the digital Voronoi diagram,
  // flipped to Delaunay, and the missing points given to `insertion` (the
  // first level; the others in `levels`, when worth_levels). False
  // (the mesh to be rebuilt from the hull fan) when that did not succeed.
  bool construct_from_voronoi(MissingPointInsertion &insertion, PointLevels &levels);
  // Phase 4 in conflict-free rounds, each followed by Phase 5 flipping so
  // that the next round's walks run in a Delaunay triangulation, until
  // `insertion` has no point left. Returns the rounds.
  long insert_in_rounds(MissingPointInsertion &insertion);
  // Phase 5, built on first use after the mesh was made or grew.
  Flipping &flipping();
  // Several point sets in one mesh: the hull fan builds the first
  // triangulation, one fan a set.
  bool packed() const { return part_starts_.size() > 2; }
  // visit(first, points) for each set: its first input index and a copy of
  // its points (the whole input once when not packed).
  template <class Visit> void for_each_part(const Visit &visit) const;
  // The device mesh with the points in Hilbert order (device_id_,
  // original_id_), no triangle yet.
  void upload_points();

  Device &device_;
  const std::vector<Point> &points_;
  DelaunayOptions options_;
  std::size_t extra_points_;
  DelaunayStats &stats_;
  std::vector<std::size_t> part_starts_;
  Clock::time_point start_;
  std::unique_ptr<PhaseTimer> timer_;
  std::unique_ptr<DeviceMesh> mesh_;
  std::unique_ptr<PrefixScan> scan_;
  std::unique_ptr<Flipping> flipping_; // null until needed (flipping())
  bool fixed_boundary_ = false;
  std::vector<int32_t> device_id_;   // input index -> device point
  std::vector<int32_t> original_id_; // device point -> input index
  std::vector<int32_t> voronoi_;
  FlipCounts flips_;
  int stamp_ = 1;
};

} // namespace clmesh
