// clmesh — GPU-QM step 1: bad triangles, off-centers, boundary midpoints and
// the insertion filter (thesis §3.3.2, §3.4.1). Kernels: cl/offcenter_insertion.cl.
#pragma once

#include "refine/triangle_claims.hpp"
#include "runtime/prefix_scan.hpp"
#include "runtime/scratch_pool.hpp"

#include "clmesh/geometry.hpp"

#include <vector>

namespace clmesh {

class OffcenterInsertion {
public:
  static constexpr const char *kPhase = "offcenter_insertion";

  // filter_rings: how many rings of neighbouring triangles the insertion
  // filter looks at by priority (2 or 3); filter_distance_rings: how many
  // more it looks at for predicted dependent pairs (0 or 1; see
  // insertion_filter); filter_near: how near, in multiples of the
  // orthogonal distance, a better candidate within the rings must be to keep
  // one out (0: at any distance); parallel_midpoints: hull midpoints never
  // keep each other out; election_rings: a bad triangle sends a candidate only
  // when none within that many rings has a better priority (0: every one, the
  // thesis's way; see elect_candidates); carry_verdicts: a search keeps the
  // verdicts of the last search's bad triangles that are as it assessed them
  // (see find_bad_triangles); group_step_limit: Tuning::group_step_limit;
  // conforming (-D): a triangle whose
  // obtuse angle faces a subsegment or boundary edge is bad, and a point in a
  // subsegment's diametral circle splits it; protected_segments (-Y 1, -YY 2):
  // boundary edges (and subsegments) no point may split: a candidate that
  // encroaches on one goes in all the same, one beyond it is dropped, and a
  // bad triangle whose candidate lies beyond such an edge of its own is left;
  // inward: parts of the domain lie a hair apart, so a boundary edge's split
  // point that rounds beyond it is moved back inside (inside_edge);
  // region_areas: the maximum area of
  // each region of DeviceMesh::tri_region (<= 0: none; empty without regions);
  // size_bound: each triangle slot's own area bound (SizeBound; null: none).
  // The candidates' lists are those of `pool` (scratch_lists): no other step
  // runs from find_bad_triangles to append_survivors.
  OffcenterInsertion(Device &device, DeviceMesh &mesh, const ScratchPool &pool,
                     TriangleClaims &tie_marks, double min_angle, double max_area, int filter_rings,
                     int filter_distance_rings, double filter_near, bool parallel_midpoints,
                     int election_rings, bool carry_verdicts, std::size_t group_step_limit,
                     bool conforming, int protected_segments, bool inward,
                     const std::vector<double> &region_areas,
                     const DeviceArray<cl_double> *size_bound = nullptr);

  // Step 1, in this order. find_bad_triangles: the bad triangles; the first
  // search examines every slot; a later one the bad triangles of the last
  // search and the triangles listed in `changed` (rewritten since,
  // duplicates allowed; every slot when null). `stamp`: the mesh's next
  // modification stamp; a bad triangle of the last search that neither it
  // nor a neighbour its verdict depends on has been rewritten since keeps
  // that verdict (see find_bad_triangles in the kernels). A short search
  // elects too, in the same launch (step_one_in_group), and given
  // new_points, when some triangle is bad and the candidates are at most
  // `room`, places them as place_candidates(stamp, room, .., *new_points)
  // would, which then only returns the count. Returns how many are bad.
  std::size_t find_bad_triangles(PrefixScan &scan, const DeviceList<cl_int> *changed, int stamp,
                                 std::size_t room = 0,
                                 const DeviceArray<cl_int> *new_points = nullptr);
  // The bad triangles that send a candidate: all of them, or with an
  // election those that no better one within election_rings rings keeps
  // waiting (see elect_candidates). Returns how many; candidates() too.
  std::size_t elect_candidates(PrefixScan &scan);
  std::size_t candidates() const { return candidates_; }
  // Whether the last search placed its candidates too (see find_bad_triangles).
  bool placed() const { return placed_; }
  // Each candidate's off-center, or the hull midpoint where it falls outside
  // or encroaches the hull, and the triangle that contains it. `stamp`: the
  // mesh's next modification stamp; a triangle rewritten later has a larger
  // one.
  void locate_candidates(int stamp);
  // Whether locations since the last call (or since these steps were made)
  // dropped candidates beyond edges that cannot be split: their bad
  // triangles are then left out of the next search (stuck).
  bool stuck_since_last_asked();
  // The insertion filter: which candidates survive. Its marks stay until
  // append_survivors, which must follow, clears them.
  void filter_candidates();
  // Appends the survivors to the mesh's points (free slots first, then from
  // point_count on; they stay on the device) and lists them in new_points,
  // not inserted yet; the first `room` of them when more survived. Returns
  // how many were appended.
  std::size_t append_survivors(std::size_t room, PrefixScan &scan,
                               const DeviceArray<cl_int> &new_points);
  // locate_candidates, filter_candidates and append_survivors in turn; a
  // short list of candidates by one work-group in one launch
  // (place_candidates_in_group). Returns how many were appended.
  std::size_t place_candidates(int stamp, std::size_t room, PrefixScan &scan,
                               const DeviceArray<cl_int> &new_points);
  // The sizes in bytes of the lists it takes from a ScratchPool.
  static std::vector<std::size_t> scratch_lists(const DeviceMesh &mesh);
  // Triangles the last search examined: the most entries a list took.
  std::size_t entries_used() const { return searched_entries_; }
  // Whether a search ran: the first one examines every slot.
  bool searched() const { return searched_; }
  // Sets flags[t] (0 before) for every slot t a search over every slot might
  // find bad now: those the last search found bad or left stuck and those in
  // `changed` (rewritten since). The others are good.
  void flag_unsettled(const DeviceList<cl_int> &changed, const DeviceArray<cl_int> &flags);
  // The next search examines only the list it is given, as later searches
  // do: its caller lists every triangle that may be bad (flag_unsettled's,
  // in new steps for the mesh the triangles moved in).
  void skip_sweep() { searched_ = true; }

  // Once, on the Delaunay triangulation: flags the hull vertices, and among
  // them the input points at hull angles below the minimum angle. Bad
  // triangles whose smallest angle is at one of those cannot be mended and are
  // left alone; count_unfixable() counts them, with those left at small
  // angles between segments and, with -Y, beside protected edges.
  std::size_t flag_hull_vertices(); // returns how many are acute
  std::size_t count_unfixable();

  double lens() const { return lens_; }

private:
  // The lists in the pool.
  enum List {
    kCandidate,
    kRadius2,
    kKeep,
    kOffset,
    kListed,
    kOrigin,
    kContainer,
    kSplitEdge,
    kSurvive,
    kPriority
  };
  // find_bad_triangles and elect_candidates by one work-group in one launch
  // (a short search; changed: null for a sweep of every slot).
  std::size_t step_one_in_group(const DeviceList<cl_int> *changed, cl_int carried, int stamp,
                                std::size_t room, const DeviceArray<cl_int> *new_points);
  // The free point slots and the first new one for appending up to `most`
  // points in group, whose slots are filled ahead; take_point_slots takes
  // those used after the read of counts (survivors, stuck_count_).
  struct Slots {
    const cl::Buffer &free_list;
    cl_int free_first, free_count, first_new;
  };
  Slots point_slots_for(std::size_t most);
  std::size_t take_point_slots(const cl_int *counts, std::size_t room, int stamp);
  static cl_int clamped(std::size_t count); // as a kernel's int, at most INT32_MAX
  // Sets the mesh's and the search's arguments of find_bad_triangles (or
  // step_one_in_group); returns the next argument's index.
  cl_uint search_args(cl::Kernel &kernel, bool use_list, cl_int carried);
  // The same for locate_candidates (or place_candidates_in_group).
  cl_uint locate_args(cl::Kernel &kernel, int stamp);
  // The filter's marks cleared, when append_survivors appends nothing.
  void clear_candidate_marks();
  Device &device_;
  DeviceMesh &mesh_;
  double ratio_bound_squared_, max_area_, offconstant_, lens_, cos_bound_;
  int filter_rings_, filter_distance_rings_;
  double filter_near2_; // squared; infinite for any distance
  bool parallel_midpoints_;
  int election_rings_;
  bool second_round_ = false; // may the election hold a second round (settle_elected)?
  bool carry_verdicts_;
  std::size_t group_step_limit_;
  bool conforming_;        // -D: triangles whose apex encroaches a subsegment are bad
  int protected_segments_; // -Y
  bool inward_;            // split points of boundary edges kept inside
  cl::Kernel flag_hull_, count_unfixable_, flag_unsettled_, find_bad_, gather_bad_, elect_,
      settle_elected_, retire_blocked_, elect_again_, gather_elected_, locate_, mark_, ties_,
      filter_, clear_, append_, step_one_in_group_, place_in_group_;
  std::size_t bad_ = 0, candidates_ = 0;
  bool searched_ = false; // the first search examines every slot
  bool elected_ = false;  // the last search elected too (step_one_in_group)
  bool placed_ = false;   // and placed the candidates, appending appended_
  std::size_t appended_ = 0;
  std::size_t searched_entries_ = 0; // triangles the last search examined
  DeviceList<cl_int> search_;        // the next search's triangles, with duplicates
  // The scratch of the scan that makes the search list: lists of the pool
  // (those of candidate_ and radius2_, not used before the candidates are
  // located; pooled_keep_, pooled_offset_), or these when the search list is
  // longer.
  DeviceArray<cl_int> search_keep_, search_offset_;
  DeviceArray<cl_double2> candidate_;
  DeviceArray<cl_int> bad_list_; // the bad triangles of the last search
  // With an election, each one's mark (priority) at that search.
  DeviceArray<cl_uint> bad_mark_;
  cl_int searched_stamp_ = 0; // the mesh's stamp at the last search
  // Per candidate: its bad triangle (the elected ones; bad_list_ without an
  // election), container, the edge it lies on, whether it survived the filter.
  DeviceArray<cl_int> origin_, container_, split_edge_, survive_;
  DeviceArray<cl_int> keep_, offset_;
  TriangleClaims &tie_mark_;   // step 1's tie marks, shared with step 3's claims
  DeviceArray<cl_int> listed_; // the triangles of a search after the first
  DeviceArray<cl_uint> priority_;
  // Per bad triangle: where the last search located its candidate (-1: not
  // located), valid while neither triangle is rewritten: a walk of one step.
  DeviceArray<cl_int> last_container_;
  DeviceArray<cl_double> radius2_;  // each candidate's insertion radius, squared
  DeviceArray<cl_int> stuck_count_; // candidates dropped so, in all
  std::size_t stuck_seen_ = 0;      // stuck_count_ at the last stuck_since_last_asked
  // stuck_count_ as a placement in group read it with its result, when the last
  // location was its.
  std::size_t stuck_total_ = 0;
  bool stuck_known_ = false;
  // Per triangle slot, set by the search that assessed it: its notes (notes
  // in the kernels): whether its candidate splits an edge of its own on the
  // boundary (splits_own_edge; it is then elected whatever its neighbours'
  // priorities), what the next search asks again, and whether a location
  // found it stuck since (is_stuck in the kernels).
  DeviceArray<cl_int> notes_;
  DeviceArray<cl_double> region_area_; // each region's maximum area (<= 0: none)
  const DeviceArray<cl_double> *size_bound_;
  // The kernels' size_bound argument (region_area_ stands in, unread, without one).
  const cl::Buffer &size_bound_buffer() const {
    return size_bound_ ? size_bound_->buffer() : region_area_.buffer();
  }
  cl_int located_stamp_ = 0; // the mesh's stamp when the last search located
  // last_container_ and notes_ hold their first values in the slots below
  // this; the rest are set as the mesh's slots come into use, so that the
  // pages past the used slots are not touched (not resident). tie_mark_ as
  // well (TriangleClaims::cover).
  std::size_t filled_slots_ = 0;
  void fill_new_slots();
  // step_one_in_group's entries, bad ones, candidates, survivors and stuck_count_
  DeviceArray<cl_int> search_counts_;
  DeviceArray<cl_int> pooled_keep_, pooled_offset_; // see search_keep_
  std::size_t search_group_;                        // step_one_in_group's work-group size
  DeviceArray<cl_int> place_counts_; // place_candidates_in_group's survivors and stuck_count_
  std::size_t place_group_;          // its work-group size
};

} // namespace clmesh
