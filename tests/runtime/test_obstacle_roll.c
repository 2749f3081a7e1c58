/* test_obstacle_roll.c — a thick rod rolling on a rigid obstacle with
 * stick-slip friction (obstacle.c), against the closed forms of a solid
 * cylinder.
 *
 * A rod lying across a box face is a solid cylinder of radius r: its
 * rotational inertia about its axis per length is rho I3 = rho A r^2 / 2,
 * half of rho A r^2, so with friction at its touching surface
 *  - on a slope alpha it rolls without slipping when mu_s >= tan(alpha) / 3,
 *    its centre accelerating at 2/3 g sin(alpha), its spin at that over r,
 *    friction taking 1/3 m g sin(alpha) (the test mirrors test_ground's
 *    test_contact_point_incline, with an obstacle box for the ground);
 *  - below that threshold it slides at g (sin(alpha) - mu_k cos(alpha)) and
 *    spins up at 2 mu_k g cos(alpha) / r;
 *  - spun at w0 on a flat box and let go, kinetic friction turns spin into
 *    rolling: angular momentum about the contact line is kept, so it ends
 *    rolling at r w0 / 3 with the spin w0 / 3, and friction has taken 2/3 of
 *    the kinetic energy.
 * In each, the mechanical energy (kinetic + elastic + gravity's potential)
 * must never rise: friction and the dampers only take energy (the largest
 * rise over the run is printed, against the integrator's error), and the
 * booked balance kinetic + elastic - work stays constant.
 *
 * Anchored on the centreline instead of the touching surface, the friction
 * ties the rod's axis to the box: the rod neither rolls nor spins up (on the
 * slope with mu_s = 0.3 it slid at g (sin - mu_k cos) = 2.781 m/s^2 instead
 * of rolling at 3.27, and a spun rod kept spinning in place at 30 rad/s).
 * Anchored at the surface but with the anchor kept as a material point of
 * the rod while stuck, a rolling rod carries it up its side (the spring sees
 * only the tangential part): the rod then rolls about a point off its
 * bottom, at 3.291 m/s^2 (+0.6 %) spinning up at 320 rad/s^2 (-2.2 %), and a
 * spun rod ends at 0.0978 m/s and 10.42 rad/s; re-anchoring at the touching
 * point at every evaluation, the stretch kept, removes it
 * (docs/physics.md, "Rigid obstacles"). */
#include "testutil.h"
#include "vec.h"
#include "internal.h"

static const double G = 9.81, R = 0.01, L = 0.1, RHO = 1000;
enum { N = 4 };
/* The closed forms are for a rigid cylinder on a rigid plane; the model's
 * largest departure from them is the penalty: the rod sinks by
 * k^-1 * its weight per element, 6.7e-6 m = 6.7e-4 r, so that the contact's
 * lever (r at the anchor) and the centre's height (r - depth) differ by
 * that fraction.  1e-3 bounds it; the rest (the rod's elasticity, the step)
 * is smaller. */
static const double TOL = 1e-3;

/* The rod along y lying on the face (normal n) of a box, its centre at `at`
 * along the face; the box 1 cm thick, 1 m along t (the face's direction
 * across y), 40 cm along y.  k: 6.7 um of depth under an element's weight. */
static swModel *scene(const double n[3], const double t[3], double at, double mu_s, double mu_k) {
  swSpec *s = sw_spec_new();
  const double ey[3] = {0, 1, 0};
  const double sink = RHO * M_PI * R * R * (L / N) * G / 1e4; /* the rest depth, ~ */
  double start[3];
  for (int k = 0; k < 3; k++) start[k] = at * t[k] - 0.5 * L * ey[k] + (R - sink) * n[k];
  swRodDesc rod = sw_test_rod("roller", N, L, R, start, ey, n);
  rod.density = RHO;
  rod.youngs = 1e7;
  rod.poisson = 0.5;
  assert_int_equal(sw_spec_add_rod(s, &rod), 0);
  const double g[3] = {0, 0, -G};
  sw_spec_set_gravity(s, g);
  swObstacleDesc o = sw_test_slope(n, 0.5, 0.2);
  o.stiffness = 1e4;
  o.damping = 1.0; /* zeta 0.06 for an element's mass */
  o.static_friction = mu_s;
  o.kinetic_friction = mu_k;
  assert_int_equal(sw_spec_add_obstacle(s, &o), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  return m;
}

/* The centre of mass's velocity along dir, and the mean spin about the
 * rod's axis (lab: omega_lab . tangent). */
static double speed_along(const swModel *m, const swData *d, const double dir[3]) {
  double M = 0, v = 0;
  for (int i = 0; i <= N; i++) {
    double u[3];
    sw_get3(m, d->v, i, u);
    M += m->mass[i];
    v += m->mass[i] * sw_v3_dot(u, dir);
  }
  return v / M;
}

static double axial_spin(const swModel *m, const swData *d) {
  double sum = 0;
  for (int e = 0; e < N; e++) {
    double Q[9], w[3], wl[3], t[3];
    sw_getQ(m, d->Q, e, Q);
    sw_get3(m, d->omega, e, w);
    sw_matT_vec(wl, Q, w);
    for (int k = 0; k < 3; k++) t[k] = SW_AT(m, d->x, e + 1, k) - SW_AT(m, d->x, e, k);
    sum += sw_v3_dot(wl, t) / sw_v3_norm(t);
  }
  return sum / N;
}

/* kinetic + elastic + gravity's potential; and the booked balance
 * kinetic + elastic - work */
static void energies(const swModel *m, swData *d, double *mech, double *booked) {
  double E[3], pot = 0;
  sw_energy(m, d, E);
  for (int i = 0; i <= N; i++) pot += m->mass[i] * G * SW_AT(m, d->x, i, 2);
  *mech = E[0] + E[1] + pot;
  *booked = E[0] + E[1] - E[2];
}

/* Run to t, tracking the largest rise of the mechanical energy above its
 * value at t = 0. */
static void run_watching(const swModel *m, swData *d, double t, double E0, double *rise) {
  while (d->time < t - 0.5 * m->dt) {
    assert_int_equal(sw_steps(m, d, 10), SW_OK);
    double mech, booked;
    energies(m, d, &mech, &booked);
    *rise = fmax(*rise, mech - E0);
  }
}

static void incline(int rolling) {
  const double a = 30.0 * M_PI / 180.0, n[3] = {-sin(a), 0, cos(a)}, t[3] = {cos(a), 0, sin(a)};
  const double down[3] = {-t[0], -t[1], -t[2]};
  /* tan(a) / 3 = 0.192: rolling above it, sliding below */
  const double mu_s = rolling ? 0.3 : 0.1, mu_k = rolling ? 0.25 : 0.1;
  swModel *m = scene(n, t, 0.3, mu_s, mu_k);
  swData *d = sw_data_new(m);
  double E0, B0, rise = 0, mech, booked;
  energies(m, d, &E0, &B0);
  const double t1 = 0.05, t2 = 0.2;
  run_watching(m, d, t1, E0, &rise);
  const double u1 = speed_along(m, d, down), w1 = axial_spin(m, d), ta = d->time;
  run_watching(m, d, t2, E0, &rise);
  const double u2 = speed_along(m, d, down), w2 = axial_spin(m, d), tb = d->time;
  energies(m, d, &mech, &booked);
  const double acc = (u2 - u1) / (tb - ta), spin = fabs(w2 - w1) / (tb - ta);
  const double K = 0.5 * RHO * M_PI * R * R * L * u2 * u2; /* the translational kinetic energy */
  fprintf(stderr, "# %s: speed %.4f -> %.4f m/s, spin %.2f -> %.2f rad/s, slip r|w| - v %.3e m/s; "
          "%d contacts, %d stuck, %d slipping; mechanical energy lost %.3e J (%.3g of the "
          "kinetic), largest rise %.3e J; booked balance drift %.3e J\n", rolling ? "rolling" : "sliding",
          u1, u2, w1, w2, R * fabs(w2) - u2, d->obstacle_contacts, d->obstacle_stuck,
          d->obstacle_slipping, E0 - mech, (E0 - mech) / K, rise, booked - B0);
  if (rolling) {
    SW_EXPECT_REL("acceleration down the slope, rolling (m/s^2)", acc, 2.0 / 3.0 * G * sin(a), TOL);
    SW_EXPECT_REL("spin-up about the axis, rolling (rad/s^2)", spin, 2.0 / 3.0 * G * sin(a) / R, TOL);
  } else {
    SW_EXPECT_REL("acceleration down the slope, sliding (m/s^2)", acc,
                  G * (sin(a) - mu_k * cos(a)), TOL);
    SW_EXPECT_REL("spin-up about the axis, sliding (rad/s^2)", spin, 2 * mu_k * G * cos(a) / R, TOL);
  }
  SW_EXPECT_ABS("largest rise of the mechanical energy / kinetic", rise / K, 0.0, 1e-4);
  SW_EXPECT_ABS("booked balance drift / kinetic", (booked - B0) / K, 0.0, 1e-3);
  sw_data_free(d);
  sw_model_free(m);
}

static void test_incline_rolls(void **state) { (void)state; incline(1); }
static void test_incline_slides(void **state) { (void)state; incline(0); }

static void test_spin_turns_to_rolling(void **state) {
  (void)state;
  const double n[3] = {0, 0, 1}, t[3] = {1, 0, 0}, mu = 0.4, w0 = 30;
  swModel *m = scene(n, t, 0.0, mu, mu);
  swData *d = sw_data_new(m);
  sw_test_run_to(m, d, 0.01); /* settle onto the face */
  for (int e = 0; e < N; e++) SW_AT(m, d->omega, e, 2) = w0; /* d3 = y: spin about the axis */
  double E0, B0, rise = 0, mech, booked;
  energies(m, d, &E0, &B0);
  const double K0 = 0.25 * RHO * M_PI * R * R * L * R * R * w0 * w0; /* J w0^2 / 2 */
  /* the slip r w0 stops after t* = r w0 / (3 mu g) = 25 ms */
  run_watching(m, d, 0.01 + 0.06, E0, &rise);
  energies(m, d, &mech, &booked);
  const double v = fabs(speed_along(m, d, t)), w = fabs(axial_spin(m, d));
  fprintf(stderr, "# spin %.0f rad/s: after 60 ms v = %.4f m/s, spin %.3f rad/s (%d stuck, %d "
          "slipping); kinetic energy left %.4f of the initial; largest rise %.3e J\n", w0, v, w,
          d->obstacle_stuck, d->obstacle_slipping, 1 - (E0 - mech) / K0, rise);
  SW_EXPECT_REL("rolling speed after the spin (m/s)", v, R * w0 / 3, TOL);
  SW_EXPECT_REL("spin left (rad/s)", w, w0 / 3, TOL);
  SW_EXPECT_REL("energy taken by friction / initial spin energy", (E0 - mech) / K0, 2.0 / 3.0, TOL);
  SW_EXPECT_ABS("largest rise of the mechanical energy / initial", rise / K0, 0.0, 1e-4);
  SW_EXPECT_ABS("booked balance drift / initial", (booked - B0) / K0, 0.0, 1e-3);
  sw_data_free(d);
  sw_model_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_incline_rolls),
      cmocka_unit_test(test_incline_slides),
      cmocka_unit_test(test_spin_turns_to_rolling),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
