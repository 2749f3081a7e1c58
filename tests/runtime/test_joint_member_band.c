/* test_joint_member_band.c — a member's band path (joint_ports.c,
 * rigid_group_band 2): an implicit rod that is a member of a larger group
 * (a rachis tied to a bone) with its lone leaves (barbs) eliminated into
 * its band and the rod condensed to its other ports alone, against the
 * dense path of the same group (the rod condensed to all its ports, the
 * leaves eliminated into that block), which solves the same linear system.
 *
 * Design.  A "feather on a bone": an implicit rachis (40 elements) whose
 * start is tied by a fixed joint to the end of a bone, a rigid body hinged
 * to space at its other end or an implicit rod clamped there, and short
 * explicit barbs (4 elements) on fixed joints (one spherical) at its nodes,
 * one of them on the rachis' root, whose port stays in the group's block
 * with its leaf, and two on one node (and two on the implicit bone, whose
 * band takes them too); gravity, every node and element
 * started moving.  One model, swData for each path (m->rigid_group_band
 * toggled around its step, as test_joint_band does; the dense path
 * factored afresh every kick as the band is).  The two must agree to
 * round-off over 20 steps (1e-12, or what a one-ulp start makes the dense
 * path differ from itself by then: the barbs' fast turns amplify a
 * round-off 1e4-fold in those steps), and over the run within what a
 * one-ulp start makes the dense path differ from itself.  Then the cost of one kick each
 * way for 4, 16 and 64 barbs on 128 elements, printed, with the group's
 * dense unknowns (asserted: the bone's 6 and the rachis' root's 6). */
#include <float.h>
#include <time.h>
#include "testutil.h"
#include "vec.h"
#include "internal.h"
#include "band_compare.h"

static const char *named(const char *stem) {
  static char name[32];
  static int count;
  snprintf(name, sizeof name, "%s%d", stem, count++);
  return name;
}

enum { RIGID, IMPLICIT };
static const char *const bone_name[2] = {"rigid bone hinged to space", "implicit bone clamped"};

/* The bone (0.1 m along x to the origin, r = 5 mm) as `bone` says, the
 * rachis (0.2 m along x, r = 2 mm, E = 100 MPa, nel elements) fixed at its
 * start to the bone's end, nleaf barbs (20 mm, r = 0.4 mm, 4 elements) at
 * nodes at[l], barb `spherical` on a spherical joint. */
static swModel *feather(int bone, int nel, int nleaf, const int *at, int spherical, swSpec **out) {
  swSpec *s = sw_spec_new();
  const double L = 0.2, x0[3] = {0, 0, 0}, b0[3] = {-0.1, 0, 0}, dx[3] = {1, 0, 0};
  swRodDesc bd = sw_test_rod(named("bone"), 10, 0.1, 5e-3, b0, dx, NULL);
  bd.density = 1750;
  if (bone == RIGID) bd.youngs = 15e9, bd.rigid = 1;
  else bd.youngs = 1e9, bd.shear_modulus = 1e9 / 3, bd.implicit = 1;
  const int b = sw_spec_add_rod(s, &bd);
  swJointDesc j;
  if (bone == RIGID) {
    sw_joint_desc_init(&j);
    j.name = named("shoulder");
    j.kind = SW_JOINT_HINGE;
    j.rod_a = b, j.node_a = 0, j.rod_b = -1;
    j.anchor[0] = b0[0];
    j.axis[1] = 1;
    sw_spec_add_joint(s, &j);
  } else {
    swBCDesc c = sw_test_clamp(b, 0);
    sw_spec_add_bc(s, &c);
  }
  swRodDesc r = sw_test_rod(named("rachis"), nel, L, 2e-3, x0, dx, NULL);
  r.youngs = 1e8, r.shear_modulus = 1e8 / 3, r.density = 1200, r.implicit = 1;
  const int rachis = sw_spec_add_rod(s, &r);
  sw_joint_desc_init(&j);
  j.name = named("root");
  j.kind = SW_JOINT_FIXED;
  j.rod_a = b, j.node_a = -1, j.rod_b = rachis, j.node_b = 0;
  sw_spec_add_joint(s, &j);
  for (int l = 0; l < nleaf + (bone == IMPLICIT ? 2 : 0); l++) {
    const int on_bone = l >= nleaf; /* the implicit bone's two barbs, at its nodes 3 and 7 */
    const double start[3] = {on_bone ? b0[0] + 0.01 * (3 + 4 * (l - nleaf)) : L * at[l] / nel, 0, 0};
    const double dir[3] = {0.1 * l, l % 2 ? -1 : 1, 0.3}, nrm[3] = {1, 0, 0};
    swRodDesc bb = sw_test_rod(named("barb"), 4, 0.02, 4e-4, start, dir, nrm);
    bb.youngs = 1e7, bb.shear_modulus = 1e7 / 3, bb.density = 1200;
    const int barb = sw_spec_add_rod(s, &bb);
    sw_joint_desc_init(&j);
    j.name = named("j");
    j.kind = l == spherical ? SW_JOINT_SPHERICAL : SW_JOINT_FIXED;
    j.rod_a = on_bone ? b : rachis, j.node_a = on_bone ? 3 + 4 * (l - nleaf) : at[l];
    j.rod_b = barb, j.node_b = 0;
    sw_spec_add_joint(s, &j);
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, SW_IMEX);
  *out = s;
  return sw_test_compile_at(s, 0.5);
}


/* Unknowns of group 0's dense block on the path `band`. */
static int unknowns(swModel *m, int band) {
  set_band(m, band);
  const int n = sw_rigid_group_unknowns(m, 0);
  set_band(m, 2);
  return n;
}

#define EARLY 20
static void same_solution(int bone) {
  static const int at[10] = {0, 4, 8, 12, 16, 16, 22, 28, 34, 40};
  swSpec *s;
  swModel *m = feather(bone, 40, 10, at, 3, &s);
  assert_int_equal(m->nrigid_group, 1);
  assert_int_equal(m->rigid_group_band[0], 2); /* the rachis' barbs in its band */
  const int nb = unknowns(m, 2), nd = unknowns(m, 0);
  swData *band = data_for(m, 2), *dense = data_for(m, 0), *ulp = data_for(m, 0);
  const long nsteps = sw_test_sanitized() ? 150 : 300;
  /* the bone's system factored afresh too */
  const BandRun r = band_against_dense(m, 2, 1, nsteps, EARLY, band, dense, ulp);
  const double *er = r.er, *dr = r.dr, *ur = r.ur;
  fprintf(stderr, "# test_same_solution: %s, rachis of 40 elements, 10 barbs%s, dt %.3g s; group "
          "block %d unknowns (dense path %d)\n", bone_name[bone],
          bone == IMPLICIT ? " (2 more on the bone)" : "", m->dt, nb, nd);
  print_band_run(&r, EARLY, nsteps);
  assert_int_equal(nb, 12); /* the bone's 6 (a body's, or its end port's) and the rachis' root's 6 */
  for (int q = 0; q < 3; q++) assert_true(er[q] <= fmax(1e-12, 10 * r.eur[q]));
  assert_true(dr[0] <= fmax(1e-12, 10 * ur[0]));
  for (int q = 1; q < 3; q++) assert_true(dr[q] <= fmax(1e-12, 10 * ur[q]));
  double vmax;
  (void)worst(dense->v, dense->v, 3 * (size_t)m->stride, &vmax);
  assert_true(vmax > 0.01); /* it moved */
  sw_data_free(band);
  sw_data_free(dense);
  sw_data_free(ulp);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_same_solution(void **state) {
  (void)state;
  same_solution(RIGID);
  same_solution(IMPLICIT);
}

static void test_cost(void **state) {
  (void)state;
  static const int leaves[3] = {4, 16, 64};
  for (int c = 0; c < 3; c++) {
    int at[64];
    for (int l = 0; l < leaves[c]; l++) at[l] = 2 + l * 126 / leaves[c];
    swSpec *s;
    swModel *m = feather(RIGID, 128, leaves[c], at, -1, &s);
    assert_int_equal(m->rigid_group_band[0], 2);
    const int nb = unknowns(m, 2), nd = unknowns(m, 0);
    swData *band = data_for(m, 2), *dense = data_for(m, 0);
    double tb, td;
    kick_times(m, 2, band, dense, &tb, &td);
    fprintf(stderr, "# test_cost: %2d barbs on 128 elements, rigid bone: member's band path %8.1f us "
            "per kick (block of %d unknowns), dense path %8.1f us (%d), dense / band %.1f\n",
            leaves[c], 1e6 * tb, nb, 1e6 * td, nd, td / tb);
    assert_int_equal(nb, 12);
    sw_data_free(band);
    sw_data_free(dense);
    sw_model_free(m);
    sw_spec_free(s);
  }
}

/* The band kept (rod_implicit.c, sw_implicit_band_kept): the feather on
 * its rigid bone swinging down from rest under gravity for T (the bone
 * turns by about 0.2 rad, the rachis and barbs with it), its band factored
 * afresh at every kick (sw_implicit_reset) and kept while it holds, at the
 * scene's step h and at h / 2 (the rod's kept factorisation is an earlier
 * configuration's matrix: a W-method, second order).  The kept run keeps
 * most kicks; its positions differ from the fresh run's by D(h), and
 * D(h) / D(h / 2) shows the order: at least the trapezoidal rule's 2, as
 * the turn a band is kept for shrinks with the step (rod_implicit.c). */
static double kept_against_fresh(double frac, double T, double *share) {
  static const int at[10] = {0, 4, 8, 12, 16, 16, 22, 28, 34, 40};
  swSpec *s;
  swModel *m = feather(RIGID, 40, 10, at, 3, &s);
  sw_spec_set_dt(s, frac * m->dt);
  sw_model_free(m);
  m = sw_test_compile(s);
  swData *kept = sw_data_new(m), *fresh = sw_data_new(m);
  assert_non_null(kept);
  assert_non_null(fresh);
  double *x0 = malloc(3 * (size_t)m->stride * sizeof(double));
  assert_non_null(x0);
  memcpy(x0, fresh->x, 3 * (size_t)m->stride * sizeof(double));
  while (kept->time < T - 0.5 * m->dt) {
    assert_int_equal(sw_step(m, kept), SW_OK);
    sw_implicit_reset(m, fresh);
    assert_int_equal(sw_step(m, fresh), SW_OK);
  }
  double nf, nk, scale;
  sw_implicit_counts(m, kept, &nf, &nk);
  *share = nk / (nf + nk);
  const double D = worst(kept->x, fresh->x, 3 * (size_t)m->stride, &scale);
  double moved = 0; /* how far any node went */
  for (int i = 0; i < 3 * m->stride; i++) moved = fmax(moved, fabs(fresh->x[i] - x0[i]));
  fprintf(stderr, "# kept_against_fresh: dt %.3g s, %.1f%% of the implicit kicks kept, positions "
          "apart by %.3e m after %g s (nodes moved up to %.3e m)\n",
          m->dt, 100 * *share, D, T, moved);
  free(x0);
  sw_data_free(kept);
  sw_data_free(fresh);
  sw_model_free(m);
  sw_spec_free(s);
  return D / moved;
}

static void test_kept_band(void **state) {
  (void)state;
  const double T = 50e-3;
  double share[2];
  const double D[2] = {kept_against_fresh(1.0, T, share), kept_against_fresh(0.5, T, share + 1)};
  const double order = log(D[0] / D[1]) / log(2.0);
  fprintf(stderr, "# test_kept_band: kept - fresh, of the largest displacement: %.3e at h, "
          "%.3e at h / 2: order %.2f\n", D[0], D[1], order);
  assert_true(share[0] > 0.5 && share[1] > 0.5); /* it keeps */
  assert_true(D[0] <= 1e-6);
  assert_true(order >= 1.5);
}

/* Every node and element of d, and the rigid bone, turning as one body
 * about the bone's hinge (y through x = -0.1 m) at W rad/s. */
static void start_turning(const swModel *m, swData *d, double W) {
  const double Om[3] = {0, W, 0}, hinge[3] = {-0.1, 0, 0};
  for (int r = 0; r < m->nrod; r++) {
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
      double x[3], rel[3], v[3];
      sw_get3(m, d->x, i, x);
      sw_v3_sub(rel, x, hinge);
      sw_v3_cross(v, Om, rel);
      for (int k = 0; k < 3; k++) SW_AT(m, d->v, i, k) = v[k];
    }
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) {
      double Q[9], w[3];
      sw_getQ(m, d->Q, e, Q);
      sw_mat_vec(w, Q, Om); /* material components */
      for (int k = 0; k < 3; k++) SW_AT(m, d->omega, e, k) = w[k];
    }
  }
  for (int b = 0; b < m->nrigid; b++) {
    const double *R = d->rigid_R + 9 * b, *I = m->rigid_inertia + 3 * b;
    double rel[3];
    sw_v3_sub(rel, d->rigid_X + 3 * b, hinge);
    sw_v3_cross(d->rigid_V + 3 * b, Om, rel);
    memcpy(d->rigid_omega + 3 * b, Om, sizeof Om);
    for (int i = 0; i < 3; i++) { /* L = R diag(I) R^T Omega */
      double s = 0;
      for (int k = 0; k < 3; k++)
        s += (R[3 * i] * I[0] * R[3 * k] + R[3 * i + 1] * I[1] * R[3 * k + 1] +
              R[3 * i + 2] * I[2] * R[3 * k + 2]) * Om[k];
      d->rigid_L[3 * b + i] = s;
    }
  }
}

/* The kept Z (joint_ports.c, kept_turns): a kick on a kept band takes Z =
 * A^-1 E of the kick that factored it and turns each rotating port's
 * columns by T = Q_k^T Q, exact for that band, where it used to solve for
 * Z with this kick's E.  The feather on its rigid bone, all of it started
 * turning about the bone's hinge at 20 rad/s, at the scene's step, run
 * twice in step; before the last kick (the band kept, its root turned
 * since), one run forgets its Z (sw_rigid_forget_kept_maps) and solves for
 * it.  The two kicks must agree to round-off, 1e-13 of each quantity's
 * largest (measured: 0, 0 and 3e-19 for x, v, omega); the kick with Z kept
 * but not turned (turn_ports' T left out) is off by 6.5e-11 in omega. */
static void test_kept_turns(void **state) {
  (void)state;
  static const int at[10] = {0, 4, 8, 12, 16, 16, 22, 28, 34, 40};
  swSpec *s;
  swModel *m = feather(RIGID, 40, 10, at, 3, &s);
  swData *turned = data_for(m, 2), *solved = data_for(m, 2);
  start_turning(m, turned, 20);
  start_turning(m, solved, 20);
  const int root = m->elem_adr[1]; /* the rachis' first element */
  double Q0[9], Q[9], r[3], ra[3], nf, nk;
  sw_getQ(m, turned->Q, root, Q0);
  const long nsteps = sw_test_sanitized() ? 300 : 1000;
  for (long k = 0; k < nsteps; k++) {
    if (k == nsteps - 1) {
      differences(m, solved, turned, ra, r);
      sw_rigid_forget_kept_maps(m, solved);
    }
    assert_int_equal(sw_step(m, turned), SW_OK);
    assert_int_equal(sw_step(m, solved), SW_OK);
  }
  for (int q = 0; q < 3; q++) assert_true(r[q] == 0); /* the same bits until then */
  differences(m, solved, turned, ra, r);
  sw_getQ(m, turned->Q, root, Q);
  double tr = 0;
  for (int c = 0; c < 9; c++) tr += Q[c] * Q0[c];
  const double turn = acos(fmin(1.0, 0.5 * (tr - 1)));
  sw_implicit_counts(m, turned, &nf, &nk);
  fprintf(stderr, "# test_kept_turns: dt %.3g s, %ld steps, the root turned %.3f rad, %.1f%% of "
          "the implicit kicks kept; the last kick with Z kept and turned - with Z solved for, "
          "relative: x %.2e v %.2e omega %.2e\n", m->dt, nsteps, turn, 100 * nk / (nf + nk),
          r[0], r[1], r[2]);
  assert_true(turn > 0.01);
  assert_true(nk > nf); /* it keeps */
  for (int q = 0; q < 3; q++) assert_true(r[q] <= 1e-13);
  sw_data_free(turned);
  sw_data_free(solved);
  sw_model_free(m);
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_same_solution),
      cmocka_unit_test(test_kept_band),
      cmocka_unit_test(test_kept_turns),
      cmocka_unit_test(test_cost),
  };
  return cmocka_run_group_tests_name("joint_member_band", tests, NULL, NULL);
}
