/* test_signal_range.c — the range of a time signal (loads.c,
 * sw_signal_range), by which the compiler and the simulator warn of an
 * activation outside [0, 1].
 *
 * References are closed forms: a constant, a ramp's and a step's two values
 * (either order), a sine's mean -+ amplitude (and, at zero frequency, the
 * one value a + b sin(phase)), a table's extreme values, and, for the
 * B-spline, the uniform cubic B-spline basis function, whose peak is 2/3 at
 * the centre of its support (de Boor 1978): the coefficients (0,0,0,1,0,0,0)
 * on 4 uniform spans make exactly that function, so the range is [0, 2/3];
 * and (1,1,1,1,1) stays 1 (the basis sums to one).  A period changes none
 * of them. */
#include "testutil.h"

static void expect_range(const char *what, swSignal s, double lo, double hi, double tol) {
  double a, b;
  sw_signal_range(&s, &a, &b);
  printf("# %s: range [%.17g, %.17g], expected [%.17g, %.17g]\n", what, a, b, lo, hi);
  assert_true(fabs(a - lo) <= tol && fabs(b - hi) <= tol);
}

static void test_closed_forms(void **state) {
  (void)state;
  expect_range("const 1.5", sw_signal_const(1.5), 1.5, 1.5, 0);
  expect_range("ramp 0.2 -> 1.5", sw_signal_ramp(0.2, 1.5, 0.1, 0.3), 0.2, 1.5, 0);
  expect_range("ramp 1 -> -0.25", sw_signal_ramp(1, -0.25, 0, 1), -0.25, 1, 0);
  expect_range("step 0.3 -> 0.9", sw_signal_step(0.3, 0.9, 0.5), 0.3, 0.9, 0);
  expect_range("sine 0.5 +- 0.7", sw_signal_sine(0.5, 0.7, 2, 0.3, 0), -0.2, 1.2, 1e-15);
  expect_range("sine 0.5 -+ 0.7 (negative amplitude)", sw_signal_sine(0.5, -0.7, 2, 0, 0), -0.2,
               1.2, 1e-15);
  expect_range("sine at 0 Hz", sw_signal_sine(0.5, 0.7, 0, 0.3, 0), 0.5 + 0.7 * sin(0.3),
               0.5 + 0.7 * sin(0.3), 0);
  expect_range("periodic ramp", sw_signal_periodic(sw_signal_ramp(0, 1.25, 0, 0.1), 0.2), 0, 1.25,
               0);
  swSignal table = sw_signal_const(0);
  table.kind = SW_SIG_TABLE;
  table.npts = 4;
  const double tt[] = {0, 0.1, 0.2, 0.3}, tv[] = {0.1, 1.4, -0.3, 0.5};
  for (int k = 0; k < 4; k++) { table.times[k] = tt[k]; table.values[k] = tv[k]; }
  expect_range("table", table, -0.3, 1.4, 0);
}

static void test_bspline(void **state) {
  (void)state;
  const double bump[] = {0, 0, 0, 1, 0, 0, 0}, one[] = {1, 1, 1, 1, 1};
  expect_range("B-spline, the uniform cubic basis function", sw_signal_bspline(bump, 7, 0, 1), 0,
               2.0 / 3.0, 1e-14);
  expect_range("B-spline of equal coefficients", sw_signal_bspline(one, 5, 0, 1), 1, 1, 1e-14);
  const double scaled[] = {0, 0, 0, 1.8, 0, 0, 0};  /* peaks at 1.2: over 1 */
  expect_range("B-spline scaled by 1.8", sw_signal_bspline(scaled, 7, 0.2, 0.5), 0, 1.2, 1e-14);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_closed_forms),
    cmocka_unit_test(test_bspline),
  };
  return cmocka_run_group_tests_name("signal_range", tests, NULL, NULL);
}
