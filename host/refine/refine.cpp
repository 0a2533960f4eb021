// clmesh — GPU-QM and GPU-QM-V (thesis chapter 3): GPU-DT, then iterations
// until no triangle is bad, each of the three steps of §3.3.2:
//   1. candidates: the bad triangles are found, elected (GPU-QM-V), their
//      off-centers located (hull midpoints where they fall outside or
//      encroach the hull, §3.4.1) and filtered (§3.3.2, §3.5), and the
//      survivors appended to the points;
//   2. insertion, in place, in one round of 1-3 and 2-4 (1-2 on the hull)
//      flips;
//   3. flip-flop: Delaunay flips together with the deletion of redundant
//      points (§3.3.2, §3.5), after the boundary routine (§3.4.1).
// Between iterations the arrays are compacted into spatial order at times,
// and the empty slots collected or the arrays grown when room runs short
// (§3.6.1). A PSLG is first triangulated by GPU-CDT (chapter 4), its
// exterior and holes removed and its domain closed by ghosts
// (domain_boundary.cl); the iterations then treat its segments as the hull
// edges of a point set.
#include "refine/refine.hpp"

#include "cdt/exterior_removal.hpp"
#include "cdt/mesh_reconstruction.hpp"
#include "dt/delaunay_scheduler.hpp"
#include "dt/missing_point_insertion.hpp"
#include "io/directed_edges.hpp"
#include "refine/domain_boundary.hpp"
#include "refine/flip_flop.hpp"
#include "refine/free_slots.hpp"
#include "refine/offcenter_insertion.hpp"
#include "refine/size_bound.hpp"
#include "refine/steiner_renumbering.hpp"
#include "refine/zorder_compaction.hpp"
#include "runtime/host_memory.hpp"
#include "runtime/host_threads.hpp"

#include "clmesh/errors.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <set>
#include <string>

namespace clmesh {

namespace {

// How many points the device can hold in the refinement's arrays: about 600
// bytes per point in all; the largest array (flip-flop's stars, 4 entries
// per list entry) takes 16 x 8/3 bytes per point.
double device_point_capacity(const Device &device) {
  const double per_point = 600, largest_per_point = 16.0 * 8 / 3;
  return std::min(0.9 * static_cast<double>(device.global_memory()) / per_point,
                  static_cast<double>(device.max_allocation()) / largest_per_point);
}

// Can the device hold the refinement's arrays for `points` points?
bool device_holds(const Device &device, std::size_t points) {
  return static_cast<double>(points) < device_point_capacity(device);
}

// The area of the points' convex hull (Andrew's monotone chain), in long
// double: the products of any two finite coordinates fit.
long double hull_area(std::vector<Point> points) {
  if (points.size() < 3)
    return 0;
  std::sort(points.begin(), points.end(),
            [](const Point &a, const Point &b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  auto cross = [](const Point &o, const Point &a, const Point &b) {
    return (static_cast<long double>(a.x) - o.x) * (static_cast<long double>(b.y) - o.y) -
           (static_cast<long double>(a.y) - o.y) * (static_cast<long double>(b.x) - o.x);
  };
  std::vector<Point> hull(2 * points.size() + 1);
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) { // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0)
      --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) { // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0)
      --k;
    hull[k++] = points[i];
  }
  long double twice = 0;
  for (std::size_t i = 1; i + 1 < k; ++i)
    twice += cross(hull[0], hull[i], hull[i + 1]);
  return twice / 2;
}

// A count or size for a message, in a few digits ("5e29", "1.2e7", "0.25").
std::string short_number(long double value, int digits = 2) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*Lg", digits, value);
  std::string out = text;
  for (const char *exponent : {"e+0", "e+", "e-0"}) {
    const std::size_t at = out.find(exponent);
    if (at != std::string::npos) {
      out.replace(at, std::string(exponent).size(), exponent[1] == '-' ? "e-" : "e");
      break;
    }
  }
  return out;
}

// -a: the points the area bound needs at least, checked against what the
// device holds before any work. The mesh covers the convex hull; triangles no
// larger than the bound number at least its area over the bound, and V points
// make fewer than 2V triangles. A bound the device cannot hold is refused,
// unless the -S limit stops the refinement sooner (the user's choice).
void check_area_bound(const Device &device, const std::vector<Point> &points,
                      const RefineOptions &options, RefineStats &stats) {
  if (!options.max_area)
    return;
  const long double area = hull_area(points);
  const long double needed = area / (2.0L * *options.max_area);
  stats.area_bound_points =
      static_cast<double>(std::min<long double>(needed, std::numeric_limits<double>::max()));
  const double capacity = device_point_capacity(device);
  if (needed < capacity)
    return;
  if (options.max_steiner &&
      static_cast<double>(points.size()) + static_cast<double>(*options.max_steiner) < capacity)
    return;
  throw OptionError(
      "-a" + short_number(*options.max_area, 6) + " needs at least ~" + short_number(needed) +
      " points on this domain (area " + short_number(area) +
      "), more than the device's memory holds (about " + short_number(capacity) + " points)" +
      (options.max_steiner
           ? "; -S" + std::to_string(*options.max_steiner) + " does not stop the refinement sooner"
           : std::string()));
}

// Refinement to minimum angles above about 33 degrees need not end (each
// Steiner point may call for another, without end): without -S, it stops at
// kAngleLimitFactor Steiner points per input point, beyond what the area
// bound needs, so that such a run ends the same on every device, whatever
// its memory. Triangle's own -q34 on coastlines and CAD outlines adds 5 to 25
// points per input point where it ends.
constexpr double kAngleLimitFactor = 100;

std::size_t steiner_limit(std::size_t n, const RefineOptions &options, const RefineStats &stats) {
  if (options.max_steiner)
    return static_cast<std::size_t>(*options.max_steiner);
  if (options.min_angle <= 33)
    return std::numeric_limits<std::size_t>::max();
  return static_cast<std::size_t>(kAngleLimitFactor * static_cast<double>(n) +
                                  2 * stats.area_bound_points);
}

// First room for Steiner points (thesis §3.6.1: the arrays grow when it runs
// out). A growth copies every array and builds the steps again, and the
// search after it sweeps every slot, so the first room is what refinement to
// the angle bound usually takes: point sets gain about 0.6 n Steiner points
// at 20 degrees and 1.8 n at 30 (uniform, Gaussian, disk; a thin circle up to
// 3.4 n), and deleted points hold their slots for a while. With -a, room
// for a quarter more than the points the area bound needs at least
// (area_points, check_area_bound): a mesh of the convex hull takes about
// that many, a domain with holes fewer. A growth adds half the room at
// least, so that few follow.
std::size_t first_room(const Device &device, std::size_t n, const RefineOptions &options,
                       double area_points) {
  const double bound = std::min(options.min_angle, 30.0) / 30.0;
  const auto angle_room =
      static_cast<std::size_t>(static_cast<double>(n) * std::max(1.0, 2.2 * bound * bound));
  const auto area_room = static_cast<std::size_t>(std::min(1.25 * area_points, 1e18));
  const std::size_t cap = options.max_steiner
                              ? std::max(n, static_cast<std::size_t>(*options.max_steiner))
                              : std::numeric_limits<std::size_t>::max();
  // The larger room when the device holds it, else the angle bound's, else
  // the input's.
  for (std::size_t room : {std::max(angle_room, area_room), angle_room}) {
    room = std::min(room, cap);
    if (device_holds(device, n + room + 4096))
      return room + 4096;
  }
  return n + 4096;
}

// The programs of the refinement's phases, built with the setup.
constexpr const char *kPrograms[] = {"offcenter_insertion.cl", "hull_encroachment.cl",
                                     "flip_flop.cl",           "free_slots.cl",
                                     "zorder_compaction.cl",   "steiner_renumbering.cl"};

// The phase objects of the steps, sized by the mesh: built again when the
// mesh grows.
struct RefinementSteps {
  RefinementSteps(DelaunayScheduler &scheduler, const RefineOptions &options, bool inward,
                  const std::vector<double> &region_areas, const DeviceArray<cl_double> *size_bound)
      : scratch(scheduler.device(), {OffcenterInsertion::scratch_lists(scheduler.mesh()),
                                     MissingPointInsertion::scratch_lists(scheduler.mesh()),
                                     FlipFlop::scratch_lists(scheduler.mesh())}),
        claims(scheduler.device(), scheduler.mesh()),
        offcenter(scheduler.device(), scheduler.mesh(), scratch, claims, options.min_angle,
                  options.max_area.value_or(-1), options.delaunay.tuning.filter_rings,
                  options.delaunay.tuning.filter_distance_rings,
                  options.delaunay.tuning.filter_near, options.delaunay.tuning.parallel_midpoints,
                  options.delaunay.tuning.election_rings, options.delaunay.tuning.carry_verdicts,
                  options.delaunay.tuning.group_step_limit, options.conforming,
                  options.protected_segments, inward, region_areas, size_bound),
        insertion(scheduler.device(), scheduler.mesh(), scheduler.scan(), &scratch),
        flipflop(scheduler.device(), scheduler.mesh(), scheduler.scan(), scratch, claims,
                 options.delaunay.tuning.algorithm == RefineAlgorithm::qmv,
                 options.delaunay.tuning.group_pass_limit),
        free_slots(scheduler.device(), scheduler.mesh(), scheduler.scan()),
        new_points(scheduler.device(), scheduler.mesh().point_capacity) {}
  // The lists of the off-centers' step, of the insertion and of flip-flop:
  // one runs at a time.
  ScratchPool scratch;
  // Step 1's tie marks and step 3's removal claims (each step leaves them empty).
  TriangleClaims claims;
  OffcenterInsertion offcenter;
  MissingPointInsertion insertion;
  FlipFlop flipflop;
  FreeSlots free_slots;
  DeviceArray<cl_int> new_points; // the points inserted in this iteration
};

// Termination is guaranteed for angles up to about 30 degrees away from
// small input angles; the bound on iterations turns anything else into
// remaining bad triangles, reported, instead of a hang.
constexpr long kMaxIterations = 1000;

// A mesh to refine (-r): its triangles (input numbering), their area
// bounds (empty: none) and, with those, each triangle's neighbours across the
// edges opposite its corners (-1 on the boundary; emptied once on the
// device).
struct GivenMesh {
  const std::vector<Triangle> &triangles;
  const std::vector<double> &max_area;
  std::vector<cl_int> &across;
  // When the mesh can be the first mesh as it is (every segment of the
  // .poly an edge of it): each triangle's links across its edges
  // (mesh_constraints), else empty.
  std::vector<cl_int> &links;
};

// The marker that tells a given mesh's inner edges among the constraints of
// its CDT (refine_mesh): they are constraints only until its triangles are
// found.
constexpr int kInnerEdge = std::numeric_limits<int>::min();

// One refinement: the mesh, its phase objects and what the iterations count.
// With a PSLG (pslg and constrained not null), of its domain; with a given
// mesh too (-r: pslg's segments then include its edges), of that mesh.
class Refinement {
public:
  Refinement(Device &device, const std::vector<Point> &points, const RefineOptions &options,
             RefineResult &result, const Pslg *pslg = nullptr,
             const ConstrainedOptions *constrained = nullptr, const GivenMesh *given = nullptr)
      : device_(device), points_(points), options_(options), result_(result), stats_(result.stats),
        pslg_(pslg), constrained_(constrained), given_(given),
        // Refinement breaks ties by triangle slot; its first compaction gives
        // the triangles a layout that depends on them alone, whichever
        // construction (and grid) built them.
        scheduler_(device, points, options.delaunay, result.mesh.stats,
                   first_room(device, points.size(), options, result.stats.area_bound_points) +
                       (pslg ? crossing_room(*pslg) : 0)),
        limit_(steiner_limit(points.size(), options, result.stats)) {}

  // GPU-DT, and for a PSLG GPU-CDT and its domain; false when all points
  // are collinear (the result then holds them without triangles).
  bool triangulate() {
    for (const char *file : kPrograms)
      device_.program(file, "setup");
    if (pslg_)
      for (const char *file : {"constraint_marking.cl", "exterior_removal.cl", "domain_boundary.cl",
                               "mesh_reconstruction.cl"})
        device_.program(file, "setup");
    // A given mesh is the first mesh itself when it can be (its triangles
    // then need no Delaunay triangulation of its points to be found in).
    given_taken_ = given_ && !given_->links.empty() &&
                   scheduler_.take_triangles(given_->triangles, given_->links);
    if (given_)
      std::vector<cl_int>().swap(given_->links);
    if (given_taken_) // its boundary is the domain's: no flip may leave it
      scheduler_.fix_boundary();
    if (!given_taken_ && !scheduler_.triangulate()) {
      scheduler_.download_collinear(result_.mesh);
      if (pslg_)
        result_.segments = distinct_segments(pslg_->segments, result_.constraints);
      return false;
    }
    const auto [low, side] = bounding_square(points_);
    low_ = low;
    side_ = side;
    if (given_)
      reconstruct();
    else if (pslg_)
      constrain();
    first_steiner_ = mesh().point_count;
    scheduler_.mesh().enable_refinement(device_);
    if (pslg_)
      set_segments();
    scheduler_.fix_boundary();
    scheduler_.release_flipping(); // the iterations flip by FlipFlop
    if (options_.size_field || options_.unsuitable || triangle_areas_) {
      device_.program("size_bound.cl", "setup");
      size_bound_ = std::make_unique<SizeBound>(
          device_, mesh(), options_.size_field, triangle_areas_.get(),
          triangle_areas_ ? &given_->across : nullptr, options_.unsuitable, options_.attributes);
      triangle_areas_.reset(); // on the device now, and so are the neighbours
      if (given_)
        std::vector<cl_int>().swap(given_->across);
      scheduler_.timer().charge(SizeBound::kPhase); // the background grids' set-up
    }
    return true; // the steps are made by the first compaction (iterate)
  }

  // The iterations, until no triangle is bad or a limit is reached.
  void iterate() {
    release_free_heap(); // the set-up's temporaries: the iterations need the room
    for (long iteration = 0;; ++iteration) {
      if (iteration == 0 || compaction_pays())
        compact();
      if (iteration == 0)
        steps_->offcenter.flag_hull_vertices();
      const std::size_t bad = find_bad_triangles(iteration != kMaxIterations);
      const std::size_t candidates = elect_candidates();
      // Step 1 is timed once, after place_candidates, on the way that goes on.
      if (bad == 0 || iteration == kMaxIterations || steiner_ >= limit_) {
        charge_step_one();
        if (bad > 0)
          stats_.stop_reason = steiner_ >= limit_ ? limit_reason() : RefineStop::iteration_limit;
        break;
      }
      // Placed with the search: there was room (make_room would have found
      // it; the points appended since have taken some of it).
      const Room room = steps_->offcenter.placed() ? Room::enough : make_room(candidates);
      if (room != Room::enough)
        charge_step_one();
      if (room == Room::grown)
        continue; // the candidates are found again in the larger arrays
      if (room == Room::exhausted)
        break; // the cause is told once the mesh is downloaded (finish())
      ++stats_.iterations;
      stats_.candidates += static_cast<long>(candidates);
      const std::size_t added = place_candidates();
      if (added == 0 && steps_->offcenter.stuck_since_last_asked())
        continue; // the next search leaves out the triangles just found stuck
      if (added == 0) {
        // The arrays did not grow past the -S limit, or every candidate fell
        // on a vertex.
        // With -Y the candidates left lie beyond edges no point may split.
        stats_.stop_reason = steiner_ + candidates > limit_ ? limit_reason()
                             : options_.protected_segments  ? RefineStop::done
                                                            : RefineStop::no_insertion;
        break;
      }
      const std::size_t inserted = insert_survivors(added);
      flip_flop(inserted, added);
    }
  }

  // The statistics, the Steiner points numbered after the input points, and
  // the mesh downloaded.
  void finish() {
    if (pslg_) {
      finish_pslg();
      return;
    }
    collect_statistics();
    steps_.reset();      // the steps' lists go before the mesh comes to the host, and
    size_bound_.reset(); // the size bounds (the statistics have counted with them)
    const std::size_t n = points_.size();
    result_.added_points = SteinerRenumbering(device_, mesh(), scheduler_.scan()).number(n);
    const std::size_t survivors = result_.added_points.size();
    stats_.inserted = static_cast<long>(survivors);
    scheduler_.download(result_.mesh);
    result_.mesh.duplicate_of.resize(n + survivors);
    stats_.inserted_more_than_once =
        deletion_log_.points_inserted_more_than_once(device_, result_.added_points);
    if (stats_.out_of_memory)
      stats_.stop_reason = memory_cause();
  }

private:
  enum class Room { enough, grown, exhausted };

  // Why the Steiner point limit is what it is: -S, or the angle bound.
  RefineStop limit_reason() const {
    return options_.max_steiner ? RefineStop::steiner_limit : RefineStop::angle_bound;
  }

  // GPU-CDT, the exterior and holes removed, and the domain closed by ghosts.
  // With -c the domain is the convex hull (less the holes and the pockets
  // between segments and hull that are only flat slivers of rounding), and
  // its hull edges join the segments, marker 1, as Triangle's -c makes them:
  // they are split on shells where segments meet them at small angles.
  void constrain() {
    constraints_ = insert_constraints(device_, scheduler_, *pslg_, result_.constraints, crossings_);
    ExteriorRemoval removal(device_, mesh());
    remove_exterior(scheduler_, removal, *pslg_, *constrained_, result_.constraints);
    if (constrained_->keep_convex_hull) {
      // Flat pockets are slivers of rounding that refinement could not mend.
      result_.constraints.eaten_triangles += removal.remove_flat_pockets();
      scheduler_.timer().charge(ExteriorRemoval::kPhase);
    }
    label_regions(removal);
    DomainBoundary boundary(device_, mesh(), scheduler_.scan());
    close_domain(boundary, removal);
    if (!constrained_->keep_convex_hull)
      return;
    std::set<std::pair<int32_t, int32_t>> segments;
    for (const Segment &s : constraints_)
      segments.insert(std::minmax(s.a, s.b));
    for (const Segment &edge : boundary.edges())
      if (segments.insert(std::minmax(edge.a, edge.b)).second)
        constraints_.push_back(edge);
  }

  // The domain left by `removal` closed by ghosts.
  void close_domain(DomainBoundary &boundary, ExteriorRemoval &removal) {
    if (!removal.removed_any()) { // the hull's ghosts close the domain
      boundary.keep_hull(removal.removed());
      scheduler_.timer().charge(DomainBoundary::kPhase);
      return;
    }
    inward_ = removal.count_flat_removed() > 0;
    const std::size_t ghosts = boundary.room_needed(removal.removed());
    if (mesh().triangle_count + ghosts > mesh().triangle_capacity)
      scheduler_.grow(ghosts / 2 + 1);
    boundary.close(removal.removed());
    scheduler_.timer().charge(DomainBoundary::kPhase);
  }

  // -r: the given mesh as the domain. With every edge of it a constraint,
  // its triangles are triangles of the CDT; they are found (and labelled
  // with their input triangle), every other triangle and those the holes
  // reach are removed, the inner edges cease to be constraints, and flips
  // make the mesh constrained Delaunay. The boundary and segments go in
  // first: a mesh that is constrained Delaunay already (as a mesh of clmesh
  // or Triangle is) then has all its triangles, and only another one needs
  // its inner edges inserted too. A mesh taken as the first mesh itself
  // (take_triangles) has them all, and only its flips are left.
  void reconstruct() {
    std::vector<Triangle> corners = given_->triangles;
    for (Triangle &t : corners)
      for (int32_t &v : t)
        v = scheduler_.device_point(v);
    MeshReconstruction reconstruction(device_, mesh(), corners);
    std::vector<Segment> outline_segments;
    for (const Segment &s : pslg_->segments)
      if (s.marker != kInnerEdge)
        outline_segments.push_back(s);
    const std::vector<Point> no_points;
    const std::vector<Region> no_regions;
    const Pslg outline{no_points, outline_segments, no_points, no_regions};
    std::vector<Segment> constraints =
        insert_constraints(device_, scheduler_, outline, result_.constraints, crossings_);
    long missing = reconstruction.label();
    const bool inner_edges = missing >= 0; // inserted too: the mesh is not CDT
    if (inner_edges) {
      std::vector<Point> more;
      constraints = insert_constraints(device_, scheduler_, *pslg_, result_.constraints, more);
      crossings_.insert(crossings_.end(), more.begin(), more.end());
      missing = reconstruction.label();
    }
    scheduler_.timer().charge(MeshReconstruction::kPhase);
    if (missing >= 0)
      throw TriangleNotInMesh{static_cast<std::size_t>(missing)};
    for (const Segment &s : constraints)
      if (s.marker != kInnerEdge)
        constraints_.push_back(s);
    result_.constraints.segments = static_cast<long>(constraints_.size());
    DeviceMesh &m = mesh();
    // With inner edges, they cease to be constraints; the flips that they
    // blocked go ahead. (Otherwise the insertion's own flips left the mesh
    // constrained Delaunay with these very constraints.) A mesh taken as it
    // is may not be Delaunay at all.
    if (inner_edges)
      m.set_constraint_rows(device_, constraints_);
    if (inner_edges || given_taken_) {
      DeviceArray<cl_int> every_slot(device_, m.triangle_count);
      every_slot.fill(device_, 1, m.triangle_count);
      FlipCounts flips;
      scheduler_.flip_flagged(every_slot, flips, "constrained_flipping");
      result_.constraints.delaunay_flips += flips.flips;
    }

    ExteriorRemoval removal(device_, m);
    removal.remove_unlabelled(reconstruction.labels());
    if (!pslg_->holes.empty() && !constrained_->ignore_holes) {
      result_.constraints.eaten_triangles = removal.run(false, pslg_->holes);
      result_.constraints.ignored_holes = removal.seeds_on_segments();
    }
    scheduler_.timer().charge(ExteriorRemoval::kPhase);
    // Each triangle's input triangle, whose attributes it inherits (the
    // labels diffuse with flips, as Triangle's attributes do), and where a
    // .area bound's lookup starts.
    const bool areas = options_.regional_areas && !given_->max_area.empty();
    if (options_.attributes || areas) {
      m.tri_region = reconstruction.labels();
      m.has_regions = true;
      region_areas_.assign(given_->triangles.size(), -1);
    }
    // The .area bounds (-a alone) bound the triangles by where they lie:
    // each input triangle those whose centroid it holds (SizeBound).
    if (areas)
      triangle_areas_ =
          std::make_unique<SizeField>(SizeField{points_, given_->max_area, given_->triangles});
    DomainBoundary boundary(device_, m, scheduler_.scan());
    close_domain(boundary, removal);
  }

  // With -a alone or -A, and regions: each triangle slot's region, kept in
  // the mesh from now on (DeviceMesh::tri_region), and each region's area
  // bound (with -a alone).
  void label_regions(ExteriorRemoval &removal) {
    if ((!options_.regional_areas && !options_.attributes) || pslg_->regions.empty())
      return;
    std::vector<Point> seeds;
    for (const Region &region : pslg_->regions) {
      seeds.push_back(region.seed);
      region_areas_.push_back(options_.regional_areas ? region.max_area : -1);
    }
    DeviceMesh &m = mesh();
    m.tri_region = removal.label_regions(seeds);
    m.has_regions = true;
    result_.constraints.ignored_regions = removal.seeds_on_segments();
  }

  // The segments as refinement's constraints; their vertices are boundary
  // vertices (never deleted, and their triangles' candidates are tested
  // against the subsegments near them).
  void set_segments() {
    DeviceMesh &m = mesh();
    m.set_segments(device_, constraints_);
    std::vector<cl_int> states(m.point_count, 0); // CLM_POINT_INPUT
    for (const Segment &s : constraints_)
      states[static_cast<std::size_t>(s.a)] = states[static_cast<std::size_t>(s.b)] =
          8; // CLM_POINT_HULL
    m.point_state.upload(device_, states);
  }

  // finish() for a PSLG: the mesh, the points added where segments cross
  // and the Steiner points, and the segments as chains of subsegments.
  void finish_pslg() {
    collect_statistics();
    steps_.reset();      // the steps' lists go before the mesh comes to the host, and
    size_bound_.reset(); // the size bounds (the statistics have counted with them)
    std::vector<int32_t> on_segment;
    std::vector<Point> steiner =
        SteinerRenumbering(device_, mesh(), scheduler_.scan()).number(first_steiner_, &on_segment);
    stats_.inserted = static_cast<long>(steiner.size());
    std::vector<int32_t> labels;
    const bool attributes = options_.attributes && mesh().has_regions;
    scheduler_.download(result_.mesh, nullptr, attributes ? &mesh().tri_region : nullptr, &labels);
    if (attributes && given_) {
      result_.triangle_origin = std::move(labels);
    } else if (options_.attributes) {
      result_.triangle_attributes.assign(result_.mesh.triangles.size(), 0.0);
      for (std::size_t t = 0; t < labels.size(); ++t)
        if (labels[t] >= 0)
          result_.triangle_attributes[t] = pslg_->regions[labels[t]].attribute;
    }
    stats_.inserted_more_than_once = deletion_log_.points_inserted_more_than_once(device_, steiner);
    result_.added_points = crossings_;
    result_.added_points.insert(result_.added_points.end(), steiner.begin(), steiner.end());
    result_.mesh.duplicate_of.resize(points_.size() + result_.added_points.size(), -1);
    if (stats_.out_of_memory)
      stats_.stop_reason = memory_cause();

    // Each segment's chain: its ends and the Steiner points on it, in order
    // of their distance from its first end.
    const std::vector<Segment> pieces =
        input_numbering(constraints_, scheduler_, result_.mesh.duplicate_of);
    std::vector<std::vector<int32_t>> on_piece(pieces.size());
    for (std::size_t k = 0; k < steiner.size(); ++k)
      if (on_segment[k] >= 0)
        on_piece[static_cast<std::size_t>(on_segment[k])].push_back(
            static_cast<int32_t>(first_steiner_ + k));
    for (std::size_t j = 0; j < pieces.size(); ++j) {
      const Point a = point(pieces[j].a);
      auto from_a = [&](int32_t v) {
        const Point p = point(v);
        return (p.x - a.x) * (p.x - a.x) + (p.y - a.y) * (p.y - a.y);
      };
      std::vector<int32_t> &chain = on_piece[j];
      std::sort(chain.begin(), chain.end(), [&](int32_t u, int32_t v) {
        const double du = from_a(u), dv = from_a(v);
        return du < dv || (du == dv && u < v);
      });
      int32_t previous = pieces[j].a;
      for (int32_t v : chain) {
        result_.segments.push_back({previous, v, pieces[j].marker});
        previous = v;
      }
      result_.segments.push_back({previous, pieces[j].b, pieces[j].marker});
    }
  }

  // The statistics of the iterations' steps.
  void collect_statistics() {
    stats_.remaining_bad += static_cast<long>(steps_->offcenter.count_unfixable());
    stats_.deleted = flips_.deleted;
    stats_.kept_redundant = flips_.kept_redundant;
    stats_.boundary_splits = flips_.midpoints;
    stats_.delaunay_flips = flips_.delaunay_flips;
    stats_.non_delaunay_flips = flips_.non_delaunay_flips;
    DelaunayStats &mesh_stats = result_.mesh.stats;
    mesh_stats.flips += flips_.delaunay_flips + flips_.non_delaunay_flips;
    mesh_stats.flip_passes += flips_.passes;
    mesh_stats.exact_predicate_calls += flips_.exact_checks;
  }

  // Output point v (input numbering, then the added points) of the result.
  Point point(int32_t v) const {
    const auto i = static_cast<std::size_t>(v);
    return i < points_.size() ? points_[i] : result_.added_points[i - points_.size()];
  }

  // Out of device memory, on the downloaded mesh: the area bound is to blame
  // while triangles above it are left, else an angle bound above about 33
  // degrees (refinement to it need not terminate), else the input's size.
  RefineStop memory_cause() const {
    const DelaunayResult &mesh = result_.mesh;
    if (options_.max_area)
      for (const auto &t : mesh.triangles) {
        const Point a = point(t[0]), b = point(t[1]), c = point(t[2]);
        if (std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / 2 >
            *options_.max_area)
          return RefineStop::area_bound;
      }
    return options_.min_angle > 33 ? RefineStop::angle_bound : RefineStop::device_memory;
  }

  DeviceMesh &mesh() { return scheduler_.mesh(); }

  // Point and triangle slots for more points: the free ones, then the ones
  // past the used ranges.
  std::size_t room() {
    const DeviceMesh &m = mesh();
    return std::min(m.point_capacity - m.point_count + m.free_points.count,
                    (m.triangle_capacity - m.triangle_count + m.free_triangles.count) / 2);
  }

  // Triangles move into spatial order at the start, then whenever their
  // slots grew by half while much work remains: at least one triangle in 16
  // bad at the last search. With less work left, the move costs more than
  // the order saves.
  bool compaction_pays() {
    return mesh().triangle_count >= compacted_slots_ + compacted_slots_ / 2 &&
           16 * last_bad_ >= mesh().triangle_count;
  }

  // Thesis §3.6.1: the live triangles and Steiner points move to the front,
  // in Z-order. Every slot number changes: the lists of triangles are void,
  // and the steps start again with new arrays (the first compaction, before
  // the first iteration, makes the first steps). Their pages go back to the
  // system for the move, and the long lists of the first iterations do not
  // hold pages while the mesh grows. After the first search, the triangles
  // that may be bad are flagged and move with their flags: the next search
  // examines those alone (in slot order, as a search of every slot lists
  // them), the others are good.
  void compact() {
    DeviceArray<cl_int> unsettled;
    const bool searched = options_.delaunay.tuning.search_flagged_after_move && steps_ &&
                          steps_->offcenter.searched();
    if (searched) {
      unsettled = DeviceArray<cl_int>(device_, mesh().triangle_count);
      unsettled.fill(device_, 0, mesh().triangle_count);
      steps_->offcenter.flag_unsettled(changed_, unsettled);
    }
    steps_.reset();
    changed_ = DeviceList<cl_int>{};
    // The size bounds move with the triangles when the slots rewritten since
    // they were set (changed_) are flagged and listed again after the move;
    // else every slot's is set again.
    const bool move_bounds = size_bound_ && searched && !sizes_stale_;
    ZOrderCompaction(device_, mesh(), scheduler_.scan())
        .compact(low_, side_, first_steiner_, searched ? &unsettled : nullptr,
                 move_bounds ? &size_bound_->bounds_to_move() : nullptr);
    make_steps();
    if (searched) {
      const std::size_t slots = mesh().triangle_count;
      DeviceArray<cl_int> offsets(device_, slots);
      changed_.items = DeviceArray<cl_int>(device_, slots);
      changed_.size = static_cast<std::size_t>(scheduler_.scan().compact_indices(
          unsettled, offsets, changed_.items, slots, FlipFlop::kPhase));
      steps_->offcenter.skip_sweep();
    }
    sizes_stale_ = !move_bounds;
    deleted_since_collection_ = false;
    compacted_slots_ = mesh().triangle_count;
    ++stats_.compactions;
    scheduler_.timer().charge(FlipFlop::kPhase); // timed with step 3
  }

  // Step 1: the bad triangles, among those rewritten since the last search
  // and the bad ones then. Returns how many there are.
  // With may_place, a short search places the candidates in the same launch
  // when they fit the room as it is (make_room has nothing to do then, and
  // place_candidates returns what was appended).
  std::size_t find_bad_triangles(bool may_place) {
    update_size_bounds();
    const bool placing = may_place && steiner_ < limit_;
    const std::size_t bad = steps_->offcenter.find_bad_triangles(
        scheduler_.scan(), &changed_, scheduler_.stamp(),
        placing ? std::min(room(), limit_ - steiner_) : 0, placing ? &steps_->new_points : nullptr);
    // The pages past this list's entries go back to the system (the next
    // one, of about the same size, writes those it keeps again).
    changed_.items.discard(device_, changed_.size, OffcenterInsertion::kPhase);
    changed_.size = 0;
    stats_.remaining_bad = static_cast<long>(bad);
    last_bad_ = bad;
    return bad;
  }

  // The sizing field's or callback's bounds of the triangles rewritten since
  // the last search (of every slot after the slots moved or grew).
  void update_size_bounds() {
    if (!size_bound_)
      return;
    size_bound_->update(sizes_stale_ ? nullptr : &changed_);
    sizes_stale_ = false;
    scheduler_.timer().charge(SizeBound::kPhase);
  }

  // The phase objects of the steps, for the mesh's arrays as they are.
  void make_steps() {
    // The mesh may have outgrown the caches.
    device_.fit_prefetching(mesh().point_capacity, options_.delaunay.tuning.prefetch_from);
    steps_ = std::make_unique<RefinementSteps>(scheduler_, options_, inward_, region_areas_,
                                               size_bound_ ? &size_bound_->bounds() : nullptr);
  }

  // Step 1: the bad triangles that send a candidate (all, without an election).
  std::size_t elect_candidates() { return steps_->offcenter.elect_candidates(scheduler_.scan()); }

  // The time since the last phase charged goes to step 1 (the phase timer
  // waits for the device: once an iteration).
  void charge_step_one() { scheduler_.timer().charge(OffcenterInsertion::kPhase); }

  // Room for every candidate: the empty slots when the room past the used
  // ranges runs short (thesis §3.6.1), then larger arrays. Growing
  // rebuilds the steps, which voids the candidates.
  Room make_room(std::size_t candidates) {
    if (room() < candidates && deleted_since_collection_) {
      steps_->free_slots.collect();
      deleted_since_collection_ = false;
    }
    if (room() >= candidates || steiner_ + candidates > limit_)
      return Room::enough;
    const std::size_t extra = std::max(candidates, mesh().point_capacity / 2);
    if (!device_holds(device_, mesh().point_capacity + extra)) {
      // Reported with the bad triangles left and the bound to blame.
      stats_.out_of_memory = true;
      return Room::exhausted;
    }
    steps_.reset(); // before the mesh grows: a lower peak
    scheduler_.grow(extra);
    ++stats_.growths;
    if (size_bound_) {
      size_bound_->fit();
      sizes_stale_ = true;
    }
    make_steps();
    return Room::grown;
  }

  // Step 1: each candidate's off-center (or hull midpoint) and the triangle
  // that contains it, the insertion filter (thesis §3.3.2; §3.5 for
  // GPU-QM-V), and the survivors joining the mesh's points, as many as there
  // is room for within the -S limit. Returns how many joined.
  std::size_t place_candidates() {
    const std::size_t added =
        steps_->offcenter.place_candidates(scheduler_.stamp(), std::min(room(), limit_ - steiner_),
                                           scheduler_.scan(), steps_->new_points);
    charge_step_one();
    return added;
  }

  // Step 2: the `added` new points inserted in one round. Returns how many
  // triangles they split.
  std::size_t insert_survivors(std::size_t added) {
    MissingPointInsertion &insertion = steps_->insertion;
    insertion.set_points(steps_->new_points, added);
    const std::size_t inserted = insertion.run_round(scheduler_.stamp()++, false);
    if (insertion.pending() > 0)
      throw InternalError("Steiner points placed in place were not all inserted in one round");
    scheduler_.timer().charge(MissingPointInsertion::kPhase);
    return inserted;
  }

  // Step 3: flip-flop from the triangles the insertion rewrote.
  void flip_flop(std::size_t inserted, std::size_t added) {
    MissingPointInsertion &insertion = steps_->insertion;
    const long deleted_before = flips_.deleted;
    changed_.append(device_, insertion.changed(), 4 * inserted);
    steps_->flipflop.run(insertion.changed(), 4 * inserted, steps_->new_points, added,
                         scheduler_.stamp(), changed_, deletion_log_, flips_);
    steps_->flipflop.trim_lists();
    insertion.trim_lists();
    steps_->scratch.trim(std::max({steps_->offcenter.entries_used(), insertion.entries_used(),
                                   steps_->flipflop.entries_used()}),
                         mesh().list_capacity, FlipFlop::kPhase);
    scheduler_.timer().charge(FlipFlop::kPhase);
    const auto deleted = static_cast<std::size_t>(flips_.deleted - deleted_before);
    deleted_since_collection_ = deleted_since_collection_ || deleted > 0;
    stats_.insertions += static_cast<long>(added);
    steiner_ += added - deleted;
  }

  Device &device_;
  const std::vector<Point> &points_;
  const RefineOptions &options_;
  RefineResult &result_;
  RefineStats &stats_;
  const Pslg *pslg_;
  const ConstrainedOptions *constrained_;
  const GivenMesh *given_;
  DelaunayScheduler scheduler_;
  std::vector<Segment> constraints_; // a PSLG's segments as they stand (device numbering)
  std::vector<Point> crossings_;     // vertices added where segments cross
  std::vector<double> region_areas_; // with regions: each one's area bound (<= 0: none)
  // Parts of the domain lie a hair apart (flat triangles among the removed
  // ones): split points of boundary edges are kept inside (inside_edge).
  bool inward_ = false;
  std::size_t first_steiner_ = 0; // slot of the first Steiner point
  // -r's .area bounds on the given mesh, until SizeBound has them.
  std::unique_ptr<SizeField> triangle_areas_;
  std::unique_ptr<SizeBound> size_bound_; // with a sizing field, .area bounds or callback
  bool sizes_stale_ = true;               // every slot's size bound is to be set again
  bool given_taken_ = false;              // the given mesh is the first mesh (take_triangles)
  std::unique_ptr<RefinementSteps> steps_;
  const std::size_t limit_; // Steiner points at most (-S)
  Point low_{};
  double side_ = 0; // the points' bounding square, for the Z-order
  FlipFlopCounts flips_;
  DeletionLog deletion_log_;
  DeviceList<cl_int> changed_; // the triangles rewritten since the last search
  std::size_t steiner_ = 0;    // Steiner points in the mesh now
  bool deleted_since_collection_ = false;
  std::size_t compacted_slots_ = 0; // triangle slots after the last compaction
  std::size_t last_bad_ = 0;        // bad triangles at the last search
};

// The constraints of a given mesh's CDT: the segments (marker 0 turned to 1
// on the mesh's boundary, as Triangle marks boundary edges), the boundary
// edges (marker 1), then the inner edges (kInnerEdge). Repeats are dropped
// later, keeping the first. `links`: each triangle's neighbours there,
// links[3 t + i] the link ((triangle << 2) | edge) across the edge opposite
// corner i of triangle t, -1 on the boundary. *segments_on_edges: whether
// every segment is an edge of the mesh.
std::vector<Segment> mesh_constraints(const std::vector<Triangle> &triangles,
                                      const std::vector<Segment> &segments, std::size_t vertices,
                                      std::vector<cl_int> &links, bool *segments_on_edges) {
  const DirectedEdges directed(triangles, vertices);
  std::vector<Segment> constraints = segments;
  *segments_on_edges = true;
  for (Segment &s : constraints) {
    const bool forward = directed.has(s.a, s.b), backward = directed.has(s.b, s.a);
    *segments_on_edges = *segments_on_edges && (forward || backward);
    if (s.marker == 0 && forward != backward)
      s.marker = 1; // on the boundary
  }
  // The edges in the order of (from, to): the boundary's, then the inner ones.
  const std::vector<DirectedEdges::Edge> &edges = directed.edges();
  const std::vector<int64_t> reverse = directed.reverses();
  // Room for them all: an edge without a reverse, or each pair once.
  std::size_t pairs = 0;
  for (std::size_t e = 0; e < edges.size(); ++e)
    pairs += reverse[e] < 0 ? 2 : 1;
  constraints.reserve(constraints.size() + pairs / 2 + 1);
  for (const bool inner : {false, true})
    for (std::size_t a = 0; a < vertices; ++a)
      for (std::size_t e = directed.first(a); e < directed.first(a + 1); ++e) {
        const auto from = static_cast<int32_t>(a), to = edges[e].head;
        if ((reverse[e] >= 0) != inner || (inner && from > to))
          continue;
        constraints.push_back({from, to, inner ? kInnerEdge : 1});
      }
  // Edge a -> b of triangle t is the one opposite t's corner after b.
  // Each edge writes its own triangle's link: the parts write apart.
  links.assign(3 * triangles.size(), -1);
  constexpr std::size_t ahead = DirectedEdges::kPrefetchAhead;
  run_parts(host_threads(edges.size()), [&](int part, int parts) {
    const auto [first, end] = part_range(edges.size(), part, parts);
    for (std::size_t e = first; e < end; ++e) {
      if (e + ahead < end && reverse[e + ahead] >= 0)
        __builtin_prefetch(&edges[static_cast<std::size_t>(reverse[e + ahead])]);
      if (reverse[e] < 0)
        continue;
      const DirectedEdges::Edge &back = edges[static_cast<std::size_t>(reverse[e])];
      links[3 * std::size_t{edges[e].triangle} + (edges[e].corner + 2) % 3] =
          static_cast<cl_int>((back.triangle << 2) | ((back.corner + 2) % 3));
    }
  });
  return constraints;
}

} // namespace

RefineResult refine_delaunay(Device &device, const std::vector<Point> &points,
                             const RefineOptions &options) {
  RefineResult result;
  check_area_bound(device, points, options, result.stats);
  Refinement refinement(device, points, options, result);
  if (!refinement.triangulate())
    return result;
  refinement.iterate();
  refinement.finish();
  return result;
}

RefineResult refine_constrained(Device &device, const Pslg &pslg,
                                const ConstrainedOptions &constrained,
                                const RefineOptions &options) {
  RefineResult result;
  check_area_bound(device, pslg.points, options, result.stats);
  Refinement refinement(device, pslg.points, options, result, &pslg, &constrained);
  if (!refinement.triangulate())
    return result;
  refinement.iterate();
  refinement.finish();
  return result;
}

RefineResult refine_mesh(Device &device, const Pslg &pslg, const std::vector<Triangle> &triangles,
                         const std::vector<double> &max_area, const ConstrainedOptions &constrained,
                         const RefineOptions &options) {
  const auto started = std::chrono::steady_clock::now();
  // Vertices that no triangle or segment uses (the middle nodes of a six-node
  // mesh, points left over) stay out of the mesh, as in Triangle. `kept`
  // numbers the others in order, so the renumbering keeps every order.
  const std::size_t n = pslg.points.size();
  std::vector<char> used(n, 0);
  for (const Triangle &t : triangles)
    for (int32_t v : t)
      used[static_cast<std::size_t>(v)] = 1;
  for (const Segment &s : pslg.segments)
    used[static_cast<std::size_t>(s.a)] = used[static_cast<std::size_t>(s.b)] = 1;
  std::vector<int32_t> kept, index_of(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    if (used[i]) {
      index_of[i] = static_cast<int32_t>(kept.size());
      kept.push_back(static_cast<int32_t>(i));
    }
  std::vector<char>().swap(used);
  // Renumbered copies only when some points stay out.
  const bool every_point = kept.size() == n;
  std::vector<Point> kept_points;
  std::vector<Triangle> renumbered_triangles;
  std::vector<Segment> renumbered_segments;
  if (!every_point) {
    kept_points.reserve(kept.size());
    for (int32_t i : kept)
      kept_points.push_back(pslg.points[static_cast<std::size_t>(i)]);
    renumbered_triangles = triangles;
    for (Triangle &t : renumbered_triangles)
      for (int32_t &v : t)
        v = index_of[static_cast<std::size_t>(v)];
    renumbered_segments = pslg.segments;
    for (Segment &s : renumbered_segments) {
      s.a = index_of[static_cast<std::size_t>(s.a)];
      s.b = index_of[static_cast<std::size_t>(s.b)];
    }
  }
  std::vector<int32_t>().swap(index_of);
  const std::vector<Point> &points = every_point ? pslg.points : kept_points;
  const std::vector<Triangle> &corners = every_point ? triangles : renumbered_triangles;
  const std::vector<Segment> &segments = every_point ? pslg.segments : renumbered_segments;
  const bool areas = options.regional_areas && !max_area.empty();
  // The mesh may be the first mesh itself when its segments are its edges
  // (as those of a mesh Triangle or clmesh wrote are): each is then one
  // already.
  std::vector<cl_int> links; // the first mesh's, when the mesh can be it
  bool as_it_is = false;
  const std::vector<Segment> constraints =
      mesh_constraints(corners, segments, points.size(), links, &as_it_is);
  std::vector<cl_int> across; // the .area bounds' walks take the triangles
  if (areas) {
    across.resize(links.size());
    std::transform(links.begin(), links.end(), across.begin(),
                   [](cl_int link) { return link < 0 ? -1 : link >> 2; });
  }
  if (!as_it_is)
    std::vector<cl_int>().swap(links);
  const std::vector<Region> no_regions;
  const Pslg subset{points, constraints, pslg.holes, no_regions};

  RefineResult result;
  check_area_bound(device, subset.points, options, result.stats);
  const GivenMesh given{corners, max_area, across, links};
  release_free_heap(); // the edge lists' pages, before the device's arrays
  // The given mesh's edges, found on the host, are part of its
  // reconstruction's time (the device's starts with the Refinement).
  const double edges_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  Refinement refinement(device, subset.points, options, result, &subset, &constrained, &given);
  if (refinement.triangulate()) {
    refinement.iterate();
    refinement.finish();
  }
  result.mesh.stats.compute_seconds += edges_seconds;
  add_phase_time(result.mesh.stats, MeshReconstruction::kPhase, edges_seconds);
  if (every_point)
    return result;
  // Back to the input's numbering; the added points follow all its points.
  const auto m = static_cast<int32_t>(kept.size());
  auto original = [&](int32_t v) {
    return v < 0 ? v : v < m ? kept[static_cast<std::size_t>(v)] : v - m + static_cast<int32_t>(n);
  };
  for (Triangle &t : result.mesh.triangles)
    for (int32_t &v : t)
      v = original(v);
  for (Segment &s : result.segments) {
    s.a = original(s.a);
    s.b = original(s.b);
  }
  std::vector<int32_t> duplicate_of(n + result.added_points.size(), -1);
  for (std::size_t v = 0; v < result.mesh.duplicate_of.size(); ++v)
    duplicate_of[static_cast<std::size_t>(original(static_cast<int32_t>(v)))] =
        original(result.mesh.duplicate_of[v]);
  result.mesh.duplicate_of = std::move(duplicate_of);
  return result;
}

} // namespace clmesh
