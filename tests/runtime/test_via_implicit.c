/* test_via_implicit.c — under integrator = imex, a filament's via rings
 * (via_implicit.c) and, when its ends are tied to rigid bodies, its Hill
 * damping inside the joints' system (joint_groups.c, dense_ends): the ring
 * no longer bounds the filament's step, the step's order stays 2, momentum
 * is kept, and the result at the larger step is that of position Verlet at
 * a small one.
 *
 * Design.  Two bones, 0.2 m, free in space, no gravity; a fully activated
 * muscle of one filament from a node of the first to a node of the second,
 * through a stiff via ring (5e7 N/m, so that the ring bounds the explicit
 * step) on a third, heavy elastic rod that carries it (test_via.c's
 * momentum scene with the ring on its own rod).  The two bones are elastic
 * (the filament's own solve takes the ring: the plain path) or rigid (the
 * filament's ends are members of the joints' system and its damping is
 * solved there: the dense path).  The observable is every node's position
 * after 2 ms of the contraction. */
#include "testutil.h"
#include "internal.h"

#define PI_T 3.14159265358979323846
static const double RADIUS = 0.008, SIGMA = 1e6, T_END = 2e-3;

static swSpec *scene(int rigid, int via, swIntegrator integ) {
  swSpec *s = sw_spec_new();
  swRodDesc bone;
  sw_rod_desc_init(&bone);
  bone.nelem = 6;
  bone.direction[0] = 1, bone.direction[1] = bone.direction[2] = 0;
  bone.normal[2] = 1, bone.normal[0] = bone.normal[1] = 0;
  bone.length = 0.2;
  bone.radius_start = bone.radius_end = 0.01;
  bone.youngs = 1e8;
  bone.density = 1750;
  bone.rigid = rigid;
  bone.name = "a";
  assert_int_equal(sw_spec_add_rod(s, &bone), 0);
  bone.name = "b";
  bone.start[0] = 0.25;
  bone.start[2] = -0.02;
  assert_int_equal(sw_spec_add_rod(s, &bone), 1);
  bone.name = "carrier"; /* heavy, elastic, along the path at the ring */
  bone.rigid = 0;
  bone.nelem = 4;
  bone.length = 0.1;
  bone.radius_start = bone.radius_end = 0.02;
  bone.density = 17500;
  bone.start[0] = 0.15, bone.start[2] = 0.03;
  assert_int_equal(sw_spec_add_rod(s, &bone), 2);
  swMuscleDesc md;
  sw_muscle_desc_init(&md);
  md.name = "m";
  md.filaments = 1;
  md.nelem = 10;
  md.radius = RADIUS;
  md.sigma_max = SIGMA;
  md.normal[1] = 1;
  const double S[3] = {0.0333333333333333333, 0, 0}, P[3] = {0.2, 0, 0.03}, A[3] = {0.35, 0, -0.02};
  memcpy(md.start, S, sizeof S);
  memcpy(md.end, A, sizeof A);
  md.attach_rod[0] = 0;
  md.attach_node[0] = 1;
  md.attach_rod[1] = 1;
  md.attach_node[1] = 3;
  if (via) {
    md.nvia = 1;
    memcpy(md.via[0], P, sizeof P);
    md.via_rod[0] = 2;
    md.via_stiffness = 5e7;
  }
  md.activation = sw_signal_const(1.0);
  assert_int_equal(sw_spec_add_muscle(s, &md), 0);
  sw_spec_set_integrator(s, integ);
  return s;
}

static swModel *compile_dt(swSpec *s, double dt) {
  sw_spec_set_dt(s, dt);
  return sw_test_compile(s);
}

/* Every node's position at T_END, run at dt (malloc'ed, 3 per node), and
 * the largest |linear momentum| / (F_max t) met at the end. */
static double *positions(int rigid, int via, swIntegrator integ, double dt, int *nnode, double *mom) {
  swSpec *s = scene(rigid, via, integ);
  swModel *m = compile_dt(s, dt);
  swData *d = sw_data_new(m);
  sw_test_run_to(m, d, T_END);
  double *x = malloc(3 * (size_t)m->nslot * sizeof *x);
  double P[3] = {0, 0, 0};
  int k = 0;
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++, k++) {
      double v[3];
      sw_get3(m, d->x, i, x + 3 * k);
      sw_get3(m, d->v, i, v);
      for (int c = 0; c < 3; c++) P[c] += m->mass[i] * v[c];
    }
  *nnode = k;
  if (mom) *mom = sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]) / (SIGMA * PI_T * RADIUS * RADIUS * d->time);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return x;
}

static double max_diff(const double *a, const double *b, int n) {
  double e = 0;
  for (int i = 0; i < 3 * n; i++) e = fmax(e, fabs(a[i] - b[i]));
  return e;
}

/* The filament's bound under Verlet (the ring on its lightest node) and
 * under imex (the ring's bone side only). */
static void bounds(int rigid, double *dt_verlet_ring, double *dt_imex_fil, double *dt_imex) {
  swSpec *s = scene(rigid, 1, SW_VERLET);
  swModel *m = sw_test_compile(s);
  *dt_verlet_ring = sw_via_stable_dt(m, 0);
  sw_model_free(m);
  sw_spec_free(s);
  s = scene(rigid, 1, SW_IMEX);
  m = sw_test_compile(s);
  *dt_imex_fil = sw_stable_dt_rod(m, m->fil_rod[0]);
  *dt_imex = sw_stable_dt(m);
  if (rigid) {
    assert_int_equal(m->fil_system[0], 1); /* the dense path */
    assert_true(m->fil_block[0] >= 0 && m->fil_block[1] >= 0);
  } else {
    assert_int_equal(m->fil_system[0], 0); /* the plain path */
  }
  assert_true(sw_via_ring_implicit(m, 0, 0));
  sw_model_free(m);
  sw_spec_free(s);
}

/* The errors of imex at dt, dt/2, .., dt/32 against position Verlet at a
 * quarter of its own stable step (everything explicit), their observed
 * order, and momentum at dt.  The Hill damping is taken by the linearly
 * implicit Euler method (muscle_implicit.c), whose tension is the exact one
 * to O(h): where it acts, the step is first order. */
static void converges(int rigid, int via, double dt, const char *what) {
  swSpec *s = scene(rigid, via, SW_VERLET);
  swModel *m = sw_test_compile(s);
  const double dt_ref = 0.25 * sw_stable_dt(m);
  sw_model_free(m);
  sw_spec_free(s);
  int n;
  double mom, err[6], *xr = positions(rigid, via, SW_VERLET, dt_ref, &n, NULL);
  for (int k = 0; k < 6; k++) {
    double *x = positions(rigid, via, SW_IMEX, dt / (1 << k), &n, k ? NULL : &mom);
    err[k] = max_diff(x, xr, n);
    free(x);
  }
  free(xr);
  /* the asymptotic order from the three finest (the ring's contact may
   * change element within a coarse step, which the first levels show) */
  const double o1 = log(err[3] / err[4]) / log(2.0), o2 = log(err[4] / err[5]) / log(2.0);
  fprintf(stderr, "#   %s: imex at %.3g s / 1, 2, .. 32 against Verlet at %.3g s:", what, dt, dt_ref);
  for (int k = 0; k < 6; k++) fprintf(stderr, " %.3g", err[k]);
  fprintf(stderr, " m (orders %.2f, %.2f); |momentum| / (F_max t) %.3g\n", o1, o2, mom);
  for (int k = 3; k < 6; k++) assert_true(err[k] < err[k - 1]);
  assert_true(o1 > 0.8 && o2 > 0.8);
  SW_EXPECT_ABS("|linear momentum| / (F_max t), imex at dt", mom, 0.0, 1e-11);
}

/* With the ring: it no longer bounds the filament's step under imex, and
 * the step above its explicit bound converges to Verlet's result. */
static void check_path(int rigid) {
  double ring, fil, est;
  bounds(rigid, &ring, &fil, &est);
  fprintf(stderr, "#   %s bones: the ring's explicit bound %.3g s; under imex the filament's %.3g s, "
          "the scene's %.3g s\n", rigid ? "rigid" : "elastic", ring, fil, est);
  assert_true(fil > 3 * ring); /* the ring no longer bounds the filament */
  assert_true(est > 1.5 * ring);
  converges(rigid, 1, fmin(3 * ring, 0.9 * est), rigid ? "rigid bones, ring" : "elastic bones, ring");
}

static void test_plain_path(void **state) {
  (void)state;
  check_path(0);
}

static void test_dense_path(void **state) {
  (void)state;
  check_path(1);
}

/* Without a via point, the dense path alone: the filament tied to two
 * rigid bodies, its damping in the joints' system. */
static void test_dense_no_ring(void **state) {
  (void)state;
  swSpec *s = scene(1, 0, SW_IMEX);
  swModel *m = sw_test_compile(s);
  assert_int_equal(m->fil_system[0], 1);
  const double dt = fmin(0.9 * sw_stable_dt(m), T_END / 20);
  sw_model_free(m);
  sw_spec_free(s);
  converges(1, 0, dt, "rigid bones, no ring");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_plain_path),
      cmocka_unit_test(test_dense_path),
      cmocka_unit_test(test_dense_no_ring),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
