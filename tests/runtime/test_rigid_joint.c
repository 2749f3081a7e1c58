/* test_rigid_joint.c — the system of the joints on rigid bodies under imex
 * (rigid_joint.c) solved group by group: the groups found on a scene of
 * independent groups (a hinged chain of three bones with a limit, a star of
 * three on spherical joints, a bone welded to space by a fixed joint, and a
 * bone hinged to the free end of an elastic rod, whose node is the group's
 * other member) and their envelopes;
 * and the kick and a whole run solved by blocks, within their envelopes,
 * against the same solved as one dense system over all the bodies (the
 * solve before the groups): the same numbers, bit for bit, and what a kick
 * costs each way.
 *
 * Design.  The scene is built through the public API; the one dense system
 * is the model with its groups merged into one, the bodies in the blocks'
 * order (group after group) and the envelope the whole matrix, which is
 * the code path of the one system exactly (rigid_joint.c, the header). */
#include "testutil.h"
#include "internal.h"

/* A unique name from a stem (the spec keeps copies). */
static const char *named(const char *stem) {
  static char name[32];
  static int count;
  snprintf(name, sizeof name, "%s%d", stem, count++);
  return name;
}

/* A small bone from (x, y, z) along dir: 0.1 m, r = 5 mm, 4 elements,
 * E = 15 GPa, 1750 kg/m^3. */
static swRodDesc small_bone(const char *stem, double x, double y, double z, const double dir[3],
                            int rigid) {
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = named(stem);
  r.nelem = 4;
  r.length = 0.1;
  r.radius_start = r.radius_end = 0.005;
  r.youngs = 15e9;
  r.density = 1750;
  r.rigid = rigid;
  r.start[0] = x, r.start[1] = y, r.start[2] = z;
  for (int k = 0; k < 3; k++) r.direction[k] = dir[k];
  r.normal[0] = 0, r.normal[1] = 1, r.normal[2] = 0; /* normal to every dir here */
  return r;
}

static swJointDesc joint_of(swJointKind kind, int rod_a, int node_a, int rod_b, int node_b) {
  swJointDesc j;
  sw_joint_desc_init(&j);
  j.name = named("j");
  j.kind = kind;
  j.rod_a = rod_a, j.node_a = node_a;
  j.rod_b = rod_b, j.node_b = node_b;
  j.axis[0] = 0, j.axis[1] = 1, j.axis[2] = 0;
  j.stiffness = 5e9; /* the reference's tendon joints (Z19 Suppl. Table 9) */
  return j;
}

/* `copies` copies, 0.5 m apart in y, of: chain A (a1-a2-a3 on hinges about
 * y, a1 hinged to space, a limit of +-0.01 rad on a2-a3 that gravity
 * drives it past), a star B (b1 and b2 hung from space at either end and
 * meeting where b3 hangs from both, on spherical joints), C (welded to
 * space by a fixed joint) and D (rigid, hinged to the free end of the
 * elastic rod E, which hangs from space): the groups {a1, a2, a3},
 * {b1, b2, b3}, {c} and {E's end node, d} per copy.  The joints of A and B
 * interleave, so the one system numbered their bodies a1, b1, a2, b2, b3,
 * c, a3; b2 is joined to none before it, b3 to b1, so B's envelope is not
 * monotone.  E's joint to space stays explicit (no body on it). */
static swModel *groups_scene(int copies, swSpec **spec) {
  static const double along[3] = {1, 0, 0}, back[3] = {-1, 0, 0}, down[3] = {0, 0, -1};
  swSpec *s = sw_spec_new();
  for (int c = 0; c < copies; c++) {
    const double y = 0.5 * c;
    swRodDesc r;
    int a[3], b[3];
    for (int i = 0; i < 3; i++) {
      r = small_bone("a", 0.1 * i, y, 0, along, 1);
      a[i] = sw_spec_add_rod(s, &r);
    }
    r = small_bone("b", 0, y + 0.1, 0, along, 1);
    b[0] = sw_spec_add_rod(s, &r);
    r = small_bone("b", 0.2, y + 0.1, 0, back, 1);
    b[1] = sw_spec_add_rod(s, &r);
    r = small_bone("b", 0.1, y + 0.1, 0, down, 1);
    b[2] = sw_spec_add_rod(s, &r);
    r = small_bone("c", 0, y + 0.2, 0, along, 1);
    const int cr = sw_spec_add_rod(s, &r);
    r = small_bone("d", 0.1, y + 0.3, 0, along, 1);
    const int dr = sw_spec_add_rod(s, &r);
    r = small_bone("e", 0, y + 0.3, 0, along, 0);
    r.youngs = 1e7; /* soft: its own step is not nanoseconds */
    const int er = sw_spec_add_rod(s, &r);
    swJointDesc j = joint_of(SW_JOINT_HINGE, a[0], 0, -1, 0);
    j.anchor[1] = y;
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_SPHERICAL, b[0], 0, -1, 0);
    j.anchor[1] = y + 0.1;
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_HINGE, a[0], -1, a[1], 0);
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_SPHERICAL, b[1], 0, -1, 0);
    j.anchor[0] = 0.2, j.anchor[1] = y + 0.1;
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_SPHERICAL, b[0], -1, b[2], 0);
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_FIXED, cr, 0, -1, 0);
    j.anchor[1] = y + 0.2;
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_SPHERICAL, b[1], -1, b[2], 0);
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_HINGE, a[1], -1, a[2], 0);
    j.has_range = 1, j.angle_min = -0.01, j.angle_max = 0.01;
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_SPHERICAL, er, 0, -1, 0);
    j.stiffness = 0; /* an elastic rod's joints: explicit, the default spring */
    j.anchor[1] = y + 0.3;
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_HINGE, er, -1, dr, 0);
    j.stiffness = 0;
    sw_spec_add_joint(s, &j);
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, SW_IMEX);
  swModel *m = sw_test_compile_at(s, 0.5);
  *spec = s;
  return m;
}

/* The model's groups and their workspace, swapped in and out whole. */
typedef struct {
  int *block, *block_body, *block_node, *block_elem, *block_rot, *block_off, *block_dof,
      *joint_block, *env, *reach, *adr, *joint_adr, *joint, *lanes;
  int ngroup;
  double *sys; /* a swData's workspace for them */
} Grouping;

static void swap_grouping(swModel *m, swData *d, Grouping *g) {
  Grouping now = {m->rigid_block, m->rigid_block_body, m->rigid_block_node, m->rigid_block_elem,
                  m->rigid_block_rot, m->rigid_block_off, m->rigid_block_dof, m->joint_block,
                  m->rigid_block_env, m->rigid_block_reach,
                  m->rigid_group_adr, m->rigid_group_joint_adr, m->rigid_group_joint,
                  m->rigid_group_lanes, m->nrigid_group, d->rigid_sys};
  m->rigid_block = g->block, m->rigid_block_body = g->block_body, m->rigid_block_env = g->env;
  m->rigid_block_node = g->block_node, m->rigid_block_elem = g->block_elem;
  m->rigid_block_rot = g->block_rot, m->joint_block = g->joint_block;
  m->rigid_block_off = g->block_off, m->rigid_block_dof = g->block_dof;
  m->rigid_block_reach = g->reach;
  m->rigid_group_adr = g->adr;
  m->rigid_group_joint_adr = g->joint_adr, m->rigid_group_joint = g->joint;
  m->rigid_group_lanes = g->lanes;
  m->nrigid_group = g->ngroup, d->rigid_sys = g->sys;
  *g = now;
}

/* The members as one group, in the blocks' order (each group's members as
 * joint_order.c ordered them, group after group), and its envelope the
 * whole matrix: the dense factorisation of the one system. */
static Grouping one_group(const swModel *m) {
  Grouping w;
  const int nb = m->nrigid_block;
  w.block = malloc((size_t)m->nrigid * sizeof(int));
  w.block_body = malloc((size_t)nb * sizeof(int));
  w.block_node = malloc((size_t)nb * sizeof(int));
  w.block_elem = malloc((size_t)nb * sizeof(int));
  w.block_rot = malloc((size_t)nb * sizeof(int));
  w.block_off = malloc((size_t)nb * sizeof(int));
  w.block_dof = malloc((size_t)nb * sizeof(int));
  w.joint_block = malloc(2 * (size_t)m->njoint * sizeof(int));
  w.env = calloc((size_t)nb, sizeof(int));
  w.reach = malloc((size_t)nb * sizeof(int));
  w.adr = malloc(2 * sizeof(int));
  w.joint_adr = malloc(2 * sizeof(int));
  w.joint = malloc((size_t)m->njoint * sizeof(int));
  w.lanes = malloc(sizeof(int));
  w.sys = malloc(((size_t)36 * nb * nb + 12 * (size_t)nb) * sizeof(double));
  assert_true(w.block && w.block_body && w.block_node && w.block_elem && w.block_rot &&
              w.block_off && w.block_dof &&
              w.joint_block && w.env && w.reach && w.adr && w.joint_adr && w.joint && w.lanes && w.sys);
  memcpy(w.block, m->rigid_block, (size_t)m->nrigid * sizeof(int));
  memcpy(w.block_body, m->rigid_block_body, (size_t)nb * sizeof(int));
  memcpy(w.block_node, m->rigid_block_node, (size_t)nb * sizeof(int));
  memcpy(w.block_elem, m->rigid_block_elem, (size_t)nb * sizeof(int));
  memcpy(w.block_rot, m->rigid_block_rot, (size_t)nb * sizeof(int));
  memcpy(w.block_dof, m->rigid_block_dof, (size_t)nb * sizeof(int));
  memcpy(w.joint_block, m->joint_block, 2 * (size_t)m->njoint * sizeof(int));
  int nj = 0;
  for (int j = 0; j < m->njoint; j++)
    if (m->joint_implicit[j]) w.joint[nj++] = j;
  for (int k = 0, off = 0; k < nb; k++) w.block_off[k] = off, off += w.block_dof[k];
  for (int s = 0; s < nb; s++) w.reach[s] = nb - 1;
  w.adr[0] = 0, w.adr[1] = nb;
  w.joint_adr[0] = 0, w.joint_adr[1] = nj;
  w.ngroup = 1;
  w.lanes[0] = 1;
  return w;
}

static void free_grouping(Grouping *g) {
  free(g->block), free(g->block_body), free(g->block_node), free(g->block_elem), free(g->block_rot);
  free(g->block_off), free(g->block_dof);
  free(g->joint_block), free(g->env), free(g->reach), free(g->adr), free(g->joint_adr), free(g->joint);
  free(g->lanes);
  free(g->sys);
}

/* Rows differing bit for bit, and the largest difference, of n doubles. */
static long differ(const double *a, const double *b, size_t n, double *worst) {
  long rows = 0;
  for (size_t i = 0; i < n; i++) {
    rows += memcmp(a + i, b + i, sizeof *a) != 0;
    *worst = fmax(*worst, fabs(a[i] - b[i]));
  }
  return rows;
}

/* The groups of one copy, in order of their first member, D's with E's
 * end node. */
static void test_groups(void **state) {
  (void)state;
  swSpec *s;
  swModel *m = groups_scene(1, &s);
  /* rods: a1 a2 a3 b1 b2 b3 c d e; all but e rigid, bodies in rod order */
  int body[8];
  for (int r = 0; r < 8; r++) body[r] = m->rod_rigid[r];
  fprintf(stderr, "# %s: %d members in the system, %d groups, first blocks %d %d %d %d\n",
          __func__, m->nrigid_block, m->nrigid_group, m->rigid_group_adr[0],
          m->rigid_group_adr[1], m->rigid_group_adr[2], m->rigid_group_adr[3]);
  assert_int_equal(m->nrigid_block, 9);
  assert_int_equal(m->nrigid_attach, 1);
  assert_int_equal(m->nrigid_group, 4);
  const int adr[5] = {0, 3, 6, 7, 9};
  for (int g = 0; g <= 4; g++) assert_int_equal(m->rigid_group_adr[g], adr[g]);
  /* within a group, the order the joints first meet them (a1, b1, a2, b2,
   * b3, c, a3, E's end node, d), but for the star B, which joint_order.c
   * takes as b1, b3, b2: its envelope Cholesky then costs 537 multiply-adds
   * instead of 753 (b3's rows reach back to b1 either way, but b2's only
   * to b3) */
  const int block[8] = {0, 1, 2, 3, 5, 4, 6, 8};
  for (int r = 0; r < 8; r++) {
    assert_int_equal(m->rigid_block[body[r]], block[r]);
    assert_int_equal(m->rigid_block_body[block[r]], body[r]);
    assert_int_equal(m->rigid_block_node[block[r]], -1);
  }
  /* the attachment: rod E's last node and element, its rotation coupled by
   * the hinge */
  const int er = 8, ne = m->rod_nelem[er];
  assert_int_equal(m->rigid_block_body[7], -1);
  assert_int_equal(m->rigid_block_node[7], m->node_adr[er] + ne);
  assert_int_equal(m->rigid_block_elem[7], m->elem_adr[er] + ne - 1);
  assert_int_equal(m->rigid_block_rot[7], 1);
  /* the envelope: a2 joined to a1, a3 to a2, b3 to b1, b2 to b3, d to E's
   * node; and the last block reaching each */
  const int env[9] = {0, 0, 1, 3, 3, 4, 6, 7, 7}, reach[9] = {1, 2, 2, 4, 5, 5, 6, 8, 8};
  for (int k = 0; k < 9; k++) {
    assert_int_equal(m->rigid_block_env[k], env[k]);
    assert_int_equal(m->rigid_block_reach[k], reach[k]);
  }
  /* joints: base A, base B1, A12, base B2, B13, C, B23, A23 implicit (0-7),
   * E to space explicit (8), D on E implicit (9) */
  const int joints[9] = {0, 2, 7, 1, 3, 4, 6, 5, 9}, jadr[5] = {0, 3, 7, 8, 9};
  for (int g = 0; g <= 4; g++) assert_int_equal(m->rigid_group_joint_adr[g], jadr[g]);
  for (int q = 0; q < 9; q++) assert_int_equal(m->rigid_group_joint[q], joints[q]);
  assert_int_equal(m->joint_implicit[8], 0);
  assert_int_equal(m->joint_implicit[9], 1);
  assert_int_equal(m->joint_block[2 * 9], 7);
  assert_int_equal(m->joint_block[2 * 9 + 1], 8);
  assert_int_equal(sw_rigid_joints_scratch(m), 2 * (18 * 18 + 36) + 6 * 6 + 12 + 12 * 12 + 24);
  sw_model_free(m);
  sw_spec_free(s);
}

/* One kick solved by blocks and as one dense system, from the same state
 * and loads, and a whole run each way: the same bits.  Four copies (36
 * members, 216 unknowns, 16 groups: a chain of 3 bodies, a star of 3, a
 * welded bone, a bone with a rod's end node) also give the cost of a kick
 * each way. */
static void test_blocks_as_whole(void **state) {
  (void)state;
  const int copies = 4;
  const long nsteps = sw_test_sanitized() ? 200 : 1000;
  swSpec *s;
  swModel *m = groups_scene(copies, &s);
  assert_int_equal(m->nrigid_group, 4 * copies);
  swData *blocks = sw_data_new(m), *whole = sw_data_new(m);
  assert_non_null(blocks);
  assert_non_null(whole);
  for (int r = 0; r < m->nrod; r++) { /* a start that turns every joint */
    if (m->rod_rigid[r] < 0) continue;
    const double V[3] = {0.01 * r, -0.02, 0.03}, W[3] = {0.5, -3.0 * r, 0.2};
    if (!m->rigid_fixed[m->rod_rigid[r]]) {
      assert_int_equal(sw_rigid_set_motion(m, blocks, r, V, W), SW_OK);
      assert_int_equal(sw_rigid_set_motion(m, whole, r, V, W), SW_OK);
    }
  }
  Grouping w = one_group(m);
  double limit = 0; /* the largest torque of a limit over the run */
  for (long k = 0; k < nsteps; k++) {
    assert_int_equal(sw_step(m, blocks), SW_OK);
    swap_grouping(m, whole, &w);
    assert_int_equal(sw_step(m, whole), SW_OK);
    swap_grouping(m, whole, &w);
    for (int i = 0; i < 3 * m->njoint; i++) limit = fmax(limit, fabs(blocks->joint_limit_torque[i]));
  }
  double worst = 0;
  long rows = differ(blocks->x, whole->x, 3 * (size_t)m->stride, &worst);
  rows += differ(blocks->v, whole->v, 3 * (size_t)m->stride, &worst);
  rows += differ(blocks->omega, whole->omega, 3 * (size_t)m->stride, &worst);
  rows += differ(blocks->Q, whole->Q, 9 * (size_t)m->stride, &worst);
  rows += differ(blocks->rigid_L, whole->rigid_L, 3 * (size_t)m->nrigid, &worst);
  rows += differ(blocks->joint_limit_torque, whole->joint_limit_torque, 3 * (size_t)m->njoint,
                 &worst);
  fprintf(stderr, "# %s: %ld steps (t = %.3g s) by blocks and as one system: %ld numbers of x, "
          "v, omega, Q, L and the limits' torques differ, largest difference %.3g "
          "(the limits' largest torque %.3g N m)\n", __func__, blocks->step, blocks->time, rows, worst,
          limit);
  assert_int_equal(rows, 0);
  assert_true(limit > 0); /* the limit was in the system */

  /* one kick, from the same state and loads (the attachments' in the
   * nodes' forces and elements' torques, restored before each); and its
   * cost each way */
  const int nb = m->nrigid;
  const size_t S3 = 3 * (size_t)m->stride, bytes = S3 * sizeof(double);
  double *load = malloc(6 * (size_t)nb * sizeof(double)), *lb = malloc(6 * (size_t)nb * sizeof(double)),
         *lw = malloc(6 * (size_t)nb * sizeof(double)), *ft = malloc(4 * bytes);
  assert_true(load && lb && lw && ft);
  for (int i = 0; i < 6 * nb; i++) load[i] = 1e-3 * sin(1.0 + i); /* N and N m */
  for (size_t i = 0; i < S3; i++) blocks->force[i] = 1e-3 * cos(1.0 + (double)i);
  for (size_t i = 0; i < S3; i++) blocks->torque[i] = 1e-5 * cos(2.0 + (double)i);
  memcpy(ft, blocks->force, bytes), memcpy(ft + S3, blocks->torque, bytes);
  const double h = m->dt;
  memcpy(lb, load, 6 * (size_t)nb * sizeof(double));
  memcpy(lw, load, 6 * (size_t)nb * sizeof(double));
  assert_int_equal(sw_rigid_joints_kick(m, blocks, h, lb), 1);
  memcpy(ft + 2 * S3, blocks->force, bytes), memcpy(ft + 3 * S3, blocks->torque, bytes);
  memcpy(blocks->force, ft, bytes), memcpy(blocks->torque, ft + S3, bytes);
  swap_grouping(m, blocks, &w);
  assert_int_equal(sw_rigid_joints_kick(m, blocks, h, lw), 1);
  swap_grouping(m, blocks, &w);
  worst = 0;
  rows = differ(lb, lw, 6 * (size_t)nb, &worst);
  rows += differ(ft + 2 * S3, blocks->force, S3, &worst);
  rows += differ(ft + 3 * S3, blocks->torque, S3, &worst);
  /* the attachments' loads were replaced */
  long changed = 0;
  for (int k = 0; k < m->nrigid_block; k++)
    if (m->rigid_block_node[k] >= 0)
      changed += memcmp(ft + 2 * S3 + m->rigid_block_node[k], ft + m->rigid_block_node[k], sizeof(double)) != 0;
  assert_int_equal(changed, m->nrigid_attach);
  double t_blocks = 1e30, t_whole = 1e30;
  for (int round = 0; round < 3; round++) { /* interleaved, the best of three of 20 ms each */
    long reps = 0;
    double t0 = sw_wall_seconds(), t;
    do {
      memcpy(lb, load, 6 * (size_t)nb * sizeof(double));
      sw_rigid_joints_kick(m, blocks, h, lb);
      reps++;
    } while ((t = sw_wall_seconds() - t0) < 0.02);
    t_blocks = fmin(t_blocks, t / (double)reps);
    swap_grouping(m, blocks, &w);
    reps = 0;
    t0 = sw_wall_seconds();
    do {
      memcpy(lw, load, 6 * (size_t)nb * sizeof(double));
      sw_rigid_joints_kick(m, blocks, h, lw);
      reps++;
    } while ((t = sw_wall_seconds() - t0) < 0.02);
    t_whole = fmin(t_whole, t / (double)reps);
    swap_grouping(m, blocks, &w);
  }
  int unknowns = 0;
  for (int g = 0; g < m->nrigid_group; g++) unknowns += sw_rigid_group_unknowns(m, g);
  fprintf(stderr, "# %s: one kick of %d members (%d unknowns) in %d groups: %ld of %d loads "
          "differ from the one system's, largest difference %.3g; %.3g us by blocks, %.3g us "
          "as one system (%.1f x)\n", __func__, m->nrigid_block, unknowns,
          m->nrigid_group, rows, 6 * nb, worst, 1e6 * t_blocks, 1e6 * t_whole, t_whole / t_blocks);
  assert_int_equal(rows, 0);
  free(load), free(lb), free(lw), free(ft);
  free_grouping(&w);
  sw_data_free(blocks);
  sw_data_free(whole);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Groups of one shape solved together, one per vector lane (joint_lanes.c),
 * against each solved alone: five chains of three bones, the first hinged
 * to space, the last past a limit, each its own group of 18 unknowns (a
 * batch of four and one alone), started turning; the same bits. */
static void test_lanes_as_alone(void **state) {
  (void)state;
  static const double along[3] = {1, 0, 0};
  const int chains = 5;
  const long nsteps = sw_test_sanitized() ? 200 : 1000;
  swSpec *s = sw_spec_new();
  for (int c = 0; c < chains; c++) {
    const double y = 0.5 * c;
    int a[3];
    for (int i = 0; i < 3; i++) {
      swRodDesc r = small_bone("l", 0.1 * i, y, 0, along, 1);
      a[i] = sw_spec_add_rod(s, &r);
    }
    swJointDesc j = joint_of(SW_JOINT_HINGE, a[0], 0, -1, 0);
    j.anchor[1] = y;
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_HINGE, a[0], -1, a[1], 0);
    sw_spec_add_joint(s, &j);
    j = joint_of(SW_JOINT_HINGE, a[1], -1, a[2], 0);
    j.has_range = 1, j.angle_min = -0.01, j.angle_max = 0.01;
    sw_spec_add_joint(s, &j);
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  sw_spec_set_integrator(s, SW_IMEX);
  swModel *m = sw_test_compile_at(s, 0.5);
  assert_int_equal(m->nrigid_group, chains);
  fprintf(stderr, "# %s: %d groups, batches from each:", __func__, m->nrigid_group);
  for (int k = 0; k < m->nrigid_group; k++) fprintf(stderr, " %d", m->rigid_group_lanes[k]);
  fprintf(stderr, "\n");
  assert_int_equal(m->rigid_group_lanes[0], 4);
  assert_int_equal(m->rigid_group_lanes[4], 1);
  swData *lanes = sw_data_new(m), *alone = sw_data_new(m);
  assert_non_null(lanes);
  assert_non_null(alone);
  for (int r = 0; r < m->nrod; r++) { /* each chain turning its own way */
    const double V[3] = {0.01 * r, -0.02, 0.03}, W[3] = {0.5 + 0.1 * r, -3.0 * r, 0.2};
    assert_int_equal(sw_rigid_set_motion(m, lanes, r, V, W), SW_OK);
    assert_int_equal(sw_rigid_set_motion(m, alone, r, V, W), SW_OK);
  }
  int *batched = m->rigid_group_lanes, ones[8] = {1, 1, 1, 1, 1, 1, 1, 1};
  double limit = 0;
  for (long k = 0; k < nsteps; k++) {
    assert_int_equal(sw_step(m, lanes), SW_OK);
    m->rigid_group_lanes = ones;
    assert_int_equal(sw_step(m, alone), SW_OK);
    m->rigid_group_lanes = batched;
    for (int i = 0; i < 3 * m->njoint; i++) limit = fmax(limit, fabs(lanes->joint_limit_torque[i]));
  }
  double worst = 0;
  long rows = differ(lanes->x, alone->x, 3 * (size_t)m->stride, &worst);
  rows += differ(lanes->v, alone->v, 3 * (size_t)m->stride, &worst);
  rows += differ(lanes->omega, alone->omega, 3 * (size_t)m->stride, &worst);
  rows += differ(lanes->Q, alone->Q, 9 * (size_t)m->stride, &worst);
  rows += differ(lanes->rigid_L, alone->rigid_L, 3 * (size_t)m->nrigid, &worst);
  rows += differ(lanes->joint_limit_torque, alone->joint_limit_torque, 3 * (size_t)m->njoint, &worst);
  fprintf(stderr, "# %s: %ld steps (t = %.3g s) in lanes and alone: %ld numbers of x, v, omega, "
          "Q, L and the limits' torques differ, largest difference %.3g (the limits' largest "
          "torque %.3g N m)\n", __func__, lanes->step, lanes->time, rows, worst, limit);
  assert_int_equal(rows, 0);
  assert_true(limit > 0);
  sw_data_free(lanes);
  sw_data_free(alone);
  sw_model_free(m);
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_groups),
      cmocka_unit_test(test_blocks_as_whole),
      cmocka_unit_test(test_lanes_as_alone),
  };
  return cmocka_run_group_tests_name("rigid_joint", tests, NULL, NULL);
}
