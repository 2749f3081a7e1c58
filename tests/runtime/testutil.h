/* testutil.h — shared helpers for the runtime tests (cmocka, TAP output).
 *
 * Every physics test prints the figure it measured on stderr as
 *   # test_name: quantity = value (reference r, error e, tolerance t)
 * so the numbers appear in `make test` output next to pass/fail.  Tests
 * that take long shrink their sizes in the sanitizer build (compiled with
 * -fsanitize=address, which defines __SANITIZE_ADDRESS__), or when
 * SW_SANITIZED is set, so that the sanitizer build exercises the same code
 * in reasonable time.  (Until issue 31 nothing set SW_SANITIZED in `make
 * test`, and the sanitizer build ran every test at full size.) */
#ifndef SW_TESTUTIL_H
#define SW_TESTUTIL_H
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <cmocka.h>
#include "sinew.h"

static inline int sw_test_sanitized(void) {
#if defined(__SANITIZE_ADDRESS__)
  return 1;
#else
  const char *s = getenv("SW_SANITIZED");
  return s && *s && *s != '0';
#endif
}

/* Print a measured figure and assert it is within tolerance. */
#define SW_EXPECT_REL(what, measured, reference, tol)                              \
  do {                                                                            \
    double m_ = (measured), r_ = (reference), e_ = fabs(m_ - r_) / fabs(r_);      \
    fprintf(stderr, "# %s: %s = %.9g (reference %.9g, rel. error %.3e, tol %.1e)\n", \
            __func__, (what), m_, r_, e_, (double)(tol));                         \
    assert_true(e_ <= (tol));                                                     \
  } while (0)

#define SW_EXPECT_ABS(what, measured, reference, tol)                              \
  do {                                                                            \
    double m_ = (measured), r_ = (reference), e_ = fabs(m_ - r_);                 \
    fprintf(stderr, "# %s: %s = %.9g (reference %.9g, abs. error %.3e, tol %.1e)\n", \
            __func__, (what), m_, r_, e_, (double)(tol));                         \
    assert_true(e_ <= (tol));                                                     \
  } while (0)

static inline swModel *sw_test_compile(swSpec *s) {
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  if (!m) fprintf(stderr, "# compile failed: %s\n", err);
  assert_non_null(m);
  return m;
}
#endif

#ifndef SW_TESTUTIL_RUN
#define SW_TESTUTIL_RUN
/* Compile at a fraction of the scene's own stable time step estimate. */
static inline swModel *sw_test_compile_at(swSpec *s, double frac) {
  swModel *m0 = sw_test_compile(s);
  sw_spec_set_dt(s, frac * sw_stable_dt(m0));
  sw_model_free(m0);
  return sw_test_compile(s);
}

/* Advance until the simulated time reaches t (whole steps). */
static inline void sw_test_run_to(const swModel *m, swData *d, double t) {
  while (d->time < t - 0.5 * m->dt) assert_int_equal(sw_step(m, d), SW_OK);
}

/* Dynamic relaxation to static equilibrium: advance in chunks of `chunk`
 * seconds until the watched coordinate moves by less than rtol of its size
 * over a chunk (at most tmax seconds).  Returns the watched value. */
static inline double sw_test_relax(const swModel *m, swData *d, const double *watch,
                                   double chunk, double tmax, double rtol) {
  double prev = *watch;
  while (d->time < tmax) {
    sw_test_run_to(m, d, d->time + chunk);
    if (fabs(*watch - prev) <= rtol * fabs(*watch)) break;
    prev = *watch;
  }
  fprintf(stderr, "#   relaxed to t = %.3g s (%ld steps)\n", d->time, d->step);
  return *watch;
}

/* Measured order of convergence from errors at h, h/2, h/4, ... */
/* Whether `steps` steps from the state in d keep the energy finite and
 * below 1000 times its start (the stable-step bisections' test of a run);
 * frees d and m. */
static inline int sw_test_stays_bounded(swModel *m, swData *d, int steps) {
  double e[3];
  sw_energy(m, d, e);
  const double e0 = e[0] + e[1];
  int ok = 1;
  for (int k = 0; k < steps && ok; k++) ok = sw_step(m, d) == SW_OK;
  if (ok) {
    sw_energy(m, d, e);
    ok = isfinite(e[0] + e[1]) && e[0] + e[1] < 1e3 * e0;
  }
  sw_data_free(d);
  sw_model_free(m);
  return ok;
}

static inline double sw_test_order(const double *err, int k) {
  return log(fabs(err[k]) / fabs(err[k + 1])) / log(2.0);
}

static inline swBCDesc sw_test_clamp(int rod, int end) {
  swBCDesc b;
  memset(&b, 0, sizeof b);
  b.kind = SW_BC_CLAMP;
  b.rod = rod;
  b.end = end;
  b.signal = sw_signal_const(1.0);
  return b;
}

/* A rod of n elements from start along dir (length, radius), its normal
 * `normal`, or when that is NULL y (z when dir is within 26 deg of y);
 * material and the rest as sw_rod_desc_init leaves them. */
static inline swRodDesc sw_test_rod(const char *name, int n, double length, double radius,
                                    const double start[3], const double dir[3],
                                    const double normal[3]) {
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = name;
  r.nelem = n;
  r.length = length;
  r.radius_start = r.radius_end = radius;
  const double along_y = fabs(dir[1]) > 0.9 * sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  const double nrm[3] = {0, along_y ? 0 : 1, along_y ? 1 : 0};
  for (int k = 0; k < 3; k++) {
    r.start[k] = start[k], r.direction[k] = dir[k];
    r.normal[k] = normal ? normal[k] : nrm[k];
  }
  return r;
}

/* Linear and angular momentum (about the origin) of every rod: the nodes'
 * m v and x x m v, and the elements' spins Q^T J w / e (e the dilatation,
 * as the kick has it; Q's rows are the directors). */
static inline void sw_test_momenta(const swModel *m, const swData *d, double P[3], double L[3]) {
  P[0] = P[1] = P[2] = L[0] = L[1] = L[2] = 0;
  for (int r = 0; r < m->nrod; r++) {
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
      double x[3], v[3];
      sw_get3(m, d->x, i, x);
      sw_get3(m, d->v, i, v);
      const double xv[3] = {x[1] * v[2] - x[2] * v[1], x[2] * v[0] - x[0] * v[2], x[0] * v[1] - x[1] * v[0]};
      for (int k = 0; k < 3; k++) P[k] += m->mass[i] * v[k], L[k] += m->mass[i] * xv[k];
    }
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) {
      double Q[9], w[3], Jw[3];
      sw_getQ(m, d->Q, e, Q);
      sw_get3(m, d->omega, e, w);
      for (int k = 0; k < 3; k++) Jw[k] = SW_AT(m, m->inertia, e, k) * w[k] / d->dilatation[e];
      for (int k = 0; k < 3; k++) L[k] += Q[k] * Jw[0] + Q[3 + k] * Jw[1] + Q[6 + k] * Jw[2];
    }
  }
}

/* A slope for a rod to lie on: a box obstacle 1 cm thick whose top face
 * passes through the origin with outward normal n (in the x-z plane), its
 * axis along y; half_a is its half size along y x n (down the slope), half_y
 * along y.  Stiffness, damping and friction are the caller's. */
static inline swObstacleDesc sw_test_slope(const double n[3], double half_a, double half_y) {
  swObstacleDesc o;
  sw_obstacle_desc_init(&o);
  o.name = "slope";
  o.shape = SW_OBSTACLE_BOX;
  for (int k = 0; k < 3; k++) o.normal[k] = n[k], o.centre[k] = -0.01 * n[k];
  o.axis[0] = 0, o.axis[1] = 1, o.axis[2] = 0; /* e2 = y x n: down the slope */
  o.half[0] = 0.01, o.half[1] = half_a, o.half[2] = half_y;
  return o;
}

/* A table signal through n (time, value) pairs (n <= SW_SIGNAL_MAXPTS). */
static inline swSignal sw_test_table(int n, const double *t, const double *v) {
  swSignal g = sw_signal_const(1.0);
  g.kind = SW_SIG_TABLE;
  g.npts = n;
  for (int k = 0; k < n; k++) g.times[k] = t[k], g.values[k] = v[k];
  return g;
}

static inline swLoadDesc sw_test_load(swLoadKind kind, int rod, int index, double x, double y, double z) {
  swLoadDesc l;
  memset(&l, 0, sizeof l);
  l.kind = kind;
  l.rod = rod;
  l.index = index;
  l.vec[0] = x; l.vec[1] = y; l.vec[2] = z;
  l.signal = sw_signal_const(1.0);
  return l;
}
#endif
