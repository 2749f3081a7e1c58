/* twist_rod.h — the twisted rod of test_twist.c, test_twist_held.c and
 * test_twist_couple.c: Greenhill's critical twist of a rod clamped at both
 * ends, and of a rod whose far end slides along its axis under a dead axial
 * force, its twist prescribed (held) or left to a dead couple (a sleeve).
 *
 * Reference.  A straight, isotropic, inextensible and unshearable rod of
 * length L, bending stiffness B = E I and twist stiffness C = G J, carrying
 * an axial twisting moment M and an axial compressive force P (P < 0:
 * tension), has lateral deflections u = x + i y that obey, to first order
 * (Love, A Treatise on the Mathematical Theory of Elasticity, 4th ed. 1927,
 * sec. 270-272; Greenhill, Proc. Inst. Mech. Eng. 1883; van der Heijden &
 * Thompson, Nonlinear Dynamics 21:71, 2000, eq. 1)
 *
 *     B u'''' - i M u''' + P u'' = 0.
 *
 * Without P, u = a + b s + c s^2 + d exp(i mu s) with mu = M / B.  Clamped
 * ends, u = u' = 0 at s = 0 and s = L, leave a non-zero solution when
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
 * With P, u = a + b s + c exp(i k1 s) + d exp(i k2 s), k1,2 the roots of
 * B k^2 - M k - P = 0.  The same four clamped conditions (derived here; with
 * pinned ends the same equation gives Greenhill's M^2/(4 B^2) + P/B =
 * pi^2/L^2) leave a non-zero solution when, with t1,2 = k1,2 L / 2,
 *
 *     (t2 - t1) sin t1 sin t2 = t1 t2 sin(t2 - t1),
 *
 * which gives Euler's clamped load P = 4 pi^2 B / L^2 at M = 0 and
 * tan t1 = t1 at P = 0.  Two far ends meet these conditions, free to move
 * along the axis, where a dead force P pushes: held (test_twist_held.c),
 * its node on the axis (slide) and its frame still (angular_velocity 0),
 * the twist between the ends prescribed, so that M = C Phi / L is the
 * holds' reaction; or in a sleeve (test_twist_couple.c), its node on the
 * axis and its frame turning about the axis only, under a dead couple M
 * about it.  A finite-
 * difference eigenproblem for M at fixed P with u = u' = 0 at both ends (400
 * points; outside this test) gives the same roots to 1e-4: M_c L / B =
 * 5.8176 at P L^2 / B = 2 pi^2 and 14.3106 at -4 pi^2.
 */
#ifndef SW_TWIST_ROD_H
#define SW_TWIST_ROD_H
#include "testutil.h"
#include "internal.h"
#include "vec.h"

static const double LEN = 1.0, RADIUS = 0.005, YOUNGS = 1e6, DENSITY = 1000, POISSON = 0.5;

/* The first positive root of tan x = x (Newton on sin x - x cos x). */
static inline double tan_root(void) {
  double x = 4.5;
  for (int k = 0; k < 50; k++) x -= (sin(x) - x * cos(x)) / (x * sin(x));
  return x;
}

/* Greenhill's clamped-clamped critical twist angle, rad. */
static inline double greenhill_twist(void) { return 2 * tan_root() * (1 + POISSON); }

/* Clamped-clamped Greenhill with an axial force: M_c L / B at P L^2 / B = p
 * (> 0 compression), the first zero above the least M with real k1,2 of the
 * condition above divided by t2 (so that it holds at P = 0 too). */
static inline double greenhill_cond(double m, double p) {
  const double dd = sqrt(m * m + 4 * p), t1 = (m + dd) / 4, t2 = (m - dd) / 4;
  return (t2 - t1) * sin(t1) * (t2 != 0 ? sin(t2) / t2 : 1) - t1 * sin(t2 - t1);
}
static inline double greenhill_moment(double p) {
  double lo = sqrt(fmax(0, -4 * p)) + 1e-3, hi = lo;
  const double g0 = greenhill_cond(lo, p);
  while (greenhill_cond(hi, p) * g0 > 0 && hi < 100) lo = hi, hi += 0.01; /* scan, then bisect */
  for (int k = 0; k < 60; k++) {
    const double mid = 0.5 * (lo + hi);
    if (greenhill_cond(mid, p) * g0 > 0) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

/* The far end: clamped; or held (slide along z, frame held: angular_velocity
 * 0), the twist prescribed; or in a sleeve (SW_BC_SLEEVE: on the axis,
 * turning about it only) under the dead twisting couple M = C phi / L that
 * holds the twist phi; either under the dead axial force `load` (N, > 0
 * compression). */
enum { FAR_CLAMPED = 0, FAR_HELD = 1, FAR_SLEEVE = 2 };
typedef struct {
  int sleeve;
  double load;
} FarEnd;

/* A rod of n elements along z, clamped at its start, its far end as `far`,
 * its frames turned uniformly through phi from the first element to the
 * last; with a load it starts shortened by P / (E A), in equilibrium. */
static inline swModel *twisted_rod(int n, double phi, FarEnd far) {
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
  const double strain = far.load / (YOUNGS * M_PI * RADIUS * RADIUS);
  for (int i = 0; i <= n; i++) x[3 * i + 2] = LEN * (1 - strain) * i / n;
  for (int i = 0; i < n; i++) {
    /* in a sleeve the twist phi runs over the length L, from the clamp's
     * frame (half an element before element 0) to the rod's tip */
    const double a = far.sleeve == FAR_SLEEVE ? phi * (i + 0.5) / n : phi * i / (n - 1);
    const double c = cos(a), sn = sin(a);
    double *q = Q + 9 * i;
    q[0] = c, q[1] = sn, q[2] = 0;   /* d1 */
    q[3] = -sn, q[4] = c, q[5] = 0;  /* d2 */
    q[6] = 0, q[7] = 0, q[8] = 1;    /* d3 */
  }
  assert_int_equal(sw_spec_set_start_shape(s, id, x, Q), SW_OK);
  free(x);
  free(Q);
  for (int end = 0; end < (far.sleeve ? 1 : 2); end++) {
    swBCDesc b = {.kind = SW_BC_CLAMP, .rod = id, .end = end, .signal = sw_signal_const(1)};
    sw_spec_add_bc(s, &b);
  }
  if (far.sleeve == FAR_SLEEVE) {
    const double twist = YOUNGS / (2 * (1 + POISSON)) * M_PI * pow(RADIUS, 4) / 2; /* C = G J */
    swBCDesc sleeve = {.kind = SW_BC_SLEEVE, .rod = id, .end = 1, .vec = {0, 0, 1}, .signal = sw_signal_const(1)};
    swLoadDesc couple = {.kind = SW_LOAD_TORQUE, .rod = id, .index = -1, .vec = {0, 0, twist * phi / LEN},
                         .signal = sw_signal_const(1)};
    sw_spec_add_bc(s, &sleeve);
    sw_spec_add_load(s, &couple);
  }
  if (far.sleeve) {
    swBCDesc line = {.kind = SW_BC_SLIDE_LINE, .rod = id, .end = 1, .vec = {0, 0, 1}, .signal = sw_signal_const(1)};
    swBCDesc still = {.kind = SW_BC_OMEGA, .rod = id, .end = 1, .signal = sw_signal_const(1)};
    swLoadDesc push = {.kind = SW_LOAD_FORCE, .rod = id, .index = -1, .vec = {0, 0, -far.load},
                       .signal = sw_signal_const(1)};
    if (far.sleeve == FAR_HELD) sw_spec_add_bc(s, &line), sw_spec_add_bc(s, &still);
    sw_spec_add_load(s, &push);
  }
  swModel *m = sw_test_compile_at(s, 0.9);
  sw_spec_free(s);
  return m;
}

/* The largest lateral deflection of the rod, m. */
static inline double lateral(const swModel *m, const swData *d) {
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
static double growth_rate(int n, double phi, FarEnd far) {
  swModel *m = twisted_rod(n, phi, far);
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
 * through sigma^2 at the twists (lo, lo + 0.02, lo + 0.04) ref. */
static inline double critical_twist(int n, double ref, double lo, FarEnd far) {
  const double f[3] = {lo, lo + 0.02, lo + 0.04};
  double p[3], y[3];
  for (int k = 0; k < 3; k++) {
    p[k] = f[k] * ref;
    const double sg = growth_rate(n, p[k], far);
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

#endif
