/* test_rigid.c — rigid rods (rigid.c) against closed forms: free fall of a
 * spinning rigid bone (X0 + V0 t + g t^2/2 and a shape that never drifts),
 * a rigid bone swinging on a hinge (period of the physical pendulum, and the
 * elastic bone doing the same), torque-free tumbling of an asymmetric body
 * (energy and angular momentum over many flips of the intermediate axis),
 * the order of the rotation scheme under an orientation-dependent torque,
 * linear damping, the energy balance of an elastic rod and a rigid rod
 * joined by joints, a clamped rigid rod holding an elastic one, the stable
 * time step of a scene with a stiff bone elastic and rigid (and the rigid
 * body's joint bound against the step at which it really blows up), and the
 * validation messages (exact text).
 *
 * Design.  Scenes are built through the public API only (swRodDesc.rigid,
 * sw_rigid_set_motion), so these are also the examples of how a rigid rod is
 * declared.  The long runs shrink under SW_SANITIZED (testutil.h). */
#include <hdf5.h>
#include <time.h>
#include <unistd.h>

#include "testutil.h"

static const double GRAV = 9.81;

/* The bone of docs: E = 15 GPa, density 1750 kg/m^3, L = 0.34 m, r = 10.5 mm,
 * 20 elements (a humerus). */
static const double BE = 15e9, BRHO = 1750, BL = 0.34, BR = 0.0105;
static const int BN = 20;

/* ---- helpers ---- */

static double norm3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

static double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double dist(const double *a, const double *b) {
  double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return norm3(d);
}

static swRodDesc rod_along(const char *name, int n, double length, double radius,
                           const double start[3], const double dir[3]) {
  return sw_test_rod(name, n, length, radius, start, dir, NULL);
}

static swRodDesc bone(const char *name, int n, const double start[3], const double dir[3],
                      int rigid) {
  swRodDesc r = rod_along(name, n, BL, BR, start, dir);
  r.youngs = BE;
  r.density = BRHO;
  r.rigid = rigid;
  return r;
}

static swJointDesc joint_of(const char *name, swJointKind kind, int rod_a, int node_a, int rod_b,
                            int node_b) {
  swJointDesc j;
  sw_joint_desc_init(&j);
  j.name = name;
  j.kind = kind;
  j.rod_a = rod_a;
  j.node_a = node_a;
  j.rod_b = rod_b;
  j.node_b = node_b;
  return j;
}

/* Centre of mass, linear and angular momentum (about the centre of mass) of
 * rod r from its nodes and elements, independently of the body state. */
static void rod_momenta(const swModel *m, const swData *d, int r, double X[3], double p[3],
                        double L[3]) {
  const int n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
  double M = 0;
  memset(X, 0, 3 * sizeof *X);
  memset(p, 0, 3 * sizeof *p);
  memset(L, 0, 3 * sizeof *L);
  for (int i = na; i <= na + n; i++) {
    M += m->mass[i];
    for (int k = 0; k < 3; k++) {
      X[k] += m->mass[i] * SW_AT(m, d->x, i, k);
      p[k] += m->mass[i] * SW_AT(m, d->v, i, k);
    }
  }
  for (int k = 0; k < 3; k++) X[k] /= M;
  for (int i = na; i <= na + n; i++) {
    double x[3], v[3];
    sw_get3(m, d->x, i, x);
    sw_get3(m, d->v, i, v);
    double rel[3] = {x[0] - X[0], x[1] - X[1], x[2] - X[2]};
    L[0] += m->mass[i] * (rel[1] * v[2] - rel[2] * v[1]);
    L[1] += m->mass[i] * (rel[2] * v[0] - rel[0] * v[2]);
    L[2] += m->mass[i] * (rel[0] * v[1] - rel[1] * v[0]);
  }
  for (int e = ea; e < ea + n; e++)
    for (int a = 0; a < 3; a++) {
      double h = SW_AT(m, m->inertia, e, a) * SW_AT(m, d->omega, e, a) / d->dilatation[e];
      for (int k = 0; k < 3; k++) L[k] += SW_AT(m, d->Q, e, 3 * a + k) * h;
    }
}

/* Largest relative change of any distance between two nodes of rod r from
 * its value at t = 0, and largest misalignment of an element's d3 with its
 * nodes' difference (the frames ride with the body). */
static void shape_error(const swModel *m, const swData *d, int r, double *dist_err,
                        double *frame_err) {
  const int n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
  *dist_err = *frame_err = 0;
  for (int i = na; i <= na + n; i++)
    for (int j = i + 1; j <= na + n; j++) {
      double x0i[3], x0j[3], xi[3], xj[3];
      sw_get3(m, m->x0, i, x0i);
      sw_get3(m, m->x0, j, x0j);
      sw_get3(m, d->x, i, xi);
      sw_get3(m, d->x, j, xj);
      double l0 = dist(x0i, x0j), l = dist(xi, xj);
      *dist_err = fmax(*dist_err, fabs(l - l0) / l0);
    }
  for (int e = 0; e < n; e++) {
    double a[3], b[3], Q[9];
    sw_get3(m, d->x, na + e, a);
    sw_get3(m, d->x, na + e + 1, b);
    sw_getQ(m, d->Q, ea + e, Q);
    double t[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, l = norm3(t);
    for (int k = 0; k < 3; k++) *frame_err = fmax(*frame_err, fabs(Q[6 + k] - t[k] / l));
  }
}

/* ---- 1. free fall ---- */

/* A rigid bone, oblique, thrown with V0 and spun with w0 under gravity: its
 * centre of mass follows X0 + V0 t + g t^2/2, which both schemes integrate
 * exactly (a quadratic in t), its angular momentum stays L0 (gravity has no
 * moment about X), and it keeps its shape exactly while it turns. */
static void free_fall(swIntegrator integ) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0.1, -0.2, 1.0}, dir[3] = {1, 0.3, 0.2};
  swRodDesc r = bone("humerus", BN, o, dir, 1);
  sw_spec_add_rod(s, &r);
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, integ);
  sw_spec_set_dt(s, 1e-4);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double V0[3] = {0.1, -0.2, 0.5}, w0[3] = {3.0, -1.0, 2.0};
  assert_int_equal(sw_rigid_set_motion(m, d, 0, V0, w0), SW_OK);
  double X0[3], p0[3], L0[3];
  rod_momenta(m, d, 0, X0, p0, L0);
  const long steps = sw_test_sanitized() ? 2000 : 20000;
  assert_int_equal(sw_steps(m, d, steps), SW_OK);
  double t = d->time, X[3], p[3], L[3], ref[3], err = 0, dX = 0, dL = 0, dist_err, frame_err;
  rod_momenta(m, d, 0, X, p, L);
  for (int k = 0; k < 3; k++) {
    ref[k] = X0[k] + V0[k] * t + 0.5 * g[k] * t * t;
    err = fmax(err, fabs(d->rigid_X[k] - ref[k]));
    dX = fmax(dX, fabs(X[k] - d->rigid_X[k]));
    dL = fmax(dL, fabs(L[k] - L0[k]) / norm3(L0));
  }
  shape_error(m, d, 0, &dist_err, &frame_err);
  const char *name = integ == SW_PEFRL ? "PEFRL" : "Verlet";
  fprintf(stderr, "# %s (%s): %ld steps to t = %.3g s, fell %.4g m, turned by about %.3g rad\n",
          __func__, name, d->step, t, dist(ref, X0), norm3(w0) * t);
  SW_EXPECT_ABS("|X - (X0 + V0 t + g t^2/2)| (m)", err, 0.0, 1e-12 * (double)steps);
  SW_EXPECT_ABS("|centre of mass of the nodes - X| (m)", dX, 0.0, 1e-13);
  SW_EXPECT_ABS("|L - L0| / |L0| (from nodes and elements)", dL, 0.0, 1e-12);
  SW_EXPECT_ABS("largest relative change of a node distance", dist_err, 0.0, 1e-12);
  SW_EXPECT_ABS("largest |d3 - unit(x_{i+1} - x_i)|", frame_err, 0.0, 1e-12);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_free_fall(void **state) {
  (void)state;
  free_fall(SW_VERLET);
  free_fall(SW_PEFRL);
}

/* A constant lab couple on one element of a free rigid bone (no gravity):
 * the element couple is turned into the body's torque, so L = tau t exactly
 * and V stays 0, whatever the body does meanwhile; the couple's work is
 * booked, kinetic - work = 0 up to the scheme's error. */
static void test_couple(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, dir[3] = {0.5, 1, -0.2}, tau[3] = {0.01, -0.02, 0.005};
  swRodDesc r = bone("humerus", BN, o, dir, 1);
  sw_spec_add_rod(s, &r);
  swLoadDesc c = sw_test_load(SW_LOAD_TORQUE, 0, 3, tau[0], tau[1], tau[2]);
  sw_spec_add_load(s, &c);
  sw_spec_set_dt(s, 1e-4);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  sw_test_run_to(m, d, sw_test_sanitized() ? 0.1 : 0.5);
  double errL = 0, e[3];
  for (int k = 0; k < 3; k++) errL = fmax(errL, fabs(d->rigid_L[k] - tau[k] * d->time));
  sw_energy(m, d, e);
  fprintf(stderr, "# %s: t = %.3g s, |w| = %.4g rad/s, kinetic %.6g J, work %.6g J\n", __func__,
          d->time, norm3(d->rigid_omega), e[0], e[2]);
  SW_EXPECT_ABS("|L - tau t| / |tau t|", errL / (norm3(tau) * d->time), 0.0, 1e-12);
  SW_EXPECT_ABS("|V| (m/s)", norm3(d->rigid_V), 0.0, 1e-15);
  SW_EXPECT_REL("kinetic energy vs work of the couple (J)", e[0], e[2], 1e-4);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 2. physical pendulum ---- */

/* The bone hung by its start on an anchored hinge (axis y) at the origin,
 * released at 5 degrees from the vertical in the x-z plane. */
static const double PTHETA0 = 5.0 * M_PI / 180.0;

/* Small-amplitude period 2 pi sqrt(I_pivot / (M g d)), d = L/2, with
 * I_pivot of the continuous rod M (L^2/3 + r^2/4), or (n > 0) of the lumped
 * node masses, M L^2 (1/3 + 1/(6 n^2)) + M r^2/4; times the finite-amplitude
 * series 1 + theta0^2/16 + 11 theta0^4/3072 when `amplitude`. */
static double pendulum_period(int n, int amplitude) {
  double I_over_M = BL * BL / 3.0 + BR * BR / 4.0;
  if (n > 0) I_over_M += BL * BL / (6.0 * n * n);
  double T0 = 2 * M_PI * sqrt(I_over_M / (GRAV * BL / 2.0)), t2 = PTHETA0 * PTHETA0;
  return amplitude ? T0 * (1 + t2 / 16.0 + 11.0 * t2 * t2 / 3072.0) : T0;
}

/* Runs the pendulum until the tip has crossed x = 0 `want` times; returns
 * the time between the first and the last crossing. */
static double swing(int rigid, int n, int want, double *dt, long *steps, double *wall) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, dir[3] = {sin(PTHETA0), 0, -cos(PTHETA0)};
  swRodDesc r = bone("humerus", n, o, dir, rigid);
  sw_spec_add_rod(s, &r);
  swJointDesc j = joint_of("shoulder", SW_JOINT_HINGE, 0, 0, -1, 0);
  j.axis[1] = 1;
  j.undamped = 1;
  sw_spec_add_joint(s, &j);
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);
  const double *tipx = &SW_AT(m, d->x, m->node_adr[0] + n, 0);
  double t[8], prev = *tipx, tprev = d->time;
  int nc = 0;
  struct timespec a, b;
  clock_gettime(CLOCK_MONOTONIC, &a);
  while (nc < want && d->time < 2.0 * want) {
    assert_int_equal(sw_step(m, d), SW_OK);
    if ((prev > 0) != (*tipx > 0)) {
      double f = prev / (prev - *tipx);
      t[nc++] = tprev + f * (d->time - tprev);
    }
    prev = *tipx;
    tprev = d->time;
  }
  clock_gettime(CLOCK_MONOTONIC, &b);
  assert_int_equal(nc, want);
  *dt = m->dt;
  *steps = d->step;
  *wall = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return t[want - 1] - t[0];
}

static void test_pendulum(void **state) {
  (void)state;
  const int san = sw_test_sanitized(), n = san ? 10 : BN;
  /* crossings at T/4, 3T/4, 5T/4: a whole period from three (half from two) */
  const int want = san ? 2 : 3;
  double dt_r, dt_e, wall_r, wall_e;
  long steps_r, steps_e;
  double Tr = swing(1, n, want, &dt_r, &steps_r, &wall_r) / (0.5 * (want - 1));
  double Te = swing(0, n, want, &dt_e, &steps_e, &wall_e) / (0.5 * (want - 1));
  fprintf(stderr, "# %s: rigid bone: dt = %.3g s, %ld steps, %.3g s wall; elastic bone: "
                  "dt = %.3g s, %ld steps, %.3g s wall\n",
          __func__, dt_r, steps_r, wall_r, dt_e, steps_e, wall_e);
  SW_EXPECT_REL("rigid: period vs 2 pi sqrt(I_pivot / (M g d)) (s)", Tr, pendulum_period(0, 0),
                1e-2);
  SW_EXPECT_REL("rigid: period vs the lumped bone at 5 degrees (s)", Tr, pendulum_period(n, 1),
                1e-4);
  SW_EXPECT_REL("elastic: period vs the lumped bone at 5 degrees (s)", Te, pendulum_period(n, 1),
                1e-4);
  SW_EXPECT_REL("rigid period vs elastic period (s)", Tr, Te, 1e-4);
  assert_true(dt_r > 5 * dt_e);
}

/* ---- 3. torque-free tumbling of an asymmetric body ---- */

/* A half ring of radius 0.1 m (24 elements, r = 5 mm) in the x-y plane:
 * three distinct principal moments. */
static swModel *half_ring(swSpec **sout, swIntegrator integ, double dt, int with_load) {
  enum { N = 24 };
  const double Ra = 0.1;
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "ring";
  r.nelem = N;
  r.length = M_PI * Ra;
  r.radius_start = r.radius_end = 0.005;
  r.density = 1000;
  r.youngs = 1e9;
  r.rigid = 1;
  int id = sw_spec_add_rod(s, &r);
  double x[3 * (N + 1)], Q[9 * N];
  for (int i = 0; i <= N; i++) {
    double phi = M_PI * i / N;
    x[3 * i] = Ra * cos(phi), x[3 * i + 1] = Ra * sin(phi), x[3 * i + 2] = 0;
  }
  for (int i = 0; i < N; i++) {
    double t[3] = {x[3 * i + 3] - x[3 * i], x[3 * i + 4] - x[3 * i + 1], 0}, l = norm3(t);
    double *q = Q + 9 * i;
    /* d1 = z, d2 = d3 x d1, d3 = tangent */
    q[0] = 0, q[1] = 0, q[2] = 1;
    q[3] = t[1] / l, q[4] = -t[0] / l, q[5] = 0;
    q[6] = t[0] / l, q[7] = t[1] / l, q[8] = 0;
  }
  assert_int_equal(sw_spec_set_rest_shape(s, id, x, Q), SW_OK);
  if (with_load) {
    /* a constant lab force at one end and gravity: a torque that depends
     * on the orientation, and a translation coupled to it through nothing
     * but the shared kicks */
    swLoadDesc f = sw_test_load(SW_LOAD_FORCE, id, 0, 0.02, 0.01, 0.03);
    sw_spec_add_load(s, &f);
    const double g[3] = {0, 0, -GRAV};
    sw_spec_set_gravity(s, g);
  }
  sw_spec_set_integrator(s, integ);
  sw_spec_set_dt(s, dt);
  *sout = s;
  return sw_test_compile(s);
}

/* Body-frame angular velocity of the body of rod 0. */
static void body_omega(const swData *d, double Om[3]) {
  const double *R = d->rigid_R, *w = d->rigid_omega;
  for (int k = 0; k < 3; k++) Om[k] = R[k] * w[0] + R[3 + k] * w[1] + R[6 + k] * w[2];
}

/* Spun mostly about its intermediate axis, the half ring flips over and over
 * (Dzhanibekov).  Angular momentum stays L0 to round-off (every piece of the
 * drift is an exact rotation that keeps lab L), and the energy error of the
 * splitting stays bounded; sw_energy's kinetic energy, summed over nodes and
 * elements, is the body's M V^2/2 + L . w/2. */
static void test_torque_free(void **state) {
  (void)state;
  swSpec *s;
  const double dt = 1e-3;
  swModel *m = half_ring(&s, SW_VERLET, dt, 0);
  swData *d = sw_data_new(m);
  const double *I = m->rigid_inertia;
  fprintf(stderr, "# %s: principal moments %.6g, %.6g, %.6g kg m^2\n", __func__, I[0], I[1], I[2]);
  assert_true(I[1] > 1.1 * I[0] && I[2] > 1.1 * I[1]);
  /* lab w = R0 (0.05, 10, 0.05): mostly the intermediate axis */
  const double Om0[3] = {0.05, 10.0, 0.05}, V0[3] = {0.01, 0, 0};
  double w0[3];
  for (int k = 0; k < 3; k++) w0[k] = m->rigid_R0[3 * k] * Om0[0] + m->rigid_R0[3 * k + 1] * Om0[1] +
                                      m->rigid_R0[3 * k + 2] * Om0[2];
  assert_int_equal(sw_rigid_set_motion(m, d, 0, V0, w0), SW_OK);
  double e[3], X[3], p[3], L0[3], L[3];
  sw_energy(m, d, e);
  const double E0 = e[0];
  rod_momenta(m, d, 0, X, p, L0);
  double M = m->rigid_mass[0], body_ke = 0.5 * M * dot3(V0, V0) +
                                         0.5 * dot3(d->rigid_L, d->rigid_omega);
  SW_EXPECT_REL("sw_energy kinetic vs M V^2/2 + L.w/2 (J)", E0, body_ke, 1e-12);
  SW_EXPECT_ABS("elastic energy of a rigid rod (J)", e[1], 0.0, 0.0);
  const double T = sw_test_sanitized() ? 5.0 : 40.0;
  double dE = 0, dL = 0, Om[3], prev_sign = 1;
  int flips = 0;
  while (d->time < T - 0.5 * dt) {
    assert_int_equal(sw_steps(m, d, 100), SW_OK);
    sw_energy(m, d, e);
    rod_momenta(m, d, 0, X, p, L);
    dE = fmax(dE, fabs(e[0] - E0) / E0);
    for (int k = 0; k < 3; k++) dL = fmax(dL, fabs(L[k] - L0[k]) / norm3(L0));
    body_omega(d, Om);
    if (Om[1] * prev_sign < 0) flips++, prev_sign = -prev_sign;
  }
  double dist_err, frame_err;
  shape_error(m, d, 0, &dist_err, &frame_err);
  fprintf(stderr, "# %s: dt = %.3g s, h |w| = %.3g, %ld steps over %.3g s, %d flips of the "
                  "intermediate axis\n", __func__, dt, dt * norm3(w0), d->step, d->time, flips);
  assert_true(flips >= (sw_test_sanitized() ? 2 : 10));
  SW_EXPECT_ABS("largest |L - L0| / |L0| (from nodes and elements)", dL, 0.0, 1e-12);
  SW_EXPECT_ABS("largest |E - E0| / E0", dE, 0.0, 1e-4);
  SW_EXPECT_ABS("largest relative change of a node distance", dist_err, 0.0, 1e-12);
  /* the energy error is the splitting's, O(h^2): halve dt */
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Order of the schemes on rigid rods: the half ring thrown and spun under
 * gravity and a constant force at one end, to t = 0.5 s, against a run at a
 * 64 times smaller step; position Verlet must converge at order 2 and PEFRL
 * at order 4 (the rotation inside PEFRL's drifts is Yoshida's fourth-order
 * composition). */
static double ring_error(swIntegrator integ, double dt, double Xref[3], double Rref[9], int set) {
  swSpec *s;
  swModel *m = half_ring(&s, integ, dt, 1);
  swData *d = sw_data_new(m);
  const double V0[3] = {0.2, 0, 0.5}, w0[3] = {1.0, 4.0, -2.0};
  assert_int_equal(sw_rigid_set_motion(m, d, 0, V0, w0), SW_OK);
  sw_test_run_to(m, d, 0.5);
  double err = 0;
  if (set) {
    memcpy(Xref, d->rigid_X, 3 * sizeof(double));
    memcpy(Rref, d->rigid_R, 9 * sizeof(double));
  } else {
    for (int k = 0; k < 3; k++) err = fmax(err, fabs(d->rigid_X[k] - Xref[k]));
    for (int k = 0; k < 9; k++) err = fmax(err, 0.1 * fabs(d->rigid_R[k] - Rref[k]));
  }
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return err;
}

static void test_time_order(void **state) {
  (void)state;
  const swIntegrator schemes[2] = {SW_VERLET, SW_PEFRL};
  const double h0[2] = {4e-3, 1e-2}, want[2] = {2.0, 4.0};
  for (int q = 0; q < 2; q++) {
    double Xref[3], Rref[9], err[3];
    ring_error(schemes[q], h0[q] / 64, Xref, Rref, 1);
    for (int k = 0; k < 3; k++) err[k] = ring_error(schemes[q], h0[q] / (1 << k), Xref, Rref, 0);
    fprintf(stderr, "# %s: %s: errors %.3e, %.3e, %.3e at dt = %.3g, %.3g, %.3g s\n", __func__,
            q ? "PEFRL" : "Verlet", err[0], err[1], err[2], h0[q], h0[q] / 2, h0[q] / 4);
    SW_EXPECT_ABS(q ? "PEFRL order" : "Verlet order", sw_test_order(err, 1), want[q], 0.15);
  }
}

/* ---- 4. linear damping ---- */

/* Uniform section: the dissipation is mass-proportional with one rate
 * c = gamma / (rho A), for translation and rotation alike, so V and L decay
 * as exp(-c t); the explicit kick does it to first order in c h. */
static void test_linear_damping(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, dir[3] = {0.2, 1, 0.1};
  swRodDesc r = bone("humerus", BN, o, dir, 1);
  double A = M_PI * BR * BR, c = 5.0;
  r.damping = SW_DAMP_LINEAR;
  r.gamma = c * BRHO * A;
  sw_spec_add_rod(s, &r);
  sw_spec_set_dt(s, 1e-4);
  swModel *m = sw_test_compile(s);
  SW_EXPECT_REL("stable dt of the damped rigid bone (s)", sw_stable_dt(m), 0.95 * 2 / c, 1e-12);
  swData *d = sw_data_new(m);
  const double V0[3] = {1, 0, 0}, w0[3] = {0, 0, 3};
  assert_int_equal(sw_rigid_set_motion(m, d, 0, V0, w0), SW_OK);
  double e[3], E0, L0 = norm3(d->rigid_L);
  sw_energy(m, d, e);
  E0 = e[0];
  sw_test_run_to(m, d, 0.2);
  double decay = exp(-c * d->time), tol = c * c * m->dt * d->time;
  SW_EXPECT_REL("|V| / |V0| vs exp(-c t)", norm3(d->rigid_V), decay, tol);
  SW_EXPECT_REL("|L| / |L0| vs exp(-c t)", norm3(d->rigid_L) / L0, decay, tol);
  sw_energy(m, d, e);
  SW_EXPECT_ABS("|kinetic - work - E0| / E0", fabs(e[0] - e[2] - E0) / E0, 0.0, 1e-3);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 5. energy balance of an elastic rod and a rigid rod joined ---- */

/* A rigid bone hung from the origin on a spherical joint, tilted, and an
 * elastic rod (E = 10 MPa, L = 0.3 m, r = 5 mm, 10 elements) hung from the
 * bone's end on a hinge (axis y), pointing elsewhere: both swing in 3D under
 * gravity.  Kinetic + elastic - work must stay E0, with the joints undamped
 * and with their default damping, whose work is booked. */
static swModel *bone_and_rod(int undamped, int clamped, int rigid_tendon, swIntegrator integ,
                             double dt_frac, swSpec **sout) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, dir_a[3] = {0.3, 0.2, -1}, dir_b[3] = {1, 0, -0.5};
  swRodDesc a = bone("humerus", BN, o, dir_a, 1);
  double end[3];
  for (int k = 0; k < 3; k++) end[k] = BL * dir_a[k] / norm3(dir_a);
  swRodDesc b = rod_along("tendon", 10, 0.3, 0.005, end, dir_b);
  b.youngs = 1e8;
  b.rigid = rigid_tendon;
  b.density = 1100;
  sw_spec_add_rod(s, &a);
  sw_spec_add_rod(s, &b);
  swJointDesc j0 = joint_of("shoulder", SW_JOINT_SPHERICAL, 0, 0, -1, 0);
  swJointDesc j1 = joint_of("elbow", SW_JOINT_HINGE, 0, -1, 1, 0);
  j1.axis[1] = 1;
  j0.undamped = j1.undamped = undamped;
  if (clamped) {
    swBCDesc c = sw_test_clamp(0, 0);
    sw_spec_add_bc(s, &c);
  } else {
    sw_spec_add_joint(s, &j0);
  }
  sw_spec_add_joint(s, &j1);
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, integ);
  *sout = s;
  return sw_test_compile_at(s, dt_frac);
}

/* Returns the largest |kinetic + elastic - work - E0| / largest kinetic. */
static double energy_balance(int undamped, int rigid_tendon, swIntegrator integ, double dt_frac) {
  swSpec *s;
  swModel *m = bone_and_rod(undamped, 0, rigid_tendon, integ, dt_frac, &s);
  swData *d = sw_data_new(m);
  double e[3], e0, worst = 0, kmax = 0;
  sw_energy(m, d, e);
  e0 = e[0] + e[1] - e[2];
  const double T = sw_test_sanitized() ? 0.05 : 0.5;
  while (d->time < T) {
    sw_test_run_to(m, d, d->time + 0.005);
    sw_energy(m, d, e);
    worst = fmax(worst, fabs(e[0] + e[1] - e[2] - e0));
    kmax = fmax(kmax, e[0]);
  }
  fprintf(stderr, "# %s: %s tendon, %s, %s joints, dt = %.3g s, %ld steps, largest kinetic "
                  "energy %.4g J, work done %.4g J, elbow angle %.4f rad: imbalance %.3g of it\n",
          __func__, rigid_tendon ? "rigid" : "elastic", integ == SW_PEFRL ? "PEFRL" : "Verlet",
          undamped ? "undamped" : "damped", m->dt, d->step, kmax, e[2], d->joint_angle[1],
          worst / kmax);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return worst / kmax;
}

/* The elastic tendon's own imbalance (the G18 law is not the gradient of
 * the quadratic energy, docs/physics.md) falls as 1/E and is a few 1e-6 at
 * E = 100 MPa; with the tendon rigid too, what is left is the integrator's
 * error, which falls as dt^2 (Verlet) or dt^4 (PEFRL). */
static void test_energy_chain(void **state) {
  (void)state;
  const char *what = "largest |kinetic + elastic - work - E0| / largest kinetic";
  SW_EXPECT_ABS(what, energy_balance(1, 0, SW_VERLET, 0.9), 0.0, 1e-5);
  SW_EXPECT_ABS(what, energy_balance(0, 0, SW_VERLET, 0.9), 0.0, 1e-5);
  SW_EXPECT_ABS(what, energy_balance(1, 0, SW_PEFRL, 0.9), 0.0, 1e-5);
  double v1 = energy_balance(1, 1, SW_VERLET, 0.5), v2 = energy_balance(1, 1, SW_VERLET, 0.25);
  double p1 = energy_balance(1, 1, SW_PEFRL, 0.5), p2 = energy_balance(1, 1, SW_PEFRL, 0.25);
  SW_EXPECT_ABS(what, fmax(v1, p1), 0.0, 1e-6);
  SW_EXPECT_REL("Verlet: imbalance ratio for dt halved", v1 / v2, 4.0, 0.25);
  SW_EXPECT_REL("PEFRL: imbalance ratio for dt halved", p1 / p2, 16.0, 0.25);
}

/* A clamped rigid bone never moves; the elastic rod hung from it swings, and
 * the balance holds (the clamp does no work on a body that does not move). */
static void test_clamped(void **state) {
  (void)state;
  swSpec *s;
  swModel *m = bone_and_rod(1, 1, 0, SW_VERLET, 0.9, &s);
  assert_int_equal(m->rigid_fixed[0], 1);
  swData *d = sw_data_new(m);
  double e[3], e0;
  sw_energy(m, d, e);
  e0 = e[0] + e[1] - e[2];
  sw_test_run_to(m, d, sw_test_sanitized() ? 0.02 : 0.2);
  double moved = 0;
  for (int i = m->node_adr[0]; i <= m->node_adr[0] + BN; i++)
    for (int k = 0; k < 3; k++)
      moved = fmax(moved, fabs(SW_AT(m, d->x, i, k) - SW_AT(m, m->x0, i, k)));
  sw_energy(m, d, e);
  int tip = m->node_adr[1] + m->rod_nelem[1];
  double xtip[3], x0tip[3];
  sw_get3(m, d->x, tip, xtip);
  sw_get3(m, m->x0, tip, x0tip);
  fprintf(stderr, "# %s: %ld steps, the hung rod's tip moved %.4g m\n", __func__, d->step,
          dist(xtip, x0tip));
  SW_EXPECT_ABS("largest displacement of a node of the clamped rigid bone (m)", moved, 0.0, 0.0);
  SW_EXPECT_ABS("|kinetic + elastic - work - E0| / kinetic", fabs(e[0] + e[1] - e[2] - e0) / e[0],
                0.0, 1e-4);
  assert_int_equal(sw_rigid_set_motion(m, d, 0, (double[3]){0, 0, 0}, (double[3]){0, 0, 0}),
                   SW_EUSAGE);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 6. stable time step ---- */

/* The bone hung from a spherical joint at the shoulder and a soft rod
 * (E = 1 MPa, L = 0.3 m, r = 5 mm, 14 elements, a muscle-like strand) hung
 * from the bone's end on another: elastic, the bone's elements set the step;
 * rigid, they do not, and the step is set by the soft rod or the joints. */
static swModel *arm(int rigid, double dt_frac) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, down[3] = {0, 0, -1}, end[3] = {0, 0, -BL};
  swRodDesc a = bone("humerus", BN, o, down, rigid);
  swRodDesc b = rod_along("strand", 14, 0.3, 0.005, end, down);
  b.youngs = 1e6;
  b.density = 1060;
  sw_spec_add_rod(s, &a);
  sw_spec_add_rod(s, &b);
  swJointDesc j0 = joint_of("shoulder", SW_JOINT_SPHERICAL, 0, 0, -1, 0);
  swJointDesc j1 = joint_of("insertion", SW_JOINT_SPHERICAL, 0, -1, 1, 0);
  sw_spec_add_joint(s, &j0);
  sw_spec_add_joint(s, &j1);
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
  swModel *m = sw_test_compile_at(s, dt_frac);
  sw_spec_free(s);
  return m;
}

static void test_stable_dt_bone(void **state) {
  (void)state;
  swModel *me = arm(0, 1.0), *mr = arm(1, 1.0);
  double dte = sw_stable_dt(me), dtr = sw_stable_dt(mr);
  double bone_e = sw_stable_dt_rod(me, 0), bone_r = sw_stable_dt_rod(mr, 0);
  double strand = sw_stable_dt_rod(mr, 1), shoulder = sw_stable_dt_joint(mr, 0);
  double insertion = sw_stable_dt_joint(mr, 1);
  fprintf(stderr, "# %s: elastic bone: scene %.4g s (bone %.4g s); rigid bone: scene %.4g s "
                  "(bone %g, strand %.4g s, shoulder %.4g s, insertion %.4g s); ratio %.1f\n",
          __func__, dte, bone_e, dtr, bone_r, strand, shoulder, insertion, dtr / dte);
  SW_EXPECT_REL("elastic: scene dt / the bone's own", dte / bone_e, 1.0, 0.1);
  assert_true(isinf(bone_r));
  assert_true(dtr > 5 * dte);
  sw_model_free(mr);
  sw_model_free(me);
  /* and the rigid scene runs at 0.9 of its estimate, the arm swinging down
   * from where the strand's weight pulls it */
  mr = arm(1, 0.9);
  swData *d = sw_data_new(mr);
  sw_test_run_to(mr, d, sw_test_sanitized() ? 0.02 : 0.2);
  fprintf(stderr, "# %s: rigid scene at dt = %.4g s: %ld steps to t = %.3g s, stable\n", __func__,
          mr->dt, d->step, d->time);
  sw_data_free(d);
  sw_model_free(mr);
}

/* The rigid bone on `njoint` anchored spherical joints (its start, and its
 * end when 2) of stiffness k, no gravity, started with a small random
 * motion: 1 when `steps` steps at dt_frac times the estimate stay bounded
 * (energy below 1e3 times the initial). */
static int rigid_on_springs_stable(int njoint, double k, double dt_frac, long steps, double *est) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, dir[3] = {1, 0.2, -0.3};
  swRodDesc r = bone("humerus", BN, o, dir, 1);
  sw_spec_add_rod(s, &r);
  for (int q = 0; q < njoint; q++) {
    swJointDesc j = joint_of(q ? "elbow" : "shoulder", SW_JOINT_SPHERICAL, 0, q ? -1 : 0, -1, 0);
    for (int c = 0; c < 3; c++) j.anchor[c] = q ? BL * dir[c] / norm3(dir) : 0;
    j.stiffness = k;
    j.undamped = 1;
    sw_spec_add_joint(s, &j);
  }
  swModel *m = sw_test_compile(s);
  *est = sw_stable_dt(m);
  sw_model_free(m);
  sw_spec_set_dt(s, dt_frac * *est);
  m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double V0[3] = {1e-3, -2e-3, 0.5e-3}, w0[3] = {0.01, 0.02, -0.03};
  sw_rigid_set_motion(m, d, 0, V0, w0);
  double e[3];
  sw_energy(m, d, e);
  double e0 = e[0] + e[1];
  int ok = sw_steps(m, d, steps) == SW_OK;
  if (ok) {
    sw_energy(m, d, e);
    ok = isfinite(e[0] + e[1]) && e[0] + e[1] < 1e3 * e0;
  }
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return ok;
}

/* The joint bound of a rigid body against the step at which it really blows
 * up (bisection, as test_stability.c does for rods): safe, and within 1.5 of
 * the limit, for one joint and for two (whose springs act on the same six
 * degrees of freedom and so are summed). */
static void test_rigid_joint_dt(void **state) {
  (void)state;
  const long steps = sw_test_sanitized() ? 3000 : 20000;
  for (int nj = 1; nj <= 2; nj++) {
    double est, lo = 0.95, hi = 3.0;
    assert_true(rigid_on_springs_stable(nj, 5e5, lo, steps, &est));
    assert_false(rigid_on_springs_stable(nj, 5e5, hi, steps, &est));
    for (int it = 0; it < 10; it++) {
      double mid = 0.5 * (lo + hi);
      if (rigid_on_springs_stable(nj, 5e5, mid, steps, &est)) lo = mid; else hi = mid;
    }
    fprintf(stderr, "# %s: %d joint%s of k = 5e5 N/m: estimate %.4g s, measured limit %.4f x "
                    "the estimate\n", __func__, nj, nj > 1 ? "s" : "", est, lo);
    assert_true(lo >= 1.0);
    assert_true(lo <= 1.5);
  }
}

/* ---- 7. output ---- */

/* The HDF5 output of a scene with a rigid rod: the rigid bone's positions,
 * as written, are those of the state, and its node distances in the file
 * are the rest distances. */
static void test_output(void **state) {
  (void)state;
  swModel *m = arm(1, 0.9);
  swData *d = sw_data_new(m);
  char path[64];
  snprintf(path, sizeof path, "/tmp/sinew_test_rigid_XXXXXX");
  int fd = mkstemp(path);
  assert_true(fd >= 0);
  close(fd);
  char err[256] = "";
  swOutputOptions opt = {.duration = 0.02, .velocity = 1, .directors = 1};
  swOutput *out = sw_output_open(path, m, &opt, err, sizeof err);
  if (!out) fprintf(stderr, "# %s\n", err);
  assert_non_null(out);
  swRunOptions ro = {.duration = 0.02, .every = 0.01, .quiet = 1};
  assert_int_equal(sw_run(m, d, out, &ro), SW_OK);
  long frames = sw_output_frames(out);
  assert_int_equal(sw_output_close(out, "complete"), SW_OK);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  hid_t ds = H5Dopen2(file, "/rods/humerus/position", H5P_DEFAULT);
  assert_true(ds >= 0);
  size_t per = 3 * (BN + 1);
  double *buf = malloc(sizeof(double) * per * (size_t)frames);
  assert_true(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
  const double *last = buf + per * (size_t)(frames - 1);
  double diff = 0, derr = 0;
  /* the file holds a row (3) per node; the state is planar */
  for (size_t q = 0; q < per; q++)
    diff = fmax(diff, fabs(last[q] - SW_AT(m, d->x, m->node_adr[0] + (int)(q / 3), q % 3)));
  for (int i = 0; i < BN; i++) {
    const double l0 = m->rest_len[m->elem_adr[0] + i];
    derr = fmax(derr, fabs(dist(last + 3 * i, last + 3 * i + 3) - l0) / l0);
  }
  fprintf(stderr, "# %s: %ld frames; the bone's centre of mass fell %.4g m\n", __func__, frames,
          m->rigid_X0[2] - d->rigid_X[2]);
  SW_EXPECT_ABS("|file - state| of the rigid bone's last frame (m)", diff, 0.0, 0.0);
  SW_EXPECT_ABS("largest relative error of an element length in the file", derr, 0.0, 1e-12);
  free(buf);
  H5Dclose(ds);
  H5Fclose(file);
  unlink(path);
  sw_data_free(d);
  sw_model_free(m);
}

/* ---- 8. validation ---- */

static void expect_error(int rigid, swDampingKind damping, int bc_kind, const char *message) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0};
  swRodDesc r = bone("humerus", 5, o, x, rigid);
  r.damping = damping;
  r.gamma = damping ? 1.0 : 0.0;
  sw_spec_add_rod(s, &r);
  if (bc_kind >= 0) {
    swBCDesc b = sw_test_clamp(0, 1);
    b.kind = (swBCKind)bc_kind;
    b.vec[2] = 1;
    sw_spec_add_bc(s, &b);
  }
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  int accepted = m != NULL;
  sw_model_free(m);
  sw_spec_free(s);
  fprintf(stderr, "# expect_error: \"%s\"\n", err);
  assert_false(accepted);
  assert_string_equal(err, message);
}

static void test_validation(void **state) {
  (void)state;
  expect_error(2, SW_DAMP_NONE, -1, "rod 'humerus': rigid must be 0 or 1, got 2");
  expect_error(1, SW_DAMP_ANALYTIC, -1,
               "rod 'humerus': analytic damping is not supported on a rigid rod (use linear damping)");
  expect_error(1, SW_DAMP_NONE, SW_BC_VELOCITY,
               "boundary condition 0 on rod 'humerus': a prescribed velocity is not supported on "
               "a rigid rod (clamp it, or hold it with a joint)");
  expect_error(1, SW_DAMP_NONE, SW_BC_OMEGA,
               "boundary condition 0 on rod 'humerus': a prescribed angular velocity is not "
               "supported on a rigid rod (clamp it, or hold it with a joint)");
  /* what is accepted: a clamp, linear damping; sw_rigid_set_motion only on
   * a free rigid rod */
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
  swRodDesc a = bone("humerus", 5, o, x, 1), b = bone("ulna", 5, o, y, 0);
  a.damping = SW_DAMP_LINEAR;
  a.gamma = 1;
  sw_spec_add_rod(s, &a);
  sw_spec_add_rod(s, &b);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double zero[3] = {0, 0, 0};
  assert_int_equal(m->nrigid, 1);
  assert_int_equal(m->rod_rigid[0], 0);
  assert_int_equal(m->rod_rigid[1], -1);
  assert_int_equal(sw_rigid_set_motion(m, d, 0, zero, zero), SW_OK);
  assert_int_equal(sw_rigid_set_motion(m, d, 1, zero, zero), SW_EUSAGE);
  assert_int_equal(sw_rigid_set_motion(m, d, 2, zero, zero), SW_EUSAGE);
  /* mass and inertia: those of the elastic rod's lumped masses and element
   * inertias (a straight rod along x: axial moment sum J^_3, transverse
   * sum m x^2 + sum J^_1) */
  double M = BRHO * M_PI * BR * BR * BL, I1 = M_PI * pow(BR, 4) / 4;
  SW_EXPECT_REL("mass (kg)", m->rigid_mass[0], M, 1e-14);
  SW_EXPECT_REL("axial moment (kg m^2)", m->rigid_inertia[0], BRHO * BL * 2 * I1, 1e-12);
  SW_EXPECT_REL("transverse moment (kg m^2)", m->rigid_inertia[1],
                M * BL * BL * (1.0 / 12 + 1.0 / (6 * 25)) + BRHO * BL * I1, 1e-12);
  assert_true(m->rigid_inertia[1] == m->rigid_inertia[2]);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- joints between rigid bodies under imex (rigid_joint.c) ---- */

/* A rigid rod of 4 elements (its centre at node 2, at the origin) anchored there by an
 * undamped spherical or fixed joint of stiffness k (k_t = k * 1 m^2 for the
 * fixed one's couple), started moving with v0 along x (spherical) or
 * spinning at w0 about y (fixed).  The lever is zero, so the body is a pure
 * translational or rotational oscillator of w = sqrt(k/M) or sqrt(k_t/I),
 * and the kick's trapezoidal step makes the scheme the implicit midpoint
 * rule, whose solution is exactly x_n = (v0/w) sin(n theta) with
 * tan(theta/2) = h w / 2 (it keeps w^2 x^2 + v^2).  Returns the largest
 * difference from it over n steps, relative to the amplitude, and the
 * scheme's stable-dt estimate. */
static double midpoint_oscillator(swJointKind kind, double hw, int nsteps, double *stable) {
  const double start[3] = {-0.01, 0, 0}, dir[3] = {1, 0, 0}, k = 1e9;
  swSpec *s = sw_spec_new();
  swRodDesc r = bone("body", 4, start, dir, 1);
  r.length = 0.02;
  r.radius_start = r.radius_end = 0.002;
  const int rod = sw_spec_add_rod(s, &r);
  swJointDesc j = joint_of("anchor", kind, rod, 2, -1, 0);
  /* anchored at the origin, where the centre is: positions near 0 keep
   * the round-off of x far below the amplitude (2e-11 m) */
  j.stiffness = k;
  j.rot_stiffness = k * 1.0;
  j.undamped = 1;
  sw_spec_add_joint(s, &j);
  sw_spec_set_integrator(s, SW_IMEX);
  sw_spec_set_dt(s, 1e-9); /* for the body's mass and inertia */
  swModel *m = sw_test_compile(s);
  const int b = m->rod_rigid[rod];
  const double M = m->rigid_mass[b];
  double I[9], w;
  if (kind == SW_JOINT_SPHERICAL) {
    w = sqrt(k / M);
  } else { /* the lab inertia about y */
    const double *R = m->rigid_R0 + 9 * b, *Ib = m->rigid_inertia + 3 * b;
    for (int i = 0; i < 9; i++) I[i] = 0;
    for (int c = 0; c < 3; c++) I[4] += R[3 + c] * Ib[c] * R[3 + c];
    w = sqrt(k / I[4]);
  }
  *stable = sw_stable_dt(m);
  const double h = hw / w;
  sw_model_free(m);
  sw_spec_set_dt(s, h);
  m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double V[3] = {1e-3, 0, 0}, Wy[3] = {0, 1e-3, 0}, zero[3] = {0, 0, 0};
  if (kind == SW_JOINT_SPHERICAL) assert_int_equal(sw_rigid_set_motion(m, d, rod, V, zero), SW_OK);
  else assert_int_equal(sw_rigid_set_motion(m, d, rod, zero, Wy), SW_OK);
  const double theta = 2 * atan(0.5 * hw), amp = 1e-3 / w;
  const double X0[3] = {d->rigid_X[3 * b], d->rigid_X[3 * b + 1], d->rigid_X[3 * b + 2]};
  double worst = 0;
  for (int n = 1; n <= nsteps; n++) {
    assert_int_equal(sw_step(m, d), SW_OK);
    double got;
    if (kind == SW_JOINT_SPHERICAL) {
      got = d->rigid_X[3 * b] - X0[0];
    } else { /* the angle about y: the body's x axis turned towards -z */
      const double *R = d->rigid_R + 9 * b, *R0 = m->rigid_R0 + 9 * b;
      /* R R0^T is the rotation since t = 0; its (0, 2) entry is sin(angle) */
      double RRt02 = R[0] * R0[6] + R[1] * R0[7] + R[2] * R0[8];
      got = asin(RRt02);
    }
    worst = fmax(worst, fabs(got - amp * sin(n * theta)) / amp);
  }
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return worst;
}

/* The stiff joint as an oscillator, at h w = 0.5 (resolved), 10 and 1000
 * (5 and 500 times past the explicit limit h w = 2): the trajectory is the
 * implicit midpoint rule's closed form to round-off, and the joints set no
 * step limit. */
static void test_implicit_joint(void **state) {
  (void)state;
  const double hws[] = {0.5, 10, 1000};
  for (int kind = 0; kind < 2; kind++) {
    const swJointKind jk = kind ? SW_JOINT_FIXED : SW_JOINT_SPHERICAL;
    for (int i = 0; i < 3; i++) {
      double stable;
      const double err = midpoint_oscillator(jk, hws[i], 200, &stable);
      fprintf(stderr, "# %s: %s joint, h w = %g: largest difference from the implicit midpoint "
              "rule's x_n = (v0/w) sin(n theta) over 200 steps: %.2e of the amplitude; "
              "stable dt %g\n", __func__, kind ? "fixed" : "spherical", hws[i], err, stable);
      assert_true(err < 1e-9);
      assert_true(isinf(stable));
    }
  }
}

/* A rigid body turning a radian a step beside a quiet elastic rod: the
 * step's vector check flags no elastic slot, and the check of the rigid
 * bodies alone (integrate.c, sw_check_rods) stops the run naming the body. */
static void test_spin_caught(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, far[3] = {1, 0, 0}, dir[3] = {0, 0, 1};
  swRodDesc quiet = bone("quiet", BN, o, dir, 0), spinner = bone("spinner", 4, far, dir, 1);
  sw_spec_add_rod(s, &quiet);
  sw_spec_add_rod(s, &spinner);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  const double V0[3] = {0, 0, 0}, w0[3] = {1.0 / m->dt, 0, 0}; /* a radian a step about x */
  assert_int_equal(sw_rigid_set_motion(m, d, 1, V0, w0), SW_OK);
  const int rc = sw_steps(m, d, 16);
  fprintf(stderr, "# %s: rc %d after %ld steps: %s\n", __func__, rc, d->step, d->error);
  assert_int_equal(rc, SW_EUNSTABLE);
  assert_non_null(strstr(d->error, "rod 'spinner'"));
  assert_non_null(strstr(d->error, "turns more than half a radian per step"));
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_validation),
      cmocka_unit_test(test_free_fall),
      cmocka_unit_test(test_couple),
      cmocka_unit_test(test_pendulum),
      cmocka_unit_test(test_torque_free),
      cmocka_unit_test(test_time_order),
      cmocka_unit_test(test_linear_damping),
      cmocka_unit_test(test_energy_chain),
      cmocka_unit_test(test_clamped),
      cmocka_unit_test(test_stable_dt_bone),
      cmocka_unit_test(test_rigid_joint_dt),
      cmocka_unit_test(test_implicit_joint),
      cmocka_unit_test(test_spin_caught),
      cmocka_unit_test(test_output),
  };
  return cmocka_run_group_tests_name("rigid", tests, NULL, NULL);
}
