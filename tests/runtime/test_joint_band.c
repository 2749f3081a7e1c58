/* test_joint_band.c — the joints' system's band path (joint_ports.c,
 * sw_band_group_solve): a group of one implicit rod and leaves alone on its
 * ports solved in the rod's band, against the dense path of the same group
 * (the rod condensed to its ports, S = C^-1, the leaves eliminated into
 * that block), which solves the same linear system another way.
 *
 * Design.  A "feather": an implicit rachis (20 elements, clamped at its
 * start, free, or hinged to space there: that joint's block alone on its
 * port) carrying short explicit barbs (4 elements) joined at their base
 * nodes to its nodes by stiff implicit joints (fixed, and one spherical;
 * two barbs on one node), under gravity, every node and element
 * started moving.  One model, two swData, each stepped with its own path
 * (m->rigid_group_band toggled around its step, as test_rigid_joint toggles
 * its batches; each swData's workspace sized for its path when it is
 * made).  The band path factors the band afresh every kick (the leaves'
 * blocks change with the state), so the dense path is made to as well
 * (sw_implicit_reset before each step: no kept factorisation of the rod),
 * and the two must agree to round-off.  Then the cost of one kick of the
 * joints' system each way for 4, 16 and 64 barbs on a rachis of 128
 * elements, printed (measured, not asserted), with the workspace each path
 * needs (asserted: the band path's grows linearly in the ports). */
#include <float.h>
#include <time.h>
#include "testutil.h"
#include "internal.h"
#include "band_compare.h"

static const char *named(const char *stem) {
  static char name[32];
  static int count;
  snprintf(name, sizeof name, "%s%d", stem, count++);
  return name;
}

/* How the rachis is held: free, clamped at its start, or hinged to space
 * there (a joint of the rod alone, its port's block without a leaf). */
enum { FREE, CLAMPED, HINGED };
static const char *const held_name[3] = {"free", "clamped", "hinged to space"};

/* A rachis of nel elements along x (0.2 m, r = 2 mm, E = 100 MPa, G = E/3),
 * implicit, held at its start as `held` says; nleaf barbs (20 mm, r =
 * 0.4 mm, E = 10 MPa, 4 elements), barb l at node at[l] of the rachis,
 * pointing alternately +y and -y and tilted up, joined base to that node by
 * a fixed joint, or spherical for barb `spherical`.  With dt = 0 the step
 * is half the stable estimate and the barbs are explicit; with dt > 0 the
 * barbs are implicit too (rod leaves: joint_groups.c) and the step dt. */
static swModel *feather_at(int nel, int nleaf, const int *at, int spherical, int held, double dt,
                           swSpec **out) {
  swSpec *s = sw_spec_new();
  const double L = 0.2, x0[3] = {0, 0, 0}, dx[3] = {1, 0, 0};
  swRodDesc r = sw_test_rod(named("rachis"), nel, L, 2e-3, x0, dx, NULL);
  r.youngs = 1e8, r.shear_modulus = 1e8 / 3, r.density = 1200, r.implicit = 1;
  const int rachis = sw_spec_add_rod(s, &r);
  if (held == CLAMPED) {
    swBCDesc c = sw_test_clamp(rachis, 0);
    sw_spec_add_bc(s, &c);
  } else if (held == HINGED) {
    swJointDesc j;
    sw_joint_desc_init(&j);
    j.name = named("pin");
    j.kind = SW_JOINT_HINGE;
    j.rod_a = rachis, j.node_a = 0, j.rod_b = -1;
    j.axis[1] = 1;
    sw_spec_add_joint(s, &j);
  }
  for (int l = 0; l < nleaf; l++) {
    const double start[3] = {L * at[l] / nel, 0, 0};
    const double dir[3] = {0.1 * l, l % 2 ? -1 : 1, 0.3}, nrm[3] = {1, 0, 0};
    swRodDesc b = sw_test_rod(named("barb"), 4, 0.02, 4e-4, start, dir, nrm);
    b.youngs = 1e7, b.shear_modulus = 1e7 / 3, b.density = 1200, b.implicit = dt > 0;
    const int barb = sw_spec_add_rod(s, &b);
    swJointDesc j;
    sw_joint_desc_init(&j);
    j.name = named("j");
    j.kind = l == spherical ? SW_JOINT_SPHERICAL : SW_JOINT_FIXED;
    j.rod_a = rachis, j.node_a = at[l];
    j.rod_b = barb, j.node_b = 0;
    sw_spec_add_joint(s, &j);
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, SW_IMEX);
  *out = s;
  if (!(dt > 0)) return sw_test_compile_at(s, 0.5);
  sw_spec_set_dt(s, dt);
  return sw_test_compile(s);
}

static swModel *feather(int nel, int nleaf, const int *at, int spherical, int held, swSpec **out) {
  return feather_at(nel, nleaf, at, spherical, held, 0, out);
}


/* The feather stepped by both paths, and by the dense path from a start one
 * unit in the last place away (every velocity times 1 + 2^-52): how far
 * the scene itself carries a round-off.  After EARLY steps, before the
 * barbs' fast rotations have amplified it much, x, v and omega agree within
 * 1e-12 of their largest or within what the one-ulp start makes them
 * differ by then (a factor 10 above it, the spread of such amplified
 * round-off); after the run, x within 1e-12, and v and omega as the one-ulp
 * start makes them differ. */
#define EARLY 20
static void same_solution_at(int held, int nleaf, const int *at, int spherical) {
  swSpec *s;
  swModel *m = feather(20, nleaf, at, spherical, held, &s);
  assert_int_equal(m->nrigid_group, 1);
  assert_int_equal(m->rigid_group_band[0], 1); /* one rod and its leaves */
  assert_int_equal(m->nrigid_block, nleaf + 1);
  swData *band = data_for(m, 1), *dense = data_for(m, 0), *ulp = data_for(m, 0);
  const long nsteps = sw_test_sanitized() ? 200 : 400;
  const BandRun r = band_against_dense(m, 1, 0, nsteps, EARLY, band, dense, ulp);
  const double *er = r.er, *dr = r.dr, *ur = r.ur;
  double fresh, kept;
  sw_implicit_counts(m, band, &fresh, &kept);
  fprintf(stderr, "# same_solution: %s rachis, %d barbs, dt %.3g s, band kicks %g fresh, %g kept\n",
          held_name[held], nleaf, m->dt, fresh, kept);
  print_band_run(&r, EARLY, nsteps);
  for (int q = 0; q < 3; q++) assert_true(er[q] <= fmax(1e-12, 10 * r.eur[q]));
  assert_true(dr[0] <= 1e-12);
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

static void same_solution(int held) {
  static const int at[7] = {2, 5, 8, 8, 11, 14, 20};
  same_solution_at(held, 7, at, 3);
}

static void test_same_solution(void **state) {
  (void)state;
  same_solution(CLAMPED);
  same_solution(FREE);
  same_solution(HINGED);
}

/* Barbs on the rachis' last two nodes: both fixed joints turn its last
 * element (the end node's, and the element after node 19), so the dense
 * path's two ports share those three unknowns (joint_alias.c: without the
 * fold its C = E^T A^-1 E had two equal rows).  The band path adds both
 * blocks to the element's rows and is the reference. */
static void test_shared_element(void **state) {
  (void)state;
  static const int at[4] = {5, 12, 19, 20};
  swSpec *s;
  swModel *m = feather(20, 4, at, -1, CLAMPED, &s);
  int aliases = 0;
  for (int q = 0; q < m->nrigid_port; q++) aliases += m->rigid_port_alias[q] >= 0;
  fprintf(stderr, "# test_shared_element: %d ports, %d of them another's rotation\n",
          m->nrigid_port, aliases);
  assert_int_equal(aliases, 1);
  sw_model_free(m);
  sw_spec_free(s);
  same_solution_at(CLAMPED, 4, at, -1);
  same_solution_at(FREE, 4, at, -1);
}

static void test_cost(void **state) {
  (void)state;
  static const int leaves[3] = {4, 16, 64};
  size_t ws[3];
  for (int c = 0; c < 3; c++) {
    int at[64];
    for (int l = 0; l < leaves[c]; l++) at[l] = 2 + l * 128 / leaves[c];
    swSpec *s;
    swModel *m = feather(128, leaves[c], at, -1, CLAMPED, &s);
    assert_int_equal(m->rigid_group_band[0], 1);
    swData *band = data_for(m, 1);
    ws[c] = sw_rigid_joints_scratch(m);
    swData *dense = data_for(m, 0);
    const size_t ws_dense = sw_rigid_joints_scratch(m);
    double tb, td;
    kick_times(m, 1, band, dense, &tb, &td);
    fprintf(stderr, "# test_cost: %2d barbs (fixed joints, %3d port unknowns) on 128 elements: "
            "band path %8.1f us per kick (%zu doubles of workspace), dense path %8.1f us "
            "(%zu doubles), dense / band %.1f\n",
            leaves[c], 6 * leaves[c], 1e6 * tb, ws[c], 1e6 * td, ws_dense, td / tb);
    sw_data_free(band);
    sw_data_free(dense);
    sw_model_free(m);
    sw_spec_free(s);
  }
  /* the band path's workspace: each port's block and each leaf's unit */
  for (int c = 1; c < 3; c++) assert_int_equal(ws[c] * (size_t)leaves[0], ws[0] * (size_t)leaves[c]);
}

/* Implicit barbs (rod leaves, joint_groups.c): each barb, an implicit rod
 * whose one joint sits on one port of its own, is eliminated into its
 * rachis' port through its condensed stiffness (rigid_joint.c), where it
 * had been a dense member whose ports made the group's block.  The same
 * feather at 4 times the explicit barbs' stable estimate, stepped three
 * ways from the same moving start: rod leaves on the band path, rod
 * leaves eliminated into the dense block, and every rod a dense member
 * (sw_rigid_joints_setup_leaves(m, 0), the path before rod leaves), each
 * kick factored afresh.  They solve one linear system three ways and
 * agree as test_same_solution's do; and the kick's cost is printed. */
static void test_rod_leaves(void **state) {
  (void)state;
  static const int at[7] = {2, 5, 8, 8, 11, 14, 20};
  swSpec *s;
  swModel *e = feather(20, 7, at, 3, CLAMPED, &s);
  const double dt = 8 * e->dt; /* 4 times the explicit estimate */
  sw_model_free(e);
  sw_spec_free(s);
  swModel *m = feather_at(20, 7, at, 3, CLAMPED, dt, &s);
  assert_int_equal(m->nrigid_group, 1);
  assert_int_equal(m->nrigid_block, 8);
  assert_int_equal(m->rigid_group_band[0], 1); /* one rod and its leaves */
  for (int k = 1; k < 8; k++) assert_true(m->rigid_block_rod[k] >= 0 && m->rigid_block_leaf[k] >= 0);
  swModel *ref = sw_test_compile(s); /* the same scene, every rod a dense member */
  sw_rigid_joints_free(ref);
  assert_true(sw_rigid_joints_setup_leaves(ref, 0));
  assert_int_equal(ref->rigid_group_band[0], 0);
  for (int k = 0; k < 8; k++) assert_true(ref->rigid_block_leaf[k] < 0);
  swData *band = data_for(m, 1), *dense = data_for(m, 0), *ulp = data_for(m, 0);
  swData *members = sw_data_new(ref);
  assert_non_null(members);
  start_moving(ref, members);
  const long nsteps = sw_test_sanitized() ? 200 : 400;
  for (long k = 0; k < nsteps; k++) {
    sw_implicit_reset(ref, members);
    assert_int_equal(sw_step(ref, members), SW_OK);
  }
  const BandRun r = band_against_dense(m, 1, 1, nsteps, EARLY, band, dense, ulp);
  double ma[3], mr[3];
  differences(m, dense, members, ma, mr);
  fprintf(stderr, "# rod leaves: clamped rachis, 7 implicit barbs, dt %.3g s (the explicit barbs' "
          "estimate %.3g s)\n", m->dt, 2 * dt / 8);
  print_band_run(&r, EARLY, nsteps);
  fprintf(stderr, "#   after %ld steps, rod leaves (dense) - every rod a member: x %.2e m (rel. %.2e), "
          "v %.2e m/s (rel. %.2e), omega %.2e rad/s (rel. %.2e)\n",
          nsteps, ma[0], mr[0], ma[1], mr[1], ma[2], mr[2]);
  for (int q = 0; q < 3; q++) assert_true(r.er[q] <= fmax(1e-12, 10 * r.eur[q]));
  assert_true(r.dr[0] <= 1e-12 && mr[0] <= 1e-12);
  for (int q = 1; q < 3; q++) assert_true(r.dr[q] <= fmax(1e-12, 10 * r.ur[q]));
  for (int q = 1; q < 3; q++) assert_true(mr[q] <= fmax(1e-12, 10 * r.ur[q]));
  double vmax;
  (void)worst(dense->v, dense->v, 3 * (size_t)m->stride, &vmax);
  assert_true(vmax > 0.01); /* it moved */
  double tb, td;
  kick_times(m, 1, band, dense, &tb, &td);
  fprintf(stderr, "#   one kick: band path %.1f us, rod leaves in the dense block %.1f us\n", 1e6 * tb,
          1e6 * td);
  sw_data_free(band);
  sw_data_free(dense);
  sw_data_free(ulp);
  sw_data_free(members);
  sw_model_free(ref);
  sw_model_free(m);
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_same_solution),
      cmocka_unit_test(test_shared_element),
      cmocka_unit_test(test_cost),
      cmocka_unit_test(test_rod_leaves),
  };
  return cmocka_run_group_tests_name("joint_band", tests, NULL, NULL);
}
