/* test_twist.c — Greenhill's critical twist of a rod clamped at both ends
 * (the reference and the measurement: twist_rod.h). */
#include "twist_rod.h"

static const FarEnd CLAMPED = {FAR_CLAMPED, 0};

/* Greenhill's critical twist at 25, 50 and 100 elements. */
static void test_greenhill(void **state) {
  (void)state;
  const double ref = greenhill_twist();
  const int ns[3] = {25, 50, 100};
  const int nres = sw_test_sanitized() ? 1 : 3;
  double ratio[3];
  fprintf(stderr, "# %s: reference Phi_c = 2 x (root of tan x = x) x (1 + nu) = %.9f rad "
          "(M_c L / B = %.6f = %.4f pi)\n", __func__, ref, 2 * tan_root(), 2 * tan_root() / M_PI);
  for (int k = 0; k < nres; k++) {
    ratio[k] = critical_twist(ns[k], ref, 1.02, CLAMPED) / ref;
    fprintf(stderr, "# %s: n = %d: Phi_c(sinew) / Phi_c(Greenhill) = %.5f\n", __func__, ns[k],
            ratio[k]);
    assert_true(fabs(ratio[k] - 1) < 0.02);
  }
  if (nres == 3) {
    const double order = log2(fabs(ratio[0] - ratio[1]) / fabs(ratio[1] - ratio[2]));
    fprintf(stderr, "# %s: differences of the ratio %.2e, %.2e: observed order %.2f\n", __func__,
            ratio[0] - ratio[1], ratio[1] - ratio[2], order);
    assert_true(order > 1.5 && order < 3);
    SW_EXPECT_REL("ratio at n = 100", ratio[2], 1.0, 1e-3);
  }
}


int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_greenhill),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
