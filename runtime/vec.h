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
 * b = (1 - cos(theta))/theta^2.  Below theta^2 = 1e-2 the series through
 * theta^8 leaves a truncation error under 3e-18. */
static inline void sw_rodrigues_coeffs(double theta2, double *a, double *b) {
  if (theta2 < 1e-2) {
    const double t = theta2;
    *a = 1.0 - t / 6.0 * (1.0 - t / 20.0 * (1.0 - t / 42.0 * (1.0 - t / 72.0)));
    *b = 0.5 * (1.0 - t / 12.0 * (1.0 - t / 30.0 * (1.0 - t / 56.0 * (1.0 - t / 90.0))));
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

/* The rotation vector phi with Qb = exp(-[phi]x) Qa, i.e. the logarithm of
 * R = Qb Qa^T (Gazzola 2018, eq. 3.6).  With w = (R12 - R21, R20 - R02,
 * R01 - R10) = 2 sin(theta) n and cos(theta) = (tr R - 1)/2, phi =
 * theta / (2 sin theta) w.  theta/sin(theta) = asin(s)/s is summed as its
 * series in s^2 for s < 0.1 (truncation < 1e-18); otherwise atan2. */
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
  if (s2 < 1e-2 && c > 0.0) {
    const double t = s2;
    f = 0.5 * (1.0 + t * (1.0 / 6 + t * (3.0 / 40 + t * (5.0 / 112 + t * (35.0 / 1152 +
        t * (63.0 / 2816 + t * (231.0 / 13312 + t * (143.0 / 10240))))))));
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

#endif
