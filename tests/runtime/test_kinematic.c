/* test_kinematic.c — kinematic joints (kinematic.c): a follower element takes
 * its frame from a leader element (Zhang et al. 2019, Suppl. Note 5.3, the
 * wing's rachis on its bone and barbs on their rachis), penalty forces are
 * exchanged, no couple is fed back.
 *
 *   1. a rachis on a bone turned at a prescribed angular velocity keeps the
 *      bone's frame (times the rotation of the layout) to round-off at every
 *      load evaluation, and turns with it;
 *   2. forces balance: a free bone and rachis keep their total linear
 *      momentum to round-off;
 *   3. the energy the imposed turn gives is booked as work: kinetic +
 *      elastic - work of the free pair stays constant up to the integrator's
 *      error, at least second order in dt, while the work booked is a
 *      hundred times that error and more (booking the follower's jumps of
 *      kinetic energy instead of the midpoint rule left a first-order error
 *      as large as the work itself);
 *   4. the reaction moved to a third node with a weight: the loads of one
 *      evaluation against k g by hand;
 *   5. the validation messages;
 *   6. a frame's correction changes the elastic energy of the follower's
 *      shear and its two bending domains: a small one (below 1e-6 rad, the
 *      drift's) is booked to first order from the couple: on the
 *      variational law, whose couple is the energy's gradient, the
 *      difference from the exact change is the dropped second-order term
 *      (it doubles with the turn); Gazzola's law printed beside it; a large
 *      one is booked exactly;
 *   7. the tie's stable step against the measured one, the leader's point
 *      counted as a mass of its own;
 *   8. a chain (bone -> rachis -> barb -> barb) declared from its end: each
 *      frame is imposed after its leader's, so every follower holds
 *      Q_f = R Q_l exactly at every load evaluation (in the order of the
 *      declarations the barbs took their leaders' frames before these were
 *      imposed, and the scene went unstable), and 1, 2 and 3 threads give
 *      the same bits.
 */
#include "testutil.h"
#include "vec.h"
#include "internal.h"

static const double X[3] = {1, 0, 0}, Y[3] = {0, 1, 0}, Z[3] = {0, 0, 1};

/* bone: 0.2 m along x, 8 elements; rachis: 0.1 m along y from the bone's
 * node 4, 6 elements, light and soft; the joint ties rachis node 0 to the
 * end of bone element 3 (node 4) and turns rachis element 0 with it */
/* A kinematic joint tying node 0 of rod `follower` to the point xi along
 * element `elem` of rod `leader` and turning the follower's element 0 with
 * that element. */
static swKinematicDesc tie(const char *name, int leader, int elem, double xi, int follower, double k) {
  swKinematicDesc kj;
  sw_kinematic_desc_init(&kj);
  kj.name = name;
  kj.leader_rod = leader;
  kj.leader_elem = elem;
  kj.leader_xi = xi;
  kj.follower_rod = follower;
  kj.follower_node = 0;
  kj.follower_elem = 0;
  kj.stiffness = k;
  return kj;
}

static swLaw scene_law = SW_LAW_VARIATIONAL; /* the energy of the balance is its forces' potential */
static int scene_rigid_bone = 0; /* test 7: the leader a rigid body */
static swSpec *scene(double k, int reaction) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, mid[3] = {0.1, 0, 0};
  swRodDesc bone = sw_test_rod("bone", 8, 0.2, 5e-3, o, X, Z);
  bone.youngs = 1e8;
  bone.density = 1000;
  bone.law = scene_law;
  bone.rigid = scene_rigid_bone;
  swRodDesc rachis = sw_test_rod("rachis", 6, 0.1, 1e-3, mid, Y, Z);
  rachis.youngs = 1e6;
  rachis.density = 300;
  rachis.law = scene_law;
  assert_int_equal(sw_spec_add_rod(s, &bone), 0);
  assert_int_equal(sw_spec_add_rod(s, &rachis), 1);
  if (reaction) {
    swRodDesc base = sw_test_rod("base", 2, 0.02, 2e-3, (const double[3]){0, 0.05, 0}, X, Z);
    assert_int_equal(sw_spec_add_rod(s, &base), 2);
  }
  swKinematicDesc kj = tie("root", 0, 3, 1.0, 1, k);
  if (reaction) {
    kj.reaction_rod = 2;
    kj.reaction_node = 1;
    kj.reaction_weight = 0.4;
  }
  assert_int_equal(sw_spec_add_kinematic(s, &kj), 0);
  return s;
}

/* the largest |Q_f - R Q_l| entry */
static double frame_gap(const swModel *m, const swData *d) {
  const swKinematicDesc *k = &m->kinematic[0];
  double Ql[9], Qf[9], RQ[9], worst = 0;
  sw_getQ(m, d->Q, k->leader_elem, Ql);
  sw_getQ(m, d->Q, k->follower_elem, Qf);
  sw_mat_mul(RQ, m->kinematic_rot, Ql);
  for (int i = 0; i < 9; i++) worst = fmax(worst, fabs(Qf[i] - RQ[i]));
  return worst;
}

/* The bone's (rod 0's) start held in place but turned about z at 20 rad/s. */
static void turn_bone(swSpec *s) {
  swBCDesc turn;
  memset(&turn, 0, sizeof turn);
  turn.kind = SW_BC_OMEGA;
  turn.rod = 0;
  turn.end = 0;
  turn.vec[2] = 20.0;
  turn.signal = sw_signal_const(1.0);
  assert_true(sw_spec_add_bc(s, &turn) >= 0);
}

/* 1. the bone's start clamped in place but turned about z at 20 rad/s */
static void test_follows_turning_bone(void **state) {
  (void)state;
  swSpec *s = scene(1e4, 0);
  turn_bone(s);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  double worst = 0;
  const long steps = 2000; /* 17 elements: cheap under the sanitizers too */
  for (long i = 0; i < steps; i++) {
    assert_int_equal(sw_steps_held(m, d, 1), SW_OK); /* the state the loads saw */
    worst = fmax(worst, frame_gap(m, d));
  }
  /* the rachis' first element has turned with the bone's element 3 */
  double Qf[9];
  sw_getQ(m, d->Q, m->kinematic[0].follower_elem, Qf);
  const double yaw = atan2(Qf[7], Qf[6]) - atan2(Y[1], Y[0]); /* its d3 in the xy plane */
  double Ql[9];
  sw_getQ(m, d->Q, m->kinematic[0].leader_elem, Ql);
  const double yaw_bone = atan2(Ql[7], Ql[6]);
  fprintf(stderr, "# %s: %ld steps of %.3g s; largest |Q_rachis - R Q_bone| at a load "
          "evaluation %.3e; the bone's element turned %.6f rad, the rachis' %.6f rad\n",
          __func__, steps, m->dt, worst, yaw_bone, yaw);
  assert_true(worst < 1e-14);
  assert_true(fabs(yaw_bone) > 0.05);
  assert_true(fabs(remainder(yaw - yaw_bone, 2 * 3.141592653589793)) < 1e-12);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void momentum(const swModel *m, const swData *d, double P[3]) {
  P[0] = P[1] = P[2] = 0;
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
      for (int c = 0; c < 3; c++) P[c] += m->mass[i] * SW_AT(m, d->v, i, c);
}

/* the free pair set spinning about z and drifting along x and z */
static void launch(const swModel *m, swData *d) {
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
      const double x = SW_AT(m, d->x, i, 0) - 0.1, y = SW_AT(m, d->x, i, 1);
      SW_AT(m, d->v, i, 0) = 0.3 - 8.0 * y;
      SW_AT(m, d->v, i, 1) = 8.0 * x;
      SW_AT(m, d->v, i, 2) = 0.1 + 2.0 * x;
    }
  for (int e = m->elem_adr[0]; e < m->elem_adr[0] + m->rod_nelem[0]; e++) {
    double Q[9], w[3], lab[3] = {0, -2.0, 8.0};
    sw_getQ(m, d->Q, e, Q);
    sw_mat_vec(w, Q, lab);
    for (int c = 0; c < 3; c++) SW_AT(m, d->omega, e, c) = w[c];
  }
}

/* 2. momentum of the free pair */
static void test_forces_balance(void **state) {
  (void)state;
  swSpec *s = scene(1e4, 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  launch(m, d);
  double P0[3], P[3], scale = 0;
  momentum(m, d, P0);
  for (int i = 0; i < m->nnode; i++) scale += m->mass[i];
  sw_test_run_to(m, d, 0.05);
  momentum(m, d, P);
  double gap = 0;
  for (int c = 0; c < 3; c++) gap = fmax(gap, fabs(P[c] - P0[c]));
  fprintf(stderr, "# %s: after %ld steps the momentum moved by %.3e N s (of %.3e kg x 0.3 m/s)\n",
          __func__, d->step, gap, scale);
  assert_true(gap < 1e-13 * scale);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* the energy balance's drift over 0.05 s, relative to the kinetic energy */
static double balance_drift(double frac, double *work) {
  swSpec *s = scene(1e4, 0);
  swModel *m = sw_test_compile_at(s, frac);
  swData *d = sw_data_new(m);
  launch(m, d);
  double e0[3], e1[3];
  sw_energy(m, d, e0);
  sw_test_run_to(m, d, 0.05);
  sw_energy(m, d, e1);
  *work = e1[2];
  const double drift = fabs((e1[0] + e1[1] - e1[2]) - (e0[0] + e0[1] - e0[2])) / e0[0];
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return drift;
}

/* 3. kinetic + elastic - work */
static void test_energy_booked(void **state) {
  (void)state;
  double w1, w2;
  const double a = balance_drift(0.4, &w1), b = balance_drift(0.2, &w2);
  fprintf(stderr, "# %s: drift of kinetic + elastic - work over 0.05 s: %.3e at 0.4 of the "
          "stable step, %.3e at 0.2 (ratio %.2f; work booked %.4e J)\n", __func__, a, b, a / b, w2);
  assert_true(b < 1e-8);
  assert_true(a / b > 3.0); /* second order at least: 4 */
  assert_true(fabs(w2) / 2.6282e-3 > 100 * b); /* the booked work is not negligible beside it */
}

/* 4. one evaluation of the loads, the reaction moved to base's node 1 at w = 0.4 */
static void test_reaction_moved(void **state) {
  (void)state;
  swSpec *s = scene(2e3, 1);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const swKinematicDesc *k = &m->kinematic[0];
  SW_AT(m, d->x, k->follower_node, 0) += 1e-3; /* gap p - x_f = (-1, 0.5, 0) mm */
  SW_AT(m, d->x, k->follower_node, 1) -= 0.5e-3;
  for (int c = 0; c < 3; c++)
    for (int i = 0; i < m->stride; i++) SW_AT(m, d->force, i, c) = SW_AT(m, d->ext_force, i, c) = 0;
  sw_kinematic_loads(m, d);
  const double want[3] = {-2.0, 1.0, 0}; /* k g, N */
  double worst = 0;
  for (int c = 0; c < 3; c++) {
    worst = fmax(worst, fabs(SW_AT(m, d->force, k->follower_node, c) - want[c]));
    worst = fmax(worst, fabs(SW_AT(m, d->force, k->reaction_node, c) + 0.4 * want[c]));
    worst = fmax(worst, fabs(SW_AT(m, d->ext_force, k->reaction_node, c) + 0.4 * want[c]));
    worst = fmax(worst, fabs(SW_AT(m, d->force, k->leader_elem + 1, c)));
  }
  fprintf(stderr, "# %s: follower %.6g %.6g N, reaction on base %.6g %.6g N; largest error "
          "%.3e N\n", __func__, SW_AT(m, d->force, k->follower_node, 0),
          SW_AT(m, d->force, k->follower_node, 1), SW_AT(m, d->force, k->reaction_node, 0),
          SW_AT(m, d->force, k->reaction_node, 1), worst);
  assert_true(worst < 1e-12);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void expect_error(void (*edit)(swSpec *s, swKinematicDesc *k), const char *message) {
  swSpec *s = scene(1e4, 0);
  swKinematicDesc k;
  sw_kinematic_desc_init(&k);
  k.name = "bad";
  k.leader_rod = 0;
  k.leader_elem = 0;
  k.follower_rod = 1;
  k.follower_node = -1;
  k.follower_elem = -1;
  k.stiffness = 1e3;
  edit(s, &k);
  assert_true(sw_spec_add_kinematic(s, &k) >= 0);
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  fprintf(stderr, "# %s\n", err);
  assert_null(m);
  assert_string_equal(err, message);
  sw_spec_free(s);
}
static void same_rod(swSpec *s, swKinematicDesc *k) { (void)s; k->leader_rod = 1; }
static void bad_xi(swSpec *s, swKinematicDesc *k) { (void)s; k->leader_xi = 1.5; }
static void no_stiffness(swSpec *s, swKinematicDesc *k) { (void)s; k->stiffness = 0; }
static void twice(swSpec *s, swKinematicDesc *k) { (void)s; k->follower_elem = 0; }
static void off_rod(swSpec *s, swKinematicDesc *k) { (void)s; k->leader_elem = 8; }
/* the bone's element 3 turned by the rachis' element 0, which the root joint turns by it */
static void cycle(swSpec *s, swKinematicDesc *k) {
  (void)s;
  k->leader_rod = 1, k->leader_elem = 0, k->follower_rod = 0, k->follower_elem = 3, k->follower_node = 4;
}

/* 5. */
static void test_validation(void **state) {
  (void)state;
  expect_error(same_rod, "kinematic joint 'bad': a rod cannot lead itself");
  expect_error(bad_xi, "kinematic joint 'bad': the point on the leader's element must be at 0..1 "
               "along it, got 1.5");
  expect_error(no_stiffness, "kinematic joint 'bad': stiffness must be > 0 and damping >= 0");
  expect_error(twice, "kinematic joints 'root' and 'bad' both turn element 0 of 'rachis'");
  expect_error(off_rod, "kinematic joint 'bad': an element or node is off its rod");
  expect_error(cycle, "kinematic joint 'root' leads itself through a chain of kinematic joints (a "
               "follower's frame must come from outside the chain)");
}

/* The work booked by one imposition that undoes a turn `delta` of the
 * follower's frame (the elastic part alone: every w is 0), and the elastic
 * energy it changed, exactly. */
static void correction(swLaw law, double scale, double *booked, double *exact) {
  scene_law = law;
  swSpec *s = scene(1e4, 0);
  scene_law = SW_LAW_VARIATIONAL;
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  /* bent, twisted and sheared near the joint: elements 1 and 2 of the
   * rachis turned, node 1 moved */
  const int e0 = m->elem_adr[1];
  for (int e = e0 + 1; e <= e0 + 2; e++) {
    double Q[9], phi[3] = {0.04 * (e - e0), -0.03, 0.02};
    sw_getQ(m, d->Q, e, Q);
    sw_rotate_frame(Q, phi);
    sw_setQ(m, d->Q, e, Q);
  }
  SW_AT(m, d->x, m->node_adr[1] + 1, 2) += 2e-4;
  sw_kinematic_impose(m, d); /* the follower on its leader's frame */
  double e[3];
  sw_energy(m, d, e);
  const double before = e[1];
  double Q[9], delta[3] = {3e-7 * scale, -2e-7 * scale, 1e-7 * scale};
  const int fe = m->kinematic[0].follower_elem;
  sw_getQ(m, d->Q, fe, Q);
  sw_rotate_frame(Q, delta);
  sw_setQ(m, d->Q, fe, Q);
  sw_energy(m, d, e);
  *exact = before - e[1];
  const double w0 = d->work;
  sw_kinematic_impose(m, d);
  sw_internal_loads(m, d);
  sw_kinematic_book(m, d);
  *booked = d->work - w0;
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* 6. */
static void test_correction_booked(void **state) {
  (void)state;
  double b1, x1, b2, x2, bg, xg, bl, xl;
  correction(SW_LAW_VARIATIONAL, 1, &b1, &x1);
  correction(SW_LAW_VARIATIONAL, 2, &b2, &x2);
  correction(SW_LAW_GAZZOLA, 1, &bg, &xg);
  correction(SW_LAW_VARIATIONAL, 3e3, &bl, &xl);
  const double r1 = fabs(b1 - x1) / fabs(x1), r2 = fabs(b2 - x2) / fabs(x2);
  fprintf(stderr, "# %s: a turn of 3.7e-7 rad undone: booked %.6e J, energy changed %.6e J "
          "(relative difference %.2e; %.2e at twice the turn); Gazzola's law: %.6e against %.6e "
          "(%.2e); a turn of 1.1e-3 rad, booked exactly: %.6e against %.6e (%.2e)\n", __func__,
          b1, x1, r1, r2, bg, xg, fabs(bg - xg) / fabs(xg), bl, xl, fabs(bl - xl) / fabs(xl));
  assert_true(fabs(x1) > 1e-14); /* the turn changes the energy */
  /* what is left is the second-order term the booking drops: it doubles
   * with the turn, relative to the energy changed */
  assert_true(r1 < 1e-4);
  assert_true(r2 / r1 > 1.8 && r2 / r1 < 2.2);
  assert_true(fabs(bl - xl) < 1e-9 * fabs(xl));
}

/* 7. the tie's stable step: the scene with a tie so stiff (k = 1e7 N/m)
 * that it bounds the step, the bone 250 times heavier than the rachis'
 * first node.  Every node and element set moving at random; stable when the
 * energy stays within 1e3 of its start over 3000 steps.  The estimate counts
 * the leader's point as a mass of its own (s = 1 + m_f / m_p, about 1
 * here: stability.c, sw_stable_dt_kinematic); the true limit, found by
 * bisection, is above it (safe) and within 1.5 of it (tight); the bound of
 * two equal masses (s = 2) is 0.71 of it. */
static int tie_stable(double frac) {
  swSpec *s = scene(1e7, 0);
  swModel *m = sw_test_compile_at(s, frac);
  sw_spec_free(s);
  swData *d = sw_data_new(m);
  unsigned seed = 777;
  for (int i = 0; i < m->nslot_elastic; i++)
    for (int c = 0; c < 3; c++) {
      seed = seed * 1103515245u + 12345u;
      SW_AT(m, d->v, i, c) = 1e-6 * ((double)(seed >> 8) / (1u << 24) - 0.5);
      seed = seed * 1103515245u + 12345u;
      SW_AT(m, d->omega, i, c) = 1e-4 * ((double)(seed >> 8) / (1u << 24) - 0.5);
    }
  return sw_test_stays_bounded(m, d, sw_test_sanitized() ? 1000 : 3000); /* frees d and m */
}

static void test_tie_stable_dt(void **state) {
  (void)state;
  swSpec *s = scene(1e7, 0);
  swModel *m = sw_test_compile(s);
  sw_spec_free(s);
  const double est = sw_stable_dt(m), tie = m->kinematic_dt[0];
  const int f = m->kinematic[0].follower_node, a = m->kinematic[0].leader_elem;
  const double m_f = m->mass[f], m_p = m->mass[a + 1]; /* xi = 1: the leader's second node */
  const double w_pair = sqrt(1e7 * (1 / m_f + 1 / m_p));
  fprintf(stderr, "# %s: tie's estimate %.4g s (the scene's %.4g s); follower node %.3g kg, leader's point "
          "%.3g kg; 0.95 x 2 / w of the pair %.4g s\n", __func__, tie, est, m_f, m_p, 0.95 * 2 / w_pair);
  assert_true(tie == est); /* the tie bounds the scene */
  /* the node's row: the pair's spring plus its rod's elements, so at most the pair's bound */
  assert_true(tie <= 0.95 * 2 / w_pair * (1 + 1e-12));
  assert_true(tie >= 0.9 * 0.95 * 2 / w_pair);
  sw_model_free(m);
  double lo = 1.0, hi = 3.0;
  assert_true(tie_stable(lo));
  assert_false(tie_stable(hi));
  for (int it = 0; it < 10; it++) {
    const double mid = 0.5 * (lo + hi);
    if (tie_stable(mid)) lo = mid; else hi = mid;
  }
  fprintf(stderr, "# %s: measured limit %.4f x the estimate (%.4f x the bound of two equal masses, s = 2)\n", __func__,
          lo, lo * sqrt(2.0 / (1 + m_f / m_p)));
  assert_true(lo >= 1.0 && lo <= 1.5);
  /* a rigid bone: its point can move more than its node's mass says, and
   * the row keeps s = 2 (the rachis' own EA / l is 2e-5 of the tie's k) */
  scene_rigid_bone = 1;
  s = scene(1e7, 0);
  m = sw_test_compile(s);
  sw_spec_free(s);
  const double rigid = m->kinematic_dt[0], ratio = rigid / (tie * sqrt((1 + m_f / m_p) / 2));
  fprintf(stderr, "# %s: on a rigid bone %.4g s, %.6f of the bound with s = 2\n", __func__, rigid, ratio);
  assert_true(fabs(ratio - 1) < 1e-3);
  sw_model_free(m);
  scene_rigid_bone = 0;
}

/* The largest |Q_f - R Q_l| entry of joint j. */
static double joint_gap(const swModel *m, const swData *d, int j) {
  const swKinematicDesc *k = &m->kinematic[j];
  double Ql[9], Qf[9], RQ[9], worst = 0;
  sw_getQ(m, d->Q, k->leader_elem, Ql);
  sw_getQ(m, d->Q, k->follower_elem, Qf);
  sw_mat_mul(RQ, m->kinematic_rot + 9 * j, Ql);
  for (int i = 0; i < 9; i++) worst = fmax(worst, fabs(Qf[i] - RQ[i]));
  return worst;
}

/* scene()'s bone and rachis, a barb on the rachis' first element and a
 * second barb on the first barb's, the joints declared from the chain's
 * end (second barb, first barb, then the rachis' root, joint 2), the bone
 * turned about z at 20 rad/s at its start; then CHAIN_FAN barbs more on
 * the rachis' first element (the first barb's level), every other one
 * passing its reaction to the bone's node 2, so that the scene spans
 * several chunks and a level's joints and their nodes several threads */
#define CHAIN_FAN 40
static swSpec *chain_scene(void) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, mid[3] = {0.1, 0, 0}, b1[3] = {0.1, 0.005, 0}, b2[3] = {0.1, 0.005, 0.004};
  swRodDesc bone = sw_test_rod("bone", 8, 0.2, 5e-3, o, X, Z);
  bone.youngs = 1e8;
  bone.density = 1000;
  swRodDesc rachis = sw_test_rod("rachis", 6, 0.1, 1e-3, mid, Y, Z);
  rachis.youngs = 1e6;
  rachis.density = 300;
  swRodDesc barb1 = sw_test_rod("barb1", 4, 0.02, 5e-4, b1, Z, X), barb2 = sw_test_rod("barb2", 4, 0.01, 5e-4, b2, X, Z);
  barb1.youngs = barb2.youngs = 1e6;
  barb1.density = barb2.density = 300;
  assert_int_equal(sw_spec_add_rod(s, &bone), 0);
  assert_int_equal(sw_spec_add_rod(s, &rachis), 1);
  assert_int_equal(sw_spec_add_rod(s, &barb1), 2);
  assert_int_equal(sw_spec_add_rod(s, &barb2), 3);
  const struct { const char *name; int leader, elem, follower; double xi, k; } ties[] = {
      {"barb2", 2, 0, 3, 0.8, 1e3}, {"barb1", 1, 0, 2, 0.5, 1e3}, {"root", 0, 3, 1, 1.0, 1e4}};
  for (int t = 0; t < 3; t++) {
    const swKinematicDesc kj = tie(ties[t].name, ties[t].leader, ties[t].elem, ties[t].xi, ties[t].follower, ties[t].k);
    assert_int_equal(sw_spec_add_kinematic(s, &kj), t);
  }
  for (int i = 0; i < CHAIN_FAN; i++) {
    const double at = (i + 0.5) / CHAIN_FAN, start[3] = {0.1, at * 0.1 / 6, 0};
    char name[16];
    snprintf(name, sizeof name, "fan%d", i);
    swRodDesc fan = sw_test_rod(name, 4, 0.01, 5e-4, start, i % 2 ? X : Z, i % 2 ? Z : X);
    fan.youngs = 1e6;
    fan.density = 300;
    const int rod = sw_spec_add_rod(s, &fan);
    assert_int_equal(rod, 4 + i);
    swKinematicDesc kj = tie(name, 1, 0, at, rod, 1e3);
    if (i % 2) kj.reaction_rod = 0, kj.reaction_node = 2, kj.reaction_weight = 0.5;
    assert_int_equal(sw_spec_add_kinematic(s, &kj), 3 + i);
  }
  turn_bone(s);
  return s;
}

/* 8. the chain's frames, and the same bits on any team */
static void test_chain_levels(void **state) {
  (void)state;
  swSpec *s = chain_scene();
  swModel *m = sw_test_compile_at(s, 0.5);
  sw_spec_free(s);
  const int nchunk = (m->nslot_elastic + m->chunk - 1) / m->chunk;
  fprintf(stderr, "# %s: %d joints in %d levels (%d, %d, %d); %d chunks of slots\n", __func__, m->nkinematic,
          m->nkinematic_level, m->kinematic_level[1] - m->kinematic_level[0],
          m->kinematic_level[2] - m->kinematic_level[1], m->kinematic_level[3] - m->kinematic_level[2], nchunk);
  assert_int_equal(m->nkinematic_level, 3);
  assert_int_equal(m->kinematic_level[2] - m->kinematic_level[1], 1 + CHAIN_FAN);
  assert_true(nchunk >= 3);
  const long steps = sw_test_sanitized() ? 400 : 1500;
  swData *ref = NULL;
  for (int threads = 1; threads <= 3; threads++) {
    swData *d = sw_data_new(m);
    assert_int_equal(sw_set_threads(d, threads), threads);
    double worst = 0;
    for (long i = 0; i < steps; i++) {
      assert_int_equal(sw_steps_held(m, d, 1), SW_OK); /* the state the loads saw */
      for (int j = 0; j < m->nkinematic; j++) worst = fmax(worst, joint_gap(m, d, j));
    }
    assert_int_equal(sw_settle(m, d), SW_OK);
    if (!ref) {
      double Qf[9], yaw;
      sw_getQ(m, d->Q, m->kinematic[0].follower_elem, Qf);
      yaw = atan2(Qf[1], Qf[0]); /* the second barb's d1 in the xy plane: it has turned with the bone */
      fprintf(stderr, "# %s: %ld steps; largest |Q_f - R Q_l| of the joints at a load evaluation "
              "%.3e; the second barb turned to %.4f rad\n", __func__, steps, worst, yaw);
      assert_true(worst < 1e-14);
      assert_true(fabs(yaw) > 0.01); /* it moved: 0.45 rad at 1500 steps, 0.027 at 400 */
      ref = d;
      continue;
    }
    size_t differ = 0, n = 0;
    const double *a[] = {ref->x, ref->v, ref->Q, ref->omega}, *b[] = {d->x, d->v, d->Q, d->omega};
    const int planes[] = {3, 3, 9, 3};
    for (int p = 0; p < 4; p++)
      for (size_t i = 0; i < (size_t)planes[p] * (size_t)m->stride; i++, n++) differ += memcmp(&a[p][i], &b[p][i], sizeof(double)) != 0;
    fprintf(stderr, "# %s: %d threads: %zu of %zu state doubles differ from 1 thread; work %.17g vs %.17g\n",
            __func__, threads, differ, n, d->work, ref->work);
    assert_int_equal(differ, 0);
    assert_true(memcmp(&d->work, &ref->work, sizeof(double)) == 0);
    sw_data_free(d);
  }
  sw_data_free(ref);
  sw_model_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_follows_turning_bone),
    cmocka_unit_test(test_forces_balance),
    cmocka_unit_test(test_energy_booked),
    cmocka_unit_test(test_reaction_moved),
    cmocka_unit_test(test_validation),
    cmocka_unit_test(test_correction_booked),
    cmocka_unit_test(test_tie_stable_dt),
    cmocka_unit_test(test_chain_levels),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
