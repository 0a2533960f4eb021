// clmesh — GPU-CDT entry point (thesis chapter 4): GPU-DT phases, then the
// constraints inserted by marking and flipping, then constrained Delaunay
// flipping, then the exterior and holes removed.
#include "cdt/constrained.hpp"

#include "cdt/constraint_insertion.hpp"
#include "cdt/exterior_removal.hpp"
#include "dt/delaunay_scheduler.hpp"

#include <algorithm>

namespace clmesh {

// Drops zero-length and repeated segments (first occurrence kept, with the
// first non-zero marker of its repeats).
std::vector<Segment> distinct_segments(std::vector<Segment> segments, ConstrainedStats &stats) {
  const std::vector<char> first = first_occurrences(segments);
  std::vector<Segment> kept;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (segments[i].a == segments[i].b || !first[i]) {
      ++stats.dropped_segments;
      continue;
    }
    kept.push_back(segments[i]);
  }
  return kept;
}

std::size_t crossing_room(const Pslg &pslg) { return 1024 + pslg.segments.size(); }

std::vector<Segment> insert_constraints(Device &device, DelaunayScheduler &scheduler,
                                        const Pslg &pslg, ConstrainedStats &stats,
                                        std::vector<Point> &added_points,
                                        std::vector<Segment> *crossed) {
  // Constraints in device numbering, duplicate endpoints resolved.
  std::vector<Segment> segments = pslg.segments;
  for (Segment &s : segments) {
    s.a = scheduler.device_point(s.a);
    s.b = scheduler.device_point(s.b);
  }
  std::vector<Segment> constraints; // as they stand in the mesh, device numbering
  DeviceArray<cl_int> touched;      // slots the insertion flipped
  {
    ConstraintInsertion insertion(device, scheduler.mesh());
    segments = distinct_segments(insertion.resolve_duplicates(segments), stats);
    stats.segments = static_cast<long>(segments.size());
    insertion.set_constraints(segments);
    insertion.run(stats, [&](const std::vector<Point> &added, const std::vector<int32_t> &near) {
      return scheduler.insert_points(added, near);
    });
    added_points = insertion.added_points();
    if (crossed) {
      crossed->clear();
      for (const int32_t origin : insertion.added_origins())
        crossed->push_back(segments[static_cast<std::size_t>(origin)]);
    }
    constraints = insertion.segments();
    touched = insertion.take_touched();
    scheduler.timer().charge(ConstraintInsertion::kPhase);
  } // its device lists are released here; the constraints stay in the mesh

  FlipCounts flips;
  scheduler.flip_flagged(touched, flips, "constrained_flipping");
  stats.delaunay_flips = flips.flips;
  return constraints;
}

bool remove_exterior(DelaunayScheduler &scheduler, ExteriorRemoval &removal, const Pslg &pslg,
                     const ConstrainedOptions &options, ConstrainedStats &stats) {
  const bool from_hull = !options.keep_convex_hull;
  const std::vector<Point> no_holes;
  const auto &holes = options.ignore_holes ? no_holes : pslg.holes;
  if (!from_hull && holes.empty())
    return false;
  stats.eaten_triangles = removal.run(from_hull, holes);
  stats.ignored_holes = removal.seeds_on_segments();
  scheduler.timer().charge(ExteriorRemoval::kPhase);
  return true;
}

std::vector<Segment> input_numbering(const std::vector<Segment> &constraints,
                                     const DelaunayScheduler &scheduler,
                                     const std::vector<int32_t> &duplicate_of) {
  const auto &original = scheduler.original_ids();
  auto input_point = [&](int32_t device_point) {
    const int32_t input = original[device_point];
    return duplicate_of[input] >= 0 ? duplicate_of[input] : input;
  };
  std::vector<Segment> result;
  for (const Segment &s : constraints)
    result.push_back({input_point(s.a), input_point(s.b), s.marker});
  return result;
}

ConstrainedResult constrained_delaunay(Device &device, const Pslg &pslg,
                                       const ConstrainedOptions &options) {
  ConstrainedResult result;
  ConstrainedStats &stats = result.stats;
  // Segment endpoints were checked by validate(Input), which triangulate() calls first.
  DelaunayScheduler scheduler(device, pslg.points, options.delaunay, result.mesh.stats,
                              crossing_room(pslg));
  device.program("constraint_marking.cl", "setup");
  device.program("exterior_removal.cl", "setup");
  if (!scheduler.triangulate()) {
    scheduler.download_collinear(result.mesh);
    result.segments = distinct_segments(pslg.segments, stats);
    return result;
  }
  std::vector<Segment> crossed;
  const std::vector<Segment> constraints =
      insert_constraints(device, scheduler, pslg, stats, result.added_points, &crossed);

  ExteriorRemoval removal(device, scheduler.mesh());
  const bool eat = remove_exterior(scheduler, removal, pslg, options, stats);
  const DeviceArray<cl_int> *label = nullptr;
  if (options.regional_attributes) {
    std::vector<Point> seeds;
    for (const Region &region : pslg.regions)
      seeds.push_back(region.seed);
    label = &removal.label_regions(seeds);
    stats.ignored_regions = removal.seeds_on_segments();
    scheduler.timer().charge(ExteriorRemoval::kPhase);
  }
  std::vector<int32_t> labels;
  scheduler.download(result.mesh, eat ? &removal.removed() : nullptr, label, &labels);
  if (options.regional_attributes) {
    result.triangle_attributes.resize(labels.size());
    for (std::size_t t = 0; t < labels.size(); ++t)
      result.triangle_attributes[t] = labels[t] >= 0 ? pslg.regions[labels[t]].attribute : 0.0;
  }

  // The segments as they stand, in input numbering; with -c the hull too.
  result.segments = input_numbering(constraints, scheduler, result.mesh.duplicate_of);
  result.crossed_segments = input_numbering(crossed, scheduler, result.mesh.duplicate_of);
  if (options.keep_convex_hull)
    add_hull_edges(result.mesh, result.segments);
  return result;
}

void add_hull_edges(const DelaunayResult &mesh, std::vector<Segment> &segments) {
  // Hull edges that are not constraints already.
  std::vector<Segment> all = segments;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i)
      if (mesh.neighbors[t][i] < 0)
        all.push_back({mesh.triangles[t][(i + 1) % 3], mesh.triangles[t][(i + 2) % 3], 1});
  const std::vector<char> first = first_occurrences(all);
  for (std::size_t k = segments.size(); k < all.size(); ++k)
    if (first[k])
      segments.push_back(all[k]);
}

} // namespace clmesh
