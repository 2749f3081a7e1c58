/* test_rod_friction.c — stick-slip friction between rods (contact.c with
 * static_friction, kinetic_friction; the elastic-Coulomb law of friction.c)
 * against Coulomb's law.
 *
 *  - A slider across two rails: two stiff rails along x at y = +-3 cm,
 *    clamped at both ends, and a light stiff slider along y lying across
 *    them, pressed down by a known load N0 and pulled along its own axis by
 *    T(t), both on the nodes of its two touching elements.  (Pulled across
 *    its axis a rod on a rod rolls, as it should: the friction acts at its
 *    surface; pulled along it, one support would let it pitch over.)
 *     . hold: T ramped to 0.8 mu_s N0 and held.  The slider's displacement
 *       is the two tangential springs', T / (2 k_t), to 1 %, and it creeps
 *       by less than 1e-9 m (a slow sway of ~5e-11 m remains) over the last 20 ms.
 *     . threshold: T ramped slowly (N0 per 100 ms): where the slider
 *       leaves the spring law by 0.2 um, T / N0 against Coulomb's threshold,
 *       mu_s / (1 + mu_s R / SPAN) (the friction couple R T moves load off
 *       the front rail, whose contact slips first).
 *     . slide: T ramped to 1.2 mu_s N0 and held; the friction force the
 *       sliding slider feels, T - M dV/dt (M its mass), over N0 is the
 *       kinetic coefficient.
 *  - Momentum: two free rods crossed at right angles, thrown at each other
 *    and sliding across each other (along both their axes), with friction
 *    and the normal damper: the total momentum changes by round-off only,
 *    while friction changed each rod's tangential momentum; and the energy
 *    balance (kinetic + elastic - work, the friction's work booked as
 *    external work) holds to the integrator's error.
 *  - Self-contact: a hairpin whose legs are thrown at each other and slide
 *    past each other; with friction (and no normal damper) the pairs within
 *    the rod are anchored, stick and slip, the momentum stays to round-off,
 *    and the work the friction does is never positive (it takes energy,
 *    never gives any: the law is passive).
 *
 * Design.  Scenes through the public API (swContactDesc with friction);
 * the loads' signals are tables; the tests read positions, velocities and
 * the work, and the contact's counts of stuck and slipping pairs only to say
 * which phase a run is in. */
#include "testutil.h"
#include "vec.h"
#include "internal.h"

/* ---- 1. crossed rods, one pulled ---- */

static const double MU_S = 0.5, MU_K = 0.3, N0 = 0.1; /* N */
static const double KC = 1e4, KT = 2e3, GC = 1.0;     /* N/m, N/m, kg/s */
static const double RB = 3e-3, R = 1e-3;              /* m: the rails' and the slider's radii */
static const double LB = 0.03, LS = 0.08, SPAN = 0.03; /* m: rails, slider, rails at y = +-SPAN */
static const double EB = 1e10, ES = 1e10;             /* Pa: both nearly rigid */
static const double SETTLE = 0.02;                    /* s: the slider settles under N0 */

/* Two rails along x at y = -SPAN and +SPAN (3 elements of 1 cm, clamped),
 * the slider along y (4 elements of 2 cm) across them, touching each at
 * the middle of an end element; N0 / 4 down on the four nodes of those
 * elements (ramped in over 5 ms), and T(t) / 4 along y on the same nodes,
 * T = top N0 (t - SETTLE) / ramp, held at top N0 after the ramp. */
static swModel *crossed_scene(double top, double ramp, double mu_s, double mu_k) {
  swSpec *s = sw_spec_new();
  const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
  for (int k = 0; k < 2; k++) {
    const double sb[3] = {-0.5 * LB, k ? SPAN : -SPAN, 0};
    swRodDesc rail = sw_test_rod(k ? "right" : "left", 3, LB, RB, sb, ex, ez);
    rail.density = 1e5, rail.youngs = EB, rail.poisson = 0.5; /* heavy: a longer step */
    rail.damping = SW_DAMP_LINEAR, rail.gamma = 1e3; /* kg/(m s): settles in ms */
    assert_int_equal(sw_spec_add_rod(s, &rail), k);
    for (int end = 0; end < 2; end++) {
      swBCDesc b = sw_test_clamp(k, end);
      assert_true(sw_spec_add_bc(s, &b) >= 0);
    }
  }
  const double ss[3] = {0, -0.5 * LS, RB + R};
  swRodDesc slider = sw_test_rod("slider", 4, LS, R, ss, ey, ez);
  slider.density = 1e4, slider.youngs = ES, slider.poisson = 0.5;
  assert_int_equal(sw_spec_add_rod(s, &slider), 2);
  const double tn[3] = {0, 0.005, 1}, vn[3] = {0, 1, 1};
  const double tt[3] = {SETTLE, SETTLE + ramp, SETTLE + ramp + 1}, vt[3] = {0, top, top};
  static const int loaded[4] = {0, 1, 3, 4};
  for (int j = 0; j < 4; j++) {
    swLoadDesc press = sw_test_load(SW_LOAD_FORCE, 2, loaded[j], 0, 0, -0.25 * N0);
    press.signal = sw_test_table(3, tn, vn);
    assert_true(sw_spec_add_load(s, &press) >= 0);
    swLoadDesc pull = sw_test_load(SW_LOAD_FORCE, 2, loaded[j], 0, 0.25 * N0, 0);
    pull.signal = sw_test_table(3, tt, vt);
    assert_true(sw_spec_add_load(s, &pull) >= 0);
  }
  swContactDesc c;
  sw_contact_desc_init(&c);
  c.name = "touch";
  c.stiffness = KC, c.damping = GC;
  c.static_friction = mu_s, c.kinetic_friction = mu_k, c.tangential_stiffness = KT;
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

/* The slider's centre of mass along y and its velocity, and its mass. */
static void slider_y(const swModel *m, const swData *d, double *X, double *V, double *M) {
  double x = 0, v = 0, mass = 0;
  for (int i = m->node_adr[2]; i <= m->node_adr[2] + m->rod_nelem[2]; i++) {
    mass += m->mass[i];
    x += m->mass[i] * SW_AT(m, d->x, i, 1);
    v += m->mass[i] * SW_AT(m, d->v, i, 1);
  }
  *X = x / mass, *V = v / mass, *M = mass;
}

/* Compliance of the stuck slider along y: the two tangential springs in
 * parallel (the rails' bending and twist, and the slider's bending under the
 * friction couples, add below 1e-3 of it). */
static double stuck_compliance(void) { return 0.5 / KT; }

static void test_crossed_holds(void **state) {
  (void)state;
  const double top = 0.8 * MU_S, ramp = 0.02;
  swModel *m = crossed_scene(top, ramp, MU_S, MU_K);
  swData *d = sw_data_new(m);
  double X0, X1, X2, V, M;
  sw_test_run_to(m, d, SETTLE);
  slider_y(m, d, &X0, &V, &M);
  sw_test_run_to(m, d, SETTLE + ramp + 0.02);
  slider_y(m, d, &X1, &V, &M);
  sw_test_run_to(m, d, SETTLE + ramp + 0.04);
  slider_y(m, d, &X2, &V, &M);
  const double T = top * N0;
  fprintf(stderr, "# crossed rods at T = %.2f mu_s N0: %d pairs, %d stuck, %d slipping; displaced "
          "%.6g m (T / (2 k_t) = %.6g m), crept %.3g m over 20 ms\n", top / MU_S, d->contact_pairs,
          d->contact_stuck, d->contact_slipping, X2 - X0, T * stuck_compliance(), X2 - X1);
  assert_true(d->contact_pairs == 2 && d->contact_stuck == d->contact_pairs);
  SW_EXPECT_REL("stuck displacement / (T / (2 k_t))", (X2 - X0) / (T * stuck_compliance()), 1.0, 0.01);
  /* a slow, lightly damped sway of ~5e-11 m remains (period ~80 ms) */
  SW_EXPECT_ABS("creep over the last 20 ms of the hold (m)", X2 - X1, 0.0, 1e-9);
  sw_data_free(d);
  sw_model_free(m);
}

/* The friction acts at the slider's underside, R below the pull: the couple
 * R T pitches it and moves R T / (2 SPAN) of the load from the front rail
 * to the back one.  The front contact slips first, when T / 2 = mu_s (N0 / 2
 * - R T / (2 SPAN)), and then the back one must take more than its cap
 * (mu_k < mu_s): the slider goes at T = mu_s N0 / (1 + mu_s R / SPAN). */
static void test_crossed_threshold(void **state) {
  (void)state;
  const double top = 2 * MU_S, ramp = 0.1; /* N0 per 100 ms */
  swModel *m = crossed_scene(top, ramp, MU_S, MU_K);
  swData *d = sw_data_new(m);
  double X0, X, V, M;
  sw_test_run_to(m, d, SETTLE);
  slider_y(m, d, &X0, &V, &M);
  double ratio = NAN;
  while (d->time < SETTLE + ramp) {
    assert_int_equal(sw_steps(m, d, 5), SW_OK);
    slider_y(m, d, &X, &V, &M);
    const double T = pull_at(d->time, top, ramp);
    if (X - X0 - T * stuck_compliance() > 2e-7) {
      ratio = T / N0;
      break;
    }
  }
  const double expect = MU_S / (1 + MU_S * R / SPAN);
  fprintf(stderr, "# crossed rods, T ramped: slides at T / N0 = %.5f (mu_s %.2f, pitched %.5f; %d "
          "slipping)\n", ratio, MU_S, expect, d->contact_slipping);
  SW_EXPECT_REL("T / N0 where the slider slides, against mu_s / (1 + mu_s R / SPAN)", ratio, expect, 0.005);
  sw_data_free(d);
  sw_model_free(m);
}

static void test_crossed_slides(void **state) {
  (void)state;
  const double top = 1.2 * MU_S, ramp = 0.02;
  swModel *m = crossed_scene(top, ramp, MU_S, MU_K);
  swData *d = sw_data_new(m);
  double X, V1, V2, M;
  sw_test_run_to(m, d, SETTLE + ramp + 0.001);
  slider_y(m, d, &X, &V1, &M);
  const double t1 = d->time;
  sw_test_run_to(m, d, SETTLE + ramp + 0.005);
  slider_y(m, d, &X, &V2, &M);
  const double t2 = d->time;
  const double friction = top * N0 - M * (V2 - V1) / (t2 - t1);
  fprintf(stderr, "# crossed rods at T = %.2f mu_s N0: sliding at %.3g m/s, %d slipping of %d; "
          "friction / N0 = %.5f (mu_k %.2f)\n", top / MU_S, V2, d->contact_slipping, d->contact_pairs,
          friction / N0, MU_K);
  assert_true(d->contact_slipping == d->contact_pairs && d->contact_pairs == 2);
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

/* The angular momentum about the origin of all rods (testutil.h). */
static void angular_momentum(const swModel *m, const swData *d, double L[3]) {
  double P[3];
  sw_test_momenta(m, d, P, L);
}

/* The rods of s touching with friction (mu_s 0.6, mu_k 0.4, 2e3 N/m),
 * compiled at half the stable step; s is freed. */
static swModel *rubbing_model(swSpec *s) {
  swContactDesc c;
  sw_contact_desc_init(&c);
  c.stiffness = 2e3, c.damping = 0.05;
  c.static_friction = 0.6, c.kinetic_friction = 0.4;
  assert_int_equal(sw_spec_add_contact(s, &c), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  return m;
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
  swModel *m = rubbing_model(s);
  swData *d = sw_data_new(m);
  /* b comes down on a at 0.2 m/s, sliding across it at 0.15 m/s along x
   * and 0.1 m/s along y: its pairs stick at times and slip at others */
  const double vb[3] = {0.15, 0.1, -0.2};
  for (int i = m->node_adr[1]; i <= m->node_adr[1] + m->rod_nelem[1]; i++) sw_set3(m, d->v, i, vb);
  double Pa0[3], Pb0[3], Pa[3], Pb[3], J0[3], J[3];
  angular_momentum(m, d, J0);
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
  angular_momentum(m, d, J);
  double dP[3], E[3], dJ[3];
  for (int k = 0; k < 3; k++) dJ[k] = J[k] - J0[k];
  for (int k = 0; k < 3; k++) dP[k] = Pa[k] + Pb[k] - Pa0[k] - Pb0[k];
  sw_energy(m, d, E);
  const double P0 = sw_v3_norm(Pb0);
  fprintf(stderr, "# rubbing rods: %d frames stuck, %d slipping; a's momentum along x %.3g, along y "
          "%.3g kg m/s (b's initial %.3g, %.3g); kinetic %.4g of %.4g J left\n", stuck, slipping, Pa[0],
          Pa[1], Pb0[0], Pb0[1], E[0], K0);
  /* friction pulled a along both of b's tangential directions */
  assert_true(stuck > 0 && slipping > 0 && Pa[0] > 1e-3 * P0 && Pa[1] > 1e-3 * P0);
  SW_EXPECT_ABS("total momentum change / initial", sw_v3_norm(dP) / P0, 0.0, 1e-13);
  /* not exact: the friction's force pair acts between the two anchored
   * surface points, apart by the overlap along n (the figure is printed) */
  fprintf(stderr, "#   angular momentum change / (P0 L) %.3g\n", sw_v3_norm(dJ) / (P0 * L));
  SW_EXPECT_ABS("energy balance drift / initial kinetic", (total_energy(m, d) - E0) / K0, 0.0, 2e-3);
  sw_data_free(d);
  sw_model_free(m);
}

/* ---- 3. self-contact: a hairpin's legs rubbing ---- */

/* A hairpin of radius RH = 2 r in the plane z = 0: a leg along x at y = -RH
 * from x = HLEG to 0, a half circle about the origin on the side x < 0, a
 * leg back at y = +RH to x = HLEG; n elements of equal rest arc length, d1
 * along z, d3 along each chord. */
enum { NH = 60 };
static const double RH = 4e-3, RHR = 2e-3, HLEG = 0.05;

static swModel *hairpin_scene(double mu) {
  const double total = 2 * HLEG + M_PI * RH;
  static double x[3 * (NH + 1)], Q[9 * NH];
  for (int i = 0; i <= NH; i++) {
    const double a = total * i / NH;
    double *p = x + 3 * i;
    if (a <= HLEG) p[0] = HLEG - a, p[1] = -RH;
    else if (a >= HLEG + M_PI * RH) p[0] = a - HLEG - M_PI * RH, p[1] = RH;
    else p[0] = -RH * sin((a - HLEG) / RH), p[1] = -RH * cos((a - HLEG) / RH);
    p[2] = 0;
  }
  for (int i = 0; i < NH; i++) {
    double t[3], *q = Q + 9 * i;
    for (int k = 0; k < 3; k++) t[k] = x[3 * i + 3 + k] - x[3 * i + k];
    sw_v3_scale(t, t, 1.0 / sw_v3_norm(t));
    const double d1[3] = {0, 0, 1};
    double d2[3];
    sw_v3_cross(d2, t, d1);
    memcpy(q, d1, sizeof d1), memcpy(q + 3, d2, sizeof d2), memcpy(q + 6, t, sizeof t);
  }
  swSpec *s = sw_spec_new();
  const double o[3] = {HLEG, -RH, 0}, dir[3] = {-1, 0, 0}, ez[3] = {0, 0, 1};
  swRodDesc r = sw_test_rod("hairpin", NH, total, RHR, o, dir, ez);
  r.density = 1000, r.youngs = 1e6, r.poisson = 0.5;
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  assert_int_equal(sw_spec_set_rest_shape(s, 0, x, Q), SW_OK);
  swContactDesc c;
  sw_contact_desc_init(&c);
  c.stiffness = 2e3, c.self = 1; /* no damper: the work done is friction's alone */
  c.static_friction = c.kinetic_friction = mu;
  assert_int_equal(sw_spec_add_contact(s, &c), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  return m;
}

/* The legs of the hairpin thrown at each other (0.3 m/s each along y) and
 * sliding past each other (0.2 m/s each along x): with self-contact
 * friction the pairs of one rod are anchored, the total momentum stays
 * (round-off), the energy balance holds, and the legs come out sliding
 * past each other more slowly than without friction. */
static double hairpin_rub(double mu) {
  swModel *m = hairpin_scene(mu);
  swData *d = sw_data_new(m);
  for (int i = 0; i <= NH; i++)
    if (SW_AT(m, d->x, i, 0) > 0) {
      const double lower = SW_AT(m, d->x, i, 1) < 0;
      const double v[3] = {lower ? 0.2 : -0.2, lower ? 0.3 : -0.3, 0};
      sw_set3(m, d->v, i, v);
    }
  double P0[3], P[3], dP[3], K0;
  rod_momentum(m, d, 0, P0);
  double E[3];
  sw_energy(m, d, E);
  K0 = E[0];
  const double E0 = total_energy(m, d);
  int stuck = 0, slipping = 0;
  double most = -INFINITY; /* the largest work done on the rod so far */
  while (d->time < 0.02) {
    assert_int_equal(sw_steps(m, d, 10), SW_OK);
    stuck += d->contact_stuck > 0;
    slipping += d->contact_slipping > 0;
    most = fmax(most, d->work);
  }
  rod_momentum(m, d, 0, P);
  for (int k = 0; k < 3; k++) dP[k] = P[k] - P0[k];
  const double M = 1000 * M_PI * RHR * RHR * (2 * HLEG + M_PI * RH);
  sw_energy(m, d, E);
  fprintf(stderr, "# hairpin, self-contact friction %.2f: %d frames stuck, %d slipping; work of the "
          "friction %.4g J, at most %.3g J (initial kinetic %.4g J)\n", mu, stuck, slipping, E[2], most, K0);
  SW_EXPECT_ABS("momentum change / (M 0.3 m/s)", sw_v3_norm(dP) / (M * 0.3), 0.0, 1e-13);
  fprintf(stderr, "#   energy balance drift / initial kinetic %.3g\n", (total_energy(m, d) - E0) / K0);
  if (mu > 0) assert_true(stuck > 0 && slipping > 0);
  else assert_true(stuck + slipping == 0);
  SW_EXPECT_ABS("the largest work the friction did so far, / initial kinetic (<= 0)", fmax(most, 0) / K0,
                0.0, 1e-12);
  sw_data_free(d);
  sw_model_free(m);
  return E[2];
}

static void test_self_friction(void **state) {
  (void)state;
  const double free = hairpin_rub(0.0), rubbed = hairpin_rub(0.5);
  assert_true(free == 0 && rubbed < 0); /* friction took energy */
}

/* N two-element rods crossing at one point (their middle nodes), all
 * touching each other: up to 4 element pairs a pair of rods against the
 * anchors' room of 4 rows an element, 8 N + 64.  Below it nothing is
 * dropped; above it the pairs beyond the room are counted in
 * d->friction_full (of which sw_run warns), never silently frictionless. */
static long crossed_star(int nrod) {
  swSpec *s = sw_spec_new();
  const double L = 0.05, r = 2e-3, ez[3] = {0, 0, 1};
  char name[nrod][16];
  for (int k = 0; k < nrod; k++) {
    const double a = M_PI * k / nrod, dir[3] = {cos(a), sin(a), 0};
    const double st[3] = {-0.5 * L * dir[0], -0.5 * L * dir[1], 0.1 * r * k};
    snprintf(name[k], sizeof name[k], "r%d", k);
    swRodDesc rod = sw_test_rod(name[k], 2, L, r, st, dir, ez);
    rod.density = 1000, rod.youngs = 1e7, rod.poisson = 0.5;
    assert_int_equal(sw_spec_add_rod(s, &rod), k);
  }
  swModel *m = rubbing_model(s);
  swData *d = sw_data_new(m);
  assert_int_equal(sw_steps(m, d, 1), SW_OK);
  const long full = d->friction_full, over = d->contact_pairs - m->contact_maxanchor;
  fprintf(stderr, "# %d crossed rods: %d pairs touching, room %d rows, %ld left frictionless\n", nrod,
          d->contact_pairs, m->contact_maxanchor, full);
  assert_true(d->contact_pairs >= nrod * (nrod - 1) / 2); /* every two rods touch */
  assert_int_equal(full, over > 0 ? over : 0);
  sw_data_free(d);
  sw_model_free(m);
  return full;
}

static void test_table_full(void **state) {
  (void)state;
  assert_int_equal(crossed_star(6), 0); /* room 112 */
  assert_true(crossed_star(24) > 0);    /* room 256 */
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_crossed_holds),
      cmocka_unit_test(test_crossed_threshold),
      cmocka_unit_test(test_crossed_slides),
      cmocka_unit_test(test_momentum),
      cmocka_unit_test(test_self_friction),
      cmocka_unit_test(test_table_full),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
