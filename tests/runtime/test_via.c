/* test_via.c — muscle paths through via points (muscle_via.c) against
 * closed forms: the rope over a frictionless pulley (equal tension on both
 * sides, ring reaction 2 T sin(theta/2)); sliding through the ring (the
 * length follows the polyline, the material at the ring follows the uniform
 * stretch, the contact stays at the ring); the moment about a hinge of a
 * muscle wrapped over a via point on the bone (T times the moment arm of the
 * line through the via point, not of the straight line); momentum of a free
 * assembly; the layout at t = 0 (eta = 1, via points on nodes) and the
 * validation messages.
 *
 * Design.  One filament of a muscle, 1 MPa peak stress, radius 8 mm (F_max
 * = 201 N), laid in the x-z plane.  Statics are reached by dynamic relaxation
 * with a heavy, damped filament (statics do not depend on density). */
#include "testutil.h"

#define PI_T 3.14159265358979323846
static const double RADIUS = 0.008, SIGMA = 1e6;

static swMuscleDesc one_filament(int nelem) {
  swMuscleDesc md;
  sw_muscle_desc_init(&md);
  md.name = "m";
  md.filaments = 1;
  md.nelem = nelem;
  md.radius = RADIUS;
  md.sigma_max = SIGMA;
  md.normal[1] = 1;
  return md;
}

static double fmax_one(void) { return SIGMA * PI_T * RADIUS * RADIUS; }

static void unit(double *u, const double *a, const double *b) {
  double n = 0;
  for (int k = 0; k < 3; k++) n += (b[k] - a[k]) * (b[k] - a[k]);
  n = sqrt(n);
  for (int k = 0; k < 3; k++) u[k] = (b[k] - a[k]) / n;
}

static double dist(const double *a, const double *b) {
  double n = 0;
  for (int k = 0; k < 3; k++) n += (b[k] - a[k]) * (b[k] - a[k]);
  return sqrt(n);
}

static double norm3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* Arc length of rod r now. */
static double arc_length(const swModel *m, const swData *d, int r) {
  double l = 0;
  for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) l += d->length[e];
  return l;
}

/* ---- layout ---- */

static void test_layout(void **state) {
  (void)state;
  swMuscleDesc md = one_filament(12);
  const double S[3] = {-0.15, 0, 0}, P[3] = {0, 0, 0.05}, E[3] = {0.1, 0, 0};
  memcpy(md.start, S, sizeof S);
  memcpy(md.end, E, sizeof E);
  md.nvia = 1;
  memcpy(md.via[0], P, sizeof P);
  swSpec *s = sw_spec_new();
  assert_int_equal(sw_spec_add_muscle(s, &md), 0);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double L = dist(S, P) + dist(P, E);
  SW_EXPECT_REL("rest length l0 = polyline length (m)", m->fil_l0[0], L, 1e-14);
  SW_EXPECT_ABS("stretch at t = 0", d->fil_stretch[0], 1.0, 1e-14);
  /* 12 elements over 0.1581 m and 0.1118 m: 7 and 5, the via point is node 7 */
  double x7[3];
  sw_get3(m, d->x, m->node_adr[0] + 7, x7);
  SW_EXPECT_ABS("via point to node 7 (m)", dist(x7, P), 0.0, 1e-15);
  /* straight at rest: no rest curvature at the bend */
  for (int v = m->vor_adr[0]; v < m->vor_adr[0] + 11; v++)
    for (int k = 0; k < 3; k++) assert_true(SW_AT(m, m->rest_kappa, v, k) == 0);
  SW_EXPECT_ABS("ring force at t = 0 (N)", norm3(d->ring_row + 2), 0.0, 1e-9);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 1. the rope over a frictionless pulley ---- */

#ifndef PULLEY_N
#define PULLEY_N 12
#endif
static void test_pulley(void **state) {
  (void)state;
  swMuscleDesc md = one_filament(PULLEY_N);
  const double S[3] = {-0.15, 0, 0}, P[3] = {0, 0, 0.05}, E[3] = {0.1, 0, 0};
  memcpy(md.start, S, sizeof S);
  memcpy(md.end, E, sizeof E);
  md.nvia = 1;
  memcpy(md.via[0], P, sizeof P); /* via_rod -1: fixed in space */
  md.density *= 100;
  md.gamma = 20;
  md.damping = SW_DAMP_ANALYTIC;
  swSpec *s = sw_spec_new();
  assert_int_equal(sw_spec_add_muscle(s, &md), 0);
  swBCDesc b = sw_test_clamp(0, 0);
  sw_spec_add_bc(s, &b);
  /* pull the free end along the second segment: passive stretch */
  double u2[3];
  unit(u2, P, E);
  const double F = 0.05 * fmax_one();
  swLoadDesc l = sw_test_load(SW_LOAD_FORCE, 0, -1, F * u2[0], F * u2[1], F * u2[2]);
  sw_spec_add_load(s, &l);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  const int n0 = m->node_adr[0], n = m->rod_nelem[0];
  double eta_prev = 0;
  while (d->time < 60) {
    sw_test_run_to(m, d, d->time + 0.25);

    if (fabs(d->fil_stretch[0] - eta_prev) < 1e-9) break;
    eta_prev = d->fil_stretch[0];
  }
  fprintf(stderr, "#   relaxed to t = %.3g s, eta = %.6f, contact element %d\n", d->time,
          d->fil_stretch[0], (int)d->ring_row[0]);
  /* tension on each side: the clamp's load at the start, the load at the end */
  double Fs[3], xs[3], xe[3];
  sw_get3(m, d->force, n0, Fs);
  sw_get3(m, d->x, n0, xs);
  sw_get3(m, d->x, n0 + n, xe);
  const double T_start = norm3(Fs), T_end = F;
  SW_EXPECT_REL("tension ratio start / end side", T_start / T_end, 1.0, 1e-3);
  /* the ring's reaction against 2 T sin(theta/2), theta the turn of the
   * filament at the contact (the directions to its two ends) */
  double a[3], e[3], x1[3], xm[3];
  sw_get3(m, d->x, n0 + 1, x1);
  sw_get3(m, d->x, n0 + n - 1, xm);
  unit(a, x1, xs); /* along element 0, toward the start */
  unit(e, xm, xe); /* along the last element, toward the end */
  const double cos_between = a[0] * e[0] + a[1] * e[1] + a[2] * e[2];
  const double theta = PI_T - acos(cos_between);
  const double R = norm3(d->ring_row + 2);
  fprintf(stderr, "#   wrap angle theta = %.4f rad (%.2f deg), T = %.4f N\n", theta,
          theta * 180 / PI_T, T_end);
  SW_EXPECT_REL("ring reaction / 2 T sin(theta/2)", R / (2 * T_end * sin(theta / 2)), 1.0, 1e-3);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_layout),
      cmocka_unit_test(test_pulley),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
