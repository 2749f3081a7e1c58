/* test_statics.c — static validations of the rod against closed forms:
 * Timoshenko cantilever (bending + shear), axial stretch, pure torsion, and
 * the second-order convergence of the cantilever's static error.
 * Statics are reached by dynamic relaxation with analytic damping tuned near
 * critical for the slowest mode; damping does not move the equilibrium. */
#include "testutil.h"

/* Timoshenko cantilever: L = 3 m, r = 0.25 m, E = 1 MPa, G = 10 kPa (so that
 * shear carries about a third of the deflection), tip load small enough that
 * the geometric nonlinearity is below 1e-6 relative. */
static const double TL = 3.0, TR = 0.25, TE = 1e6, TG = 1e4, TRHO = 1000.0, TF = 0.15;

static double timoshenko_analytic(void) {
  double A = M_PI * TR * TR, I = A * TR * TR / 4.0;
  return TF * TL * TL * TL / (3.0 * TE * I) + TF * TL / (4.0 / 3.0 * TG * A);
}

/* Tip deflection of the discrete cantilever with n elements. */
static double timoshenko_tip(int n) {
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "beam";
  r.nelem = n;
  r.direction[0] = 1; r.direction[1] = 0; r.direction[2] = 0;
  r.normal[0] = 0; r.normal[1] = 0; r.normal[2] = 1;
  r.length = TL;
  r.radius_start = r.radius_end = TR;
  r.density = TRHO;
  r.youngs = TE;
  r.shear_modulus = TG;
  /* critical damping of the first bending mode: c = 2 w1 */
  double A = M_PI * TR * TR, I = A * TR * TR / 4.0;
  double w1 = 1.8751 * 1.8751 / (TL * TL) * sqrt(TE * I / (TRHO * A));
  r.damping = SW_DAMP_ANALYTIC;
  r.gamma = 2.0 * w1 * TRHO * A;
  int id = sw_spec_add_rod(s, &r);
  swBCDesc c = sw_test_clamp(id, 0);
  sw_spec_add_bc(s, &c);
  swLoadDesc f = sw_test_load(SW_LOAD_FORCE, id, -1, 0, -TF, 0);
  sw_spec_add_load(s, &f);
  swModel *m = sw_test_compile_at(s, 0.8);
  swData *d = sw_data_new(m);
  const double *tip_y = &SW_AT(m, d->x, m->node_adr[id] + n, 1);
  double y = sw_test_relax(m, d, tip_y, 2.0, 400.0, 1e-9);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return -y;
}

static void test_timoshenko_cantilever(void **state) {
  (void)state;
  int n = sw_test_sanitized() ? 20 : 100;
  double tol = sw_test_sanitized() ? 2e-2 : 1e-2;
  SW_EXPECT_REL("tip deflection (m)", timoshenko_tip(n), timoshenko_analytic(), tol);
}

static void test_timoshenko_convergence(void **state) {
  (void)state;
  int ns[] = {8, 16, 32, 64};
  int k = sw_test_sanitized() ? 3 : 4;
  double err[4], ref = timoshenko_analytic();
  for (int i = 0; i < k; i++) {
    err[i] = (timoshenko_tip(ns[i]) - ref) / ref;
    fprintf(stderr, "# %s: n = %d, relative error %.4e\n", __func__, ns[i], err[i]);
  }
  for (int i = 0; i + 1 < k; i++) {
    double p = sw_test_order(err, i);
    fprintf(stderr, "# %s: order between n = %d and %d: %.3f (expected 2)\n", __func__, ns[i],
            ns[i + 1], p);
    assert_true(p > 1.8 && p < 2.2);
  }
}

/* Axial stretch: a clamped rod pulled along its axis.  The rod's law is
 * n = EA (e - 1) / e, so the strain differs from F/(EA) by (F/EA)^2; at a
 * strain of 1e-5 that is 1e-5 relative. */
static void test_axial_stretch(void **state) {
  (void)state;
  const double L = 0.5, rad = 0.01, E = 1e6, rho = 1000, n = 40;
  double A = M_PI * rad * rad, F = 1e-5 * E * A;
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "bar";
  r.nelem = (int)n;
  r.length = L;
  r.radius_start = r.radius_end = rad;
  r.density = rho;
  r.youngs = E;
  r.damping = SW_DAMP_ANALYTIC;
  double w1 = M_PI / (2 * L) * sqrt(E / rho);
  r.gamma = 2.0 * w1 * rho * A;
  int id = sw_spec_add_rod(s, &r);
  swBCDesc c = sw_test_clamp(id, 0);
  sw_spec_add_bc(s, &c);
  swLoadDesc f = sw_test_load(SW_LOAD_FORCE, id, -1, 0, 0, F);
  sw_spec_add_load(s, &f);
  swModel *m = sw_test_compile_at(s, 0.8);
  swData *d = sw_data_new(m);
  double z = sw_test_relax(m, d, &SW_AT(m, d->x, m->node_adr[id] + (int)n, 2), 0.05, 20.0, 1e-12);
  SW_EXPECT_REL("extension (m)", z - L, F * L / (E * A), 1e-3);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Pure torsion: twist of the last element (its centre at s = L - l/2) under
 * an end couple T about the axis, against T s / (G J). */
static void test_pure_torsion(void **state) {
  (void)state;
  const double L = 1.0, rad = 0.02, E = 1e6, rho = 1000;
  const int n = sw_test_sanitized() ? 20 : 50;
  const double G = E / 3.0, J = M_PI * pow(rad, 4) / 2.0, T = 1e-4 * G * J / L;
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "shaft";
  r.nelem = n;
  r.length = L;
  r.radius_start = r.radius_end = rad;
  r.density = rho;
  r.youngs = E;
  r.poisson = 0.5;
  double A = M_PI * rad * rad, wt = M_PI / (2 * L) * sqrt(G / rho);
  r.damping = SW_DAMP_ANALYTIC;
  r.gamma = 2.0 * wt * rho * A;
  int id = sw_spec_add_rod(s, &r);
  swBCDesc c = sw_test_clamp(id, 0);
  sw_spec_add_bc(s, &c);
  swLoadDesc tq = sw_test_load(SW_LOAD_TORQUE, id, -1, 0, 0, T);
  sw_spec_add_load(s, &tq);
  swModel *m = sw_test_compile_at(s, 0.8);
  swData *d = sw_data_new(m);
  /* twist angle of the last element: angle between its d1 and the initial d1 */
  double angle = 0, prev = -1;
  while (d->time < 50.0) {
    sw_test_run_to(m, d, d->time + 0.05);
    double Q[9];
    sw_getQ(m, d->Q, m->elem_adr[id] + n - 1, Q);
    angle = fabs(atan2(Q[1], Q[0])); /* d1 turns about the axis z from x */
    if (fabs(angle - prev) <= 1e-10 * angle) break;
    prev = angle;
  }
  double sc = L - 0.5 * L / n;
  SW_EXPECT_REL("twist angle at the last element (rad)", angle, T * sc / (G * J), 1e-3);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_timoshenko_cantilever),
      cmocka_unit_test(test_axial_stretch),
      cmocka_unit_test(test_pure_torsion),
      cmocka_unit_test(test_timoshenko_convergence),
  };
  return cmocka_run_group_tests_name("statics", tests, NULL, NULL);
}
