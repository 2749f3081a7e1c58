/* test_threads.c — a step on any number of threads gives the same bits
 * (issue 10).
 *
 * One scene exercises every part of the step that threads touch: eight
 * elastic rods (about 780 slots, so thirteen chunks) and a rigid one, a
 * clamp, a prescribed end velocity, a point force and a point couple, linear
 * and analytic damping, gravity, spherical, hinge and fixed joints, one of
 * them anchored, a ground with friction under all rods, water around two of
 * them and contact among all.  It runs for the same number of steps on 1, 2, 3 and 4
 * threads with position Verlet and with PEFRL (600 and 300 steps; under the
 * sanitizers, where a step costs several times as much, 300 and 150, with
 * 24 element pairs in contact at the end either way), and every state array (all
 * planes of x, v, Q, omega and the derived strains and loads), the joint
 * records, the time and the work are compared bit for bit.  A run made
 * unstable on purpose must stop at the same step with the same message on
 * any number of threads.  And a run's steps in held calls of any length,
 * with the whole state read between them, give the bits of one call. */
#include "testutil.h"
#include "internal.h" /* sw_sweep_fits */

static const double UP[3] = {0, 0, 1}, ALONG[3] = {1, 0, 0};

static swRodDesc rod(const char *name, int n, double x, double y, const double dir[3]) {
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = name;
  r.nelem = n;
  r.length = 0.5;
  r.radius_start = 0.01;
  r.radius_end = 0.008;
  r.density = 1100;
  r.youngs = 2e6;
  r.start[0] = x;
  r.start[1] = y;
  for (int k = 0; k < 3; k++) r.direction[k] = dir[k];
  r.normal[0] = 0, r.normal[1] = dir[1] != 0 ? 0 : 1, r.normal[2] = dir[1] != 0 ? 1 : 0;
  return r;
}

static swJointDesc joint(const char *name, swJointKind kind, int ra, int na, int rb, int nb) {
  swJointDesc j;
  sw_joint_desc_init(&j);
  j.name = name;
  j.kind = kind;
  j.rod_a = ra, j.node_a = na, j.rod_b = rb, j.node_b = nb;
  for (int k = 0; k < 3; k++) j.axis[k] = UP[k];
  return j;
}

static swSpec *scene(swIntegrator integ) {
  swSpec *s = sw_spec_new();
  char names[9][8];
  for (int r = 0; r < 8; r++) {
    snprintf(names[r], sizeof names[r], "r%d", r);
    /* chains: r1 -> r2 (ball), r3 -> r5 (hinge) -> body (weld) */
    const double x = r == 2 || r == 5 ? 0.5 : 0.0, y = r == 2 ? 0.1 : r == 5 ? 0.3 : 0.1 * r;
    swRodDesc d = rod(names[r], r == 5 ? 260 : 50 + 7 * r, x, y, ALONG);
    if (r == 2) d.damping = SW_DAMP_LINEAR, d.gamma = 0.05;
    if (r == 3) d.damping = SW_DAMP_ANALYTIC, d.gamma = 0.2;
    sw_spec_add_rod(s, &d);
  }
  swRodDesc b = rod("body", 12, 1.0, 0.3, ALONG);
  b.rigid = 1;
  sw_spec_add_rod(s, &b);
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, integ);
  swBCDesc c = {.kind = SW_BC_CLAMP, .rod = 0, .end = 0, .signal = sw_signal_const(1)};
  sw_spec_add_bc(s, &c);
  swBCDesc v = {.kind = SW_BC_VELOCITY, .rod = 4, .end = 1, .vec = {0, 0.05, 0.02},
                .signal = sw_signal_sine(0, 1, 40, 0, 0)};
  sw_spec_add_bc(s, &v);
  swLoadDesc f = {.kind = SW_LOAD_FORCE, .rod = 1, .index = -1, .vec = {0, 0, 0.02},
                  .signal = sw_signal_ramp(0, 1, 0, 1e-3)};
  sw_spec_add_load(s, &f);
  swLoadDesc t = {.kind = SW_LOAD_TORQUE, .rod = 6, .index = 3, .vec = {1e-4, 0, 2e-4},
                  .signal = sw_signal_const(1)};
  sw_spec_add_load(s, &t);
  swJointDesc j[] = {joint("ball", SW_JOINT_SPHERICAL, 1, -1, 2, 0),
                     joint("hinge", SW_JOINT_HINGE, 3, -1, 5, 0),
                     joint("weld", SW_JOINT_FIXED, 5, -1, 8, 0),
                     joint("pin", SW_JOINT_HINGE, 7, 0, -1, 0),
                     joint("mid", SW_JOINT_SPHERICAL, 6, 20, 7, 30)};
  for (int k = 0; k < 5; k++) {
    if (k == 3) for (int q = 0; q < 3; q++) j[k].anchor[q] = q == 1 ? 0.7 : 0.0;
    if (k == 4) { /* two interior nodes 0.1 m apart: a soft stretched spring */
      j[k].stiffness = 0.5;
      j[k].damping = 1e-3;
    }
    sw_spec_add_joint(s, &j[k]);
  }
  swGroundDesc gr;
  sw_ground_desc_init(&gr);
  gr.origin[2] = -0.012; /* just below the rods: the sagging ones touch it */
  gr.stiffness = 2e3;
  gr.damping = 1.0;
  for (int k = 0; k < 3; k++) gr.mu_kinetic[k] = k == 2 ? 0.6 : 0.3, gr.mu_static[k] = 0.5;
  sw_spec_add_ground(s, &gr);
  static const int wet[] = {6, 7};
  swFluidDesc fl;
  sw_fluid_desc_init(&fl);
  fl.model = SW_FLUID_QUADRATIC;
  fl.density = 1000;
  fl.drag_coefficient = 1.0;
  fl.buoyancy = 1;
  fl.nrods = 2;
  fl.rods = wet;
  sw_spec_add_fluid(s, &fl);
  swContactDesc ct;
  sw_contact_desc_init(&ct);
  ct.stiffness = 1e3;
  ct.damping = 0.1;
  sw_spec_add_contact(s, &ct);
  return s;
}

typedef struct {
  double time, work;
  long step;
  int rc, pairs;
  char error[512];
  double *planes; /* all per-slot arrays the step writes, back to back */
  double *joints;
} snapshot;

/* Every array of swData that a step writes, at its full stride. */
static double **arrays(swData *d, int *planes) {
  static double *a[16];
  static const int np[] = {3, 3, 9, 3, 1, 1, 3, 3, 1, 3, 3, 3, 3, 3, 3};
  double *p[] = {d->x, d->v, d->Q, d->omega, d->length, d->dilatation, d->sigma, d->stress,
                 d->vor_dilatation, d->kappa, d->couple, d->force, d->torque, d->ext_force,
                 d->ext_torque};
  for (int k = 0; k < 15; k++) a[k] = p[k], planes[k] = np[k];
  a[15] = NULL;
  return a;
}

/* A copy of every array of arrays(), back to back. */
static double *copy_planes(const swModel *m, swData *d) {
  int np[16];
  double **a = arrays(d, np);
  size_t total = 0;
  for (int k = 0; a[k]; k++) total += (size_t)np[k] * (size_t)m->stride;
  double *planes = malloc(total * sizeof(double));
  assert_non_null(planes);
  size_t at = 0;
  for (int k = 0; a[k]; k++) {
    const size_t n = (size_t)np[k] * (size_t)m->stride;
    memcpy(planes + at, a[k], n * sizeof(double));
    at += n;
  }
  return planes;
}

static snapshot run(const swModel *m, int threads, long steps) {
  swData *d = sw_data_new(m);
  assert_non_null(d);
  assert_int_equal(sw_set_threads(d, threads), threads);
  snapshot s = {0};
  s.rc = sw_steps(m, d, steps / 2);
  if (s.rc == SW_OK) s.rc = sw_steps(m, d, steps - steps / 2); /* two calls: the regions meet */
  s.time = d->time, s.work = d->work, s.step = d->step, s.pairs = d->contact_pairs;
  memcpy(s.error, d->error, sizeof s.error);
  s.planes = copy_planes(m, d);
  s.joints = malloc((4 * (size_t)m->njoint + 1) * sizeof(double));
  assert_non_null(s.joints);
  memcpy(s.joints, d->joint_force, 3 * (size_t)m->njoint * sizeof(double));
  memcpy(s.joints + 3 * m->njoint, d->joint_angle, (size_t)m->njoint * sizeof(double));
  sw_data_free(d);
  return s;
}

static size_t snapshot_doubles(const swModel *m) {
  int np[16];
  swData *d = sw_data_new(m);
  double **a = arrays(d, np);
  size_t total = 0;
  for (int k = 0; a[k]; k++) total += (size_t)np[k] * (size_t)m->stride;
  sw_data_free(d);
  return total;
}

static void same_bits(const swModel *m, const snapshot *a, const snapshot *b, int threads) {
  const size_t n = snapshot_doubles(m);
  size_t differ = 0;
  for (size_t i = 0; i < n; i++) differ += memcmp(&a->planes[i], &b->planes[i], sizeof(double)) != 0;
  fprintf(stderr, "# %d threads: %zu of %zu state doubles differ from 1 thread; work %.17g vs %.17g\n",
          threads, differ, n, b->work, a->work);
  assert_int_equal(differ, 0);
  assert_memory_equal(a->joints, b->joints, 4 * (size_t)m->njoint * sizeof(double));
  assert_memory_equal(&a->work, &b->work, sizeof a->work);
  assert_memory_equal(&a->time, &b->time, sizeof a->time);
  assert_int_equal(a->step, b->step);
  assert_int_equal(a->rc, b->rc);
  assert_int_equal(a->pairs, b->pairs);
  assert_string_equal(a->error, b->error);
}

/* The run of `one` (1 thread) again on 2, 3 and 4 threads: the same bits. */
static void same_on_teams(const swModel *m, const snapshot *one, long steps) {
  for (int t = 2; t <= 4; t++) {
    snapshot more = run(m, t, steps);
    same_bits(m, one, &more, t);
    free(more.planes);
    free(more.joints);
  }
}

static void compare(swIntegrator integ, double dt_frac, long steps, int want_rc) {
  swSpec *s = scene(integ);
  swModel *m = sw_test_compile_at(s, dt_frac);
  assert_true((m->nslot_elastic + m->chunk - 1) / m->chunk > 4); /* several chunks a thread */
  snapshot one = run(m, 1, steps);
  assert_int_equal(one.rc, want_rc);
  fprintf(stderr, "# %s: %ld steps, %d element pairs in contact at the end\n",
          integ == SW_PEFRL ? "PEFRL" : "Verlet", one.step, one.pairs);
  same_on_teams(m, &one, steps);
  if (want_rc != SW_OK) fprintf(stderr, "# unstable on every team: %s\n", one.error);
  free(one.planes);
  free(one.joints);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_verlet(void **state) {
  (void)state;
  compare(SW_VERLET, 0.5, sw_test_sanitized() ? 300 : 600, SW_OK);
}

static void test_pefrl(void **state) {
  (void)state;
  compare(SW_PEFRL, 0.5, sw_test_sanitized() ? 150 : 300, SW_OK);
}

static void test_unstable(void **state) {
  (void)state;
  compare(SW_VERLET, 3.0, 600, SW_EUNSTABLE);
}

/* A ground at height z under the split scenes, with kinetic and static
 * friction, and with `rolling`, rolling friction at the contact point too
 * (the ground then reads the elements' spin and couples). */
static void add_ground(swSpec *s, double z, int rolling) {
  swGroundDesc gr;
  sw_ground_desc_init(&gr);
  gr.origin[2] = z;
  gr.stiffness = 2e3;
  gr.damping = 1.0;
  for (int k = 0; k < 3; k++) gr.mu_kinetic[k] = k == 2 ? 0.6 : 0.3, gr.mu_static[k] = 0.5;
  if (rolling) gr.mu_rolling = 0.01, gr.contact_point = 1;
  sw_spec_add_ground(s, &gr);
}

/* ---- fluids across a thread's first slot ----
 * A fluid's loads go element by element to both nodes of each element, and
 * each thread adds them to its own slots (environment.c), which start where
 * its chunks start, in the middle of a rod as often as not.  The scene above
 * never cuts a wet rod there (its chunk boundaries fall in dry rods), the
 * wing does: its node at a thread's first slot lost the half of the drag of
 * the element before it, so 2 threads gave other bits than 1 (and other
 * physics).  Here two clamped rods of 150 elements sag under gravity, one
 * in a quadratic drag with a flow across it, one in Stokes drag: 302 slots
 * in 5 chunks of 64, so that every team of 2 to 4 threads starts a thread
 * inside a wet rod (slots 64, 128 and 192).  They lie on a ground, which
 * the owner of each rod's first slot loads rod by rod: on 3 threads it
 * added its loads to nodes of another thread while that one added their
 * drag (9767 of 13680 doubles differed, the work changing from run to run)
 * until a barrier went between the two (environment.c). */
static swSpec *wet_scene(void) {
  swSpec *s = sw_spec_new();
  static const char *names[] = {"quadratic", "stokes"};
  static const int rods[2][1] = {{0}, {1}};
  for (int r = 0; r < 2; r++) {
    swRodDesc d = rod(names[r], 150, 0, 0.1 * r, ALONG);
    sw_spec_add_rod(s, &d);
    swBCDesc c = {.kind = SW_BC_CLAMP, .rod = r, .end = 0, .signal = sw_signal_const(1)};
    sw_spec_add_bc(s, &c);
    swFluidDesc fl;
    sw_fluid_desc_init(&fl);
    fl.model = r == 0 ? SW_FLUID_QUADRATIC : SW_FLUID_STOKES;
    fl.density = 1000;
    fl.drag_coefficient = 1.0;
    fl.viscosity = 1e-3;
    fl.velocity[1] = r == 0 ? 0.2 : 0.0; /* loads from the first step */
    fl.nrods = 1;
    fl.rods = rods[r];
    sw_spec_add_fluid(s, &fl);
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  /* and a ground just below them, which the rods' owners load whole
   * (environment.c): the drag of their nodes on other threads must be in
   * before the ground adds its loads and reads them (it raced there) */
  add_ground(s, -0.005, 0);
  return s;
}

static void test_fluid_split(void **state) {
  (void)state;
  swSpec *s = wet_scene();
  swModel *m = sw_test_compile_at(s, 0.5);
  /* the threads' first slots, inside the rods (0-150 and 151-301) */
  assert_int_equal(m->chunk, 64);
  assert_int_equal(m->nslot_elastic, 302);
  const long steps = sw_test_sanitized() ? 150 : 300;
  snapshot one = run(m, 1, steps);
  assert_int_equal(one.rc, SW_OK);
  fprintf(stderr, "# fluids: %d slots in chunks of %d, %ld steps, work %.6g J\n", m->nslot_elastic,
          m->chunk, one.step, one.work);
  same_on_teams(m, &one, steps);
  free(one.planes);
  free(one.joints);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- torque waves and a ground on rods cut by the threads ----
 * A rod's torque waves and its ground are loaded whole by the thread that
 * owns the rod's first slot (environment.c), onto elements and nodes that
 * lie in other threads' slots when the rod is cut; without a fluid no
 * barrier stands between the two, as both run on that one thread, after
 * the internal loads of every thread are in.  Two rods of 150 elements, one
 * wave measured from each end, lie on a ground with static, kinetic and
 * rolling friction at the contact point (so the ground reads the elements'
 * spin and the waves' couples): 302 slots in chunks of 64, every team of 2
 * to 4 threads cutting a rod.  The waves must bend the rods sideways, and
 * 2, 3 and 4 threads give the bits of one. */
static swSpec *wave_scene(void) {
  swSpec *s = sw_spec_new();
  static const char *names[] = {"forward", "reversed"};
  for (int r = 0; r < 2; r++) {
    swRodDesc d = rod(names[r], 150, 0, 0.1 * r, ALONG);
    d.start[2] = 0.01; /* resting on the ground (radius 1 cm at its start) */
    sw_spec_add_rod(s, &d);
    swWaveDesc w;
    sw_wave_desc_init(&w);
    w.name = names[r];
    w.rod = r;
    w.ncoef = 6;
    for (int k = 0; k < w.ncoef; k++) w.coef[k] = 2e-3 * (1 + k % 3);
    w.wavelength = 0.25;
    w.period = 0.02;
    w.reverse = r;
    sw_spec_add_wave(s, &w);
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  add_ground(s, 0.0, 1);
  return s;
}

static void test_wave_ground_split(void **state) {
  (void)state;
  swSpec *s = wave_scene();
  swModel *m = sw_test_compile_at(s, 0.5);
  assert_int_equal(m->chunk, 64);
  assert_int_equal(m->nslot_elastic, 302);
  const long steps = sw_test_sanitized() ? 300 : 600;
  snapshot one = run(m, 1, steps);
  assert_int_equal(one.rc, SW_OK);
  /* the waves did bend the rods sideways (y), which gravity and the
   * ground alone would not: the largest sideways move of a node */
  double sideways = 0;
  for (int i = 0; i < m->nslot_elastic; i++) {
    const size_t at = (size_t)m->stride + (size_t)i; /* plane y of x, and of x0 */
    sideways = fmax(sideways, fabs(one.planes[at] - m->x0[at]));
  }
  fprintf(stderr, "# waves on a ground: %d slots in chunks of %d, %ld steps, largest sideways "
          "move %.3e m, work %.6g J\n", m->nslot_elastic, m->chunk, one.step, sideways, one.work);
  assert_true(sideways > 1e-5);
  same_on_teams(m, &one, steps);
  free(one.planes);
  free(one.joints);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- the fused sweep ----
 * A one-thread Verlet step of rods under gravity, clamps, prescribed ends,
 * point loads and damping runs its kick and drift as one sweep over the
 * slots, block by block, with the scratch arrays in windows (integrate.c);
 * two or more threads run the phased step.  The scene below puts an end
 * with a prescribed angular velocity on the first slot of a block, with its
 * element on the block before; coils one rod so tightly (0.3 rad from
 * element to element) that every one of its domains takes the exact
 * logarithm; and
 * spins another about its axis fast enough (0.15 rad a step) that its
 * frames take the exact rotation in every drift.  The state, the time, the
 * work, and the strains and energies recomputed from the final state must
 * have the same bits on 1, 2 and 3 threads, with the boundary conditions
 * declared in slot order (looked up by slot) and out of it (all scanned).
 * (The loads and strains the step leaves behind are scratch, and the sweep
 * keeps only windows of them, so those are compared after sw_energy
 * recomputes them.) */
enum { COIL = 400, SPUN = 3 };

static void coil_shape(int n, double *x, double *Q) {
  const double R = 0.02, step = 0.3, rise = 0.002;
  for (int i = 0; i <= n; i++) {
    x[3 * i] = 0.3 + R * cos(step * i), x[3 * i + 1] = 0.5 + R * sin(step * i), x[3 * i + 2] = rise * i;
  }
  for (int e = 0; e < n; e++) {
    double t[3], len = 0, *q = Q + 9 * e;
    for (int k = 0; k < 3; k++) t[k] = x[3 * (e + 1) + k] - x[3 * e + k], len += t[k] * t[k];
    len = sqrt(len);
    for (int k = 0; k < 3; k++) t[k] /= len;
    /* d1 = unit(z - (z . t) t), d2 = t x d1, d3 = t */
    double d1[3] = {-t[2] * t[0], -t[2] * t[1], 1 - t[2] * t[2]}, n1 = 0;
    for (int k = 0; k < 3; k++) n1 += d1[k] * d1[k];
    for (int k = 0; k < 3; k++) d1[k] /= sqrt(n1);
    const double d2[3] = {t[1] * d1[2] - t[2] * d1[1], t[2] * d1[0] - t[0] * d1[2], t[0] * d1[1] - t[1] * d1[0]};
    for (int k = 0; k < 3; k++) q[k] = d1[k], q[3 + k] = d2[k], q[6 + k] = t[k];
  }
}

static swSpec *sweep_scene(int unsorted) {
  swSpec *s = sw_spec_new();
  static const char *names[] = {"turned", "loaded", "coil", "spun"};
  static const int nelem[] = {512, 300, COIL, 200};
  for (int r = 0; r < 4; r++) {
    swRodDesc d = rod(names[r], nelem[r], 0, 0.1 * r, ALONG);
    if (r == 1) d.damping = SW_DAMP_LINEAR, d.gamma = 0.05;
    if (r == 2) d.damping = SW_DAMP_ANALYTIC, d.gamma = 0.2, d.length = 0.25;
    const int id = sw_spec_add_rod(s, &d);
    if (r == 2) {
      double x[3 * (COIL + 1)], Q[9 * COIL];
      coil_shape(COIL, x, Q);
      assert_int_equal(sw_spec_set_rest_shape(s, id, x, Q), SW_OK);
    }
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  swBCDesc bc[] = {{.kind = SW_BC_CLAMP, .rod = 0, .end = 0, .signal = sw_signal_const(1)},
                   {.kind = SW_BC_OMEGA, .rod = 0, .end = 1, .vec = {0, 1, 3}, .signal = sw_signal_sine(0, 1, 40, 0, 0)},
                   {.kind = SW_BC_CLAMP, .rod = 2, .end = 0, .signal = sw_signal_const(1)},
                   {.kind = SW_BC_VELOCITY, .rod = 2, .end = 1, .vec = {0, 0.05, 0.02}, .signal = sw_signal_const(1)}};
  for (int k = 0; k < 4; k++) sw_spec_add_bc(s, &bc[unsorted ? (k + 1) % 4 : k]);
  swLoadDesc f = {.kind = SW_LOAD_FORCE, .rod = 1, .index = -1, .vec = {0, 0, 0.02},
                  .signal = sw_signal_ramp(0, 1, 0, 1e-3)};
  sw_spec_add_load(s, &f);
  swLoadDesc t = {.kind = SW_LOAD_TORQUE, .rod = 1, .index = 7, .vec = {1e-4, 0, 2e-4},
                  .signal = sw_signal_const(1)};
  sw_spec_add_load(s, &t);
  return s;
}

/* The state after `steps` steps on `threads` threads, the rod "spun"
 * turning about its axis at 0.15 rad a step from the start; the strains,
 * couples and energies are recomputed from it (sw_energy). */
static snapshot sweep_run(const swModel *m, int threads, long steps, double energy[3]) {
  swData *d = sw_data_new(m);
  assert_non_null(d);
  assert_int_equal(sw_set_threads(d, threads), threads);
  for (int e = m->elem_adr[SPUN]; e < m->elem_adr[SPUN] + m->rod_nelem[SPUN]; e++)
    SW_AT(m, d->omega, e, 2) = 0.15 / m->dt; /* material frame: about d3 */
  snapshot s = {0};
  s.rc = sw_steps(m, d, steps / 2);
  if (s.rc == SW_OK) s.rc = sw_steps(m, d, steps - steps / 2);
  sw_energy(m, d, energy);
  s.time = d->time, s.work = d->work, s.step = d->step;
  memcpy(s.error, d->error, sizeof s.error);
  s.planes = copy_planes(m, d);
  sw_data_free(d);
  return s;
}

static void sweep_case(int unsorted) {
  swSpec *s = sweep_scene(unsorted);
  swModel *m = sw_test_compile_at(s, 0.5);
  assert_true(sw_sweep_fits(m));
  assert_int_equal(m->bc_slot_order, !unsorted); /* conditions looked up by slot, or all scanned */
  /* the turned end: its node on the first slot of block 1, its element on the last of block 0 */
  assert_int_equal(m->node_adr[0] + m->rod_nelem[0], 512);
  double e1[3], en[3];
  snapshot one = sweep_run(m, 1, 400, e1);
  assert_int_equal(one.rc, SW_OK);
  fprintf(stderr, "# sweep (conditions %s): %d slots, %ld steps; energies %.6g %.6g %.6g J\n",
          unsorted ? "out of slot order" : "in slot order", m->nslot_elastic, one.step, e1[0], e1[1], e1[2]);
  for (int t = 2; t <= 3; t++) {
    snapshot more = sweep_run(m, t, 400, en);
    /* all but the external loads, which sw_energy does not recompute */
    const size_t n = snapshot_doubles(m) - 6 * (size_t)m->stride;
    size_t differ = 0;
    for (size_t i = 0; i < n; i++) differ += memcmp(&one.planes[i], &more.planes[i], sizeof(double)) != 0;
    fprintf(stderr, "# sweep vs %d threads (phased): %zu of %zu doubles differ\n", t, differ, n);
    assert_int_equal(differ, 0);
    assert_memory_equal(e1, en, sizeof e1);
    assert_memory_equal(&one.work, &more.work, sizeof one.work);
    assert_memory_equal(&one.time, &more.time, sizeof one.time);
    assert_int_equal(one.step, more.step);
    free(more.planes);
  }
  free(one.planes);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_sweep(void **state) {
  (void)state;
  sweep_case(0);
  sweep_case(1);
}

/* ---- held steps ----
 * The run loop ends its calls of the step where it reads the state (frames,
 * expectations' samples, every 256 steps) with sw_steps_held, and reads the
 * whole step between sw_whole_begin and sw_whole_end (integrate.c, "Held
 * steps").  Whatever the lengths of the calls and whatever is read in
 * between (here sw_energy, which recomputes every strain and couple), the
 * state must have the bits of one call of sw_steps, on 1 and 2 threads: for
 * the scene above with both schemes (PEFRL is never held) and for the
 * sweep's.  The derived arrays are compared after sw_energy recomputes them
 * from the final state (the external loads, which it does not, are left
 * out). */
static int advance(const swModel *m, swData *d, long steps, int held) {
  if (!held) return sw_steps(m, d, steps);
  static const long len[] = {1, 7, 50, 3, 128, 2, 256};
  int rc = SW_OK;
  for (long done = 0, c = 0; done < steps && rc == SW_OK; c++) {
    long k = len[c % 7] < steps - done ? len[c % 7] : steps - done;
    rc = sw_steps_held(m, d, k);
    done += k;
    if (rc == SW_OK) rc = sw_whole_begin(m, d);
    double e[3];
    if (rc == SW_OK) sw_energy(m, d, e);
    sw_whole_end(m, d);
  }
  const int settled = sw_settle(m, d);
  return rc == SW_OK ? settled : rc;
}

static snapshot held_run(const swModel *m, int threads, long steps, int held, double energy[3]) {
  swData *d = sw_data_new(m);
  assert_non_null(d);
  assert_int_equal(sw_set_threads(d, threads), threads);
  snapshot s = {0};
  s.rc = advance(m, d, steps, held);
  assert_int_equal(d->held, 0);
  /* the joints as read at the end (sw_settle measures them so) */
  for (int j = 0; j < m->njoint; j++) sw_joint_measure(m, d, j);
  sw_energy(m, d, energy);
  s.time = d->time, s.work = d->work, s.step = d->step;
  s.planes = copy_planes(m, d);
  s.joints = malloc((4 * (size_t)m->njoint + 1) * sizeof(double));
  assert_non_null(s.joints);
  memcpy(s.joints, d->joint_force, 3 * (size_t)m->njoint * sizeof(double));
  memcpy(s.joints + 3 * m->njoint, d->joint_angle, (size_t)m->njoint * sizeof(double));
  sw_data_free(d);
  return s;
}

static void held_case(swSpec *s, const char *what, long steps) {
  swModel *m = sw_test_compile_at(s, 0.5);
  double e1[3], en[3];
  snapshot one = held_run(m, 1, steps, 0, e1);
  assert_int_equal(one.rc, SW_OK);
  for (int t = 1; t <= 2; t++) {
    snapshot held = held_run(m, t, steps, 1, en);
    assert_int_equal(held.rc, SW_OK);
    const size_t n = snapshot_doubles(m) - 6 * (size_t)m->stride;
    size_t differ = 0;
    for (size_t i = 0; i < n; i++) differ += memcmp(&one.planes[i], &held.planes[i], sizeof(double)) != 0;
    fprintf(stderr, "# %s, %ld steps in held calls of 1 to 256 steps on %d thread%s, the whole "
            "state read between them: %zu of %zu doubles differ from one call; energy %.17g J\n",
            what, steps, t, t > 1 ? "s" : "", differ, n, en[0] + en[1]);
    assert_int_equal(differ, 0);
    assert_memory_equal(e1, en, sizeof e1);
    assert_memory_equal(one.joints, held.joints, 4 * (size_t)m->njoint * sizeof(double));
    assert_memory_equal(&one.work, &held.work, sizeof one.work);
    assert_memory_equal(&one.time, &held.time, sizeof one.time);
    assert_int_equal(one.step, held.step);
    free(held.planes);
    free(held.joints);
  }
  free(one.planes);
  free(one.joints);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_held(void **state) {
  (void)state;
  held_case(scene(SW_VERLET), "Verlet, joints, rigid body, ground, water, contact", 600);
  held_case(scene(SW_PEFRL), "PEFRL (never held)", 200);
  held_case(sweep_scene(0), "Verlet, the fused sweep", 400);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_verlet),
      cmocka_unit_test(test_pefrl),
      cmocka_unit_test(test_unstable),
      cmocka_unit_test(test_fluid_split),
      cmocka_unit_test(test_wave_ground_split),
      cmocka_unit_test(test_sweep),
      cmocka_unit_test(test_held),
  };
  return cmocka_run_group_tests_name("threads", tests, NULL, NULL);
}
