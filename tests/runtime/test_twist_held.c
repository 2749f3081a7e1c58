/* test_twist_held.c — Greenhill's critical twist of a rod clamped at its
 * start, its far end sliding along the axis under a dead axial force with
 * its frame held, the twist prescribed (the reference and the measurement:
 * twist_rod.h). */
#include "twist_rod.h"

/* A sleeve at the far end under a dead axial force, compressive (half of
 * Euler's clamped load P_E = 4 pi^2 B / L^2) and tensile (P_E): the critical
 * twist at 50 and 100 elements against the clamped-clamped condition with
 * P.  Unlike the twist alone (test_greenhill, where the rod's length drops
 * out of Phi_c = M_c L / C), the force's share P L^2 / B depends on where
 * the discrete clamps sit, within an element of the ends: the error is of
 * first order, and the extrapolation 2 r(100) - r(50) is checked (the
 * sanitized build: tension at 50 elements only). */
static void test_greenhill_sleeve(void **state) {
  (void)state;
  const double bend = YOUNGS * M_PI * pow(RADIUS, 4) / 4, euler = 4 * M_PI * M_PI * bend / (LEN * LEN);
  const double share[2] = {-1.0, 0.5};
  const int ns[2] = {50, 100};
  const int nload = sw_test_sanitized() ? 1 : 2, nres = sw_test_sanitized() ? 1 : 2;
  /* the condition's own limit at P -> 0: tan x = x */
  SW_EXPECT_REL("M_c L / B as P -> 0", greenhill_moment(1e-9), 2 * tan_root(), 1e-6);
  for (int j = 0; j < nload; j++) {
    const double p = share[j] * euler * LEN * LEN / bend, mc = greenhill_moment(p);
    const double ref = mc * (1 + POISSON);
    const FarEnd far = {FAR_HELD, share[j] * euler};
    fprintf(stderr, "# %s: P = %+.2f x 4 pi^2 B / L^2 = %+.6f N: M_c L / B = %.6f, Phi_c = %.6f rad\n",
            __func__, share[j], far.load, mc, ref);
    double ratio[2];
    for (int k = 0; k < nres; k++) {
      ratio[k] = critical_twist(ns[k], ref, 1.04, far) / ref;
      fprintf(stderr, "# %s: P = %+.2f P_E, n = %d: Phi_c(sinew) / Phi_c(Greenhill) = %.5f\n", __func__,
              share[j], ns[k], ratio[k]);
      assert_true(fabs(ratio[k] - 1) < 0.02);
    }
    if (nres == 2) {
      const double rich = 2 * ratio[1] - ratio[0];
      fprintf(stderr, "# %s: P = %+.2f P_E: error ratio (n = 50 / n = 100) %.2f, extrapolated ratio %.5f\n",
              __func__, share[j], (ratio[0] - 1) / (ratio[1] - 1), rich);
      assert_true((ratio[0] - 1) / (ratio[1] - 1) > 1.6 && (ratio[0] - 1) / (ratio[1] - 1) < 2.6);
      SW_EXPECT_REL("extrapolated ratio", rich, 1.0, 1e-3);
    }
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_greenhill_sleeve),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
