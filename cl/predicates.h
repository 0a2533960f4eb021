/*
 * clmesh — exact geometric predicates for the device (OpenCL C 1.2) and the host (C++17).
 *
 * Thesis §3.6.3 (exact arithmetic): every orientation and in-circle decision of the mesher is
 * exact.  Each predicate is split into a fast check and an exact check so that the device can
 * run them as two kernels: the fast check evaluates the determinant in floating point and
 * certifies its sign with a forward error bound; only the items it cannot certify are sent to
 * the exact check, which evaluates the whole determinant with floating-point expansions.
 *
 * The method is the one of J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
 * Fast Robust Geometric Predicates", Discrete & Computational Geometry 18(3):305-363, 1997:
 *   - an expansion is a sum of doubles, stored in increasing order of magnitude, whose
 *     components do not overlap; its sign is the sign of its largest (last) component;
 *   - two_sum / fast_two_sum give a + b exactly as a rounded sum plus its rounding error;
 *   - two_product gives a * b exactly as a rounded product plus its error, by Dekker's
 *     splitting of each factor into two 26-bit halves (no fused multiply-add is used);
 *   - expansion sum (Shewchuk's fast expansion sum, Theorem 13) and scale expansion
 *     (Theorem 19) keep the outputs strongly nonoverlapping under round-to-nearest-even;
 *     zero components are dropped as they appear ("zero elimination").
 * The code here was written for clmesh from the paper's description.
 *
 * Requirements on the compiler: IEEE double arithmetic with round-to-nearest-even, no
 * contraction of a * b + c into a fused multiply-add and no value-changing optimisations:
 * the device includer enables cl_khr_fp64 and sets `#pragma OPENCL FP_CONTRACT OFF` (never
 * build with -cl-fast-relaxed-math or -cl-mad-enable); the host is compiled with
 * -ffp-contract=off (and without -ffast-math).
 *
 * Input range: coordinates are finite and every non-zero coordinate has a magnitude in
 * [1e-50, 1e50] (clmesh::kMinCoordinate, kMaxCoordinate).  All exact values handled below are
 * integer multiples of 2^-876 (a 1e-50 coordinate is a multiple of 2^-219 and the in-circle
 * determinant has degree 4) and are below 1e201 in magnitude, so no intermediate result
 * underflows or overflows and every error-free transformation is exact.
 *
 * The file is valid as plain C in both languages: no references, templates or std::.
 */
#ifndef CLMESH_PREDICATES_H
#define CLMESH_PREDICATES_H

/* Every function is file-local and inlinable on both sides. */
#define CLM_FN static inline
/* The exact stages, reached by few calls.  On the host, and on CPU devices (whose programs the
 * host builds with CLM_EXACT_OUT_OF_LINE), they stay out of line: a CPU device runs a
 * work-group's items in one thread, whose stack would hold every item's expansion arrays
 * (kilobytes each) if they were inlined, and overflows at large work-groups.  On other devices
 * they are inlined: called out of line, NVIDIA's OpenCL (driver 580 on an H100) returns wrong
 * signs from them, as the device's predicate check (predicate_check.cl) shows.  CLM_EXACT_INLINE
 * (CLMESH_BUILD_OPTIONS=-DCLM_EXACT_INLINE) inlines them on a CPU device too, as a GPU builds
 * them, for tests. */
#if defined(__OPENCL_VERSION__) && (defined(CLM_EXACT_INLINE) || !defined(CLM_EXACT_OUT_OF_LINE))
#define CLM_COLD static inline
#else
#define CLM_COLD static __attribute__((noinline))
#endif

/* Returned by the fast checks when the floating-point sign cannot be certified. */
#define CLM_UNCERTAIN 2

/* Half an ulp of 1.0: the relative rounding error of one operation. */
#define CLM_EPSILON 0x1p-53
/* 2^ceil(53/2) + 1: Dekker's splitter for 53-bit significands. */
#define CLM_SPLITTER 134217729.0
/* Shewchuk's error-bound coefficients of the floating-point stage ("A") of each predicate. */
#define CLM_CCWERRBOUND_A ((3.0 + 16.0 * CLM_EPSILON) * CLM_EPSILON)
#define CLM_ICCERRBOUND_A ((10.0 + 96.0 * CLM_EPSILON) * CLM_EPSILON)

/* Proven maximum expansion lengths (with zero elimination a result is never longer than the
 * sum of its inputs' lengths, a scaled expansion never longer than twice its input):
 *   product a*b                        2
 *   2x2 minor px*qy - py*qx            2 + 2         = 4
 *   orientation (three minors)         4 + 4 + 4     = 12
 *   orientation scaled by x, then x    12 * 2 * 2    = 48   (same for y)
 *   lifted term (x*x + y*y) * orient   48 + 48       = 96
 *   in-circle determinant, 4 terms     96 * 4        = 384 (partial sums 192, 288)
 * and for the in-circle determinant of the differences to d (clm_incircle_translated):
 *   lifted term (x*x + y*y) * minor    16 + 16       = 32
 *   determinant, 3 terms               32 * 3        = 96 (partial sum 64) */
#define CLM_LEN_MINOR 4
#define CLM_LEN_ORIENT 12
#define CLM_LEN_SCALED1 24
#define CLM_LEN_SCALED2 48
#define CLM_LEN_LIFTED 96
#define CLM_LEN_PARTIAL 288
#define CLM_LEN_INCIRCLE 384
#define CLM_LEN_TRANSLATED_TERM 32
#define CLM_LEN_TRANSLATED 96

/* ---------------------------------------------------------------------------------------- */
/* Error-free transformations                                                                */
/* ---------------------------------------------------------------------------------------- */

CLM_FN double clm_absd(double x) { return x < 0.0 ? -x : x; }

CLM_FN int clm_signd(double x) { return (x > 0.0) - (x < 0.0); }

/* s + e == a + b exactly, s = fl(a + b).  Valid for any a, b (Knuth's Two-Sum). */
CLM_FN void clm_two_sum(double a, double b, double *s, double *e) {
  double sum = a + b;
  double b_virtual = sum - a;
  double a_virtual = sum - b_virtual;
  double b_roundoff = b - b_virtual;
  double a_roundoff = a - a_virtual;
  *s = sum;
  *e = a_roundoff + b_roundoff;
}

/* s + e == a + b exactly, s = fl(a + b).  Requires |a| >= |b| (or a == 0) (Dekker). */
CLM_FN void clm_fast_two_sum(double a, double b, double *s, double *e) {
  double sum = a + b;
  double b_virtual = sum - a;
  *s = sum;
  *e = b - b_virtual;
}

/* hi + lo == a, both halves with at most 26 significant bits (Dekker's splitting). */
CLM_FN void clm_split(double a, double *hi, double *lo) {
  double c = CLM_SPLITTER * a;
  double a_big = c - a;
  double a_hi = c - a_big;
  *hi = a_hi;
  *lo = a - a_hi;
}

/* p + e == a * b exactly, p = fl(a * b), with b already split into b_hi + b_lo.  The partial
 * products of the halves are exact, so the error of fl(a * b) is recovered by subtracting them
 * one at a time from p. */
CLM_FN void clm_two_product_presplit(double a, double b, double b_hi, double b_lo, double *p,
                                     double *e) {
  double prod = a * b;
  double a_hi, a_lo;
  clm_split(a, &a_hi, &a_lo);
  double err1 = prod - a_hi * b_hi;
  double err2 = err1 - a_lo * b_hi;
  double err3 = err2 - a_hi * b_lo;
  *p = prod;
  *e = a_lo * b_lo - err3;
}

/* p + e == a * b exactly, p = fl(a * b). */
CLM_FN void clm_two_product(double a, double b, double *p, double *e) {
  double b_hi, b_lo;
  clm_split(b, &b_hi, &b_lo);
  clm_two_product_presplit(a, b, b_hi, b_lo, p, e);
}

/* ---------------------------------------------------------------------------------------- */
/* Expansion arithmetic                                                                      */
/* ---------------------------------------------------------------------------------------- */

/* h = e + f.  e (elen >= 1 components) and f (flen >= 1) are strongly nonoverlapping
 * expansions in increasing order of magnitude; so is h.  Returns the length of h, at most
 * elen + flen and at least 1 (a zero sum is the one-component expansion {0}).  h must not
 * alias e or f.
 *
 * The components of e and f are merged by increasing magnitude into one sequence g; a running
 * approximation q accumulates them with two_sum and every non-zero rounding error is emitted
 * as the next component of h (Shewchuk's fast expansion sum, Theorem 13). */
CLM_FN int clm_expansion_sum(int elen, const double *e, int flen, const double *f, double *h) {
  int ei = 0, fi = 0, hn = 0;
  double q, g, sum, err;
  /* First component of g: the smaller-magnitude head. */
  if (clm_absd(f[0]) < clm_absd(e[0]))
    q = f[fi++];
  else
    q = e[ei++];
  while (ei < elen || fi < flen) {
    if (fi >= flen || (ei < elen && clm_absd(e[ei]) <= clm_absd(f[fi])))
      g = e[ei++];
    else
      g = f[fi++];
    clm_two_sum(q, g, &sum, &err);
    if (err != 0.0)
      h[hn++] = err;
    q = sum;
  }
  if (q != 0.0 || hn == 0)
    h[hn++] = q;
  return hn;
}

/* h = b * e.  e (elen >= 1) is a strongly nonoverlapping expansion in increasing order of
 * magnitude; so is h (Shewchuk's scale expansion, Theorem 19).  Returns the length of h, at
 * most 2 * elen and at least 1.  h must not alias e. */
CLM_FN int clm_scale_expansion(int elen, const double *e, double b, double *h) {
  double b_hi, b_lo, q, hi, lo, sum, err;
  int i, hn = 0;
  clm_split(b, &b_hi, &b_lo);
  clm_two_product_presplit(e[0], b, b_hi, b_lo, &q, &err);
  if (err != 0.0)
    h[hn++] = err;
  for (i = 1; i < elen; i++) {
    /* e[i] * b == hi + lo; add lo to the running q, then hi (which dominates the sum). */
    clm_two_product_presplit(e[i], b, b_hi, b_lo, &hi, &lo);
    clm_two_sum(q, lo, &sum, &err);
    if (err != 0.0)
      h[hn++] = err;
    clm_fast_two_sum(hi, sum, &q, &err);
    if (err != 0.0)
      h[hn++] = err;
  }
  if (q != 0.0 || hn == 0)
    h[hn++] = q;
  return hn;
}

/* Sign of an expansion: the sign of its largest component, which is the last one. */
CLM_FN int clm_expansion_sign(int elen, const double *e) { return clm_signd(e[elen - 1]); }

/* h = px * qy - py * qx exactly (at most CLM_LEN_MINOR components). */
CLM_FN int clm_minor2(double px, double py, double qx, double qy, double *h) {
  double plus[2], minus[2];
  clm_two_product(px, qy, &plus[1], &plus[0]);
  clm_two_product(py, qx, &minus[1], &minus[0]);
  minus[0] = -minus[0];
  minus[1] = -minus[1];
  return clm_expansion_sum(2, plus, 2, minus, h);
}

/* h = m1 + m2 + m3 for three minors (at most CLM_LEN_ORIENT components). */
CLM_FN int clm_sum3(int n1, const double *m1, int n2, const double *m2, int n3, const double *m3,
                    double *h) {
  double t[2 * CLM_LEN_MINOR];
  int tn = clm_expansion_sum(n1, m1, n2, m2, t);
  return clm_expansion_sum(tn, t, n3, m3, h);
}

/* ---------------------------------------------------------------------------------------- */
/* orient2d: sign of | ax ay 1 ; bx by 1 ; cx cy 1 | = (a - c) x (b - c).                    */
/* +1: a, b, c counter-clockwise; -1: clockwise; 0: collinear.                               */
/* ---------------------------------------------------------------------------------------- */

/* Fast check: +1 / -1 when Shewchuk's bound certifies the floating-point sign, 0 when both
 * products are exactly zero (certainly collinear), else CLM_UNCERTAIN. */
CLM_FN int clm_orient2d_filter(double ax, double ay, double bx, double by, double cx, double cy) {
  double detleft = (ax - cx) * (by - cy);
  double detright = (ay - cy) * (bx - cx);
  double det = detleft - detright;
  double detsum, errbound;
  /* The sign of a rounded difference or product is exact, so when the two products do not
   * have the same strict sign the sign of det is certain. */
  if (detleft > 0.0) {
    if (detright <= 0.0)
      return 1;
    detsum = detleft + detright;
  } else if (detleft < 0.0) {
    if (detright >= 0.0)
      return -1;
    detsum = -detleft - detright;
  } else {
    return -clm_signd(detright);
  }
  errbound = CLM_CCWERRBOUND_A * detsum;
  if (det > errbound)
    return 1;
  if (-det > errbound)
    return -1;
  return CLM_UNCERTAIN;
}

/* Exact check on the original coordinates:
 *   det = (ax*by - ay*bx) + (bx*cy - by*cx) + (cx*ay - cy*ax),
 * each product an exact two-component expansion (no exact differences are assumed). */
CLM_COLD int clm_orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy) {
  double ab[CLM_LEN_MINOR], bc[CLM_LEN_MINOR], ca[CLM_LEN_MINOR], det[CLM_LEN_ORIENT];
  int abn = clm_minor2(ax, ay, bx, by, ab);
  int bcn = clm_minor2(bx, by, cx, cy, bc);
  int can = clm_minor2(cx, cy, ax, ay, ca);
  int detn = clm_sum3(abn, ab, bcn, bc, can, ca, det);
  return clm_expansion_sign(detn, det);
}

CLM_FN int clm_orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  int s = clm_orient2d_filter(ax, ay, bx, by, cx, cy);
  if (s != CLM_UNCERTAIN)
    return s;
  return clm_orient2d_exact(ax, ay, bx, by, cx, cy);
}

/* ---------------------------------------------------------------------------------------- */
/* incircle: sign of the lifted determinant                                                   */
/*   | ax ay ax^2+ay^2 1 ; bx by bx^2+by^2 1 ; cx cy cx^2+cy^2 1 ; dx dy dx^2+dy^2 1 |        */
/* > 0 when d lies inside the circle through a, b, c given counter-clockwise, < 0 outside,   */
/* 0 on it (the sign flips when a, b, c are clockwise).                                       */
/* ---------------------------------------------------------------------------------------- */

/* Fast check: +1 / -1 when Shewchuk's bound certifies the floating-point sign of the
 * determinant (evaluated on differences to d), else CLM_UNCERTAIN. */
CLM_FN int clm_incircle_filter(double ax, double ay, double bx, double by, double cx, double cy,
                               double dx, double dy) {
  double adx = ax - dx, ady = ay - dy;
  double bdx = bx - dx, bdy = by - dy;
  double cdx = cx - dx, cdy = cy - dy;
  double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  double cdxady = cdx * ady, adxcdy = adx * cdy;
  double adxbdy = adx * bdy, bdxady = bdx * ady;
  double alift = adx * adx + ady * ady;
  double blift = bdx * bdx + bdy * bdy;
  double clift = cdx * cdx + cdy * cdy;
  double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  double permanent = (clm_absd(bdxcdy) + clm_absd(cdxbdy)) * alift +
                     (clm_absd(cdxady) + clm_absd(adxcdy)) * blift +
                     (clm_absd(adxbdy) + clm_absd(bdxady)) * clift;
  double errbound = CLM_ICCERRBOUND_A * permanent;
  if (det > errbound)
    return 1;
  if (-det > errbound)
    return -1;
  return CLM_UNCERTAIN;
}

/* out = sign * (px^2 + py^2) * o for an orientation expansion o (at most CLM_LEN_LIFTED
 * components); sign is +1.0 or -1.0 (negation is exact). */
CLM_FN int clm_lifted_term(int on, const double *o, double px, double py, double sign,
                           double *out) {
  double once[CLM_LEN_SCALED1], xx[CLM_LEN_SCALED2], yy[CLM_LEN_SCALED2];
  int n1 = clm_scale_expansion(on, o, px, once);
  int xn = clm_scale_expansion(n1, once, sign * px, xx);
  n1 = clm_scale_expansion(on, o, py, once);
  int yn = clm_scale_expansion(n1, once, sign * py, yy);
  return clm_expansion_sum(xn, xx, yn, yy, out);
}

/* Exact check on the original coordinates.  Expanding along the lifted column,
 *   det = lift(a) O(b,c,d) - lift(b) O(a,c,d) + lift(c) O(a,b,d) - lift(d) O(a,b,c)
 * with O(p,q,r) = M(p,q) + M(q,r) + M(r,p), M(p,q) = px*qy - py*qx, and
 * lift(p) = px*px + py*py, every product formed exactly. */
CLM_COLD int clm_incircle_exact(double ax, double ay, double bx, double by, double cx, double cy,
                                double dx, double dy) {
  double ab[CLM_LEN_MINOR], bc[CLM_LEN_MINOR], cd[CLM_LEN_MINOR], da[CLM_LEN_MINOR];
  double ac[CLM_LEN_MINOR], ca[CLM_LEN_MINOR], bd[CLM_LEN_MINOR], db[CLM_LEN_MINOR];
  double orient[CLM_LEN_ORIENT];
  double term[CLM_LEN_LIFTED], acc_a[CLM_LEN_PARTIAL], acc_b[CLM_LEN_INCIRCLE];
  int abn, bcn, cdn, dan, acn, bdn, i, on, tn, an, bn;

  abn = clm_minor2(ax, ay, bx, by, ab);
  bcn = clm_minor2(bx, by, cx, cy, bc);
  cdn = clm_minor2(cx, cy, dx, dy, cd);
  dan = clm_minor2(dx, dy, ax, ay, da);
  acn = clm_minor2(ax, ay, cx, cy, ac);
  bdn = clm_minor2(bx, by, dx, dy, bd);
  for (i = 0; i < acn; i++)
    ca[i] = -ac[i];
  for (i = 0; i < bdn; i++)
    db[i] = -bd[i];

  /* + lift(a) O(b,c,d) */
  on = clm_sum3(bcn, bc, cdn, cd, bdn, db, orient);
  an = clm_lifted_term(on, orient, ax, ay, 1.0, acc_a); /* <= 96 */
  /* - lift(b) O(a,c,d) */
  on = clm_sum3(acn, ac, cdn, cd, dan, da, orient);
  tn = clm_lifted_term(on, orient, bx, by, -1.0, term);
  bn = clm_expansion_sum(an, acc_a, tn, term, acc_b); /* <= 192 */
  /* + lift(c) O(a,b,d) */
  on = clm_sum3(abn, ab, bdn, bd, dan, da, orient);
  tn = clm_lifted_term(on, orient, cx, cy, 1.0, term);
  an = clm_expansion_sum(bn, acc_b, tn, term, acc_a); /* <= 288 */
  /* - lift(d) O(a,b,c) */
  on = clm_sum3(abn, ab, bcn, bc, acn, ca, orient);
  tn = clm_lifted_term(on, orient, dx, dy, -1.0, term);
  bn = clm_expansion_sum(an, acc_a, tn, term, acc_b); /* <= 384 */
  return clm_expansion_sign(bn, acc_b);
}

/* a + b when it is exact; *inexact set otherwise. */
CLM_FN double clm_exact_sum(double a, double b, int *inexact) {
  double s, e;
  clm_two_sum(a, b, &s, &e);
  *inexact |= e != 0.0;
  return s;
}

/* a * b when it is exact; *inexact set otherwise. */
CLM_FN double clm_exact_product(double a, double b, int *inexact) {
  double p, e;
  clm_two_product(a, b, &p, &e);
  *inexact |= e != 0.0;
  return p;
}

/* The differences of a, b and c to d; 0 when one of them was rounded. */
CLM_FN int clm_exact_differences(double ax, double ay, double bx, double by, double cx, double cy,
                                 double dx, double dy, double *adx, double *ady, double *bdx,
                                 double *bdy, double *cdx, double *cdy) {
  int inexact = 0;
  *adx = clm_exact_sum(ax, -dx, &inexact);
  *ady = clm_exact_sum(ay, -dy, &inexact);
  *bdx = clm_exact_sum(bx, -dx, &inexact);
  *bdy = clm_exact_sum(by, -dy, &inexact);
  *cdx = clm_exact_sum(cx, -dx, &inexact);
  *cdy = clm_exact_sum(cy, -dy, &inexact);
  return !inexact;
}

/* The adaptive middle stage (Shewchuk's stage B): when the differences to d are exact (their
 * rounding error is zero, as on integer or dyadic lattices, where cocircular points are the
 * rule), the 3x3 determinant of the differences,
 *   lift(a-d) M(b-d, c-d) + lift(b-d) M(c-d, a-d) + lift(c-d) M(a-d, b-d),
 * formed exactly, is the determinant, in far fewer components than clm_incircle_exact.
 * CLM_UNCERTAIN when a difference was rounded. */
CLM_COLD int clm_incircle_translated(double ax, double ay, double bx, double by, double cx,
                                     double cy, double dx, double dy) {
  double adx, ady, bdx, bdy, cdx, cdy;
  if (!clm_exact_differences(ax, ay, bx, by, cx, cy, dx, dy, &adx, &ady, &bdx, &bdy, &cdx, &cdy))
    return CLM_UNCERTAIN;
  double bc[CLM_LEN_MINOR], ca[CLM_LEN_MINOR], ab[CLM_LEN_MINOR];
  double ta[CLM_LEN_TRANSLATED_TERM], tb[CLM_LEN_TRANSLATED_TERM], tc[CLM_LEN_TRANSLATED_TERM];
  double partial[2 * CLM_LEN_TRANSLATED_TERM], det[CLM_LEN_TRANSLATED];
  int bcn = clm_minor2(bdx, bdy, cdx, cdy, bc);
  int can = clm_minor2(cdx, cdy, adx, ady, ca);
  int abn = clm_minor2(adx, ady, bdx, bdy, ab);
  int an = clm_lifted_term(bcn, bc, adx, ady, 1.0, ta);
  int bn = clm_lifted_term(can, ca, bdx, bdy, 1.0, tb);
  int cn = clm_lifted_term(abn, ab, cdx, cdy, 1.0, tc);
  int pn = clm_expansion_sum(an, ta, bn, tb, partial);
  int detn = clm_expansion_sum(pn, partial, cn, tc, det);
  return clm_expansion_sign(detn, det);
}

/* Does x have at most 26 significant bits (Dekker's split leaves no low half)?  The product
 * of two such doubles is exact. */
CLM_FN int clm_fits_half(double x) {
  double hi, lo;
  clm_split(x, &hi, &lo);
  return lo == 0.0;
}

/* The cheapest exact stage, for lattice-like points (integer or dyadic coordinates of few
 * bits, where cocircular points are the rule): the determinant of the differences to d,
 *   lift(a-d) M(b-d, c-d) + lift(b-d) M(c-d, a-d) + lift(c-d) M(a-d, b-d),
 * evaluated in doubles with every operation checked exact: the differences and sums by
 * two_sum's error, the products of differences by their factors' 26 bits (clm_fits_half), the
 * three lifted products by two_product's error.  When all are exact the double is the
 * determinant, zero included; else CLM_UNCERTAIN (the expansions decide). */
CLM_COLD int clm_incircle_in_doubles(double ax, double ay, double bx, double by, double cx,
                                     double cy, double dx, double dy) {
  int inexact = 0;
  double adx, ady, bdx, bdy, cdx, cdy;
  if (!clm_exact_differences(ax, ay, bx, by, cx, cy, dx, dy, &adx, &ady, &bdx, &bdy, &cdx, &cdy) ||
      !clm_fits_half(adx) || !clm_fits_half(ady) || !clm_fits_half(bdx) || !clm_fits_half(bdy) ||
      !clm_fits_half(cdx) || !clm_fits_half(cdy))
    return CLM_UNCERTAIN;
  double bc = clm_exact_sum(bdx * cdy, -(bdy * cdx), &inexact);
  double ca = clm_exact_sum(cdx * ady, -(cdy * adx), &inexact);
  double ab = clm_exact_sum(adx * bdy, -(ady * bdx), &inexact);
  double alift = clm_exact_sum(adx * adx, ady * ady, &inexact);
  double blift = clm_exact_sum(bdx * bdx, bdy * bdy, &inexact);
  double clift = clm_exact_sum(cdx * cdx, cdy * cdy, &inexact);
  double ta = clm_exact_product(alift, bc, &inexact);
  double tb = clm_exact_product(blift, ca, &inexact);
  double tc = clm_exact_product(clift, ab, &inexact);
  double det = clm_exact_sum(clm_exact_sum(ta, tb, &inexact), tc, &inexact);
  return inexact ? CLM_UNCERTAIN : clm_signd(det);
}

/* The exact sign after the filter failed: the stage in doubles or the translated stage when
 * one applies, else the determinant of the original coordinates. */
CLM_FN int clm_incircle_after_filter(double ax, double ay, double bx, double by, double cx,
                                     double cy, double dx, double dy) {
  int s = clm_incircle_in_doubles(ax, ay, bx, by, cx, cy, dx, dy);
  if (s != CLM_UNCERTAIN)
    return s;
  s = clm_incircle_translated(ax, ay, bx, by, cx, cy, dx, dy);
  if (s != CLM_UNCERTAIN)
    return s;
  return clm_incircle_exact(ax, ay, bx, by, cx, cy, dx, dy);
}

CLM_FN int clm_incircle(double ax, double ay, double bx, double by, double cx, double cy, double dx,
                        double dy) {
  int s = clm_incircle_filter(ax, ay, bx, by, cx, cy, dx, dy);
  if (s != CLM_UNCERTAIN)
    return s;
  return clm_incircle_after_filter(ax, ay, bx, by, cx, cy, dx, dy);
}

/* ---------------------------------------------------------------------------------------- */
/* incircle with symbolic perturbation: never 0                                               */
/* ---------------------------------------------------------------------------------------- */

/* Decides a zero in-circle determinant by perturbing the lifting symbolically, the rule of
 * CGAL's Delaunay_triangulation_2 (Triangulation_2::side_of_oriented_circle with perturb):
 * the point of larger lexicographic (x, then y) rank is lifted by a larger infinitesimal, so
 * the leading non-zero monomial of the perturbed determinant is found by scanning the points
 * from the largest down.  If that point is d its coefficient is -O(a,b,c) < 0: d is outside;
 * if it is a, b or c the coefficient is the orientation with d in its place.  For a
 * counter-clockwise a, b, c two points always decide; the loop therefore stops above the
 * smallest point exactly as CGAL's does. */
CLM_FN int clm_incircle_perturbed(double ax, double ay, double bx, double by, double cx, double cy,
                                  double dx, double dy) {
  double px[4], py[4];
  int order[4], i, j, k, o;
  px[0] = ax, py[0] = ay, px[1] = bx, py[1] = by;
  px[2] = cx, py[2] = cy, px[3] = dx, py[3] = dy;
  /* Insertion sort of {a, b, c, d} by (x, y). */
  for (i = 0; i < 4; i++) {
    k = i;
    for (j = i - 1; j >= 0; j--) {
      int w = order[j];
      if (px[w] < px[k] || (px[w] == px[k] && py[w] < py[k]))
        break;
      order[j + 1] = w;
    }
    order[j + 1] = k;
  }
  for (i = 3; i > 0; i--) {
    k = order[i];
    if (k == 3)
      return -1;
    if (k == 2)
      o = clm_orient2d(ax, ay, bx, by, dx, dy);
    else if (k == 1)
      o = clm_orient2d(ax, ay, dx, dy, cx, cy);
    else
      o = clm_orient2d(dx, dy, bx, by, cx, cy);
    if (o != 0)
      return o;
  }
  return -1;
}

/* For a counter-clockwise triangle a, b, c and a point d distinct from a, b, c: +1 when d is
 * inside the circumcircle, -1 otherwise; a cocircular d is decided by the perturbation. */
CLM_FN int clm_incircle_sos(double ax, double ay, double bx, double by, double cx, double cy,
                            double dx, double dy) {
  int s = clm_incircle(ax, ay, bx, by, cx, cy, dx, dy);
  if (s != 0)
    return s;
  return clm_incircle_perturbed(ax, ay, bx, by, cx, cy, dx, dy);
}

/* Same as clm_incircle_sos for a caller that already knows clm_incircle_filter was uncertain
 * (the device's exact-check kernel): goes straight to the exact determinant. */
CLM_FN int clm_incircle_sos_exact(double ax, double ay, double bx, double by, double cx, double cy,
                                  double dx, double dy) {
  int s = clm_incircle_after_filter(ax, ay, bx, by, cx, cy, dx, dy);
  if (s != 0)
    return s;
  return clm_incircle_perturbed(ax, ay, bx, by, cx, cy, dx, dy);
}

#endif /* CLMESH_PREDICATES_H */
