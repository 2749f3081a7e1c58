/* test_joint_alias.c — two ports of one implicit rod that turn the same
 * element (joint_alias.c): the wing's digits, a tapered bone whose last two
 * nodes each carry a feather on a fixed joint, both joints turning its
 * last element.
 *
 * Design.  The scene: the digits of models/pigeon_wing.sinew (75 mm,
 * r = 12 mm to 2 mm, 5 elements, E = 15 GPa, 875 kg/m^3, implicit, here
 * clamped at its start) and two implicit rachises (r = 2.5 mm, 40 elements,
 * keratin of the wing: E = 2.5 MPa, 2.5 kg/m^3) fixed at the bone's nodes 4
 * and 5, each with four explicit barbs on fixed joints (so the group takes
 * the member's band path, as the wing's does), under gravity, at 1 us (the
 * wing's step).  Asserted:
 *  - the bone's second port is marked as the first's rotation;
 *  - with the fold, 3000 steps stay bounded; with the marks cleared (the
 *    runtime before the fold: the condensation's C = E^T A^-1 E with two
 *    equal rows), the run grows without bound (the resolved wing's digits
 *    blew up within 16 steps so);
 *  - the member's band path and the dense path (every port condensed,
 *    both with the fold) agree to round-off after 20 steps;
 *  - against the same scene at an eighth of the step, the rachises' tips'
 *    mean fall over the first 2 ms is within 0.5% at 1 us, and the error
 *    falls with the step at an order of at least 1.5 (printed). */
#include "testutil.h"
#include "internal.h"
#include "band_compare.h"

static swModel *digits(double dt, swSpec **out) {
  swSpec *s = sw_spec_new();
  const double b0[3] = {0, 0, 0}, dx[3] = {1, 0, 0}, dy[3] = {0, 1, 0}, nz[3] = {0, 0, 1};
  swRodDesc bd = sw_test_rod("digits", 5, 0.075, 12e-3, b0, dx, nz);
  bd.radius_end = 2e-3;
  bd.youngs = 15e9, bd.shear_modulus = 10e9, bd.density = 875, bd.implicit = 1;
  const int bone = sw_spec_add_rod(s, &bd);
  swBCDesc c = sw_test_clamp(bone, 0);
  sw_spec_add_bc(s, &c);
  static const char *const rname[2] = {"rachis4", "rachis5"};
  static const char *const jname[2] = {"root4", "root5"};
  static char barb_name[8][16], barb_joint[8][16];
  for (int f = 0; f < 2; f++) {
    const double start[3] = {0.075 * (4 + f) / 5, 0, 0};
    swRodDesc r = sw_test_rod(rname[f], 40, 0.2, 2.5e-3, start, dy, nz);
    r.direction[2] = 0.1 * f;
    r.youngs = 2.5e6, r.shear_modulus = 2.5e6 * 2 / 3, r.density = 2.5, r.implicit = 1;
    const int rachis = sw_spec_add_rod(s, &r);
    swJointDesc j;
    sw_joint_desc_init(&j);
    j.name = jname[f];
    j.kind = SW_JOINT_FIXED;
    j.rod_a = bone, j.node_a = 4 + f, j.rod_b = rachis, j.node_b = 0;
    j.stiffness = 5e5;
    sw_spec_add_joint(s, &j);
    for (int l = 0; l < 4; l++) {
      const int node = 10 + 8 * l, w = 4 * f + l;
      snprintf(barb_name[w], sizeof barb_name[w], "barb%d", w);
      snprintf(barb_joint[w], sizeof barb_joint[w], "tie%d", w);
      const double at[3] = {start[0], 0.2 * node / 40, 0.02 * f * node / 40};
      const double dir[3] = {l % 2 ? -1 : 1, 0.5, 0};
      swRodDesc b = sw_test_rod(barb_name[w], 4, 0.03, 1.5e-3, at, dir, nz);
      b.youngs = 2.5e6, b.shear_modulus = 2.5e6 * 2 / 3, b.density = 2.5;
      const int barb = sw_spec_add_rod(s, &b);
      sw_joint_desc_init(&j);
      j.name = barb_joint[w];
      j.kind = SW_JOINT_FIXED;
      j.rod_a = rachis, j.node_a = node, j.rod_b = barb, j.node_b = 0;
      j.stiffness = 5e3;
      sw_spec_add_joint(s, &j);
    }
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, SW_IMEX);
  sw_spec_set_dt(s, dt);
  *out = s;
  return sw_test_compile(s);
}

static int rod_named(const swModel *m, const char *name) {
  for (int r = 0; r < m->nrod; r++)
    if (!strcmp(m->rod_name[r], name)) return r;
  return -1;
}

static int aliases(const swModel *m) {
  int n = 0;
  for (int q = 0; q < m->nrigid_port; q++) n += m->rigid_port_alias[q] >= 0;
  return n;
}

/* The mean z of the two rachises' tips. */
static double tips_z(const swModel *m, const swData *d) {
  double z = 0;
  for (int f = 0; f < 2; f++) {
    const int r = rod_named(m, f ? "rachis5" : "rachis4");
    assert_true(r >= 0);
    z += 0.5 * SW_AT(m, d->x, m->node_adr[r] + m->rod_nelem[r], 2);
  }
  return z;
}

static void test_marked(void **state) {
  (void)state;
  swSpec *s;
  swModel *m = digits(1e-6, &s);
  fprintf(stderr, "# test_marked: %d groups, %d ports, %d another's rotation; group 0's path %d\n",
          m->nrigid_group, m->nrigid_port, aliases(m), m->rigid_group_band[0]);
  assert_int_equal(m->nrigid_group, 1);
  assert_int_equal(m->rigid_group_band[0], 2); /* the barbs in their rachis' bands */
  assert_int_equal(aliases(m), 1);
  const int bone = rod_named(m, "digits");
  for (int q = 0; q < m->nrigid_port; q++) /* node 5's port is node 4's element's */
    if (m->rigid_port_alias[q] >= 0) {
      const int t = m->rigid_port_alias[q];
      assert_int_equal(m->rigid_port_elem[q], m->rigid_port_elem[t]);
      assert_int_equal(m->rigid_port_elem[q], m->elem_adr[bone] + 4);
      assert_int_not_equal(m->rigid_port_node[q], m->rigid_port_node[t]);
    }
  sw_model_free(m);
  sw_spec_free(s);
}

/* 3000 steps at 1 us from rest, with and without the fold. */
static void test_bounded(void **state) {
  (void)state;
  swSpec *s;
  swModel *m = digits(1e-6, &s);
  swData *d = sw_data_new(m);
  assert_non_null(d);
  const int with = sw_test_stays_bounded(m, d, 3000); /* frees m and d */
  sw_spec_free(s);
  m = digits(1e-6, &s);
  for (int q = 0; q < m->nrigid_port; q++) m->rigid_port_alias[q] = -1;
  d = sw_data_new(m);
  long k = 0;
  double e[3];
  int ok = 1;
  for (; k < 3000 && ok; k++) {
    ok = sw_step(m, d) == SW_OK;
    sw_energy(m, d, e);
    ok = ok && isfinite(e[0] + e[1]) && fabs(e[0] + e[1]) < 1.0;
  }
  fprintf(stderr, "# test_bounded: with the fold 3000 steps of 1 us %s; without it, %s after %ld "
          "steps\n", with ? "bounded" : "NOT bounded", ok ? "still bounded" : "unbounded", k);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  assert_true(with);
  assert_false(ok);
}

static void test_paths_agree(void **state) {
  (void)state;
  swSpec *s;
  swModel *m = digits(1e-6, &s);
  swData *band = data_for(m, 2), *dense = data_for(m, 0), *ulp = data_for(m, 0);
  const BandRun r = band_against_dense(m, 2, 1, 200, 20, band, dense, ulp);
  print_band_run(&r, 20, 200);
  for (int q = 0; q < 3; q++) assert_true(r.er[q] <= fmax(1e-12, 10 * r.eur[q]));
  for (int q = 0; q < 3; q++) assert_true(r.dr[q] <= fmax(1e-12, 10 * r.ur[q]));
  sw_data_free(band);
  sw_data_free(dense);
  sw_data_free(ulp);
  sw_model_free(m);
  sw_spec_free(s);
}

/* The tips' mean z over the first T at steps of 1 us / 2^c, c = 0 .. 3,
 * and the order of the differences against the finest (the mean, not the
 * z at T: the tips ring after gravity comes on, and their fast modes'
 * phase at T is not what the step converges first). */
static void test_quarter_step(void **state) {
  (void)state;
  const double T = 2e-3;
  double z[4], z0 = 0;
  for (int c = 0; c < 4; c++) {
    swSpec *s;
    swModel *m = digits(1e-6 / (1 << c), &s);
    swData *d = sw_data_new(m);
    assert_non_null(d);
    z0 = tips_z(m, d);
    double sum = 0.5 * z0, zk = z0;
    long n = 0;
    while (d->time < T - 0.5 * m->dt) { /* the mean over (0, T), trapezoidal rule */
      assert_int_equal(sw_step(m, d), SW_OK);
      zk = tips_z(m, d);
      sum += zk, n++;
    }
    z[c] = (sum - 0.5 * zk) / n;
    sw_data_free(d);
    sw_model_free(m);
    sw_spec_free(s);
  }
  const double fall = z0 - z[3], err[3] = {z[0] - z[3], z[1] - z[3], z[2] - z[3]};
  fprintf(stderr, "# test_quarter_step: against 1/8 us, the mean fall's error at 1, 1/2, 1/4 us: "
          "%.3g %.3g %.3g of it; order %.2f, %.2f\n", err[0] / fall, err[1] / fall, err[2] / fall,
          sw_test_order(err, 0), sw_test_order(err, 1));
  assert_true(fall > 1e-6); /* they fell */
  assert_true(fabs(err[0]) <= 5e-3 * fall);
  assert_true(sw_test_order(err, 0) >= 1.5); /* the trapezoidal rule's 2 (1.8 to 2.4 here) */
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_marked),
      cmocka_unit_test(test_bounded),
      cmocka_unit_test(test_paths_agree),
      cmocka_unit_test(test_quarter_step),
  };
  return cmocka_run_group_tests_name("joint_alias", tests, NULL, NULL);
}
