/* joint_alias.c — ports of one implicit rod that turn the same element.
 *
 * Design.  An implicit rod joins the joints' system as a member whose
 * unknowns are its ports' (joint_ports.c): a joint's node's velocity and,
 * when the joint turns it, the angular velocity of the joint's element.
 * Two joints on neighbouring nodes can turn one element: a rod's last
 * element is its end node's and also, at the node before, the element after
 * that node (joint.c, joint_element), so a bone with a feather tied at its
 * tip and one at the node before (the wing's digits) has two ports whose
 * rotation is the same three unknowns of the rod.  The condensation's
 * C = E^T A^-1 E then has two equal rows and columns: singular in exact
 * arithmetic, factored by round-off, and S = C^-1 holds numbers of the size
 * of 1 / round-off, which amplified the round-off of the state 14-fold a
 * step at 1 us (the resolved wing's digits, a scene of two fixed joints
 * on a bone's last two nodes: tests/runtime/test_joint_alias.c).
 *
 * A port whose rotation is an earlier kept port's element (its alias,
 * m->rigid_port_alias, set here at setup) leaves that rotation out of the
 * condensation (E has no columns there, C the identity's rows), and in the
 * group's block its three rows and columns are folded into its target's:
 * with T the map from the group's unknowns without them to all of them
 * (x_alias = x_target), the block becomes T^T K T and the right-hand side
 * T^T b, which is what the joints and leaves on both ports add to the one
 * rotation (K_tt + K_ta + K_at + K_aa on the target's block, K_tc + K_ac on
 * its rows); the alias's rows are then those of the identity with zero on
 * the right, and after the solve its unknowns take the target's values, so
 * that the joints' finish and the leaves read the rotation where they left
 * it.  A port's translation is its node's alone (one port per node).
 */
#include <stdlib.h>
#include "sinew.h"
#include "internal.h"

/* Whether group g condenses port q (a rod member's): every port but a band
 * port of a member's band path (rigid_port_moff < 0), whose block is added
 * in the rod's band.  The band path (rigid_group_band 1) condenses none,
 * and reads no alias; its ports are marked as its dense path would need
 * them (tests compare the two paths). */
static int kept(const swModel *m, int g, int q) {
  return m->rigid_group_band[g] != 2 || m->rigid_port_moff[q] >= 0;
}

int sw_port_alias_setup(swModel *m) {
  const size_t NP = (size_t)(m->nrigid_port > 0 ? m->nrigid_port : 1);
  m->rigid_port_alias = malloc(NP * sizeof(int));
  if (!m->rigid_port_alias) return 0;
  for (int q = 0; q < m->nrigid_port; q++) m->rigid_port_alias[q] = -1;
  for (int g = 0; g < m->nrigid_group; g++) /* (on the band path too: its dense path's) */
    for (int k = m->rigid_group_adr[g]; k < m->rigid_group_adr[g + 1]; k++) {
      if (m->rigid_block_rod[k] < 0) continue;
      const int q0 = m->rigid_block_port_adr[k], q1 = m->rigid_block_port_adr[k + 1];
      for (int q = q0; q < q1; q++) {
        if (!m->rigid_port_rot[q] || !kept(m, g, q)) continue;
        for (int t = q0; t < q && m->rigid_port_alias[q] < 0; t++)
          if (m->rigid_port_rot[t] && kept(m, g, t) && m->rigid_port_alias[t] < 0 &&
              m->rigid_port_elem[t] == m->rigid_port_elem[q])
            m->rigid_port_alias[q] = t;
      }
    }
  return 1;
}

/* Port q's first rotation unknown in group g's block (off: the group's
 * numbering of its members, as rigid_joint.c's group_off). */
static int rot_row(const swModel *m, int g, int k, int q, const int *off) {
  const int band = m->rigid_group_band[g] == 2;
  return band ? m->rigid_port_moff[q] + 3 : off[k] + m->rigid_port_off[q] + 3;
}

/* The stored entry (i, j) of the lower triangle. */
static double *at(double *A, int n, int i, int j) {
  return i >= j ? A + (size_t)i * (size_t)n + j : A + (size_t)j * (size_t)n + i;
}

/* The fold of rows a .. a + 2 into t .. t + 2 (t < a, both in member k),
 * over the entries the envelope stores: member k's own rows, its rows'
 * columns of the members from env[k], and the rows of the later members
 * whose envelope reaches k. */
static void fold(const swModel *m, int g, int k, int t, int a, const int *off, const int *dof,
                 double *A, int n, double *rhs) {
  const int first = m->rigid_group_adr[g], last = m->rigid_group_adr[g + 1];
  for (int s = first; s < last && m->rigid_block_leaf[s] < 0; s++) {
    if (s != k && (s < k ? s < m->rigid_block_env[k] : m->rigid_block_env[s] > k)) continue;
    for (int c = off[s]; c < off[s] + dof[s]; c++) {
      if ((c >= t && c < t + 3) || (c >= a && c < a + 3)) continue;
      for (int i = 0; i < 3; i++) {
        *at(A, n, t + i, c) += *at(A, n, a + i, c);
        *at(A, n, a + i, c) = 0;
      }
    }
  }
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      T[3 * i + j] = *at(A, n, t + i, t + j) + *at(A, n, a + i, t + j) + *at(A, n, t + i, a + j) +
                     *at(A, n, a + i, a + j);
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j <= i; j++) {
      *at(A, n, t + i, t + j) = T[3 * i + j];
      *at(A, n, a + i, a + j) = i == j;
    }
    for (int j = 0; j < 3; j++) *at(A, n, a + i, t + j) = 0;
    rhs[t + i] += rhs[a + i];
    rhs[a + i] = 0;
  }
}

void sw_port_alias_fold(const swModel *m, int g, const int *off, const int *dof, double *A,
                        int n, double *rhs) {
  if (m->rigid_group_band[g] == 1) return;
  for (int k = m->rigid_group_adr[g]; k < m->rigid_group_adr[g + 1]; k++) {
    if (m->rigid_block_rod[k] < 0) continue;
    for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++) {
      const int t = m->rigid_port_alias[q];
      if (t >= 0)
        fold(m, g, k, rot_row(m, g, k, t, off), rot_row(m, g, k, q, off), off, dof, A, n, rhs);
    }
  }
}

void sw_port_alias_copy(const swModel *m, int g, const int *off, double *du) {
  if (m->rigid_group_band[g] == 1) return;
  for (int k = m->rigid_group_adr[g]; k < m->rigid_group_adr[g + 1]; k++) {
    if (m->rigid_block_rod[k] < 0) continue;
    for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++) {
      const int t = m->rigid_port_alias[q];
      if (t < 0) continue;
      const int rt = rot_row(m, g, k, t, off), ra = rot_row(m, g, k, q, off);
      for (int i = 0; i < 3; i++) du[ra + i] = du[rt + i];
    }
  }
}
