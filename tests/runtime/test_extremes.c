/* test_extremes.c — the step at the edges of what users build: stiffness
 * ratios of 10^6 in one scene, radii from 10 um to 10 cm, 2 to 2000
 * elements, no damping and overwhelming damping, very long runs and very
 * fast spin.
 *
 * Design.  Each scene runs at 0.5x and 0.9x its own stable step estimate
 * (sw_stable_dt) and must stay bounded; at 2x it must be caught
 * (SW_EUNSTABLE, with the rod named).  "Bounded" is judged against the
 * energy the scene started with: position Verlet conserves a shadow
 * energy, which near the limit differs from the true one by a factor of
 * several (for an oscillator at h w = 1.8 the potential energy is weighed by
 * 1 - (h w)^2 / 4 = 0.19), so a bounded run keeps its energy within 10x of
 * the start, and without a trend: the largest deviation in the last quarter
 * of the run is no more than twice that of the first quarter.  Scenes start
 * with small random velocities on every node and element, which excite all
 * modes, the fastest included.  Damping is checked against closed forms: a
 * freely translating rod with analytic damping slows as exp(-c t) to
 * rounding, whatever c dt, and under gravity creeps at g / c. */
#include "testutil.h"

/* Small random velocities on every node and angular velocities on every
 * element (the draws in slot order, from a fixed seed). */
static void perturb(const swModel *m, swData *d, double v, double w) {
  unsigned seed = 2024;
  for (int r = 0; r < m->nrod; r++)
    for (int i = 0; i <= m->rod_nelem[r]; i++)
      for (int k = 0; k < 3; k++) {
        seed = seed * 1103515245u + 12345u;
        SW_AT(m, d->v, m->node_adr[r] + i, k) += v * ((double)(seed >> 8) / (1u << 24) - 0.5);
        if (i == m->rod_nelem[r]) continue;
        seed = seed * 1103515245u + 12345u;
        SW_AT(m, d->omega, m->elem_adr[r] + i, k) += w * ((double)(seed >> 8) / (1u << 24) - 0.5);
      }
}

/* kinetic + elastic - work done on the scene (constant for a conservative
 * scene, and for a damped one whose losses are booked as work) */
static double balance(const swModel *m, swData *d) {
  double e[3];
  sw_energy(m, d, e);
  return e[0] + e[1] - e[2];
}

typedef struct {
  int rc;            /* of the run                                    */
  long steps;        /* taken                                         */
  double first, last; /* largest |E - E0| / E0 in the first and last quarter */
  double worst;      /* largest E / E0                                */
} Outcome;

/* `steps` steps, the balance checked every `every`. */
static Outcome run_watch(const swModel *m, swData *d, long steps, long every) {
  Outcome o = {SW_OK, 0, 0, 0, 0};
  const double e0 = balance(m, d);
  for (long k = 0; k < steps && o.rc == SW_OK; k += every) {
    o.rc = sw_steps(m, d, every);
    const double e = balance(m, d), dev = fabs(e - e0) / e0;
    if (!isfinite(e)) o.rc = SW_EUNSTABLE;
    if (k < steps / 4 && dev > o.first) o.first = dev;
    if (k >= steps - steps / 4 && dev > o.last) o.last = dev;
    if (e / e0 > o.worst) o.worst = e / e0;
  }
  o.steps = d->step;
  return o;
}

/* One scene at 0.5x, 0.9x (bounded) and 2x (caught) of its estimate.
 * `build` adds the scene's rods, joints and conditions to s. */
typedef void (*Build)(swSpec *s, const void *arg);

static void ladder(const char *label, Build build, const void *arg, long steps) {
  const double fracs[] = {0.5, 0.9, 2.0};
  for (int f = 0; f < 3; f++) {
    swSpec *s = sw_spec_new();
    build(s, arg);
    swModel *m = sw_test_compile_at(s, fracs[f]);
    sw_spec_free(s);
    swData *d = sw_data_new(m);
    perturb(m, d, 1e-4, 1e-3);
    const long every = steps / 40 > 0 ? steps / 40 : 1;
    Outcome o = run_watch(m, d, steps, every);
    fprintf(stderr, "# %s at %.1fx the estimate (dt %.3g s): %s after %ld steps; energy "
            "at most %.3g x the start, drift %.2e in the first quarter, %.2e in the last%s%s\n",
            label, fracs[f], m->dt, o.rc == SW_OK ? "bounded" : "unstable", o.steps, o.worst,
            o.first, o.last, o.rc == SW_OK ? "" : ": ", o.rc == SW_OK ? "" : d->error);
    if (fracs[f] < 1) {
      assert_int_equal(o.rc, SW_OK);
      assert_true(o.worst < 10.0);
      assert_true(o.last <= 2.0 * o.first + 1e-6); /* below 1e-6: round-off */
    } else {
      assert_int_equal(o.rc, SW_EUNSTABLE);
      assert_non_null(strstr(d->error, "rod '"));
      assert_non_null(strstr(d->error, "stable dt estimate"));
    }
    sw_data_free(d);
    sw_model_free(m);
  }
}

typedef struct {
  double radius, length, youngs;
  int n;
} RodArg;

static swRodDesc rod_desc(const char *name, const RodArg *a, double y0) {
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = name;
  r.nelem = a->n;
  r.length = a->length;
  r.radius_start = r.radius_end = a->radius;
  r.density = 1000;
  r.youngs = a->youngs;
  r.start[1] = y0;
  r.direction[0] = 1, r.direction[1] = 0, r.direction[2] = 0;
  r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
  return r;
}

/* a free rod */
static void build_rod(swSpec *s, const void *arg) {
  swRodDesc r = rod_desc("fibre", arg, 0);
  sw_spec_add_rod(s, &r);
}

/* Radii from 10 um to 10 cm and 2 to 2000 elements (element length over
 * radius from 1e4 to 0.001), 0.2 m long, E = 1 MPa. */
static void test_sizes(void **state) {
  (void)state;
  const double radii[] = {1e-5, 1e-3, 1e-1};
  const int counts[] = {2, 20, 2000};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      if (sw_test_sanitized() && counts[j] > 20) continue;
      RodArg a = {radii[i], 0.2, 1e6, counts[j]};
      char label[96];
      snprintf(label, sizeof label, "rod of radius %g m, %d elements", radii[i], counts[j]);
      ladder(label, build_rod, &a, counts[j] > 20 ? 2000 : 20000);
    }
}

/* A soft rod (E = 10 kPa) hanging from a stiff one (E = 10 GPa) by a
 * spherical joint: a stiffness ratio of 10^6 in one scene, the joint's
 * damping booked as work. */
static void build_pair(swSpec *s, const void *arg) {
  (void)arg;
  RodArg stiff = {0.005, 0.2, 1e10, 10}, soft = {0.005, 0.2, 1e4, 10};
  swRodDesc a = rod_desc("stiff", &stiff, 0), b = rod_desc("soft", &soft, 0);
  b.start[0] = 0.2;
  int ra = sw_spec_add_rod(s, &a), rb = sw_spec_add_rod(s, &b);
  swJointDesc j;
  sw_joint_desc_init(&j);
  j.name = "link";
  j.rod_a = ra, j.node_a = -1;
  j.rod_b = rb, j.node_b = 0;
  sw_spec_add_joint(s, &j);
}

static void test_stiffness_ratio(void **state) {
  (void)state;
  ladder("E ratio 1e6 across a joint", build_pair, NULL, sw_test_sanitized() ? 4000 : 20000);
}

/* A free rod in uniform translation with analytic damping: no deformation,
 * so every node slows as dv/dt = -c v with c = gamma / (rho A), and the
 * kick integrates that exactly: v_k = v0 exp(-c k dt) to rounding, whatever
 * c dt.  Here c dt = 50.  Under gravity the same rod creeps at g / c. */
static void test_overwhelming_damping(void **state) {
  (void)state;
  for (int gravity = 0; gravity <= 1; gravity++) {
    swSpec *s = sw_spec_new();
    RodArg a = {0.01, 0.5, 1e6, 20};
    swRodDesc r = rod_desc("syrup", &a, 0);
    r.damping = SW_DAMP_ANALYTIC;
    const double rhoA = 1000 * M_PI * 1e-4;
    sw_spec_add_rod(s, &r); /* undamped: its elastic estimate sets dt */
    swModel *m0 = sw_test_compile(s);
    const double dt = 0.9 * sw_stable_dt(m0), c = 50 / dt;
    sw_model_free(m0);
    sw_spec_free(s);
    s = sw_spec_new();
    r.gamma = c * rhoA;
    sw_spec_add_rod(s, &r);
    sw_spec_set_dt(s, dt);
    const double g[3] = {0, 0, -9.81};
    if (gravity) sw_spec_set_gravity(s, g);
    swModel *m = sw_test_compile(s);
    sw_spec_free(s);
    swData *d = sw_data_new(m);
    for (int i = 0; i <= m->rod_nelem[0]; i++) SW_AT(m, d->v, i, 1) = 1.0;
    if (!gravity) {
      assert_int_equal(sw_steps(m, d, 10), SW_OK);
      double worst = 0;
      const double ref = exp(-c * 10 * dt);
      for (int i = 0; i <= m->rod_nelem[0]; i++)
        worst = fmax(worst, fabs(SW_AT(m, d->v, i, 1) - ref) / ref);
      fprintf(stderr, "# %s: c dt = 50, speed after 10 steps %.6e m/s (exp(-c t) = %.6e), largest "
              "relative error %.2e (tol 1e-12)\n", __func__, SW_AT(m, d->v, 0, 1), ref, worst);
      assert_true(worst < 1e-12);
    } else {
      assert_int_equal(sw_steps(m, d, 1000), SW_OK);
      const double creep = 9.81 / c; /* terminal velocity a / c */
      double worst = 0;
      for (int i = 0; i <= m->rod_nelem[0]; i++)
        worst = fmax(worst, fabs(-SW_AT(m, d->v, i, 2) - creep) / creep);
      fprintf(stderr, "# %s: under gravity the rod creeps at %.9e m/s (g / c = %.9e), largest "
              "relative error %.2e (tol 1e-9)\n", __func__, -SW_AT(m, d->v, 0, 2), creep, worst);
      assert_true(worst < 1e-9);
    }
    sw_data_free(d);
    sw_model_free(m);
  }
}

/* Largest |Q Q^T - I| over the rod's elements. */
static double orthonormality(const swModel *m, const swData *d) {
  double worst = 0;
  for (int e = 0; e < m->rod_nelem[0]; e++) {
    double Q[9];
    sw_getQ(m, d->Q, e, Q);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        worst = fmax(worst, fabs(Q[3 * i] * Q[3 * j] + Q[3 * i + 1] * Q[3 * j + 1] +
                                 Q[3 * i + 2] * Q[3 * j + 2] - (i == j)));
  }
  return worst;
}

/* 10^7 steps of an undamped free rod (10^6 under the sanitizers): the
 * energy stays bounded with no trend (position Verlet is symplectic). */
static void test_long_run(void **state) {
  (void)state;
  const long steps = sw_test_sanitized() ? 1000000 : 10000000;
  swSpec *s = sw_spec_new();
  RodArg a = {0.01, 0.2, 1e6, 4};
  swRodDesc r = rod_desc("marathon", &a, 0);
  sw_spec_add_rod(s, &r);
  swModel *m = sw_test_compile_at(s, 0.9);
  sw_spec_free(s);
  swData *d = sw_data_new(m);
  perturb(m, d, 1e-3, 1e-2);
  Outcome o = run_watch(m, d, steps, 1000);
  const double ortho = orthonormality(m, d);
  fprintf(stderr, "# %s: %ld steps at 0.9x the estimate: largest relative energy deviation %.3e "
          "in the first quarter, %.3e in the last (tol: at most 2x the first, and 0.05); "
          "directors orthonormal to %.2e\n", __func__, o.steps, o.first, o.last, ortho);
  assert_int_equal(o.rc, SW_OK);
  assert_true(o.last <= 2.0 * o.first && o.last < 0.05);
  assert_true(ortho < 1e-12);
  sw_data_free(d);
  sw_model_free(m);
}

/* A rod spinning about its own axis at 1000 rad/s (a principal axis, so no
 * inertial couple: it turns at that rate exactly), and a short stiff rod
 * tumbling end over end at 1000 rad/s: the directors stay orthonormal to
 * 1e-12, and the spinning one has turned by w t. */
static void test_spin(void **state) {
  (void)state;
  const double W = 1000;
  for (int tumble = 0; tumble <= 1; tumble++) {
    swSpec *s = sw_spec_new();
    RodArg a = tumble ? (RodArg){0.001, 0.02, 1e10, 10} : (RodArg){0.01, 0.2, 1e6, 20};
    swRodDesc r = rod_desc(tumble ? "tumbler" : "spinner", &a, 0);
    r.start[0] = tumble ? -0.01 : 0;
    sw_spec_add_rod(s, &r);
    swModel *m = sw_test_compile_at(s, 0.9);
    sw_spec_free(s);
    swData *d = sw_data_new(m);
    const int n = m->rod_nelem[0];
    for (int e = 0; e < n; e++) SW_AT(m, d->omega, e, tumble ? 0 : 2) = W; /* material frame */
    if (tumble) /* d1 along z: turning about d1 moves the nodes along y, v = W x z */
      for (int i = 0; i <= n; i++) SW_AT(m, d->v, i, 1) = W * SW_AT(m, d->x, i, 0);
    const double turns = tumble ? 200 : 2000; /* rad */
    const long steps = (long)(turns / (W * m->dt)) + 1;
    assert_int_equal(sw_steps(m, d, steps), SW_OK);
    const double ortho = orthonormality(m, d);
    if (!tumble) {
      /* d1 starts along z and turns about d3 = x */
      double worst = 0, Q[9];
      const double th = W * d->time;
      for (int e = 0; e < n; e++) {
        sw_getQ(m, d->Q, e, Q);
        worst = fmax(worst, fabs(Q[2] - cos(th)) + fabs(fabs(Q[1]) - fabs(sin(th))));
      }
      fprintf(stderr, "# %s: spun about its axis at %g rad/s for %ld steps (%.0f rad): directors "
              "orthonormal to %.2e (tol 1e-12), angle off w t by %.2e (tol 1e-9)\n", __func__, W,
              steps, th, ortho, worst);
      assert_true(worst < 1e-9);
    } else {
      fprintf(stderr, "# %s: tumbling end over end at %g rad/s for %ld steps: directors "
              "orthonormal to %.2e (tol 1e-12)\n", __func__, W, steps, ortho);
    }
    assert_true(ortho < 1e-12);
    sw_data_free(d);
    sw_model_free(m);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_sizes),
      cmocka_unit_test(test_stiffness_ratio),
      cmocka_unit_test(test_overwhelming_damping),
      cmocka_unit_test(test_long_run),
      cmocka_unit_test(test_spin),
  };
  return cmocka_run_group_tests_name("extremes", tests, NULL, NULL);
}
