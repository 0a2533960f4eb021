// clmesh — the vertices of the Voronoi diagram (-v): the circumcentre of every
// triangle of the output mesh, and the point attributes interpolated there
// (Triangle's writevoronoi: org + xi * (dest - org) + eta * (apex - org)).
//
// The circumcentre is computed as an offset from the triangle's first vertex
// a, with b and c the other two:
//   dx = (cy |b|^2 - by |c|^2) / 2D,  dy = (bx |c|^2 - cx |b|^2) / 2D,
//   D = bx cy - by cx,  bx = b.x - a.x (and so on),
// where the differences, D and both numerators are exact floating-point
// expansions (cl/predicates.h) from the input coordinates: nothing cancels,
// however flat the triangle. Each of D and the numerators is then rounded to
// a double within (1 + 1e-9) eps of it, relative (eps = 2^-53), the offset is
// one division (relative error below 4 eps in all) and the centre one addition:
//   |computed x - exact x| <= 4 eps |dx| + eps |x|   (and likewise for y).
// Most triangles take a fast path with the same guarantee: when the four
// differences are exact doubles (nearby points), D and the numerators are
// evaluated in double-double arithmetic and kept when their error bound is
// below 1e-9 eps of them; the others (far apart corners, flat triangles,
// numerators near zero) take the expansions.
// A triangle with D == 0 (none in a valid mesh) gets NaN coordinates.
#include "common.h"

// Lengths of the exact expansions below (each at most the sum, or twice the
// length for a product by a two-component factor, of its operands').
#define CLM_VV_DIFFERENCE 2 // p - q
#define CLM_VV_PRODUCT 8    // (p - q)(r - s)
#define CLM_VV_QUADRATIC 16 // a sum of two products
#define CLM_VV_CUBIC 64     // a difference times a quadratic
#define CLM_VV_NUMERATOR 128

// p - q exactly: one component when the rounded difference is exact (as it
// is for nearby points), else two, the smaller first.
typedef struct {
  double c[CLM_VV_DIFFERENCE];
  int n;
} Difference;

static inline Difference exact_difference(double p, double q) {
  Difference d;
  double hi, lo;
  clm_two_sum(p, -q, &hi, &lo);
  d.n = lo != 0.0 ? 2 : 1;
  d.c[0] = lo != 0.0 ? lo : hi;
  d.c[1] = hi;
  return d;
}

// h = e * f for an expansion e of en components (at most CLM_VV_QUADRATIC)
// and an exact difference f: at most 4 en components (2 en when f has one).
static inline int times_difference(int en, const double *e, const Difference *f, double *h) {
  if (f->n == 1)
    return clm_scale_expansion(en, e, f->c[0], h);
  double low[2 * CLM_VV_QUADRATIC], high[2 * CLM_VV_QUADRATIC];
  const int low_n = clm_scale_expansion(en, e, f->c[0], low);
  const int high_n = clm_scale_expansion(en, e, f->c[1], high);
  return clm_expansion_sum(low_n, low, high_n, high, h);
}

// h = e0 * f0 + sign * e1 * f1 (sign +1 or -1) for four exact differences:
// at most CLM_VV_QUADRATIC components.
static inline int product_sum(const Difference *e0, const Difference *f0, const Difference *e1,
                              const Difference *f1, double sign, double *h) {
  double first[CLM_VV_PRODUCT], second[CLM_VV_PRODUCT];
  const int first_n = times_difference(e0->n, e0->c, f0, first);
  const int second_n = times_difference(e1->n, e1->c, f1, second);
  for (int i = 0; i < second_n; ++i)
    second[i] *= sign;
  return clm_expansion_sum(first_n, first, second_n, second, h);
}

// h = f0 * q0 - f1 * q1 for exact differences and quadratics: a numerator,
// at most CLM_VV_NUMERATOR components.
static inline int numerator(const Difference *f0, int q0n, const double *q0, const Difference *f1,
                            int q1n, const double *q1, double *h) {
  double first[CLM_VV_CUBIC], second[CLM_VV_CUBIC];
  const int first_n = times_difference(q0n, q0, f0, first);
  const int second_n = times_difference(q1n, q1, f1, second);
  for (int i = 0; i < second_n; ++i)
    second[i] = -second[i];
  return clm_expansion_sum(first_n, first, second_n, second, h);
}

// The sum of an expansion's components, from the smallest.
static inline double component_sum(int n, const double *e) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    sum += e[i];
  return sum;
}

// An expansion of at most CLM_VV_NUMERATOR components as a double within
// (1 + 1e-9) eps of its value, relative: the component sum s, corrected by
// the sum of the exact residual e - s. A sum of n non-overlapping components
// errs by a few n eps relative at most, so the residual is that small and its
// own sum's error is of the order n^2 eps^2.
static inline double nearest_double(int n, const double *e) {
  const double sum = component_sum(n, e), minus_sum = -sum;
  double residual[CLM_VV_NUMERATOR + 1];
  const int residual_n = clm_expansion_sum(n, e, 1, &minus_sum, residual);
  return sum + component_sum(residual_n, residual);
}

// D and the two numerators, each rounded within (1 + 1e-9) eps of its exact
// value, relative: the values the centre is computed from.
typedef struct {
  double det, nx, ny;
} CenterParts;

// The exact path: every quantity an expansion, rounded once at the end.
CLM_COLD CenterParts exact_parts(const Difference *bx, const Difference *by, const Difference *cx,
                                 const Difference *cy) {
  double det[CLM_VV_QUADRATIC], b2[CLM_VV_QUADRATIC], c2[CLM_VV_QUADRATIC];
  const int det_n = product_sum(bx, cy, by, cx, -1.0, det);
  const int b2_n = product_sum(bx, bx, by, by, 1.0, b2);
  const int c2_n = product_sum(cx, cx, cy, cy, 1.0, c2);
  double nx[CLM_VV_NUMERATOR], ny[CLM_VV_NUMERATOR];
  const int nx_n = numerator(cy, b2_n, b2, by, c2_n, c2, nx);
  const int ny_n = numerator(bx, c2_n, c2, cx, b2_n, b2, ny);
  CenterParts parts;
  parts.det = nearest_double(det_n, det);
  parts.nx = nearest_double(nx_n, nx);
  parts.ny = nearest_double(ny_n, ny);
  return parts;
}

// The fast path's checks (see fast_parts): the error bound of the
// double-double value, 4 eps^2 S for D and 30 eps^2 S for a numerator (S the
// sum of the magnitudes of its two products), must stay below 1e-9 eps of the
// value; the constants hold twice these bounds.
#define CLM_VV_DET_CHECK (8.0 * CLM_EPSILON * 1e9)
#define CLM_VV_NUMERATOR_CHECK (64.0 * CLM_EPSILON * 1e9)

// q + ql = x^2 + y^2 within 4.01 eps^2 of it (all four exact parts are
// positive, so nothing cancels).
static inline void square_sum(double x, double y, double *q, double *ql) {
  double p1, e1, p2, e2, t;
  clm_two_product(x, x, &p1, &e1);
  clm_two_product(y, y, &p2, &e2);
  clm_two_sum(p1, p2, q, &t);
  *ql = t + (e1 + e2);
}

// f0 (q0 + q0l) - f1 (q1 + q1l) in double-double arithmetic; false when the
// check cannot certify it within (1 + 1e-9) eps.
static inline bool fast_numerator(double f0, double q0, double q0l, double f1, double q1,
                                  double q1l, double *value) {
  double x1, x2, y1, y2, s, t;
  clm_two_product(f0, q0, &x1, &x2);
  clm_two_product(f1, q1, &y1, &y2);
  clm_two_sum(x1, -y1, &s, &t);
  *value = s + (((t + x2) - y2) + (f0 * q0l - f1 * q1l));
  return CLM_VV_NUMERATOR_CHECK * (clm_absd(x1) + clm_absd(y1)) <= clm_absd(*value);
}

// The fast path, for the common case: every difference exact as one double
// and the triangle not too flat (D and the numerators are then known in
// double-double arithmetic to far better than eps, and rounded like the
// exact path's). False when it does not apply.
static inline bool fast_parts(const Difference *bx, const Difference *by, const Difference *cx,
                              const Difference *cy, CenterParts *parts) {
  if (bx->n != 1 || by->n != 1 || cx->n != 1 || cy->n != 1)
    return false;
  const double x = bx->c[0], y = by->c[0], u = cx->c[0], v = cy->c[0];
  double d1, d2, d3, d4, s, t;
  clm_two_product(x, v, &d1, &d2);
  clm_two_product(y, u, &d3, &d4);
  clm_two_sum(d1, -d3, &s, &t);
  parts->det = s + ((t + d2) - d4);
  if (!(CLM_VV_DET_CHECK * (clm_absd(d1) + clm_absd(d3)) <= clm_absd(parts->det)))
    return false;
  double b2, b2l, c2, c2l;
  square_sum(x, y, &b2, &b2l);
  square_sum(u, v, &c2, &c2l);
  return fast_numerator(v, b2, b2l, y, c2, c2l, &parts->nx) &&
         fast_numerator(x, c2, c2l, u, b2, b2l, &parts->ny);
}

// points: x, y per point; triangles: three vertex indices each (CCW);
// attributes: attribute_count per point. Writes centers (x, y per triangle)
// and center_attributes (attribute_count per triangle).
__kernel void voronoi_vertices(__global const double *points, __global const int *triangles,
                               __global const double *attributes, const int attribute_count,
                               __global double *centers, __global double *center_attributes,
                               const int n) {
  const int t = get_global_id(0);
  if (t >= n)
    return;
  const int ia = triangles[3 * t], ib = triangles[3 * t + 1], ic = triangles[3 * t + 2];
  const double ax = points[2 * ia], ay = points[2 * ia + 1];
  const Difference bx = exact_difference(points[2 * ib], ax),
                   by = exact_difference(points[2 * ib + 1], ay),
                   cx = exact_difference(points[2 * ic], ax),
                   cy = exact_difference(points[2 * ic + 1], ay);
  CenterParts parts;
  if (!fast_parts(&bx, &by, &cx, &cy, &parts))
    parts = exact_parts(&bx, &by, &cx, &cy);

  const double d = parts.det, two_d = 2.0 * d;
  const double dx = d != 0.0 ? parts.nx / two_d : NAN;
  const double dy = d != 0.0 ? parts.ny / two_d : NAN;
  centers[2 * t] = ax + dx;
  centers[2 * t + 1] = ay + dy;

  // Triangle's coordinates of the centre in the frame (b - a, c - a).
  const double bxd = bx.c[bx.n - 1], byd = by.c[by.n - 1], cxd = cx.c[cx.n - 1],
               cyd = cy.c[cy.n - 1];
  const double xi = (cyd * dx - cxd * dy) / d, eta = (bxd * dy - byd * dx) / d;
  for (int k = 0; k < attribute_count; ++k) {
    const double origin = attributes[ia * attribute_count + k];
    center_attributes[t * attribute_count + k] =
        origin + xi * (attributes[ib * attribute_count + k] - origin) +
        eta * (attributes[ic * attribute_count + k] - origin);
  }
}
