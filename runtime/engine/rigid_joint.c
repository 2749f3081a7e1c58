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

/* Whether node `node` (and element `elem`) of explicit elastic rod `rod`
 * can be an attachment of the system (the header): kicked by integrate.c's
 * plain kick. */
static int elastic_attachable(const swModel *m, int rod, int node, int elem) {
  if (m->rod_implicit[rod]) return 0;
  return m->kick_exact[node] == 0.0 && m->kick_exact[elem] == 0.0;
}

/* The kind of the boundary condition on node `node` of rod `rod`, or -1. */
static int bc_on_node(const swModel *m, int rod, int node) {
  for (int k = 0; k < m->nbc; k++)
    if (m->bc[k].rod == rod && sw_bc_node(m, &m->bc[k]) == node) return (int)m->bc[k].kind;
  return -1;
}

/* A joint's side at setup: a moving body, an attachment, a port of an
 * implicit rod (joint_ports.c), or still (space, a fixed body, a clamped
 * node, whose node and end element never move). */
typedef struct {
  int body, node, elem; /* body >= 0, or node >= 0 (and elem), or neither: still */
  int rod;              /* node >= 0 on an implicit rod: a port */
  int ok;               /* it can be in the system */
} Side;

static Side joint_side(const swModel *m, int j, int side) {
  const swJointDesc *jd = &m->joint[j];
  const int rod = side ? jd->rod_b : jd->rod_a;
  const int node = side ? m->joint_node_b[j] : m->joint_node_a[j];
  const int elem = side ? m->joint_elem_b[j] : m->joint_elem_a[j];
  Side s = {moving_body(m, rod), -1, -1, -1, 0};
  if (s.body >= 0 || holds_still(m, rod)) {
    s.ok = 1;
    return s;
  }
  const int bc = bc_on_node(m, rod, node);
  if (bc == SW_BC_CLAMP) s.ok = 1; /* still */
  else if (bc >= 0) return s;      /* a prescribed motion: stays explicit */
  else if (m->rod_implicit[rod]) s.rod = rod, s.node = node, s.elem = elem, s.ok = 1;
  else if (elastic_attachable(m, rod, node, elem)) s.node = node, s.elem = elem, s.ok = 1;
  return s;
}

/* Filaments with the implicit Hill tension (muscle.c) joined to ports.
 * That tension is solved per filament with its end nodes as free masses
 * under the kick's loads, the joints' springs among them, so it takes up a
 * joint's force at once; with the joint in this system as well, the
 * joint's stiffness reaches the rod through the tension explicitly
 * (measured on the arm with every bone and tendon implicit: the 0.5 s
 * flexion within 0.17 % at 40 us, 42-120 % off from 48 us up).  So a
 * filament whose ends are each joined to one port, or clamped, is solved
 * in the system (joint_ports.c, m->fil_system): its ends become one
 * eliminated pair with the filament's damping between them.  ready[f]
 * says so; a joint of any other implicit filament to a port stays
 * explicit, and its own bound (stability.c) holds the step. */
static void hill_ready(const swModel *m, const int *fil_of_rod, int *ready) {
  for (int f = 0; f < m->nfil; f++) ready[f] = m->fil_implicit[f] != 0;
  const size_t nf = m->nfil > 0 ? (size_t)m->nfil : 1;
  int *seen = calloc(2 * nf, sizeof(int)); /* joints per end */
  if (!seen) {
    for (int f = 0; f < m->nfil; f++) ready[f] = 0;
    return;
  }
  for (int j = 0; j < m->njoint; j++)
    for (int side = 0; side < 2; side++) {
      const int rod = side ? m->joint[j].rod_b : m->joint[j].rod_a;
      const int f = rod >= 0 ? fil_of_rod[rod] : -1;
      if (f < 0 || !ready[f]) continue;
      const int node = side ? m->joint_node_b[j] : m->joint_node_a[j], na = m->node_adr[rod];
      const int end = node == na ? 0 : node == na + m->rod_nelem[rod] ? 1 : -1;
      const Side other = joint_side(m, j, 1 - side);
      if (end < 0 || other.rod < 0 || seen[2 * f + end]++) ready[f] = 0;
    }
  for (int f = 0; f < m->nfil; f++) { /* an end without a joint must be clamped */
    const int bits = m->fil_implicit[f];
    if (ready[f] && !seen[2 * f] && !(bits & SW_FIL_HELD_START)) ready[f] = 0;
    if (ready[f] && !seen[2 * f + 1] && !(bits & SW_FIL_HELD_END)) ready[f] = 0;
    if (ready[f] && !seen[2 * f] && !seen[2 * f + 1]) ready[f] = 0; /* no joint at all */
  }
  free(seen);
}

/* Whether joint j ties an implicit filament that is not ready to a port. */
static int hill_on_port(const swModel *m, int j, const Side *s, const int *fil_of_rod,
                        const int *ready) {
  if (s[0].rod < 0 && s[1].rod < 0) return 0;
  const int rods[2] = {m->joint[j].rod_a, m->joint[j].rod_b};
  for (int side = 0; side < 2; side++) {
    if (s[side].node < 0 || s[side].rod >= 0) continue; /* not an attachment */
    const int f = fil_of_rod[rods[side]];
    if (f >= 0 && m->fil_implicit[f] && !ready[f]) return 1;
  }
  return 0;
}

/* The representative of member s's set (union-find with path halving:
 * Tarjan and van Leeuwen, J. ACM 31, 1984). */
static int find_root(int *parent, int s) {
  while (parent[s] != s) s = parent[s] = parent[parent[s]];
  return s;
}

/* The groups of the system, its members and joints numbered group by group
 * (the header).  On entry the members are numbered in the order the joints
 * first meet them (the one system's numbering, which the groups keep):
 * member[2 j + side] is that number of joint j's side (-1: still), and
 * body, node and elem describe each member; root, group_of and next are
 * scratch of nb ints.  On return m->joint_block holds the blocks. */
static void number_groups(swModel *m, const int *member, const int *body, const int *node,
                          const int *elem, const int *rod, const int *rdof, const int *leaf,
                          const int *partner, int *root, int *group_of, int *next) {
  const int nb = m->nrigid_block;
  for (int s = 0; s < nb; s++) root[s] = s, group_of[s] = -1;
  for (int j = 0; j < m->njoint; j++) { /* the edges */
    const int sa = member[2 * j], sb = member[2 * j + 1];
    if (!m->joint_implicit[j] || sa < 0 || sb < 0) continue; /* to space or a fixed body */
    const int ra = find_root(root, sa), rb = find_root(root, sb);
    if (ra != rb) root[ra > rb ? ra : rb] = ra < rb ? ra : rb;
  }
  for (int s = 0; s < nb; s++) /* a filament's two ends, eliminated together */
    if (partner[s] > s) {
      const int ra = find_root(root, s), rb = find_root(root, partner[s]);
      if (ra != rb) root[ra > rb ? ra : rb] = ra < rb ? ra : rb;
    }
  for (int s = 0; s < nb; s++) root[s] = find_root(root, s);
  int ngroup = 0; /* the groups, in the order of their first member */
  for (int s = 0; s < nb; s++)
    if (group_of[root[s]] < 0) group_of[root[s]] = ngroup++;
  m->nrigid_group = ngroup;
  /* the blocks: sorted by group, each group's members in the one system's
   * order (a counting sort), its leaves (joint_ports.c) after the others */
  int *adr = m->rigid_group_adr, *jadr = m->rigid_group_joint_adr, *block = root;
  for (int g = 0; g <= ngroup; g++) adr[g] = jadr[g] = 0;
  for (int s = 0; s < nb; s++) adr[group_of[root[s]] + 1]++;
  for (int g = 0; g < ngroup; g++) adr[g + 1] += adr[g];
  memcpy(next, adr, (size_t)ngroup * sizeof(int));
  for (int pass = 0; pass < 2; pass++)
    for (int s = 0; s < nb; s++) {
      if ((leaf[s] >= 0) != pass) continue;
      const int k = next[group_of[root[s]]]++;
      block[s] = k; /* root[s] is read no more for s */
      m->rigid_block_body[k] = body[s];
      m->rigid_block_node[k] = node[s];
      m->rigid_block_elem[k] = elem[s];
      m->rigid_block_rod[k] = rod[s];
      m->rigid_block_leaf[k] = leaf[s]; /* a port's number before sorting: setup renumbers */
      m->rigid_block_dof[k] = rdof[s];  /* a rod member's: its ports' */
      m->rigid_block_rot[k] = 0;
      if (body[s] >= 0) m->rigid_block[body[s]] = k;
    }
  for (int q = 0; q < 2 * m->njoint; q++) m->joint_block[q] = member[q] >= 0 ? block[member[q]] : -1;
  /* the joints likewise, each group's in joint order; the group of a joint
   * is that of a member on it */
  for (int j = 0; j < m->njoint; j++) {
    if (!m->joint_implicit[j]) continue;
    const int *jb = m->joint_block + 2 * j, k = jb[0] >= 0 ? jb[0] : jb[1];
    int g = 0, hi = ngroup - 1; /* the group whose blocks hold k: adr[g] <= k < adr[g + 1] */
    while (g < hi) {
      const int mid = (g + hi + 1) / 2;
      if (adr[mid] <= k) g = mid;
      else hi = mid - 1;
    }
    next[j] = g; /* next is read no more as the blocks' counter */
    jadr[g + 1]++;
    /* a member whose element's rotation a joint couples */
    const swJointDesc *jd = &m->joint[j];
    if (jd->kind != SW_JOINT_SPHERICAL || sw_joint_limited(jd))
      for (int side = 0; side < 2; side++)
        if (jb[side] >= 0) m->rigid_block_rot[jb[side]] = 1;
  }
  for (int g = 0; g < ngroup; g++) jadr[g + 1] += jadr[g];
  /* each member's unknowns in its group: a body's six, an attachment's
   * three of its node, and three of its element when a joint turns it, a
   * rod's its ports'; a leaf's place (off) among its group's leaves */
  for (int g = 0; g < ngroup; g++)
    for (int k = adr[g], off = 0, nleaf = 0; k < adr[g + 1]; k++) {
      if (m->rigid_block_rod[k] < 0)
        m->rigid_block_dof[k] = m->rigid_block_body[k] >= 0 || m->rigid_block_rot[k] ? 6 : 3;
      if (m->rigid_block_leaf[k] >= 0) {
        m->rigid_block_off[k] = nleaf++;
        continue;
      }
      m->rigid_block_off[k] = off;
      off += m->rigid_block_dof[k];
    }
  for (int j = 0, *fill = group_of; j < m->njoint; j++) { /* group_of: a cursor per group */
    if (j == 0) memcpy(fill, jadr, (size_t)ngroup * sizeof(int));
    if (m->joint_implicit[j]) m->rigid_group_joint[fill[next[j]]++] = j;
  }
  /* the envelope: the earliest block each is joined to, and the last block
   * whose envelope reaches each */
  for (int s = 0; s < nb; s++) m->rigid_block_env[s] = s;
  for (int j = 0; j < m->njoint; j++) {
    const int sa = m->joint_block[2 * j], sb = m->joint_block[2 * j + 1];
    if (!m->joint_implicit[j] || sa < 0 || sb < 0) continue;
    if (m->rigid_block_leaf[sa] >= 0 || m->rigid_block_leaf[sb] >= 0) continue; /* eliminated first */
    const int lo = sa < sb ? sa : sb, hi = sa < sb ? sb : sa;
    if (lo < m->rigid_block_env[hi]) m->rigid_block_env[hi] = lo;
  }
  for (int s = 0; s < nb; s++) m->rigid_block_reach[s] = s;
  for (int t = 0; t < nb; t++)
    for (int s = m->rigid_block_env[t]; s < t; s++)
      if (m->rigid_block_reach[s] < t) m->rigid_block_reach[s] = t;
}

/* The ports' numbers sorted by member (each member's in the order the
 * joints first meet them) and each port's first unknown in its member:
 * pmember, pnode, pelem and prot describe the np ports as setup met them;
 * joint_port and the leaves' ports are renumbered. */
static void number_ports(swModel *m, int np, const int *pmember, const int *pnode,
                         const int *pelem, const int *prot, const int *block, int *order) {
  const int nb = m->nrigid_block;
  int *adr = m->rigid_block_port_adr;
  for (int k = 0; k <= nb; k++) adr[k] = 0;
  for (int q = 0; q < np; q++) adr[block[pmember[q]] + 1]++;
  for (int k = 0; k < nb; k++) adr[k + 1] += adr[k];
  int *fill = order + np; /* a cursor per member */
  memcpy(fill, adr, (size_t)nb * sizeof(int));
  for (int q = 0; q < np; q++) {
    const int k = block[pmember[q]], t = fill[k]++;
    order[q] = t;
    m->rigid_port_node[t] = pnode[q];
    m->rigid_port_elem[t] = pelem[q];
    m->rigid_port_rot[t] = prot[q];
  }
  for (int k = 0; k < nb; k++)
    for (int t = adr[k], off = 0; t < adr[k + 1]; t++) {
      m->rigid_port_off[t] = off;
      off += m->rigid_port_rot[t] ? 6 : 3;
    }
  for (int q = 0; q < 2 * m->njoint; q++)
    if (m->joint_port[q] >= 0) m->joint_port[q] = order[m->joint_port[q]];
  for (int k = 0; k < nb; k++)
    if (m->rigid_block_leaf[k] >= 0) m->rigid_block_leaf[k] = order[m->rigid_block_leaf[k]];
  for (int k = 0; k < nb; k++)
    if (m->rigid_block_rod[k] >= 0) m->rod_block[m->rigid_block_rod[k]] = k;
}

/* Each attachment member's leaf port (joint_ports.c): the one port all its
 * implicit joints reach, or -1 (a joint to anything else, or to two ports). */
static void find_leaves(const swModel *m, int nb, const int *member, const int *node, const int *rod,
                        int *leaf) {
  for (int k = 0; k < nb; k++) leaf[k] = node[k] >= 0 && rod[k] < 0 ? -2 : -1; /* -2: none yet */
  for (int j = 0; j < m->njoint; j++) {
    if (!m->joint_implicit[j]) continue;
    for (int side = 0; side < 2; side++) {
      const int k = member[2 * j + side], other = 2 * j + 1 - side;
      if (k < 0 || leaf[k] == -1) continue;
      const int q = m->joint_port[other];
      if (q < 0 || (leaf[k] != -2 && leaf[k] != q)) leaf[k] = -1;
      else leaf[k] = q;
    }
  }
  for (int k = 0; k < nb; k++)
    if (leaf[k] == -2) leaf[k] = -1;
}

/* The rod member that port q belongs to: the last block whose first port
 * is at or before q (rigid_block_port_adr is non-decreasing). */
static int port_member(const swModel *m, int q) {
  int lo = 0, hi = m->nrigid_block - 1;
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (m->rigid_block_port_adr[mid] <= q) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

/* A leaf's unit (joint_ports.c): the leaf itself, or it and its partner,
 * whose lower block owns the workspace; the leaf's rows in it (ro), its
 * port's columns in the coupling (co), the unit's unknowns (du) and ports'
 * (dQ), and for the elimination the ports' places in the dense block. */
typedef struct {
  double *ws;
  int owner, ro, co, du, dQ, np, qoff[2], qdof[2];
} Unit;

static int port_dof(const swModel *m, int q) { return m->rigid_port_rot[q] ? 6 : 3; }

static Unit compute_unit(const swModel *m, int k) {
  const int *off = m->rigid_block_off, *dof = m->rigid_block_dof;
  const int p = m->rigid_block_partner[k];
  Unit u;
  u.owner = p >= 0 && p < k ? p : k;
  const int mate = u.owner == k ? p : k; /* the owner's partner, or -1 */
  u.ws = NULL;
  u.ro = u.owner == k ? 0 : dof[u.owner];
  u.co = u.owner == k ? 0 : port_dof(m, m->rigid_block_leaf[u.owner]);
  u.np = mate >= 0 ? 2 : 1;
  u.du = u.dQ = 0;
  for (int i = 0; i < u.np; i++) {
    const int leaf = i ? mate : u.owner, q = m->rigid_block_leaf[leaf];
    u.qdof[i] = port_dof(m, q);
    u.qoff[i] = off[port_member(m, q)] + m->rigid_port_off[q];
    u.du += dof[leaf];
    u.dQ += u.qdof[i];
  }
  return u;
}

/* Every leaf's unit, once at setup (m->rigid_leaf_unit). */
static void store_units(swModel *m) {
  for (int k = 0; k < m->nrigid_block; k++) {
    if (m->rigid_block_leaf[k] < 0) continue;
    const Unit u = compute_unit(m, k);
    int *w = m->rigid_leaf_unit + 10 * (size_t)k;
    w[0] = u.owner, w[1] = u.ro, w[2] = u.co, w[3] = u.du, w[4] = u.dQ, w[5] = u.np;
    w[6] = u.qoff[0], w[7] = u.qoff[1], w[8] = u.qdof[0], w[9] = u.qdof[1];
  }
}

static Unit leaf_unit(const swModel *m, double *leaf_ws, int k) {
  const int *w = m->rigid_leaf_unit + 10 * (size_t)k;
  const Unit u = {leaf_ws + (size_t)m->rigid_block_off[w[0]] * SW_LEAF_WS,
                  w[0], w[1], w[2], w[3], w[4], w[5], {w[6], w[7]}, {w[8], w[9]}};
  return u;
}

/* The filaments solved in the system (hill_ready): m->fil_system, and
 * their end leaves paired (partner, -1) and marked with the filament (lfil,
 * -1), members numbered as setup met them. */
static void pair_leaves(swModel *m, int nb, const int *member, const int *leaf,
                        const int *fil_of_rod, const int *ready, int *partner, int *lfil) {
  for (int k = 0; k < nb; k++) partner[k] = lfil[k] = -1;
  for (int j = 0; j < m->njoint; j++) {
    if (!m->joint_implicit[j]) continue;
    for (int side = 0; side < 2; side++) {
      const int rod = side ? m->joint[j].rod_b : m->joint[j].rod_a, k = member[2 * j + side];
      const int f = rod >= 0 ? fil_of_rod[rod] : -1;
      if (f < 0 || !ready[f] || k < 0 || leaf[k] < 0) continue;
      m->fil_system[f] = 1;
      lfil[k] = f;
    }
  }
  for (int k = 0; k < nb; k++) /* the filament's other end, if it is a leaf too */
    for (int t = k + 1; t < nb && lfil[k] >= 0; t++)
      if (lfil[t] == lfil[k]) partner[k] = t, partner[t] = k;
}

/* A pair's elimination couples its two ports' members: the envelope takes
 * that edge too, and the reach follows. */
static void pair_envelope(swModel *m) {
  const int nb = m->nrigid_block;
  int changed = 0;
  for (int k = 0; k < nb; k++) {
    const int t = m->rigid_block_partner[k];
    if (t <= k) continue;
    const int a = port_member(m, m->rigid_block_leaf[k]), b = port_member(m, m->rigid_block_leaf[t]);
    const int lo = a < b ? a : b, hi = a < b ? b : a;
    if (lo < m->rigid_block_env[hi]) m->rigid_block_env[hi] = lo, changed = 1;
  }
  if (!changed) return;
  for (int s = 0; s < nb; s++) m->rigid_block_reach[s] = s;
  for (int t = 0; t < nb; t++)
    for (int s = m->rigid_block_env[t]; s < t; s++)
      if (m->rigid_block_reach[s] < t) m->rigid_block_reach[s] = t;
}

int sw_rigid_joints_setup(swModel *m) {
  const size_t J = (size_t)(m->njoint ? m->njoint : 1), B = (size_t)(m->nrigid ? m->nrigid : 1);
  const size_t R = (size_t)(m->nrod ? m->nrod : 1);
  const size_t NB = B + 2 * J; /* members: at most every body and every joint's two sides */
  m->joint_implicit = calloc(J, sizeof(int));
  m->joint_block = malloc(2 * J * sizeof(int));
  m->joint_port = malloc(2 * J * sizeof(int));
  m->rod_block = malloc(R * sizeof(int));
  m->rigid_block = malloc(B * sizeof(int));
  m->rigid_block_body = malloc(NB * sizeof(int));
  m->rigid_block_node = malloc(NB * sizeof(int));
  m->rigid_block_elem = malloc(NB * sizeof(int));
  m->rigid_block_rot = malloc(NB * sizeof(int));
  m->rigid_block_off = malloc(NB * sizeof(int));
  m->rigid_block_dof = malloc(NB * sizeof(int));
  m->rigid_block_rod = malloc(NB * sizeof(int));
  m->rigid_block_leaf = malloc(NB * sizeof(int));
  m->rigid_block_partner = malloc(NB * sizeof(int));
  m->rigid_block_fil = malloc(NB * sizeof(int));
  m->rigid_leaf_unit = malloc(10 * NB * sizeof(int));
  m->fil_system = calloc((size_t)(m->nfil ? m->nfil : 1), sizeof(int));
  m->rigid_block_port_adr = malloc((NB + 1) * sizeof(int));
  m->rigid_port_node = malloc(2 * J * sizeof(int));
  m->rigid_port_elem = malloc(2 * J * sizeof(int));
  m->rigid_port_rot = malloc(2 * J * sizeof(int));
  m->rigid_port_off = malloc(2 * J * sizeof(int));
  m->rigid_group_adr = malloc((NB + 1) * sizeof(int));
  m->rigid_group_joint_adr = malloc((NB + 1) * sizeof(int));
  m->rigid_group_joint = malloc(J * sizeof(int));
  m->rigid_block_env = malloc(NB * sizeof(int));
  m->rigid_block_reach = malloc(NB * sizeof(int));
  m->nrigid_block = m->nrigid_group = m->nrigid_attach = m->nrigid_port = 0;
  if (!m->joint_implicit || !m->joint_block || !m->joint_port || !m->rod_block || !m->rigid_block ||
      !m->rigid_block_body || !m->rigid_block_node || !m->rigid_block_elem || !m->rigid_block_rot ||
      !m->rigid_block_off || !m->rigid_block_dof || !m->rigid_block_rod || !m->rigid_block_leaf ||
      !m->rigid_block_partner || !m->rigid_block_fil || !m->fil_system || !m->rigid_leaf_unit ||
      !m->rigid_block_port_adr || !m->rigid_port_node || !m->rigid_port_elem ||
      !m->rigid_port_rot || !m->rigid_port_off || !m->rigid_group_adr ||
      !m->rigid_group_joint_adr || !m->rigid_group_joint || !m->rigid_block_env ||
      !m->rigid_block_reach)
    return 0;
  for (int b = 0; b < m->nrigid; b++) m->rigid_block[b] = -1;
  for (size_t r = 0; r < R; r++) m->rod_block[r] = -1;
  for (size_t q = 0; q < 2 * J; q++) m->joint_block[q] = m->joint_port[q] = -1;
  m->rigid_group_adr[0] = m->rigid_group_joint_adr[0] = m->rigid_block_port_adr[0] = 0;
  if (m->integrator != SW_IMEX) return 1;
  /* the members in the order the joints first meet them: member[2 j + side]
   * their number, body/node/elem/rod what each is; the ports likewise */
  const size_t S = (size_t)m->stride;
  const size_t F = (size_t)(m->nfil ? m->nfil : 1);
  int *scratch = malloc((2 * J + 11 * NB + 2 * S + 10 * J + 2 * R + F) * sizeof(int));
  if (!scratch) return 0;
  int *member = scratch, *body = member + 2 * J, *node = body + NB, *elem = node + NB;
  int *rod = elem + NB, *rdof = rod + NB, *leaf = rdof + NB;
  int *first = leaf + NB; /* rigid bodies' numbers (nrigid <= NB), then number_groups' scratch */
  int *at_node = first + 4 * NB; /* the attachment on each node slot, or -1 */
  int *port_at = at_node + S;    /* the port on each node slot, or -1 */
  int *pmember = port_at + S, *pnode = pmember + 2 * J, *pelem = pnode + 2 * J;
  int *prot = pelem + 2 * J, *porder = prot + 2 * J; /* 2 J + NB: number_ports' */
  int *rod_first = porder + 2 * J + NB, *fil_of_rod = rod_first + R, *ready = fil_of_rod + R;
  for (size_t r = 0; r < R; r++) fil_of_rod[r] = -1;
  for (int f = 0; f < m->nfil; f++) fil_of_rod[m->fil_rod[f]] = f;
  hill_ready(m, fil_of_rod, ready);
  int nb = 0, np = 0;
  for (int b = 0; b < m->nrigid; b++) first[b] = -1;
  for (size_t i = 0; i < S; i++) at_node[i] = port_at[i] = -1;
  for (size_t r = 0; r < R; r++) rod_first[r] = -1;
  for (int j = 0; j < m->njoint; j++) {
    const Side s[2] = {joint_side(m, j, 0), joint_side(m, j, 1)};
    member[2 * j] = member[2 * j + 1] = -1;
    /* both sides in reach, and a rigid body or an implicit rod moving on one */
    if (!s[0].ok || !s[1].ok) continue;
    if (s[0].body < 0 && s[1].body < 0 && s[0].rod < 0 && s[1].rod < 0) continue;
    if (hill_on_port(m, j, s, fil_of_rod, ready)) continue;
    m->joint_implicit[j] = 1;
    for (int side = 0; side < 2; side++) {
      int k = -1;
      if (s[side].body >= 0) k = first[s[side].body];
      else if (s[side].rod >= 0) k = rod_first[s[side].rod];
      else if (s[side].node >= 0) k = at_node[s[side].node]; /* its element is the node's (joint.c) */
      else continue; /* still */
      if (k < 0) { /* a new member */
        k = nb++;
        body[k] = s[side].body, node[k] = elem[k] = -1, rod[k] = s[side].rod, rdof[k] = 0;
        if (s[side].body >= 0) first[s[side].body] = k;
        else if (s[side].rod >= 0) rod_first[s[side].rod] = k;
        else node[k] = s[side].node, elem[k] = s[side].elem, at_node[s[side].node] = k, m->nrigid_attach++;
      }
      member[2 * j + side] = k;
      if (s[side].rod < 0) continue;
      int q = port_at[s[side].node]; /* the rod's port on that node */
      if (q < 0) {
        q = port_at[s[side].node] = np++;
        pmember[q] = k, pnode[q] = s[side].node, pelem[q] = s[side].elem, prot[q] = 0;
      }
      m->joint_port[2 * j + side] = q;
    }
    const swJointDesc *jd = &m->joint[j]; /* a port whose element a joint turns */
    if (jd->kind != SW_JOINT_SPHERICAL || sw_joint_limited(jd))
      for (int side = 0; side < 2; side++)
        if (m->joint_port[2 * j + side] >= 0) prot[m->joint_port[2 * j + side]] = 1;
  }
  for (int q = 0; q < np; q++) rdof[pmember[q]] += prot[q] ? 6 : 3;
  m->nrigid_block = nb;
  m->nrigid_port = np;
  find_leaves(m, nb, member, node, rod, leaf);
  int *partner = at_node, *lfil = port_at; /* the node maps are read no more (S >= nb) */
  pair_leaves(m, nb, member, leaf, fil_of_rod, ready, partner, lfil);
  if (nb) number_groups(m, member, body, node, elem, rod, rdof, leaf, partner, first, first + NB,
                        first + 2 * NB);
  /* block[] of number_groups: its root array, first[0 .. nb) */
  for (int k = 0; k < nb; k++) {
    m->rigid_block_partner[first[k]] = partner[k] >= 0 ? first[partner[k]] : -1;
    m->rigid_block_fil[first[k]] = lfil[k];
  }
  if (np) number_ports(m, np, pmember, pnode, pelem, prot, first, porder);
  pair_envelope(m);
  store_units(m);
  free(scratch);
  return 1;
}

void sw_rigid_joints_free(swModel *m) {
  free(m->joint_implicit);
  free(m->joint_block);
  free(m->rigid_block);
  free(m->rigid_block_body);
  free(m->rigid_block_node);
  free(m->rigid_block_elem);
  free(m->rigid_block_rot);
  free(m->rigid_block_off);
  free(m->rigid_block_dof);
  free(m->rigid_group_adr);
  free(m->rigid_group_joint_adr);
  free(m->rigid_group_joint);
  free(m->rigid_block_env);
  free(m->rigid_block_reach);
  free(m->joint_port);
  free(m->rod_block);
  free(m->rigid_block_rod);
  free(m->rigid_block_leaf);
  free(m->rigid_block_partner);
  free(m->rigid_block_fil);
  free(m->rigid_leaf_unit);
  free(m->fil_system);
  free(m->rigid_block_port_adr);
  free(m->rigid_port_node);
  free(m->rigid_port_elem);
  free(m->rigid_port_rot);
  free(m->rigid_port_off);
}

/* The end of group g's members in the dense block: its leaves come last. */
static int dense_end(const swModel *m, int g) {
  int end = m->rigid_group_adr[g + 1];
  while (end > m->rigid_group_adr[g] && m->rigid_block_leaf[end - 1] >= 0) end--;
  return end;
}

int sw_rigid_group_unknowns(const swModel *m, int g) {
  const int last = dense_end(m, g) - 1;
  return last < m->rigid_group_adr[g] ? 0 : m->rigid_block_off[last] + m->rigid_block_dof[last];
}

/* Doubles of group g's workspace: its matrix, right-hand side and the
 * factorisation's column (cholesky_solve), then each leaf's and each rod
 * member's (joint_ports.c). */
static size_t group_scratch(const swModel *m, int g) {
  const size_t n = (size_t)sw_rigid_group_unknowns(m, g);
  size_t len = n * n + 2 * n;
  for (int k = m->rigid_group_adr[g]; k < m->rigid_group_adr[g + 1]; k++) {
    if (m->rigid_block_leaf[k] >= 0) len += SW_LEAF_WS;
    else if (m->rigid_block_rod[k] >= 0) len += sw_port_member_scratch(m, k);
  }
  return len;
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

/* The side's 3x6 position rate map, the node's velocity J = [I, -[r]x]. */
static void side_map(const double *r, double *Jpos) {
  memset(Jpos, 0, 18 * sizeof(double));
  for (int c = 0; c < 3; c++) Jpos[6 * c + c] = 1;
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
 * A is n x n, member s's unknowns at rows off[s] .. off[s] + dof[s] - 1,
 * and by the joints the rows of member s are zero left of the rows of
 * member env[s] (the earliest member joined to s, or s), so the rows of the
 * members up to reach[s] (the last whose env is s or before) are the only
 * ones with entries below the diagonal in the columns of s; env and reach
 * number the members from base.  L has the same envelope (no fill-in
 * outside it: George and Liu, Computer Solution of Large Sparse Positive
 * Definite Systems, 1981, ch. 4).
 *
 * The factorisation is right-looking (Golub and Van Loan, sec. 4.2.8, the
 * outer-product form): once column j of L is known, L(i, j) L(k, j) is
 * taken off every A(i, k), j < k <= i, of the rows that reach column j.
 * The updates of one column are independent of one another and run as
 * vector operations, where the left-looking form's dot products were
 * chains of dependent multiply-adds (the muscular snake's groups of 36
 * unknowns spent most of their kick there).  Column j is copied out (col,
 * n doubles of scratch) so that the update of a row reads it contiguously,
 * and kept in row j of A's upper triangle (L^T) as well as in the lower,
 * so that both solves are vector updates along rows: L y = b column by
 * column (b(i) -= L(i, j) y(j), L's column j being L^T's row j), and
 * L^T x = y likewise (b(k) -= L(i, k) x(i), along L's row i).  Every
 * number is taken off in an order set by the rows and columns alone, so a
 * group's solve gives the bits of the same rows within one system over all
 * the groups (whose extra entries are zeros).  The diagonal keeps
 * 1 / L(j, j), the solves' only use of it.
 * Returns 0 if A is not positive definite. */
static int cholesky_solve(double *restrict A, int n, double *restrict rhs, double *restrict col,
                          const int *env, const int *reach, const int *off, const int *dof,
                          int base) {
  for (int sj = 0, j = 0; j < n; j++) {
    if (j == off[sj] + dof[sj]) sj++; /* the member of column j */
    const int rl = reach[sj] - base, last = off[rl] + dof[rl] - 1; /* the last row reaching j */
    double *restrict Aj = A + (size_t)j * n;
    const double djj = Aj[j];
    if (!(djj > 0)) return 0;
    const double inv = 1.0 / sqrt(djj);
    Aj[j] = inv;
    for (int t = sj; t <= rl; t++) { /* L(i, j) of member t's rows, 0 outside the envelope */
      const int inside = off[env[t] - base] <= j;
      for (int i = t == sj ? j + 1 : off[t]; i < off[t] + dof[t]; i++) {
        col[i] = inside ? A[(size_t)i * n + j] * inv : 0.0;
        A[(size_t)i * n + j] = Aj[i] = col[i];
      }
    }
    for (int i = j + 1; i <= last; i++) {
      if (col[i] == 0.0) continue; /* nothing to take off row i */
      const double lij = col[i];
      double *restrict Ai = A + (size_t)i * n;
#pragma omp simd
      for (int k = j + 1; k <= i; k++) Ai[k] -= lij * col[k];
    }
  }
  for (int sj = 0, j = 0; j < n; j++) { /* L y = rhs, column by column */
    if (j == off[sj] + dof[sj]) sj++;
    const double *restrict Lj = A + (size_t)j * n; /* row j of L^T: column j of L */
    const int rl = reach[sj] - base, last = off[rl] + dof[rl] - 1;
    const double y = rhs[j] * Lj[j];
    rhs[j] = y;
#pragma omp simd
    for (int i = j + 1; i <= last; i++) rhs[i] -= Lj[i] * y;
  }
  int si = 0; /* L^T x = y, column by column of L^T, from the last member */
  while (off[si] + dof[si] < n) si++;
  for (int i = n - 1; i >= 0; i--) {
    if (i < off[si]) si--;
    const double *restrict Li = A + (size_t)i * n; /* row i of L */
    const double x = rhs[i] * Li[i];
    rhs[i] = x;
#pragma omp simd
    for (int k = off[env[si] - base]; k < i; k++) rhs[k] -= Li[k] * x;
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
 * element's torque (material components, turned to the lab). */
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
  double Q[9], t[3];
  *mass = m->mass[i];
  element_inertia(m, d, e, Il);
  sw_get3(m, d->force, i, F);
  sw_getQ(m, d->Q, e, Q);
  sw_get3(m, d->torque, e, t);
  sw_matT_vec(F + 3, Q, t);
}

/* Where a joint's side writes in group g's system: the matrix (A, or a
 * leaf's own block or coupling, joint_ports.c), its leading dimension, and
 * the side's first unknown and count there. */
typedef struct {
  int block, leaf; /* the member (-1: still); leaf: its place among the group's leaves, -1 */
  int off, dof;    /* in the dense block: a member's, or a rod member's port's */
} SideSlot;

static SideSlot side_slot(const swModel *m, int j, int side, int first) {
  SideSlot t = {m->joint_block[2 * j + side], -1, 0, 0};
  if (t.block < 0) return t;
  const int k = t.block, q = m->joint_port[2 * j + side];
  t.dof = m->rigid_block_dof[k];
  if (m->rigid_block_leaf[k] >= 0) t.leaf = m->rigid_block_off[k];
  else t.off = m->rigid_block_off[k];
  if (q >= 0) t.off += m->rigid_port_off[q], t.dof = m->rigid_port_rot[q] ? 6 : 3;
  t.block -= first;
  return t;
}

/* The dashpot of a filament in the system (muscle.c, system_part) between
 * its end leaves: h c' b b^T on the unit's rows of each end's node. */
static void unit_dashpot(const swModel *m, const swData *d, double h, double *leaf_ws, int k) {
  const int f = m->rigid_block_fil[k];
  if (f < 0) return;
  const Unit u = leaf_unit(m, leaf_ws, k);
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

/* The trapezoidal loads of group g (the header): its system assembled into
 * A (n x n, n its dense members' unknowns) and rhs, its leaves eliminated
 * and its implicit rods condensed to their ports (joint_ports.c), factored
 * and solved, and the loads of its members replaced: a body's in load[], an
 * attachment's node force and, when a joint couples its element's rotation,
 * element torque, an implicit rod's every node and element.  ws: the
 * leaves' and rods' workspace.  Returns 0 if the block (or a rod's system)
 * could not be factored. */
static int group_kick(const swModel *m, swData *d, double h, int g, double *A, double *rhs,
                      double *ws, double *load) {
  const int first = m->rigid_group_adr[g], nb = m->rigid_group_adr[g + 1] - first;
  const int nd = dense_end(m, g) - first, n = sw_rigid_group_unknowns(m, g);
  const int *off = m->rigid_block_off + first, *dof = m->rigid_block_dof + first;
  double *leaf_ws = ws, *rod_ws = ws + (size_t)(nb - nd) * SW_LEAF_WS;
  memset(A, 0, (size_t)n * n * sizeof(double));
  for (int s = 0, wrod = 0; s < nb; s++) { /* mass, and the right-hand side h F */
    const int k = first + s;
    if (m->rigid_block_rod[k] >= 0) { /* S and S p0 (joint_ports.c) */
      double *w = rod_ws + wrod;
      wrod += (int)sw_port_member_scratch(m, k);
      if (!sw_port_member_assemble(m, d, h, k, w, A, n, off[s], rhs)) return 0;
      continue;
    }
    double M, Il[9], F[6];
    member_inertia(m, d, k, load, &M, Il, F);
    const int leaf = m->rigid_block_leaf[k] >= 0;
    const Unit u = leaf ? leaf_unit(m, leaf_ws, k) : (Unit){0};
    double *B = leaf ? u.ws : A; /* a leaf's unit: A_uu, C, X, b */
    const size_t ld = leaf ? (size_t)u.du : (size_t)n, o = leaf ? (size_t)u.ro : (size_t)off[s];
    double *b = leaf ? B + 432 + o : rhs + o;
    if (leaf && u.owner == k) memset(B, 0, SW_LEAF_WS * sizeof(double));
    for (int i = 0; i < 3; i++) {
      B[(o + i) * ld + o + i] = M;
      if (dof[s] == 6)
        for (int k3 = 0; k3 < 3; k3++) B[(o + 3 + i) * ld + o + 3 + k3] = Il[3 * i + k3];
    }
    for (int i = 0; i < dof[s]; i++) b[i] = h * F[i];
  }
  static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int q = m->rigid_group_joint_adr[g]; q < m->rigid_group_joint_adr[g + 1]; q++) {
    const int j = m->rigid_group_joint[q];
    const swJointDesc *jd = &m->joint[j];
    const SideSlot side[2] = {side_slot(m, j, 0, first), side_slot(m, j, 1, first)};
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
    double Jp[2][18], gl[3] = {0, 0, 0};
    for (int sd = 0; sd < 2; sd++) {
      if (side[sd].block < 0) continue;
      const int b = m->rigid_block_body[first + side[sd].block];
      double r[3] = {0, 0, 0}; /* an attachment's or a port's joint sits on its node */
      if (b >= 0) lever(m, d, b, node[sd], r);
      side_map(r, Jp[sd]);
    }
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
    for (int s = 0; s < 2; s++)
      for (int t = 0; t < 2; t++) {
        const SideSlot *ss = &side[s], *st = &side[t];
        if (ss->block < 0 || st->block < 0) continue;
        const double sign = s == t ? 1.0 : -1.0; /* rates are side b minus side a */
        if (ss->leaf >= 0) { /* a leaf's own block (t = s) or its coupling to the port */
          const Unit u = leaf_unit(m, leaf_ws, first + ss->block);
          if (s == t) add_pair(u.ws, u.du, u.ro, ss->dof, u.ro, ss->dof, wpos, wrot, wlim, Jp[s], Jp[t], PtP, ggT);
          else add_pair(u.ws + 144, u.dQ, u.ro, ss->dof, u.co, st->dof, -wpos, -wrot, -wlim, Jp[s], Jp[t], PtP, ggT);
          continue;
        }
        if (st->leaf >= 0) continue; /* C_a^T: the leaf's elimination uses C_a */
        add_pair(A, n, ss->off, ss->dof, st->off, st->dof, sign * wpos, sign * wrot, sign * wlim,
                 Jp[s], Jp[t], PtP, ggT);
      }
  }
  for (int s = nd; s < nb; s++) { /* the leaves' units eliminated into their ports */
    const Unit u = leaf_unit(m, leaf_ws, first + s);
    if (u.owner != first + s) continue;
    unit_dashpot(m, d, h, leaf_ws, first + s);
    if (!sw_leaf_condense(u.ws, u.du, u.dQ, u.np, u.qoff, u.qdof, A, n, rhs)) return 0;
  }
  if (!cholesky_solve(A, n, rhs, rhs + n, m->rigid_block_env + first, m->rigid_block_reach + first,
                      off, dof, first))
    return 0;
  for (int s = 0, wrod = 0; s < nb; s++) { /* the loads that give du */
    const int k = first + s, b = m->rigid_block_body[k];
    if (m->rigid_block_rod[k] >= 0) {
      sw_port_member_finish(m, d, h, k, rod_ws + wrod, rhs + off[s]);
      wrod += (int)sw_port_member_scratch(m, k);
      continue;
    }
    const double *du = rhs + off[s];
    if (m->rigid_block_leaf[k] >= 0) { /* a unit's velocities, once, by its owner */
      const Unit u = leaf_unit(m, leaf_ws, k);
      if (u.owner == k) sw_leaf_recover(u.ws, u.du, u.dQ, u.np, u.qoff, u.qdof, rhs);
      du = u.ws + 432 + u.ro;
    }
    double M, Il[9], F[6], dL[3] = {0, 0, 0};
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
    const Unit u = leaf_unit(m, leaf_ws, k);
    if (f < 0 || u.owner != k) continue;
    const double *dv[2] = {NULL, NULL}; /* start, end: NULL when clamped */
    const int ends[2] = {k, m->rigid_block_partner[k]};
    for (int i = 0; i < u.np; i++) {
      const int start = m->rigid_block_node[ends[i]] == m->node_adr[m->fil_rod[f]];
      dv[start ? 0 : 1] = u.ws + 432 + (i ? m->rigid_block_dof[k] : 0);
    }
    sw_muscle_ops(m)->system_tension(m, d, f, dv[0], dv[1]);
  }
  return 1;
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
  for (int g = 0; g < m->nrigid_group; g++) {
    const size_t n = (size_t)sw_rigid_group_unknowns(m, g);
    double *rhs = A + n * n;
    ok &= group_kick(m, d, h, g, A, rhs, rhs + 2 * n, load);
    A += group_scratch(m, g);
  }
  return ok;
}
