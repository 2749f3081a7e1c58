/* rigid_joint.c — joints between rigid bodies, linearly implicit (SW_IMEX).
 *
 * Design.  A joint is a penalty spring-damper (joint.c).  Between two bones
 * held rigid (rigid.c), or a rigid bone and space, a stiff one (the snake
 * robot of Zhang et al. 2019, Suppl. Table 9: k = 5e9 N/m) sets a stable
 * step of h w < 2 with w^2 ~ k / m_eff, nanoseconds for small bones.  Under
 * integrator = imex those joints are integrated with the trapezoidal rule
 * instead, inside position Verlet's kick: with u = (V_b, w_b) the bodies'
 * velocities, M their mass and lab inertia, K and C the joints' tangent
 * stiffness and damping in u, and F the loads of the kick (the joints'
 * included, evaluated at the midpoint configuration x_{1/2}),
 *   (M + h/2 C + h^2/4 K) du = h F.
 * For a linear spring this is exactly the implicit midpoint rule
 * (x_{1/2} + h/4 du is the mean of the step's end positions when
 * x_{1/2} = x_0 + h/2 u_0), which is unconditionally stable, second order
 * and symplectic; the step no longer sees the joints' frequencies
 * (stability.c), only what the rest of the scene needs.
 *
 * The tangent is the Gauss-Newton part of each joint's loads (the terms
 * with the load itself times a lever's turn are dropped: they are the load
 * over the stiffness smaller):
 *   position spring, gap rate  g' = J_b u_b - J_a u_a,  J = [I, -[r]x],
 *     r the lever from the body's centre of mass to the joint node:
 *     K += k J^T J,  C += nu J^T J (signed blocks for the two sides);
 *   hinge (k_t about the two directions normal to the axis a) and fixed
 *   (about all three), relative rotation rate w_b - w_a:
 *     K += k_t P,  C += c_t P,  P = I - a a^T (hinge) or I (fixed);
 *   a limit outside its range (joint.c, "Limits"), its coordinate's rate
 *   -/+ (w_b - w_a) . g:  K += k_l g g^T,  C += c_l g g^T, so a stiff limit
 *   is implicit too (its state at the kick's midpoint decides whether it
 *   is in the system, as the joint's loads are evaluated there).  Because
 *   contact switches on and off there, a limit still bounds the step
 *   (stability.c, implicit_limit_dt); the tangent keeps a resting contact
 *   converging up to that bound.
 * The system couples only the bodies the joints connect: it is block
 * diagonal over the connected components of the graph whose vertices are
 * the moving bodies and whose edges are the implicit joints, here called
 * groups (in the muscular snake, a rib and the two tendons on it: 3 bodies,
 * 18 unknowns, touching no other rigid body, since the ribs hang on the
 * elastic backbone by explicit joints).  Each group's block is symmetric
 * positive definite, 6 unknowns per body, and is assembled, factored by
 * Cholesky (Golub and Van Loan, Matrix Computations, 4th ed., sec. 4.2)
 * and solved on its own each kick: at most sum (6 n_g)^3 / 3 flops, dense,
 * instead of (6 sum n_g)^3 / 3 for the whole (the 4-pair snake's 8 groups
 * of 18 unknowns cost 64 times less than its 144 as one), and less within
 * the group's envelope (cholesky_solve): a chain of n bones, whose rows
 * reach back one body, costs about 6 n x 12^2 / 2 flops instead of
 * (6 n)^3 / 3 (8 bones: 48 unknowns, 3.5e3 flops against 3.7e4).  The
 * groups are found once, at setup, by union-find and numbered in the order
 * their bodies are first met in the joints, as the one system numbered its
 * bodies, and each group keeps its bodies in that order; so a block is the
 * whole system's rows and columns in the same order, and its factor and
 * solution are the whole's to the bit (the whole's factor is block
 * diagonal too, and zero outside the envelope: an entry there is 0 less
 * products with a zero factor, and so is each term the sums skip).  The
 * bodies' new velocities replace the loads they would have had (F_eff =
 * M dV / h, tau_eff = I dw / h) and rigid.c's kick goes on as before.  A
 * joint that touches an elastic rod stays explicit.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* The rigid body on a joint's side (rod, -1 for space), or -1 when that
 * side is space or a body that never moves. */
static int moving_body(const swModel *m, int rod) {
  if (rod < 0 || !sw_rod_is_rigid(m, rod)) return -1;
  const int b = m->rod_rigid[rod];
  return m->rigid_fixed[b] ? -1 : b;
}

/* A side that is space or a fixed body holds still. */
static int holds_still(const swModel *m, int rod) {
  return rod < 0 || (sw_rod_is_rigid(m, rod) && m->rigid_fixed[m->rod_rigid[rod]]);
}

/* The representative of body b's set (union-find with path halving:
 * Tarjan and van Leeuwen, J. ACM 31, 1984). */
static int find_root(int *parent, int b) {
  while (parent[b] != b) b = parent[b] = parent[parent[b]];
  return b;
}

/* The group of implicit joint j: that of a moving body on it. */
static int joint_group(const swModel *m, const int *root, const int *group_of, int j) {
  const int ba = moving_body(m, m->joint[j].rod_a);
  return group_of[root[ba >= 0 ? ba : moving_body(m, m->joint[j].rod_b)]];
}

/* The groups of the system, and its bodies and joints numbered group by
 * group (the header).  order[s] is the body the one system numbered s
 * (first met in the joints); root, group_of and next are scratch of nrigid
 * ints. */
static void number_groups(swModel *m, const int *order, int *root, int *group_of, int *next) {
  const int nb = m->nrigid_block;
  for (int b = 0; b < m->nrigid; b++) root[b] = b, group_of[b] = -1;
  for (int j = 0; j < m->njoint; j++) { /* the edges */
    if (!m->joint_implicit[j]) continue;
    const int ba = moving_body(m, m->joint[j].rod_a), bb = moving_body(m, m->joint[j].rod_b);
    if (ba < 0 || bb < 0) continue; /* to space or a fixed body */
    const int ra = find_root(root, ba), rb = find_root(root, bb);
    if (ra != rb) root[ra > rb ? ra : rb] = ra < rb ? ra : rb;
  }
  for (int b = 0; b < m->nrigid; b++) root[b] = find_root(root, b);
  /* the groups, in the order of their first body */
  int ngroup = 0;
  for (int s = 0; s < nb; s++)
    if (group_of[root[order[s]]] < 0) group_of[root[order[s]]] = ngroup++;
  m->nrigid_group = ngroup;
  /* the blocks: sorted by group, each group's bodies in the one system's
   * order (a counting sort) */
  int *adr = m->rigid_group_adr, *jadr = m->rigid_group_joint_adr;
  for (int g = 0; g <= ngroup; g++) adr[g] = jadr[g] = 0;
  for (int s = 0; s < nb; s++) adr[group_of[root[order[s]]] + 1]++;
  for (int g = 0; g < ngroup; g++) adr[g + 1] += adr[g];
  memcpy(next, adr, (size_t)ngroup * sizeof(int));
  for (int s = 0; s < nb; s++) {
    const int b = order[s], block = next[group_of[root[b]]]++;
    m->rigid_block[b] = block;
    m->rigid_block_body[block] = b;
  }
  /* the joints likewise, each group's in joint order */
  for (int j = 0; j < m->njoint; j++)
    if (m->joint_implicit[j]) jadr[joint_group(m, root, group_of, j) + 1]++;
  for (int g = 0; g < ngroup; g++) jadr[g + 1] += jadr[g];
  memcpy(next, jadr, (size_t)ngroup * sizeof(int));
  for (int j = 0; j < m->njoint; j++)
    if (m->joint_implicit[j]) m->rigid_group_joint[next[joint_group(m, root, group_of, j)]++] = j;
  /* the envelope: the earliest block each is joined to, and the last block
   * whose envelope reaches each */
  for (int s = 0; s < nb; s++) m->rigid_block_env[s] = s;
  for (int j = 0; j < m->njoint; j++) {
    if (!m->joint_implicit[j]) continue;
    const int ba = moving_body(m, m->joint[j].rod_a), bb = moving_body(m, m->joint[j].rod_b);
    if (ba < 0 || bb < 0) continue;
    const int sa = m->rigid_block[ba], sb = m->rigid_block[bb];
    const int lo = sa < sb ? sa : sb, hi = sa < sb ? sb : sa;
    if (lo < m->rigid_block_env[hi]) m->rigid_block_env[hi] = lo;
  }
  for (int s = 0; s < nb; s++) m->rigid_block_reach[s] = s;
  for (int t = 0; t < nb; t++)
    for (int s = m->rigid_block_env[t]; s < t; s++)
      if (m->rigid_block_reach[s] < t) m->rigid_block_reach[s] = t;
}

int sw_rigid_joints_setup(swModel *m) {
  const size_t J = (size_t)(m->njoint ? m->njoint : 1), B = (size_t)(m->nrigid ? m->nrigid : 1);
  m->joint_implicit = calloc(J, sizeof(int));
  m->rigid_block = malloc(B * sizeof(int));
  m->rigid_block_body = malloc(B * sizeof(int));
  m->rigid_group_adr = malloc((B + 1) * sizeof(int));
  m->rigid_group_joint_adr = malloc((B + 1) * sizeof(int));
  m->rigid_group_joint = malloc(J * sizeof(int));
  m->rigid_block_env = malloc(B * sizeof(int));
  m->rigid_block_reach = malloc(B * sizeof(int));
  m->nrigid_block = m->nrigid_group = 0;
  if (!m->joint_implicit || !m->rigid_block || !m->rigid_block_body || !m->rigid_group_adr ||
      !m->rigid_group_joint_adr || !m->rigid_group_joint || !m->rigid_block_env ||
      !m->rigid_block_reach)
    return 0;
  for (int b = 0; b < m->nrigid; b++) m->rigid_block[b] = -1;
  m->rigid_group_adr[0] = m->rigid_group_joint_adr[0] = 0;
  if (m->integrator != SW_IMEX) return 1;
  /* the bodies in the order the joints first meet them (the one system's
   * numbering, which the groups keep), into rigid_block_body */
  for (int j = 0; j < m->njoint; j++) {
    const swJointDesc *jd = &m->joint[j];
    const int ba = moving_body(m, jd->rod_a), bb = moving_body(m, jd->rod_b);
    const int a_ok = ba >= 0 || holds_still(m, jd->rod_a), b_ok = bb >= 0 || holds_still(m, jd->rod_b);
    if (!a_ok || !b_ok || (ba < 0 && bb < 0)) continue; /* an elastic side, or nothing moves */
    m->joint_implicit[j] = 1;
    if (ba >= 0 && m->rigid_block[ba] < 0) m->rigid_block_body[m->rigid_block[ba] = m->nrigid_block++] = ba;
    if (bb >= 0 && m->rigid_block[bb] < 0) m->rigid_block_body[m->rigid_block[bb] = m->nrigid_block++] = bb;
  }
  if (!m->nrigid_block) return 1;
  int *scratch = malloc(4 * B * sizeof(int));
  if (!scratch) return 0;
  memcpy(scratch, m->rigid_block_body, (size_t)m->nrigid_block * sizeof(int));
  number_groups(m, scratch, scratch + B, scratch + 2 * B, scratch + 3 * B);
  free(scratch);
  return 1;
}

void sw_rigid_joints_free(swModel *m) {
  free(m->joint_implicit);
  free(m->rigid_block);
  free(m->rigid_block_body);
  free(m->rigid_group_adr);
  free(m->rigid_group_joint_adr);
  free(m->rigid_group_joint);
  free(m->rigid_block_env);
  free(m->rigid_block_reach);
}

/* Doubles of swData's workspace: each group's matrix and right-hand side,
 * one group after another. */
size_t sw_rigid_joints_scratch(const swModel *m) {
  size_t len = 0;
  for (int g = 0; g < m->nrigid_group; g++) {
    const size_t n = 6 * (size_t)(m->rigid_group_adr[g + 1] - m->rigid_group_adr[g]);
    len += n * n + n;
  }
  return len;
}

/* A[rows of s, cols of t] += w * Ms^T Mt, with Ms, Mt 3x6 (row-major). */
static void add_block(double *A, int n, int s, int t, double w, const double *Ms, const double *Mt) {
  for (int i = 0; i < 6; i++)
    for (int k = 0; k < 6; k++) {
      double sum = 0;
      for (int c = 0; c < 3; c++) sum += Ms[6 * c + i] * Mt[6 * c + k];
      A[(size_t)(6 * s + i) * (size_t)n + (size_t)(6 * t + k)] += w * sum;
    }
}

/* The side's 3x6 rate maps: position, the node's velocity J = [I, -[r]x];
 * rotation, the element's angular velocity [0, P]. */
static void side_maps(const double *r, const double *P, double *Jpos, double *Jrot) {
  memset(Jpos, 0, 18 * sizeof(double));
  memset(Jrot, 0, 18 * sizeof(double));
  for (int c = 0; c < 3; c++) {
    Jpos[6 * c + c] = 1;
    for (int k = 0; k < 3; k++) Jrot[6 * c + 3 + k] = P[3 * c + k];
  }
  /* -[r]x w = w x r: row c of -[r]x */
  Jpos[6 * 0 + 4] = r[2], Jpos[6 * 0 + 5] = -r[1];
  Jpos[6 * 1 + 3] = -r[2], Jpos[6 * 1 + 5] = r[0];
  Jpos[6 * 2 + 3] = r[1], Jpos[6 * 2 + 4] = -r[0];
}

/* The joint's lever on a side (node minus the body's centre of mass). */
static void lever(const swModel *m, const swData *d, int b, int node, double *r) {
  double x[3];
  sw_get3(m, d->x, node, x);
  sw_v3_sub(r, x, d->rigid_X + 3 * b);
}

/* In place: A = L L^T (lower triangle), then A x = rhs solved into rhs.
 * A is n x n, 6 rows a body, and by the joints the rows of body s are zero
 * left of the rows of body env[s] (the earliest body joined to s, or s), so
 * the rows of the bodies up to reach[s] (the last whose env is s or before)
 * are the only ones with entries below the diagonal in the columns of s;
 * env and reach number the bodies from base.  L has the same envelope (no
 * fill-in outside it: George and Liu, Computer Solution of Large Sparse
 * Positive Definite Systems, 1981, ch. 4), so the sums run inside it: the
 * terms they skip are products with a zero factor, and the numbers are the
 * dense factorisation's, bit for bit.  Returns 0 if A is not positive
 * definite. */
static int cholesky_solve(double *A, int n, double *rhs, const int *env, const int *reach,
                          int base) {
  for (int j = 0; j < n; j++) {
    const int sj = j / 6, fj = 6 * (env[sj] - base); /* row j's first column */
    double djj = A[(size_t)j * n + j];
    for (int k = fj; k < j; k++) djj -= A[(size_t)j * n + k] * A[(size_t)j * n + k];
    if (!(djj > 0)) return 0;
    const double ljj = sqrt(djj);
    A[(size_t)j * n + j] = ljj;
    for (int t = sj; t <= reach[sj] - base; t++) {
      const int ft = 6 * (env[t] - base);
      if (ft > j) continue; /* outside the envelope: L_ij = A_ij = 0 */
      const int k0 = ft > fj ? ft : fj;
      for (int i = t == sj ? j + 1 : 6 * t; i < 6 * t + 6; i++) {
        double s = A[(size_t)i * n + j];
        for (int k = k0; k < j; k++) s -= A[(size_t)i * n + k] * A[(size_t)j * n + k];
        A[(size_t)i * n + j] = s / ljj;
      }
    }
  }
  for (int i = 0; i < n; i++) { /* L y = rhs */
    double s = rhs[i];
    for (int k = 6 * (env[i / 6] - base); k < i; k++) s -= A[(size_t)i * n + k] * rhs[k];
    rhs[i] = s / A[(size_t)i * n + i];
  }
  for (int i = n - 1; i >= 0; i--) { /* L^T x = y */
    const int si = i / 6;
    double s = rhs[i];
    for (int t = si; t <= reach[si] - base; t++) {
      if (6 * (env[t] - base) > i) continue;
      for (int k = t == si ? i + 1 : 6 * t; k < 6 * t + 6; k++) s -= A[(size_t)k * n + i] * rhs[k];
    }
    rhs[i] = s / A[(size_t)i * n + i];
  }
  return 1;
}

/* The lab inertia R diag(I) R^T of body b. */
static void lab_inertia(const swModel *m, const swData *d, int b, double *Il) {
  const double *R = d->rigid_R + 9 * b, *I = m->rigid_inertia + 3 * b;
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++)
      Il[3 * i + k] = R[3 * i] * I[0] * R[3 * k] + R[3 * i + 1] * I[1] * R[3 * k + 1] +
                      R[3 * i + 2] * I[2] * R[3 * k + 2];
}

/* The trapezoidal loads of group g (the header): its system assembled into
 * A (n x n, n = 6 x its bodies) and rhs, factored and solved, and the loads
 * of its bodies replaced.  Returns 0 if the block could not be factored. */
static int group_kick(const swModel *m, const swData *d, double h, int g, double *A,
                      double *rhs, double *load) {
  const int first = m->rigid_group_adr[g], nb = m->rigid_group_adr[g + 1] - first, n = 6 * nb;
  memset(A, 0, (size_t)n * n * sizeof(double));
  for (int s = 0; s < nb; s++) { /* mass, and the right-hand side h F */
    const int b = m->rigid_block_body[first + s];
    double Il[9];
    lab_inertia(m, d, b, Il);
    for (int i = 0; i < 3; i++) {
      A[(size_t)(6 * s + i) * n + 6 * s + i] = m->rigid_mass[b];
      for (int k = 0; k < 3; k++) A[(size_t)(6 * s + 3 + i) * n + 6 * s + 3 + k] = Il[3 * i + k];
    }
    for (int i = 0; i < 6; i++) rhs[6 * s + i] = h * load[6 * b + i];
  }
  static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int q = m->rigid_group_joint_adr[g]; q < m->rigid_group_joint_adr[g + 1]; q++) {
    const int j = m->rigid_group_joint[q];
    const swJointDesc *jd = &m->joint[j];
    const int body[2] = {moving_body(m, jd->rod_a), moving_body(m, jd->rod_b)};
    const int node[2] = {m->joint_node_a[j], m->joint_node_b[j]};
    /* the rotation's projector: the hinge's axis carried by side a */
    double P[9];
    memcpy(P, I3, sizeof P);
    if (jd->kind == SW_JOINT_HINGE) {
      double Q[9], ax[3];
      sw_getQ(m, d->Q, m->joint_elem_a[j], Q);
      sw_matT_vec(ax, Q, m->joint_axis_a + 3 * j);
      for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) P[3 * i + k] -= ax[i] * ax[k];
    }
    const double wpos = 0.25 * h * h * jd->stiffness + 0.5 * h * jd->damping;
    const double wrot = jd->kind == SW_JOINT_SPHERICAL
                            ? 0.0 : 0.25 * h * h * jd->rot_stiffness + 0.5 * h * jd->rot_damping;
    double Jp[2][18], Jr[2][18], Jl[18] = {0}, gl[3] = {0, 0, 0};
    for (int side = 0; side < 2; side++) {
      if (body[side] < 0) continue;
      double r[3];
      lever(m, d, body[side], node[side], r);
      side_maps(r, P, Jp[side], Jr[side]);
    }
    /* the limit's rate map, one row [0, g^T], the same on both sides */
    const double wlim = sw_joint_limit_tangent(m, d, j, gl)
                            ? 0.25 * h * h * jd->limit_stiffness + 0.5 * h * jd->limit_damping : 0.0;
    for (int k = 0; k < 3; k++) Jl[3 + k] = gl[k];
    for (int s = 0; s < 2; s++)
      for (int t = 0; t < 2; t++) {
        if (body[s] < 0 || body[t] < 0) continue;
        const double sign = s == t ? 1.0 : -1.0; /* rates are side b minus side a */
        const int bs = m->rigid_block[body[s]] - first, bt = m->rigid_block[body[t]] - first;
        add_block(A, n, bs, bt, sign * wpos, Jp[s], Jp[t]);
        if (wrot > 0) add_block(A, n, bs, bt, sign * wrot, Jr[s], Jr[t]);
        if (wlim > 0) add_block(A, n, bs, bt, sign * wlim, Jl, Jl);
      }
  }
  if (!cholesky_solve(A, n, rhs, m->rigid_block_env + first, m->rigid_block_reach + first, first))
    return 0;
  for (int s = 0; s < nb; s++) { /* the loads that give du */
    const int b = m->rigid_block_body[first + s];
    double Il[9], dL[3];
    lab_inertia(m, d, b, Il);
    sw_mat_vec(dL, Il, rhs + 6 * s + 3);
    for (int i = 0; i < 3; i++) {
      load[6 * b + i] = m->rigid_mass[b] * rhs[6 * s + i] / h;
      load[6 * b + 3 + i] = dL[i] / h;
    }
  }
  return 1;
}

/* load[6 b .. 6 b + 5] = (F, tau) of every moving body, on entry the kick's
 * loads; on return, for the bodies of the system, the loads that give the
 * trapezoidal velocities (the header), group by group.  Returns 0 if a
 * group's block could not be factored (not positive definite: a non-finite
 * state); that group's bodies keep their loads, the others are solved. */
int sw_rigid_joints_kick(const swModel *m, swData *d, double h, double *load) {
  int ok = 1;
  double *A = d->rigid_sys;
  for (int g = 0; g < m->nrigid_group; g++) {
    const size_t n = 6 * (size_t)(m->rigid_group_adr[g + 1] - m->rigid_group_adr[g]);
    double *rhs = A + n * n;
    ok &= group_kick(m, d, h, g, A, rhs, load);
    A = rhs + n;
  }
  return ok;
}
