/* test_twist.c — twist mechanics of the rod against the classical
 * stability theory: Greenhill's critical twist of a rod clamped at both
 * ends.
 *
 * Reference.  A straight, isotropic, inextensible and unshearable rod of
 * length L, bending stiffness B = E I and twist stiffness C = G J, carrying
 * an axial twisting moment M and no axial force, has lateral deflections
 * u = x + i y that obey, to first order (Love, A Treatise on the
 * Mathematical Theory of Elasticity, 4th ed. 1927, sec. 270-272; Greenhill,
 * Proc. Inst. Mech. Eng. 1883; van der Heijden & Thompson, Nonlinear
 * Dynamics 21:71, 2000, eq. 1 with the axial force zero)
 *
 *     B u'''' - i M u''' = 0,
 *
 * so u = a + b s + c s^2 + d exp(i mu s) with mu = M / B.  Clamped ends,
 * u = u' = 0 at s = 0 and s = L, leave a non-zero solution when
 *
 *     (e^{i theta} - 1) - (i theta / 2)(1 + e^{i theta}) = 0,  theta = M L / B,
 *
 * that is, multiplied by e^{-i theta/2}: tan(theta / 2) = theta / 2.  Its
 * first root, theta/2 = 4.4934..., gives the clamped-clamped critical moment
 * M_c L / B = 8.9868 = 2.861 pi (the pinned-pinned one is 2 pi).  The
 * critical twist angle between the ends is Phi_c = M_c L / C =
 * 8.9868 B / C; for a circular section, J = 2 I and G = E / (2 (1 + nu)),
 * Phi_c = 8.9868 (1 + nu).  The test finds the root of tan x = x by Newton
 * itself rather than quoting it.
 *
 * Measurement.  The straight twisted rod is an equilibrium at every twist;
 * past Phi_c its lowest lateral mode has a negative stiffness and grows as
 * exp(sigma t), with sigma^2 = -omega^2(Phi), a smooth function of the
 * twist that crosses zero at the rod's own critical twist.  Each run starts
 * the rod straight with its frames turned uniformly through Phi between
 * its clamped ends (sw_spec_set_start_shape; the clamps hold the start
 * frames, boundary.c), gives it a lateral velocity of 1e-10 m/s, and fits
 * sigma to the logarithm of the largest lateral deflection over its last
 * hundredfold growth, still far inside the linear range.  Three twists
 * above the reference (1.02, 1.04, 1.06 Phi_c) give three sigma^2; the
 * parabola through them crosses zero at the measured critical twist.
 * Slow twisting of one end (SW_BC_OMEGA) finds the same point only as the
 * twist at which a deflection first becomes visible, which lags the
 * bifurcation by the time the growth needs: this measures the bifurcation
 * itself.  The rod is slender (r / L = 0.005): its shear flexibility moves
 * the critical twist by about pi^2 (r/L)^2 E / (4/3 G) ~ 5e-4 of it.
 */
#include "testutil.h"
#include "internal.h"
#include "vec.h"

static const double LEN = 1.0, RADIUS = 0.005, YOUNGS = 1e6, DENSITY = 1000, POISSON = 0.5;

/* The first positive root of tan x = x (Newton on sin x - x cos x). */
static double tan_root(void) {
  double x = 4.5;
  for (int k = 0; k < 50; k++) x -= (sin(x) - x * cos(x)) / (x * sin(x));
  return x;
}

/* Greenhill's clamped-clamped critical twist angle, rad. */
static double greenhill_twist(void) { return 2 * tan_root() * (1 + POISSON); }

/* A rod of n elements along z, clamped at both ends, its frames turned
 * uniformly through phi from the first element to the last. */
static swModel *twisted_rod(int n, double phi) {
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "greenhill";
  r.nelem = n;
  r.length = LEN;
  r.radius_start = r.radius_end = RADIUS;
  r.youngs = YOUNGS;
  r.density = DENSITY;
  r.poisson = POISSON;
  int id = sw_spec_add_rod(s, &r);
  double *x = calloc(3 * (size_t)(n + 1), sizeof(double)), *Q = calloc(9 * (size_t)n, sizeof(double));
  for (int i = 0; i <= n; i++) x[3 * i + 2] = LEN * i / n;
  for (int i = 0; i < n; i++) {
    const double a = phi * i / (n - 1), c = cos(a), sn = sin(a);
    double *q = Q + 9 * i;
    q[0] = c, q[1] = sn, q[2] = 0;   /* d1 */
    q[3] = -sn, q[4] = c, q[5] = 0;  /* d2 */
    q[6] = 0, q[7] = 0, q[8] = 1;    /* d3 */
  }
  assert_int_equal(sw_spec_set_start_shape(s, id, x, Q), SW_OK);
  free(x);
  free(Q);
  for (int end = 0; end < 2; end++) {
    swBCDesc b = {.kind = SW_BC_CLAMP, .rod = id, .end = end, .signal = sw_signal_const(1)};
    sw_spec_add_bc(s, &b);
  }
  swModel *m = sw_test_compile_at(s, 0.9);
  sw_spec_free(s);
  return m;
}

/* The largest lateral deflection of the rod, m. */
static double lateral(const swModel *m, const swData *d) {
  double a = 0;
  for (int i = 0; i <= m->rod_nelem[0]; i++) {
    double x[3];
    sw_get3(m, d->x, m->node_adr[0] + i, x);
    a = fmax(a, hypot(x[0], x[1]));
  }
  return a;
}

/* The growth rate sigma (1/s) of the lateral deflection of the rod of n
 * elements twisted through phi; 0 if it did not grow a thousandfold. */
static double growth_rate(int n, double phi) {
  swModel *m = twisted_rod(n, phi);
  swData *d = sw_data_new(m);
  for (int i = 1; i < n; i++) /* a lateral nudge, zero at the clamps */
    SW_AT(m, d->v, m->node_adr[0] + i, 0) = 1e-10 * pow(sin(M_PI * i / n), 2);
  enum { MAXS = 4096 };
  static double ts[MAXS], la[MAXS];
  int ns = 0;
  const double every = 0.02, tmax = 200;
  while (d->time < tmax && ns < MAXS) {
    sw_test_run_to(m, d, d->time + every);
    ts[ns] = d->time;
    la[ns++] = log(lateral(m, d));
    if (la[ns - 1] > log(1e-5 * LEN)) break;
  }
  double sigma = 0;
  if (la[ns - 1] - la[0] > log(1e3)) { /* least squares over the last hundredfold */
    double st = 0, sl = 0, stt = 0, stl = 0;
    int k = 0;
    for (int j = ns - 1; j >= 0 && la[j] > la[ns - 1] - log(100); j--, k++) {
      st += ts[j], sl += la[j], stt += ts[j] * ts[j], stl += ts[j] * la[j];
    }
    sigma = (k * stl - st * sl) / (k * stt - st * st);
  }
  fprintf(stderr, "#   n = %d, Phi = %.5f rad: sigma = %.6f 1/s (t = %.2f s, %ld steps)\n", n, phi,
          sigma, d->time, d->step);
  sw_data_free(d);
  sw_model_free(m);
  return sigma;
}

/* The critical twist of the rod of n elements: the zero of the parabola
 * through sigma^2 at three twists above the reference. */
static double critical_twist(int n) {
  const double ref = greenhill_twist(), f[3] = {1.02, 1.04, 1.06};
  double p[3], y[3];
  for (int k = 0; k < 3; k++) {
    p[k] = f[k] * ref;
    const double sg = growth_rate(n, p[k]);
    y[k] = sg * sg;
  }
  /* Newton's divided differences: y = y0 + a (p - p0) + b (p - p0)(p - p1) */
  const double a = (y[1] - y[0]) / (p[1] - p[0]);
  const double b = ((y[2] - y[1]) / (p[2] - p[1]) - a) / (p[2] - p[0]);
  double z = p[0] - y[0] / a;  /* start from the chord, then Newton */
  for (int k = 0; k < 30; k++) {
    const double v = y[0] + a * (z - p[0]) + b * (z - p[0]) * (z - p[1]);
    const double dv = a + b * (2 * z - p[0] - p[1]);
    z -= v / dv;
  }
  return z;
}

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
    ratio[k] = critical_twist(ns[k]) / ref;
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
