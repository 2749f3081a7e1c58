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
 * The system couples only the members the joints connect (the moving
 * bodies, and the elastic attachments below): it is block diagonal over the
 * connected components of the graph whose vertices are the members and
 * whose edges are the implicit joints, here called groups (in the muscular
 * snake, a rib, the two tendons on it, the backbone node it hangs on and
 * the two filament ends on the tendons: 3 bodies and 3 attachments, 30
 * unknowns, touching no other group, since the rods between are explicit).
 * Each group's block is symmetric positive definite, 6 unknowns per body,
 * and is assembled, factored by
 * Cholesky (Golub and Van Loan, Matrix Computations, 4th ed., sec. 4.2)
 * and solved on its own each kick: at most sum (6 n_g)^3 / 3 flops, dense,
 * instead of (6 sum n_g)^3 / 3 for the whole (the 4-pair snake's 8 groups
 * of 18 unknowns, before the attachments, cost 64 times less than its 144
 * as one), and less within
 * the group's envelope (joint_envelope.c): a chain of n bones, whose rows
 * reach back one body, costs about 6 n x 12^2 / 2 flops instead of
 * (6 n)^3 / 3 (8 bones: 48 unknowns, 3.5e3 flops against 3.7e4).  The
 * groups are found once, at setup, by union-find and numbered in the order
 * their bodies are first met in the joints; within a group the members
 * take the order that makes the envelope's work least (joint_order.c: the
 * muscular snake's ring of a pair, 3455 multiply-adds instead of 9773 in
 * the order met).  A block is the rows and columns of the one system over
 * all the groups in that order, and its factor and solution are that
 * whole's to the bit (the whole's factor is block diagonal too, and zero
 * outside the envelope: an entry there is 0 less products with a zero
 * factor, and so is each term the sums skip).  The
 * bodies' new velocities replace the loads they would have had (F_eff =
 * M dV / h, tau_eff = I dw / h) and rigid.c's kick goes on as before.
 *
 * Elastic attachments (issue 31).  A joint between a rigid body and a node
 * of an elastic rod (the muscular snake's ribs hinged on its backbone, the
 * tendons on the ribs joined to the muscle filaments; tendons on rigid
 * bones) is as stiff as one between two bodies, and its explicit bound was
 * what held the snake's step (25 us, against 54 us for the filaments and 77
 * us for the backbone).  Such a joint is in the system too: its elastic side
 * is a member of the group with the node's velocity (mass m_i) as unknowns
 * and, when a joint turns the element (hinge, fixed, a limit), the angular
 * velocity of the joint's element (lab inertia Q^T diag(J^/e) Q, the
 * element's kick of integrate.c written in the lab frame): six unknowns
 * like a body's, or three; its lever is r = 0 since the joint sits on the
 * node.  The rod's
 * own loads on that node and element (elasticity, damping, the other
 * joints, muscles, environments) stay explicit and are part of F, so the
 * member's row is that of the explicit kick plus the joint's implicit
 * spring: an IMEX splitting in which the stiff joint spring no longer
 * bounds the step and the rod's own bound (stability.c) is unchanged, since
 * h^2/4 K only adds to the mass the explicit loads act on.  The new
 * velocities replace the node's force and, when a joint couples the
 * element's rotation (hinge, fixed, a limit), its torque (F_eff = m_i dv / h,
 * tau_eff = (J^/e) Q dw / h), before integrate.c's kick of the elastic
 * slots, which therefore follows the solve (sw_rigid_loads).  A node is
 * eligible when its rod is kicked explicitly by integrate.c's plain kick:
 * not rigid, not an implicit rod (rod_implicit.c solves its own system),
 * not integrated with exact (analytic) damping, and not held by a boundary
 * condition.  A joint between two elastic rods, or an elastic rod and space,
 * stays explicit (it would merge the rods' systems).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* The end of group g's members in the dense block: its leaves come last. */
static int dense_end(const swModel *m, int g) {
  int end = m->rigid_group_adr[g + 1];
  while (end > m->rigid_group_adr[g] && m->rigid_block_leaf[end - 1] >= 0) end--;
  return end;
}

/* Group g's numbering of its members' unknowns: their first and count,
 * over their kept ports under a member's band path (rigid_group_band 2,
 * joint_ports.c). */
static const int *group_off(const swModel *m, int g) {
  return m->rigid_group_band[g] == 2 ? m->rigid_block_moff : m->rigid_block_off;
}
static const int *group_dof(const swModel *m, int g) {
  return m->rigid_group_band[g] == 2 ? m->rigid_block_mdof : m->rigid_block_dof;
}

int sw_rigid_group_unknowns(const swModel *m, int g) {
  const int last = dense_end(m, g) - 1;
  return last < m->rigid_group_adr[g] ? 0 : group_off(m, g)[last] + group_dof(m, g)[last];
}

/* The band ports of group g under a member's band path (rigid_port_moff). */
static int member_band_ports(const swModel *m, int g) {
  int nbp = 0;
  if (m->rigid_group_band[g] != 2) return 0;
  for (int k = m->rigid_group_adr[g]; k < m->rigid_group_adr[g + 1]; k++) {
    if (m->rigid_block_rod[k] < 0) continue;
    for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++)
      nbp += m->rigid_port_moff[q] < 0;
  }
  return nbp;
}

/* A group solved in its rod's band (m->rigid_group_band): its ports. */
static int band_ports(const swModel *m, int g) {
  const int k = m->rigid_group_adr[g];
  return m->rigid_group_band[g] == 1 ? m->rigid_block_port_adr[k + 1] - m->rigid_block_port_adr[k] : 0;
}

/* Doubles of group g's leaves' workspaces: the last unit's place and size
 * (joint_groups.c, store_units, lays them out owner after owner; the
 * leaves are the group's last members, a partner after its owner). */
static size_t leaf_doubles(const swModel *m, int g) {
  for (int k = m->rigid_group_adr[g + 1] - 1; k >= m->rigid_group_adr[g]; k--) {
    if (m->rigid_block_leaf[k] < 0) return 0; /* no leaf after the dense members */
    const int *w = m->rigid_leaf_unit + SW_LEAF_UNIT * (size_t)k;
    if (w[0] == k) return (size_t)w[10] + sw_unit_size(w[3], w[4]);
  }
  return 0;
}

/* Doubles of group g's rod members' workspaces (joint_ports.c): its dense
 * rods' (leaves 0), which come first in its rods' part, or its rod
 * leaves' (leaves 1), which follow them.  On the band path its one rod is
 * not condensed and has none. */
static size_t rods_scratch(const swModel *m, int g, int leaves) {
  const int band = m->rigid_group_band[g];
  size_t len = 0;
  for (int k = m->rigid_group_adr[g]; k < m->rigid_group_adr[g + 1]; k++) {
    if (m->rigid_block_rod[k] < 0 || (m->rigid_block_leaf[k] >= 0) != leaves) continue;
    if (!leaves && band == 1) continue;
    len += sw_port_member_scratch(m, k, !leaves && band == 2);
  }
  return len;
}

/* Doubles of group g's workspace: its matrix, right-hand side and the
 * factorisation's column (joint_envelope.c), then each leaf's and each rod
 * member's (joint_ports.c); in the band path, the ports' blocks and
 * right-hand sides (sw_band_group_solve), then each leaf's; in a member's
 * band path, the band ports' blocks and right-hand sides come first. */
static size_t group_scratch(const swModel *m, int g) {
  const size_t units = leaf_doubles(m, g) + rods_scratch(m, g, 0) + rods_scratch(m, g, 1);
  const size_t ports = (size_t)(SW_BAND_PORT + 6);
  if (m->rigid_group_band[g] == 1) return (size_t)band_ports(m, g) * ports + units;
  const size_t n = (size_t)sw_rigid_group_unknowns(m, g);
  return n * n + 2 * n + (size_t)member_band_ports(m, g) * ports + units;
}

/* Doubles of swData's workspace: each group's, one after another. */
size_t sw_rigid_joints_scratch(const swModel *m) {
  size_t len = 0;
  for (int g = 0; g < m->nrigid_group; g++) len += group_scratch(m, g);
  return len;
}

/* One joint's terms of the block (rows of member s, columns of member t):
 * wp Js^T Jt + wr Rs^T Rt + wl Ls^T Lt for its rate maps (3x6, row-major),
 * the position's J = [I, X] (X = -[r]x, side_map), the rotation's R =
 * [0, P] and the limit's L = [0, g^T] (the same on both sides, so their
 * products PtP = P^T P and ggT = g g^T come in once per joint), each
 * weight signed by the sides; the blocks start at rows os and columns ot,
 * ds and dt unknowns (3: an attachment whose rotation no joint turns, X =
 * 0 there since its lever is 0).  Written out for these shapes, the products
 * with the zero and unit blocks of the maps left out: each entry is the sum
 * over c of the maps' rows in the same order as the full product, so the
 * numbers are the same; it costs a fifth of the generic 6x3x6 product. */
static void add_pair(double *A, int n, int os, int ds, int ot, int dt, double wp, double wr,
                     double wl, const double *Js, const double *Jt, const double *PtP,
                     const double *ggT) {
  double *B = A + (size_t)os * (size_t)n + (size_t)ot;
  for (int i = 0; i < 3; i++) {
    double *Bi = B + (size_t)i * (size_t)n, *Bq = B + (size_t)(3 + i) * (size_t)n;
    Bi[i] += wp; /* I^T I */
    for (int k = 0; k < 3; k++) {
      if (dt == 6) Bi[3 + k] += wp * Jt[6 * i + 3 + k]; /* I^T Xt */
      if (ds < 6) continue; /* a member of three unknowns: its node alone */
      Bq[k] += wp * Js[6 * k + 3 + i];     /* Xs^T I */
      if (dt < 6) continue;
      double xx = 0;                       /* Xs^T Xt */
      for (int c = 0; c < 3; c++) xx += Js[6 * c + 3 + i] * Jt[6 * c + 3 + k];
      Bq[3 + k] += wp * xx;
      if (wr != 0) Bq[3 + k] += wr * PtP[3 * i + k]; /* 0: no rotation term */
      if (wl != 0) Bq[3 + k] += wl * ggT[3 * i + k]; /* 0: no limit in contact */
    }
  }
}

/* The side's 3x6 position rate map, the node's velocity J = [I, -[r]x]
 * (-[r]x w = w x r).  Every entry is written, zeros too: a memset of the
 * 18 was a `rep stos` under GCC's generic tuning, whose start-up cost a
 * quarter of the four-pair snake's assembly at x86-64-v3. */
static void side_map(const double *r, double *Jpos) {
  const double J[18] = {1, 0, 0, 0,     r[2],  -r[1], /* row 0 */
                        0, 1, 0, -r[2], 0,     r[0],  /* row 1 */
                        0, 0, 1, r[1],  -r[0], 0};    /* row 2 */
  memcpy(Jpos, J, sizeof J);
}

/* The joint's lever on a side (node minus the body's centre of mass). */
static void lever(const swModel *m, const swData *d, int b, int node, double *r) {
  double x[3];
  sw_get3(m, d->x, node, x);
  sw_v3_sub(r, x, d->rigid_X + 3 * b);
}

/* The lab inertia R diag(I) R^T of body b. */
static void lab_inertia(const swModel *m, const swData *d, int b, double *Il) {
  const double *R = d->rigid_R + 9 * b, *I = m->rigid_inertia + 3 * b;
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++)
      Il[3 * i + k] = R[3 * i] * I[0] * R[3 * k] + R[3 * i + 1] * I[1] * R[3 * k + 1] +
                      R[3 * i + 2] * I[2] * R[3 * k + 2];
}

/* The lab inertia Q^T diag(J^/e) Q of elastic element e: its kick
 * (J^/e) dw/dt = tau (integrate.c) in the lab frame. */
static void element_inertia(const swModel *m, const swData *d, int e, double *Il) {
  double Q[9];
  sw_getQ(m, d->Q, e, Q);
  const double dil = sw_inertia_dilatation(m, d, e);
  const double J[3] = {SW_AT(m, m->inertia, e, 0) / dil, SW_AT(m, m->inertia, e, 1) / dil,
                       SW_AT(m, m->inertia, e, 2) / dil};
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++)
      Il[3 * i + k] = Q[i] * J[0] * Q[k] + Q[3 + i] * J[1] * Q[3 + k] + Q[6 + i] * J[2] * Q[6 + k];
}

/* Member k's mass, lab inertia and loads (F, tau) in lab components: a
 * body's from load[], an attachment's from its node's force and its
 * element's torque (material components, turned to the lab; neither, nor
 * the inertia, for an attachment of three unknowns). */
static void member_inertia(const swModel *m, const swData *d, int k, const double *load,
                           double *mass, double *Il, double *F) {
  const int b = m->rigid_block_body[k];
  if (b >= 0) {
    *mass = m->rigid_mass[b];
    lab_inertia(m, d, b, Il);
    memcpy(F, load + 6 * b, 6 * sizeof(double));
    return;
  }
  const int i = m->rigid_block_node[k], e = m->rigid_block_elem[k];
  *mass = m->mass[i];
  sw_get3(m, d->force, i, F);
  if (m->rigid_block_dof[k] < 6) return; /* its node alone: no rotation */
  double Q[9], t[3];
  element_inertia(m, d, e, Il);
  sw_getQ(m, d->Q, e, Q);
  sw_get3(m, d->torque, e, t);
  sw_matT_vec(F + 3, Q, t);
}

/* A leaf's unit (joint_ports.c), as joint_groups.c stored it: the leaf
 * itself, or it and its partner, whose lower block owns the workspace; the
 * leaf's rows in it (ro), its port's columns in the coupling (co), the
 * unit's unknowns (du) and ports' (dQ), and for the elimination the ports'
 * places in the dense block. */
typedef struct {
  double *ws;
  int owner, ro, co, du, dQ, np, qoff[2], qdof[2];
  int inband; /* its port's block is a band port's (qoff 6 t among them) */
  int plain;  /* a lone leaf without a dashpot: eliminated in closed form (leaf_plain.c) */
} Unit;

/* Whether leaf k is a lone leaf without a dashpot, eliminated with its
 * port's own block of its joints in closed form (leaf_plain.c); a rod
 * leaf's block is its rod's condensed stiffness, not a mass. */
static int plain_leaf(const swModel *m, int k) {
  const int *w = m->rigid_leaf_unit + SW_LEAF_UNIT * (size_t)k;
  return w[5] == 1 && m->rigid_block_fil[w[0]] < 0 && m->rigid_block_rod[w[0]] < 0;
}

/* band: the group's rigid_group_band, first its first member.  Inlined: a
 * Unit returned through memory, three times for each of the resolved
 * wing's 3072 barbs a kick, had cost some 8% of its step. */
static inline __attribute__((always_inline)) Unit leaf_unit(const swModel *m, double *leaf_ws,
                                                            int k, int band, int first) {
  const int *w = m->rigid_leaf_unit + SW_LEAF_UNIT * (size_t)k;
  Unit u = {leaf_ws + w[10],
            w[0], w[1], w[2], w[3], w[4], w[5], {w[6], w[7]}, {w[8], w[9]}, 0,
            plain_leaf(m, k)};
  if (band == 1) { /* the band path's place of its one port: 6 t (sw_band_group_solve) */
    u.qoff[0] = 6 * (m->rigid_block_leaf[u.owner] - m->rigid_block_port_adr[first]);
    u.inband = 1;
  } else if (band == 2) /* a member's band path: the kept port's place, or the band port's */
    for (int i = 0; i < u.np; i++) {
      const int mo = m->rigid_port_moff[m->rigid_block_leaf[i ? m->rigid_block_partner[u.owner] : u.owner]];
      u.qoff[i] = mo >= 0 ? mo : 6 * (-1 - mo);
      u.inband |= mo < 0; /* a lone leaf's (a pair's ports are kept) */
    }
  return u;
}

/* Units eliminated together (sw_leaf_condense): the same unknowns and ports. */
#define UNIT_BATCH 16
static int same_shape(const Unit *a, const Unit *b) {
  return a->du == b->du && a->dQ == b->dQ && a->np == b->np && a->qdof[0] == b->qdof[0] &&
         a->inband == b->inband && a->plain == b->plain &&
         (a->np < 2 || a->qdof[1] == b->qdof[1]);
}

/* A joint of a plain leaf on its port (leaf_plain.c), the leaf's dof
 * unknowns: its own block and its coupling to the port, as add_pair makes
 * them when both levers are 0 (J = [I, 0]: the sums add its zero products
 * of the lever, which change nothing), w_p I on the position and w_r P^T P
 * + w_l g g^T on the rotation, signed; the port's own block is the leaf's
 * closed form's. */
static void plain_joint(const Unit *u, int dof, double wp, double wr, double wl, const double *PtP,
                        const double *ggT) {
  double *A = u->ws + (size_t)u->ro * (size_t)u->du + u->ro;
  double *C = sw_unit_C(u->ws, u->du) + (size_t)u->ro * (size_t)u->dQ + u->co;
  for (int i = 0; i < 3; i++) A[i * u->du + i] += wp, C[i * u->dQ + i] += -wp;
  if (dof < 6) return;
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) {
      double *a = A + (3 + i) * u->du + 3 + k, *c = C + (3 + i) * u->dQ + 3 + k;
      if (wr != 0) *a += wr * PtP[3 * i + k], *c += -wr * PtP[3 * i + k];
      if (wl != 0) *a += wl * ggT[3 * i + k], *c += -wl * ggT[3 * i + k];
    }
}

/* Where a joint's side writes in group g's system: its member (numbered
 * from the group's first), whether that is a leaf (whose unit holds its
 * rows, joint_ports.c), and otherwise the side's first unknown and count
 * in the dense block (a rod member's: its port's). */
typedef struct {
  int block, leaf; /* the member (-1: still); leaf: its place among the group's leaves, -1 */
  int off, dof;    /* in the dense block: a member's, or a rod member's port's */
  int inband;      /* a band port's: off is 6 t among the band ports' blocks */
} SideSlot;

static SideSlot side_slot(const swModel *m, int j, int side, int first, int band) {
  SideSlot t = {m->joint_block[2 * j + side], -1, 0, 0, 0};
  if (t.block < 0) return t;
  const int k = t.block, q = m->joint_port[2 * j + side];
  t.dof = m->rigid_block_dof[k];
  if (m->rigid_block_leaf[k] >= 0) t.leaf = m->rigid_block_off[k];
  else t.off = band == 2 ? m->rigid_block_moff[k] : m->rigid_block_off[k];
  if (q >= 0 && band == 1)
    t.off = 6 * (q - m->rigid_block_port_adr[k]), t.dof = sw_port_dof(m, q), t.inband = 1;
  else if (q >= 0 && band == 2) {
    const int mo = m->rigid_port_moff[q];
    t.off = mo >= 0 ? mo : 6 * (-1 - mo), t.dof = sw_port_dof(m, q), t.inband = mo < 0;
  } else if (q >= 0) t.off += m->rigid_port_off[q], t.dof = sw_port_dof(m, q);
  t.block -= first;
  return t;
}

/* The dashpot of a filament in the system (muscle.c, system_part) between
 * its end leaves: h c' b b^T on the unit's rows of each end's node. */
static void unit_dashpot(const swModel *m, const swData *d, double h, double *leaf_ws, int k) {
  const int f = m->rigid_block_fil[k];
  if (f < 0) return;
  const Unit u = leaf_unit(m, leaf_ws, k, 0, 0);
  const double *sys = d->fil_sys + 8 * (size_t)f, w = h * sys[1];
  double b[12] = {0};
  const int ends[2] = {u.owner, m->rigid_block_partner[u.owner]};
  for (int i = 0; i < u.np; i++) {
    const int leaf = ends[i], start = m->rigid_block_node[leaf] == m->node_adr[m->fil_rod[f]];
    const int ro = leaf == u.owner ? 0 : m->rigid_block_dof[u.owner];
    for (int c = 0; c < 3; c++) b[ro + c] = sys[(start ? 2 : 5) + c];
  }
  for (int i = 0; i < u.du; i++)
    for (int c = 0; c < u.du; c++) u.ws[i * u.du + c] += w * b[i] * b[c];
}

/* The dense filaments of group g (joint_groups.c, dense_ends): each one's
 * damping between its end nodes, h c' b b^T over their velocity unknowns
 * (muscle_implicit.c, system_part; the rows of A's lower triangle), or,
 * with du the solution, its tension and the pull that follows
 * (system_tension). */
static void dense_filaments(const swModel *m, swData *d, double h, int g, double *A, int n,
                            const double *du) {
  const int first = m->rigid_group_adr[g], last = m->rigid_group_adr[g + 1];
  for (int f = 0; f < m->nfil; f++) {
    const int *kb = m->fil_block + 2 * f;
    const int k = kb[0] >= 0 ? kb[0] : kb[1];
    if (k < first || k >= last) continue; /* none, or another group's */
    const double *sys = d->fil_sys + 8 * (size_t)f;
    const double *v[2] = {NULL, NULL};
    int o[2] = {-1, -1};
    for (int e = 0; e < 2; e++)
      if (kb[e] >= 0) o[e] = m->rigid_block_off[kb[e]], v[e] = du ? du + o[e] : NULL;
    if (du) {
      sw_muscle_ops(m)->system_tension(m, d, f, v[0], v[1]);
      continue;
    }
    const double w = h * sys[1];
    for (int a = 0; a < 2; a++)
      for (int b = 0; b < 2; b++) {
        if (o[a] < 0 || o[b] < 0 || o[a] < o[b]) continue; /* row a at or below row b */
        const double *ba = sys + (a ? 5 : 2), *bb = sys + (b ? 5 : 2);
        for (int i = 0; i < 3; i++)
          for (int c = 0; c < 3; c++)
            if (o[a] > o[b] || c <= i) A[(size_t)(o[a] + i) * n + o[b] + c] += w * ba[i] * bb[c];
      }
  }
}

/* The trapezoidal loads of group g (the header), in three parts: its
 * system assembled into A (n x n, n its dense members' unknowns) and rhs,
 * its leaves eliminated and its implicit rods condensed to their ports
 * (joint_ports.c) (group_assemble); factored and solved (joint_envelope.c,
 * or with groups of its shape, sw_cholesky_lanes); and the loads of its
 * members replaced (group_finish): a body's in load[], an attachment's node
 * force and, when a joint couples its element's rotation, element torque,
 * an implicit rod's every node and element.  ws: the leaves' and rods'
 * workspace.  In the band path (m->rigid_group_band, joint_ports.c) A is
 * the ports' blocks (row length 6, port t's at row and column 6 t) and rhs
 * their right-hand sides, the rod is not condensed, and the solve
 * (sw_band_group_solve) sets the rod's loads and leaves the ports' lab
 * velocity changes in rhs, from which group_finish recovers the leaves.
 * In a member's band path (rigid_group_band 2) the band ports' blocks P
 * and right-hand sides R lead ws (group_ports); the rods are condensed to
 * their kept ports after the joints and leaves are in (their bands take
 * P and R), and their finish leaves the band ports' velocity changes in R.
 * Returns 0 if the block (or a rod's system) could not be factored. */
typedef struct {
  double *P, *R, *leaf_ws, *rod_ws; /* P, R: the band ports' (NULL: none) */
} GroupWs;

static GroupWs group_ports(const swModel *m, int g, double *A, double *rhs, double *ws) {
  const int band = m->rigid_group_band[g];
  const size_t nbp = (size_t)member_band_ports(m, g);
  GroupWs w = {band == 1 ? A : NULL, band == 1 ? rhs : NULL, ws, NULL};
  if (band == 2) w.P = ws, w.R = ws + nbp * SW_BAND_PORT, w.leaf_ws = w.R + 6 * nbp;
  w.rod_ws = w.leaf_ws + leaf_doubles(m, g);
  return w;
}

static int group_assemble(const swModel *m, swData *d, double h, int g, double *A, double *rhs,
                          double *ws, double *load) {
  const int first = m->rigid_group_adr[g], nb = m->rigid_group_adr[g + 1] - first;
  const int band = m->rigid_group_band[g], bu = band == 1; /* the band path (header) */
  const int nd = dense_end(m, g) - first, n = bu ? 6 : sw_rigid_group_unknowns(m, g);
  const int *off = group_off(m, g) + first, *dof = group_dof(m, g) + first;
  const GroupWs gw = group_ports(m, g, A, rhs, ws);
  double *leaf_ws = gw.leaf_ws, *rod_ws = gw.rod_ws;
  const int np = bu ? band_ports(m, g) : member_band_ports(m, g);
  if (gw.P) { /* the ports' blocks (row length 6) and right-hand sides */
    memset(gw.P, 0, (size_t)np * SW_BAND_PORT * sizeof(double));
    memset(gw.R, 0, (size_t)np * 6 * sizeof(double));
  }
  /* zeros where the assembly adds: each dense member's rows over its
   * envelope up to the end of its diagonal block (A's lower triangle, the
   * only part the envelope Cholesky reads, and the block sw_port_member_assemble
   * solves in).  The rest of A is neither added to nor read before the
   * factorisation writes it (or keeps the zeros it has from the start). */
  for (int s = 0; s < nd && !bu; s++) {
    const int c0 = off[m->rigid_block_env[first + s] - first], c1 = off[s] + dof[s];
    for (int i = off[s]; i < c1; i++) memset(A + (size_t)i * n + c0, 0, (size_t)(c1 - c0) * sizeof(double));
  }
  size_t wleaf = rods_scratch(m, g, 0); /* the rod leaves' workspaces follow the dense rods' */
  for (int s = 0, wrod = 0; s < nb; s++) { /* mass, and the right-hand side h F */
    const int k = first + s, leaf = m->rigid_block_leaf[k] >= 0, rod = m->rigid_block_rod[k] >= 0;
    if (rod && !leaf && bu) continue; /* its band: sw_band_group_solve */
    if (rod && !leaf && band == 2) { /* condensed below: its rows' zeros */
      memset(rhs + off[s], 0, (size_t)dof[s] * sizeof(double));
      continue;
    }
    if (rod && !leaf) { /* S and S p0 (joint_ports.c) */
      double *w = rod_ws + wrod;
      wrod += (int)sw_port_member_scratch(m, k, 0);
      if (!sw_port_member_assemble(m, d, h, k, w, A, n, off[s], rhs, NULL, NULL)) return 0;
      continue;
    }
    const Unit u = leaf ? leaf_unit(m, leaf_ws, k, band, first) : (Unit){0};
    if (rod) { /* a rod leaf: S and S p0 its block and right-hand side in its unit */
      memset(u.ws, 0, sw_unit_size(u.du, u.dQ) * sizeof(double));
      double *w = rod_ws + wleaf;
      wleaf += sw_port_member_scratch(m, k, 0);
      double *ub = sw_unit_b(u.ws, u.du, u.dQ); /* its right-hand side */
      if (!sw_port_member_assemble(m, d, h, k, w, u.ws, u.du, u.ro, ub, NULL, NULL)) return 0;
      continue;
    }
    double M, Il[9], F[6];
    member_inertia(m, d, k, load, &M, Il, F);
    double *B = leaf ? u.ws : A; /* a leaf's unit: A_uu, C, X, b */
    const size_t ld = leaf ? (size_t)u.du : (size_t)n, o = leaf ? (size_t)u.ro : (size_t)off[s];
    double *b = leaf ? sw_unit_b(B, u.du, u.dQ) + o : rhs + o;
    if (leaf && u.owner == k) { /* the unit's A_uu, C and b (X is copied from C) */
      memset(B, 0, (size_t)(u.du * u.du) * sizeof(double));
      memset(sw_unit_C(B, u.du), 0, (size_t)(u.du * u.dQ) * sizeof(double));
      memset(sw_unit_b(B, u.du, u.dQ), 0, (size_t)u.du * sizeof(double));
    }
    for (int i = 0; i < 3; i++) {
      B[(o + i) * ld + o + i] = M;
      if (dof[s] == 6)
        for (int k3 = 0; k3 < 3; k3++) B[(o + 3 + i) * ld + o + 3 + k3] = Il[3 * i + k3];
    }
    for (int i = 0; i < dof[s]; i++) b[i] = h * F[i];
    if (leaf && u.plain) { /* its inertia, for its closed form and its finish */
      double *Mu = sw_unit_M(B, u.du, u.dQ);
      Mu[0] = M;
      if (dof[s] == 6) memcpy(Mu + 1, Il, sizeof Il);
    }
  }
  static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int q = m->rigid_group_joint_adr[g]; q < m->rigid_group_joint_adr[g + 1]; q++) {
    const int j = m->rigid_group_joint[q];
    const swJointDesc *jd = &m->joint[j];
    const SideSlot side[2] = {side_slot(m, j, 0, first, band), side_slot(m, j, 1, first, band)};
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
    double gl[3] = {0, 0, 0};
    /* the limit's rate map, one row [0, g^T], the same on both sides */
    const double wlim = sw_joint_limit_tangent(m, d, j, gl)
                            ? 0.25 * h * h * jd->limit_stiffness + 0.5 * h * jd->limit_damping : 0.0;
    double PtP[9], ggT[9]; /* the rotation's and the limit's products, once */
    for (int i = 0; i < 3; i++)
      for (int k = 0; k < 3; k++) {
        double pp = 0, gg = 0;
        for (int c = 0; c < 3; c++) pp += P[3 * c + i] * P[3 * c + k];
        gg += gl[i] * gl[k];
        PtP[3 * i + k] = pp, ggT[3 * i + k] = gg;
      }
    const int pl = side[0].leaf >= 0 ? 0 : side[1].leaf >= 0 ? 1 : -1;
    if (pl >= 0 && plain_leaf(m, first + side[pl].block)) { /* no levers: its blocks directly */
      const Unit u = leaf_unit(m, leaf_ws, first + side[pl].block, band, first);
      plain_joint(&u, side[pl].dof, wpos, wrot, wlim, PtP, ggT);
      continue;
    }
    double Jp[2][18];
    for (int sd = 0; sd < 2; sd++) {
      if (side[sd].block < 0) continue;
      const int b = m->rigid_block_body[first + side[sd].block];
      double r[3] = {0, 0, 0}; /* an attachment's or a port's joint sits on its node */
      if (b >= 0) lever(m, d, b, node[sd], r);
      side_map(r, Jp[sd]);
    }
    for (int s = 0; s < 2; s++)
      for (int t = 0; t < 2; t++) {
        const SideSlot *ss = &side[s], *st = &side[t];
        if (ss->block < 0 || st->block < 0) continue;
        const double sign = s == t ? 1.0 : -1.0; /* rates are side b minus side a */
        if (ss->leaf >= 0) { /* a leaf's own block (t = s) or its coupling to the port */
          const Unit u = leaf_unit(m, leaf_ws, first + ss->block, band, first);
          if (s == t) add_pair(u.ws, u.du, u.ro, ss->dof, u.ro, ss->dof, wpos, wrot, wlim, Jp[s], Jp[t], PtP, ggT);
          else
            add_pair(sw_unit_C(u.ws, u.du), u.dQ, u.ro, ss->dof, u.co, st->dof, -wpos, -wrot,
                     -wlim, Jp[s], Jp[t], PtP, ggT);
          continue;
        }
        if (st->leaf >= 0) continue; /* C_a^T: the leaf's elimination uses C_a */
        if (s == t && side[1 - s].leaf >= 0 && plain_leaf(m, first + side[1 - s].block))
          continue; /* the port's own block: with the leaf, in closed form (leaf_plain.c) */
        if (ss->inband != st->inband) continue; /* not made: a band port's others are leaves */
        if (ss->off + ss->dof <= st->off) continue; /* above the diagonal: never read */
        add_pair(ss->inband ? gw.P : A, ss->inband ? 6 : n, ss->off, ss->dof, st->off, st->dof,
                 sign * wpos, sign * wrot, sign * wlim, Jp[s], Jp[t], PtP, ggT);
      }
  }
  if (m->fil_block && !bu) dense_filaments(m, d, h, g, A, n, NULL);
  /* the leaves' units eliminated into their ports, in their order, the
   * consecutive ones of the same shape together (sw_leaf_condense) */
  Unit batch[UNIT_BATCH];
  double *bws[UNIT_BATCH];
  const int *bqoff[UNIT_BATCH];
  for (int s = nd, nu = 0; s <= nb; s++) {
    Unit u = {0};
    if (s < nb) {
      u = leaf_unit(m, leaf_ws, first + s, band, first);
      if (u.owner != first + s) continue;
      unit_dashpot(m, d, h, leaf_ws, first + s);
    }
    if (nu > 0 && (s == nb || nu == UNIT_BATCH || !same_shape(&u, &batch[0]))) {
      const int ib = batch[0].inband; /* into the band ports' blocks, or the dense block */
      for (int i = 0; i < nu; i++) bws[i] = batch[i].ws, bqoff[i] = batch[i].qoff;
      for (int i = 0; i < nu && batch[0].plain; i++)
        if (!sw_leaf_condense_plain(bws[i], batch[0].du, batch[0].dQ, bqoff[i][0], ib ? gw.P : A,
                                    ib ? 6 : n, ib ? gw.R : rhs))
          return 0;
      if (!batch[0].plain &&
          !sw_leaf_condense(bws, bqoff, nu, batch[0].du, batch[0].dQ, batch[0].np, batch[0].qdof,
                            ib ? gw.P : A, ib ? 6 : n, ib ? gw.R : rhs))
        return 0;
      nu = 0;
    }
    if (s < nb) batch[nu++] = u;
  }
  for (int s = 0, wrod = 0; s < nd && band == 2; s++) { /* the rods, their band ports in their bands */
    const int k = first + s;
    if (m->rigid_block_rod[k] < 0) continue;
    double *w = rod_ws + wrod;
    wrod += (int)sw_port_member_scratch(m, k, 1);
    if (!sw_port_member_assemble(m, d, h, k, w, A, n, off[s], rhs, gw.P, gw.R)) return 0;
  }
  if (!bu) sw_port_alias_fold(m, g, off - first, dof - first, A, n, rhs); /* (joint_alias.c) */
  return 1;
}

static int group_solve(const swModel *m, swData *d, double h, int g, double *A, double *rhs) {
  const int first = m->rigid_group_adr[g], n = sw_rigid_group_unknowns(m, g);
  if (m->rigid_group_band[g] == 1) return sw_band_group_solve(m, d, h, first, A, rhs);
  return sw_envelope_cholesky_solve(A, n, rhs, rhs + n, m->rigid_block_env + first,
                                    m->rigid_block_reach + first, group_off(m, g) + first,
                                    group_dof(m, g) + first, first);
}

static void group_finish(const swModel *m, swData *d, double h, int g, double *A, double *rhs,
                         double *ws, double *load) {
  const int first = m->rigid_group_adr[g], nb = m->rigid_group_adr[g + 1] - first;
  const int nd = dense_end(m, g) - first, n = sw_rigid_group_unknowns(m, g);
  const int band = m->rigid_group_band[g], bu = band == 1;
  const int *off = group_off(m, g) + first, *dof = group_dof(m, g) + first;
  const GroupWs gw = group_ports(m, g, A, rhs, ws);
  double *leaf_ws = gw.leaf_ws, *rod_ws = gw.rod_ws;
  if (!bu) sw_port_alias_copy(m, g, off - first, rhs); /* an alias' rotation: its target's */
  size_t wleaf = rods_scratch(m, g, 0);
  for (int s = 0, wrod = 0; s < nb; s++) { /* the loads that give du */
    const int k = first + s, b = m->rigid_block_body[k];
    const int rod_leaf = m->rigid_block_rod[k] >= 0 && m->rigid_block_leaf[k] >= 0;
    if (m->rigid_block_rod[k] >= 0 && !rod_leaf && bu) continue; /* set by sw_band_group_solve */
    if (m->rigid_block_rod[k] >= 0 && !rod_leaf) { /* (the band ports' velocity changes into R) */
      sw_port_member_finish(m, d, h, k, rod_ws + wrod, rhs + off[s], band == 2 ? gw.R : NULL);
      wrod += (int)sw_port_member_scratch(m, k, band == 2);
      continue;
    }
    const double *du = rhs + off[s];
    double M, Il[9], F[6], dL[3] = {0, 0, 0};
    const Unit u = m->rigid_block_leaf[k] >= 0 ? leaf_unit(m, leaf_ws, k, band, first) : (Unit){0};
    if (u.ws) { /* a unit's velocities, once, by its owner */
      const double *pu = u.inband ? gw.R : rhs; /* its ports' solved velocity changes */
      if (u.owner == k && u.plain) sw_leaf_recover_plain(u.ws, u.du, u.dQ, u.qoff[0], pu);
      else if (u.owner == k) sw_leaf_recover(u.ws, u.du, u.dQ, u.np, u.qoff, u.qdof, pu);
      du = sw_unit_b(u.ws, u.du, u.dQ) + u.ro;
    }
    if (rod_leaf) { /* its port's velocity change gives its every unknown's (joint_ports.c) */
      sw_port_member_finish(m, d, h, k, rod_ws + wleaf, du, NULL);
      wleaf += sw_port_member_scratch(m, k, 0);
      continue;
    }
    if (u.plain) { /* its inertia as the assembly found it */
      const double *Mu = sw_unit_M(u.ws, u.du, u.dQ);
      M = Mu[0];
      if (dof[s] == 6) memcpy(Il, Mu + 1, sizeof Il);
    } else
      member_inertia(m, d, k, load, &M, Il, F);
    if (dof[s] == 6) sw_mat_vec(dL, Il, du + 3);
    if (b >= 0) {
      for (int i = 0; i < 3; i++) {
        load[6 * b + i] = M * du[i] / h;
        load[6 * b + 3 + i] = dL[i] / h;
      }
      continue;
    }
    const int i = m->rigid_block_node[k], e = m->rigid_block_elem[k];
    for (int c = 0; c < 3; c++) SW_AT(m, d->force, i, c) = M * du[c] / h;
    if (dof[s] == 6) { /* tau_eff = (J^/e) Q dw / h, material components */
      double Q[9], t[3];
      sw_getQ(m, d->Q, e, Q);
      sw_mat_vec(t, Q, dL);
      for (int c = 0; c < 3; c++) SW_AT(m, d->torque, e, c) = t[c] / h;
    }
  }
  for (int s = nd; s < nb; s++) { /* the filaments in the system: their tension */
    const int k = first + s, f = m->rigid_block_fil[k];
    if (f < 0) continue;
    const Unit u = leaf_unit(m, leaf_ws, k, band, first);
    if (u.owner != k) continue;
    const double *dv[2] = {NULL, NULL}; /* start, end: NULL when clamped */
    const int ends[2] = {k, m->rigid_block_partner[k]};
    for (int i = 0; i < u.np; i++) {
      const int start = m->rigid_block_node[ends[i]] == m->node_adr[m->fil_rod[f]];
      dv[start ? 0 : 1] = sw_unit_b(u.ws, u.du, u.dQ) + (i ? m->rigid_block_dof[k] : 0);
    }
    sw_muscle_ops(m)->system_tension(m, d, f, dv[0], dv[1]);
  }
  if (m->fil_block && !bu) dense_filaments(m, d, h, g, A, n, rhs);
}

/* The via rings' force changes of group g's filaments in the system, on
 * both sides (sw_muscle_system_tension computed them at the solved
 * tension), in the order group_finish set the tensions: its leaf pairs',
 * then its dense filaments'.  Added once the batch the group is solved in
 * is finished: a ring's bone-side force is explicit (via_implicit.c), and
 * may fall on a member of another group (the muscular snake's rings sit on
 * the backbone between its pairs' ribs), which takes it in its system when
 * it is solved after, as a load of its kick, and on top of its solved
 * loads when it was solved before or with it. */
static void group_rings(const swModel *m, swData *d, int g) {
  if (!m->nring) return;
  const int first = m->rigid_group_adr[g], last = m->rigid_group_adr[g + 1];
  for (int k = first; k < last; k++) {
    const int f = m->rigid_block_fil[k];
    if (f >= 0 && m->rigid_block_leaf[k] >= 0 && m->rigid_leaf_unit[SW_LEAF_UNIT * (size_t)k] == k)
      sw_via_implicit_add(m, d, f, 0, m->nslot);
  }
  for (int f = 0; m->fil_block && f < m->nfil; f++) {
    const int *kb = m->fil_block + 2 * f, k = kb[0] >= 0 ? kb[0] : kb[1];
    if (k >= first && k < last) sw_via_implicit_add(m, d, f, 0, m->nslot);
  }
}

/* Group g's right-hand side and workspace in its part A of d->rigid_sys
 * (group_scratch): after its n x n block, or on the band path after its
 * ports' blocks. */
static double *group_rhs(const swModel *m, int g, double *A, double **ws) {
  const size_t n = (size_t)sw_rigid_group_unknowns(m, g), np = (size_t)band_ports(m, g);
  double *rhs = np ? A + np * SW_BAND_PORT : A + n * n;
  *ws = rhs + (np ? 6 * np : 2 * n);
  return rhs;
}

void sw_rigid_forget_kept_maps(const swModel *m, swData *d) {
  double *A = d->rigid_sys;
  for (int g = 0; g < m->nrigid_group; A += group_scratch(m, g), g++) {
    if (m->rigid_group_band[g] != 2) continue;
    double *ws, *rhs = group_rhs(m, g, A, &ws);
    const GroupWs gw = group_ports(m, g, A, rhs, ws);
    const int first = m->rigid_group_adr[g], nd = dense_end(m, g) - first;
    for (int s = 0, wrod = 0; s < nd; s++) /* group_assemble's rods */
      if (m->rigid_block_rod[first + s] >= 0) {
        sw_port_member_forget(m, first + s, gw.rod_ws + wrod);
        wrod += (int)sw_port_member_scratch(m, first + s, 1);
      }
  }
}

/* load[6 b .. 6 b + 5] = (F, tau) of every moving body, on entry the kick's
 * loads; on return, for the bodies of the system, the loads that give the
 * trapezoidal velocities (the header), group by group, and likewise the
 * force and torque of each attachment's node and element in d.  Returns 0
 * if a group's block could not be factored (not positive definite: a
 * non-finite state); that group's members keep their loads, the others are
 * solved. */
int sw_rigid_joints_kick(const swModel *m, swData *d, double h, double *load) {
  int ok = 1;
  double *A = d->rigid_sys;
  for (int g = 0; g < m->nrigid_group;) {
    /* a batch of groups of one shape (joint_lanes.c), or one group */
    const int nl = m->rigid_group_lanes[g] > 1 ? m->rigid_group_lanes[g] : 1;
    double *Ab[SW_GROUP_LANES], *rhs[SW_GROUP_LANES], *ws[SW_GROUP_LANES];
    int okb[SW_GROUP_LANES], all = 1;
    for (int u = 0; u < nl; u++) {
      Ab[u] = A, rhs[u] = group_rhs(m, g + u, A, &ws[u]);
      okb[u] = group_assemble(m, d, h, g + u, Ab[u], rhs[u], ws[u], load);
      all &= okb[u];
      A += group_scratch(m, g + u);
    }
    const int first = m->rigid_group_adr[g];
    const int together = nl > 1 && all &&
        sw_cholesky_lanes(Ab, rhs, nl, sw_rigid_group_unknowns(m, g), m->rigid_block_env + first,
                          m->rigid_block_reach + first, m->rigid_block_off + first,
                          m->rigid_block_dof + first, first, d->rigid_lanes);
    for (int u = 0; u < nl && !together; u++) /* one by one: alone, or a lane failed */
      if (okb[u]) okb[u] = group_solve(m, d, h, g + u, Ab[u], rhs[u]);
    for (int u = 0; u < nl; u++) {
      if (okb[u]) group_finish(m, d, h, g + u, Ab[u], rhs[u], ws[u], load);
      ok &= okb[u];
    }
    for (int u = 0; u < nl; u++)
      if (okb[u]) group_rings(m, d, g + u);
    g += nl;
  }
  return ok;
}
