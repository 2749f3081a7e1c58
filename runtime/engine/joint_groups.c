/* joint_groups.c — which joints the joints' system takes, and its members,
 * groups, ports and leaves (the setup of rigid_joint.c's system).
 *
 * Design.  Under integrator = imex a joint is implicit when each side is
 * something the system holds (a moving rigid body, a port of an implicit
 * rod, a free node of an explicit rod, or still: space, a fixed body, a
 * clamped node) and a body or an implicit rod moves on one side; a joint
 * between two explicit rods stays explicit.  The sides become the system's
 * members, numbered in the order the joints first meet them: a body (six
 * unknowns), an attachment (a node, three, and its element's three when a
 * joint turns it), an implicit rod (its ports, joint_ports.c).  Union-find
 * over the implicit joints (and over each filament's two ends, which its
 * Hill damping couples) gives the groups, the connected components, each
 * one dense block of the system with its envelope (rigid_joint.c).  Leaves,
 * attachments (or implicit rods on one port of their own) whose joints all
 * reach one port, go last in their group and
 * are eliminated before it is factored; a filament whose ends are both
 * such leaves (or clamped) has its damping solved in the system, its ends
 * eliminated as one unit, and so does one whose ends are attachments that
 * are not leaves (dense_ends), its damper between their unknowns.  A group
 * of one implicit rod and leaves alone takes the band path (band_group,
 * joint_ports.c): no dense block, its leaves eliminated into the rod's
 * band; in another group, a rod member's ports that only lone leaves reach
 * go into its band likewise, the member keeping its other ports
 * (member_bands).  All of it is computed once, at setup, into the model's rigid_* arrays;
 * rigid_joint.c's kick only reads them.
 */
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
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

/* The kind of the boundary condition on node `node` of rod `rod`, or -1.  A
 * clamp that lets go (until) is a prescribed motion like a velocity. */
static int bc_on_node(const swModel *m, int rod, int node) {
  for (int k = 0; k < m->nbc; k++)
    if (m->bc[k].rod == rod && sw_bc_node(m, &m->bc[k]) == node)
      return m->bc[k].kind == SW_BC_CLAMP && m->bc[k].until > 0 ? SW_BC_VELOCITY : (int)m->bc[k].kind;
  return -1;
}

/* A joint's side at setup: a moving body, an attachment, a port of an
 * implicit rod (joint_ports.c), or still (space, a fixed body, a clamped
 * node when the joint does not turn its element, which turns against the
 * clamp's couple: boundary.c). */
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
  const int turns = jd->kind != SW_JOINT_SPHERICAL || sw_joint_limited(jd);
  if (bc == SW_BC_CLAMP) s.ok = !turns; /* still: the node; the end element turns against the clamp */
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

/* Filaments whose ends are dense members of the system (issue 31): an
 * implicit filament not solved through ports (hill_ready) whose every end
 * is an attachment member that is not a leaf, or clamped, has its Hill
 * damping solved in the system too, as h c' b b^T between its end nodes'
 * unknowns (rigid_joint.c, muscle_implicit.c's system_part).  Otherwise its
 * own solve would take its ends as free masses under the kick's loads, the
 * joints' springs among them, and carry those springs' forces into the
 * tension explicitly: on the muscular snake, whose filaments are tied to
 * rigid tendons, that grew a lateral swing of the tendons (365 Hz) from a
 * step of 45 us (spans of 0.15 of the body) or 63 us (0.35).  fend[2 f +
 * e]: the member at end e of filament f (setup's numbering), -1 when
 * clamped, or both -1 when f is not such a filament; fil_system marked.
 * at_node: the member on each node slot, leaf: each member's leaf port. */
static void dense_ends(swModel *m, const int *at_node, const int *leaf, const int *ready, int *fend) {
  for (int f = 0; f < m->nfil; f++) {
    const int bits = m->fil_implicit[f], r = m->fil_rod[f];
    const int ends[2] = {m->node_adr[r], m->node_adr[r] + m->rod_nelem[r]};
    const int held[2] = {(bits & SW_FIL_HELD_START) != 0, (bits & SW_FIL_HELD_END) != 0};
    fend[2 * f] = fend[2 * f + 1] = -1;
    if (!(bits & SW_FIL_IMPLICIT) || ready[f]) continue;
    int ok = 1, k[2];
    for (int e = 0; e < 2; e++) {
      k[e] = held[e] ? -1 : at_node[ends[e]];
      if (!held[e] && (k[e] < 0 || leaf[k[e]] >= 0)) ok = 0;
    }
    if (!ok || (k[0] < 0 && k[1] < 0)) continue;
    fend[2 * f] = k[0], fend[2 * f + 1] = k[1];
    m->fil_system[f] = 1;
  }
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

/* The dense members (not leaves) of every group, group by group, each
 * group's in the order joint_order.c chooses (a new array, NULL when out of
 * memory).  Its edges are what the envelope takes (number_groups below,
 * pair_envelope): the implicit joints between dense members, each dense
 * filament's two ends, and the ports' members of each leaf pair; its
 * unknowns a body's six, a rod member's ports', an attachment's three and
 * its element's three when a joint turns it.  Members numbered as setup met
 * them; root and group_of as number_groups has them. */
static int *dense_member_order(const swModel *m, const int *member, const int *body, const int *rod,
                               const int *rdof, const int *leaf, const int *leaf_member,
                               const int *partner, const int *fend, const int *root,
                               const int *group_of) {
  const int nb = m->nrigid_block;
  const size_t N = (size_t)nb, E = (size_t)m->njoint + (size_t)m->nfil + N + 1;
  int *group = malloc(N * sizeof(int)), *dof = malloc(N * sizeof(int));
  int *edges = malloc(2 * E * sizeof(int)), *order = malloc(N * sizeof(int));
  int ok = group && dof && edges && order, ne = 0;
  for (int s = 0; ok && s < nb; s++) {
    group[s] = leaf[s] < 0 ? group_of[root[s]] : -1;
    dof[s] = body[s] >= 0 ? 6 : rod[s] >= 0 ? rdof[s] : 3;
  }
  for (int j = 0; ok && j < m->njoint; j++) {
    const int sa = member[2 * j], sb = member[2 * j + 1];
    if (!m->joint_implicit[j]) continue;
    const swJointDesc *jd = &m->joint[j]; /* an attachment whose element it turns */
    if (jd->kind != SW_JOINT_SPHERICAL || sw_joint_limited(jd))
      for (int side = 0; side < 2; side++) {
        const int k = member[2 * j + side];
        if (k >= 0 && body[k] < 0 && rod[k] < 0) dof[k] = 6;
      }
    if (sa >= 0 && sb >= 0 && leaf[sa] < 0 && leaf[sb] < 0) edges[2 * ne] = sa, edges[2 * ne + 1] = sb, ne++;
  }
  for (int f = 0; ok && f < m->nfil; f++)
    if (fend[2 * f] >= 0 && fend[2 * f + 1] >= 0)
      edges[2 * ne] = fend[2 * f], edges[2 * ne + 1] = fend[2 * f + 1], ne++;
  for (int s = 0; ok && s < nb; s++)
    if (partner[s] > s && leaf_member[s] >= 0 && leaf_member[partner[s]] >= 0 &&
        leaf_member[s] != leaf_member[partner[s]])
      edges[2 * ne] = leaf_member[s], edges[2 * ne + 1] = leaf_member[partner[s]], ne++;
  if (ok) ok = sw_order_members(nb, group, m->nrigid_group, dof, ne, edges, order);
  free(group), free(dof), free(edges);
  if (!ok) free(order), order = NULL;
  return order;
}

/* The groups of the system, its members and joints numbered group by group
 * (the header).  On entry the members are numbered in the order the joints
 * first meet them (the one system's numbering, which the groups keep):
 * member[2 j + side] is that number of joint j's side (-1: still), and
 * body, node and elem describe each member; root, group_of and next are
 * scratch of nb ints.  On return m->joint_block holds the blocks. */
static int number_groups(swModel *m, const int *member, const int *body, const int *node,
                         const int *elem, const int *rod, const int *rdof, const int *leaf,
                         const int *leaf_member, const int *partner, const int *fend, int *root,
                         int *group_of, int *next) {
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
  for (int f = 0; f < m->nfil; f++) /* a filament's dense ends (dense_ends), likewise */
    if (fend[2 * f] >= 0 && fend[2 * f + 1] >= 0) {
      const int ra = find_root(root, fend[2 * f]), rb = find_root(root, fend[2 * f + 1]);
      if (ra != rb) root[ra > rb ? ra : rb] = ra < rb ? ra : rb;
    }
  for (int s = 0; s < nb; s++) root[s] = find_root(root, s);
  int ngroup = 0; /* the groups, in the order of their first member */
  for (int s = 0; s < nb; s++)
    if (group_of[root[s]] < 0) group_of[root[s]] = ngroup++;
  m->nrigid_group = ngroup;
  /* the order of each group's dense members (joint_order.c) */
  int *dense_order = dense_member_order(m, member, body, rod, rdof, leaf, leaf_member, partner, fend,
                                        root, group_of);
  if (!dense_order) return 0;
  /* the blocks: sorted by group, each group's dense members in that order,
   * its leaves (joint_ports.c) after them in the order setup met them */
  int *adr = m->rigid_group_adr, *jadr = m->rigid_group_joint_adr, *block = root;
  for (int g = 0; g <= ngroup; g++) adr[g] = jadr[g] = 0;
  for (int s = 0; s < nb; s++) adr[group_of[root[s]] + 1]++;
  for (int g = 0; g < ngroup; g++) adr[g + 1] += adr[g];
  memcpy(next, adr, (size_t)ngroup * sizeof(int));
  int ndense = 0;
  for (int s = 0; s < nb; s++) ndense += leaf[s] < 0;
  for (int t = 0; t < ndense + nb; t++) { /* the dense members, then the leaves */
    const int s = t < ndense ? dense_order[t] : t - ndense;
    if (t >= ndense && leaf[s] < 0) continue;
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
  free(dense_order);
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
  for (int f = 0; f < m->nfil; f++) { /* a dense filament's damping couples its ends */
    if (fend[2 * f] < 0 || fend[2 * f + 1] < 0) continue;
    const int sa = block[fend[2 * f]], sb = block[fend[2 * f + 1]];
    const int lo = sa < sb ? sa : sb, hi = sa < sb ? sb : sa;
    if (lo < m->rigid_block_env[hi]) m->rigid_block_env[hi] = lo;
  }
  for (int s = 0; s < nb; s++) m->rigid_block_reach[s] = s;
  for (int t = 0; t < nb; t++)
    for (int s = m->rigid_block_env[t]; s < t; s++)
      if (m->rigid_block_reach[s] < t) m->rigid_block_reach[s] = t;
  return 1;
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
      off += sw_port_dof(m, t);
    }
  for (int q = 0; q < 2 * m->njoint; q++)
    if (m->joint_port[q] >= 0) m->joint_port[q] = order[m->joint_port[q]];
  for (int k = 0; k < nb; k++)
    if (m->rigid_block_leaf[k] >= 0) m->rigid_block_leaf[k] = order[m->rigid_block_leaf[k]];
  for (int k = 0; k < nb; k++)
    if (m->rigid_block_rod[k] >= 0) m->rod_block[m->rigid_block_rod[k]] = k;
}

/* Each member's leaf port (joint_ports.c): the one port all its implicit
 * joints reach, or -1 (a joint to anything else, or to two ports).  An
 * attachment can be a leaf, and so can an implicit rod whose joints all
 * sit on one port of its own (an implicit barb on its rachis: rod leaves),
 * its leaf port a dense member's: of two rods that are each other's only
 * neighbour, the one met first stays dense.  pmember: each port's member
 * as setup met them; rod_leaves 0 keeps every rod dense (the tests' other
 * path, sw_rigid_joints_setup_leaves). */
static void find_leaves(const swModel *m, int nb, const int *member, const int *node, const int *rod,
                        const int *pmember, int rod_leaves, int *leaf) {
  int *own = rod_leaves ? malloc((size_t)(nb > 0 ? nb : 1) * sizeof(int)) : NULL; /* a rod's one port */
  for (int k = 0; k < nb; k++) {
    leaf[k] = (node[k] >= 0 && rod[k] < 0) || (rod[k] >= 0 && own) ? -2 : -1; /* -2: none yet */
    if (own) own[k] = -2;
  }
  for (int j = 0; j < m->njoint; j++) {
    if (!m->joint_implicit[j]) continue;
    for (int side = 0; side < 2; side++) {
      const int k = member[2 * j + side], other = 2 * j + 1 - side;
      if (k < 0 || leaf[k] == -1) continue;
      const int q = m->joint_port[other];
      if (q < 0 || (leaf[k] != -2 && leaf[k] != q)) leaf[k] = -1;
      else leaf[k] = q;
      if (rod[k] < 0 || leaf[k] < 0) continue;
      const int mine = m->joint_port[2 * j + side]; /* a rod leaf: one port of its own */
      if (own[k] != -2 && own[k] != mine) leaf[k] = -1;
      else own[k] = mine;
    }
  }
  for (int k = 0; k < nb; k++)
    if (leaf[k] == -2) leaf[k] = -1;
  for (int k = 0; k < nb; k++) /* a rod leaf hangs on a dense member's port, and is no filament */
    for (int f = 0; rod[k] >= 0 && leaf[k] >= 0 && f < m->nfil; f++)
      if (m->fil_rod[f] == rod[k]) leaf[k] = -1;
  for (int k = 0; k < nb; k++)
    if (rod[k] >= 0 && leaf[k] >= 0 && leaf[pmember[leaf[k]]] >= 0) leaf[k] = -1;
  free(own);
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

/* Every leaf's unit (rigid_joint.c's Unit, m->rigid_leaf_unit): the leaf
 * itself, or it and its partner, whose lower block owns the workspace; the
 * leaf's rows in it, its port's columns in the coupling, the unit's
 * unknowns and its ports', and the ports' places in the dense block. */
static void store_units(swModel *m) {
  const int *off = m->rigid_block_off, *dof = m->rigid_block_dof;
  for (int k = 0; k < m->nrigid_block; k++) {
    if (m->rigid_block_leaf[k] < 0) continue;
    const int p = m->rigid_block_partner[k], owner = p >= 0 && p < k ? p : k;
    const int mate = owner == k ? p : k; /* the owner's partner, or -1 */
    int *w = m->rigid_leaf_unit + SW_LEAF_UNIT * (size_t)k;
    w[0] = owner;
    w[1] = owner == k ? 0 : dof[owner];
    w[2] = owner == k ? 0 : sw_port_dof(m, m->rigid_block_leaf[owner]);
    w[5] = mate >= 0 ? 2 : 1;
    w[3] = w[4] = 0;
    w[7] = w[9] = 0;
    for (int i = 0; i < w[5]; i++) {
      const int leaf = i ? mate : owner, q = m->rigid_block_leaf[leaf];
      w[8 + i] = sw_port_dof(m, q);
      w[6 + i] = off[port_member(m, q)] + m->rigid_port_off[q];
      w[3] += dof[leaf];
      w[4] += w[8 + i];
    }
  }
  for (int g = 0; g < m->nrigid_group; g++) /* the workspaces, owner after owner */
    for (int k = m->rigid_group_adr[g], at = 0; k < m->rigid_group_adr[g + 1]; k++) {
      int *w = m->rigid_leaf_unit + SW_LEAF_UNIT * (size_t)k;
      if (m->rigid_block_leaf[k] < 0 || w[0] != k) continue;
      w[10] = at;
      at += (int)sw_unit_size(w[3], w[4]);
    }
  for (int k = 0; k < m->nrigid_block; k++) { /* a partner's: its owner's */
    int *w = m->rigid_leaf_unit + SW_LEAF_UNIT * (size_t)k;
    if (m->rigid_block_leaf[k] >= 0 && w[0] != k)
      w[10] = m->rigid_leaf_unit[SW_LEAF_UNIT * (size_t)w[0] + 10];
  }
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

/* Whether group g takes the band path (joint_ports.c, sw_band_group_solve):
 * its one dense member an implicit rod, every other a leaf alone (no
 * filament's pair, which would join two ports), no joint between two of
 * the rod's ports, no dense filament, and each port's element next to its
 * node (rows within the half-bandwidth). */
static int band_group(const swModel *m, int g) {
  const int first = m->rigid_group_adr[g], last = m->rigid_group_adr[g + 1];
  if (m->rigid_block_rod[first] < 0) return 0;
  for (int k = first + 1; k < last; k++)
    if (m->rigid_block_leaf[k] < 0 || m->rigid_block_partner[k] >= 0) return 0;
  for (int q = m->rigid_group_joint_adr[g]; q < m->rigid_group_joint_adr[g + 1]; q++) {
    const int j = m->rigid_group_joint[q];
    if (m->joint_block[2 * j] == first && m->joint_block[2 * j + 1] == first) return 0;
  }
  for (int f = 0; f < 2 * m->nfil; f++)
    if (m->fil_block[f] >= first && m->fil_block[f] < last) return 0;
  const int r = m->rigid_block_rod[first];
  for (int q = m->rigid_block_port_adr[first]; q < m->rigid_block_port_adr[first + 1]; q++) {
    const int i = m->rigid_port_node[q] - m->node_adr[r], e = m->rigid_port_elem[q] - m->elem_adr[r];
    if (m->rigid_port_rot[q] && e != i && e != i - 1) return 0;
  }
  return 1;
}

/* The band path of a member (joint_ports.c): in a group not on the band
 * path, a port of a rod member is a band port when lone leaves are joined
 * to it (no filament's, whose dashpot or pair stays dense) and nothing but
 * them and still sides (space, a fixed body, a clamped node), and its
 * element is next to its node; a member keeps its other ports, at least
 * one (none would make the group one rod and leaves: the band path's).  A
 * group with a band port is marked 2, its members' unknowns renumbered
 * over the kept ports (rigid_block_moff, _mdof, rigid_port_moff); the
 * dense numbering stays, for the dense path (rigid_group_band 0). */
static int member_bands(swModel *m) {
  const size_t NB = (size_t)(m->nrigid_block > 0 ? m->nrigid_block : 1);
  const size_t NP = (size_t)(m->nrigid_port > 0 ? m->nrigid_port : 1);
  m->rigid_block_moff = malloc(NB * sizeof(int));
  m->rigid_block_mdof = malloc(NB * sizeof(int));
  m->rigid_port_moff = malloc(NP * sizeof(int));
  int *lone = calloc(2 * NP, sizeof(int)), *other = lone ? lone + NP : NULL;
  if (!m->rigid_block_moff || !m->rigid_block_mdof || !m->rigid_port_moff || !lone) {
    free(lone);
    return 0;
  }
  memcpy(m->rigid_block_moff, m->rigid_block_off, (size_t)m->nrigid_block * sizeof(int));
  memcpy(m->rigid_block_mdof, m->rigid_block_dof, (size_t)m->nrigid_block * sizeof(int));
  memcpy(m->rigid_port_moff, m->rigid_port_off, (size_t)m->nrigid_port * sizeof(int));
  for (int k = 0; k < m->nrigid_block; k++) {
    const int q = m->rigid_block_leaf[k];
    if (q < 0) continue;
    if (m->rigid_block_partner[k] >= 0 || m->rigid_block_fil[k] >= 0) other[q] = 1;
    else lone[q]++;
  }
  for (int j = 0; j < m->njoint; j++)
    for (int side = 0; m->joint_implicit[j] && side < 2; side++) {
      const int q = m->joint_port[2 * j + side], ob = m->joint_block[2 * j + 1 - side];
      if (q >= 0 && ob >= 0 && m->rigid_block_leaf[ob] < 0) other[q] = 1; /* a dense member, or a port */
    }
  for (int g = 0; g < m->nrigid_group; g++) {
    const int first = m->rigid_group_adr[g], last = m->rigid_group_adr[g + 1];
    int nband = 0, dense_fil = 0; /* a dense filament (rigid_joint.c) reads the dense numbering */
    for (int f = 0; f < 2 * m->nfil; f++) dense_fil |= m->fil_block[f] >= first && m->fil_block[f] < last;
    if (m->rigid_group_band[g] || dense_fil) continue;
    for (int k = first; k < last; k++) {
      const int r = m->rigid_block_rod[k];
      if (r < 0 || m->rigid_block_leaf[k] >= 0) continue; /* a rod leaf keeps its one port */
      int kept = 0, o = 0;
      for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++) {
        const int i = m->rigid_port_node[q] - m->node_adr[r], e = m->rigid_port_elem[q] - m->elem_adr[r];
        other[q] |= !lone[q] || (m->rigid_port_rot[q] && e != i && e != i - 1);
        kept += other[q];
      }
      for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++) {
        if (kept && !other[q]) m->rigid_port_moff[q] = -1 - nband++;
        else m->rigid_port_moff[q] = o, o += sw_port_dof(m, q);
      }
      m->rigid_block_mdof[k] = o;
    }
    if (!nband) continue;
    m->rigid_group_band[g] = 2;
    for (int k = first, o = 0; k < last; k++)
      if (m->rigid_block_leaf[k] < 0) m->rigid_block_moff[k] = o, o += m->rigid_block_mdof[k];
    for (int k = first; k < last; k++) { /* a kept port's place in the group's block */
      if (m->rigid_block_rod[k] < 0 || m->rigid_block_leaf[k] >= 0) continue;
      for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++)
        if (m->rigid_port_moff[q] >= 0) m->rigid_port_moff[q] += m->rigid_block_moff[k];
    }
  }
  free(lone);
  return 1;
}

/* m->rigid_group_band (the band path, then a member's), then the batches of
 * groups of one shape (joint_lanes.c), which leave those groups alone. */
static int finish_groups(swModel *m) {
  m->rigid_group_band = calloc((size_t)(m->nrigid_group > 0 ? m->nrigid_group : 1), sizeof(int));
  if (!m->rigid_group_band) return 0;
  for (int g = 0; g < m->nrigid_group; g++) m->rigid_group_band[g] = band_group(m, g);
  return member_bands(m) && sw_port_alias_setup(m) && sw_group_lanes_setup(m);
}

int sw_rigid_joints_setup(swModel *m) { return sw_rigid_joints_setup_leaves(m, 1); }

int sw_rigid_joints_setup_leaves(swModel *m, int rod_leaves) {
  const size_t J = (size_t)(m->njoint ? m->njoint : 1), B = (size_t)(m->nrigid ? m->nrigid : 1);
  const size_t R = (size_t)(m->nrod ? m->nrod : 1);
  const size_t NB = B + 2 * J; /* members: at most every body and every joint's two sides */
  m->rigid_group_lanes = m->rigid_group_band = NULL;
  m->rigid_block_moff = m->rigid_block_mdof = m->rigid_port_moff = m->rigid_port_alias = NULL;
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
  m->rigid_leaf_unit = malloc(SW_LEAF_UNIT * NB * sizeof(int));
  m->fil_system = calloc((size_t)(m->nfil ? m->nfil : 1), sizeof(int));
  m->fil_block = malloc(2 * (size_t)(m->nfil ? m->nfil : 1) * sizeof(int));
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
      !m->rigid_block_partner || !m->rigid_block_fil || !m->fil_system || !m->fil_block ||
      !m->rigid_leaf_unit ||
      !m->rigid_block_port_adr || !m->rigid_port_node || !m->rigid_port_elem ||
      !m->rigid_port_rot || !m->rigid_port_off || !m->rigid_group_adr ||
      !m->rigid_group_joint_adr || !m->rigid_group_joint || !m->rigid_block_env ||
      !m->rigid_block_reach)
    return 0;
  for (int b = 0; b < m->nrigid; b++) m->rigid_block[b] = -1;
  for (size_t r = 0; r < R; r++) m->rod_block[r] = -1;
  for (int q = 0; q < 2 * m->nfil; q++) m->fil_block[q] = -1;
  for (size_t q = 0; q < 2 * J; q++) m->joint_block[q] = m->joint_port[q] = -1;
  m->rigid_group_adr[0] = m->rigid_group_joint_adr[0] = m->rigid_block_port_adr[0] = 0;
  if (m->integrator != SW_IMEX) return finish_groups(m);
  /* the members in the order the joints first meet them: member[2 j + side]
   * their number, body/node/elem/rod what each is; the ports likewise */
  const size_t S = (size_t)m->stride;
  const size_t F = (size_t)(m->nfil ? m->nfil : 1);
  int *scratch = malloc((2 * J + 12 * NB + 2 * S + 10 * J + 2 * R + 3 * F) * sizeof(int));
  if (!scratch) return 0;
  int *member = scratch, *body = member + 2 * J, *node = body + NB, *elem = node + NB;
  int *rod = elem + NB, *rdof = rod + NB, *leaf = rdof + NB;
  int *first = leaf + NB; /* rigid bodies' numbers (nrigid <= NB), then number_groups' scratch */
  int *at_node = first + 4 * NB; /* the attachment on each node slot, or -1 */
  int *port_at = at_node + S;    /* the port on each node slot, or -1 */
  int *pmember = port_at + S, *pnode = pmember + 2 * J, *pelem = pnode + 2 * J;
  int *prot = pelem + 2 * J, *porder = prot + 2 * J; /* 2 J + NB: number_ports' */
  int *rod_first = porder + 2 * J + NB, *fil_of_rod = rod_first + R, *ready = fil_of_rod + R;
  int *fend = ready + F; /* dense_ends: each filament's end members, -1 */
  int *leaf_member = fend + 2 * F; /* each leaf's port's member, -1 */
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
    if (sw_joint_has_arm(&m->joint[j])) continue; /* an arm's couple: explicit (joint.c) */
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
  find_leaves(m, nb, member, node, rod, pmember, rod_leaves, leaf);
  dense_ends(m, at_node, leaf, ready, fend);
  int *partner = at_node, *lfil = port_at; /* the node maps are read no more (S >= nb) */
  pair_leaves(m, nb, member, leaf, fil_of_rod, ready, partner, lfil);
  for (int k = 0; k < nb; k++) /* each leaf's port's member: a leaf pair's coupling */
    leaf_member[k] = leaf[k] >= 0 ? pmember[leaf[k]] : -1;
  if (nb && !number_groups(m, member, body, node, elem, rod, rdof, leaf, leaf_member, partner, fend,
                           first, first + NB, first + 2 * NB)) {
    free(scratch);
    return 0;
  }
  /* block[] of number_groups: its root array, first[0 .. nb) */
  for (int k = 0; k < nb; k++) {
    m->rigid_block_partner[first[k]] = partner[k] >= 0 ? first[partner[k]] : -1;
    m->rigid_block_fil[first[k]] = lfil[k];
  }
  for (int q = 0; q < 2 * m->nfil; q++) m->fil_block[q] = fend[q] >= 0 ? first[fend[q]] : -1;
  if (np) number_ports(m, np, pmember, pnode, pelem, prot, first, porder);
  pair_envelope(m);
  store_units(m);
  free(scratch);
  return finish_groups(m);
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
  free(m->rigid_group_lanes);
  free(m->rigid_group_band);
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
  free(m->fil_block);
  free(m->rigid_block_port_adr);
  free(m->rigid_port_node);
  free(m->rigid_port_elem);
  free(m->rigid_port_rot);
  free(m->rigid_port_off);
  free(m->rigid_block_moff);
  free(m->rigid_block_mdof);
  free(m->rigid_port_moff);
  free(m->rigid_port_alias);
}
