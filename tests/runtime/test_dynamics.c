/* test_dynamics.c — dynamic validations: the first bending eigenfrequency of
 * a clamped-free rod against Euler-Bernoulli, energy conservation of an
 * undamped rod over 10^6 steps, the measured order in dt of both
 * integrators on a swinging rod, a rod spinning about its axis by more
 * per step than the drift's small-angle series covers, the decay of a
 * spin under each rotational dissipation, and gravity on weightless rods. */
#include "testutil.h"

/* Slender cantilever: E = 1 MPa, rho = 1000 kg/m^3, L = 1 m, r = 5 mm, so
 * (r/L)^2 = 2.5e-5 and shear and rotary inertia are negligible. */
static const double VL = 1.0, VR = 0.005, VE = 1e6, VRHO = 1000.0;
static const double BETA1 = 1.8751040687119611; /* first root of cos cosh = -1 */

static double eb_frequency(void) {
  double A = M_PI * VR * VR, I = A * VR * VR / 4.0;
  return BETA1 * BETA1 / (2 * M_PI * VL * VL) * sqrt(VE * I / (VRHO * A));
}

/* Euler-Bernoulli first mode shape of a clamped-free beam at s. */
static double mode1(double s) {
  double b = BETA1 / VL, bl = BETA1;
  double sg = (cosh(bl) + cos(bl)) / (sinh(bl) + sin(bl));
  return cosh(b * s) - cos(b * s) - sg * (sinh(b * s) - sin(b * s));
}

/* The slender rod of these tests, n elements along x (d1 along z). */
static swRodDesc slender_rod(const char *name, int n) {
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = name;
  r.nelem = n;
  r.direction[0] = 1; r.direction[1] = 0; r.direction[2] = 0;
  r.normal[0] = 0; r.normal[1] = 0; r.normal[2] = 1;
  r.length = VL;
  r.radius_start = r.radius_end = VR;
  r.density = VRHO;
  r.youngs = VE;
  return r;
}

/* A cantilever along x, clamped at its start, given the mode-1 velocity
 * profile (amplitude v0 at the tip) along y. */
static swModel *vibrating_rod(int n, swIntegrator integ, double dt_frac, double v0, swData **dout) {
  swSpec *s = sw_spec_new();
  swRodDesc r = slender_rod("reed", n);
  int id = sw_spec_add_rod(s, &r);
  swBCDesc c = sw_test_clamp(id, 0);
  sw_spec_add_bc(s, &c);
  sw_spec_set_integrator(s, integ);
  swModel *m = sw_test_compile_at(s, dt_frac);
  sw_spec_free(s);
  swData *d = sw_data_new(m);
  for (int i = 1; i <= n; i++)
    SW_AT(m, d->v, m->node_adr[id] + i, 1) = v0 * mode1(VL * i / n) / mode1(VL);
  *dout = d;
  return m;
}

static void test_first_bending_frequency(void **state) {
  (void)state;
  int n = 50;
  swData *d;
  swModel *m = vibrating_rod(n, SW_VERLET, 0.9, 1e-3, &d);
  const double *tip = &SW_AT(m, d->x, m->node_adr[0] + n, 1);
  /* times of upward zero crossings of the tip, linearly interpolated */
  double crossings[8];
  int nc = 0, want = sw_test_sanitized() ? 2 : 4;
  double prev = *tip, tprev = d->time;
  double f_ref = eb_frequency();
  while (nc < want && d->time < (want + 1) / f_ref) {
    assert_int_equal(sw_step(m, d), SW_OK);
    if (prev < 0 && *tip >= 0) crossings[nc++] = tprev + (d->time - tprev) * (-prev) / (*tip - prev);
    prev = *tip;
    tprev = d->time;
  }
  assert_int_equal(nc, want);
  double f = (nc - 1) / (crossings[nc - 1] - crossings[0]);
  fprintf(stderr, "# %s: n = %d, dt = %.3g s, %d periods measured\n", __func__, n, m->dt, nc - 1);
  SW_EXPECT_REL("first eigenfrequency (Hz)", f, f_ref, 1e-2);
  sw_data_free(d);
  sw_model_free(m);
}

static double total_energy(const swModel *m, swData *d) {
  double e[3];
  sw_energy(m, d, e);
  return e[0] + e[1] - e[2];
}

static void test_energy_conservation(void **state) {
  (void)state;
  long nsteps = sw_test_sanitized() ? 100000 : 1000000;
  int n = 50;
  swData *d;
  /* a large amplitude (tip speed 0.05 m/s, about 4% of L in deflection), so
   * that the motion is geometrically nonlinear */
  swModel *m = vibrating_rod(n, SW_VERLET, 0.9, 5e-2, &d);
  double e0 = total_energy(m, d), worst = 0;
  for (long k = 1; k <= nsteps; k++) {
    assert_int_equal(sw_step(m, d), SW_OK);
    if (k % 1000 == 0) {
      double dev = fabs(total_energy(m, d) - e0) / e0;
      if (dev > worst) worst = dev;
    }
  }
  double tipmax = fabs(SW_AT(m, d->x, m->node_adr[0] + n, 1));
  fprintf(stderr, "# %s: %ld steps, %.3g s simulated, energy %.6g J, tip y at end %.3g m\n", __func__,
          nsteps, d->time, e0, tipmax);
  SW_EXPECT_ABS("max relative energy drift", worst, 0.0, 5e-3);
  sw_data_free(d);
  sw_model_free(m);
}

/* A rod pinned at its top end (node held, element free to turn), released
 * at 30 degrees under gravity: a swinging physical pendulum with elastic
 * modes.  Returns the tip position after `t_end` seconds. */
static void swing(swIntegrator integ, double dt, double t_end, double tip[3]) {
  const int n = 16;
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "pendulum";
  r.nelem = n;
  double a = 30.0 * M_PI / 180.0;
  r.direction[0] = sin(a); r.direction[1] = 0; r.direction[2] = -cos(a);
  r.normal[0] = 0; r.normal[1] = 1; r.normal[2] = 0;
  r.length = 0.5;
  r.radius_start = r.radius_end = 0.01;
  r.density = 1000;
  r.youngs = 1e6;
  int id = sw_spec_add_rod(s, &r);
  swBCDesc pin;
  memset(&pin, 0, sizeof pin);
  pin.kind = SW_BC_VELOCITY;
  pin.rod = id;
  pin.signal = sw_signal_const(0.0);
  sw_spec_add_bc(s, &pin);
  double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, integ);
  sw_spec_set_dt(s, dt);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  long steps = lround(t_end / dt);
  for (long k = 0; k < steps; k++) assert_int_equal(sw_step(m, d), SW_OK);
  sw_get3(m, d->x, m->node_adr[id] + n, tip);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void check_time_order(swIntegrator integ, const char *name, double expected, double dt0) {
  const double T = 0.256; /* a whole number of steps for every dt below */
  double ref[3], tip[3], err[4];
  int k = 3;
  swing(integ, dt0 / 64, T, ref);
  for (int i = 0; i < k; i++) {
    double dt = dt0 / (1 << i);
    swing(integ, dt, T, tip);
    err[i] = sqrt(pow(tip[0] - ref[0], 2) + pow(tip[1] - ref[1], 2) + pow(tip[2] - ref[2], 2));
    fprintf(stderr, "# %s: %s dt = %.3e s, tip error %.3e m\n", __func__, name, dt, err[i]);
  }
  for (int i = 0; i + 1 < k; i++) {
    double p = sw_test_order(err, i);
    fprintf(stderr, "# %s: %s measured order %.3f (expected %.0f)\n", __func__, name, p, expected);
    assert_true(fabs(p - expected) < 0.25);
  }
}

static void test_time_order_verlet(void **state) {
  (void)state;
  check_time_order(SW_VERLET, "position Verlet", 2.0, 4e-5);
}

static void test_time_order_pefrl(void **state) {
  (void)state;
  check_time_order(SW_PEFRL, "PEFRL", 4.0, 3.2e-4);
}

/* A free straight rod spinning about its own axis at W: no strain, and the
 * inertial couple (J w / e) x w vanishes (J w is along w), so every frame
 * turns about the axis at the constant rate W, exactly.  W dt = 0.3 rad, three
 * times the angle up to which the drift turns frames with the small-angle
 * series of Rodrigues' formula: this is the drift's exact path
 * (integrate.c, drift_frames), which must give the exact angle to rounding. */
static void test_fast_spin(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  swRodDesc r = slender_rod("spinner", 20);
  sw_spec_add_rod(s, &r);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  swData *d = sw_data_new(m);
  const double turn = 0.3, W = turn / m->dt; /* rad per step, rad/s */
  for (int e = 0; e < r.nelem; e++) SW_AT(m, d->omega, e, 2) = W;
  const long steps = 100;
  assert_int_equal(sw_steps(m, d, steps), SW_OK);
  const double theta = turn * (double)steps; /* 30 rad: almost five turns */
  double worst = 0, worst_x = 0;
  for (int e = 0; e < r.nelem; e++) {
    double Q[9];
    sw_getQ(m, d->Q, e, Q);
    /* d1 starts along z and turns about x: (0, -+sin theta, cos theta) */
    worst = fmax(worst, fabs(Q[2] - cos(theta)));
    worst = fmax(worst, fabs(fabs(Q[1]) - fabs(sin(theta))));
    worst = fmax(worst, fabs(Q[6] - 1.0)); /* d3 stays along x */
  }
  for (int i = 0; i <= r.nelem; i++) worst_x = fmax(worst_x, fabs(SW_AT(m, d->x, i, 1)) + fabs(SW_AT(m, d->x, i, 2)));
  fprintf(stderr, "# %s: %.1f rad per step for %ld steps: largest frame error %.3e, largest "
          "sideways drift of a node %.3e m (tol 1e-12 each)\n", __func__, turn, steps, worst, worst_x);
  assert_true(worst < 1e-12);
  assert_true(worst_x < 1e-12);
  sw_data_free(d);
  sw_model_free(m);
}

/* Claim: a free rod spinning about its axis loses its spin at the rate its
 * rotational dissipation sets: exp(-gamma t / (rho A)) by default (the couple
 * density gamma (I_k / A) w, so rotation decays as translation does) and
 * exp(-gamma_rot t / (rho I_3)) with gamma_rot given (Gazzola 2018's couple
 * density gamma_rot w per unit length).  gamma = 1 kg m^-1 s^-1: 12.7 /s;
 * gamma_rot = 3e-5 N s: 48.6 /s (rho I_3 = 6.17e-7 kg m), each measured over
 * 50 ms with linear and with analytic damping (the analytic kick is exact,
 * the linear one first order in h). */
static void test_rotational_damping(void **state) {
  (void)state;
  const double W0 = 10, T = 0.05, gamma = 1, gamma_rot = 3e-5;
  for (int variant = 0; variant < 4; variant++) {
    const int given = variant & 1, analytic = variant >> 1;
    swSpec *s = sw_spec_new();
    swRodDesc r = slender_rod("spinner", 10);
    r.damping = analytic ? SW_DAMP_ANALYTIC : SW_DAMP_LINEAR;
    r.gamma = gamma;
    if (given) r.gamma_rot = gamma_rot;
    sw_spec_add_rod(s, &r);
    swModel *m = sw_test_compile_at(s, 0.5);
    sw_spec_free(s);
    swData *d = sw_data_new(m);
    for (int e = 0; e < r.nelem; e++) SW_AT(m, d->omega, e, 2) = W0;
    sw_test_run_to(m, d, T);
    const double A = M_PI * VR * VR, I3 = A * VR * VR / 2;
    const double rate = given ? gamma_rot / (VRHO * I3) : gamma / (VRHO * A);
    fprintf(stderr, "# %s: %s, %s damping: spin %.6f rad/s after %.3f s\n", __func__,
            given ? "gamma_rot given" : "default", analytic ? "analytic" : "linear",
            SW_AT(m, d->omega, r.nelem / 2, 2), d->time);
    /* the linear kick's error is first order: (rate h)^2 / 2 a step at
     * most, rate^2 h t over the run */
    SW_EXPECT_REL("spin about the axis (rad/s)", SW_AT(m, d->omega, r.nelem / 2, 2),
                  W0 * exp(-rate * d->time), analytic ? 1e-9 : rate * rate * m->dt * d->time);
    sw_data_free(d);
    sw_model_free(m);
  }
}

/* Claim: gravity does not act on a weightless rod, elastic or rigid, and
 * acts on the others as before.  Three free rods in g = (0, 0, -9.81)
 * m/s^2 for 50 ms: a plain one falls g t^2 / 2 at every node (position
 * Verlet is exact for a constant acceleration, to round-off), a weightless
 * one and a weightless rigid one do not move at all. */
static void test_weightless(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  swRodDesc a = slender_rod("falls", 10), b = slender_rod("floats", 10), c = slender_rod("block", 4);
  b.start[1] = 0.1;
  b.weightless = 1;
  c.start[1] = 0.2;
  c.weightless = 1;
  c.rigid = 1;
  const int ia = sw_spec_add_rod(s, &a), ib = sw_spec_add_rod(s, &b), ic = sw_spec_add_rod(s, &c);
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  swData *d = sw_data_new(m);
  sw_test_run_to(m, d, 0.05);
  const double drop = 0.5 * 9.81 * d->time * d->time;
  double fall = 0, still = 0;
  for (int i = 0; i <= a.nelem; i++)
    fall = fmax(fall, fabs(SW_AT(m, d->x, m->node_adr[ia] + i, 2) + drop));
  const int ids[2] = {ib, ic}, ns[2] = {b.nelem, c.nelem};
  for (int r = 0; r < 2; r++)
    for (int i = 0; i <= ns[r]; i++)
      for (int k = 0; k < 3; k++) {
        const int slot = m->node_adr[ids[r]] + i;
        const double x0 = k == 0 ? VL * i / ns[r] : k == 1 ? (r ? 0.2 : 0.1) : 0.0;
        still = fmax(still, fabs(SW_AT(m, d->x, slot, k) - x0));
      }
  fprintf(stderr, "# %s: after %.3f s the plain rod is %.3e m off g t^2 / 2 = %.6f m; the "
          "weightless ones moved %.3e m (tol 1e-12 each)\n", __func__, d->time, fall, drop, still);
  assert_true(fall < 1e-12);
  assert_true(still < 1e-12);
  sw_data_free(d);
  sw_model_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_weightless),
      cmocka_unit_test(test_first_bending_frequency),
      cmocka_unit_test(test_time_order_verlet),
      cmocka_unit_test(test_time_order_pefrl),
      cmocka_unit_test(test_energy_conservation),
      cmocka_unit_test(test_fast_spin),
      cmocka_unit_test(test_rotational_damping),
  };
  return cmocka_run_group_tests_name("dynamics", tests, NULL, NULL);
}
