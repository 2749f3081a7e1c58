/* vec.h — 3-vector, 3x3 frame and rotation algebra (internal to the runtime).
 *
 * Design.  Everything here is a static inline function on plain double arrays,
 * output argument first, so the compiler can inline it into the rod loops and
 * keep the loops free of calls.  A director frame Q is a row-major 3x3 matrix
 * whose rows are d1, d2, d3 (lab components): Q v maps lab components to
 * material ones, Q^T v back.  Rotations follow Gazzola et al. 2018, sec. 2:
 * material-frame angular velocity w evolves the frame as dQ/dt = -[w]x Q, so a
 * constant w over h rotates it exactly by exp(-h [w]x) (Rodrigues' formula),
 * and the curvature between neighbouring frames is the rotation vector of
 * Q_{i+1} Q_i^T = exp(-D [k]x) (the matrix logarithm).
 *
 * For small angles both the exponential and the logarithm use the Taylor
 * series of their scalar coefficients, truncated where the next term is below
 * double round-off, so they stay exact to machine precision while avoiding
 * the cancellation and the cost of sin/cos/atan2 (see the thresholds below).
 */
#ifndef SW_VEC_H
#define SW_VEC_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define SW_PI 3.14159265358979323846

static inline void sw_v3_sub(double *r, const double *a, const double *b) {
  r[0] = a[0] - b[0]; r[1] = a[1] - b[1]; r[2] = a[2] - b[2];
}
static inline void sw_v3_add(double *r, const double *a, const double *b) {
  r[0] = a[0] + b[0]; r[1] = a[1] + b[1]; r[2] = a[2] + b[2];
}
static inline void sw_v3_scale(double *r, const double *a, double s) {
  r[0] = a[0] * s; r[1] = a[1] * s; r[2] = a[2] * s;
}
static inline double sw_v3_dot(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
/* x clamped to [0, 1] */
static inline double sw_clamp01(double x) { return x < 0 ? 0 : (x > 1 ? 1 : x); }
static inline double sw_v3_norm(const double *a) { return sqrt(sw_v3_dot(a, a)); }
static inline void sw_v3_cross(double *r, const double *a, const double *b) {
  double r0 = a[1] * b[2] - a[2] * b[1];
  double r1 = a[2] * b[0] - a[0] * b[2];
  double r2 = a[0] * b[1] - a[1] * b[0];
  r[0] = r0; r[1] = r1; r[2] = r2;
}
/* r = Q a  (lab -> material) */
static inline void sw_mat_vec(double *r, const double *Q, const double *a) {
  double r0 = Q[0] * a[0] + Q[1] * a[1] + Q[2] * a[2];
  double r1 = Q[3] * a[0] + Q[4] * a[1] + Q[5] * a[2];
  double r2 = Q[6] * a[0] + Q[7] * a[1] + Q[8] * a[2];
  r[0] = r0; r[1] = r1; r[2] = r2;
}
/* r = Q^T a  (material -> lab) */
static inline void sw_matT_vec(double *r, const double *Q, const double *a) {
  double r0 = Q[0] * a[0] + Q[3] * a[1] + Q[6] * a[2];
  double r1 = Q[1] * a[0] + Q[4] * a[1] + Q[7] * a[2];
  double r2 = Q[2] * a[0] + Q[5] * a[1] + Q[8] * a[2];
  r[0] = r0; r[1] = r1; r[2] = r2;
}
/* C = A B */
static inline void sw_mat_mul(double *C, const double *A, const double *B) {
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      T[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
  for (int k = 0; k < 9; k++) C[k] = T[k];
}

/* Coefficients of Rodrigues' formula, R = I - a [u]x + b [u]x^2 with the
 * unnormalised axis u = theta * n:  a = sin(theta)/theta,
 * b = (1 - cos(theta))/theta^2.  Below theta^2 = 1e-2 their Taylor series
 * through theta^8 (Horner's rule in t = theta^2, with the reciprocal
 * factorials as constants, so no division) leaves a truncation error under
 * 3e-18. */
typedef struct { double a, b; } swRodrigues;
static inline swRodrigues sw_rodrigues_series(double t) {
  return (swRodrigues){
      1.0 + t * (-1.0 / 6 + t * (1.0 / 120 + t * (-1.0 / 5040 + t * (1.0 / 362880)))),
      0.5 + t * (-1.0 / 24 + t * (1.0 / 720 + t * (-1.0 / 40320 + t * (1.0 / 3628800))))};
}
static inline void sw_rodrigues_coeffs(double theta2, double *a, double *b) {
  if (theta2 < 1e-2) {
    const swRodrigues c = sw_rodrigues_series(theta2);
    *a = c.a;
    *b = c.b;
  } else {
    const double theta = sqrt(theta2), sh = sin(0.5 * theta);
    *a = sin(theta) / theta;
    *b = 2.0 * sh * sh / theta2; /* = (1 - cos)/theta^2 without cancellation */
  }
}

/* Q <- exp(-[phi]x) Q : the exact rotation of a director frame by the
 * material-frame rotation vector phi (Gazzola 2018, eq. 3.5 / Rodrigues).
 * Applied to each column c of Q:  c - a phi x c + b phi x (phi x c). */
static inline void sw_rotate_frame(double *Q, const double *phi) {
  double a, b;
  sw_rodrigues_coeffs(sw_v3_dot(phi, phi), &a, &b);
  for (int k = 0; k < 3; k++) {
    double c[3] = {Q[k], Q[3 + k], Q[6 + k]}, pc[3], ppc[3];
    sw_v3_cross(pc, phi, c);
    sw_v3_cross(ppc, phi, pc);
    Q[k] = c[0] - a * pc[0] + b * ppc[0];
    Q[3 + k] = c[1] - a * pc[1] + b * ppc[1];
    Q[6 + k] = c[2] - a * pc[2] + b * ppc[2];
  }
}

/* theta / (2 sin theta) from t = sin^2 theta (cos theta > 0): half of
 * asin(s)/s = sum_n C(2n, n) / (4^n (2n + 1)) t^n, summed to n = 13, whose
 * truncation is below 1e-19 of it for t < SW_LOG_SERIES_S2 = 1/16 (theta
 * below 14.5 degrees).  The range is that wide so that the rod pass's
 * vector loop (rod.c) takes nearly every domain of a bent rod: a domain
 * past it is redone with atan2, which was a seventh of a cantilever's step
 * at 5.7 degrees (s^2 < 1e-2, eight terms). */
#define SW_LOG_SERIES_S2 0.0625
static inline double sw_log_series(double t) {
  return 0.5 * (1.0 + t * (1.0 / 6 + t * (3.0 / 40 + t * (5.0 / 112 + t * (35.0 / 1152 +
         t * (63.0 / 2816 + t * (231.0 / 13312 + t * (143.0 / 10240 + t * (6435.0 / 557056 +
         t * (12155.0 / 1245184 + t * (46189.0 / 5505024 + t * (88179.0 / 12058624 +
         t * (676039.0 / 104857600 + t * (1300075.0 / 226492416))))))))))))));
}

/* The rotation vector phi with Qb = exp(-[phi]x) Qa, i.e. the logarithm of
 * R = Qb Qa^T (Gazzola 2018, eq. 3.6).  With w = (R12 - R21, R20 - R02,
 * R01 - R10) = 2 sin(theta) n and cos(theta) = (tr R - 1)/2, phi =
 * theta / (2 sin theta) w.  theta/sin(theta) = asin(s)/s is summed as its
 * series in s^2 for s^2 < SW_LOG_SERIES_S2 (sw_log_series); otherwise atan2. */
static inline void sw_frame_log(double *phi, const double *Qa, const double *Qb) {
  /* R_jk = d^b_j . d^a_k */
  const double *a1 = Qa, *a2 = Qa + 3, *a3 = Qa + 6;
  const double *b1 = Qb, *b2 = Qb + 3, *b3 = Qb + 6;
  double w0 = sw_v3_dot(b2, a3) - sw_v3_dot(b3, a2);
  double w1 = sw_v3_dot(b3, a1) - sw_v3_dot(b1, a3);
  double w2 = sw_v3_dot(b1, a2) - sw_v3_dot(b2, a1);
  double tr = sw_v3_dot(b1, a1) + sw_v3_dot(b2, a2) + sw_v3_dot(b3, a3);
  double s2 = 0.25 * (w0 * w0 + w1 * w1 + w2 * w2); /* sin^2(theta) */
  double c = 0.5 * (tr - 1.0);                     /* cos(theta)   */
  double f;                                        /* theta / (2 sin theta) */
  if (s2 < SW_LOG_SERIES_S2 && c > 0.0) {
    f = sw_log_series(s2);
  } else {
    double s = sqrt(s2);
    double theta = atan2(s, c);
    f = s > 1e-300 ? 0.5 * theta / s : 0.5; /* theta = pi with s = 0 is degenerate */
  }
  phi[0] = f * w0; phi[1] = f * w1; phi[2] = f * w2;
}

/* Build a right-handed orthonormal frame with d3 along `dir` and d1 along the
 * part of `normal` orthogonal to it.  Returns 0 if dir is zero or parallel to
 * normal. */
static inline int sw_frame_from(double *Q, const double *dir, const double *normal) {
  double d3[3], d1[3], d2[3];
  double nd = sw_v3_norm(dir), nn = sw_v3_norm(normal);
  if (!(nd > 0) || !(nn > 0)) return 0;
  sw_v3_scale(d3, dir, 1.0 / nd);
  /* d2 = unit(d3 x normal), d1 = d2 x d3.  When normal is nearly parallel to
   * dir the cross product carries a relative error eps / angle, which one
   * projection of d2 off d3 removes; d1 = d2 x d3 is then orthonormal to
   * round-off. */
  sw_v3_cross(d2, d3, normal);
  double n2 = sw_v3_norm(d2);
  if (!(n2 > 1e-12 * nn)) return 0;
  sw_v3_scale(d2, d2, 1.0 / n2);
  double p = sw_v3_dot(d2, d3);
  for (int k = 0; k < 3; k++) d2[k] -= p * d3[k];
  sw_v3_scale(d2, d2, 1.0 / sw_v3_norm(d2));
  sw_v3_cross(d1, d2, d3);
  for (int k = 0; k < 3; k++) { Q[k] = d1[k]; Q[3 + k] = d2[k]; Q[6 + k] = d3[k]; }
  return 1;
}

/* Values for the loop bodies: a 3-vector and a director frame (rows d1, d2,
 * d3) as small structs passed by value.  Unlike the double[3] arrays above,
 * which a loop body would have to keep in memory per vector lane, these live
 * in registers, so a loop written with them vectorizes.  Each operation
 * rounds exactly as its array form above does (same products, same order of
 * sums). */
typedef struct { double x, y, z; } sw3;
typedef struct { sw3 d1, d2, d3; } swFrame;

static inline sw3 sw3_add(sw3 a, sw3 b) { return (sw3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline sw3 sw3_sub(sw3 a, sw3 b) { return (sw3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline sw3 sw3_scale(sw3 a, double s) { return (sw3){a.x * s, a.y * s, a.z * s}; }
static inline double sw3_dot(sw3 a, sw3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline sw3 sw3_cross(sw3 a, sw3 b) {
  return (sw3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/* c ? a : b in the loop bodies, c being 0 or 1, with both a and b computed
 * and no branch.  GCC compiles ?: on computed values as control flow and
 * moves the arithmetic of each value into its arm; under its default
 * -ftrapping-math it may then vectorize the loop only where the vector unit
 * can mask that arithmetic lane by lane, which AVX-512 can and AVX2 cannot
 * (at -march=x86-64-v3 the loops were left scalar, "control flow in loop";
 * docs/performance.md).  Selected on the bits through a mask, the values are
 * computed on every lane and the selection is a blend at every instruction
 * set; the result is a or b exactly, as with ?:. */
static inline double sw_select(int c, double a, double b) {
  uint64_t ua, ub;
  memcpy(&ua, &a, sizeof ua);
  memcpy(&ub, &b, sizeof ub);
  const uint64_t mask = (uint64_t)0 - (uint64_t)(c != 0);
  const uint64_t r = (ua & mask) | (ub & ~mask);
  double x;
  memcpy(&x, &r, sizeof x);
  return x;
}

static inline sw3 sw3_select(int c, sw3 a, sw3 b) {
  return (sw3){sw_select(c, a.x, b.x), sw_select(c, a.y, b.y), sw_select(c, a.z, b.z)};
}

/* max and min of two numbers, inline: x > y ? x : y and x < y ? x : y, one
 * instruction each (maxsd, minsd).  x86-64 has no instruction with C's
 * fmax, which returns the number when one argument is a NaN, so GCC
 * compiles fmax to a call into libm unless told that there are no NaNs
 * (-ffinite-math-only): a per-element loop paid a call for each, and the
 * ground's friction, a chain of dependent operations from one element to
 * the next, the call's latency too (docs/benchmarks.md, "The muscular
 * snake's step").  For numbers these are glibc's fmax and fmin to the bit,
 * signed zeros included (x86-64 glibc computes them with maxsd and minsd:
 * fmax(0.0, -0.0) is -0.0 in both) and when x is a NaN; when y is a NaN
 * they return it, where fmax and fmin return x.  Use them where a NaN
 * argument means that the state is lost anyway (a NaN load makes its node's
 * velocity NaN, which the step's check reports), or as sw_max(x, bound)
 * for a running bound that is never NaN, which passes a NaN x over as fmax
 * does.  Loops that keep such a bound beside another reduction must use
 * these, not fmax and fmin: GCC 12.2 for 64-bit Arm (Debian 12's, -O3,
 * armv8-a and armv8.2-a+sve) stops with an internal compiler error
 * (vect_transform_reduction) vectorizing them with fmax or fmin
 * (planform.c's bounding box, contact.c's grid size, io/accuracy.c's
 * ranges; bench/bench_aarch64.sh compiles every runtime file for Arm). */
static inline double sw_max(double x, double y) { return x > y ? x : y; }
static inline double sw_min(double x, double y) { return x < y ? x : y; }

/* Q a (lab -> material) and Q^T a (material -> lab) */
static inline sw3 sw_frame_apply(swFrame Q, sw3 a) {
  return (sw3){sw3_dot(Q.d1, a), sw3_dot(Q.d2, a), sw3_dot(Q.d3, a)};
}
static inline sw3 sw_frame_apply_t(swFrame Q, sw3 a) {
  return (sw3){Q.d1.x * a.x + Q.d2.x * a.y + Q.d3.x * a.z, Q.d1.y * a.x + Q.d2.y * a.y + Q.d3.y * a.z,
               Q.d1.z * a.x + Q.d2.z * a.y + Q.d3.z * a.z};
}
/* slot i of a planar array (sinew.h, "Layout") with planes of S doubles */
static inline sw3 sw3_load(const double *a, size_t S, int i) {
  return (sw3){a[i], a[S + i], a[2 * S + i]};
}
static inline void sw3_store(double *a, size_t S, int i, sw3 v) {
  a[i] = v.x; a[S + i] = v.y; a[2 * S + i] = v.z;
}
static inline swFrame sw_frame_load(const double *Q, size_t S, int i) {
  return (swFrame){sw3_load(Q, S, i), sw3_load(Q + 3 * S, S, i), sw3_load(Q + 6 * S, S, i)};
}
static inline void sw_frame_store(double *Q, size_t S, int i, swFrame F) {
  sw3_store(Q, S, i, F.d1); sw3_store(Q + 3 * S, S, i, F.d2); sw3_store(Q + 6 * S, S, i, F.d3);
}

/* The small-angle side of sw_frame_log on frames held as values, in two
 * parts so that a loop over slots can run them as two loops (rod.c): the
 * first, sw_frame_log_parts, gives w (= 2 sin(theta) n), t = sin^2 theta and
 * whether the series serves (t < SW_LOG_SERIES_S2 and cos theta > 0, 1 or
 * 0); the second is phi = sw_log_series(t) w.  Where `small` is 1 phi has
 * the bits sw_frame_log gives; a loop redoes the few slots where it is 0
 * with sw_frame_log: a vector loop cannot branch per slot, and calling
 * atan2 on every lane to keep a few would cost more than the rest of the
 * loop's arithmetic.  (The tests are combined with & rather than &&, which
 * would be a branch the vectorizer sees as control flow.) */
typedef struct { sw3 w; double t; int small; } swLogParts;
static inline swLogParts sw_frame_log_parts(swFrame a, swFrame b) {
  const double w0 = sw3_dot(b.d2, a.d3) - sw3_dot(b.d3, a.d2);
  const double w1 = sw3_dot(b.d3, a.d1) - sw3_dot(b.d1, a.d3);
  const double w2 = sw3_dot(b.d1, a.d2) - sw3_dot(b.d2, a.d1);
  const double tr = sw3_dot(b.d1, a.d1) + sw3_dot(b.d2, a.d2) + sw3_dot(b.d3, a.d3);
  const double t = 0.25 * (w0 * w0 + w1 * w1 + w2 * w2), c = 0.5 * (tr - 1.0);
  return (swLogParts){{w0, w1, w2}, t, (t < SW_LOG_SERIES_S2) & (c > 0.0)};
}

/* beta(theta) of the inverse of the SO(3) exponential's Jacobian,
 *   J_l^-1(phi) = I - [phi]x / 2 + beta [phi]x^2,
 *   beta = 1 / theta^2 - cos(theta/2) / (2 theta sin(theta/2)),  theta = |phi|,
 * from theta^2 (0 <= theta <= pi, as sw_frame_log gives).  Its series,
 * sum_n (-1)^(n+1) B_2n theta^(2n-2) / (2n)! = 1/12 + theta^2/720 +
 * theta^4/30240 + ... (from that of cot(theta/2); B the Bernoulli numbers),
 * summed to n = 7, is exact to round-off below theta^2 = SW_BETA_SERIES_TH2
 * (truncation below 1e-20 of it), where the closed form loses digits; the
 * series alone serves sw_frame_log_parts's range (theta^2 < 0.064).  rod.c
 * forms the variational bending couple with it. */
#define SW_BETA_SERIES_TH2 0.07
static inline double sw_dexpinv_beta_small(double th2) {
  return 1.0 / 12 + th2 * (1.0 / 720 + th2 * (1.0 / 30240 + th2 * (1.0 / 1209600 +
         th2 * (1.0 / 47900160 + th2 * (691.0 / 1307674368000.0 + th2 * (1.0 / 74724249600.0))))));
}
static inline double sw_dexpinv_beta(double th2) {
  if (th2 < SW_BETA_SERIES_TH2) return sw_dexpinv_beta_small(th2);
  const double th = sqrt(th2);
  return 1.0 / th2 - cos(0.5 * th) / (2.0 * th * sin(0.5 * th));
}

/* One column c of a frame (c = (d1_k, d2_k, d3_k)) turned by Rodrigues'
 * formula with the coefficients a, b of sw_rodrigues_coeffs:
 * c - a phi x c + b phi x (phi x c), as sw_rotate_frame turns it.  With the
 * series' a, b, the small-angle side of exp(-[phi]x) Q, exact where
 * |phi|^2 < 1e-2 (sw_frame_small_turn); integrate.c turns the frames that
 * turn by more with sw_rotate_frame. */
static inline sw3 sw_rodrigues_column(sw3 c, sw3 phi, double a, double b) {
  const sw3 pc = sw3_cross(phi, c), ppc = sw3_cross(phi, pc);
  return (sw3){c.x - a * pc.x + b * ppc.x, c.y - a * pc.y + b * ppc.y, c.z - a * pc.z + b * ppc.z};
}

/* One Newton step of the polar decomposition towards the nearest rotation,
 * Q <- (3 I - Q Q^T) Q / 2, written as d_i += E_ij d_j / 2 with the small
 * E = I - Q Q^T (E_ij = delta_ij - d_i . d_j): it takes an error eps in
 * orthonormality to O(eps^2), so round-off cannot accumulate in the frames
 * over a long run (the rigid bodies' drift does the same, rigid.c). */
static inline swFrame sw_frame_orthonormalize(swFrame Q) {
  const double e11 = 0.5 * (1.0 - sw3_dot(Q.d1, Q.d1)), e22 = 0.5 * (1.0 - sw3_dot(Q.d2, Q.d2));
  const double e33 = 0.5 * (1.0 - sw3_dot(Q.d3, Q.d3)), e12 = -0.5 * sw3_dot(Q.d1, Q.d2);
  const double e13 = -0.5 * sw3_dot(Q.d1, Q.d3), e23 = -0.5 * sw3_dot(Q.d2, Q.d3);
  const sw3 a = Q.d1, b = Q.d2, c = Q.d3;
  return (swFrame){{a.x + e11 * a.x + e12 * b.x + e13 * c.x, a.y + e11 * a.y + e12 * b.y + e13 * c.y,
                    a.z + e11 * a.z + e12 * b.z + e13 * c.z},
                   {b.x + e12 * a.x + e22 * b.x + e23 * c.x, b.y + e12 * a.y + e22 * b.y + e23 * c.y,
                    b.z + e12 * a.z + e22 * b.z + e23 * c.z},
                   {c.x + e13 * a.x + e23 * b.x + e33 * c.x, c.y + e13 * a.y + e23 * b.y + e33 * c.y,
                    c.z + e13 * a.z + e23 * b.z + e33 * c.z}};
}

static inline int sw_frame_small_turn(sw3 phi) { return sw3_dot(phi, phi) < 1e-2; }

#endif
