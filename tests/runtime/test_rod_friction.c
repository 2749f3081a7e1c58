/* test_rod_friction.c — stick-slip friction between rods (contact.c with
 * static_friction, kinetic_friction; the elastic-Coulomb law of friction.c)
 * against Coulomb's law.
 *
 *  - Two rods crossed at right angles: a stiff base along x, clamped at both
 *    ends, and a light slider along y lying on it, pressed down by a known
 *    load N0 and pulled along x (along the base) by T(t), both at the two
 *    nodes of the slider's middle element, whose midpoint sits on the base:
 *    the slider moves as a rigid body and the contact carries N0 and T.
 *     . hold: T ramped to 0.8 mu_s N0 and held.  The slider's displacement
 *       is the tangential spring's, T / k_t, plus the base's stretch under T
 *       (its two outer elements in parallel, T l / (2 EA)); it must match
 *       that to 1 %, and creep by less than 1e-10 m over the last 40 ms.
 *     . threshold: T ramped slowly (0.4 N0 per 100 ms): where the slider
 *       leaves the spring law by 5 um, T / N0 is the static coefficient.
 *     . slide: T ramped to 1.2 mu_s N0 and held; the slider then accelerates
 *       and the friction force it feels, T - M dV/dt (M its mass), over N0
 *       is the kinetic coefficient.
 *  - Momentum: two free rods crossed at right angles, thrown at each other
 *    and sliding across each other (along both their axes), with friction
 *    and the normal damper: the total momentum changes by round-off only,
 *    while friction changed each rod's tangential momentum; and the energy
 *    balance (kinetic + elastic - work, the friction's work booked as
 *    external work) holds to the integrator's error, beside the kinetic
 *    energy the friction took.
 *
 * Design.  Scenes through the public API (swContactDesc with friction);
 * the loads' signals are tables; the tests read positions and velocities,
 * and the contact's counts of stuck and slipping pairs only to say which
 * phase a run is in. */
#include "testutil.h"
#include "vec.h"
#include "internal.h"

/* ---- 1. crossed rods, one pulled ---- */

static const double MU_S = 0.5, MU_K = 0.3, N0 = 0.1; /* N */
static const double KC = 1e4, KT = 2e3, GC = 1.0;     /* N/m, N/m, kg/s */
static const double RB = 3e-3, R = 1e-3, LB = 0.09, LS = 0.03; /* m: radii, base, slider */
static const double EB = 1e9, ES = 1e9;               /* Pa */
static const double SETTLE = 0.02;                    /* s: the slider settles under N0 */

static swSignal table(int n, const double *t, const double *v) {
  swSignal g = sw_signal_const(1.0);
  g.kind = SW_SIG_TABLE;
  g.npts = n;
  for (int k = 0; k < n; k++) g.times[k] = t[k], g.values[k] = v[k];
  return g;
}

/* The base along x (3 elements of 3 cm, clamped), the slider along y (3
 * elements of 1 cm) on it, touching; N0 down on the slider's nodes 1, 2
 * (ramped in over 5 ms), and T(t) = top N0 (t - SETTLE) / ramp along x,
 * held at top N0 after the ramp. */
static swModel *crossed_scene(double top, double ramp) {
  swSpec *s = sw_spec_new();
  const double sb[3] = {-0.5 * LB, 0, 0}, ex[3] = {1, 0, 0}, ez[3] = {0, 0, 1};
  swRodDesc base = sw_test_rod("base", 3, LB, RB, sb, ex, ez);
  base.density = 1000, base.youngs = EB, base.poisson = 0.5;
  base.damping = SW_DAMP_LINEAR, base.gamma = 10.0; /* kg/(m s): its bending settles in ms */
  assert_int_equal(sw_spec_add_rod(s, &base), 0);
  const double ss[3] = {0, -0.5 * LS, RB + R}, ey[3] = {0, 1, 0};
  swRodDesc slider = sw_test_rod("slider", 3, LS, R, ss, ey, ez);
  slider.density = 1000, slider.youngs = ES, slider.poisson = 0.5;
  assert_int_equal(sw_spec_add_rod(s, &slider), 1);
  for (int end = 0; end < 2; end++) {
    swBCDesc b = sw_test_clamp(0, end);
    assert_true(sw_spec_add_bc(s, &b) >= 0);
  }
  const double tn[3] = {0, 0.005, 1}, vn[3] = {0, 1, 1};
  const double tt[3] = {SETTLE, SETTLE + ramp, SETTLE + ramp + 1}, vt[3] = {0, top, top};
  for (int node = 1; node <= 2; node++) {
    swLoadDesc press = sw_test_load(SW_LOAD_FORCE, 1, node, 0, 0, -0.5 * N0);
    press.signal = table(3, tn, vn);
    assert_true(sw_spec_add_load(s, &press) >= 0);
    swLoadDesc pull = sw_test_load(SW_LOAD_FORCE, 1, node, 0.5 * N0, 0, 0);
    pull.signal = table(3, tt, vt);
    assert_true(sw_spec_add_load(s, &pull) >= 0);
  }
  swContactDesc c;
  sw_contact_desc_init(&c);
  c.name = "touch";
  c.stiffness = KC, c.damping = GC;
  c.static_friction = MU_S, c.kinetic_friction = MU_K, c.tangential_stiffness = KT;
  assert_int_equal(sw_spec_add_contact(s, &c), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  return m;
}

/* The pull T(t), N, as the scene's table gives it. */
static double pull_at(double t, double top, double ramp) {
  if (t <= SETTLE) return 0;
  return N0 * top * fmin(1.0, (t - SETTLE) / ramp);
}

/* The slider's centre of mass along x and its velocity, and its mass. */
static void slider_x(const swModel *m, const swData *d, double *X, double *V, double *M) {
  double x = 0, v = 0, mass = 0;
  for (int i = m->node_adr[1]; i <= m->node_adr[1] + m->rod_nelem[1]; i++) {
    mass += m->mass[i];
    x += m->mass[i] * SW_AT(m, d->x, i, 0);
    v += m->mass[i] * SW_AT(m, d->v, i, 0);
  }
  *X = x / mass, *V = v / mass, *M = mass;
}

/* Compliance of the stuck contact along x: the tangential spring and the
 * base's two outer elements (clamped, in parallel) stretched by T. */
static double stuck_compliance(void) {
  const double EA = EB * M_PI * RB * RB, l = LB / 3;
  return 1.0 / KT + l / (2 * EA);
}

static void test_crossed_holds(void **state) {
  (void)state;
  const double top = 0.8 * MU_S, ramp = 0.02;
  swModel *m = crossed_scene(top, ramp);
  swData *d = sw_data_new(m);
  double X0, X1, X2, V, M;
  sw_test_run_to(m, d, SETTLE);
  slider_x(m, d, &X0, &V, &M);
  sw_test_run_to(m, d, SETTLE + ramp + 0.02);
  slider_x(m, d, &X1, &V, &M);
  sw_test_run_to(m, d, SETTLE + ramp + 0.06);
  slider_x(m, d, &X2, &V, &M);
  const double T = top * N0;
  fprintf(stderr, "# crossed rods at T = %.2f mu_s N0: %d pairs, %d stuck, %d slipping; displaced "
          "%.6g m (T / k_t = %.6g m), crept %.3g m over 40 ms\n", top / MU_S, d->contact_pairs,
          d->contact_stuck, d->contact_slipping, X1 - X0, T / KT, X2 - X1);
  assert_true(d->contact_pairs > 0 && d->contact_stuck == d->contact_pairs);
  SW_EXPECT_REL("stuck displacement / (T (1/k_t + l/(2EA)))", (X2 - X0) / (T * stuck_compliance()),
                1.0, 0.01);
  SW_EXPECT_ABS("creep over the 40 ms hold (m)", X2 - X1, 0.0, 1e-10);
  sw_data_free(d);
  sw_model_free(m);
}

static void test_crossed_threshold(void **state) {
  (void)state;
  const double top = 2 * MU_S, ramp = 0.25; /* 0.4 N0 per 100 ms */
  swModel *m = crossed_scene(top, ramp);
  swData *d = sw_data_new(m);
  double X0, X, V, M;
  sw_test_run_to(m, d, SETTLE);
  slider_x(m, d, &X0, &V, &M);
  double ratio = NAN;
  while (d->time < SETTLE + ramp) {
    assert_int_equal(sw_steps(m, d, 5), SW_OK);
    slider_x(m, d, &X, &V, &M);
    const double T = pull_at(d->time, top, ramp);
    if (X - X0 - T * stuck_compliance() > 5e-6) {
      ratio = T / N0;
      break;
    }
  }
  fprintf(stderr, "# crossed rods, T ramped: slides at T / N0 = %.5f (mu_s %.2f; %d slipping)\n", ratio,
          MU_S, d->contact_slipping);
  SW_EXPECT_REL("static coefficient measured, T / N0 where the slider slides", ratio, MU_S, 0.01);
  sw_data_free(d);
  sw_model_free(m);
}

static void test_crossed_slides(void **state) {
  (void)state;
  const double top = 1.2 * MU_S, ramp = 0.02;
  swModel *m = crossed_scene(top, ramp);
  swData *d = sw_data_new(m);
  double X, V1, V2, M;
  sw_test_run_to(m, d, SETTLE + ramp + 0.001);
  slider_x(m, d, &X, &V1, &M);
  const double t1 = d->time;
  sw_test_run_to(m, d, SETTLE + ramp + 0.005);
  slider_x(m, d, &X, &V2, &M);
  const double t2 = d->time;
  const double friction = top * N0 - M * (V2 - V1) / (t2 - t1);
  fprintf(stderr, "# crossed rods at T = %.2f mu_s N0: sliding at %.3g m/s, %d slipping of %d; "
          "friction / N0 = %.5f (mu_k %.2f)\n", top / MU_S, V2, d->contact_slipping, d->contact_pairs,
          friction / N0, MU_K);
  assert_true(d->contact_slipping == d->contact_pairs && d->contact_pairs > 0);
  SW_EXPECT_REL("kinetic coefficient measured, (T - M dV/dt) / N0", friction / N0, MU_K, 0.01);
  sw_data_free(d);
  sw_model_free(m);
}

/* ---- 2. momentum of two free rods rubbing ---- */

static double total_energy(const swModel *m, swData *d) {
  double E[3];
  sw_energy(m, d, E);
  return E[0] + E[1] - E[2];
}

static void rod_momentum(const swModel *m, const swData *d, int r, double P[3]) {
  P[0] = P[1] = P[2] = 0;
  for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
    for (int k = 0; k < 3; k++) P[k] += m->mass[i] * SW_AT(m, d->v, i, k);
}

static void test_momentum(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  const double L = 0.05, r = 2e-3, gap = 1e-4, ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
  const double sa[3] = {-0.5 * L, 0, 0}, sb[3] = {0, -0.5 * L, 2 * r + gap};
  swRodDesc a = sw_test_rod("a", 11, L, r, sa, ex, ez), b = sw_test_rod("b", 11, L, r, sb, ey, ez);
  a.density = b.density = 1000, a.youngs = b.youngs = 1e7, a.poisson = b.poisson = 0.5;
  assert_int_equal(sw_spec_add_rod(s, &a), 0);
  assert_int_equal(sw_spec_add_rod(s, &b), 1);
  swContactDesc c;
  sw_contact_desc_init(&c);
  c.stiffness = 2e3, c.damping = 0.05;
  c.static_friction = 0.6, c.kinetic_friction = 0.4;
  assert_int_equal(sw_spec_add_contact(s, &c), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  swData *d = sw_data_new(m);
  /* b comes down on a at 0.2 m/s, sliding across it at 0.15 m/s along x
   * and 0.1 m/s along y: its pairs stick at times and slip at others */
  const double vb[3] = {0.08, 0.05, -0.2};
  for (int i = m->node_adr[1]; i <= m->node_adr[1] + m->rod_nelem[1]; i++) sw_set3(m, d->v, i, vb);
  double Pa0[3], Pb0[3], Pa[3], Pb[3];
  rod_momentum(m, d, 0, Pa0);
  rod_momentum(m, d, 1, Pb0);
  const double E0 = total_energy(m, d), K0 = 0.5 * sw_v3_dot(Pb0, vb);
  int stuck = 0, slipping = 0;
  while (d->time < 0.01) {
    assert_int_equal(sw_steps(m, d, 10), SW_OK);
    stuck += d->contact_stuck > 0;
    slipping += d->contact_slipping > 0;
  }
  rod_momentum(m, d, 0, Pa);
  rod_momentum(m, d, 1, Pb);
  double dP[3], E[3];
  for (int k = 0; k < 3; k++) dP[k] = Pa[k] + Pb[k] - Pa0[k] - Pb0[k];
  sw_energy(m, d, E);
  const double P0 = sw_v3_norm(Pb0);
  fprintf(stderr, "# rubbing rods: %d frames stuck, %d slipping; a's momentum along x %.3g, along y "
          "%.3g kg m/s (b's initial %.3g, %.3g); kinetic %.4g of %.4g J left\n", stuck, slipping, Pa[0],
          Pa[1], Pb0[0], Pb0[1], E[0], K0);
  /* friction pulled a along both of b's tangential directions */
  assert_true(stuck > 0 && slipping > 0 && Pa[0] > 1e-3 * P0 && Pa[1] > 1e-3 * P0);
  SW_EXPECT_ABS("total momentum change / initial", sw_v3_norm(dP) / P0, 0.0, 1e-13);
  SW_EXPECT_ABS("energy balance drift / initial kinetic", (total_energy(m, d) - E0) / K0, 0.0, 2e-3);
  sw_data_free(d);
  sw_model_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_crossed_holds),
      cmocka_unit_test(test_crossed_threshold),
      cmocka_unit_test(test_crossed_slides),
      cmocka_unit_test(test_momentum),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
