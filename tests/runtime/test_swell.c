/* test_swell.c — rods whose geometry changes in time (swell.c) against the
 * closed forms of a circular section and of a helix.
 *
 * A straight rod whose radius follows r(t) = r0 (1 + t / 1 s): at several
 * times its bending stiffness must be E pi r^4 / 4, its twist stiffness
 * G pi r^4 / 2, its axial stiffness E pi r^2, its total mass rho0 pi r0^2 L
 * to round-off when conserved (and rho0 pi r^2 L when the density is
 * fixed), its rotational inertia rho pi r^4 / 4 per length with the density
 * of that mode.
 *
 * A free helical filament (Zhang et al. 2019, Table 3's coil: helix radius
 * 10 mm, 9 turns on a 0.425 m core) whose filament radius grows by half with
 * its rest twist tied to it, k3 ~ r0 / r (the reference's code, mattialab/
 * elastica source/Polymer.cpp; Charles, Gazzola & Mahadevan, PRL 2019):
 * growing slowly under damping, it must release twist and contract, and
 * settle where a rod of rest curvature kappa and rest twist tau' = tau / g
 * rests, the helix of radius kappa / (kappa^2 + tau'^2) and rise
 * tau' / (kappa^2 + tau'^2) per radian, whose end-to-end length over the arc
 * length L is sqrt((c theta)^2 + (2 R sin(theta / 2))^2), theta =
 * L sqrt(kappa^2 + tau'^2).  Also against the discrete rod's own rest shape
 * (its rest rotations composed), which the continuum form approximates to
 * second order in the element length.
 *
 * The stable step of a rod thickening to twice its radius (mass conserved,
 * twist hardened 1e4 times so the twist waves bound the step, w ~ g) must be
 * half the estimate at t = 0; the rod run at the t = 0 estimate must be
 * declared unstable, and at its own estimate it must not. */
#include "testutil.h"
#include "internal.h"
#include "vec.h"

static swRodDesc straight_rod(double r0, double grow_by, double over) {
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "fibre";
  r.nelem = 10;
  r.length = 0.5;
  r.radius_start = r.radius_end = r0;
  r.density = 1200;
  r.youngs = 2e6;
  r.poisson = 0.5;
  r.swell = 1;
  r.swell_radius = sw_signal_ramp(r0, r0 * (1 + grow_by), 0.0, over);
  return r;
}

static void test_stiffness_and_mass(void **state) {
  (void)state;
  const double r0 = 0.004, E = 2e6, G = E / 3, rho0 = 1200, L = 0.5;
  for (int grows = 0; grows <= 1; grows++) {
    swSpec *s = sw_spec_new();
    swRodDesc r = straight_rod(r0, 1.0, 1.0);
    r.swell_mass_grows = grows;
    sw_spec_add_rod(s, &r);
    swModel *m = sw_test_compile(s);
    swData *d = sw_data_new(m);
    double worst_B = 0, worst_S = 0, worst_J = 0, worst_M = 0;
    const double times[] = {0.0, 0.25, 0.6, 1.0, 2.0};
    for (size_t q = 0; q < sizeof times / sizeof *times; q++) {
      sw_swell_update(m, d, times[q]);
      const double rt = r0 * (1 + fmin(times[q], 1.0)), A = M_PI * rt * rt, I = A * rt * rt / 4;
      const double rho = grows ? rho0 : rho0 * (r0 / rt) * (r0 / rt);
      const int v = m->vor_adr[0] + 4, e = m->elem_adr[0] + 4;
      worst_B = fmax(worst_B, fabs(SW_AT(m, d->bend_now, v, 0) / (E * I) - 1));
      worst_B = fmax(worst_B, fabs(SW_AT(m, d->bend_now, v, 2) / (G * 2 * I) - 1));
      worst_S = fmax(worst_S, fabs(SW_AT(m, d->shear_now, e, 2) / (E * A) - 1));
      worst_S = fmax(worst_S, fabs(SW_AT(m, d->shear_now, e, 0) / (4.0 / 3.0 * G * A) - 1));
      worst_J = fmax(worst_J, fabs(SW_AT(m, d->inertia_now, e, 0) / (rho * m->rest_len[e] * I) - 1));
      double M = 0;
      for (int i = 0; i <= r.nelem; i++) M += d->mass_now[m->node_adr[0] + i];
      const double M_ref = grows ? rho0 * A * L : rho0 * M_PI * r0 * r0 * L;
      worst_M = fmax(worst_M, fabs(M / M_ref - 1));
      assert_true(fabs(d->radius_now[e] / rt - 1) < 1e-14);
    }
    printf("# swell (%s): worst relative error over t = 0..2 s: B %.1e, S %.1e, J^ %.1e, "
           "mass %.1e\n", grows ? "density fixed" : "mass conserved", worst_B, worst_S, worst_J,
           worst_M);
    assert_true(worst_B < 1e-13 && worst_S < 1e-13 && worst_J < 1e-13);
    assert_true(worst_M < 1e-14);   /* conserved to round-off, or grown exactly */
    sw_data_free(d);
    sw_model_free(m);
    sw_spec_free(s);
  }
}

/* ---- the free helical filament ---- */
static const double HR = 0.01, CORE = 0.425, TURNS = 9;   /* Zhang 2019, Table 3 */

/* End-to-end length of a helix of curvature k and torsion t over arc L. */
static double helix_span(double k, double t, double L) {
  const double q = k * k + t * t, R = k / q, c = t / q, th = L * sqrt(q);
  return sqrt(c * th * c * th + 4 * R * R * sin(th / 2) * sin(th / 2));
}

/* The discrete rod's own rest shape with rest curvature (k1, k2, w k3):
 * each frame the previous turned by exp(-[kappa D]) (rod.c's kappa =
 * log(Q_{j+1} Q_j^T) / D), each node the previous plus l^ d3. */
static double discrete_span(const swModel *m, double w) {
  const int n = m->rod_nelem[0], ea = m->elem_adr[0], va = m->vor_adr[0];
  double Q[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, x[3] = {0, 0, 0};
  for (int i = 0; i < n; i++) {
    for (int k = 0; k < 3; k++) x[k] += m->rest_len[ea + i] * Q[6 + k];
    if (i == n - 1) break;
    double phi[3];
    for (int k = 0; k < 3; k++) phi[k] = SW_AT(m, m->rest_kappa, va + i, k) * m->rest_vor_len[va + i];
    phi[2] *= w;
    sw_rotate_frame(Q, phi);
  }
  return sqrt(sw_v3_dot(x, x));
}

static double end_to_end(const swModel *m, const swData *d) {
  double a[3], b[3], dx[3];
  sw_get3(m, d->x, m->node_adr[0], a);
  sw_get3(m, d->x, m->node_adr[0] + m->rod_nelem[0], b);
  sw_v3_sub(dx, b, a);
  return sqrt(sw_v3_dot(dx, dx));
}

static double mean_twist(const swModel *m, const swData *d) {
  double t = 0;
  const int n = m->rod_nelem[0], va = m->vor_adr[0];
  for (int j = 0; j < n - 1; j++) t += SW_AT(m, d->kappa, va + j, 2);
  return t / (n - 1);
}

static void test_helix_releases_twist(void **state) {
  (void)state;
  const int n = 108;                       /* 12 elements a turn, as the reference's code */
  const double pitch = CORE / TURNS, c = pitch / (2 * M_PI);
  const double L = 2 * M_PI * TURNS * sqrt(HR * HR + c * c);
  const double a0 = 0.002, g_end = 1.5, t_grow = 2.0, t_end = sw_test_sanitized() ? 4.0 : 8.0;
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "coil";
  r.nelem = n;
  r.length = L;
  r.radius_start = r.radius_end = a0;
  r.density = 1670;
  r.youngs = 1e6;
  r.poisson = 0.5;
  r.damping = SW_DAMP_LINEAR;
  r.gamma = 0.15;                          /* about critical for the coil's slowest mode */
  r.swell = 1;
  r.swell_radius = sw_signal_ramp(a0, g_end * a0, 0.0, t_grow);
  r.swell_twist_radius = 1;
  int id = sw_spec_add_rod(s, &r);
  double *x = malloc(sizeof(double) * 3 * (n + 1)), *Q = malloc(sizeof(double) * 9 * n);
  const double start[3] = {0, 0, 0}, axis[3] = {0, 0, 1}, normal[3] = {1, 0, 0};
  char err[200];
  assert_int_equal(sw_shape_helix(n, HR, pitch, L, 1, start, axis, normal, x, Q, err, sizeof err), SW_OK);
  assert_int_equal(sw_spec_set_rest_shape(s, id, x, Q), SW_OK);
  free(x);
  free(Q);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);
  const double span0 = end_to_end(m, d), twist0 = mean_twist(m, d);
  double half = 0;
  while (d->time < t_end - 0.5 * m->dt) {
    assert_int_equal(sw_step(m, d), SW_OK);
    if (half == 0 && d->time >= 0.5 * t_grow) half = end_to_end(m, d);
  }
  sw_internal_loads(m, d);
  const double span = end_to_end(m, d), twist = mean_twist(m, d);
  /* the rest curvature the model computed from the helix's frames */
  const int v = m->vor_adr[0] + n / 2;
  const double k = hypot(SW_AT(m, m->rest_kappa, v, 0), SW_AT(m, m->rest_kappa, v, 1));
  const double tau = SW_AT(m, m->rest_kappa, v, 2);
  const double closed = helix_span(k, tau / g_end, L), discrete = discrete_span(m, 1 / g_end);
  printf("# free coil, filament radius x%.1f over %.0f s (k3 ~ r0/r): end-to-end %.4f -> %.4f m "
         "(%.4f halfway), mean twist %.2f -> %.2f rad/m (tau / g = %.2f); at rest: discrete rod "
         "%.4f m (error %.1e), helix kappa = %.2f, tau' = %.2f: %.4f m (error %.1e), dt %.2e s\n",
         g_end, t_grow, span0, span, half, twist0, twist, tau / g_end, discrete,
         fabs(span / discrete - 1), k, tau / g_end, closed, fabs(span / closed - 1), m->dt);
  assert_true(span < span0 && half < span0 && span < half);   /* contracts as it grows */
  assert_true(twist < twist0);                               /* twist released */
  assert_true(fabs(twist / (tau / g_end) - 1) < 0.02);
  assert_true(fabs(span / discrete - 1) < (sw_test_sanitized() ? 0.05 : 0.01));
  assert_true(fabs(span / closed - 1) < (sw_test_sanitized() ? 0.06 : 0.02));
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- the stable step ---- */
static swSpec *hardened_rod(int swell) {
  swSpec *s = sw_spec_new();
  swRodDesc r = straight_rod(0.005, 1.0, 0.05);
  r.swell = swell;
  r.nelem = 20;
  r.twist_hardening = 1e4;
  sw_spec_add_rod(s, &r);
  return s;
}

/* Steps to t from a small twisting kick; the status of the first failure. */
static int run_twisted(swSpec *s, double dt, double t, double *when) {
  sw_spec_set_dt(s, dt);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  for (int i = 0; i < m->rod_nelem[0]; i++) SW_AT(m, d->omega, m->elem_adr[0] + i, 2) = (i % 2 ? 1 : -1) * 1e-3;
  int st = SW_OK;
  while (st == SW_OK && d->time < t) st = sw_step(m, d);
  *when = d->time;
  sw_data_free(d);
  sw_model_free(m);
  return st;
}

static void test_stable_dt_follows_radius(void **state) {
  (void)state;
  swSpec *still = hardened_rod(0), *swelling = hardened_rod(1);
  swModel *m0 = sw_test_compile(still), *m1 = sw_test_compile(swelling);
  const double dt0 = sw_stable_dt(m0), dt1 = sw_stable_dt(m1);
  sw_model_free(m0);
  sw_model_free(m1);
  double when_old, when_new;
  const int old = run_twisted(swelling, dt0, 0.1, &when_old);
  const int fine = run_twisted(swelling, dt1, 0.1, &when_new);
  printf("# radius x2 in 50 ms, mass conserved, twist hardened 1e4: stable dt %.3e s at t = 0, "
         "%.3e s over the run (ratio %.4f, closed form 1/2); at the t = 0 estimate: %s at "
         "t = %.1f ms (radius x%.2f); at the run's: %s to %.0f ms\n",
         dt0, dt1, dt1 / dt0, old == SW_EUNSTABLE ? "unstable" : "stable", 1e3 * when_old,
         1 + fmin(when_old / 0.05, 1.0), fine == SW_OK ? "stable" : "unstable", 1e3 * when_new);
  assert_true(fabs(dt1 / dt0 - 0.5) < 0.01);
  assert_int_equal(old, SW_EUNSTABLE);
  assert_int_equal(fine, SW_OK);
  sw_spec_free(still);
  sw_spec_free(swelling);
}

/* ---- an implicit rod that swells ---- */
/* A cantilever sagging under gravity while its radius grows by half (mass
 * conserved: the weight stays, E I grows as g^4, so the sag falls to
 * 1 / g^4 of its value), damped: implicit under imex at 20 times the
 * explicit estimate, against the explicit rod at its own; the implicit rod
 * never keeps a factorisation. */
static double sag_run(int implicit, double *fresh, double *kept) {
  swSpec *s = sw_spec_new();
  swRodDesc r = straight_rod(0.004, 0.5, 0.2);
  r.nelem = 20;
  r.youngs = 2e8;
  r.damping = SW_DAMP_LINEAR;
  r.gamma = 0.5;
  r.implicit = implicit;
  r.direction[0] = 1, r.direction[1] = 0, r.direction[2] = 0;   /* horizontal */
  r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
  int id = sw_spec_add_rod(s, &r);
  swBCDesc c = sw_test_clamp(id, 0);
  sw_spec_add_bc(s, &c);
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  swModel *m0 = sw_test_compile(s);
  const double dt = sw_stable_dt_elastic(m0, 0);
  sw_model_free(m0);
  sw_spec_set_integrator(s, implicit ? SW_IMEX : SW_VERLET);
  sw_spec_set_dt(s, implicit ? 20 * dt : 0.9 * dt);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  sw_test_run_to(m, d, 0.6);
  double tip[3];
  sw_get3(m, d->x, m->node_adr[0] + m->rod_nelem[0], tip);
  if (fresh) sw_implicit_counts(m, d, fresh, kept);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return -tip[2];
}

static void test_implicit_swelling_rod(void **state) {
  (void)state;
  double fresh = 0, kept = 0;
  const double sag_explicit = sag_run(0, NULL, NULL), sag_implicit = sag_run(1, &fresh, &kept);
  printf("# cantilever, radius x1.5 in 0.2 s, at 0.6 s: tip sag %.6e m explicit, %.6e m implicit at "
         "20x the explicit step (difference %.1e of the sag); implicit kicks %.0f afresh, %.0f kept\n",
         sag_explicit, sag_implicit, fabs(sag_implicit / sag_explicit - 1), fresh, kept);
  /* the settled sag of the thickened cantilever, weight kept (mass
   * conserved): w L^4 / (8 E I), I = pi (1.5 r0)^4 / 4 (Euler-Bernoulli) */
  const double r1 = 1.5 * 0.004, w = 1200 * M_PI * 0.004 * 0.004 * 9.81;
  const double sag_closed = w * pow(0.5, 4) / (8 * 2e8 * M_PI * pow(r1, 4) / 4);
  printf("# its settled sag against w L^4 / (8 E I(1.5 r0)) = %.6e m: explicit %.1e, implicit %.1e\n",
         sag_closed, fabs(sag_explicit / sag_closed - 1), fabs(sag_implicit / sag_closed - 1));
  assert_true(fabs(sag_implicit / sag_explicit - 1) < 0.02);
  assert_true(fabs(sag_explicit / sag_closed - 1) < 0.03);
  assert_true(kept == 0 && fresh > 0);
}

static void test_bad_radius_signal(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  swRodDesc r = straight_rod(0.004, -1.5, 1.0);   /* reaches -2 mm */
  sw_spec_add_rod(s, &r);
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  printf("# %s\n", err);
  assert_null(m);
  assert_non_null(strstr(err, "rod 'fibre': its radius signal must stay > 0"));
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_stiffness_and_mass),
      cmocka_unit_test(test_helix_releases_twist),
      cmocka_unit_test(test_stable_dt_follows_radius),
      cmocka_unit_test(test_implicit_swelling_rod),
      cmocka_unit_test(test_bad_radius_signal),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
