/* test_friction.c — stick-slip friction between rods and rigid obstacles
 * (obstacle.c, the elastic-Coulomb anchor law) against closed forms.
 *
 *  - Capstan (Euler-Eytelwein): a light rope over a fixed cylinder, pulled
 *    by T1 on one end and T2 on the other, wrap angle theta = pi/2 (one end
 *    pulled along the top, the other down) or pi (both down).  T2 is ramped
 *    slowly from T1 until the rope slides (the node where the rope meets the
 *    cylinder on the slack side moves by 0.1 mm): the ratio T2/T1 there is
 *    the threshold, compared with the capstan's ratio for two mu and two
 *    theta.  The friction acts at the rope's surface, on the drum's radius
 *    R, while the tension runs along its centreline at R + r: moments about
 *    the drum's axis, (T2 - T1)(R + r) = R * integral of mu dN, with dN = T
 *    dtheta, give T2/T1 = exp(mu theta R / (R + r)) (exp(mu theta) for a
 *    thin rope; here R / (R + r) = 30/31).  Below it (0.85 of it) the rope
 *    holds: the creep of its ends over the last 40 ms of the run is printed
 *    and must be below 1e-6 m; above it (1.15 of it) the rope slides away.
 *  - Inclined plane: a short rod on a box's face tilted by alpha, under
 *    gravity, mu_s = 0.5, mu_k = 0.3: at tan alpha = 0.36 < mu_s it stays
 *    (creep below 1e-7 m), at tan alpha = 0.70 it slides with acceleration
 *    g (sin alpha - mu_k cos alpha).
 *
 * Design.  Scenes are built through the public API (swObstacleDesc with
 * static_friction, kinetic_friction); the rope's ends carry point loads
 * whose signals ramp T2; tests read positions and the contact records. */
#include "testutil.h"
#include "vec.h"
#include "internal.h"

/* ---- 1. the capstan ---- */

enum { NROPE = 60 };
static const double ROPE_L = 0.3, ROPE_R = 1e-3, CYL_R = 0.03, T1 = 1.0;
static const double SETTLE = 0.04; /* s: the rope wraps and comes to rest */

/* The rope along x over the top of a cylinder along y (centre at the
 * origin), its middle node at the top; T1 on node 0 (along -x for theta =
 * pi/2, down for pi) and T2 = T1 ratio(t) down on the last node.  Both
 * rise from 0 over the first 5 ms (a gentler fall onto the post); T2/T1
 * then goes from 1 at SETTLE to `ratio` at SETTLE + ramp. */
static swModel *capstan_scene(double mu, double theta, double ratio, double ramp) {
  swSpec *s = sw_spec_new();
  const double start[3] = {-0.5 * ROPE_L, 0, CYL_R + ROPE_R + 1e-6}, ex[3] = {1, 0, 0};
  swRodDesc r = sw_test_rod("rope", NROPE, ROPE_L, ROPE_R, start, ex, NULL);
  r.density = 1000;
  r.youngs = 3e7; /* EA = 94 N: 1 % under T1; bending length sqrt(EI / T1) = 5 mm */
  r.poisson = 0.5;
  r.damping = SW_DAMP_LINEAR;
  r.gamma = 1.0; /* kg/(m s): 1 / 300 s */
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  const double ts[3] = {0, 0.005, 1}, vs[3] = {0, 1, 1};
  const double tt[4] = {0, 0.005, SETTLE, SETTLE + ramp}, vt[4] = {0, 1, 1, ratio};
  swLoadDesc slack = sw_test_load(SW_LOAD_FORCE, 0, 0, theta < 2 ? -T1 : 0, 0, theta < 2 ? 0 : -T1);
  slack.signal = sw_test_table(3, ts, vs);
  assert_true(sw_spec_add_load(s, &slack) >= 0);
  swLoadDesc tight = sw_test_load(SW_LOAD_FORCE, 0, -1, 0, 0, -T1);
  tight.signal = sw_test_table(4, tt, vt);
  assert_true(sw_spec_add_load(s, &tight) >= 0);
  swObstacleDesc o;
  sw_obstacle_desc_init(&o);
  o.name = "post";
  o.shape = SW_OBSTACLE_CYLINDER;
  o.radius = CYL_R;
  o.axis[0] = 0, o.axis[1] = 1, o.axis[2] = 0;
  o.stiffness = 1e4; /* 20 um under an element's 0.17 N */
  o.damping = 0.02;
  o.static_friction = o.kinetic_friction = mu;
  assert_int_equal(sw_spec_add_obstacle(s, &o), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  return m;
}

/* Where the rope meets the cylinder on the slack side: its top node for
 * theta = pi/2 (the slack end runs along the top), the node a quarter
 * turn from the top for pi. */
static int slack_node(double theta) {
  const double arc = theta < 2 ? 0.0 : 0.5 * M_PI * CYL_R;
  return NROPE / 2 - (int)lround(arc / (ROPE_L / NROPE));
}

static const double RAMP = 0.16;

/* The capstan's ratio for a rope of radius ROPE_R whose friction acts at
 * its surface on the drum of radius CYL_R (see the top). */
static double capstan_ratio(double mu, double theta) {
  return exp(mu * theta * CYL_R / (CYL_R + ROPE_R));
}

/* The ratio T2/T1 at which the rope slides, T2 ramped from T1 to 1.6
 * capstan_ratio T1 over RAMP after SETTLE: where the slack node has moved
 * by 0.1 mm (the slack end holds until the whole wrap slips). */
static double capstan_threshold(double mu, double theta) {
  const double top = 1.6 * capstan_ratio(mu, theta);
  swModel *m = capstan_scene(mu, theta, top, RAMP);
  swData *d = sw_data_new(m);
  const int watch = m->node_adr[0] + slack_node(theta);
  while (d->time < SETTLE) assert_int_equal(sw_steps(m, d, 10), SW_OK);
  double x0[3], x[3];
  sw_get3(m, d->x, watch, x0);
  double ratio = NAN;
  while (d->time < SETTLE + RAMP) {
    assert_int_equal(sw_steps(m, d, 10), SW_OK);
    sw_get3(m, d->x, watch, x);
    double dx[3];
    sw_v3_sub(dx, x, x0);
    if (sw_v3_norm(dx) > 1e-4) {
      ratio = 1.0 + (top - 1.0) * (d->time - SETTLE) / RAMP;
      break;
    }
  }
  fprintf(stderr, "# capstan mu %.2f theta %.4f: slides at T2/T1 = %.4f, exp(mu theta R / (R + r)) = "
          "%.4f, exp(mu theta) = %.4f (%d contacts, %d stuck, %d slipping)\n", mu, theta, ratio,
          capstan_ratio(mu, theta), exp(mu * theta),
          d->obstacle_contacts, d->obstacle_stuck, d->obstacle_slipping);
  sw_data_free(d);
  sw_model_free(m);
  return ratio;
}

static void threshold_case(double mu, double theta) {
  char what[96];
  snprintf(what, sizeof what, "capstan threshold T2/T1, mu %.1f, theta %.3f", mu, theta);
  SW_EXPECT_REL(what, capstan_threshold(mu, theta), capstan_ratio(mu, theta), 0.05);
}

static void test_capstan_threshold(void **state) {
  (void)state;
  threshold_case(0.2, 0.5 * M_PI);
  threshold_case(0.2, M_PI);
  threshold_case(0.4, 0.5 * M_PI);
  threshold_case(0.4, M_PI);
}

/* T2/T1 = frac capstan_ratio(mu, theta), reached 10 ms after SETTLE: the ends' largest
 * displacement over [t1, t1 + 0.02] and [t1, t1 + 0.04], t1 = SETTLE + 0.06 s. */
static double capstan_creep(double mu, double theta, double frac) {
  swModel *m = capstan_scene(mu, theta, frac * capstan_ratio(mu, theta), 0.01);
  swData *d = sw_data_new(m);
  const int a = m->node_adr[0], b = a + NROPE;
  const double t1 = SETTLE + 0.06;
  while (d->time < t1) assert_int_equal(sw_steps(m, d, 10), SW_OK);
  double xa[3], xb[3], ya[3], yb[3], da[3], db[3];
  sw_get3(m, d->x, a, xa);
  sw_get3(m, d->x, b, xb);
  double creep = 0, half = 0;
  while (d->time < t1 + 0.04) {
    assert_int_equal(sw_steps(m, d, 10), SW_OK);
    sw_get3(m, d->x, a, ya);
    sw_get3(m, d->x, b, yb);
    sw_v3_sub(da, ya, xa);
    sw_v3_sub(db, yb, xb);
    creep = fmax(creep, fmax(sw_v3_norm(da), sw_v3_norm(db)));
    if (d->time < t1 + 0.02) half = creep;
  }
  fprintf(stderr, "# capstan mu %.2f theta %.4f at %.2f of its ratio: ends moved %.3g m over "
          "20 ms, %.3g m over 40 ms (%d stuck, %d slipping)\n", mu, theta, frac, half, creep,
          d->obstacle_stuck, d->obstacle_slipping);
  sw_data_free(d);
  sw_model_free(m);
  return creep;
}

static void test_capstan_holds(void **state) {
  (void)state;
  SW_EXPECT_ABS("capstan creep of the ends over 40 ms at 0.85 of the ratio, m",
                capstan_creep(0.3, M_PI, 0.85), 0.0, 1e-6);
  assert_true(capstan_creep(0.3, M_PI, 1.15) > 0.01); /* above the threshold it runs away */
}

/* ---- 2. a rod on an inclined plane ---- */

static const double G = 9.81, MU_S = 0.5, MU_K = 0.3;

/* A rod of 2 cm along the slope of a box face tilted by alpha about y
 * (the face through the origin), under gravity.  Returns the model. */
static swModel *incline_scene(double alpha) {
  swSpec *s = sw_spec_new();
  const double n[3] = {-sin(alpha), 0, cos(alpha)}, t[3] = {cos(alpha), 0, sin(alpha)};
  const double r = 1e-3, L = 0.02;
  double start[3];
  for (int k = 0; k < 3; k++) start[k] = -0.5 * L * t[k] + (r + 1e-7) * n[k];
  swRodDesc rod = sw_test_rod("rod", 5, L, r, start, t, NULL);
  rod.density = 1000;
  rod.youngs = 1e7;
  rod.poisson = 0.5;
  assert_int_equal(sw_spec_add_rod(s, &rod), 0);
  const double g[3] = {0, 0, -G};
  sw_spec_set_gravity(s, g);
  swObstacleDesc o = sw_test_slope(n, 0.2, 0.05); /* 40 cm long */
  o.stiffness = 100;
  o.damping = 0.05;
  o.static_friction = MU_S;
  o.kinetic_friction = MU_K;
  assert_int_equal(sw_spec_add_obstacle(s, &o), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  return m;
}

/* The rod's centre of mass and its velocity along the slope. */
static void along_slope(const swModel *m, const swData *d, double alpha, double *X, double *V) {
  const double t[3] = {cos(alpha), 0, sin(alpha)};
  double M = 0, x = 0, v = 0;
  for (int i = 0; i <= m->rod_nelem[0]; i++) {
    double p[3], u[3];
    sw_get3(m, d->x, i, p);
    sw_get3(m, d->v, i, u);
    M += m->mass[i];
    x += m->mass[i] * sw_v3_dot(p, t);
    v += m->mass[i] * sw_v3_dot(u, t);
  }
  *X = x / M, *V = v / M;
}

static void test_incline_sticks(void **state) {
  (void)state;
  const double alpha = atan(0.36);
  swModel *m = incline_scene(alpha);
  swData *d = sw_data_new(m);
  double X0, X1, X2, V;
  while (d->time < 0.1) assert_int_equal(sw_steps(m, d, 20), SW_OK);
  along_slope(m, d, alpha, &X0, &V);
  while (d->time < 0.15) assert_int_equal(sw_steps(m, d, 20), SW_OK);
  along_slope(m, d, alpha, &X1, &V);
  while (d->time < 0.2) assert_int_equal(sw_steps(m, d, 20), SW_OK);
  along_slope(m, d, alpha, &X2, &V);
  fprintf(stderr, "# incline tan %.2f < mu_s %.2f: %d contacts, %d stuck; moved %.3g m over "
          "0.10-0.15 s, %.3g m over 0.15-0.20 s\n", tan(alpha), MU_S, d->obstacle_contacts,
          d->obstacle_stuck, X1 - X0, X2 - X1);
  assert_int_equal(d->obstacle_stuck, d->obstacle_contacts);
  SW_EXPECT_ABS("incline below mu_s: creep over 0.1 s (m)", fabs(X2 - X0), 0.0, 1e-7);
  sw_data_free(d);
  sw_model_free(m);
}

static void test_incline_slides(void **state) {
  (void)state;
  const double alpha = atan(0.70);
  swModel *m = incline_scene(alpha);
  swData *d = sw_data_new(m);
  double X, V1, V2, t1, t2;
  while (d->time < 0.05) assert_int_equal(sw_steps(m, d, 20), SW_OK);
  along_slope(m, d, alpha, &X, &V1);
  t1 = d->time;
  while (d->time < 0.15) assert_int_equal(sw_steps(m, d, 20), SW_OK);
  along_slope(m, d, alpha, &X, &V2);
  t2 = d->time;
  assert_int_equal(d->obstacle_slipping, d->obstacle_contacts);
  /* down the slope: -t */
  SW_EXPECT_REL("incline above mu_s: acceleration down the slope (m/s^2)", -(V2 - V1) / (t2 - t1),
                G * (sin(alpha) - MU_K * cos(alpha)), 0.01);
  sw_data_free(d);
  sw_model_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_capstan_threshold), cmocka_unit_test(test_capstan_holds),
      cmocka_unit_test(test_incline_sticks),    cmocka_unit_test(test_incline_slides),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
