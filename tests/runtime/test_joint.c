/* test_joint.c — joints (joint.c) against closed forms: a steel rod swinging
 * on an anchored hinge and a forearm on a spherical joint (period of the
 * physical pendulum), free rotation about the hinge axis under a couple
 * (rigid-body angular acceleration) and clamp-like stiffness across it
 * (cantilever deflection; a forearm on a hinge under an off-axis torque),
 * two rods joined by a fixed joint bending like one rod (Timoshenko
 * cantilever; a bone, with the default and the reference's stiffness), a
 * spherical joint carrying the weight of the rod hung from it,
 * the energy balance of a jointed chain (undamped and damped), conservation
 * of angular momentum of a free jointed assembly, the stable time step of a
 * stiff joint against the step at which it really blows up, the defaults,
 * the validation messages (exact text) and the HDF5 output of joints.
 *
 * Design.  Each scene is built through the public API (swSpec, sw_compile,
 * sw_step), so these are also the examples of how a joint is declared.  The
 * dynamic scenes use stiff rods, so that the rods' own elasticity shifts the
 * reference figures by far less than the tolerance; the long runs shrink
 * under SW_SANITIZED (testutil.h).
 *
 * Three claims of docs/validation.md ("Joints (issue 4, validation 4)") are
 * asserted here as stated, on arm-like scenes (a forearm-sized bone: 0.255 m,
 * r = 10.5 mm, E = 15 GPa, 1750 kg/m^3) with the reference's joint stiffness
 * k = 5e5 N/m (Zhang 2019, Suppl. Table 5): a hinge under an off-axis torque
 * keeps off-axis rotation below 1e-3 rad (test_hinge_off_axis_torque); a rod
 * on a spherical joint swings with the small-amplitude period of a physical
 * pendulum within 1% (test_pendulum_spherical); two rods joined by a fixed
 * joint deflect like one rod within 1% (test_fixed_joint_cantilever,
 * test_fixed_joint_bone_cantilever, which also shows where the reference's
 * k_f breaks the claim). */
#include <hdf5.h>
#include <unistd.h>

#include "testutil.h"
#include "internal.h"   /* sw_joint_measure: the angle of a state set by hand */

static const double GRAV = 9.81;

/* ---- scene helpers ---- */

static swRodDesc rod_along(const char *name, int n, double length, double radius,
                           const double start[3], const double dir[3]) {
  return sw_test_rod(name, n, length, radius, start, dir, NULL);
}

static swRodDesc steel(swRodDesc r) {
  r.density = 7800;
  r.youngs = 200e9;
  r.poisson = 0.3;
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

static double norm3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/* An arm-like rod: forearm-sized bone (Zhang 2019, Suppl. Note 2 and Table 1:
 * bone E = 15 GPa, 1.75 g/cm^3; the ulna's length and the humerus' radius),
 * and the reference's spherical/hinge/fixed joint stiffness
 * k = k_f = 5e5 kg/s^2 (Suppl. Table 5). */
static const double FL = 0.255, FR = 10.5e-3, FE = 15e9, FRHO = 1750, K_REF = 5e5;

static swRodDesc bone(swRodDesc r) {
  r.density = FRHO;
  r.youngs = FE;
  r.poisson = 0.5;
  return r;
}

/* ---- 1. pendulum ---- */

/* A steel rod (L = 0.5 m, r = 1 cm) hung by its start on an anchored joint at
 * the origin, released at 5 degrees from the vertical in the x-z plane under
 * gravity -z.  Hinge axis y. */
static const double PL = 0.5, PR = 0.01, PTHETA0 = 5.0 * M_PI / 180.0;

static swModel *pendulum(swJointKind kind, int n, swSpec **sout) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, dir[3] = {sin(PTHETA0), 0, -cos(PTHETA0)};
  swRodDesc r = steel(rod_along("pendulum", n, PL, PR, o, dir));
  int id = sw_spec_add_rod(s, &r);
  swJointDesc j = joint_of("pivot", kind, id, 0, -1, 0);
  j.axis[1] = 1.0;
  j.undamped = 1;
  assert_int_equal(sw_spec_add_joint(s, &j), 0);
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
  swModel *m = sw_test_compile_at(s, 0.9);
  *sout = s;
  return m;
}

/* Physical pendulum of a rod pivoted at its end, with the rotary inertia of
 * its cross-sections, I = M (L^2/3 + r^2/4), and the finite-amplitude series
 * T = T0 (1 + theta0^2/16 + 11 theta0^4/3072).  With n > 0, the same for the
 * lumped masses of n elements (model.c), whose moment of inertia about the
 * end is the trapezoidal rule's, M L^2 (1/3 + 1/(6 n^2)): the discretisation
 * error of the rod itself, which the joint should not add to. */
static double pendulum_period_n(int n) {
  double I_over_M = PL * PL / 3.0 + PR * PR / 4.0;
  if (n > 0) I_over_M += PL * PL / (6.0 * n * n);
  double T0 = 2 * M_PI * sqrt(I_over_M / (GRAV * PL / 2.0));
  double t2 = PTHETA0 * PTHETA0;
  return T0 * (1 + t2 / 16.0 + 11.0 * t2 * t2 / 3072.0);
}
static double pendulum_period(void) { return pendulum_period_n(0); }

/* Runs the pendulum until the tip has crossed x = 0 `want` times; returns
 * the time between the first and the last crossing, and the largest |y| of
 * any node and the hinge angle at the first crossing. */
static double swing_crossings(const swModel *m, swData *d, int want, double *max_y,
                              double *angle_at_crossing) {
  const int n = m->rod_nelem[0], i0 = m->node_adr[0];
  const double *tipx = &SW_AT(m, d->x, i0 + n, 0);
  double t[8], prev = *tipx, tprev = d->time, aprev = d->joint_angle[0];
  int nc = 0;
  *max_y = 0;
  const double tmax = 2.0 * pendulum_period() * want;
  while (nc < want && d->time < tmax) {
    assert_int_equal(sw_step(m, d), SW_OK);
    double a = d->joint_angle[0];
    if ((prev > 0) != (*tipx > 0)) {
      double f = prev / (prev - *tipx);
      t[nc] = tprev + f * (d->time - tprev);
      if (nc == 0) *angle_at_crossing = aprev + f * (a - aprev);
      nc++;
    }
    for (int i = 0; i <= n; i++) *max_y = fmax(*max_y, fabs(SW_AT(m, d->x, i0 + i, 1)));
    prev = *tipx;
    tprev = d->time;
    aprev = a;
  }
  assert_int_equal(nc, want);
  return t[want - 1] - t[0];
}

static void test_pendulum_hinge_period(void **state) {
  (void)state;
  const int n = sw_test_sanitized() ? 10 : 20;
  swSpec *s;
  swModel *m = pendulum(SW_JOINT_HINGE, n, &s);
  swData *d = sw_data_new(m);
  /* crossings at T/4, 3T/4, 5T/4: a whole period from three (half from two) */
  int want = sw_test_sanitized() ? 2 : 3;
  double max_y, angle = 0;
  double span = swing_crossings(m, d, want, &max_y, &angle);
  double T = span / (0.5 * (want - 1));
  fprintf(stderr, "# %s: n = %d, dt = %.3g s, %d crossings\n", __func__, n, m->dt, want);
  SW_EXPECT_REL("period (s)", T, pendulum_period(), 5e-3);
  SW_EXPECT_REL("period vs the lumped-mass pendulum (s)", T, pendulum_period_n(n), 1e-4);
  /* at the bottom the rod has turned by theta0 about +y */
  SW_EXPECT_REL("hinge angle at the bottom (rad)", angle, PTHETA0, 1e-2);
  SW_EXPECT_ABS("largest |y| of a node (m)", max_y, 0.0, 1e-12);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Claim: a rod on a spherical joint swings with the small-amplitude period of
 * a physical pendulum, T = 2 pi sqrt(I_pivot / (m g d)), within 1%.  The
 * forearm hung from an anchored spherical joint with the reference's
 * k = 5e5 N/m, released 5 degrees from the vertical in a vertical plane at
 * an azimuth of 0.6 rad (no joint axis, so no plane is special), undamped.
 * I_pivot = M (L^2/3 + r^2/4) (the cross-sections' rotary inertia is 1.3e-3
 * of it, so it counts at this tolerance), d = L/2.  The period is timed by
 * zero crossings of the tip's horizontal offset along the swing direction,
 * over three periods (one under the sanitizers).  What separates the two is
 * known: the lumped masses' inertia, M L^2/(6 n^2), and the finite amplitude,
 * T0 theta0^2/16; the second check holds the joint to that account. */
static void test_pendulum_spherical(void **state) {
  (void)state;
  const int n = sw_test_sanitized() ? 10 : 20, want = sw_test_sanitized() ? 3 : 7;
  const double theta0 = 5.0 * M_PI / 180.0, e[3] = {cos(0.6), sin(0.6), 0};
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0};
  double dir[3] = {sin(theta0) * e[0], sin(theta0) * e[1], -cos(theta0)};
  swRodDesc r = bone(rod_along("forearm", n, FL, FR, o, dir));
  sw_spec_add_rod(s, &r);
  swJointDesc j = joint_of("shoulder", SW_JOINT_SPHERICAL, 0, 0, -1, 0);
  j.stiffness = K_REF;
  j.undamped = 1;
  sw_spec_add_joint(s, &j);
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);

  const double M = FRHO * M_PI * FR * FR * FL, d_cm = FL / 2;
  const double I_pivot = M * (FL * FL / 3 + FR * FR / 4);
  const double T0 = 2 * M_PI * sqrt(I_pivot / (M * GRAV * d_cm));
  const int i0 = m->node_adr[0];
  const double *tip_x = &SW_AT(m, d->x, i0 + n, 0), *tip_y = &SW_AT(m, d->x, i0 + n, 1);
  double along = *tip_x * e[0] + *tip_y * e[1], t_prev = 0, t[8], off_plane = 0;
  int nc = 0;
  while (nc < want && d->time < 2.0 * T0 * want) {
    assert_int_equal(sw_step(m, d), SW_OK);
    double a = *tip_x * e[0] + *tip_y * e[1];
    for (int i = 0; i <= n; i++)
      off_plane = fmax(off_plane, fabs(e[0] * SW_AT(m, d->x, i0 + i, 1) -
                                       e[1] * SW_AT(m, d->x, i0 + i, 0)));
    if ((along > 0) != (a > 0)) t[nc++] = t_prev + along / (along - a) * (d->time - t_prev);
    along = a;
    t_prev = d->time;
  }
  assert_int_equal(nc, want);
  double T = (t[want - 1] - t[0]) / (0.5 * (want - 1));
  fprintf(stderr, "# %s: n = %d, dt = %.3g s, k = %.3g N/m, %d crossings (%.3g periods), "
                  "I_pivot = %.6g kg m^2, m g d = %.6g N m\n",
          __func__, n, m->dt, m->joint[0].stiffness, want, 0.5 * (want - 1), I_pivot, M * GRAV * d_cm);
  SW_EXPECT_REL("period vs 2 pi sqrt(I_pivot/(m g d)) (s)", T, T0, 1e-2);
  double lumped = M * (FL * FL * (1.0 / 3 + 1.0 / (6.0 * n * n)) + FR * FR / 4);
  double t2 = theta0 * theta0;
  double T_n = 2 * M_PI * sqrt(lumped / (M * GRAV * d_cm)) * (1 + t2 / 16 + 11 * t2 * t2 / 3072);
  SW_EXPECT_REL("period vs the lumped-mass pendulum at 5 deg (s)", T, T_n, 1e-4);
  SW_EXPECT_ABS("largest distance of a node from the swing plane (m)", off_plane, 0.0, 1e-12);
  SW_EXPECT_ABS("joint angle of a spherical joint (rad)", d->joint_angle[0], 0.0, 0.0);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 2. a hinge turns freely about its axis and is stiff across it ---- */

/* A steel rod along +x from an anchored hinge at the origin (axis y), no
 * gravity, a constant tip force F.  With a force damping gamma (analytic)
 * or none. */
static swModel *hinged_beam(int n, const double F[3], double gamma, swSpec **sout) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, dir[3] = {1, 0, 0};
  swRodDesc r = steel(rod_along("beam", n, PL, PR, o, dir));
  if (gamma > 0) {
    r.damping = SW_DAMP_ANALYTIC;
    r.gamma = gamma;
  }
  int id = sw_spec_add_rod(s, &r);
  swJointDesc j = joint_of("hinge", SW_JOINT_HINGE, id, 0, -1, 0);
  j.axis[1] = 1.0;
  sw_spec_add_joint(s, &j);
  swLoadDesc f = sw_test_load(SW_LOAD_FORCE, id, -1, F[0], F[1], F[2]);
  sw_spec_add_load(s, &f);
  *sout = s;
  return sw_test_compile_at(s, 0.9);
}

/* Turns rod r rigidly by `angle` about the z axis through point p: nodes
 * x -> p + R (x - p), directors d_i -> R d_i (rows of Q: Q -> Q R^T). */
static void turn_rod_about_z(const swModel *m, swData *d, int r, const double p[3],
                             double angle) {
  const double c = cos(angle), s = sin(angle);
  for (int i = 0; i <= m->rod_nelem[r]; i++) {
    double x[3];
    sw_get3(m, d->x, m->node_adr[r] + i, x);
    double dx = x[0] - p[0], dy = x[1] - p[1];
    x[0] = p[0] + c * dx - s * dy;
    x[1] = p[1] + s * dx + c * dy;
    sw_set3(m, d->x, m->node_adr[r] + i, x);
  }
  for (int e = 0; e < m->rod_nelem[r]; e++) {
    double Q[9];
    sw_getQ(m, d->Q, m->elem_adr[r] + e, Q);
    for (int row = 0; row < 3; row++) {
      double a = Q[3 * row], b = Q[3 * row + 1];
      Q[3 * row] = c * a - s * b;
      Q[3 * row + 1] = s * a + c * b;
    }
    sw_setQ(m, d->Q, m->elem_adr[r] + e, Q);
  }
}

/* One convention for the hinge angle (docs/physics.md, "Hinge angle"): the
 * angle, right-handed about the axis, from a reference tangent to the moving
 * rod's tangent: rod a's tangent for a hinge between two rods (rod b moves),
 * rod a's tangent at t = 0, fixed in space, for an anchored hinge (rod a
 * moves).  Turning the moving rod by +30 degrees about the axis (z) reads
 * +30 degrees in both; a two-rod hinge built with rod b at +90 degrees from
 * rod a reads +90 degrees at t = 0, and turning rod a by +30 degrees about
 * the joint reads 90 - 30. */
static void test_hinge_angle_convention(void **state) {
  (void)state;
  const double o[3] = {0, 0, 0}, x1[3] = {0.2, 0, 0}, ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
  const double turn = 30 * M_PI / 180;
  /* anchored at the origin, rod a along +x */
  swRodDesc ra = steel(rod_along("a", 8, 0.2, 0.005, o, ex));
  swRodDesc rb = steel(rod_along("b", 8, 0.2, 0.005, x1, ey));
  swSpec *s = sw_spec_new();
  int a = sw_spec_add_rod(s, &ra);
  swJointDesc j = joint_of("pivot", SW_JOINT_HINGE, a, 0, -1, 0);
  j.axis[2] = 1;
  sw_spec_add_joint(s, &j);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);
  sw_joint_measure(m, d, 0);
  SW_EXPECT_ABS("anchored hinge at t = 0 (rad)", d->joint_angle[0], 0.0, 1e-15);
  turn_rod_about_z(m, d, 0, o, turn);
  sw_joint_measure(m, d, 0);
  SW_EXPECT_ABS("anchored hinge, rod a turned +30 deg about the axis (rad)", d->joint_angle[0],
                turn, 1e-12);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  /* two rods: a along +x, b from a's end along +y (+90 degrees about z) */
  s = sw_spec_new();
  a = sw_spec_add_rod(s, &ra);
  int b = sw_spec_add_rod(s, &rb);
  j = joint_of("elbow", SW_JOINT_HINGE, a, -1, b, 0);
  j.axis[2] = 1;
  sw_spec_add_joint(s, &j);
  m = sw_test_compile_at(s, 0.9);
  d = sw_data_new(m);
  sw_joint_measure(m, d, 0);
  SW_EXPECT_ABS("two-rod hinge, b at +90 deg from a (rad)", d->joint_angle[0], M_PI / 2, 1e-12);
  turn_rod_about_z(m, d, 1, x1, turn);
  sw_joint_measure(m, d, 0);
  SW_EXPECT_ABS("two-rod hinge, b turned +30 deg more (rad)", d->joint_angle[0],
                M_PI / 2 + turn, 1e-12);
  turn_rod_about_z(m, d, 1, x1, -turn);
  turn_rod_about_z(m, d, 0, x1, turn);
  sw_joint_measure(m, d, 0);
  SW_EXPECT_ABS("two-rod hinge, a turned +30 deg instead (rad)", d->joint_angle[0],
                M_PI / 2 - turn, 1e-12);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Tip force along +z on a rod along +x: a moment -F L about y, the hinge's
 * free direction, so the rod turns as a rigid body, theta = -F L t^2/(2 I)
 * with I = M (L^2/3 + r^2/4), while the angle stays small (the lever turns
 * with the rod by 1 - cos(theta) ~ 1e-4). */
static void test_hinge_free_about_axis(void **state) {
  (void)state;
  const double F[3] = {0, 0, 1.0};
  swSpec *s;
  swModel *m = hinged_beam(sw_test_sanitized() ? 10 : 20, F, 0, &s);
  swData *d = sw_data_new(m);
  double M = 7800 * M_PI * PR * PR * PL, I = M * (PL * PL / 3 + PR * PR / 4);
  double t = sqrt(2 * 0.02 * I / (F[2] * PL)); /* 0.02 rad */
  sw_test_run_to(m, d, t);
  double ref = -F[2] * PL * d->time * d->time / (2 * I);
  fprintf(stderr, "# %s: t = %.4g s, %ld steps\n", __func__, d->time, d->step);
  SW_EXPECT_REL("hinge angle (rad)", d->joint_angle[0], ref, 1e-2);
  int n = m->rod_nelem[0];
  SW_EXPECT_REL("tip z / L (rad)", SW_AT(m, d->x, m->node_adr[0] + n, 2) / PL, -ref, 1e-2);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Tip force along y, out of the hinge's plane: the hinge couple holds the
 * first element as a clamp would (default k_t = EI / (l/2), the clamp domain
 * of boundary.c), so the tip deflects as a Timoshenko cantilever,
 * F L^3/(3 EI) + F L/(4/3 G A), plus the joint gap F/k. */
static void test_hinge_stiff_across_axis(void **state) {
  (void)state;
  const int n = sw_test_sanitized() ? 10 : 20;
  const double F[3] = {0, 10.0, 0};
  double A = M_PI * PR * PR, I = A * PR * PR / 4, E = 200e9, G = E / 2.6;
  double w1 = 1.8751 * 1.8751 / (PL * PL) * sqrt(E * I / (7800 * A));
  swSpec *s;
  swModel *m = hinged_beam(n, F, 2 * w1 * 7800 * A, &s);
  swData *d = sw_data_new(m);
  double y = sw_test_relax(m, d, &SW_AT(m, d->x, m->node_adr[0] + n, 1), 20 / w1, 400 / w1, 1e-7);
  double ref = F[1] * pow(PL, 3) / (3 * E * I) + F[1] * PL / (4.0 / 3.0 * G * A) +
               F[1] / m->joint[0].stiffness;
  SW_EXPECT_REL("out-of-plane tip deflection (m)", y, ref, 2e-2);
  SW_EXPECT_ABS("hinge angle (rad)", d->joint_angle[0], 0.0, 1e-9);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* The forearm hanging on an anchored hinge at the origin (axis y, the elbow's
 * flexion axis), k = 5e5 N/m, default k_t, under gravity, with two couples on
 * its last element (the hand): tau_perp along (x + z)/sqrt(2),
 * perpendicular to the axis (sideways bending and twist), raised over t_rise
 * (a step if 0), and tau_y = 0.1 N m
 * about the axis from t = 0.  Returns the largest off-axis rotation of the
 * hinge over [0, T]: the angle between the axis as the rod's first element
 * carries it, Q^T alpha_a, and the hinge axis (what k_t holds; rotation about
 * the axis leaves it unchanged).  The other figures go to `out`. */
typedef struct {
  double dt, kt;        /* step (s) and the default k_t (N m/rad)           */
  double time, angle;   /* end of the run (s) and the hinge angle then (rad) */
  double max_at;        /* when the off-axis rotation was largest (s)       */
  double bone_rotation; /* elbow element to hand element at the end (rad)   */
} swHingeRun;

static double forearm_off_axis(double t_rise, double T, double tau_perp, swHingeRun *out) {
  const int n = 20; /* also under the sanitizers: the default k_t grows with n */
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, down[3] = {0, 0, -1};
  swRodDesc r = bone(rod_along("forearm", n, FL, FR, o, down));
  sw_spec_add_rod(s, &r);
  swJointDesc j = joint_of("elbow", SW_JOINT_HINGE, 0, 0, -1, 0);
  j.axis[1] = 1;
  j.stiffness = K_REF;
  sw_spec_add_joint(s, &j);
  const double tp = tau_perp / sqrt(2.0);
  swLoadDesc off = sw_test_load(SW_LOAD_TORQUE, 0, -1, tp, 0, tp);
  if (t_rise > 0) off.signal = sw_signal_ramp(0, 1, 0, t_rise);
  swLoadDesc about = sw_test_load(SW_LOAD_TORQUE, 0, -1, 0, 0.1, 0);
  sw_spec_add_load(s, &off);
  sw_spec_add_load(s, &about);
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);
  const double *alpha = m->joint_axis_a, u[3] = {0, 1, 0};
  double worst = 0;
  out->max_at = 0;
  while (d->time < T - 0.5 * m->dt) {
    assert_int_equal(sw_step(m, d), SW_OK);
    double Q[9], aa[3], c[3];
    sw_getQ(m, d->Q, m->joint_elem_a[0], Q);
    for (int k = 0; k < 3; k++) aa[k] = Q[k] * alpha[0] + Q[3 + k] * alpha[1] + Q[6 + k] * alpha[2];
    c[0] = aa[1] * u[2] - aa[2] * u[1];
    c[1] = aa[2] * u[0] - aa[0] * u[2];
    c[2] = aa[0] * u[1] - aa[1] * u[0];
    double off_axis = atan2(norm3(c), aa[0] * u[0] + aa[1] * u[1] + aa[2] * u[2]);
    if (off_axis > worst) worst = off_axis, out->max_at = d->time;
  }
  /* the bone's own elastic rotation from the elbow's element to the hand's,
   * acos((tr(Q_hand Q_elbow^T) - 1) / 2): it bends and twists far more than
   * the hinge gives */
  double Qe[9], Qh[9];
  sw_getQ(m, d->Q, m->joint_elem_a[0], Qe);
  sw_getQ(m, d->Q, m->elem_adr[0] + n - 1, Qh);
  double tr = 0;
  for (int k = 0; k < 9; k++) tr += Qh[k] * Qe[k];
  out->bone_rotation = acos(fmin(1.0, 0.5 * (tr - 1.0)));
  out->dt = m->dt;
  out->kt = m->joint[0].rot_stiffness;
  out->angle = d->joint_angle[0];
  out->time = d->time;
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return worst;
}

/* The pendulum that rotation about the axis should follow if it is free:
 * I theta'' = tau_y - M g (L/2) sin(theta) from rest, with the inertia of the
 * n lumped masses and the cross-sections, I = M (L^2 (1/3 + 1/(6 n^2)) + r^2/4);
 * classical RK4 at 1e-5 s, far below the error it is compared at. */
static double forced_pendulum_angle(double tau_y, int n, double T) {
  const double M = FRHO * M_PI * FR * FR * FL;
  const double I = M * (FL * FL * (1.0 / 3 + 1.0 / (6.0 * n * n)) + FR * FR / 4);
  const double mgd = M * GRAV * FL / 2;
  double th = 0, w = 0;
  const int steps = (int)ceil(T / 1e-5);
  const double h = T / steps;
#define SW_ACC(a) ((tau_y - mgd * sin(a)) / I)
  for (int i = 0; i < steps; i++) {
    double k1t = w, k1w = SW_ACC(th);
    double k2t = w + 0.5 * h * k1w, k2w = SW_ACC(th + 0.5 * h * k1t);
    double k3t = w + 0.5 * h * k2w, k3w = SW_ACC(th + 0.5 * h * k2t);
    double k4t = w + h * k3w, k4w = SW_ACC(th + h * k3t);
    th += h / 6 * (k1t + 2 * k2t + 2 * k3t + k4t);
    w += h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
#undef SW_ACC
  return th;
}

/* Claim: a hinge under an off-axis torque keeps off-axis rotation below
 * 1e-3 rad, and rotation about the axis stays free.  tau_perp = 10 N m,
 * about 50 times the forearm's largest gravity moment; it rises over
 * 10 ms (a muscle's force rises over tens of ms; the slowest off-axis mode,
 * the forearm's first bending mode held by the hinge, has a period of about
 * 6 ms).  The statics: the default k_t = E I / (l/2) makes the hinge as stiff
 * across its axis as half an element of the bone, T l / (2 E I) = 4.45e-4
 * rad (inversely proportional to n), while the bone bends and twists by tens
 * of times that between the elbow and the hand (printed).  The same torque
 * applied as a step is printed too, not asserted: the undamped bending mode
 * then overshoots the static figure about 2.5 times, past the claim. */
static void test_hinge_off_axis_torque(void **state) {
  (void)state;
  const double T = sw_test_sanitized() ? 0.05 : 0.2, t_rise = 0.01, tau = 10.0;
  swHingeRun run;
  double worst = forearm_off_axis(t_rise, T, tau, &run);
  double A = M_PI * FR * FR, I = A * FR * FR / 4, l = FL / 20;
  fprintf(stderr, "# %s: forearm n = 20, dt = %.3g s, k = %.3g N/m, k_t = %.5g N m/rad, "
                  "%.3g N m off-axis raised over %.3g s, %.3g s run; static hinge compliance "
                  "T l/(2EI) = %.4g rad; largest at t = %.4g s; the bone's own rotation "
                  "elbow to hand at the end %.4g rad\n",
          __func__, run.dt, K_REF, run.kt, tau, t_rise, run.time, tau * l / (2 * FE * I),
          run.max_at, run.bone_rotation);
  fprintf(stderr, "# %s: largest off-axis rotation of the hinge = %.4e rad (claim: < 1e-3 rad)\n",
          __func__, worst);
  assert_true(worst < 1e-3);
  SW_EXPECT_REL("rotation about the axis vs a free rigid pendulum driven by tau_y (rad)", run.angle,
                forced_pendulum_angle(0.1, 20, run.time), 1e-2);
  swHingeRun step;
  double worst_step = forearm_off_axis(0, 0.02, tau, &step);
  fprintf(stderr, "# %s: not asserted: the same torque as a step at t = 0: largest off-axis "
                  "rotation %.4e rad at t = %.4g s\n",
          __func__, worst_step, step.max_at);
}

/* ---- 3. a fixed joint makes two rods one ---- */

/* A cantilever along x, clamped at its start, under a tip force -F along y,
 * relaxed to static equilibrium with analytic damping at twice the first
 * mode's frequency: one rod of 2 n_each elements, or (joined) two rods of
 * n_each elements and half the length welded end to end by a fixed joint of
 * positional stiffness k (0: the default). */
typedef struct {
  double L, r, E, G, rho, F; /* m, m, Pa, Pa, kg/m^3, N                 */
  double chunk, tmax;        /* relaxation: chunk and longest run, s      */
} swBeam;

static double cantilever_tip(const swBeam *b, int n_each, int joined, double k) {
  swSpec *s = sw_spec_new();
  double A = M_PI * b->r * b->r, I = A * b->r * b->r / 4.0;
  double w1 = 1.8751 * 1.8751 / (b->L * b->L) * sqrt(b->E * I / (b->rho * A));
  const double dir[3] = {1, 0, 0};
  int nr = joined ? 2 : 1;
  for (int q = 0; q < nr; q++) {
    const double start[3] = {q * b->L / 2, 0, 0};
    swRodDesc r = rod_along(q ? "outer" : "inner", joined ? n_each : 2 * n_each,
                            joined ? b->L / 2 : b->L, b->r, start, dir);
    r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
    r.density = b->rho;
    r.youngs = b->E;
    r.shear_modulus = b->G;
    r.damping = SW_DAMP_ANALYTIC;
    r.gamma = 2.0 * w1 * b->rho * A;
    sw_spec_add_rod(s, &r);
  }
  swBCDesc c = sw_test_clamp(0, 0);
  sw_spec_add_bc(s, &c);
  if (joined) {
    swJointDesc j = joint_of("weld", SW_JOINT_FIXED, 0, -1, 1, 0);
    j.stiffness = k;
    sw_spec_add_joint(s, &j);
  }
  swLoadDesc f = sw_test_load(SW_LOAD_FORCE, nr - 1, -1, 0, -b->F, 0);
  sw_spec_add_load(s, &f);
  swModel *m = sw_test_compile_at(s, 0.8);
  swData *d = sw_data_new(m);
  int tip = m->node_adr[nr - 1] + m->rod_nelem[nr - 1];
  double y = sw_test_relax(m, d, &SW_AT(m, d->x, tip, 1), b->chunk, b->tmax, 1e-9);
  if (joined)
    fprintf(stderr, "#   weld: k = %.4g N/m, k_t = %.4g N m/rad\n", m->joint[0].stiffness,
            m->joint[0].rot_stiffness);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return -y;
}

/* Claim: two rods joined by a fixed joint deflect like one rod within 1%.
 * The Timoshenko cantilever of test_statics.c (L = 3 m, r = 0.25 m,
 * E = 1 MPa, G = 10 kPa, F = 0.15 N, so shear carries a third of the
 * deflection), made of two rods of L/2 welded end to end (default k). */
static void test_fixed_joint_cantilever(void **state) {
  (void)state;
  const swBeam b = {3.0, 0.25, 1e6, 1e4, 1000.0, 0.15, 2.0, 400.0};
  int n_each = sw_test_sanitized() ? 10 : 50;
  double A = M_PI * b.r * b.r, I = A * b.r * b.r / 4.0;
  double ref = b.F * pow(b.L, 3) / (3.0 * b.E * I) + b.F * b.L / (4.0 / 3.0 * b.G * A);
  double joined = cantilever_tip(&b, n_each, 1, 0), one = cantilever_tip(&b, n_each, 0, 0);
  fprintf(stderr, "# %s: two rods of %d elements joined vs one rod of %d\n", __func__, n_each,
          2 * n_each);
  SW_EXPECT_REL("tip deflection, joined (m)", joined, ref, sw_test_sanitized() ? 3e-2 : 1e-2);
  SW_EXPECT_REL("tip deflection, joined vs one rod (m) [claim: within 1%]", joined, one, 1e-2);
  /* and the tighter bound this scene has always met */
  assert_true(fabs(joined - one) <= 1e-3 * fabs(one));
}

/* The same claim on an arm-like scene: the forearm-sized bone (G = E/3) as a
 * cantilever under a 10 N tip load (a 1 kg weight in the hand), two halves
 * of 10 elements welded at mid-length.  With the default k = EA/(2 l) the
 * claim holds.  With the reference's k_f = 5e5 N/m it does not: the weld
 * carries the whole shear force F, so its gap adds F / k_f to the tip
 * deflection, 3 E I / (k_f L^3) = 5.2% of this bone's, and that is exactly
 * what is measured (the rotational part k_t adds nothing: it is the bending
 * stiffness of the Voronoi domain the weld stands in for).  A bone this size
 * needs k_f >= 100 * 3 E I / L^3 = 2.6e6 N/m for 1%. */
static void test_fixed_joint_bone_cantilever(void **state) {
  (void)state;
  const int n_each = 10;
  double A = M_PI * FR * FR, I = A * FR * FR / 4.0;
  double w1 = 1.8751 * 1.8751 / (FL * FL) * sqrt(FE * I / (FRHO * A));
  const swBeam b = {FL, FR, FE, FE / 3, FRHO, 10.0, 20 / w1, 400 / w1};
  double one = cantilever_tip(&b, n_each, 0, 0);
  double joined = cantilever_tip(&b, n_each, 1, 0);
  double joined_ref = cantilever_tip(&b, n_each, 1, K_REF);
  double ref = b.F * pow(b.L, 3) / (3.0 * b.E * I) + b.F * b.L / (4.0 / 3.0 * b.G * A);
  fprintf(stderr, "# %s: bone L = %.3g m, r = %.3g m, F = %.3g N, two rods of %d elements joined "
                  "vs one rod of %d; one rod %.6g m (Timoshenko %.6g m)\n",
          __func__, b.L, b.r, b.F, n_each, 2 * n_each, one, ref);
  SW_EXPECT_REL("tip deflection, joined with the default k vs one rod (m) [claim: within 1%]",
                joined, one, 1e-2);
  fprintf(stderr, "# %s: with the reference's k_f = %.3g N/m: joined vs one rod, rel. difference "
                  "%.4e (the claim's 1%% does not hold here); F/k_f / one rod = %.4e\n",
          __func__, K_REF, (joined_ref - one) / one, b.F / K_REF / one);
  SW_EXPECT_REL("extra tip deflection with k_f vs the weld's gap F/k_f (m)", joined_ref - one,
                b.F / K_REF, 1e-4);
}

/* ---- 4. a spherical joint carries the weight of what hangs from it ---- */

static void test_spherical_carries_weight(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  const double E = 1e9, rho = 1000, La = 0.5, ra = 0.01, Lb = 0.3, rb = 0.005;
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, down[3] = {0, 0, -1}, tip[3] = {La, 0, 0};
  double Aa = M_PI * ra * ra, Ia = Aa * ra * ra / 4;
  double w1 = 1.8751 * 1.8751 / (La * La) * sqrt(E * Ia / (rho * Aa));
  swRodDesc a = rod_along("arm", 10, La, ra, o, x), b = rod_along("load", 6, Lb, rb, tip, down);
  a.youngs = b.youngs = E;
  a.density = b.density = rho;
  a.damping = b.damping = SW_DAMP_ANALYTIC;
  /* critical damping of the arm's first bending mode and of the swing of
   * the hanging rod, w = sqrt(3 g / (2 Lb)) */
  double wp = sqrt(1.5 * GRAV / Lb);
  a.gamma = 2 * w1 * rho * Aa;
  b.gamma = 2 * wp * rho * M_PI * rb * rb;
  sw_spec_add_rod(s, &a);
  sw_spec_add_rod(s, &b);
  swBCDesc c = sw_test_clamp(0, 0);
  sw_spec_add_bc(s, &c);
  swJointDesc j = joint_of("hook", SW_JOINT_SPHERICAL, 0, -1, 1, 0);
  sw_spec_add_joint(s, &j);
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);
  /* relaxed when the hanging rod's tip stops moving (its swing is the
   * slowest mode) */
  int tip_b = m->node_adr[1] + m->rod_nelem[1];
  const int san = sw_test_sanitized();
  sw_test_relax(m, d, &SW_AT(m, d->x, tip_b, 0), 2 / wp, 200 / wp, san ? 1e-8 : 1e-11);
  const double tol = san ? 1e-5 : 1e-6;
  double weight = rho * M_PI * rb * rb * Lb * GRAV;
  SW_EXPECT_REL("vertical joint force on the arm (N)", -d->joint_force[2], weight, tol);
  SW_EXPECT_ABS("horizontal joint force / weight", hypot(d->joint_force[0], d->joint_force[1]) / weight,
                0.0, tol);
  /* the gap carries it: |g| = weight / k */
  int na = m->joint_node_a[0], nb = m->joint_node_b[0];
  double gap[3] = {SW_AT(m, d->x, nb, 0) - SW_AT(m, d->x, na, 0),
                   SW_AT(m, d->x, nb, 1) - SW_AT(m, d->x, na, 1),
                   SW_AT(m, d->x, nb, 2) - SW_AT(m, d->x, na, 2)};
  SW_EXPECT_REL("gap (m)", norm3(gap), weight / m->joint[0].stiffness, 10 * tol);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 5. energy and momentum ---- */

/* A chain of three rods: rod a hangs from an anchored spherical joint at the
 * origin (when `anchored`), rod b hangs from a on a hinge (axis y), rod c is
 * welded to b by a fixed joint; all start straight but pointing in different
 * directions, so every joint works in 3D.  E = 100 MPa, r = 1 cm, L = 0.3 m,
 * 8 elements each. */
/* With chain_arm set, the elbow holds the middle rod 4 cm beside the upper
 * rod's end, on an arm carried by its last element (swJointDesc.arm_a). */
static int chain_arm = 0;
static const double CHAIN_ARM[3] = {0.01, 0.04, 0.0};

static swModel *chain(int anchored, int undamped, int gravity, double dt_frac, swSpec **sout) {
  swSpec *s = sw_spec_new();
  const double dirs[3][3] = {{0.3, 0.2, -1}, {1, 0, -0.5}, {0, 1, -1}};
  const char *names[3] = {"upper", "middle", "lower"};
  double start[3] = {0, 0, 0};
  for (int k = 0; k < 3; k++) {
    if (k == 1 && chain_arm)
      for (int q = 0; q < 3; q++) start[q] += CHAIN_ARM[q];
    swRodDesc r = rod_along(names[k], 8, 0.3, 0.01, start, dirs[k]);
    r.youngs = 1e8;
    r.density = 1000;
    sw_spec_add_rod(s, &r);
    double len = norm3(dirs[k]);
    for (int q = 0; q < 3; q++) start[q] += 0.3 * dirs[k][q] / len;
  }
  swJointDesc j[3] = {joint_of("shoulder", SW_JOINT_SPHERICAL, 0, 0, -1, 0),
                      joint_of("elbow", SW_JOINT_HINGE, 0, -1, 1, 0),
                      joint_of("weld", SW_JOINT_FIXED, 1, -1, 2, 0)};
  j[1].axis[1] = 1;
  if (chain_arm) memcpy(j[1].arm_a, CHAIN_ARM, sizeof CHAIN_ARM);
  for (int k = anchored ? 0 : 1; k < 3; k++) {
    j[k].undamped = undamped;
    sw_spec_add_joint(s, &j[k]);
  }
  if (gravity) {
    const double g[3] = {0, 0, -GRAV};
    sw_spec_set_gravity(s, g);
  }
  *sout = s;
  return sw_test_compile_at(s, dt_frac);
}

static void energy_balance(int undamped) {
  swSpec *s;
  swModel *m = chain(1, undamped, 1, 0.9, &s);
  swData *d = sw_data_new(m);
  double e[3], e0, worst = 0, kmax = 0, joint_max = 0;
  sw_energy(m, d, e);
  e0 = e[0] + e[1] - e[2];
  const double T = sw_test_sanitized() ? 0.1 : 0.5;
  while (d->time < T) {
    sw_test_run_to(m, d, d->time + 0.005);
    sw_energy(m, d, e);
    worst = fmax(worst, fabs(e[0] + e[1] - e[2] - e0));
    kmax = fmax(kmax, e[0]);
    for (int k = 0; k < 3; k++) joint_max = fmax(joint_max, norm3(d->joint_force + 3 * k));
  }
  fprintf(stderr, "# %s: %s joints, %ld steps, largest kinetic energy %.4g J, work done %.4g J, "
                  "largest joint force %.3g N, elbow angle %.4f rad\n",
          __func__, undamped ? "undamped" : "damped", d->step, kmax, e[2], joint_max,
          d->joint_angle[1]);
  SW_EXPECT_ABS("largest |kinetic + elastic - work - E0| / largest kinetic", worst / kmax, 0.0,
                1e-4);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_energy_undamped(void **state) {
  (void)state;
  energy_balance(1);
}

/* With the default joint damping the dissipated work is booked: the balance
 * still holds. */
static void test_energy_damped(void **state) {
  (void)state;
  energy_balance(0);
}

/* Linear momentum sum m v, and angular momentum about the origin,
 * sum m x x v + sum Q^T J^ w / e. */
static void momenta(const swModel *m, const swData *d, double p[3], double L[3]) {
  memset(p, 0, 3 * sizeof *p);
  memset(L, 0, 3 * sizeof *L);
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
      double x[3], v[3];
      sw_get3(m, d->x, i, x);
      sw_get3(m, d->v, i, v);
      double mass = m->mass[i];
      for (int k = 0; k < 3; k++) p[k] += mass * v[k];
      L[0] += mass * (x[1] * v[2] - x[2] * v[1]);
      L[1] += mass * (x[2] * v[0] - x[0] * v[2]);
      L[2] += mass * (x[0] * v[1] - x[1] * v[0]);
    }
  for (int r = 0; r < m->nrod; r++)
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) {
      double Q[9], w[3];
      sw_getQ(m, d->Q, e, Q);
      sw_get3(m, d->omega, e, w);
      for (int a = 0; a < 3; a++) {
        double h = SW_AT(m, m->inertia, e, a) * w[a] / d->dilatation[e];
        for (int k = 0; k < 3; k++) L[k] += Q[3 * a + k] * h;
      }
    }
}

/* The chain without its anchor, floating free and tumbling for a time T at
 * a fraction of the stable step; returns the largest relative changes of
 * linear and angular momentum. */
static void free_chain_drift(double dt_frac, double T, double *dp, double *dL) {
  swSpec *s;
  swModel *m = chain(0, 1, 0, dt_frac, &s);
  swData *d = sw_data_new(m);
  /* rigid rotation about an oblique axis, plus a sideways push of the middle
   * rod that bends the hinge and the weld */
  const double spin[3] = {1.0, -2.0, 0.5};
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
      double x[3], v[3];
      sw_get3(m, d->x, i, x);
      v[0] = spin[1] * x[2] - spin[2] * x[1];
      v[1] = spin[2] * x[0] - spin[0] * x[2];
      v[2] = spin[0] * x[1] - spin[1] * x[0];
      sw_set3(m, d->v, i, v);
    }
  for (int i = m->node_adr[1]; i <= m->node_adr[1] + m->rod_nelem[1]; i++)
    SW_AT(m, d->v, i, 1) += 0.05;
  for (int r = 0; r < m->nrod; r++) /* w = Q spin, material frame */
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++)
      for (int a = 0; a < 3; a++) {
        double da[3];
        for (int k = 0; k < 3; k++) da[k] = SW_AT(m, d->Q, e, 3 * a + k);
        SW_AT(m, d->omega, e, a) = da[0] * spin[0] + da[1] * spin[1] + da[2] * spin[2];
      }
  double p0[3], L0[3], p[3], L[3];
  momenta(m, d, p0, L0);
  *dp = *dL = 0;
  while (d->time < T) {
    sw_test_run_to(m, d, d->time + 0.01);
    momenta(m, d, p, L);
    for (int q = 0; q < 3; q++) {
      *dp = fmax(*dp, fabs(p[q] - p0[q]) / norm3(p0));
      *dL = fmax(*dL, fabs(L[q] - L0[q]) / norm3(L0));
    }
  }
  fprintf(stderr, "# %s: dt = %.3g s, %ld steps, |p0| = %.4g kg m/s, |L0| = %.4g kg m^2/s, "
                  "elbow angle %.4f rad: |p - p0| / |p0| <= %.3g, |L - L0| / |L0| <= %.3g\n",
          __func__, m->dt, d->step, norm3(p0), norm3(L0), d->joint_angle[0], *dp, *dL);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* The joint forces and couples come in equal and opposite pairs, and the
 * undamped joints' forces lie along the gap, so linear and angular momentum
 * are both conserved to round-off: the drift turns each element by its exact
 * free rotation (integrate.c), so the integrator adds no error of its own to
 * L.  (When the inertial couple was a couple in the kick, L drifted by about
 * 2.1e-9 at 0.9 of the stable step, 9.0e-10 at 0.45.)  A couple
 * imbalance would show as a drift that does not depend on dt either, but
 * far above round-off (the 28,000 steps at the smaller dt allow some 1e-12). */
static void test_momentum_free_chain(void **state) {
  (void)state;
  const double T = sw_test_sanitized() ? 0.05 : 0.5;
  double dp1, dL1, dp2, dL2;
  free_chain_drift(0.9, T, &dp1, &dL1);
  free_chain_drift(0.45, T, &dp2, &dL2);
  SW_EXPECT_ABS("largest |p - p0| / |p0|", fmax(dp1, dp2), 0.0, 1e-12);
  SW_EXPECT_ABS("largest |L - L0| / |L0|, 0.9 and 0.45 of the stable step", fmax(dL1, dL2), 0.0, 1e-11);
}

/* The same with the elbow on an arm: its spring's force acts at the arm's
 * end and turns the upper rod's element by r x F, so linear and angular
 * momentum are still kept (without that couple L would drift by about the
 * force's moment r x F over the run); the undamped chain's energy balance
 * closes as the plain chain's does. */
static void test_arm_momentum_energy(void **state) {
  (void)state;
  const double T = sw_test_sanitized() ? 0.05 : 0.5;
  double dp1, dL1, dp2, dL2;
  chain_arm = 1;
  free_chain_drift(0.9, T, &dp1, &dL1);
  free_chain_drift(0.45, T, &dp2, &dL2);
  SW_EXPECT_ABS("arm: largest |p - p0| / |p0|", fmax(dp1, dp2), 0.0, 1e-12);
  SW_EXPECT_ABS("arm: largest |L - L0| / |L0|", fmax(dL1, dL2), 0.0, 1e-11);
  swSpec *s;
  swModel *m = chain(1, 1, 1, 0.9, &s);
  swData *d = sw_data_new(m);
  double e[3], e0, worst = 0, kmax = 0;
  sw_energy(m, d, e);
  e0 = e[0] + e[1] - e[2];
  while (d->time < T) {
    sw_test_run_to(m, d, d->time + 0.005);
    sw_energy(m, d, e);
    worst = fmax(worst, fabs(e[0] + e[1] - e[2] - e0));
    kmax = fmax(kmax, e[0]);
  }
  /* the point on the arm stays with the middle rod's start */
  double xa[3], xb[3], Q[9], r[3];
  sw_get3(m, d->x, m->joint_node_a[1], xa);
  sw_get3(m, d->x, m->joint_node_b[1], xb);
  sw_getQ(m, d->Q, m->joint_elem_a[1], Q);
  for (int k = 0; k < 3; k++) /* r = Q^T o */
    r[k] = Q[k] * m->joint_arm_a[3] + Q[3 + k] * m->joint_arm_a[4] + Q[6 + k] * m->joint_arm_a[5];
  const double gap = sqrt(pow(xa[0] + r[0] - xb[0], 2) + pow(xa[1] + r[1] - xb[1], 2) +
                          pow(xa[2] + r[2] - xb[2], 2));
  fprintf(stderr, "# %s: undamped, gravity, %.2f s: |E - E0| <= %.3e J of kinetic energy up to "
          "%.3e J; the arm's end %.3e m from the middle rod's start (arm %.3f m)\n", __func__, T,
          worst, kmax, gap, norm3(CHAIN_ARM));
  assert_true(worst < 1e-3 * kmax);
  assert_true(gap < 2e-3);
  chain_arm = 0;
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 6. stable time step ---- */

/* A soft rod (E = 1 MPa, L = 1 m, r = 2.5 cm, 20 elements) anchored at its
 * start by a spherical joint of stiffness `k`, no gravity, with a small
 * deterministic velocity noise; returns whether `steps` steps at `dt` stay
 * stable. */
static int anchored_rod_stable(double k, double dt_frac, long steps, double *dt_est) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0};
  swRodDesc r = rod_along("rod", 20, 1.0, 0.025, o, x);
  sw_spec_add_rod(s, &r);
  swJointDesc j = joint_of("pin", SW_JOINT_SPHERICAL, 0, 0, -1, 0);
  j.stiffness = k;
  j.undamped = 1;
  sw_spec_add_joint(s, &j);
  swModel *m = sw_test_compile(s);
  *dt_est = sw_stable_dt(m);
  sw_model_free(m);
  sw_spec_set_dt(s, dt_frac * *dt_est);
  m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  unsigned long long seed = 12345;
  /* node by node, component by component (the order of the draws) */
  for (int rod = 0; rod < m->nrod; rod++)
    for (int i = m->node_adr[rod]; i <= m->node_adr[rod] + m->rod_nelem[rod]; i++)
      for (int c = 0; c < 3; c++) {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        SW_AT(m, d->v, i, c) = 1e-6 * ((double)(seed >> 11) / 9007199254740992.0 - 0.5);
      }
  int rc = sw_steps(m, d, steps);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return rc == SW_OK;
}

/* A joint 100 times stiffer than the rod's elements: its bound, not the
 * rod's, sets the estimate, and the estimate holds: stable at 0.95 of it,
 * unstable at 1.2 (tests/runtime/test_stability.c does the same for rods). */
static void test_stiff_joint_stable_dt(void **state) {
  (void)state;
  double EA_l = 1e6 * M_PI * 0.025 * 0.025 / 0.05, est, est_soft;
  long steps = sw_test_sanitized() ? 5000 : 20000;
  assert_true(anchored_rod_stable(0.5 * EA_l, 0.95, 100, &est_soft));
  assert_true(anchored_rod_stable(100 * EA_l, 0.95, steps, &est));
  fprintf(stderr, "# %s: estimate %.4g s with k = 100 EA/l, %.4g s with the default k = EA/(2l)\n",
          __func__, est, est_soft);
  /* node of mass m/2 on the joint spring: w^2 ~ (k + EA/l) / (m/2) */
  double mass = 1000 * M_PI * 0.025 * 0.025 * 0.05;
  SW_EXPECT_REL("estimate vs 0.95 * 2 / w of the end node", est,
                0.95 * 2 / sqrt((100 + 1) * EA_l / (0.5 * mass)), 2e-2);
  int blew = !anchored_rod_stable(100 * EA_l, 1.2, steps, &est);
  fprintf(stderr, "# %s: at 1.2 times the estimate the run %s\n", __func__,
          blew ? "went unstable" : "stayed stable");
  assert_true(blew);
}

/* ---- 7. defaults, validation ---- */

static void test_defaults(void **state) {
  (void)state;
  swJointDesc j;
  memset(&j, 0x55, sizeof j);
  sw_joint_desc_init(&j);
  assert_int_equal(j.kind, SW_JOINT_SPHERICAL);
  assert_int_equal(j.rod_a, 0);
  assert_int_equal(j.node_a, -1);
  assert_int_equal(j.rod_b, -1);
  assert_int_equal(j.node_b, 0);
  assert_true(j.stiffness == 0 && j.damping == 0 && j.rot_stiffness == 0 && j.rot_damping == 0);
  assert_true(j.axis[0] == 0 && j.axis[1] == 0 && j.axis[2] == 0 && j.undamped == 0);
  assert_non_null(j.name);

  /* two different rods joined by a fixed joint: the resolved values */
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, p[3] = {0.5, 0, 0};
  swRodDesc a = rod_along("stiff", 10, 0.5, 0.01, o, x), b = rod_along("soft", 5, 0.4, 0.02, p, x);
  a.youngs = 1e9;
  b.youngs = 1e6;
  sw_spec_add_rod(s, &a);
  sw_spec_add_rod(s, &b);
  swJointDesc f = joint_of("weld", SW_JOINT_FIXED, 0, -1, 1, 0);
  sw_spec_add_joint(s, &f);
  swModel *m = sw_test_compile(s);
  const swJointDesc *r = &m->joint[0];
  assert_string_equal(r->name, "weld");
  assert_int_equal(r->node_a, 10);
  assert_int_equal(m->joint_node_a[0], m->node_adr[0] + 10);
  assert_int_equal(m->joint_node_b[0], m->node_adr[1]);
  assert_int_equal(m->joint_elem_a[0], m->elem_adr[0] + 9);
  assert_int_equal(m->joint_elem_b[0], m->elem_adr[1]);
  double la = 0.05, lb = 0.08, Aa = M_PI * 1e-4, Ab = M_PI * 4e-4;
  double k = 0.5 * fmin(1e9 * Aa / la, 1e6 * Ab / lb);
  SW_EXPECT_REL("k = min(EA/l)/2 (N/m)", r->stiffness, k, 1e-12);
  double ma = 0.5 * 1000 * Aa * la, mb = 0.5 * 1000 * Ab * lb, mu = ma * mb / (ma + mb);
  SW_EXPECT_REL("nu = 0.2 sqrt(k mu) (N s/m)", r->damping, 0.2 * sqrt(k * mu), 1e-12);
  double Ia = Aa * 1e-4 / 4, Ib = Ab * 4e-4 / 4, D = 0.5 * (la + lb);
  double kt = fmin(1e9 * Ia, 1e6 * Ib) / D;
  SW_EXPECT_REL("k_t = min(EI)/D (N m/rad)", r->rot_stiffness, kt, 1e-12);
  double Ja = 1000 * la * Ia, Jb = 1000 * lb * Ib;
  SW_EXPECT_REL("c_t = 0.2 sqrt(k_t J_mu) (N m s/rad)", r->rot_damping,
                0.2 * sqrt(kt * Ja * Jb / (Ja + Jb)), 1e-12);
  /* the default joint does not lower the scene's stable step by more than
   * what its damper costs (here the stiff rod's elements set it) */
  double rods_dt = fmin(sw_stable_dt_rod(m, 0), sw_stable_dt_rod(m, 1));
  SW_EXPECT_REL("scene dt estimate / the rods' own", sw_stable_dt(m) / rods_dt, 1.0, 0.1);
  sw_model_free(m);
  sw_spec_free(s);

  /* given values are kept; undamped means no damping */
  s = sw_spec_new();
  sw_spec_add_rod(s, &a);
  swJointDesc h = joint_of("pin", SW_JOINT_HINGE, 0, 0, -1, 0);
  h.axis[2] = 2.0;
  h.stiffness = 123;
  h.rot_stiffness = 4.5;
  h.undamped = 1;
  sw_spec_add_joint(s, &h);
  m = sw_test_compile(s);
  r = &m->joint[0];
  assert_true(r->stiffness == 123 && r->rot_stiffness == 4.5 && r->damping == 0 && r->rot_damping == 0);
  assert_int_equal(r->node_b, -1);
  assert_int_equal(m->joint_node_b[0], -1);
  assert_int_equal(m->joint_elem_b[0], -1);
  swData *d = sw_data_new(m);
  assert_true(d->joint_angle[0] == 0);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Compile a scene with one rod of 5 elements ('arm') and a second ('hand'),
 * plus joint j; it must fail with exactly `message`. */
static void expect_joint_error(const swJointDesc *j, const char *message) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, p[3] = {0.5, 0, 0};
  swRodDesc a = rod_along("arm", 5, 0.5, 0.01, o, x), b = rod_along("hand", 4, 0.2, 0.01, p, x);
  sw_spec_add_rod(s, &a);
  sw_spec_add_rod(s, &b);
  swJointDesc first = joint_of("wrist", SW_JOINT_SPHERICAL, 0, -1, 1, 0);
  sw_spec_add_joint(s, &first);
  sw_spec_add_joint(s, j);
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  int accepted = m != NULL;
  sw_model_free(m);
  sw_spec_free(s);
  fprintf(stderr, "# expect_joint_error: \"%s\"\n", err);
  assert_false(accepted);
  assert_string_equal(err, message);
}

static void test_validation(void **state) {
  (void)state;
  swJointDesc j = joint_of("elbow", SW_JOINT_HINGE, 0, -1, 1, 0);
  j.axis[1] = 1;
  swJointDesc bad = j;
  bad.kind = (swJointKind)7;
  expect_joint_error(&bad, "joint 'elbow': unknown kind 7");
  bad = j, bad.rod_a = 2;
  expect_joint_error(&bad, "joint 'elbow': rod_a index 2 out of range [0, 2)");
  bad = j, bad.rod_a = -1;
  expect_joint_error(&bad, "joint 'elbow': rod_a index -1 out of range [0, 2)");
  bad = j, bad.rod_b = -2;
  expect_joint_error(&bad, "joint 'elbow': rod_b index -2 out of range [0, 2) (-1 = anchored)");
  bad = j, bad.node_a = 6;
  expect_joint_error(&bad, "joint 'elbow': node_a 6 out of range for rod 'arm' (nodes 0..5, -1 = last)");
  bad = j, bad.node_b = -2;
  expect_joint_error(&bad, "joint 'elbow': node_b -2 out of range for rod 'hand' (nodes 0..4, -1 = last)");
  bad = j, bad.rod_b = 0, bad.node_b = 5;
  expect_joint_error(&bad, "joint 'elbow': joins node 5 of rod 'arm' to itself");
  bad = j, bad.rod_b = -1, bad.anchor[2] = NAN;
  expect_joint_error(&bad, "joint 'elbow': anchor is not finite");
  bad = j, bad.axis[1] = 0;
  expect_joint_error(&bad, "joint 'elbow': hinge axis must be finite and nonzero");
  bad = j, bad.axis[0] = INFINITY;
  expect_joint_error(&bad, "joint 'elbow': hinge axis must be finite and nonzero");
  bad = j, bad.stiffness = -1;
  expect_joint_error(&bad, "joint 'elbow': stiffness must be finite and >= 0 (0 = automatic), got -1");
  bad = j, bad.damping = NAN;
  expect_joint_error(&bad, "joint 'elbow': damping must be finite and >= 0 (0 = automatic), got nan");
  bad = j, bad.rot_stiffness = INFINITY;
  expect_joint_error(&bad, "joint 'elbow': rotational stiffness must be finite and >= 0 (0 = automatic), got inf");
  bad = j, bad.rot_damping = -2.5;
  expect_joint_error(&bad, "joint 'elbow': rotational damping must be finite and >= 0 (0 = automatic), got -2.5");
  bad = j, bad.undamped = 1, bad.damping = 3;
  expect_joint_error(&bad, "joint 'elbow': declared undamped but damping is given");
  bad = j, bad.name = "wrist";
  expect_joint_error(&bad, "joint 'wrist': name already used by joint 0");
  /* a spherical joint needs no axis */
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0};
  swRodDesc a = rod_along("arm", 5, 0.5, 0.01, o, x);
  sw_spec_add_rod(s, &a);
  swJointDesc ok = joint_of("free", SW_JOINT_SPHERICAL, 0, 2, -1, 0);
  sw_spec_add_joint(s, &ok);
  swModel *m = sw_test_compile(s);
  assert_int_equal(m->njoint, 1);
  assert_int_equal(m->joint_elem_a[0], 2); /* interior node i -> element i */
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 8. output ---- */

static void test_joint_output(void **state) {
  (void)state;
  swSpec *s;
  swModel *m = chain(1, 0, 1, 0.9, &s);
  swData *d = sw_data_new(m);
  char path[64];
  snprintf(path, sizeof path, "/tmp/sinew_test_joint_XXXXXX");
  int fd = mkstemp(path);
  assert_true(fd >= 0);
  close(fd);
  char err[256] = "";
  swOutputOptions opt = {.duration = 0.01};
  swOutput *out = sw_output_open(path, m, &opt, err, sizeof err);
  if (!out) fprintf(stderr, "# %s\n", err);
  assert_non_null(out);
  swRunOptions ro = {.duration = 0.01, .every = 0.005, .quiet = 1};
  assert_int_equal(sw_run(m, d, out, &ro), SW_OK);
  long frames = sw_output_frames(out);
  assert_int_equal(sw_output_close(out, "complete"), SW_OK);

  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  const char *names[3] = {"shoulder", "elbow", "weld"};
  for (int k = 0; k < 3; k++) {
    char p[128];
    snprintf(p, sizeof p, "/joints/%s/force", names[k]);
    hid_t ds = H5Dopen2(file, p, H5P_DEFAULT);
    assert_true(ds >= 0);
    hid_t sp = H5Dget_space(ds);
    hsize_t dims[2];
    assert_int_equal(H5Sget_simple_extent_ndims(sp), 2);
    H5Sget_simple_extent_dims(sp, dims, NULL);
    assert_true(dims[0] == (hsize_t)frames && dims[1] == 3);
    double *buf = malloc(sizeof(double) * 3 * (size_t)frames);
    assert_true(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
    /* the last frame is the final state (measured there, not half a step off) */
    double diff = 0;
    for (int q = 0; q < 3; q++) diff = fmax(diff, fabs(buf[3 * (frames - 1) + q] - d->joint_force[3 * k + q]));
    fprintf(stderr, "# %s: %s [%llu, 3], last force (%.4g, %.4g, %.4g) N, |file - state| = %.3g\n",
            __func__, p, (unsigned long long)dims[0], buf[3 * (frames - 1)], buf[3 * (frames - 1) + 1],
            buf[3 * (frames - 1) + 2], diff);
    assert_true(diff == 0);
    free(buf);
    assert_true(H5Aexists(ds, "units") > 0);
    H5Sclose(sp);
    H5Dclose(ds);
    snprintf(p, sizeof p, "/joints/%s/angle", names[k]);
    assert_int_equal(H5Lexists(file, p, H5P_DEFAULT) > 0, k == 1); /* hinges only */
  }
  hid_t ds = H5Dopen2(file, "/joints/elbow/angle", H5P_DEFAULT);
  hid_t sp = H5Dget_space(ds);
  hsize_t dims[1];
  assert_int_equal(H5Sget_simple_extent_ndims(sp), 1);
  H5Sget_simple_extent_dims(sp, dims, NULL);
  assert_true(dims[0] == (hsize_t)frames);
  double angle[16];
  assert_true(frames <= 16);
  assert_true(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, angle) >= 0);
  fprintf(stderr, "# %s: /joints/elbow/angle [%llu]: first %.6g rad, last %.6g rad (state %.6g)\n",
          __func__, (unsigned long long)dims[0], angle[0], angle[frames - 1], d->joint_angle[1]);
  assert_true(angle[frames - 1] == d->joint_angle[1]);
  /* the elbow starts at the angle from the upper rod's tangent (0.3, 0.2, -1)
   * to the middle rod's (1, 0, -0.5) about y: in the x-z plane, from
   * (0.3, -1) to (1, -0.5), i.e. atan2(y . (ta x tb), ta . tb - ta_y tb_y) */
  double a0 = atan2(-1 * 1 - 0.3 * -0.5, 0.3 * 1 + -1 * -0.5);
  SW_EXPECT_ABS("initial elbow angle (rad)", angle[0], a0, 1e-12);
  H5Sclose(sp);
  H5Dclose(ds);
  H5Fclose(file);
  unlink(path);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_defaults),
      cmocka_unit_test(test_validation),
      cmocka_unit_test(test_joint_output),
      cmocka_unit_test(test_pendulum_hinge_period),
      cmocka_unit_test(test_pendulum_spherical),
      cmocka_unit_test(test_hinge_free_about_axis),
      cmocka_unit_test(test_hinge_angle_convention),
      cmocka_unit_test(test_hinge_stiff_across_axis),
      cmocka_unit_test(test_hinge_off_axis_torque),
      cmocka_unit_test(test_fixed_joint_cantilever),
      cmocka_unit_test(test_fixed_joint_bone_cantilever),
      cmocka_unit_test(test_spherical_carries_weight),
      cmocka_unit_test(test_energy_undamped),
      cmocka_unit_test(test_energy_damped),
      cmocka_unit_test(test_momentum_free_chain),
      cmocka_unit_test(test_arm_momentum_energy),
      cmocka_unit_test(test_stiff_joint_stable_dt),
  };
  return cmocka_run_group_tests_name("joint", tests, NULL, NULL);
}
