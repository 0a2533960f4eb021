// clmesh — GPU-QM step 1 (thesis §3.3.2, §3.4.1): bad triangles, their
// Steiner candidates and the insertion filter.
//
// A triangle is bad when its circumradius-to-shortest-edge ratio exceeds the
// bound of the minimum angle, or its area exceeds the maximum area. Its
// candidate is Üngör's off-center: the circumcenter, moved along the shortest
// edge's bisector to no farther than offconstant times that edge from its
// midpoint (as Triangle computes it). A candidate outside the hull, or inside
// the diametral lens of a hull edge of its container (Triangle's test: the
// candidate sees the edge at an angle of at least 180 - 2 x the minimum angle),
// becomes the midpoint of that hull edge (the convex hull is the boundary). A PSLG's domain is
// closed by ghosts as a hull is (domain_boundary.cl), and its interior segments act alike: a walk
// to a candidate stops at a subsegment, and a candidate in a subsegment's lens splits it. A
// subsegment that meets another segment at a small angle at one end is split on a power of two
// from that end (concentric shells, Ruppert's remedy for small input angles; shell_centre).
// -D tests diametral circles instead of lenses and makes triangles facing a subsegment with an
// obtuse angle bad; -Y keeps boundary edges (-YY all subsegments) whole. Priority: midpoints
// before off-centers (§3.4.1: segment-split before triangle-split), then for skinny triangles
// the shorter the shortest edge, the worse, and for those only too large the larger, the worse;
// containers are marked with atomic minimum of it, and a candidate
// survives the insertion filter when it owns its container's mark and no neighbouring container
// has a better one, nor one that goes first and would make it redundant in step 3 (GPU-QM-V).
// Quality decisions use floating point, as Triangle's do; the insertion that follows uses the exact
// predicates.
#include "common.h"
#include "election.h"
#include "group_scan.h"
#include "mesh_params.h"
#include "prefetch.h"
#include "refinement.h"

// Priorities are the bits of a positive float (the squared shortest edge, or
// its inverse):
// the top bit is free to rank off-centers after midpoints.
#define CLM_OFFCENTER_RANK 0x80000000u
static inline bool is_midpoint_priority(uint priority) { return !(priority & CLM_OFFCENTER_RANK); }
// A tie mark with no candidate (the host fills tie_mark with it too).
#define CLM_NO_CANDIDATE 0x7fffffff

// Marks the hull vertices (CLM_POINT_HULL), and among them those whose hull
// angle is below the minimum angle (CLM_POINT_ACUTE_HULL; cos_bound: its
// cosine; none when acute_bound is 0): no refinement can mend the angle
// every triangle there has at them (Triangle leaves those too). Run once, on
// the convex hull of the Delaunay triangulation, ghost by ghost.
// A vertex where the boundary passes twice (two holes, or a hole and the
// outside, touching there) ends acute if either corner is: the marks never
// turn an acute vertex back, whatever order the ghosts run in.
__kernel void flag_hull_vertices(CLM_MESH_PARAMS, const int acute_bound, const double cos_bound,
                                 volatile __global int *flagged, const int n) {
  const int g = get_global_id(0);
  if (g >= n)
    return;
  const VertexTriple tri = load_vertices(tri_vertex, g);
  if (!is_ghost(tri) || is_dead(tri))
    return;
  // Ghost (infinity, a, b) over hull edge a-b; the next ghost, across its
  // edge b-infinity, is (infinity, b, c).
  const int k = infinite_index(tri);
  const int a = tri.v[next3(k)], b = tri.v[prev3(k)];
  const int next = link_triangle(tri_neighbor[3 * g + next3(k)]);
  const VertexTriple following = load_vertices(tri_vertex, next);
  const int j = following.v[0] == b ? 0 : (following.v[1] == b ? 1 : 2);
  const int c =
      following.v[next3(j)] == CLM_INFINITE ? following.v[prev3(j)] : following.v[next3(j)];
  volatile __global int *state = (volatile __global int *)&point_state[b];
  for (int seen = *state; seen != CLM_POINT_HULL && seen != CLM_POINT_ACUTE_HULL;) {
    const int was = atomic_cmpxchg(state, seen, CLM_POINT_HULL);
    if (was == seen)
      break;
    seen = was;
  }
  // The domain lies left of c -> b -> a: a reflex corner of a PSLG's
  // boundary is not acute, however small the angle between its edges.
  if (!acute_bound || a < 0 || c < 0 || a == c || orient_vertices(points, c, b, a) <= 0)
    return;
  const double2 u = points[a] - points[b], w = points[c] - points[b];
  const double dot = u.x * w.x + u.y * w.y;
  const double lengths = sqrt((u.x * u.x + u.y * u.y) * (w.x * w.x + w.y * w.y));
  if (dot > cos_bound * lengths) // angle(a, b, c) below the bound
  {
    atomic_xchg(state, CLM_POINT_ACUTE_HULL);
    atomic_inc(flagged);
  }
}

// Whether a corner of the triangle is a hull vertex.
static inline bool touches_hull(__global const int *point_state, VertexTriple tri) {
  return on_hull(point_state[tri.v[0]]) || on_hull(point_state[tri.v[1]]) ||
         on_hull(point_state[tri.v[2]]);
}

// The quality of a real triangle: skinny (circumradius-to-shortest-edge
// ratio above the bound), large (area above max_area), its shortest edge
// (opposite vertex `shortest`, where its smallest angle is) and whether it
// cannot be mended: that angle is at an acute hull vertex or the input's
// (see below), or the triangle is flat, its corners within rounding noise of
// the line of its longest edge. A flat triangle lies in a sliver of the
// domain made by rounding (a boundary or segment chain a hair from straight
// beside a hull edge or another chain, which bound it, since the triangle
// across its longest edge would otherwise be Delaunay): every point that
// could split it lands within the same noise, and splitting it only makes
// more. Without segments (point_segment 0 in assess and the functions that
// call it) no angle is the input's.
typedef struct {
  double2 p[3];
  double length_squared[3];
  int shortest;
  bool skinny, large, unfixable;
} Quality;

// Do the ends of edge x-y lie on two segments that meet at a small input
// angle, at the same distance from where they meet? Then the triangle's small
// angle is the input's, and splitting it would only cut the shells around that
// vertex finer (Triangle leaves such triangles too).
static inline bool across_input_angle(__global const double2 *points,
                                      __global const int *point_segment,
                                      __global const int *segment_end, int x, int y) {
  const int sx = point_segment[x], sy = point_segment[y];
  if (sx < 0 || sy < 0 || sx == sy)
    return false;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const int apex = segment_end[2 * sx + i];
      if (apex != segment_end[2 * sy + j])
        continue;
      const double dx = squared_length(points[x] - points[apex]),
                   dy = squared_length(points[y] - points[apex]);
      return dx < 1.002 * dy && dy < 1.002 * dx;
    }
  return false;
}

// The tighter of two area bounds (<= 0: none).
static inline double tighter_bound(double a, double b) {
  if (b <= 0)
    return a;
  return a > 0 ? fmin(a, b) : b;
}

// The area bound of triangle slot t: -a's (max_area, <= 0: none); with
// regions, its region's (region_area, <= 0: none); with a sizing field or
// callback (sized), the slot's own (size_bound, size_bound.cl): the
// tightest.
static inline double area_bound_of(__global const int *tri_region, int regional,
                                   __global const double *region_area,
                                   __global const double *size_bound, int sized, double max_area,
                                   int t) {
  const int r = regional ? tri_region[t] : -1;
  const double bound = tighter_bound(max_area, r >= 0 ? region_area[r] : -1);
  return sized ? tighter_bound(bound, size_bound[t]) : bound;
}

// Do all three corners of tri lie on one segment (at least one added on it)?
// Rounded split points leave a segment a hair from straight, so flips may
// make such a sliver; splitting it would only make more.
static inline bool along_one_segment(__global const int *point_segment,
                                     __global const int *segment_end, VertexTriple tri) {
  int s = -1;
  for (int i = 0; i < 3 && s < 0; ++i)
    s = point_segment[tri.v[i]] >= 0 ? point_segment[tri.v[i]] : -1;
  if (s < 0)
    return false;
  for (int i = 0; i < 3; ++i)
    if (point_segment[tri.v[i]] != s && segment_end[2 * s] != tri.v[i] &&
        segment_end[2 * s + 1] != tri.v[i])
      return false;
  return true;
}

static inline Quality assess(__global const double2 *points, __global const int *point_state,
                             __global const int *point_segment, __global const int *segment_end,
                             VertexTriple tri, double ratio_bound_squared, double max_area) {
  Quality q;
  for (int i = 0; i < 3; ++i)
    q.p[i] = points[tri.v[i]];
  q.shortest = 0;
  for (int i = 0; i < 3; ++i) {
    const double2 d = q.p[prev3(i)] - q.p[next3(i)]; // edge opposite vertex i
    q.length_squared[i] = squared_length(d);
    if (q.length_squared[i] < q.length_squared[q.shortest])
      q.shortest = i;
  }
  const double2 d1 = q.p[1] - q.p[0], d2 = q.p[2] - q.p[0];
  const double twice_area = d1.x * d2.y - d1.y * d2.x;
  // R^2 / l^2 = (l0 l1 l2)^2 / (16 K^2 l^2) with l the shortest edge.
  const double ratio_squared = q.length_squared[0] * q.length_squared[1] * q.length_squared[2] /
                               (4.0 * twice_area * twice_area * q.length_squared[q.shortest]);
  q.skinny = ratio_bound_squared > 0 && ratio_squared > ratio_bound_squared;
  q.large = max_area > 0 && 0.5 * twice_area > max_area;
  q.unfixable =
      q.skinny && !q.large &&
      (point_state[tri.v[q.shortest]] == CLM_POINT_ACUTE_HULL || flat_corners(q.p) ||
       (point_segment && (along_one_segment(point_segment, segment_end, tri) ||
                          across_input_angle(points, point_segment, segment_end,
                                             tri.v[next3(q.shortest)], tri.v[prev3(q.shortest)]))));
  return q;
}

// The candidate of triangle `tri` when it is bad and can be mended: its
// off-center (Üngör's, as Triangle computes it, on the side of the shortest
// edge), its priority, the shortest edge's squared length as a float, and
// whether it is bad by its area alone (area_only). The search and the
// location both compute it, so that no per-slot copy is kept.
// -Y (protect 1): does edge i of real triangle t lie on the domain's
// boundary? -YY (protect 2): or on a segment? No point may split it.
static inline bool is_protected(CLM_MESH_PARAMS, int t, int i, int protect) {
  return protect && (is_ghost(load_vertices(tri_vertex, link_triangle(tri_neighbor[3 * t + i]))) ||
                     (protect > 1 && subsegment_at(CLM_MESH_ARGS, t, i)));
}

// The protected edges of real triangle t, bit i for edge i.
static inline int protected_edges(CLM_MESH_PARAMS, int t, int protect) {
  int mask = 0;
  for (int i = 0; i < 3 && protect; ++i)
    mask |= is_protected(CLM_MESH_ARGS, t, i, protect) << i;
  return mask;
}

// Does c lie on or beyond (right of) an edge of triangle p[] in mask?
static inline bool beyond_edges(const double2 *p, int mask, double2 c) {
  for (int i = 0; i < 3; ++i) {
    const double2 a = p[next3(i)], e = p[prev3(i)] - a, f = c - a;
    if ((mask >> i & 1) && e.x * f.y - e.y * f.x <= 0)
      return true;
  }
  return false;
}

static inline bool bad_triangle_candidate(__global const double2 *points,
                                          __global const int *point_state,
                                          __global const int *point_segment,
                                          __global const int *segment_end, VertexTriple tri,
                                          double ratio_bound_squared, double max_area,
                                          double offconstant, bool encroaching, int protected_mask,
                                          double2 *steiner, uint *priority, bool *area_only) {
  const Quality q =
      assess(points, point_state, point_segment, segment_end, tri, ratio_bound_squared, max_area);
  if (!encroaching && ((!q.skinny && !q.large) || q.unfixable))
    return false;
  if (encroaching && flat_corners(q.p))
    return false; // -D: a flat triangle faces its longest edge at about 180 degrees; left
  // Circumcenter relative to a, the origin of the shortest edge a-b (r: apex).
  const int shortest = q.shortest;
  const double2 a = q.p[next3(shortest)], b = q.p[prev3(shortest)], r = q.p[shortest];
  const double2 e = b - a, f = r - a;
  const double e2 = squared_length(e), f2 = squared_length(f);
  const double denominator = 2.0 * (e.x * f.y - e.y * f.x);
  const double2 center =
      (double2)((f.y * e2 - e.y * f2) / denominator, (e.x * f2 - f.x * e2) / denominator);
  const double2 middle = 0.5 * e, away = center - middle; // from the edge's midpoint
  const double reach = offconstant * sqrt(e2), distance = sqrt(squared_length(away));
  const double2 offset =
      !encroaching && distance > reach ? middle + away * (reach / distance) : center;
  *steiner = a + offset;
  // Skinny triangles: the shorter the shortest edge, the worse. Triangles
  // only too large: the larger the better, so that an area bound refines the
  // whole domain at once rather than as a front from where it began.
  *area_only = !q.skinny && !encroaching;
  *priority = as_uint(*area_only ? (float)(1.0 / q.length_squared[shortest])
                                 : (float)q.length_squared[shortest]);
  // A degenerate computation leaves the triangle alone, and so does a
  // candidate beyond an edge of its own that no point may split (-Y).
  return isfinite(steiner->x) && isfinite(steiner->y) &&
         !beyond_edges(q.p, protected_mask, *steiner);
}

// The second triangle a candidate on an edge splits (a ghost for a hull
// midpoint), or -1.
static inline int split_partner(__global const int *tri_neighbor, __global const int *container,
                                __global const int *split_edge, int k) {
  return split_edge[k] < 0 ? -1 : link_triangle(tri_neighbor[3 * container[k] + split_edge[k]]);
}

// Whether located candidate k splits a hull edge (its partner is a ghost) or
// a subsegment.
static inline bool splits_subsegment(CLM_MESH_PARAMS, __global const int *container,
                                     __global const int *split_edge, int k) {
  const int partner = split_partner(tri_neighbor, container, split_edge, k);
  if (partner < 0)
    return false;
  if (is_ghost(load_vertices(tri_vertex, partner)))
    return true;
  return subsegment_at(CLM_MESH_ARGS, container[k], split_edge[k]);
}

// Is edge i of real triangle t a subsegment or on the domain's boundary? A
// ghost lies across boundary edges only, whose ends are hull vertices: their
// states, at hand, spare most edges the read of the triangle across.
static inline bool bounds_domain(CLM_MESH_PARAMS, int t, int i) {
  return (on_hull(point_state[tri_vertex[3 * t + next3(i)]]) &&
          on_hull(point_state[tri_vertex[3 * t + prev3(i)]]) &&
          is_ghost(load_vertices(tri_vertex, link_triangle(tri_neighbor[3 * t + i])))) ||
         subsegment_at(CLM_MESH_ARGS, t, i);
}

// The cosine of the angle at vertex o between o-x and o-y.
static inline double corner_cosine(__global const double2 *points, int o, int x, int y) {
  const double2 u = points[x] - points[o], w = points[y] - points[o];
  return (u.x * w.x + u.y * w.y) / sqrt(squared_length(u) * squared_length(w));
}

// The end of subsegment (or boundary edge) e of real triangle t around which
// it is split on a shell, or -1 (at its midpoint). An end is a candidate when
// segments meet there and another subsegment or boundary edge at it is an
// edge of t or of the triangle across e (as Triangle decides), at an acute
// angle to e: only there can points on one segment encroach on the other.
// Of two candidate ends the one at the smaller angle is the centre, so that
// a segment leaving a fan of small angles is split on the fan's shells
// however its far end meets the boundary (two ends at equal angles: the
// midpoint).
static inline int shell_centre(CLM_MESH_PARAMS, int t, int e) {
  const int a = tri_vertex[3 * t + next3(e)], b = tri_vertex[3 * t + prev3(e)];
  const bool joint_a = point_segment[a] == CLM_SEGMENT_JOINT,
             joint_b = point_segment[b] == CLM_SEGMENT_JOINT;
  if (!joint_a && !joint_b)
    return -1;
  // Across e, u = (d, b, a): its edge next3(j) ends at a, prev3(j) at b.
  const int link = tri_neighbor[3 * t + e], u = link_triangle(link), j = link_edge(link);
  const bool real_u = !is_ghost(load_vertices(tri_vertex, u));
  const int c = tri_vertex[3 * t + e], d = real_u ? tri_vertex[3 * u + j] : -1;
  double cos_a = -2, cos_b = -2;
  if (joint_a && bounds_domain(CLM_MESH_ARGS, t, prev3(e)))
    cos_a = corner_cosine(points, a, b, c);
  if (joint_a && real_u && bounds_domain(CLM_MESH_ARGS, u, next3(j)))
    cos_a = fmax(cos_a, corner_cosine(points, a, b, d));
  if (joint_b && bounds_domain(CLM_MESH_ARGS, t, next3(e)))
    cos_b = corner_cosine(points, b, a, c);
  if (joint_b && real_u && bounds_domain(CLM_MESH_ARGS, u, prev3(j)))
    cos_b = fmax(cos_b, corner_cosine(points, b, a, d));
  if (fmax(cos_a, cos_b) <= 0 || cos_a == cos_b)
    return -1;
  return cos_a > cos_b ? a : b;
}

// The point that splits subsegment (or hull edge) a-b: its midpoint; or, with
// a shell centre (a or b, see shell_centre), the point at a power of two from
// it between a third and two thirds of the way (concentric shells: segments
// that meet at a small angle are split at the same distances from their
// common vertex, so that they stop encroaching on each other).
static inline double2 subsegment_split(__global const double2 *points, int centre, int a, int b) {
  if (centre < 0)
    return 0.5 * (points[a] + points[b]);
  const bool from_a = centre == a;
  const double2 from = from_a ? points[a] : points[b], to = from_a ? points[b] : points[a];
  const double length = sqrt(squared_length(to - from));
  int exponent;
  frexp(length / 1.5, &exponent);
  const double shell = ldexp(1.0, exponent - 1); // 1.5 shell <= length < 3 shell
  return from + (to - from) * (shell / length);
}

// Split point s of edge a-b of the domain's boundary (the domain left of
// a -> b), moved back onto a-b or inside when rounding left it beyond: one
// unit in the last place at a time toward the inside, a few times at most.
// When parts of a PSLG's domain lie a hair apart (polygons whose edges
// overlap a hair from collinear: the exterior or a hole between them has
// flat triangles; `inward`, see Refinement), the domain then never grows by
// rounding into another part. Otherwise nothing lies beyond, and the split
// point stays as rounding leaves it.
static inline double2 inside_edge(__global const double2 *points, int a, int b, double2 s) {
  const double2 normal = (double2)(points[a].y - points[b].y, points[b].x - points[a].x);
  for (int step = 0; step < 4 && orient_point(points, a, b, s) < 0; ++step) {
    if (normal.x != 0)
      s.x = nextafter(s.x, normal.x > 0 ? (double)INFINITY : -(double)INFINITY);
    if (normal.y != 0)
      s.y = nextafter(s.y, normal.y > 0 ? (double)INFINITY : -(double)INFINITY);
  }
  return s;
}

// Can boundary edge or subsegment e of real triangle t be split within the
// precision of the arithmetic? Its split point (subsegment_split, in *split;
// on a boundary edge with `inward`, kept inside: inside_edge) must leave
// every new triangle counter-clockwise (on a run of boundary
// points a hair from straight it may not), and lie farther than rounding
// noise from the ends of e and from the apexes on both sides: within it, it
// is that vertex to the arithmetic (a hull edge that -c makes a boundary
// edge, passing a hair from boundary vertices, would be split onto them, and
// its pieces again, down to lengths of the noise). An edge that cannot be
// split is kept whole as -Y keeps the boundary: a candidate in its lens goes
// in all the same, one beyond it is dropped, and a bad triangle whose
// candidate lies beyond it is left (stranded).
static inline bool splittable(CLM_MESH_PARAMS, int inward, int t, int e, double2 *split) {
  const int a = tri_vertex[3 * t + next3(e)], b = tri_vertex[3 * t + prev3(e)],
            apex = tri_vertex[3 * t + e];
  const int link = tri_neighbor[3 * t + e], u = link_triangle(link);
  const bool boundary = is_ghost(load_vertices(tri_vertex, u));
  double2 s = subsegment_split(points, shell_centre(CLM_MESH_ARGS, t, e), a, b);
  if (boundary && inward)
    s = inside_edge(points, a, b, s);
  *split = s;
  const double noise = rounding_noise(points[a], points[b]);
  if (indistinct(s, points[a], noise) || indistinct(s, points[b], noise) ||
      indistinct(s, points[apex], noise) || orient_point(points, apex, a, s) <= 0 ||
      orient_point(points, b, apex, s) <= 0 ||
      (boundary && inward && orient_point(points, a, b, s) < 0))
    return false;
  if (boundary)
    return true;
  const int across = tri_vertex[3 * u + link_edge(link)]; // (across, b, a) splits too
  return !indistinct(s, points[across], noise) && orient_point(points, across, b, s) > 0 &&
         orient_point(points, a, across, s) > 0;
}

// The edges of real triangle t that bound the domain and that candidate c
// lies on or beyond, bit i for edge i.
static inline int edges_behind(CLM_MESH_PARAMS, int t, VertexTriple tri, double2 c) {
  double2 p[3];
  for (int i = 0; i < 3; ++i)
    p[i] = points[tri.v[i]];
  int mask = 0;
  for (int i = 0; i < 3; ++i)
    if (beyond_edges(p, 1 << i, c) && bounds_domain(CLM_MESH_ARGS, t, i))
      mask |= 1 << i;
  return mask;
}

// Can an edge of real triangle t in mask not be split (splittable)?
static inline bool unsplittable_edge(CLM_MESH_PARAMS, int inward, int t, int mask) {
  double2 split;
  for (int i = 0; i < 3; ++i)
    if ((mask >> i & 1) && !splittable(CLM_MESH_ARGS, inward, t, i, &split))
      return true;
  return false;
}

// Does candidate c of bad real triangle t lie on or beyond an edge of t
// that bounds the domain and cannot be split (splittable)? No point then
// mends t: it is left and counted.
static inline bool stranded(CLM_MESH_PARAMS, int inward, int t, VertexTriple tri, double2 c) {
  return unsplittable_edge(CLM_MESH_ARGS, inward, t, edges_behind(CLM_MESH_ARGS, t, tri, c));
}

// notes[t] of a bad triangle slot, set by the search that assessed it (of
// a slot found not bad: 0, or the stuck bit while it holds): whether its
// candidate splits an edge of its own on the boundary
// (splits_own_edge, with an election; see elect_candidates), the edges that
// bound the domain and its candidate lies on or beyond (edges_behind: the
// triangle is stranded once one of them cannot be split), the edges whose
// subsegment test reads the apex across them (apex_dependent_edges), and
// whether a location since found it stuck (is_stuck; set by
// locate_candidates).
#define CLM_NOTE_SPLITS_OWN_EDGE 1
#define CLM_NOTE_BEHIND_SHIFT 1 // 3 bits
#define CLM_NOTE_APEX_SHIFT 4   // 3 bits
#define CLM_NOTE_STUCK 0x80
#define CLM_NOTE_AREA_ONLY 0x100 // see settle_elected

// Is bad triangle t stuck: did a location drop its candidate beyond a
// boundary edge or subsegment that cannot be split (splittable), not one of
// t's own? The location sets the stuck bit of t's notes (CLM_NOTE_STUCK); it
// holds while t is not rewritten since, that is while t's stamp is below
// located_stamp, the last location's: a t rewritten since is assessed again
// by the next search, which clears the bit (find_bad_triangles). Such a
// triangle is left and counted as a stranded one is, until a compaction or
// growth renews the steps (the notes) and its candidate is located again.
static inline bool is_stuck(__global const int *modified_stamp, __global const int *notes,
                            int located_stamp, int t) {
  return (notes[t] & CLM_NOTE_STUCK) && modified_stamp[t] < located_stamp;
}

// Does candidate c of bad real triangle t split an edge of its own on the
// domain's boundary or a subsegment, one a point may split (-Y): does c lie
// on or beyond it, or in its diametral lens (`lens`, Triangle's test)? The
// location (locate_candidates) then nearly always makes c that edge's
// midpoint; the other candidates of triangles with a corner on the boundary
// become midpoints far less often.
static inline bool splits_own_edge(CLM_MESH_PARAMS, int t, VertexTriple tri, double2 c, double lens,
                                   int protect) {
  for (int i = 0; i < 3; ++i) {
    const int a = tri.v[next3(i)], b = tri.v[prev3(i)];
    if (!on_hull(point_state[a]) || !on_hull(point_state[b]))
      continue;
    const double2 pa = points[a], e = points[b] - pa, f = c - pa;
    if ((e.x * f.y - e.y * f.x <= 0 || in_lens(pa, points[b], c, lens)) &&
        bounds_domain(CLM_MESH_ARGS, t, i) && !is_protected(CLM_MESH_ARGS, t, i, protect))
      return true;
  }
  return false;
}

// -D (conforming Delaunay): does real triangle t have an edge on a subsegment
// or the boundary whose diametral circle holds the opposite vertex (the angle
// there is obtuse)? Its circumcenter then lies beyond that edge, so the walk
// to it stops there and the edge is split.
static inline bool encroaches_subsegment(CLM_MESH_PARAMS, int t, VertexTriple tri) {
  for (int i = 0; i < 3; ++i) {
    const double2 r = points[tri.v[i]], a = points[tri.v[next3(i)]] - r,
                  b = points[tri.v[prev3(i)]] - r;
    if (a.x * b.x + a.y * b.y >= 0)
      continue;
    return is_ghost(load_vertices(tri_vertex, link_triangle(tri_neighbor[3 * t + i]))) ||
           subsegment_at(CLM_MESH_ARGS, t, i);
  }
  return false;
}

// The edges of real triangle t whose subsegment test (is_subsegment) reads
// the apex across them: an end was added on a segment. The test of the
// others, and whether an edge lies on the domain's boundary (a ghost
// across), stay as they are while t is not rewritten.
static inline int apex_dependent_edges(CLM_MESH_PARAMS, VertexTriple tri) {
  int mask = 0;
  for (int i = 0; i < 3 && constrained; ++i)
    if (point_segment[tri.v[next3(i)]] >= 0 || point_segment[tri.v[prev3(i)]] >= 0)
      mask |= 1 << i;
  return mask;
}

// Is bad triangle t as the last search assessed it (stamp: that search's
// stamp)? Neither t nor a triangle across an apex-dependent edge of its
// notes is rewritten since: its corners, their points and segments, its
// area bound and its edges' subsegment tests are the same, and so are the
// states of its corners: a Steiner point marked redundant since was either
// deleted, which rewrote t, or kept as it was (points added since are corners
// of rewritten triangles only).
static inline bool assessed_as_is(CLM_MESH_PARAMS, int t, int note, int stamp) {
  if (modified_stamp[t] >= stamp)
    return false;
  for (int i = 0; i < 3; ++i)
    if ((note >> (CLM_NOTE_APEX_SHIFT + i) & 1) &&
        modified_stamp[link_triangle(tri_neighbor[3 * t + i])] >= stamp)
      return false;
  return true;
}

// Prefetching for find_bad_triangles over a list (prefetch.h): every entry
// needs its stamp, notes and triangle; one carried from the last
// search (below `carried`) that is as assessed needs its mark, the others
// their corners, and in a constrained mesh their segments (point_segment
// and constraint_start, else 0).
static inline void prefetch_search(__global const int *list, int gid, int n, int carried, int stamp,
                                   __global const double2 *points, __global const int *point_state,
                                   __global const int *point_segment,
                                   __global const int *constraint_start,
                                   __global const int *tri_vertex,
                                   __global const int *modified_stamp, __global const int *notes,
                                   volatile __global const uint *tri_mark) {
  const int far = entry_ahead(list, gid, 2, n);
  if (far >= 0) {
    warm(modified_stamp + far);
    warm(notes + far);
    warm(tri_vertex + 3 * far);
  }
  const int near = entry_ahead(list, gid, 1, n);
  if (near >= 0 && gid + CLM_AHEAD < carried && modified_stamp[near] < stamp) {
    warm_for_write(tri_mark + near);
  } else {
    warm_corners(points, point_state, tri_vertex, near);
    if (point_segment)
      warm_corner_segments(point_segment, constraint_start, tri_vertex, near);
  }
}

// Per entry: is_bad[gid] for the triangle list[gid] (use_list), else for
// slot gid. The list holds the bad triangles of the last search, first, in
// its order (the first `carried` entries), and the triangles changed since:
// the others are still good (thesis §3.3.2). A carried one that is as that
// search assessed it (assessed_as_is; searched_stamp: its stamp) keeps its
// verdict: only whether an edge behind its candidate can still be split and
// whether it got stuck are asked again, and with an election its mark is the
// one kept in carried_mark[gid]. Every other triangle is assessed. With an
// election, each bad triangle marks its slot with its priority, ranked as a
// midpoint's when a corner is on the hull; each one assessed sets notes[slot].
// find_bad_triangles' arguments after the mesh's (see there), shared with
// search_in_group.
#define CLM_SEARCH_PARAMS                                                                          \
  __global int *list, const int use_list, const int carried, const int searched_stamp,             \
      __global uint *carried_mark, const double ratio_bound_squared, const double max_area,        \
      __global const double *region_area, __global const double *size_bound, const int sized,      \
      const double offconstant, const int conforming, const int protect, const int inward,         \
      const int located_stamp, __global int *is_bad, const int election, const double lens,        \
      __global int *notes
#define CLM_SEARCH_ARGS                                                                            \
  list, use_list, carried, searched_stamp, carried_mark, ratio_bound_squared, max_area,            \
      region_area, size_bound, sized, offconstant, conforming, protect, inward, located_stamp,     \
      is_bad, election, lens, notes

// Entry gid of find_bad_triangles (of n).
static inline void search_entry(CLM_MESH_PARAMS, CLM_SEARCH_PARAMS, const int gid, const int n) {
  if (use_list)
    prefetch_search(list, gid, n, carried, searched_stamp, points, point_state, CLM_SEGMENTS_IF_ANY,
                    constraint_start, tri_vertex, modified_stamp, notes, tri_mark);
  else
    warm_corners(points, point_state, tri_vertex, slot_ahead(gid, 1, n));
  const int t = use_list ? list[gid] : gid;
  if (gid < carried) {
    const int note = notes[t];
    if (assessed_as_is(CLM_MESH_ARGS, t, note, searched_stamp)) {
      const bool bad =
          !unsplittable_edge(CLM_MESH_ARGS, inward, t, note >> CLM_NOTE_BEHIND_SHIFT & 7) &&
          !(note & CLM_NOTE_STUCK);
      is_bad[gid] = bad;
      if (bad && election)
        tri_mark[t] = carried_mark[gid];
      return;
    }
  }
  const VertexTriple tri = load_vertices(tri_vertex, t);
  double2 steiner;
  uint priority;
  bool area_only;
  bool bad = !is_ghost(tri) && !is_dead(tri) &&
             bad_triangle_candidate(
                 points, point_state, CLM_SEGMENTS_IF_ANY, segment_end, tri, ratio_bound_squared,
                 area_bound_of(tri_region, regional, region_area, size_bound, sized, max_area, t),
                 offconstant, conforming && encroaches_subsegment(CLM_MESH_ARGS, t, tri),
                 protected_edges(CLM_MESH_ARGS, t, protect), &steiner, &priority, &area_only);
  const int behind = bad ? edges_behind(CLM_MESH_ARGS, t, tri, steiner) : 0;
  const bool stuck = is_stuck(modified_stamp, notes, located_stamp, t);
  bad = bad && !unsplittable_edge(CLM_MESH_ARGS, inward, t, behind) && !stuck;
  is_bad[gid] = bad;
  if (!bad) {
    notes[t] = stuck ? CLM_NOTE_STUCK : 0; // a stuck bit from before a rewrite goes
    return;
  }
  int note = (behind << CLM_NOTE_BEHIND_SHIFT) |
             (apex_dependent_edges(CLM_MESH_ARGS, tri) << CLM_NOTE_APEX_SHIFT);
  if (election) {
    tri_mark[t] = touches_hull(point_state, tri) ? priority : priority | CLM_OFFCENTER_RANK;
    if (splits_own_edge(CLM_MESH_ARGS, t, tri, steiner, lens, protect))
      note |= CLM_NOTE_SPLITS_OWN_EDGE;
    if (area_only)
      note |= CLM_NOTE_AREA_ONLY;
  }
  notes[t] = note;
}

__kernel void find_bad_triangles(CLM_MESH_PARAMS, CLM_SEARCH_PARAMS, const int n) {
  const int gid = get_global_id(0);
  if (gid < n)
    search_entry(CLM_MESH_ARGS, CLM_SEARCH_ARGS, gid, n);
}

// counts[0]: the bad triangles left as they are, counted at the end over
// every slot: those whose smallest angle is the input's or which are flat
// (assess; with -D, flat ones that face a subsegment obtusely), those whose candidate lies beyond
// an edge that cannot be split (stranded, is_stuck), and with -Y those whose candidate lies beyond
// an edge of their own no point may split.
__kernel void count_unfixable_triangles(CLM_MESH_PARAMS, const double ratio_bound_squared,
                                        const double max_area, __global const double *region_area,
                                        __global const double *size_bound, const int sized,
                                        const double offconstant, const int conforming,
                                        const int protect, const int inward,
                                        __global const int *notes, const int located_stamp,
                                        volatile __global int *counts, const int n) {
  const int t = get_global_id(0);
  if (t >= n)
    return;
  warm_corners(points, point_state, tri_vertex, slot_ahead(t, 1, n));
  const VertexTriple tri = load_vertices(tri_vertex, t);
  if (is_ghost(tri) || is_dead(tri))
    return;
  const double bound =
      area_bound_of(tri_region, regional, region_area, size_bound, sized, max_area, t);
  const Quality q = assess(points, point_state, CLM_SEGMENTS_IF_ANY, segment_end, tri,
                           ratio_bound_squared, bound);
  const bool encroaching = conforming && encroaches_subsegment(CLM_MESH_ARGS, t, tri);
  if (!q.skinny && !q.large && !encroaching)
    return; // a good triangle: no candidate, nothing to count
  double2 steiner;
  uint priority;
  bool area_only;
  const int mask = protected_edges(CLM_MESH_ARGS, t, protect);
  if (q.unfixable || (encroaching && flat_corners(q.p)) ||
      (mask &&
       bad_triangle_candidate(points, point_state, CLM_SEGMENTS_IF_ANY, segment_end, tri,
                              ratio_bound_squared, bound, 1e300, false, 0, &steiner, &priority,
                              &area_only) &&
       beyond_edges(q.p, mask, steiner)) ||
      (bad_triangle_candidate(points, point_state, CLM_SEGMENTS_IF_ANY, segment_end, tri,
                              ratio_bound_squared, bound, offconstant, encroaching, mask, &steiner,
                              &priority, &area_only) &&
       (stranded(CLM_MESH_ARGS, inward, t, tri, steiner) ||
        is_stuck(modified_stamp, notes, located_stamp, t))))
    atomic_inc(counts);
}

// The bad triangles as a list in the order of the search (offsets by prefix
// sum), so that candidate k is the same on every device and for every
// work-group size; with an election, each one's mark in carried_mark, for
// the next search (find_bad_triangles).
static inline void gather_bad_entry(__global const int *is_bad, __global const int *offset,
                                    __global const int *list, const int use_list,
                                    volatile __global const uint *tri_mark, const int election,
                                    __global int *origin, __global uint *carried_mark,
                                    const int gid) {
  if (!is_bad[gid])
    return;
  const int t = use_list ? list[gid] : gid;
  origin[offset[gid]] = t;
  if (election)
    carried_mark[offset[gid]] = tri_mark[t];
}

__kernel void gather_bad_triangles(__global const int *is_bad, __global const int *offset,
                                   __global const int *list, const int use_list,
                                   __global const uint *tri_mark, const int election,
                                   __global int *origin, __global uint *carried_mark, const int n) {
  const int gid = get_global_id(0);
  if (gid < n)
    gather_bad_entry(is_bad, offset, list, use_list, tri_mark, election, origin, carried_mark, gid);
}

// Before the triangles move (zorder_compaction.cl): flags[t] = 1 for each
// slot t that a search after the move must assess again, the others being
// left as good. A triangle was good at its last assessment unless the last
// search found it bad (bad[0 .. bad_count)) or left it out as stuck (its
// notes, set in the first `noted` slots), and it is as then unless it was
// rewritten since (changed[0 .. changed_count), negative entries none). A
// search over every slot would find no other bad triangle. flags: 0 before.
__kernel void flag_unsettled(__global const int *bad, const int bad_count,
                             __global const int *changed, const int changed_count,
                             __global const int *notes, const int noted, __global int *flags,
                             const int n) {
  const int gid = get_global_id(0);
  if (gid >= n)
    return;
  if (gid < bad_count)
    flags[bad[gid]] = 1;
  if (gid < changed_count && changed[gid] >= 0)
    flags[changed[gid]] = 1;
  if (gid < noted && (notes[gid] & CLM_NOTE_STUCK))
    flags[gid] = 1;
}

// Prefetching for a kernel that reads the marks of `rings` rings of
// triangles (2 or 3) around each triangle of `list` (prefetch.h): the
// triangle's mark (and its entry in `also`, the tie marks or notes, or 0:
// none) and links, then its neighbours' marks and links, then the marks of
// theirs, with three rings their links too and each stage one earlier
// (warming the third ring's marks as well costs more than it saves).
static inline void prefetch_rings(__global const int *list, int k, int n,
                                  volatile __global const uint *tri_mark, __global const int *also,
                                  __global const int *tri_neighbor, const int rings) {
  const int far = entry_ahead(list, k, rings + 1, n);
  if (far >= 0) {
    warm(tri_mark + far);
    if (also)
      warm(also + far);
    warm(tri_neighbor + 3 * far);
  }
  const int middle = entry_ahead(list, k, rings, n);
  for (int i = 0; i < 3 && middle >= 0; ++i) {
    const int u = link_triangle(tri_neighbor[3 * middle + i]);
    warm(tri_mark + u);
    warm(tri_neighbor + 3 * u);
  }
  const int near = entry_ahead(list, k, rings - 1, n);
  for (int i = 0; i < 3 && near >= 0; ++i) {
    const int u = link_triangle(tri_neighbor[3 * near + i]);
    for (int j = 0; j < 3 && u >= 0; ++j) {
      const int w = link_triangle(tri_neighbor[3 * u + j]);
      warm(tri_mark + w);
      if (rings > 2)
        warm(tri_neighbor + 3 * w);
    }
  }
}

// Are the marks of the triangles within `rings` rings of t (1: its
// neighbours; 2: and theirs), t itself left out, all at least `least`?
static inline bool marks_around_at_least(__global const int *tri_neighbor,
                                         volatile __global const uint *tri_mark, const int rings,
                                         int t, uint least) {
  for (int i = 0; i < 3; ++i) {
    const int u = link_triangle(tri_neighbor[3 * t + i]);
    if (tri_mark[u] < least)
      return false;
    for (int j = 0; j < 3 && rings > 1; ++j) {
      const int w = link_triangle(tri_neighbor[3 * u + j]);
      if (w != t && tri_mark[w] < least)
        return false;
    }
  }
  return true;
}

// The election (GPU-QM-V): bad triangle bad[k] sends a candidate in this
// iteration only when no bad triangle within `rings` rings of it (1: its
// neighbours; 2: and theirs) has a better priority (the marks of
// find_bad_triangles); equal priorities all send theirs. The others, whose
// candidates the insertion filter would mostly leave out, wait for a later
// iteration without being located, which saves most of the location and
// filtering work. The best bad triangle always sends its candidate, so the
// refinement goes on. So do those whose candidate splits an edge of their
// own on the boundary (notes, set by find_bad_triangles): hull
// midpoints never keep each other out, so the bad triangles along the hull
// do not wait for each other in turn. The others with a corner on the
// boundary rank before the rest but take part: along a PSLG's jagged
// outline they are most bad triangles, their candidates are mostly
// off-centers, and most of those would lose in the filter.
static inline bool is_elected(__global const int *bad, __global const int *tri_neighbor,
                              volatile __global const uint *tri_mark, const int rings,
                              __global const int *notes, const int k) {
  const int t = bad[k];
  return (notes[t] & CLM_NOTE_SPLITS_OWN_EDGE) ||
         marks_around_at_least(tri_neighbor, tri_mark, rings, t, tri_mark[t]);
}

__kernel void elect_candidates(__global const int *bad, __global const int *tri_neighbor,
                               __global const uint *tri_mark, const int rings,
                               __global const int *notes, __global int *elected, const int n) {
  const int k = get_global_id(0);
  prefetch_rings(bad, k, n, tri_mark, notes, tri_neighbor, 2);
  if (k < n)
    elected[k] = is_elected(bad, tri_neighbor, tri_mark, rings, notes, k);
}

// A second round of the election (Luby's), when triangles may have an area
// bound and the first round elected fewer than one bad triangle in
// CLM_SECOND_ROUND_SHARE (cl/election.h): a triangle bad by its area alone
// (CLM_NOTE_AREA_ONLY, set by find_bad_triangles) that the first round left
// out, with no elected triangle within `rings` rings (no mark 0 there), is
// elected when no such triangle within them has a better priority. Where an area bound refines
// large triangles, the first round elects about one bad triangle in seven and the second about
// doubles that, with points the area bound mostly asks for anyway (for the angle bound it would add
// points that later insertions make needless). Three passes, each reading only marks the others do
// not write: the elected triangles mark their slots 0, which no priority beats (settle_elected);
// the others that take no part clear their marks (retire_blocked); those left are elected as in the
// first round (elect_again). gather_elected clears every mark after.
static inline void settle_elected_entry(__global const int *bad, __global const int *elected,
                                        volatile __global uint *tri_mark, const int k) {
  if (elected[k])
    tri_mark[bad[k]] = 0;
}

static inline void retire_blocked_entry(__global const int *bad, __global const int *tri_neighbor,
                                        volatile __global uint *tri_mark, const int rings,
                                        __global const int *notes, __global const int *elected,
                                        const int k) {
  const int t = bad[k];
  if (!elected[k] && (!(notes[t] & CLM_NOTE_AREA_ONLY) ||
                      !marks_around_at_least(tri_neighbor, tri_mark, rings, t, 1)))
    tri_mark[t] = CLM_NO_MARK;
}

static inline void elect_again_entry(__global const int *bad, __global const int *tri_neighbor,
                                     volatile __global const uint *tri_mark, const int rings,
                                     __global const int *notes, __global int *elected,
                                     const int k) {
  if (!elected[k] && tri_mark[bad[k]] != CLM_NO_MARK)
    elected[k] = is_elected(bad, tri_neighbor, tri_mark, rings, notes, k);
}

__kernel void settle_elected(__global const int *bad, __global const int *elected,
                             __global uint *tri_mark, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    settle_elected_entry(bad, elected, tri_mark, k);
}

__kernel void retire_blocked(__global const int *bad, __global const int *tri_neighbor,
                             __global uint *tri_mark, const int rings, __global const int *notes,
                             __global const int *elected, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    retire_blocked_entry(bad, tri_neighbor, tri_mark, rings, notes, elected, k);
}

__kernel void elect_again(__global const int *bad, __global const int *tri_neighbor,
                          __global const uint *tri_mark, const int rings, __global const int *notes,
                          __global int *elected, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    elect_again_entry(bad, tri_neighbor, tri_mark, rings, notes, elected, k);
}

// The elected bad triangles as the candidates' origins (offsets by prefix sum),
// each bad triangle's mark cleared. One left waiting forgets where its last
// candidate was: it may be rewritten before the next search that locates it.
static inline void gather_elected_entry(__global const int *bad, __global const int *elected,
                                        __global const int *offset,
                                        volatile __global uint *tri_mark,
                                        __global int *last_container, __global int *origin,
                                        const int k) {
  const int t = bad[k];
  tri_mark[t] = CLM_NO_MARK;
  if (elected[k])
    origin[offset[k]] = t;
  else
    last_container[t] = -1;
}

__kernel void gather_elected(__global const int *bad, __global const int *elected,
                             __global const int *offset, __global uint *tri_mark,
                             __global int *last_container, __global int *origin, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    gather_elected_entry(bad, elected, offset, tri_mark, last_container, origin, k);
}

// A short search by one work-group (the first part of step_one_in_group):
// the last search's `last_bad` bad triangles (bad) and the
// `changed_count` triangles changed since copied to `search`, its duplicates
// removed into list (group_unique, with unique_keep and unique_offset; with
// use_list 0 both counts are 0 and the search sweeps the `slots` slots), then
// find_bad_triangles, the bad ones' prefix sum and gather_bad_triangles
// (into bad), and with an election (rings > 0) elect_candidates (and its
// second round where second_round allows it, settle_elected), the elected
// ones' prefix sum and gather_elected (into origin). counts[0..3): the
// entries searched, the bad triangles, the candidates. The barriers stand
// outside any data-dependent branch.
#define CLM_SEARCH_GROUP_PARAMS                                                                    \
  __global int *bad, const int last_bad, __global const int *changed, const int changed_count,     \
      __global int *search, __global int *unique_keep, __global int *unique_offset,                \
      __global int *offset, const int rings, const int second_round, __global int *last_container, \
      __global int *origin, __local int *scratch, __global int *counts, const int slots
#define CLM_SEARCH_GROUP_ARGS                                                                      \
  bad, last_bad, changed, changed_count, search, unique_keep, unique_offset, offset, rings,        \
      second_round, last_container, origin, scratch, counts, slots
// Returns the bad triangles and the candidates to every work-item.
static inline int2 search_in_group(CLM_MESH_PARAMS, CLM_SEARCH_PARAMS, CLM_SEARCH_GROUP_PARAMS) {
  const int lid = get_local_id(0), size = get_local_size(0);
  for (int i = lid; i < last_bad; i += size)
    search[i] = bad[i];
  for (int i = lid; i < changed_count; i += size)
    search[last_bad + i] = changed[i];
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int listed = group_unique(search, last_bad + changed_count, tri_mark, unique_keep,
                                  unique_offset, list, scratch);
  const int n = use_list ? listed : slots;
  for (int k = lid; k < n; k += size)
    search_entry(CLM_MESH_ARGS, CLM_SEARCH_ARGS, k, n);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int bad_count = group_exclusive_scan(is_bad, offset, n, scratch);
  for (int k = lid; k < n; k += size)
    gather_bad_entry(is_bad, offset, list, use_list, tri_mark, election, bad, carried_mark, k);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int electing = rings > 0 ? bad_count : 0;
  for (int k = lid; k < electing; k += size) {
    prefetch_rings(bad, k, electing, tri_mark, notes, tri_neighbor, 2);
    is_bad[k] = is_elected(bad, tri_neighbor, tri_mark, rings, notes, k);
  }
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int first_round = group_exclusive_scan(is_bad, offset, electing, scratch);
  // The second round (settle_elected), its passes empty when it does not run.
  const int again = second_round && CLM_SECOND_ROUND_SHARE * first_round < electing ? electing : 0;
  for (int k = lid; k < again; k += size)
    settle_elected_entry(bad, is_bad, tri_mark, k);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < again; k += size)
    retire_blocked_entry(bad, tri_neighbor, tri_mark, rings, notes, is_bad, k);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < again; k += size)
    elect_again_entry(bad, tri_neighbor, tri_mark, rings, notes, is_bad, k);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int elected = group_exclusive_scan(is_bad, offset, electing, scratch);
  for (int k = lid; k < electing; k += size)
    gather_elected_entry(bad, is_bad, offset, tri_mark, last_container, origin, k);
  const int candidates = rings > 0 ? elected : bad_count;
  if (lid == 0) {
    counts[0] = n;
    counts[1] = bad_count;
    counts[2] = candidates;
  }
  return (int2)(bad_count, candidates);
}

// The insertion radius of located candidate k at c (thesis §3.5): the
// distance to the nearest vertex of its bad triangle; for a split of a hull
// edge or subsegment, to the nearer end. Squared.
static inline double insertion_radius2_of(CLM_MESH_PARAMS, __global const int *container,
                                          __global const int *split_edge,
                                          __global const int *origin, double2 c, int k) {
  if (splits_subsegment(CLM_MESH_ARGS, container, split_edge, k)) {
    const int t = container[k], e = split_edge[k];
    const int a = tri_vertex[3 * t + next3(e)], b = tri_vertex[3 * t + prev3(e)];
    const double to_a = squared_length(points[a] - c);
    return shell_centre(CLM_MESH_ARGS, t, e) >= 0 ? fmin(to_a, squared_length(points[b] - c))
                                                  : to_a;
  }
  double radius2 = INFINITY;
  for (int i = 0; i < 3; ++i)
    radius2 = fmin(radius2, squared_length(points[tri_vertex[3 * origin[k] + i]] - c));
  return radius2;
}

#define CLM_WALK_BLOCKED 3

// walk_to_point within the domain: the walk stops before it would cross the
// domain's boundary (into a ghost) or a subsegment; that edge of
// result.triangle is result.edge (outcome CLM_WALK_BLOCKED).
static inline WalkResult walk_in_domain(CLM_MESH_PARAMS, int t, double2 p, int max_steps) {
  WalkResult result = {CLM_WALK_LOST, t, -1, -1};
  for (int step = 0; step < max_steps; ++step) {
    const VertexTriple tri = load_vertices(tri_vertex, t);
    const int cross = edge_to_cross(points, tri, p, &result, first_edge_to_test(t, step));
    if (cross < 0)
      break;
    const int u = link_triangle(tri_neighbor[3 * t + cross]);
    if (is_ghost(load_vertices(tri_vertex, u)) || subsegment_at(CLM_MESH_ARGS, t, cross)) {
      result.outcome = CLM_WALK_BLOCKED;
      result.edge = cross;
      break;
    }
    t = u;
    result.triangle = t;
  }
  return result;
}

// Computes the candidate of bad triangle origin[k] and its priority, and
// locates it walking from that triangle, or from the container
// found for it by the last search (last_container[origin], kept when neither
// triangle was rewritten since: modified_stamp below located_stamp, the
// stamp of that search). A candidate beyond the hull (or the domain's
// boundary) or a subsegment, or inside the diametral lens of a hull edge or
// subsegment of its container, splits that edge instead (subsegment_split),
// inserted on that edge a hair off it as rounding leaves it (as Triangle
// splits a segment), when the edge can be split within precision
// (splittable): else the candidate goes in as it is, or, beyond the edge, is
// dropped. split_edge[k]: the edge of container[k] the candidate lies on (the
// edge a split splits), or -1 inside; container[k] = -1 when it falls on a
// vertex or is dropped.
// Prefetching for locate_candidates (prefetch.h): the bad triangle where a
// walk starts, its corners and its neighbours, and in a constrained mesh its
// corners' segments (point_segment and constraint_start, else 0).
static inline void
prefetch_walk_start(__global const int *origin, int k, int n, __global const double2 *points,
                    __global const int *point_state, __global const int *point_segment,
                    __global const int *constraint_start, __global const int *tri_vertex,
                    __global const int *tri_neighbor, __global const int *modified_stamp,
                    __global const int *last_container) {
  const int far = entry_ahead(origin, k, 2, n);
  if (far >= 0) {
    warm_triangle(tri_vertex, tri_neighbor, far);
    warm(modified_stamp + far);
    warm(last_container + far);
  }
  const int near = entry_ahead(origin, k, 1, n);
  warm_corners(points, point_state, tri_vertex, near);
  warm_neighbours(tri_vertex, tri_neighbor, near);
  if (point_segment)
    warm_corner_segments(point_segment, constraint_start, tri_vertex, near);
}

// locate_candidates' arguments after the mesh's, shared with place_in_group.
#define CLM_LOCATE_PARAMS                                                                          \
  __global int *last_container, const int located_stamp, const double ratio_bound_squared,         \
      const double max_area, __global const double *region_area,                                   \
      __global const double *size_bound, const int sized, const double offconstant,                \
      const int conforming, const int protect, __global double2 *candidate,                        \
      __global int *container, __global int *split_edge, __global const int *origin,               \
      __global uint *priority, __global double *radius2, const double lens, const int inward,      \
      const int stamp, __global int *notes, volatile __global int *stuck_count,                    \
      const int max_steps
#define CLM_LOCATE_ARGS                                                                            \
  last_container, located_stamp, ratio_bound_squared, max_area, region_area, size_bound, sized,    \
      offconstant, conforming, protect, candidate, container, split_edge, origin, priority,        \
      radius2, lens, inward, stamp, notes, stuck_count, max_steps

// Candidate k of locate_candidates.
static inline void locate_entry(CLM_MESH_PARAMS, CLM_LOCATE_PARAMS, const int k) {
  const int bad = origin[k], known = last_container[bad];
  double2 c;
  uint rank;
  bool area_only;
  const VertexTriple bad_triangle = load_vertices(tri_vertex, bad);
  bad_triangle_candidate(
      points, point_state, CLM_SEGMENTS_IF_ANY, segment_end, bad_triangle, ratio_bound_squared,
      area_bound_of(tri_region, regional, region_area, size_bound, sized, max_area, bad),
      offconstant, conforming && encroaches_subsegment(CLM_MESH_ARGS, bad, bad_triangle),
      protected_edges(CLM_MESH_ARGS, bad, protect), &c, &rank,
      &area_only); // bad: the search found it so
  candidate[k] = c;
  const bool unchanged =
      modified_stamp[bad] < located_stamp && known >= 0 && modified_stamp[known] < located_stamp;
  const WalkResult walk = walk_in_domain(CLM_MESH_ARGS, unchanged ? known : bad, c, max_steps);
  int t = walk.outcome == CLM_WALK_LOST ? bad : walk.triangle;
  const VertexTriple tri = load_vertices(tri_vertex, t);
  int hull_edge = walk.outcome == CLM_WALK_BLOCKED ? walk.edge : -1;
  double2 split;
  if (hull_edge >= 0 && is_protected(CLM_MESH_ARGS, t, hull_edge, protect))
    hull_edge = -1; // beyond an edge no point may split (-Y): dropped, not located
  else if (hull_edge >= 0 && !splittable(CLM_MESH_ARGS, inward, t, hull_edge, &split)) {
    hull_edge = -1; // beyond an edge no point can split: dropped, and bad stuck
    notes[bad] |= CLM_NOTE_STUCK;
    atomic_inc(stuck_count);
  } else if (hull_edge < 0 && touches_hull(point_state, tri)) {
    // A hull edge or subsegment of the container, or of a neighbour that
    // c's cavity takes (its circumcircle holds c), whose diametral lens
    // holds c is encroached: it is split instead (Triangle tests the
    // subsegments of the new star; every such edge near c has a vertex of
    // the container).
    for (int r = -1; r < 3 && hull_edge < 0; ++r) {
      const int s = r < 0 ? t : link_triangle(tri_neighbor[3 * t + r]);
      const VertexTriple near = load_vertices(tri_vertex, s);
      if (is_ghost(near))
        continue;
      for (int i = 0; i < 3 && hull_edge < 0; ++i) {
        const int a = tri_vertex[3 * s + next3(i)], b = tri_vertex[3 * s + prev3(i)];
        if (!on_hull(point_state[a]) || !on_hull(point_state[b]))
          continue;
        const int u = link_triangle(tri_neighbor[3 * s + i]);
        if ((!is_ghost(load_vertices(tri_vertex, u)) && !subsegment_at(CLM_MESH_ARGS, s, i)) ||
            is_protected(CLM_MESH_ARGS, s, i, protect))
          continue; // not a boundary edge or subsegment; or one c may encroach (-Y)
        if (in_lens(points[a], points[b], c, lens) &&
            (r < 0 || circumcircle_holds(points, near, c)) &&
            splittable(CLM_MESH_ARGS, inward, s, i, &split)) {
          hull_edge = i;
          t = s;
        }
      }
    }
  }
  if (hull_edge >= 0)
    candidate[k] = split;
  // Segment-split goes before triangle-split (thesis §3.4.1): off-centers
  // rank after every midpoint, in their own order.
  priority[k] = hull_edge < 0 ? rank | CLM_OFFCENTER_RANK : rank;
  const bool located = walk.outcome == CLM_WALK_LOCATED || hull_edge >= 0;
  container[k] = located ? t : -1;
  last_container[bad] = located ? t : -1;
  split_edge[k] = hull_edge >= 0 ? hull_edge : walk.edge;
  if (located)
    radius2[k] =
        insertion_radius2_of(CLM_MESH_ARGS, container, split_edge, origin, candidate[k], k);
}

__kernel void locate_candidates(CLM_MESH_PARAMS, CLM_LOCATE_PARAMS, const int n) {
  const int k = get_global_id(0);
  prefetch_walk_start(origin, k, n, points, point_state, CLM_SEGMENTS_IF_ANY, constraint_start,
                      tri_vertex, tri_neighbor, modified_stamp, last_container);
  if (k < n)
    locate_entry(CLM_MESH_ARGS, CLM_LOCATE_ARGS, k);
}

// Marks each candidate's container (and its partner) with its priority.
static inline void mark_container_of(__global const int *container, __global const int *split_edge,
                                     __global const int *tri_neighbor,
                                     __global const uint *priority,
                                     volatile __global uint *tri_mark, const int k) {
  if (container[k] < 0)
    return;
  atomic_min(&tri_mark[container[k]], priority[k]);
  const int partner = split_partner(tri_neighbor, container, split_edge, k);
  if (partner >= 0)
    atomic_min(&tri_mark[partner], priority[k]);
}

__kernel void mark_candidate_containers(__global const int *container,
                                        __global const int *split_edge,
                                        __global const int *tri_neighbor,
                                        __global const uint *priority,
                                        volatile __global uint *tri_mark, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    mark_container_of(container, split_edge, tri_neighbor, priority, tri_mark, k);
}

// The insertion filter: survive[k] = 1 when candidate k owns its container's
// mark (and its partner's) and no neighbouring container is marked with a
// better priority. Among candidates of equal priority, the smallest index
// keeps the container. The survivors' triangles are then pairwise distinct,
// so they are all inserted in one round, in place.
static inline void mark_tie_of(__global const int *container, __global const int *split_edge,
                               __global const int *tri_neighbor, __global const uint *priority,
                               volatile __global const uint *tri_mark,
                               volatile __global int *tie_mark, const int k) {
  if (container[k] < 0)
    return;
  if (tri_mark[container[k]] == priority[k])
    atomic_min(&tie_mark[container[k]], k);
  const int partner = split_partner(tri_neighbor, container, split_edge, k);
  if (partner >= 0 && tri_mark[partner] == priority[k])
    atomic_min(&tie_mark[partner], k);
}

__kernel void mark_candidate_ties(__global const int *container, __global const int *split_edge,
                                  __global const int *tri_neighbor, __global const uint *priority,
                                  __global const uint *tri_mark, volatile __global int *tie_mark,
                                  const int n) {
  const int k = get_global_id(0);
  if (k < n)
    mark_tie_of(container, split_edge, tri_neighbor, priority, tri_mark, tie_mark, k);
}

// Whether candidates j and k are closer than sqrt(factor2) times the
// distance at which they would be orthogonal (|c_j - c_k|^2 = r_j^2 + r_k^2).
static inline bool closer_than(__global const double2 *candidate, __global const double *radius2,
                               int j, int k, double factor2) {
  return squared_length(candidate[j] - candidate[k]) < factor2 * (radius2[j] + radius2[k]);
}

// Does the best candidate of container x, within `ring` rings of candidate
// k's container, keep k out? Within the priority rings, when it has better
// priority and is near (closer_than near2; near2 is infinite for GPU-QM, the
// thesis's rule at any distance); with distance rings (any ring up to rings + distance_rings), also
// when it goes first (better priority, or equal and a smaller index) and the
// two would be a dependent pair of GPU-QM-V (Claim 3.5.1: less than
// orthogonal), of which k would be deleted again.
static inline bool beaten(volatile __global const uint *tri_mark, __global const int *tie_mark,
                          __global const double2 *candidate, __global const double *radius2, int x,
                          int ring, int rings, int distance_rings, double near2, int k, uint mine) {
  const uint mark = tri_mark[x];
  if (mark > mine)
    return false;
  if (mark < mine && ring <= rings) {
    if (isinf(near2))
      return true;
    const int j = tie_mark[x];
    return j == CLM_NO_CANDIDATE || closer_than(candidate, radius2, j, k, near2);
  }
  if (distance_rings == 0)
    return false;
  const int j = tie_mark[x];
  return j != CLM_NO_CANDIDATE && (mark < mine || j < k) &&
         closer_than(candidate, radius2, j, k, 1.0);
}

// rings: how far the filter looks by priority, 2 (the neighbours and theirs)
// or 3 (and theirs). The thesis looks at the neighbours only; each ring
// further makes the parallel insertion closer to the sequential order of
// priorities: fewer points, more iterations. distance_rings: how many rings
// further (0 or 1) it also leaves out predicted dependent pairs (GPU-QM-V:
// without it, two candidates of equal priority, on either side of the same
// short edge, were both inserted and one deleted again in step 3). near2
// (GPU-QM-V): far better candidates are left to their own neighbourhoods;
// along a thin ring the small triangles send their candidates into the same
// few large triangles, whose neighbours otherwise waited one iteration each.
// parallel_midpoints: a midpoint needs its container and partner only, since
// only midpoints rank before it and two midpoints never conflict: they split
// different hull edges (a container or partner they share goes by its mark)
// and are never a dependent pair.
// insertion_filter's arguments after the mesh's, shared with place_in_group
// (which writes tie_mark through the same name).
#define CLM_FILTER_PARAMS                                                                          \
  __global const int *container, __global const int *split_edge, __global const uint *priority,    \
      __global int *tie_mark, __global const double2 *candidate, __global const double *radius2,   \
      const int rings, const int distance_rings, const double near2, const int parallel_midpoints, \
      __global int *survive
#define CLM_FILTER_ARGS                                                                            \
  container, split_edge, priority, tie_mark, candidate, radius2, rings, distance_rings, near2,     \
      parallel_midpoints, survive

// Whether candidate k survives.
static inline bool survives(CLM_MESH_PARAMS, __global const int *container,
                            __global const int *split_edge, __global const uint *priority,
                            __global const int *tie_mark, __global const double2 *candidate,
                            __global const double *radius2, const int rings,
                            const int distance_rings, const double near2,
                            const int parallel_midpoints, const int k) {
  const int t = container[k];
  const uint mine = priority[k];
  const int reach = rings + distance_rings;
  bool wins = t >= 0 && tri_mark[t] == mine && tie_mark[t] == k;
  const bool ringed = !(parallel_midpoints && is_midpoint_priority(mine));
#define CLM_BEATEN(x, ring)                                                                        \
  beaten(tri_mark, tie_mark, candidate, radius2, x, ring, rings, distance_rings, near2, k, mine)
  for (int i = 0; i < 3 && wins && ringed; ++i) {
    const int u = link_triangle(tri_neighbor[3 * t + i]);
    wins = !CLM_BEATEN(u, 1);
    for (int j = 0; j < 3 && wins; ++j) {
      const int w = link_triangle(tri_neighbor[3 * u + j]);
      if (w == t)
        continue;
      wins = !CLM_BEATEN(w, 2);
      for (int l = 0; l < 3 && wins && reach > 2; ++l) {
        const int x = link_triangle(tri_neighbor[3 * w + l]);
        if (x == t || x == u)
          continue;
        wins = !CLM_BEATEN(x, 3);
        for (int m = 0; m < 3 && wins && reach > 3; ++m) {
          const int y = link_triangle(tri_neighbor[3 * x + m]);
          if (y != w)
            wins = !CLM_BEATEN(y, 4);
        }
      }
    }
  }
#undef CLM_BEATEN
  const int partner = wins ? split_partner(tri_neighbor, container, split_edge, k) : -1;
  if (partner >= 0)
    wins = tri_mark[partner] == mine && tie_mark[partner] == k;
  return wins;
}

// Candidate k of insertion_filter, its prefetching first (of n).
static inline void filter_entry(CLM_MESH_PARAMS, CLM_FILTER_PARAMS, const int k, const int n) {
  prefetch_rings(container, k, n, tri_mark, tie_mark, tri_neighbor,
                 rings + distance_rings > 2 ? 3 : 2);
  if (k < n)
    survive[k] = survives(CLM_MESH_ARGS, container, split_edge, priority, tie_mark, candidate,
                          radius2, rings, distance_rings, near2, parallel_midpoints, k);
}

__kernel void insertion_filter(CLM_MESH_PARAMS, CLM_FILTER_PARAMS, const int n) {
  filter_entry(CLM_MESH_ARGS, CLM_FILTER_ARGS, get_global_id(0), n);
}

// Candidate k's marks on its container and partner cleared, after the
// filter (by append_survivors, or by clear_candidate_marks when none is
// appended).
static inline void clear_marks_of(__global const int *container, __global const int *split_edge,
                                  __global const int *tri_neighbor,
                                  volatile __global uint *tri_mark, __global int *tie_mark, int k) {
  if (container[k] < 0)
    return;
  tri_mark[container[k]] = CLM_NO_MARK;
  tie_mark[container[k]] = CLM_NO_CANDIDATE;
  const int partner = split_partner(tri_neighbor, container, split_edge, k);
  if (partner >= 0) {
    tri_mark[partner] = CLM_NO_MARK;
    tie_mark[partner] = CLM_NO_CANDIDATE;
  }
}

__kernel void clear_candidate_marks(__global const int *container, __global const int *split_edge,
                                    __global const int *tri_neighbor, __global uint *tri_mark,
                                    __global int *tie_mark, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    clear_marks_of(container, split_edge, tri_neighbor, tri_mark, tie_mark, k);
}

// The survivors become points of the mesh (slots by prefix sum over the
// candidates, free slots first, see allocate_slot), listed in new_points,
// each to be inserted in its container, on split_edge when it lies on an
// edge. Each gets its state, priority and insertion radius (thesis §3.5: the
// distance to the nearest vertex of its bad triangle; to the nearer end for a
// split of a hull edge or subsegment), and a split its segment.
// Only the first `count` survivors are taken (the -S limit). Every
// candidate clears the filter's marks (tie_mark and tri_mark): nothing here
// reads them. append_entry: candidate k's part (of append_survivors and of
// the in-group placement).
static inline void append_entry(CLM_MESH_PARAMS, __global const double2 *candidate,
                                __global const int *container, __global const int *split_edge,
                                __global const double *radius2, __global const uint *priority,
                                __global const int *survive, __global const int *offset,
                                __global const int *free_points, const int free_first,
                                const int free_count, const int first_new, __global int *new_points,
                                __global int *tie_mark, const int count, const int k) {
  clear_marks_of(container, split_edge, tri_neighbor, tri_mark, tie_mark, k);
  if (!survive[k] || offset[k] >= count)
    return;
  const int p = allocate_slot(free_points, free_first, free_count, first_new, offset[k]);
  const double2 c = candidate[k];
  const bool midpoint = splits_subsegment(CLM_MESH_ARGS, container, split_edge, k);
  const int t = container[k], e = split_edge[k];
  const int a = midpoint ? tri_vertex[3 * t + next3(e)] : -1,
            b = midpoint ? tri_vertex[3 * t + prev3(e)] : -1;
  // (Without constraints no point lies on a segment: the rows are not read.)
  point_segment[p] = midpoint && constrained
                         ? segment_of_edge(constraint_start, constraint_adjacent,
                                           constraint_segment, point_segment, a, b)
                         : CLM_NO_SEGMENT;
  if (midpoint && point_segment[p] >= 0 && point_segment[a] < 0 && point_segment[b] < 0)
    mark_segment_split(constraint_start, constraint_adjacent, constraint_segment, a, b);
  points[p] = c;
  location[p] = container[k];
  location_edge[p] = split_edge[k];
  original_id[p] = p; // numbered again at the end (number_steiner_points)
  point_state[p] = midpoint ? CLM_POINT_NEW_MIDPOINT : CLM_POINT_NEW;
  insertion_radius2[p] = radius2[k];
  point_priority[p] = midpoint ? 0u : priority[k] & ~CLM_OFFCENTER_RANK;
  new_points[offset[k]] = p;
}

__kernel void append_survivors(CLM_MESH_PARAMS, __global const double2 *candidate,
                               __global const int *container, __global const int *split_edge,
                               __global const double *radius2, __global const uint *priority,
                               __global const int *survive, __global const int *offset,
                               __global const int *free_points, const int free_first,
                               const int free_count, const int first_new, __global int *new_points,
                               __global int *tie_mark, const int count, const int n) {
  const int k = get_global_id(0);
  if (k < n)
    append_entry(CLM_MESH_ARGS, candidate, container, split_edge, radius2, priority, survive,
                 offset, free_points, free_first, free_count, first_new, new_points, tie_mark,
                 count, k);
}

// A short placement by one work-group (place_candidates_in_group, or the
// second part of step_one_in_group): locate_candidates, mark_candidate_containers,
// mark_candidate_ties and insertion_filter in turn, the survivors' prefix
// sum, and append_survivors of the first min(survivors, room).
// counts[0..2): the survivors, stuck_count[0] after the locations.
#define CLM_PLACE_GROUP_PARAMS                                                                     \
  __global int *tie_mark, const int rings, const int distance_rings, const double near2,           \
      const int parallel_midpoints, __global int *survive, __global int *offset,                   \
      __global const int *free_points, const int free_first, const int free_count,                 \
      const int first_new, __global int *new_points, const int room, __local int *scratch,         \
      __global int *counts, const int n
static inline void place_in_group(CLM_MESH_PARAMS, CLM_LOCATE_PARAMS, CLM_PLACE_GROUP_PARAMS) {
  const int lid = get_local_id(0), size = get_local_size(0);
  for (int k = lid; k < n; k += size) {
    prefetch_walk_start(origin, k, n, points, point_state, CLM_SEGMENTS_IF_ANY, constraint_start,
                        tri_vertex, tri_neighbor, modified_stamp, last_container);
    locate_entry(CLM_MESH_ARGS, CLM_LOCATE_ARGS, k);
  }
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < n; k += size)
    mark_container_of(container, split_edge, tri_neighbor, priority, tri_mark, k);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < n; k += size)
    mark_tie_of(container, split_edge, tri_neighbor, priority, tri_mark, tie_mark, k);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  for (int k = lid; k < n; k += size)
    filter_entry(CLM_MESH_ARGS, container, split_edge, priority, tie_mark, candidate, radius2,
                 rings, distance_rings, near2, parallel_midpoints, survive, k, n);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int survivors = group_exclusive_scan(survive, offset, n, scratch);
  const int count = min(survivors, room);
  for (int k = lid; k < n; k += size)
    append_entry(CLM_MESH_ARGS, candidate, container, split_edge, radius2, priority, survive,
                 offset, free_points, free_first, free_count, first_new, new_points, tie_mark,
                 count, k);
  if (lid == 0) {
    counts[0] = survivors;
    counts[1] = *stuck_count;
  }
}

__kernel void place_candidates_in_group(CLM_MESH_PARAMS, CLM_LOCATE_PARAMS,
                                        CLM_PLACE_GROUP_PARAMS) {
  place_in_group(CLM_MESH_ARGS, CLM_LOCATE_ARGS, tie_mark, rings, distance_rings, near2,
                 parallel_midpoints, survive, offset, free_points, free_first, free_count,
                 first_new, new_points, room, scratch, counts, n);
}

// Step 1 whole by one work-group in one launch: search_in_group, then, when
// some triangle is bad and the candidates are at most place_room (-1: the
// host goes on by itself), place_in_group of every candidate (else of none),
// its counts in counts[3..5). The arguments are search_in_group's, then
// place_in_group's that it lacks.
__kernel void step_one_in_group(
    CLM_MESH_PARAMS, CLM_SEARCH_PARAMS, CLM_SEARCH_GROUP_PARAMS, __global double2 *candidate,
    __global int *container, __global int *split_edge, __global uint *priority,
    __global double *radius2, const int stamp, volatile __global int *stuck_count,
    const int max_steps, __global int *tie_mark, const int filter_rings, const int distance_rings,
    const double near2, const int parallel_midpoints, __global int *survive,
    __global const int *free_points, const int free_first, const int free_count,
    const int first_new, __global int *new_points, const int room, const int place_room) {
  const int2 found = search_in_group(CLM_MESH_ARGS, CLM_SEARCH_ARGS, CLM_SEARCH_GROUP_ARGS);
  group_barrier(CLK_GLOBAL_MEM_FENCE);
  const int n = found.x > 0 && found.y <= place_room ? found.y : 0;
  place_in_group(CLM_MESH_ARGS, last_container, located_stamp, ratio_bound_squared, max_area,
                 region_area, size_bound, sized, offconstant, conforming, protect, candidate,
                 container, split_edge, rings > 0 ? origin : bad, priority, radius2, lens, inward,
                 stamp, notes, stuck_count, max_steps, tie_mark, filter_rings, distance_rings,
                 near2, parallel_midpoints, survive, offset, free_points, free_first, free_count,
                 first_new, new_points, room, scratch, counts + 3, n);
}
