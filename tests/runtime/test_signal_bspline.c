/* test_signal_bspline.c — B-spline and periodic time signals (loads.c).
 *
 * The B-spline signal is evaluated by de Boor's algorithm on the uniform
 * clamped knot vector, without allocation; the independent reference is
 * GSL's gsl_bspline (order 4, uniform breakpoints) with the same
 * coefficients, compared at many times to 1e-12 of the largest coefficient.
 * Clamping: the end values are the first and last coefficients, and the
 * signal is constant outside [t0, t0 + T].  Periodic signals repeat from t0
 * on (a sawtooth from a periodic ramp, a periodic B-spline).  Bad signals
 * are refused by sw_compile with messages naming the load (exact text). */
#include <gsl/gsl_bspline.h>
#include <gsl/gsl_vector.h>

#include "testutil.h"

/* GSL's clamped cubic B-spline with coefficients c[0..n) over [a, b] at x. */
static double gsl_spline(const double *c, int n, double a, double b, double x) {
  gsl_bspline_workspace *w = gsl_bspline_alloc(4, (size_t)n - 2);
  gsl_vector *B = gsl_vector_alloc((size_t)n);
  gsl_bspline_knots_uniform(a, b, w);
  gsl_bspline_eval(x, B, w);
  double s = 0;
  for (int j = 0; j < n; j++) s += c[j] * gsl_vector_get(B, (size_t)j);
  gsl_vector_free(B);
  gsl_bspline_free(w);
  return s;
}

static void test_bspline_matches_gsl(void **state) {
  (void)state;
  const int sizes[] = {4, 5, 6, 7, 12, 33, SW_SIGNAL_MAXPTS};
  const double t0 = 0.3, T = 1.7;
  double worst = 0;
  unsigned seed = 12345;
  for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
    const int n = sizes[k];
    double c[SW_SIGNAL_MAXPTS], cmax = 0;
    for (int j = 0; j < n; j++) {
      seed = seed * 1103515245u + 12345u;
      c[j] = ((seed >> 8) % 20001) / 1000.0 - 10.0;
      if (fabs(c[j]) > cmax) cmax = fabs(c[j]);
    }
    swSignal s = sw_signal_bspline(c, n, t0, T);
    for (int i = 0; i <= 2000; i++) {
      const double t = t0 + T * i / 2000.0;
      const double err = fabs(sw_signal_eval(&s, t) - gsl_spline(c, n, t0, t0 + T, t)) / cmax;
      if (err > worst) worst = err;
    }
  }
  SW_EXPECT_ABS("max |de Boor - gsl| / max|c| over 7 sizes x 2001 times", worst, 0.0, 1e-12);
}

static void test_bspline_clamped_ends(void **state) {
  (void)state;
  const double c[6] = {0.5, 17.4, 48.5, 5.4, 14.7, -2.0};
  swSignal s = sw_signal_bspline(c, 6, 1.0, 2.0);
  SW_EXPECT_ABS("value at t0", sw_signal_eval(&s, 1.0), c[0], 1e-15);
  SW_EXPECT_ABS("value at t0 + T", sw_signal_eval(&s, 3.0), c[5], 1e-15);
  SW_EXPECT_ABS("value just after t0", sw_signal_eval(&s, 1.0 + 1e-12), c[0], 1e-9);
  SW_EXPECT_ABS("value just before t0 + T", sw_signal_eval(&s, 3.0 - 1e-12), c[5], 1e-9);
  assert_true(sw_signal_eval(&s, -5.0) == c[0]);
  assert_true(sw_signal_eval(&s, 99.0) == c[5]);
  /* constant coefficients give a constant (partition of unity) */
  const double one[9] = {2, 2, 2, 2, 2, 2, 2, 2, 2};
  swSignal u = sw_signal_bspline(one, 9, 0.0, 1.0);
  double worst = 0;
  for (int i = 0; i <= 1000; i++) worst = fmax(worst, fabs(sw_signal_eval(&u, i / 1000.0) - 2.0));
  SW_EXPECT_ABS("constant coefficients: max deviation from 2", worst, 0.0, 1e-14);
}

static void test_periodic_signals(void **state) {
  (void)state;
  /* a ramp 0 -> 1 over [0.5, 1.5], repeated every 1 s: a sawtooth */
  swSignal saw = sw_signal_periodic(sw_signal_ramp(0.0, 1.0, 0.5, 1.0), 1.0);
  double worst = 0;
  for (int i = 0; i < 1000; i++) {
    const double t = 0.5 + 7.0 * i / 1000.0 + 1e-7;
    const double phase = fmod(t - 0.5, 1.0);
    worst = fmax(worst, fabs(sw_signal_eval(&saw, t) - phase));
  }
  SW_EXPECT_ABS("periodic ramp vs sawtooth (7 periods)", worst, 0.0, 1e-12);
  assert_true(sw_signal_eval(&saw, 0.2) == 0.0); /* before t0: not repeated */
  /* a B-spline over [0, 0.8] repeated every 0.8 s */
  const double c[5] = {0, 1, -1, 2, 0};
  swSignal b = sw_signal_periodic(sw_signal_bspline(c, 5, 0.0, 0.8), 0.8);
  swSignal once = sw_signal_bspline(c, 5, 0.0, 0.8);
  worst = 0;
  for (int i = 0; i < 1000; i++) {
    const double u = 0.8 * i / 1000.0;
    for (int k = 1; k <= 5; k++)
      worst = fmax(worst, fabs(sw_signal_eval(&b, u + 0.8 * k) - sw_signal_eval(&once, u)));
  }
  SW_EXPECT_ABS("periodic B-spline vs one period (5 repeats)", worst, 0.0, 1e-12);
}

/* sw_compile's message for a rod with one load carrying signal g. */
static void expect_signal_error(swSignal g, const char *message) {
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "arm";
  r.nelem = 4;
  sw_spec_add_rod(s, &r);
  swLoadDesc l = sw_test_load(SW_LOAD_FORCE, 0, -1, 1, 0, 0);
  l.signal = g;
  sw_spec_add_load(s, &l);
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  assert_null(m);
  fprintf(stderr, "# error: %s\n", err);
  assert_string_equal(err, message);
  sw_spec_free(s);
}

static void test_signal_errors(void **state) {
  (void)state;
  const double c[4] = {0, 1, 2, 3};
  expect_signal_error(sw_signal_bspline(c, 3, 0, 1),
                      "load 0 on rod 'arm': B-spline signal needs 4..64 coefficients, has 3");
  expect_signal_error(sw_signal_bspline(c, 4, 0, 0),
                      "load 0 on rod 'arm': B-spline signal duration must be > 0");
  expect_signal_error(sw_signal_periodic(sw_signal_const(1), -1),
                      "load 0 on rod 'arm': signal period must be >= 0 (0: not periodic), got -1");
  swSignal bad = sw_signal_bspline(c, 4, 0, 1);
  bad.values[2] = NAN;
  expect_signal_error(bad, "load 0 on rod 'arm': B-spline coefficient 2 is not finite");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_bspline_matches_gsl),
    cmocka_unit_test(test_bspline_clamped_ends),
    cmocka_unit_test(test_periodic_signals),
    cmocka_unit_test(test_signal_errors),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
