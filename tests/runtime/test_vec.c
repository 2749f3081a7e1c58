/* test_vec.c — unit tests of the 3-vector, frame and rotation algebra of
 * runtime/engine/vec.h.
 *
 * Checks the sw_v3_* basics and the cross-product identities (Lagrange,
 * Jacobi, a x (b x c) = b (a.c) - c (a.b)); that sw_mat_vec and sw_matT_vec
 * invert each other for an orthonormal frame; that sw_rotate_frame keeps a
 * frame orthonormal through 10^5 random small rotations and agrees with
 * exp(-[phi]x) built independently (the matrix exponential's Taylor series
 * summed to convergence in long double, cross-checked against a quaternion)
 * on both branches of sw_rodrigues_coeffs; that sw_frame_log inverts
 * sw_rotate_frame on both of its branches with the sign convention
 * Qb = exp(-[phi]x) Qa, continuously across the branch thresholds; and that
 * sw_frame_from builds a right-handed orthonormal frame with d3 along the
 * direction, also when the normal is nearly parallel to it, and rejects
 * degenerate input; and that sw_max and sw_min as running bounds keep the
 * bounds fmax and fmin keep.  Worst errors are printed as "# ..." lines. */
#include "testutil.h"
#include "vec.h"

/* ---- helpers: deterministic random numbers and reference rotations ---- */

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;

/* splitmix64, uniform in [0, 1) */
static double urand(void) {
  uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1.0p-53;
}

static double srand_sym(void) { return 2.0 * urand() - 1.0; }

/* Random unit vector (rejection from the unit ball). */
static void random_unit(double *u) {
  double n2;
  do {
    u[0] = srand_sym(); u[1] = srand_sym(); u[2] = srand_sym();
    n2 = sw_v3_dot(u, u);
  } while (n2 > 1.0 || n2 < 1e-4);
  sw_v3_scale(u, u, 1.0 / sqrt(n2));
}

/* Rotation matrix of a unit quaternion (w, x, y, z), long double. */
static void quat_matrix(long double *R, long double w, long double x, long double y, long double z) {
  R[0] = 1 - 2 * (y * y + z * z); R[1] = 2 * (x * y - w * z); R[2] = 2 * (x * z + w * y);
  R[3] = 2 * (x * y + w * z); R[4] = 1 - 2 * (x * x + z * z); R[5] = 2 * (y * z - w * x);
  R[6] = 2 * (x * z - w * y); R[7] = 2 * (y * z + w * x); R[8] = 1 - 2 * (x * x + y * y);
}

/* Random orthonormal frame from a random unit quaternion. */
static void random_frame(double *Q) {
  long double q[4], n2 = 0, R[9];
  do {
    n2 = 0;
    for (int k = 0; k < 4; k++) { q[k] = srand_sym(); n2 += q[k] * q[k]; }
  } while (n2 > 1.0L || n2 < 1e-4L);
  long double inv = 1.0L / sqrtl(n2);
  quat_matrix(R, q[0] * inv, q[1] * inv, q[2] * inv, q[3] * inv);
  for (int k = 0; k < 9; k++) Q[k] = (double)R[k];
}

/* Reference R = exp(-[phi]x): the Taylor series sum_k M^k / k! with
 * M = -[phi]x, summed in long double until the terms stop contributing. */
static void expm_taylor(long double *R, const double *phi) {
  long double M[9] = {0, phi[2], -phi[1], -phi[2], 0, phi[0], phi[1], -phi[0], 0};
  long double term[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int k = 0; k < 9; k++) R[k] = term[k];
  for (int j = 1; j < 200; j++) {
    long double next[9], big = 0;
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) {
        long double s = 0;
        for (int k = 0; k < 3; k++) s += term[3 * r + k] * M[3 * k + c];
        next[3 * r + c] = s / j;
      }
    for (int k = 0; k < 9; k++) {
      term[k] = next[k];
      R[k] += term[k];
      if (fabsl(term[k]) > big) big = fabsl(term[k]);
    }
    if (big < 1e-30L) break;
  }
}

/* The same rotation from a quaternion: a turn by -theta about n = phi/theta. */
static void expm_quat(long double *R, const double *phi) {
  long double th = sqrtl((long double)phi[0] * phi[0] + (long double)phi[1] * phi[1] +
                         (long double)phi[2] * phi[2]);
  long double s = th > 0 ? -sinl(0.5L * th) / th : -0.5L;
  quat_matrix(R, cosl(0.5L * th), s * phi[0], s * phi[1], s * phi[2]);
}

/* Largest |A_ij - (R Q)_ij|. */
static double max_diff_RQ(const double *A, const long double *R, const double *Q) {
  double e = 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      long double s = 0;
      for (int k = 0; k < 3; k++) s += R[3 * i + k] * Q[3 * k + j];
      double d = (double)fabsl((long double)A[3 * i + j] - s);
      if (d > e) e = d;
    }
  return e;
}

/* Frobenius norm of Q Q^T - I, accumulated in long double. */
static double orth_error(const double *Q) {
  long double s = 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      long double p = 0;
      for (int k = 0; k < 3; k++) p += (long double)Q[3 * i + k] * Q[3 * j + k];
      p -= (i == j);
      s += p * p;
    }
  return (double)sqrtl(s);
}

static double det3(const double *Q) {
  return Q[0] * (Q[4] * Q[8] - Q[5] * Q[7]) - Q[1] * (Q[3] * Q[8] - Q[5] * Q[6]) +
         Q[2] * (Q[3] * Q[7] - Q[4] * Q[6]);
}

static double v3_maxdiff(const double *a, const double *b) {
  return fmax(fabs(a[0] - b[0]), fmax(fabs(a[1] - b[1]), fabs(a[2] - b[2])));
}

/* ---- sw_v3_* ---- */

static void test_v3_basics(void **state) {
  (void)state;
  const double a[3] = {1.5, -2.0, 0.25}, b[3] = {-0.5, 4.0, 8.0};
  double r[3];
  sw_v3_add(r, a, b);
  assert_true(r[0] == 1.0 && r[1] == 2.0 && r[2] == 8.25);
  sw_v3_sub(r, a, b);
  assert_true(r[0] == 2.0 && r[1] == -6.0 && r[2] == -7.75);
  sw_v3_scale(r, a, -2.0);
  assert_true(r[0] == -3.0 && r[1] == 4.0 && r[2] == -0.5);
  assert_true(sw_v3_dot(a, b) == -0.75 - 8.0 + 2.0);
  const double p[3] = {3.0, -4.0, 12.0};
  assert_true(sw_v3_norm(p) == 13.0);
  const double z[3] = {0, 0, 0};
  assert_true(sw_v3_norm(z) == 0.0);
  /* in-place use: output may alias an input */
  double c[3] = {1, 2, 3};
  sw_v3_add(c, c, c);
  assert_true(c[0] == 2 && c[1] == 4 && c[2] == 6);
  sw_v3_scale(c, c, 0.5);
  sw_v3_sub(c, c, a);
  assert_true(c[0] == -0.5 && c[1] == 4.0 && c[2] == 2.75);
}

static void test_cross_identities(void **state) {
  (void)state;
  const double e1[3] = {1, 0, 0}, e2[3] = {0, 1, 0}, e3[3] = {0, 0, 1};
  double r[3];
  sw_v3_cross(r, e1, e2);
  assert_true(r[0] == 0 && r[1] == 0 && r[2] == 1);
  sw_v3_cross(r, e2, e3);
  assert_true(r[0] == 1 && r[1] == 0 && r[2] == 0);
  sw_v3_cross(r, e3, e1);
  assert_true(r[0] == 0 && r[1] == 1 && r[2] == 0);
  sw_v3_cross(r, e2, e1);
  assert_true(r[0] == 0 && r[1] == 0 && r[2] == -1);
  const double a0[3] = {2, 3, 4}, b0[3] = {5, 6, 7};
  sw_v3_cross(r, a0, b0); /* (3*7-4*6, 4*5-2*7, 2*6-3*5) */
  assert_true(r[0] == -3 && r[1] == 6 && r[2] == -3);

  double worst = 0;
  for (int t = 0; t < 1000; t++) {
    double a[3], b[3], c[3], axb[3], bxa[3], axa[3], tmp[3], lhs[3], rhs[3];
    for (int k = 0; k < 3; k++) { a[k] = srand_sym(); b[k] = srand_sym(); c[k] = srand_sym(); }
    sw_v3_cross(axb, a, b);
    sw_v3_cross(bxa, b, a);
    sw_v3_cross(axa, a, a);
    /* anticommutative, a x a = 0 exactly */
    for (int k = 0; k < 3; k++) assert_true(axb[k] == -bxa[k] && axa[k] == 0.0);
    /* orthogonal to both factors */
    worst = fmax(worst, fabs(sw_v3_dot(axb, a)));
    worst = fmax(worst, fabs(sw_v3_dot(axb, b)));
    /* Lagrange: |a x b|^2 = |a|^2 |b|^2 - (a.b)^2 */
    double ab = sw_v3_dot(a, b);
    worst = fmax(worst, fabs(sw_v3_dot(axb, axb) - (sw_v3_dot(a, a) * sw_v3_dot(b, b) - ab * ab)));
    /* a x (b x c) = b (a.c) - c (a.b) */
    double bxc[3];
    sw_v3_cross(bxc, b, c);
    sw_v3_cross(lhs, a, bxc);
    for (int k = 0; k < 3; k++) rhs[k] = b[k] * sw_v3_dot(a, c) - c[k] * ab;
    worst = fmax(worst, v3_maxdiff(lhs, rhs));
    /* Jacobi: a x (b x c) + b x (c x a) + c x (a x b) = 0 */
    double cxa[3], j2[3], j3[3];
    sw_v3_cross(cxa, c, a);
    sw_v3_cross(j2, b, cxa);
    sw_v3_cross(j3, c, axb);
    for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(lhs[k] + j2[k] + j3[k]));
    /* triple product is cyclic: a.(b x c) = b.(c x a) */
    worst = fmax(worst, fabs(sw_v3_dot(a, bxc) - sw_v3_dot(b, cxa)));
    /* aliased output: r = a x r */
    memcpy(tmp, b, sizeof tmp);
    sw_v3_cross(tmp, a, tmp);
    for (int k = 0; k < 3; k++) assert_true(tmp[k] == axb[k]);
    memcpy(tmp, a, sizeof tmp);
    sw_v3_cross(tmp, tmp, b);
    for (int k = 0; k < 3; k++) assert_true(tmp[k] == axb[k]);
  }
  fprintf(stderr, "# %s: worst residual of the cross-product identities %.3e (tol 1e-14)\n",
          __func__, worst);
  assert_true(worst < 1e-14);
}

/* ---- frames ---- */

static void test_mat_vec_inverse(void **state) {
  (void)state;
  /* a hand-checked product */
  const double M[9] = {1, 2, 3, 4, 5, 6, 7, 8, 10}, v[3] = {1, -1, 2};
  double r[3];
  sw_mat_vec(r, M, v);
  assert_true(r[0] == 5 && r[1] == 11 && r[2] == 19);
  sw_matT_vec(r, M, v);
  assert_true(r[0] == 11 && r[1] == 13 && r[2] == 17);
  double C[9];
  sw_mat_mul(C, M, M);
  const double MM[9] = {30, 36, 45, 66, 81, 102, 109, 134, 169};
  for (int k = 0; k < 9; k++) assert_true(C[k] == MM[k]);
  memcpy(C, M, sizeof C);
  sw_mat_mul(C, C, M); /* aliased output */
  for (int k = 0; k < 9; k++) assert_true(C[k] == MM[k]);

  double worst = 0, worst_rows = 0;
  for (int t = 0; t < 1000; t++) {
    double Q[9], a[3], b[3], c[3];
    random_frame(Q);
    for (int k = 0; k < 3; k++) a[k] = srand_sym();
    sw_mat_vec(b, Q, a);
    sw_matT_vec(c, Q, b);
    worst = fmax(worst, v3_maxdiff(c, a));
    sw_matT_vec(b, Q, a);
    sw_mat_vec(c, Q, b);
    worst = fmax(worst, v3_maxdiff(c, a));
    /* in place */
    memcpy(c, a, sizeof c);
    sw_mat_vec(c, Q, c);
    sw_matT_vec(c, Q, c);
    worst = fmax(worst, v3_maxdiff(c, a));
    /* the rows are the directors: Q d_j = e_j, Q^T e_j = d_j */
    for (int j = 0; j < 3; j++) {
      double ej[3] = {0, 0, 0};
      ej[j] = 1;
      sw_mat_vec(b, Q, Q + 3 * j);
      worst_rows = fmax(worst_rows, v3_maxdiff(b, ej));
      sw_matT_vec(b, Q, ej);
      assert_true(b[0] == Q[3 * j] && b[1] == Q[3 * j + 1] && b[2] == Q[3 * j + 2]);
    }
  }
  fprintf(stderr, "# %s: worst |Q^T Q a - a| = %.3e, |Q d_j - e_j| = %.3e (tol 1e-15)\n",
          __func__, worst, worst_rows);
  assert_true(worst < 1e-15);
  assert_true(worst_rows < 1e-15);
}

/* Each rotation is orthogonal only to round-off, so Q Q^T - I performs a
 * random walk: about 2e-16 sqrt(N) after N rotations (measured up to 10^7),
 * 5e-14 after 10^5, so a flat 1e-14 cannot hold without re-orthonormalising.
 * The envelope 1e-15 sqrt(N) + 1e-15, checked after every rotation, passes
 * the random walk and fails a systematic drift, which would grow like N eps
 * (1e-11 at N = 10^5). */
static void test_rotate_frame_stays_orthonormal(void **state) {
  (void)state;
  const int nstep = 100000;
  double Q[9];
  random_frame(Q);
  double e0 = orth_error(Q), worst = e0, worst_ratio = 0;
  for (int t = 1; t <= nstep; t++) {
    /* small rotations as in a time step, on both branches of the
     * coefficients (|phi| up to 0.2, so theta^2 up to 4e-2) */
    double phi[3], u[3];
    random_unit(u);
    double th = 0.2 * urand();
    sw_v3_scale(phi, u, th);
    sw_rotate_frame(Q, phi);
    double e = orth_error(Q);
    if (e > worst) worst = e;
    double ratio = e / (1e-15 * sqrt((double)t) + 1e-15);
    if (ratio > worst_ratio) worst_ratio = ratio;
  }
  double det = det3(Q), tol = 1e-15 * sqrt((double)nstep) + 1e-15;
  fprintf(stderr,
          "# %s: ||Q Q^T - I||_F = %.3e at start, worst %.3e over %d rotations "
          "(%.2f eps sqrt(N)), final %.3e; worst error / (1e-15 sqrt(n) + 1e-15) = %.3f "
          "(tol 1); det - 1 = %.3e (tol %.1e)\n",
          __func__, e0, worst, nstep, worst / (0x1.0p-52 * sqrt((double)nstep)), orth_error(Q),
          worst_ratio, det - 1.0, tol);
  assert_true(worst_ratio <= 1.0);
  assert_true(fabs(det - 1.0) < tol);
}

/* Angles of the tests of sw_rotate_frame: both branches of
 * sw_rodrigues_coeffs (theta^2 < 1e-2 on the series), either side of the
 * threshold by a relative 1e-12 and by one rounding, and the extremes. */
static const double ROT_ANGLES[] = {0.0, 1e-12, 1e-8, 1e-4, 1e-2, 0.05, 0.099999999999,
                                    0.1 - 1e-17, 0.1, 0.100000000001, 0.2, 0.5, 1.0, 2.0,
                                    3.0, 3.14, 3.1415926};

static void test_rotate_frame_against_exp(void **state) {
  (void)state;
  const int naxes = 200;
  double worst_all = 0, worst_ref = 0, worst_series = 0, worst_trig = 0;
  for (size_t ia = 0; ia < sizeof ROT_ANGLES / sizeof *ROT_ANGLES; ia++) {
    double th = ROT_ANGLES[ia], worst = 0;
    for (int t = 0; t < naxes; t++) {
      double Q[9], Q0[9], u[3], phi[3];
      random_frame(Q0);
      random_unit(u);
      sw_v3_scale(phi, u, th);
      long double Rt[9], Rq[9];
      expm_taylor(Rt, phi);
      expm_quat(Rq, phi);
      for (int k = 0; k < 9; k++)
        worst_ref = fmax(worst_ref, (double)fabsl(Rt[k] - Rq[k]));
      memcpy(Q, Q0, sizeof Q);
      sw_rotate_frame(Q, phi);
      worst = fmax(worst, max_diff_RQ(Q, Rt, Q0));
    }
    double th2 = th * th;
    if (th2 < 1e-2) worst_series = fmax(worst_series, worst);
    else worst_trig = fmax(worst_trig, worst);
    worst_all = fmax(worst_all, worst);
    fprintf(stderr, "# %s: theta = %.17g (%s branch): max |Q' - exp(-[phi]x) Q| = %.3e\n",
            __func__, th, th2 < 1e-2 ? "series" : "sin/cos", worst);
  }
  fprintf(stderr,
          "# %s: worst %.3e (series branch %.3e, sin/cos branch %.3e; tol 1e-15); "
          "Taylor vs quaternion reference %.3e\n",
          __func__, worst_all, worst_series, worst_trig, worst_ref);
  assert_true(worst_ref < 1e-17);
  assert_true(worst_all < 1e-15);
}

/* The Rodrigues coefficients themselves against long double, on a fine sweep
 * through the threshold theta^2 = 1e-2, and their jump across it.  What
 * enters the rotation is a theta and b theta^2 (the terms multiply phi x c
 * and phi x (phi x c)), so those are held to round-off.  b alone is printed:
 * just above the threshold (1 - cos theta) / theta^2 loses digits to the
 * cancellation in 1 - cos theta (about 2e-14 relative at theta = 0.1), which
 * the factor theta^2 makes harmless in the rotation. */
static void test_rodrigues_coeffs(void **state) {
  (void)state;
  double worst_a = 0, worst_b = 0, worst_bt2 = 0;
  for (int k = -2000; k <= 2000; k++) {
    double t2 = 1e-2 * (1.0 + 1e-3 * k / 2000.0);
    if (k == -2000) t2 = 1e-14;
    if (k == -1999) t2 = 1e-6;
    if (k == 1999) t2 = 1.0;
    if (k == 2000) t2 = 9.0;
    double a, b;
    sw_rodrigues_coeffs(t2, &a, &b);
    long double th = sqrtl((long double)t2), sh = sinl(0.5L * th);
    long double ar = sinl(th) / th, br = 2.0L * sh * sh / (long double)t2;
    worst_a = fmax(worst_a, (double)(fabsl(a - ar) / ar));
    worst_b = fmax(worst_b, (double)(fabsl(b - br) / br));
    worst_bt2 = fmax(worst_bt2, (double)(fabsl(b - br) * t2));
  }
  double t_lo = nextafter(1e-2, 0.0), a_lo, b_lo, a_hi, b_hi;
  sw_rodrigues_coeffs(t_lo, &a_lo, &b_lo);
  sw_rodrigues_coeffs(1e-2, &a_hi, &b_hi);
  double jump_a = fabs(a_hi - a_lo), jump_bt2 = fabs(b_hi - b_lo) * 1e-2;
  fprintf(stderr,
          "# %s: worst rel. error of a = %.3e (tol 4e-16); of b theta^2 = %.3e (tol 2e-16); "
          "b alone %.3e; jump at theta^2 = 1e-2: a %.3e, b theta^2 %.3e (tol 2e-16)\n",
          __func__, worst_a, worst_bt2, worst_b, jump_a, jump_bt2);
  assert_true(worst_a < 4e-16);
  assert_true(worst_bt2 < 2e-16);
  assert_true(jump_a < 2e-16 && jump_bt2 < 2e-16);
}

/* ---- sw_frame_log ---- */

/* Sign convention on a hand-computed case: phi = (0, 0, theta) turns d1
 * towards d2 about d3 (a positive turn about the material axis d3), keeping
 * d3; and the log of that pair is +phi. */
static void test_frame_log_sign_convention(void **state) {
  (void)state;
  double Qa[9], Qb[9], phi_out[3];
  random_frame(Qa);
  for (int axis = 0; axis < 3; axis++) {
    const double th = 0.7;
    double phi[3] = {0, 0, 0};
    phi[axis] = th;
    memcpy(Qb, Qa, sizeof Qb);
    sw_rotate_frame(Qb, phi);
    int i = (axis + 1) % 3, j = (axis + 2) % 3; /* d_i -> cos d_i + sin d_j */
    double di[3], dj[3];
    for (int k = 0; k < 3; k++) {
      di[k] = cos(th) * Qa[3 * i + k] + sin(th) * Qa[3 * j + k];
      dj[k] = -sin(th) * Qa[3 * i + k] + cos(th) * Qa[3 * j + k];
    }
    assert_true(v3_maxdiff(Qb + 3 * axis, Qa + 3 * axis) < 1e-15);
    assert_true(v3_maxdiff(Qb + 3 * i, di) < 1e-15);
    assert_true(v3_maxdiff(Qb + 3 * j, dj) < 1e-15);
    sw_frame_log(phi_out, Qa, Qb);
    assert_true(v3_maxdiff(phi_out, phi) < 1e-15);
    /* the reverse pair gives -phi */
    sw_frame_log(phi_out, Qb, Qa);
    for (int k = 0; k < 3; k++) assert_true(fabs(phi_out[k] + phi[k]) < 1e-15);
  }
  /* the same convention independently of sw_rotate_frame: Qb = exp(-[phi]x) Qa
   * from the Taylor series, rounded to double */
  double worst = 0;
  for (int t = 0; t < 200; t++) {
    double u[3], phi[3];
    long double R[9];
    random_frame(Qa);
    random_unit(u);
    sw_v3_scale(phi, u, 0.05 + 3.0 * urand());
    expm_taylor(R, phi);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        long double acc = 0;
        for (int k = 0; k < 3; k++) acc += R[3 * i + k] * Qa[3 * k + j];
        Qb[3 * i + j] = (double)acc;
      }
    sw_frame_log(phi_out, Qa, Qb);
    double d[3];
    sw_v3_sub(d, phi_out, phi);
    worst = fmax(worst, sw_v3_norm(d) / sw_v3_norm(phi));
  }
  fprintf(stderr, "# %s: log(Qa, exp(-[phi]x) Qa) = +phi for theta in [0.05, 3.05]: worst "
                  "relative error %.3e (tol 1e-14)\n",
          __func__, worst);
  assert_true(worst < 1e-14);
  /* identical frames: zero */
  sw_frame_log(phi_out, Qa, Qa);
  assert_true(sw_v3_norm(phi_out) < 1e-16);
}

/* Angles of the logarithm tests: the series branch is taken while
 * s^2 = sin^2(theta) < 1/16 and cos(theta) > 0, i.e. theta < asin(0.25).
 * Qb carries the rounding of sw_rotate_frame (about 1e-16 absolute) and the
 * dot products of general frames add as much, so the recovered phi has an
 * absolute floor of that size: the bound is 1e-14 |phi| + 2.5e-16.  Near
 * theta = pi the axis comes from w = 2 sin(theta) n, so the rounding is
 * amplified by 1/sin(theta) (7e-15 relative at 3.1 rad). */
static void test_frame_log_inverts_rotation(void **state) {
  (void)state;
  const double thc = asin(0.25);
  const double angles[] = {1e-12, 1e-9, 1e-6, 1e-3, 1e-2, 0.05, 0.1, 0.2, thc * (1 - 1e-6),
                           thc * (1 - 1e-15), thc, thc * (1 + 1e-15), thc * (1 + 1e-6), 0.3,
                           0.5, 1.0, SW_PI / 2, 2.0, 2.5, 3.0, 3.04, 3.05, 3.1};
  const int naxes = 500;
  double worst_series = 0, worst_trig = 0, worst_abs = 0, worst_excess = 0;
  for (size_t ia = 0; ia < sizeof angles / sizeof *angles; ia++) {
    double th = angles[ia], worst = 0, worst_a = 0;
    for (int t = 0; t < naxes; t++) {
      double Qa[9], Qb[9], u[3], phi[3], out[3], d[3];
      random_frame(Qa);
      random_unit(u);
      sw_v3_scale(phi, u, th);
      memcpy(Qb, Qa, sizeof Qb);
      sw_rotate_frame(Qb, phi);
      sw_frame_log(out, Qa, Qb);
      sw_v3_sub(d, out, phi);
      double e = sw_v3_norm(d);
      worst = fmax(worst, e / th);
      worst_a = fmax(worst_a, e);
      worst_excess = fmax(worst_excess, e / (1e-14 * th + 2.5e-16));
    }
    worst_abs = fmax(worst_abs, worst_a);
    if (th >= 0.05) {
      if (th < thc) worst_series = fmax(worst_series, worst);
      else worst_trig = fmax(worst_trig, worst);
    }
    fprintf(stderr, "# %s: theta = %.17g (%s): max |log - phi| = %.3e, relative %.3e\n",
            __func__, th, th < thc ? "series" : "atan2", worst_a, worst);
  }
  /* From axis-aligned frames the dot products are exact and the relative
   * precision survives down to the tiniest angles. */
  const double tiny[] = {1e-12, 1e-9, 1e-6, 1e-3};
  double worst_tiny_rel = 0;
  for (size_t ia = 0; ia < sizeof tiny / sizeof *tiny; ia++)
    for (int t = 0; t < naxes; t++) {
      const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      double Qb[9], u[3], phi[3], out[3], d[3];
      random_unit(u);
      sw_v3_scale(phi, u, tiny[ia]);
      memcpy(Qb, I, sizeof Qb);
      sw_rotate_frame(Qb, phi);
      sw_frame_log(out, I, Qb);
      sw_v3_sub(d, out, phi);
      worst_tiny_rel = fmax(worst_tiny_rel, sw_v3_norm(d) / tiny[ia]);
    }
  fprintf(stderr,
          "# %s: worst relative error for theta >= 0.05: series branch %.3e, atan2 branch %.3e "
          "(tol 1e-14); worst absolute %.3e; worst error / (1e-14 theta + 2.5e-16) = %.3f "
          "(tol 1); theta <= 1e-3 from the identity frame: relative %.3e (tol 1e-15)\n",
          __func__, worst_series, worst_trig, worst_abs, worst_excess, worst_tiny_rel);
  assert_true(worst_series < 1e-14);
  assert_true(worst_trig < 1e-14);
  assert_true(worst_excess <= 1.0);
  assert_true(worst_tiny_rel < 1e-15);
}

/* Continuity across the branch threshold of the logarithm: along a fixed axis
 * and from a fixed frame, |log| minus the angle must not jump as theta
 * crosses asin(0.25) in steps of a few roundings: the error on both sides
 * stays at the round-off level of the generic angles (about 1.5e-15). */
static void test_frame_log_continuity(void **state) {
  (void)state;
  const double thc = asin(0.25);
  double worst = 0, Qa[9], u[3];
  int nseries = 0, ntrig = 0;
  random_frame(Qa);
  random_unit(u);
  for (int k = -200; k <= 200; k++) {
    double th = thc * (1.0 + 1e-15 * k), phi[3], Qb[9], out[3], d[3];
    sw_v3_scale(phi, u, th);
    memcpy(Qb, Qa, sizeof Qb);
    sw_rotate_frame(Qb, phi);
    sw_frame_log(out, Qa, Qb);
    sw_v3_sub(d, out, phi);
    worst = fmax(worst, sw_v3_norm(d) / th);
    if (th < thc) nseries++; else ntrig++;
  }
  /* and through the threshold of the exponential on the way */
  double worst_exp = 0;
  for (int k = -200; k <= 200; k++) {
    double th = 0.1 * (1.0 + 1e-15 * k), phi[3], Qb[9], out[3], d[3];
    sw_v3_scale(phi, u, th);
    memcpy(Qb, Qa, sizeof Qb);
    sw_rotate_frame(Qb, phi);
    sw_frame_log(out, Qa, Qb);
    sw_v3_sub(d, out, phi);
    worst_exp = fmax(worst_exp, sw_v3_norm(d) / th);
  }
  fprintf(stderr,
          "# %s: worst relative error within 2e-13 of theta = asin(0.25): %.3e (%d series, %d "
          "atan2 samples); of theta = 0.1: %.3e (tol 4e-15)\n",
          __func__, worst, nseries, ntrig, worst_exp);
  assert_true(nseries > 0 && ntrig > 0);
  assert_true(worst < 4e-15);
  assert_true(worst_exp < 4e-15);
}

/* beta of the inverse Jacobian (sw_dexpinv_beta): its series over the
 * range the rod pass's vector loop gives it (theta^2 up to 0.064 there, up
 * to SW_BETA_SERIES_TH2 here) against the same series taken to ten terms
 * in long double from the Bernoulli numbers, sum_n (-1)^(n+1) B_2n
 * theta^(2n-2) / (2n)! (the closed form cannot serve: its cancellation of
 * 1/theta^2 against 1/12 costs more than the difference measured), and
 * against the closed form where that is exact enough (theta^2 >= 0.05):
 * within 1e-15 relative. */
static void test_dexpinv_beta_series(void **state) {
  (void)state;
  static const long double bern[10][2] = {{1, 6}, {-1, 30}, {1, 42}, {-1, 30}, {5, 66},
                                          {-691, 2730}, {7, 6}, {-3617, 510}, {43867, 798},
                                          {-174611, 330}}; /* B_2 .. B_20 */
  double worst = 0, worst_closed = 0;
  for (int k = 0; k < 2000; k++) { /* the series' side: theta^2 < SW_BETA_SERIES_TH2 */
    const double th2 = SW_BETA_SERIES_TH2 * k / 2000.0;
    long double sum = 0, fact = 1, pw = 1;
    for (int n = 1; n <= 10; n++) {
      fact *= (2.0L * n - 1) * (2.0L * n); /* (2n)! */
      sum += (n % 2 ? 1 : -1) * bern[n - 1][0] / bern[n - 1][1] * pw / fact;
      pw *= th2;
    }
    worst = fmax(worst, (double)(fabsl((long double)sw_dexpinv_beta(th2) - sum) / sum));
    if (th2 >= 0.05) {
      const double th = sqrt(th2);
      const double closed = 1.0 / th2 - cos(0.5 * th) / (2.0 * th * sin(0.5 * th));
      worst_closed = fmax(worst_closed, fabs(sw_dexpinv_beta(th2) - closed) / closed);
    }
  }
  fprintf(stderr, "# %s: theta^2 in [0, %g]: largest relative difference from the ten-term "
          "series %.3e (tol 1e-15), from the closed form above 0.05 %.3e (tol 1e-13)\n",
          __func__, SW_BETA_SERIES_TH2, worst, worst_closed);
  assert_true(worst < 1e-15);
  assert_true(worst_closed < 1e-13);
}

/* ---- sw_frame_from ---- */

/* Well-conditioned input: the normal at least 30 degrees off the direction
 * (tolerance 2e-15: see the next test for how it degrades below that). */
static void test_frame_from(void **state) {
  (void)state;
  double worst = 0;
  for (int t = 0; t < 1000; t++) {
    double dir[3], nrm[3], Q[9] = {0}, d2[3], u[3];
    do {
      for (int k = 0; k < 3; k++) { dir[k] = 10 * srand_sym(); nrm[k] = srand_sym(); }
      sw_v3_cross(d2, dir, nrm);
    } while (sw_v3_norm(d2) < 0.5 * sw_v3_norm(dir) * sw_v3_norm(nrm));
    assert_int_equal(sw_frame_from(Q, dir, nrm), 1);
    worst = fmax(worst, orth_error(Q));
    worst = fmax(worst, fabs(det3(Q) - 1.0));
    /* d1 x d2 = d3 */
    sw_v3_cross(d2, Q, Q + 3);
    worst = fmax(worst, v3_maxdiff(d2, Q + 6));
    /* d3 along dir, d1 in the (dir, normal) plane on the side of normal */
    sw_v3_scale(u, dir, 1.0 / sw_v3_norm(dir));
    worst = fmax(worst, v3_maxdiff(Q + 6, u));
    assert_true(sw_v3_dot(Q, nrm) > 0);
    worst = fmax(worst, fabs(sw_v3_dot(Q + 3, nrm)) / sw_v3_norm(nrm));
  }
  fprintf(stderr, "# %s: worst orthonormality/handedness/alignment error %.3e (tol 2e-15)\n",
          __func__, worst);
  assert_true(worst < 2e-15);

  /* a hand-checked frame: d3 = z, d1 = x gives d2 = y */
  double Q[9];
  const double z[3] = {0, 0, 2}, xz[3] = {3, 0, 5};
  assert_int_equal(sw_frame_from(Q, z, xz), 1);
  const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int k = 0; k < 9; k++) assert_true(Q[k] == I[k]);

  /* degenerate input is rejected */
  const double zero[3] = {0, 0, 0}, dir[3] = {1, 2, 3}, par[3] = {-2, -4, -6};
  const double nan3[3] = {NAN, 0, 1};
  assert_int_equal(sw_frame_from(Q, zero, xz), 0);
  assert_int_equal(sw_frame_from(Q, dir, dir), 0);
  assert_int_equal(sw_frame_from(Q, dir, par), 0);
  assert_int_equal(sw_frame_from(Q, dir, zero), 0);
  assert_int_equal(sw_frame_from(Q, nan3, xz), 0);
  assert_int_equal(sw_frame_from(Q, dir, nan3), 0);
}

/* Ill-conditioned but accepted input: the normal a small angle alpha off the
 * direction (sw_frame_from accepts alpha down to about 1e-12).  The frame it
 * returns must still be orthonormal to round-off; one Gram-Schmidt
 * projection leaves d1 . d3 of order eps / alpha, so this needs a second
 * projection or d1 built as d2 x d3. */
static void test_frame_from_nearly_parallel(void **state) {
  (void)state;
  const double dir[3] = {1, 2, 3}, perp[3] = {3, 0, -1};
  double worst = 0, worst_alpha = 0;
  for (double alpha = 1e-1; alpha > 5e-12; alpha /= 10) {
    double nrm[3], Q[9] = {0};
    for (int k = 0; k < 3; k++) nrm[k] = dir[k] / sqrt(14.0) + alpha * perp[k] / sqrt(10.0);
    assert_int_equal(sw_frame_from(Q, dir, nrm), 1);
    double e = orth_error(Q);
    fprintf(stderr, "# %s: alpha = %.0e: ||Q Q^T - I||_F = %.3e, d1 . d3 = %.3e\n", __func__,
            alpha, e, sw_v3_dot(Q, Q + 6));
    if (e > worst) { worst = e; worst_alpha = alpha; }
  }
  fprintf(stderr, "# %s: worst ||Q Q^T - I||_F = %.3e at alpha = %.0e (tol 2e-15)\n", __func__,
          worst, worst_alpha);
  assert_true(worst < 2e-15);
}

/* sw_max(x, bound) and sw_min(x, bound), which stand for fmax and fmin in the loops
 * GCC 12.2 for Arm cannot vectorize with them (vec.h): the same bound as
 * fmax and fmin over runs of values with NaNs and infinities among them
 * (a NaN passed over), in a loop of two reductions as in contact.c. */
static void test_run_bounds(void **state) {
  (void)state;
  double x[64];
  for (int k = 0; k < 64; k++) x[k] = 200 * urand() - 100;
  x[5] = NAN, x[17] = INFINITY, x[40] = -INFINITY, x[41] = NAN, x[63] = NAN;
  for (int start = 0; start < 64; start += 7) {
    double a = 0, b = 0, c = INFINITY, e = INFINITY, widest = 0, w2 = 0, ref_w = 0, ref_w2 = 0;
    for (int k = start; k < 64; k++) {
      a = fmax(a, x[k]), b = sw_max(x[k], b);
      c = fmin(c, x[k]), e = sw_min(x[k], e);
      widest = sw_max(fabs(x[k]), widest), w2 = sw_max(x[k] * x[k], w2);
      ref_w = fmax(ref_w, fabs(x[k])), ref_w2 = fmax(ref_w2, x[k] * x[k]);
    }
    assert_true(a == b && c == e);
    assert_true(widest == ref_w && w2 == ref_w2);
    assert_false(isnan(b) || isnan(e) || isnan(widest) || isnan(w2));
  }
  assert_true(sw_max(NAN, 1.0) == 1.0 && sw_min(NAN, 1.0) == 1.0);
  assert_true(sw_max(-5.0, -INFINITY) == -5.0 && sw_min(5.0, INFINITY) == 5.0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_v3_basics),
      cmocka_unit_test(test_cross_identities),
      cmocka_unit_test(test_mat_vec_inverse),
      cmocka_unit_test(test_rotate_frame_stays_orthonormal),
      cmocka_unit_test(test_rotate_frame_against_exp),
      cmocka_unit_test(test_rodrigues_coeffs),
      cmocka_unit_test(test_frame_log_sign_convention),
      cmocka_unit_test(test_frame_log_inverts_rotation),
      cmocka_unit_test(test_frame_log_continuity),
      cmocka_unit_test(test_dexpinv_beta_series),
      cmocka_unit_test(test_frame_from),
      cmocka_unit_test(test_frame_from_nearly_parallel),
      cmocka_unit_test(test_run_bounds),
  };
  return cmocka_run_group_tests_name("vec", tests, NULL, NULL);
}
