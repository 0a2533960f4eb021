// clmesh — GPU-QM step 3: flip-flop, Delaunay flips together with the
// deletion of redundant Steiner points (thesis §3.3.2 Algorithms 3.1 and 3.2,
// §3.5 for GPU-QM-V's orthogonal test), after the boundary routine of §3.4.1
// (HullEncroachment). Kernels: cl/flip_flop.cl.
#pragma once

#include "refine/hull_encroachment.hpp"
#include "refine/triangle_claims.hpp"
#include "runtime/scratch_pool.hpp"

#include "clmesh/geometry.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace clmesh {

struct FlipFlopCounts {
  long delaunay_flips = 0;
  long non_delaunay_flips = 0; // flops and 3-1 flips
  long deleted = 0;            // redundant points deleted
  long midpoints = 0;          // hull midpoints inserted (none is ever deleted)
  long kept_redundant = 0;     // redundant points in degenerate stars, kept
  long passes = 0;
  long exact_checks = 0;
};

// The coordinates of every Steiner point deleted as redundant, kept on the
// device until the end (thesis §3.7 counts the points inserted more than
// once: deleted as redundant, then inserted again).
struct DeletionLog {
  DeviceList<cl_double2> coordinates;
  // A point was inserted more than once when its coordinates were deleted
  // twice, or deleted and are among the `survivors` (Steiner points of the
  // final mesh).
  long points_inserted_more_than_once(Device &device, const std::vector<Point> &survivors) const;
};

class FlipFlop {
public:
  static constexpr const char *kPhase = "flipflop_deletion";

  // orthogonal_test: GPU-QM-V (delete one of two connected new points only
  // when they are less than orthogonal) instead of GPU-QM (always).
  // group_pass_limit: Tuning::group_pass_limit.
  // The lists of the passes are those of `pool` (scratch_lists, from
  // kStar on): no other step runs while run() does.
  FlipFlop(Device &device, DeviceMesh &mesh, PrefixScan &scan, const ScratchPool &pool,
           TriangleClaims &removal_claims, bool orthogonal_test, std::size_t group_pass_limit);
  // The sizes in bytes of the lists it takes from a ScratchPool.
  static std::vector<std::size_t> scratch_lists(const DeviceMesh &mesh);

  // Step 3 of one iteration: from the triangles `changed` (n entries, -1
  // ignored), the points new_points[0 .. m) having just been inserted.
  // Returns when every edge is locally Delaunay and no redundant point is left.
  // Every triangle it rewrites is appended to `rewritten`, every point it
  // deletes to `deleted`.
  void run(const DeviceArray<cl_int> &changed, std::size_t n, const DeviceArray<cl_int> &new_points,
           std::size_t m, int &stamp, DeviceList<cl_int> &rewritten, DeletionLog &deleted,
           FlipFlopCounts &counts);
  // The most entries a list took in the last run.
  std::size_t entries_used() const { return run_entries_; }
  // After run: the boundary routine's lists keep the memory of the entries
  // the run took and give the rest back (HullEncroachment::trim_lists).
  void trim_lists();

private:
  // The lists in the pool.
  enum List {
    kStar,
    kActive,
    kNextActive,
    kCount,
    kOffset,
    kExactList,
    kOperation,
    kProposal,
    kApplied,
    kStarSize,
    kStarOffset,
    kTracked
  };
  // What a pass leaves: `next` entries in next_active_ (its results and
  // losers); when stars were looked for, the next list (those and the
  // redundant points' stars, without repeats) in active_, `length` long.
  struct PassResult {
    std::size_t next = 0;
    int marked = 0; // points marked redundant in the pass
    bool looked_for_stars = false;
    std::size_t stars = 0;
    std::size_t length = 0;
  };
  // Short lists take one work-group for pass after pass
  // (flipflop_passes_in_group) when the points to track are few too. Either
  // way the pass's entries in next_active_ are appended to `rewritten`.
  static constexpr std::size_t kTrackedInGroup = 8192;
  PassResult pass_by_kernels(std::size_t n, cl_int any_redundant, cl_int stamp,
                             DeviceList<cl_int> &rewritten, FlipFlopCounts &counts);
  // Passes from pass `pass` of the run on, by one work-group, while the
  // active list (n entries) stays short; advances pass and stamp by the
  // passes it made and returns the active list's length. When they empty
  // the list, they also end the iteration's points (new_points[0 .. m),
  // finish_iteration) and bring back the totals.
  std::size_t passes_in_group(std::size_t n, long &pass, int &stamp,
                              const DeviceArray<cl_int> &new_points, std::size_t m,
                              DeviceList<cl_int> &rewritten, FlipFlopCounts &counts);
  void propose(cl_int items, cl_int any_redundant, cl_int *uncertain);
  // Sets FlipFlop's buffers as CLM_FLIPFLOP_PARAMS (cl/flip_flop.cl) from
  // argument `first` on; returns the index after them.
  cl_uint bind_lists(cl::Kernel &kernel, cl_uint first) const;
  // Sets a kernel's arguments: CLM_MESH_PARAMS, CLM_FLIPFLOP_PARAMS, then `scalars`.
  template <typename... Scalars> void bind(cl::Kernel &kernel, const Scalars &...scalars) {
    set_args_from(kernel, bind_lists(kernel, mesh_.bind(kernel, 0)), scalars...);
  }
  // Tracks the redundant points, lists their stars after the pass's `next`
  // entries (*stars of them) and removes repeats into active_; returns the length.
  std::size_t find_stars(int stamp, std::size_t next, std::size_t *stars);

  Device &device_;
  DeviceMesh &mesh_;
  PrefixScan &scan_;
  HullEncroachment encroachment_;
  cl_int orthogonal_test_;
  std::size_t group_pass_limit_;
  std::size_t pass_group_ = 1; // flipflop_passes_in_group's work-group size (Device::single_group)
  std::size_t tracked_n_ = 0;
  bool tracked_known_ = true; // else the old points of tracked_n_ are on the device
  // Makes tracked_n_ known (m: the new points), reading the boundary
  // routine's count when the passes have not brought it back.
  void know_tracked(std::size_t m);
  bool redundant_left_ = false;
  cl::Kernel propose_, propose_exact_, apply_, relink_, gather_next_, track_, emit_, finish_,
      keep_stuck_, passes_in_group_, log_deleted_;
  DeviceArray<cl_int> active_, next_active_, exact_list_, operation_, proposal_, star_, applied_,
      count_, offset_;
  DeviceArray<cl_int> redundant_mark_, redundant_anchor_, star_size_, star_offset_, tracked_;
  std::size_t marks_filled_ = 0; // redundant_mark_ is set (0) below this point
  std::size_t run_entries_ = 0;  // the most entries of a list in the last run
  DeviceArray<cl_int> marked_count_, exact_count_;
  // The deletion log's length as log_deleted_points counts it, and as the
  // host last set or advanced it (SIZE_MAX: never set).
  DeviceArray<cl_int> logged_;
  std::size_t logged_size_ = SIZE_MAX;
  // flipflop_passes_in_group's result (see the kernel).
  static constexpr std::size_t kGroupResults = 16;
  DeviceArray<cl_int> pass_result_;
  // The running totals of the kernels (CLM_TOTAL_* in cl/flip_flop.cl):
  // Delaunay flips, flops, removals, surviving midpoints, points kept, then
  // (kFailures) stars lost; those before it as last read.
  static constexpr std::size_t kFailures = 5, kTotals = kFailures + 1;
  DeviceArray<cl_int> totals_;
  std::array<cl_int, kFailures> last_totals_{};
  // Whether the last passes in group ended the run, and the totals they read.
  bool finished_in_group_ = false;
  std::array<cl_int, kTotals> group_totals_{};
  // Per triangle slot: the smallest entry proposing a removal whose star's
  // smallest slot it is, which applies it (removal_claim in the kernels);
  // empty between passes. Shared with step 1's tie marks.
  TriangleClaims &removal_claim_;
};

} // namespace clmesh
