/* test_joint_limit.c — joint limits (joint.c, "Limits") against closed
 * forms: a pendulum on a hinge with a range rests pressed against it, its
 * overshoot the static penalty deflection tau / k_l and its limit couple the
 * gravity moment (explicit, and implicit under SW_IMEX at a step the limit's
 * stiffness would not allow explicitly); an undamped limit gives back the
 * angular speed it takes (elastic bounce) with kinetic + elastic - work
 * conserved; a spherical pendulum pushed sideways stops at its cone in any
 * azimuth; a limit between two free rods conserves angular momentum (its
 * couples are equal and opposite); and the validation messages.
 *
 * Design.  The scenes are built through the public API.  The static scenes
 * use rigid rods (rigid.c), so that the closed forms of a rigid rod on a
 * pivot hold without the rod's own bending; the dynamic ones use stiff steel
 * rods and a soft limit, whose contact lasts far longer than the rods' own
 * vibrations.  Long runs shrink under SW_SANITIZED (testutil.h).
 */
#include "testutil.h"
#include "vec.h"
#include "internal.h"

static const double GRAV = 9.81;
/* a steel rod, L = 0.5 m, r = 1 cm: M = rho pi r^2 L */
static const double L = 0.5, R = 0.01, RHO = 7800;

static double rod_mass(void) { return RHO * M_PI * R * R * L; }
static double norm3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

static swRodDesc steel_rod(const char *name, int n, double length, const double start[3],
                           const double dir[3], const double normal[3]) {
  swRodDesc r = sw_test_rod(name, n, length, R, start, dir, normal);
  r.density = RHO;
  r.youngs = 200e9;
  r.poisson = 0.3;
  return r;
}

static swJointDesc anchored_joint(swJointKind kind) {
  swJointDesc j;
  sw_joint_desc_init(&j);
  j.name = "pivot";
  j.kind = kind;
  j.rod_a = 0;
  j.node_a = 0;
  j.rod_b = -1;
  return j;
}

/* ---- 1. a hinge pendulum resting on its limit ---- */

/* A rigid rod along +x from a hinge at the origin (axis y), range
 * (-0.5, 0.5) rad, k_l = 100 N m/rad, gravity -z: it falls from 0 (level)
 * towards +0.5 rad and rests there, pressed by the gravity moment
 * tau = M g (L/2) cos(theta) (its centre of mass at L/2 cos(theta) from the
 * pivot horizontally), so theta - 0.5 = tau / k_l.  Returns the measured
 * angle and limit couple. */
static const double HI = 0.5, KL = 100.0;
/* The default k_l of that rod's hinge: EI / D, D half an element. */
static double default_kl(void) { return 200e9 * M_PI * pow(R, 4) / 4.0 / (0.5 * L / 4); }
static double pivot_inertia(void) { return rod_mass() * L * L / 3.0; }
static void hinge_at_limit(swIntegrator integ, double kl, double dt, double *theta,
                           double *torque_y) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, z[3] = {0, 0, 1};
  swRodDesc r = steel_rod("arm", 4, L, o, x, z);
  r.rigid = 1;
  r.damping = SW_DAMP_LINEAR;
  r.gamma = 2.0; /* settles the free swing; no force at rest */
  sw_spec_add_rod(s, &r);
  swJointDesc j = anchored_joint(SW_JOINT_HINGE);
  j.axis[1] = 1;
  j.has_range = 1;
  j.angle_min = -HI;
  j.angle_max = HI;
  j.limit_stiffness = kl;
  j.limit_damping = sqrt(kl * pivot_inertia()); /* half of critical */
  assert_int_equal(sw_spec_add_joint(s, &j), 0);
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, integ);
  swModel *m;
  if (dt > 0) {
    sw_spec_set_dt(s, dt);
    m = sw_test_compile(s);
  } else {
    m = sw_test_compile_at(s, 0.9);
  }
  swData *d = sw_data_new(m);
  sw_test_relax(m, d, &d->joint_angle[0], 0.5, 20.0, 1e-10);
  sw_joint_measure(m, d, 0);
  *theta = d->joint_angle[0];
  *torque_y = d->joint_limit_torque[1];
  const double *t = d->joint_limit_torque;
  fprintf(stderr, "# %s: %s, k_l = %.4g N m/rad, dt = %.3g s (%.3g of the explicit limit's "
          "bound 2 / sqrt(k_l / I)), theta = %.9f rad, limit torque (%.3g, %.9g, %.3g) N m\n",
          __func__, integ == SW_IMEX ? "imex" : "verlet", kl, m->dt,
          m->dt / (2.0 / sqrt(kl / pivot_inertia())), *theta, t[0], t[1], t[2]);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void check_at_limit(double kl, double theta, double torque_y) {
  const double tau = rod_mass() * GRAV * 0.5 * L * cos(theta);
  SW_EXPECT_REL("limit couple -C_y (N m) vs gravity moment M g L/2 cos(theta)", -torque_y, tau,
                1e-6);
  SW_EXPECT_REL("overshoot theta - theta_max (rad) vs tau / k_l", theta - HI, tau / kl, 1e-6);
}

static void test_hinge_rests_at_limit(void **state) {
  (void)state;
  double theta, ty;
  hinge_at_limit(SW_VERLET, KL, 0, &theta, &ty);
  check_at_limit(KL, theta, ty);
}

/* The same under SW_IMEX (rigid_joint.c: the joint's springs implicit, the
 * limit in the system's tangent) with the default, stiff k_l, at 0.9 of the
 * stable step, which the limit bounds (stability.c): it rests at the same
 * place. */
static void test_hinge_rests_at_limit_imex(void **state) {
  (void)state;
  const double kl = default_kl();
  double theta, ty;
  hinge_at_limit(SW_IMEX, kl, 0, &theta, &ty);
  check_at_limit(kl, theta, ty);
}

/* ---- 2. an elastic bounce ---- */

/* Angular momentum about the origin, sum m x x v + sum Q^T J w / e. */
static void angular_momentum(const swModel *m, const swData *d, double Lm[3]) {
  memset(Lm, 0, 3 * sizeof *Lm);
  for (int r = 0; r < m->nrod; r++) {
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
      double x[3], v[3], c[3];
      sw_get3(m, d->x, i, x);
      sw_get3(m, d->v, i, v);
      sw_v3_cross(c, x, v);
      for (int k = 0; k < 3; k++) Lm[k] += m->mass[i] * c[k];
    }
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) {
      double Q[9], w[3];
      sw_getQ(m, d->Q, e, Q);
      sw_get3(m, d->omega, e, w);
      for (int a = 0; a < 3; a++) {
        double h = SW_AT(m, m->inertia, e, a) * w[a] / d->dilatation[e];
        for (int k = 0; k < 3; k++) Lm[k] += Q[3 * a + k] * h;
      }
    }
  }
}

/* Sets a rigid rotation with angular velocity w (lab) about the origin on
 * rods [r0, r1). */
static void spin(const swModel *m, swData *d, int r0, int r1, const double w[3]) {
  for (int r = r0; r < r1; r++) {
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
      double x[3], v[3];
      sw_get3(m, d->x, i, x);
      sw_v3_cross(v, w, x);
      sw_set3(m, d->v, i, v);
    }
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) {
      double Q[9], wm[3];
      sw_getQ(m, d->Q, e, Q);
      sw_mat_vec(wm, Q, w);
      sw_set3(m, d->omega, e, wm);
    }
  }
}

/* The angular velocity about z (lab) of rod r, its elements' mean. */
static double spin_z(const swModel *m, const swData *d, int r) {
  double sum = 0;
  for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) {
    double Q[9], wm[3], w[3];
    sw_getQ(m, d->Q, e, Q);
    sw_get3(m, d->omega, e, wm);
    sw_matT_vec(w, Q, wm);
    sum += w[2];
  }
  return sum / m->rod_nelem[r];
}

/* A steel rod spinning at w0 = 2 rad/s about a hinge at its start (axis z,
 * no gravity), undamped, range (-0.3, 0.3) rad, k_l = 20 N m/rad: it hits
 * the upper limit and comes back.  An undamped penalty is a conservative
 * spring, so it leaves with the speed it came in with: when the angle is
 * back to 0 the rod turns at -w0.  The contact lasts pi sqrt(I / k_l) =
 * 0.22 s, some 1e4 times the rod's lowest bending period, so the rod's own
 * vibration takes almost nothing. */
static void test_elastic_bounce(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
  swRodDesc r = steel_rod("arm", 6, L, o, x, y);
  sw_spec_add_rod(s, &r);
  swJointDesc j = anchored_joint(SW_JOINT_HINGE);
  j.axis[2] = 1;
  j.undamped = 1;
  j.has_range = 1;
  j.angle_min = -0.3;
  j.angle_max = 0.3;
  j.limit_stiffness = 20.0;
  assert_int_equal(sw_spec_add_joint(s, &j), 0);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);
  const double w0[3] = {0, 0, 2.0};
  spin(m, d, 0, 1, w0);
  double e[3], E0, worst = 0, kmax = 0, peak = 0, tmax = 0, Lz0[3];
  sw_energy(m, d, e);
  E0 = e[0] + e[1] - e[2];
  const double K0 = e[0];
  angular_momentum(m, d, Lz0);
  double prev = d->joint_angle[0], w_back = 0;
  int hit = 0;
  while (d->time < 1.0) {
    assert_int_equal(sw_step(m, d), SW_OK);
    const double a = d->joint_angle[0];
    if (a > HI - 0.2 && !hit) hit = 1;
    peak = fmax(peak, a);
    tmax = fmax(tmax, norm3(d->joint_limit_torque));
    if (d->step % 64 == 0) {
      sw_energy(m, d, e);
      worst = fmax(worst, fabs(e[0] + e[1] - e[2] - E0));
      kmax = fmax(kmax, e[0]);
    }
    if (hit && prev > 0 && a <= 0) { /* back through 0 */
      double Lz[3];
      angular_momentum(m, d, Lz);
      w_back = Lz[2] / Lz0[2] * w0[2];
      sw_energy(m, d, e);
      fprintf(stderr, "# %s: back through 0: kinetic %.9g J (%.9g J at the start), elastic "
              "%.3g J, angle rate %.6f rad/s, elements' mean spin %.6f rad/s\n", __func__, e[0],
              K0, e[1], (a - prev) / m->dt, spin_z(m, d, 0));
      break;
    }
    prev = a;
  }
  const double I = rod_mass() * (L * L / 3.0 + R * R / 4.0) + rod_mass() * L * L / (6.0 * 36.0);
  fprintf(stderr, "# %s: t = %.4f s, %ld steps, peak angle %.5f rad (closed form for a rigid "
          "rod 0.3 + w0 sqrt(I / k_l) = %.5f), largest limit couple %.4g N m\n", __func__,
          d->time, d->step, peak, 0.3 + 2.0 * sqrt(I / 20.0), tmax);
  SW_EXPECT_REL("angular speed after the bounce, L_z / I (rad/s), vs before", -w_back, 2.0, 1e-6);
  SW_EXPECT_REL("peak angle (rad) vs 0.3 + w0 sqrt(I / k_l)", peak, 0.3 + 2.0 * sqrt(I / 20.0),
                1e-3);
  SW_EXPECT_ABS("largest |kinetic + elastic - work - E0| / largest kinetic", worst / kmax, 0.0,
                1e-8);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 3. a cone ---- */

/* A rigid rod hung along -z from a spherical joint at the origin, cone
 * 0.4 rad, k_l = 100 N m/rad, gravity -z, pushed at its tip by F = 10 N
 * horizontally in azimuth phi: it swings out in that azimuth to the cone
 * and rests at psi with k_l (psi - cone) = F L cos(psi) - M g (L/2) sin(psi)
 * (the moments about the pivot in the plane of the swing). */
static void cone_pendulum(double phi) {
  const double CONE = 0.4, F = 10.0;
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, down[3] = {0, 0, -1}, x[3] = {1, 0, 0};
  swRodDesc r = steel_rod("arm", 4, L, o, down, x);
  r.rigid = 1;
  r.damping = SW_DAMP_LINEAR;
  r.gamma = 2.0;
  sw_spec_add_rod(s, &r);
  swJointDesc j = anchored_joint(SW_JOINT_SPHERICAL);
  j.cone = CONE;
  j.limit_stiffness = KL;
  j.limit_damping = 6.0;
  assert_int_equal(sw_spec_add_joint(s, &j), 0);
  swLoadDesc push = sw_test_load(SW_LOAD_FORCE, 0, -1, F * cos(phi), F * sin(phi), 0);
  sw_spec_add_load(s, &push);
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);
  double tip[3] = {0, 0, 0};
  const int last = m->node_adr[0] + m->rod_nelem[0];
  double watch = 0;
  while (d->time < 20.0) { /* relax on the tip's height */
    sw_test_run_to(m, d, d->time + 0.5);
    sw_get3(m, d->x, last, tip);
    if (fabs(tip[2] - watch) <= 1e-11) break;
    watch = tip[2];
  }
  sw_joint_measure(m, d, 0);
  double pivot[3], arm[3]; /* the rod from its joint node (the joint's gap, 1e-7 m, aside) */
  sw_get3(m, d->x, m->node_adr[0], pivot);
  sw_v3_sub(arm, tip, pivot);
  const double psi = acos(-arm[2] / norm3(arm)), azimuth = atan2(arm[1], arm[0]);
  const double tau = F * L * cos(psi) - rod_mass() * GRAV * 0.5 * L * sin(psi);
  const double *t = d->joint_limit_torque;
  fprintf(stderr, "# %s: phi = %.4f rad: t = %.3g s, psi = %.9f rad, azimuth %.9f rad, limit "
          "torque (%.6g, %.6g, %.6g) N m\n", __func__, phi, d->time, psi, azimuth, t[0], t[1],
          t[2]);
  SW_EXPECT_ABS("azimuth of the swing (rad) vs the push's", remainder(azimuth - phi, 2 * M_PI),
                0.0, 1e-9);
  SW_EXPECT_REL("overshoot psi - cone (rad) vs tau / k_l", psi - CONE, tau / KL, 1e-6);
  SW_EXPECT_REL("|limit couple| (N m) vs F L cos(psi) - M g L/2 sin(psi)", norm3(t), tau, 1e-6);
  /* the swing turns the rod about -(z x p), p the push's direction; the
   * limit couple turns it back, about +(z x p) */
  SW_EXPECT_ABS("limit couple along z x p / |C|", (t[0] * -sin(phi) + t[1] * cos(phi)) / norm3(t),
                1.0, 1e-9);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_cone_two_azimuths(void **state) {
  (void)state;
  cone_pendulum(0.0);
  cone_pendulum(2.0);
}

/* ---- 4. two free rods ---- */

/* Two steel rods end to end along x, hinged (axis z, range (-0.2, 0.2) rad,
 * default limit stiffness and damping) and floating free without gravity;
 * rod b spins at 3 rad/s about the hinge, rod a is at rest.  The limit
 * stops the relative turn several times; its couples are equal and
 * opposite, so the angular momentum stays what it was (to round-off, as
 * the free chain of test_joint.c). */
static void test_two_rods_momentum(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, mid[3] = {0.3, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
  swRodDesc ra = steel_rod("a", 6, 0.3, o, x, y), rb = steel_rod("b", 6, 0.3, mid, x, y);
  sw_spec_add_rod(s, &ra);
  sw_spec_add_rod(s, &rb);
  swJointDesc j;
  sw_joint_desc_init(&j);
  j.name = "elbow";
  j.kind = SW_JOINT_HINGE;
  j.rod_a = 0;
  j.node_a = -1;
  j.rod_b = 1;
  j.node_b = 0;
  j.axis[2] = 1;
  j.has_range = 1;
  j.angle_min = -0.2;
  j.angle_max = 0.2;
  assert_int_equal(sw_spec_add_joint(s, &j), 0);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);
  /* rod b turns about the hinge point: v = w x (x - mid) */
  const double w[3] = {0, 0, 3.0};
  spin(m, d, 1, 2, w);
  for (int i = m->node_adr[1]; i <= m->node_adr[1] + m->rod_nelem[1]; i++)
    SW_AT(m, d->v, i, 1) -= w[2] * mid[0];
  double L0[3], Lm[3], dL = 0, tmax = 0, amax = 0, amin = 0;
  angular_momentum(m, d, L0);
  const double T = sw_test_sanitized() ? 0.2 : 0.4;
  while (d->time < T) {
    sw_test_run_to(m, d, d->time + 0.002);
    angular_momentum(m, d, Lm);
    for (int k = 0; k < 3; k++) dL = fmax(dL, fabs(Lm[k] - L0[k]) / norm3(L0));
    tmax = fmax(tmax, norm3(d->joint_limit_torque));
    amax = fmax(amax, d->joint_angle[0]);
    amin = fmin(amin, d->joint_angle[0]);
  }
  fprintf(stderr, "# %s: %ld steps, |L0| = %.4g kg m^2/s, hinge angle in [%.4f, %.4f] rad, "
          "k_l = %.4g N m/rad, largest limit couple %.4g N m: |L - L0| / |L0| <= %.3g\n",
          __func__, d->step, norm3(L0), amin, amax, m->joint[0].limit_stiffness, tmax, dL);
  assert_true(tmax > 0 && amax > 0.2); /* the limit was met */
  SW_EXPECT_ABS("largest |L - L0| / |L0|", dL, 0.0, 1e-11);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- defaults and validation ---- */

/* k_l = the hinge's own k_t by default, and for a cone what k_t would be
 * (min EI / D); the element's step bound takes the larger of k_t and k_l,
 * so the default limit leaves the stable step as it was. */
static void test_defaults(void **state) {
  (void)state;
  double dt[2], kl[2], kt[2];
  for (int limited = 0; limited < 2; limited++) {
    swSpec *s = sw_spec_new();
    const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
    swRodDesc r = steel_rod("arm", 4, L, o, x, y);
    sw_spec_add_rod(s, &r);
    swJointDesc j = anchored_joint(SW_JOINT_HINGE);
    j.axis[2] = 1;
    j.has_range = limited;
    j.angle_min = -1;
    j.angle_max = 1;
    sw_spec_add_joint(s, &j);
    swJointDesc c = anchored_joint(SW_JOINT_SPHERICAL);
    c.name = "tip";
    c.node_a = -1;
    c.anchor[0] = L;
    c.cone = limited ? 0.5 : 0;
    sw_spec_add_joint(s, &c);
    swModel *m = sw_test_compile(s);
    dt[limited] = sw_stable_dt(m);
    kl[limited] = m->joint[0].limit_stiffness;
    kt[limited] = m->joint[0].rot_stiffness;
    if (limited) {
      /* EI / (l/2) of the end element, the clamp's bend */
      SW_EXPECT_REL("cone's default k_l (N m/rad) vs EI / D", m->joint[1].limit_stiffness,
                    default_kl(), 1e-12);
      assert_true(m->joint[1].limit_damping > 0);
    }
    sw_model_free(m);
    sw_spec_free(s);
  }
  SW_EXPECT_REL("range's default k_l (N m/rad) vs the hinge's k_t", kl[1], kt[1], 0);
  SW_EXPECT_REL("stable dt with the default limits / without", dt[1], dt[0], 1e-12);
}

static void expect_error(const swJointDesc *j, int rod_dir_x, const char *message) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, z[3] = {0, 0, -1}, y[3] = {0, 1, 0};
  swRodDesc a = steel_rod("a", 4, L, o, z, x);
  swRodDesc b = steel_rod("b", 4, L, (double[3]){0, 0, -L}, rod_dir_x ? x : z, y);
  sw_spec_add_rod(s, &a);
  sw_spec_add_rod(s, &b);
  sw_spec_add_joint(s, j);
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  fprintf(stderr, "# %s: %s\n", __func__, err);
  assert_null(m);
  assert_string_equal(err, message);
  sw_spec_free(s);
}

static void test_validation(void **state) {
  (void)state;
  swJointDesc j;
  sw_joint_desc_init(&j);
  j.name = "elbow";
  j.kind = SW_JOINT_HINGE;
  j.rod_a = 0;
  j.node_a = -1;
  j.rod_b = 1;
  j.node_b = 0;
  j.axis[1] = 1;
  j.has_range = 1;
  j.angle_min = -2.5;
  j.angle_max = -3;
  expect_error(&j, 1, "joint 'elbow': angle range must be finite with angle_min < angle_max, "
                      "got [-2.5, -3] rad");
  /* the forearm along x from an upper arm along -z: -pi/2 at t = 0 */
  j.angle_min = -1;
  j.angle_max = 0;
  expect_error(&j, 1, "joint 'elbow': its hinge angle at t = 0 is -1.5708 rad, outside its "
                      "range [-1, 0] rad: the limit would throw it on the first step");
  j.angle_min = -2.5;
  j.limit_stiffness = -1;
  expect_error(&j, 1, "joint 'elbow': limit stiffness must be finite and >= 0 (0 = automatic), "
                      "got -1");
  j.limit_stiffness = 0;
  j.kind = SW_JOINT_SPHERICAL;
  expect_error(&j, 1, "joint 'elbow': an angle range is for a hinge, not a spherical joint");
  j.has_range = 0;
  j.cone = M_PI;
  expect_error(&j, 0, "joint 'elbow': cone must be in (0, pi) rad (0 = none), got 3.14159");
  j.kind = SW_JOINT_HINGE;
  j.cone = 1;
  expect_error(&j, 0, "joint 'elbow': a cone is for a spherical joint, not a hinge joint");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_defaults),
      cmocka_unit_test(test_validation),
      cmocka_unit_test(test_hinge_rests_at_limit),
      cmocka_unit_test(test_hinge_rests_at_limit_imex),
      cmocka_unit_test(test_elastic_bounce),
      cmocka_unit_test(test_cone_two_azimuths),
      cmocka_unit_test(test_two_rods_momentum),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
