/* test_obstacle.c — rigid obstacles (obstacle.c) against closed forms: a rod
 * at rest across a sphere, a cylinder, a capsule, an ellipsoid and on a box
 * under gravity carries its weight (the contact forces sum to it) with the
 * static penetration weight / k of the one element that touches (n k on a
 * face, where every element takes its share); a rod thrown flat at a box's
 * top face moves as the same rod thrown at a ground plane of the same
 * stiffness and damping (the same law there: equal to round-off); a capsule
 * carried by a free bone, struck by a rod, keeps the pair's momentum and
 * angular momentum (nodes and element spins) to round-off and, undamped, its
 * energy to O(dt^2), damped, the balance of /diagnostics/energy; a rod of
 * long elements thrown at a sphere smaller than an element between its
 * nodes stops and bounces (the segment-shape distance: the nodes alone would
 * pass it); the chunk-box broad phase finds the same loads, bit for bit, as
 * the brute force loop on a field of many obstacles; the validation messages.
 *
 * Design.  Scenes are built through the public API (swObstacleDesc,
 * sw_spec_add_obstacle); tests read the contact records and figures the
 * runtime leaves in the state and call obstacle.c's kernel directly
 * (internal.h) only to compare the two broad phases. */
#include "testutil.h"
#include "vec.h"
#include "internal.h"

static const double RE = 1e7, RRHO = 1000, RL = 0.1, RR = 0.002, G = 9.81;

static swRodDesc rod_desc(const char *name, int n, double length, double radius, const double start[3],
                          const double dir[3]) {
  swRodDesc r = sw_test_rod(name, n, length, radius, start, dir, NULL);
  r.density = RRHO;
  r.youngs = RE;
  r.poisson = 0.5;
  return r;
}

static double rod_mass(const swModel *m, int r) {
  double M = 0;
  for (int i = 0; i <= m->rod_nelem[r]; i++) M += m->mass[m->node_adr[r] + i];
  return M;
}

static double total_energy(const swModel *m, swData *d) {
  double E[3];
  sw_energy(m, d, E);
  return E[0] + E[1] - E[2];
}

/* Sum of the recorded contact forces along z, N. */
static double contact_lift(const swData *d) {
  double lift = 0;
  for (int c = 0; c < d->obstacle_contacts; c++)
    lift += d->obstacle_contact[c].force * d->obstacle_contact[c].normal[2];
  return lift;
}

/* ---- 1. a rod at rest on each shape ---- */

enum { NREST = 21 };

/* The rod along x, its middle over the shape's top at z = 0 (its axis r
 * above), under gravity; k sets the penetration well below the radius. */
static void rest_on(swObstacleShape shape) {
  static const char *const names[] = {"sphere", "capsule", "cylinder", "box", "ellipsoid"};
  const double k = 1000, Rs = 0.02;
  swSpec *s = sw_spec_new();
  const double start[3] = {-0.5 * RL, 0, RR}, ex[3] = {1, 0, 0}, g[3] = {0, 0, -G};
  swRodDesc r = rod_desc("rod", NREST, RL, RR, start, ex);
  r.damping = SW_DAMP_LINEAR;
  r.gamma = 1.0; /* kg/(m s): the rod's bending settles in ~10 ms */
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  sw_spec_set_gravity(s, g);
  swObstacleDesc o;
  sw_obstacle_desc_init(&o);
  o.name = names[shape];
  o.shape = shape;
  o.stiffness = k;
  o.damping = 2 * sqrt(k * 1e-4); /* about critical for one element's mass */
  o.radius = Rs;
  o.length = 0.03;
  o.axis[0] = 0, o.axis[1] = 1, o.axis[2] = 0; /* across the rod */
  o.normal[0] = 1, o.normal[1] = 0, o.normal[2] = 0;
  o.half[0] = 0.03, o.half[1] = 0.02, o.half[2] = Rs; /* ellipsoid: z up, Rs */
  if (shape == SW_OBSTACLE_BOX) o.half[0] = RL, o.half[1] = 0.01, o.half[2] = 0.01;
  const double cz = shape == SW_OBSTACLE_BOX ? -o.half[2] : shape == SW_OBSTACLE_ELLIPSOID ? -o.half[1] : -Rs;
  o.centre[2] = cz;
  if (shape == SW_OBSTACLE_ELLIPSOID) /* the semi-axis along axis (y) is o.half[2] */
    o.half[0] = 0.03, o.half[1] = Rs, o.half[2] = 0.015;
  assert_int_equal(sw_spec_add_obstacle(s, &o), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  swData *d = sw_data_new(m);
  const double W = rod_mass(m, 0) * G;
  const int mid = m->node_adr[0] + NREST / 2;
  sw_test_relax(m, d, &SW_AT(m, d->x, mid, 2), 0.01, 0.3, 1e-9);
  assert_int_equal(sw_step(m, d), SW_OK);
  char what[96];
  snprintf(what, sizeof what, "%s: contact force / weight", names[shape]);
  SW_EXPECT_REL(what, contact_lift(d) / W, 1.0, 1e-4);
  const double expect = shape == SW_OBSTACLE_BOX ? W / (NREST * k) : W / k;
  snprintf(what, sizeof what, "%s: penetration (m), %d element(s) touch", names[shape],
           d->obstacle_contacts);
  SW_EXPECT_REL(what, d->obstacle_max_depth, expect, 2e-3);
  if (shape != SW_OBSTACLE_BOX) assert_int_equal(d->obstacle_contacts, 1);
  sw_data_free(d);
  sw_model_free(m);
}

static void test_rest_sphere(void **state) { (void)state; rest_on(SW_OBSTACLE_SPHERE); }
static void test_rest_cylinder(void **state) { (void)state; rest_on(SW_OBSTACLE_CYLINDER); }
static void test_rest_capsule(void **state) { (void)state; rest_on(SW_OBSTACLE_CAPSULE); }
static void test_rest_ellipsoid(void **state) { (void)state; rest_on(SW_OBSTACLE_ELLIPSOID); }
static void test_rest_box(void **state) { (void)state; rest_on(SW_OBSTACLE_BOX); }

/* ---- 2. a box's face against the ground's plane ---- */

/* A rod flat above z = 0, thrown down at 0.1 m/s without gravity, on a
 * ground plane (box = 0) or a box's top face of the same k and gamma. */
static swModel *throw_flat(int box) {
  swSpec *s = sw_spec_new();
  const double start[3] = {-0.5 * RL, 0, RR * 1.5}, ex[3] = {1, 0, 0};
  swRodDesc r = rod_desc("rod", 10, RL, RR, start, ex);
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  const double k = 50, gamma = 0.02;
  if (box) {
    swObstacleDesc o;
    sw_obstacle_desc_init(&o);
    o.shape = SW_OBSTACLE_BOX;
    o.half[0] = o.half[1] = 1, o.half[2] = 0.5;
    o.centre[2] = -0.5;
    o.stiffness = k, o.damping = gamma;
    assert_int_equal(sw_spec_add_obstacle(s, &o), 0);
  } else {
    swGroundDesc g;
    sw_ground_desc_init(&g);
    g.stiffness = k, g.damping = gamma;
    g.contact_tolerance = 1e-300; /* the plane's edge of contact, as the box's */
    assert_int_equal(sw_spec_add_ground(s, &g), 0);
  }
  sw_spec_set_dt(s, 2e-6);
  swModel *m = sw_test_compile(s);
  sw_spec_free(s);
  return m;
}

static void test_box_face_is_ground(void **state) {
  (void)state;
  swModel *m[2] = {throw_flat(0), throw_flat(1)};
  swData *d[2];
  const double v[3] = {0, 0, -0.1};
  for (int j = 0; j < 2; j++) {
    d[j] = sw_data_new(m[j]);
    for (int i = 0; i <= 10; i++) sw_set3(m[j], d[j]->v, i, v);
  }
  double worst = 0, vz_end = 0, deepest = 0;
  for (int frame = 0; frame < 40; frame++) { /* 40 ms: down, in, out and up */
    for (int j = 0; j < 2; j++) assert_int_equal(sw_steps(m[j], d[j], 500), SW_OK);
    deepest = fmax(deepest, d[1]->obstacle_max_depth);
    for (int i = 0; i <= 10; i++)
      for (int q = 0; q < 3; q++)
        worst = fmax(worst, fabs(SW_AT(m[0], d[0]->x, i, q) - SW_AT(m[1], d[1]->x, i, q)));
  }
  vz_end = SW_AT(m[1], d[1]->v, 5, 2);
  fprintf(stderr, "# %s: deepest %.3g m, rebound velocity %.4g m/s (restitution %.3f)\n", __func__,
          deepest, vz_end, vz_end / 0.1);
  assert_true(deepest > 0 && vz_end > 0); /* it did touch and bounce */
  SW_EXPECT_ABS("largest difference of node positions, box - ground (m)", worst, 0.0, 1e-15);
  for (int j = 0; j < 2; j++) sw_data_free(d[j]), sw_model_free(m[j]);
}

/* ---- 3. a capsule carried by a free bone ---- */

/* The bone along x (0.1 m, r = 5 mm, E = 10 MPa) carries a capsule 2 cm
 * off its middle node along y, its axis along z; a thin rod along z, 3 cm
 * further along y, is thrown at it (off its centre, so the bone turns). */
static swModel *carried_scene(double gamma, double mu) {
  swSpec *s = sw_spec_new();
  const double sb[3] = {-0.05, 0, 0}, ex[3] = {1, 0, 0}, ez[3] = {0, 0, 1};
  swRodDesc bone = rod_desc("bone", 10, 0.1, 0.005, sb, ex);
  assert_int_equal(sw_spec_add_rod(s, &bone), 0);
  const double sr[3] = {0.003, 0.02 + 0.006 + RR + 1e-4, -0.04};
  swRodDesc rod = rod_desc("rod", 16, 0.08, RR, sr, ez);
  assert_int_equal(sw_spec_add_rod(s, &rod), 1);
  swObstacleDesc o;
  sw_obstacle_desc_init(&o);
  o.name = "pulley";
  o.shape = SW_OBSTACLE_CAPSULE;
  o.radius = 0.006, o.length = 0.03;
  o.centre[1] = 0.02;
  o.carrier_rod = 0, o.carrier_node = 5;
  o.stiffness = 200, o.damping = gamma;
  o.static_friction = o.kinetic_friction = mu;
  static const int touch[1] = {1};
  o.nrods = 1, o.rods = touch;
  assert_int_equal(sw_spec_add_obstacle(s, &o), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  return m;
}

static void carried_run(double gamma, double mu) {
  swModel *m = carried_scene(gamma, mu);
  swData *d = sw_data_new(m);
  const double v[3] = {0, -0.2, mu > 0 ? 0.1 : 0}; /* with friction, sliding along the axis too */
  for (int i = m->node_adr[1]; i <= m->node_adr[1] + m->rod_nelem[1]; i++) sw_set3(m, d->v, i, v);
  double P0[3], L0[3], P[3], L[3];
  sw_test_momenta(m, d, P0, L0);
  const double E0 = total_energy(m, d);
  double deepest = 0;
  int touched = 0, stuck = 0;
  while (d->time < 0.02) {
    assert_int_equal(sw_steps(m, d, 50), SW_OK);
    touched += d->obstacle_contacts > 0;
    stuck += d->obstacle_stuck > 0;
    deepest = fmax(deepest, d->obstacle_max_depth);
  }
  sw_test_momenta(m, d, P, L);
  double bone_P[3] = {0, 0, 0};
  for (int i = 0; i <= 10; i++)
    for (int k = 0; k < 3; k++) bone_P[k] += m->mass[i] * SW_AT(m, d->v, i, k);
  fprintf(stderr, "# carried (gamma %g, mu %g): %d frames in contact (%d stuck), deepest %.3g m, bone's "
          "momentum (%.3g, %.3g, %.3g) kg m/s\n", gamma, mu, touched, stuck, deepest, bone_P[0], bone_P[1],
          bone_P[2]);
  assert_true(touched > 0 && bone_P[1] < -1e-6); /* the bone felt the blow */
  if (mu > 0) assert_true(bone_P[2] > 1e-3 * fabs(bone_P[1]) && stuck > 0); /* and the friction */
  const double Pref = rod_mass(m, 1) * 0.2, Lref = Pref * 0.05;
  SW_EXPECT_ABS("momentum change / initial", sw_v3_norm((double[3]){P[0] - P0[0], P[1] - P0[1],
                P[2] - P0[2]}) / Pref, 0.0, 1e-12);
  /* with friction the bone also twists about its own axis, and the rod,
   * whose friction acts at its surface with a couple, rolls and twists:
   * the change is then 4e-11 damped and 1.6e-10 undamped whatever dt (5e-16
   * without).  Not the friction's: the loads of every evaluation balance to
   * 1e-19 N m, and between contacts, with no load but the rods' own, the
   * change wanders by 1e-10 (a frictionless blow that moved 1.5 cm along
   * the capsule, off its symmetry, so that the normal forces twist the bone
   * too, changes it by 4e-13; the same rod spun at 3000 rad/s about a tilted
   * axis, by 1.3e-11) */
  SW_EXPECT_ABS("angular momentum change / (p 5 cm)", sw_v3_norm((double[3]){L[0] - L0[0],
                L[1] - L0[1], L[2] - L0[2]}) / Lref, 0.0, mu > 0 ? 1e-9 : 1e-12);
  const double K0 = 0.5 * rod_mass(m, 1) * 0.04;
  SW_EXPECT_ABS(gamma > 0 || mu > 0 ? "energy balance drift / initial kinetic (damped or friction)"
                          : "energy drift / initial kinetic (undamped)",
                (total_energy(m, d) - E0) / K0, 0.0, 2e-3);
  sw_data_free(d);
  sw_model_free(m);
}

static void test_carried_undamped(void **state) { (void)state; carried_run(0.0, 0.0); }
static void test_carried_damped(void **state) { (void)state; carried_run(0.05, 0.0); }
/* with friction the bone feels the tangential force too; the friction's
 * work (stored and dissipated) is booked with the external loads' */
static void test_carried_friction(void **state) { (void)state; carried_run(0.05, 0.5); }
static void test_carried_friction_undamped(void **state) { (void)state; carried_run(0.0, 0.5); }

/* ---- 4. no tunnelling between nodes ---- */

/* A rod of 4 elements of 25 mm, r = 0.5 mm, thrown along -z at 0.5 m/s at
 * a sphere of radius 2 mm centred under the middle of an element: its
 * nodes pass 10 mm from the centre, far outside the sphere. */
static void test_no_tunnel(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  const double start[3] = {-0.05 + 0.0125, 0, 0.004}, ex[3] = {1, 0, 0};
  swRodDesc r = rod_desc("thread", 4, 0.1, 0.0005, start, ex);
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  swObstacleDesc o;
  sw_obstacle_desc_init(&o);
  o.radius = 0.002;
  o.stiffness = 100;
  assert_int_equal(sw_spec_add_obstacle(s, &o), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  swData *d = sw_data_new(m);
  const double v[3] = {0, 0, -0.5};
  for (int i = 0; i <= 4; i++) sw_set3(m, d->v, i, v);
  double lowest = INFINITY, deepest = 0;
  while (d->time < 0.02) {
    assert_int_equal(sw_steps(m, d, 20), SW_OK);
    lowest = fmin(lowest, 0.5 * (SW_AT(m, d->x, 1, 2) + SW_AT(m, d->x, 2, 2)));
    deepest = fmax(deepest, d->obstacle_max_depth);
  }
  fprintf(stderr, "# %s: lowest point of the struck element %.4g m above the centre, deepest %.3g m, "
          "final velocity %.3g m/s\n", __func__, lowest, deepest, SW_AT(m, d->v, 2, 2));
  assert_true(lowest > 0.002);           /* never reached the sphere's centre plane */
  assert_true(deepest < 0.0005);         /* nor sank its radius into it */
  assert_true(SW_AT(m, d->v, 2, 2) > 0); /* and bounced */
  sw_data_free(d);
  sw_model_free(m);
}

/* ---- 5. broad phase against brute force ---- */

static void test_broad_vs_brute(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  for (int r = 0; r < 6; r++) {
    const double start[3] = {-0.1, -0.05 + 0.02 * r, 0.003 * r}, dir[3] = {1, 0.1 * r, 0.05};
    swRodDesc rd = rod_desc(r ? "r" : "r0", 40, 0.2, RR, start, dir);
    sw_spec_add_rod(s, &rd);
  }
  unsigned seed = 12345;
  for (int k = 0; k < 60; k++) {
    swObstacleDesc o;
    sw_obstacle_desc_init(&o);
    o.shape = (swObstacleShape)(k % 5);
    seed = seed * 1103515245u + 12345u;
    for (int q = 0; q < 3; q++) {
      seed = seed * 1103515245u + 12345u;
      o.centre[q] = ((seed >> 8) % 1000) * 2e-4 - 0.1;
      o.axis[q] = ((seed >> 4) % 7) - 3.0;
      o.half[q] = 0.003 + ((seed >> 12) % 10) * 1e-3;
    }
    if (sw_v3_norm(o.axis) == 0) o.axis[2] = 1;
    o.radius = 0.004, o.length = 0.01;
    o.stiffness = 10, o.damping = 0.01;
    sw_spec_add_obstacle(s, &o);
  }
  sw_spec_set_dt(s, 1e-6);
  swModel *m = sw_test_compile(s);
  sw_spec_free(s);
  swData *d = sw_data_new(m);
  const size_t S = (size_t)m->stride;
  double *f = calloc(6 * S, sizeof(double)), *t = calloc(6 * S, sizeof(double));
  long tests[2];
  int contacts[2];
  for (int phase = 0; phase < 2; phase++) {
    memset(d->force, 0, 3 * S * sizeof(double));
    memset(d->torque, 0, 3 * S * sizeof(double));
    sw_obstacle_loads_with(m, d, (swObstaclePhase)phase);
    memcpy(f + 3 * S * phase, d->force, 3 * S * sizeof(double));
    memcpy(t + 3 * S * phase, d->torque, 3 * S * sizeof(double));
    tests[phase] = d->obstacle_tests;
    contacts[phase] = d->obstacle_contacts;
  }
  fprintf(stderr, "# %s: %d contacts; narrow tests %ld (chunk boxes) vs %ld (brute force)\n", __func__,
          contacts[0], tests[0], tests[1]);
  assert_true(contacts[0] > 0 && contacts[0] == contacts[1]);
  assert_true(tests[0] < tests[1] / 4);
  assert_memory_equal(f, f + 3 * S, 3 * S * sizeof(double));
  assert_memory_equal(t, t + 3 * S, 3 * S * sizeof(double));
  free(f), free(t);
  sw_data_free(d);
  sw_model_free(m);
}

/* ---- 6. validation messages ---- */

static void expect_reject(const swObstacleDesc *o, const char *message) {
  swSpec *s = sw_spec_new();
  const double start[3] = {0, 0, 0.1}, ex[3] = {1, 0, 0};
  swRodDesc r = rod_desc("rod", 4, RL, RR, start, ex);
  sw_spec_add_rod(s, &r);
  sw_spec_add_obstacle(s, o);
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  sw_spec_free(s);
  assert_null(m);
  fprintf(stderr, "# rejected: %s\n", err);
  assert_string_equal(err, message);
}

static void test_validation(void **state) {
  (void)state;
  swObstacleDesc o;
  sw_obstacle_desc_init(&o);
  o.name = "post";
  o.stiffness = 1;
  expect_reject(&o, "obstacle 'post': radius must be > 0");
  o.radius = 0.01;
  o.shape = SW_OBSTACLE_BOX;
  expect_reject(&o, "obstacle 'post': its three half sizes must be > 0");
  o.shape = SW_OBSTACLE_SPHERE;
  o.axis[2] = 0;
  expect_reject(&o, "obstacle 'post': axis must be a nonzero vector");
  o.axis[2] = 1;
  o.stiffness = 0;
  expect_reject(&o, "obstacle 'post': stiffness must be > 0");
  o.stiffness = 1;
  o.static_friction = -0.1;
  expect_reject(&o, "obstacle 'post': friction coefficients must be >= 0");
  o.static_friction = 0.2, o.kinetic_friction = 0.3;
  expect_reject(&o, "obstacle 'post': kinetic friction 0.3 exceeds static friction 0.2");
  o.kinetic_friction = 0.2, o.tangential_stiffness = -1;
  expect_reject(&o, "obstacle 'post': tangential stiffness must be >= 0");
  o.static_friction = o.kinetic_friction = o.tangential_stiffness = 0;
  o.carrier_rod = 0, o.carrier_node = 9;
  expect_reject(&o, "obstacle 'post': carrier node 9 out of range for rod 'rod' (nodes 0..4, -1 = last)");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_rest_sphere),      cmocka_unit_test(test_rest_cylinder),
      cmocka_unit_test(test_rest_capsule),     cmocka_unit_test(test_rest_ellipsoid),
      cmocka_unit_test(test_rest_box),         cmocka_unit_test(test_box_face_is_ground),
      cmocka_unit_test(test_carried_undamped), cmocka_unit_test(test_carried_damped),
      cmocka_unit_test(test_carried_friction), cmocka_unit_test(test_carried_friction_undamped),
      cmocka_unit_test(test_no_tunnel),        cmocka_unit_test(test_broad_vs_brute),
      cmocka_unit_test(test_validation),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
