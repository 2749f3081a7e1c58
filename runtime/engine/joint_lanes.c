/* joint_lanes.c — groups of the joints' system that have one shape,
 * factored and solved together, one group per vector lane.
 *
 * Design.  A group's block is small (the muscular snake's pair group: 60
 * unknowns, 573 entries below the diagonal within its envelope) and its
 * envelope Cholesky (joint_envelope.c, sw_envelope_cholesky_solve) is mostly short rows:
 * a row's update from one column is a vector loop of a few entries, whose
 * set-up, remainder and the column's copy cost more than its multiply-adds
 * (on the four-pair snake, after the members' order of joint_order.c, the
 * factorisation was still 30% of a step for 3455 multiply-adds a group).
 * Scenes repeat their parts: the snake's pairs, a hand's fingers, a walker's
 * legs give groups whose members, unknowns and envelope are the same
 * (their shape), only their numbers differing.  Up to SW_GROUP_LANES
 * consecutive groups of one shape are found at setup (rigid_group_lanes:
 * how many from each first one, 0 inside a batch); each step their blocks,
 * assembled apart as before, are copied into one interleaved block, entry
 * (i, k) of group u at [i n + k][u], and factored and solved there by the
 * scalar algorithm with every number operation written once for all lanes:
 * each lane does exactly its group's operations, in the same order (a row
 * the scalar code skips because its factor entry is 0 keeps its numbers in
 * that lane), so the bits are those of solving each group alone, and the
 * vector is across the groups instead of along a row.  A lane whose block
 * is not positive definite sends the batch back to the scalar solve, group
 * by group, from the blocks it copied (which it leaves as they were). */
#include <math.h>
#include <stdlib.h>
#include "sinew.h"
#include "internal.h"

#define LANES SW_GROUP_LANES
_Static_assert(LANES == 4, "take_off and the copy in write four lanes");

/* The dense members of group g: from its first block to its first leaf. */
static int dense_members(const swModel *m, int g) {
  const int first = m->rigid_group_adr[g];
  int end = m->rigid_group_adr[g + 1];
  while (end > first && m->rigid_block_leaf[end - 1] >= 0) end--;
  return end - first;
}

/* Whether groups a and b have one shape: dense members of the same
 * unknowns, at the same places, with the same envelope and reach. */
static int same_shape(const swModel *m, int a, int b) {
  const int na = dense_members(m, a), fa = m->rigid_group_adr[a], fb = m->rigid_group_adr[b];
  if (na != dense_members(m, b) || na == 0) return 0;
  if (m->rigid_group_band[a] || m->rigid_group_band[b]) return 0; /* solved in a rod's band */
  for (int s = 0; s < na; s++)
    if (m->rigid_block_dof[fa + s] != m->rigid_block_dof[fb + s] ||
        m->rigid_block_off[fa + s] != m->rigid_block_off[fb + s] ||
        m->rigid_block_env[fa + s] - fa != m->rigid_block_env[fb + s] - fb ||
        m->rigid_block_reach[fa + s] - fa != m->rigid_block_reach[fb + s] - fb)
      return 0;
  return 1;
}

int sw_group_lanes_setup(swModel *m) {
  const int ng = m->nrigid_group;
  m->rigid_group_lanes = malloc((size_t)(ng > 0 ? ng : 1) * sizeof(int));
  if (!m->rigid_group_lanes) return 0;
  for (int g = 0, start = 0; g < ng; g++) {
    if (g > 0 && m->rigid_group_lanes[start] < LANES && same_shape(m, start, g)) {
      m->rigid_group_lanes[start]++;
      m->rigid_group_lanes[g] = 0;
    } else {
      m->rigid_group_lanes[start = g] = 1;
    }
  }
  return 1;
}

size_t sw_rigid_lanes_scratch(const swModel *m) {
  size_t len = 0;
  for (int g = 0; g < m->nrigid_group; g++) {
    if (m->rigid_group_lanes[g] < 2) continue;
    const size_t n = (size_t)sw_rigid_group_unknowns(m, g), need = LANES * (n * n + 2 * n);
    if (need > len) len = need;
  }
  return len;
}

/* w[k][u] -= l[u] c[k][u] for k < len: a row's update in every lane. */
static void take_off(double *restrict w, const double *restrict c, const double *l, int len) {
  const double l0 = l[0], l1 = l[1], l2 = l[2], l3 = l[3];
  for (int q = 0; q < LANES * len; q += LANES) {
    w[q] -= l0 * c[q];
    w[q + 1] -= l1 * c[q + 1];
    w[q + 2] -= l2 * c[q + 2];
    w[q + 3] -= l3 * c[q + 3];
  }
}

int sw_cholesky_lanes(double *const *A, double *const *rhs, int nl, int n, const int *env,
                      const int *reach, const int *off, const int *dof, int base, double *ws) {
  double (*restrict W)[LANES] = (double (*)[LANES])ws;
  double (*restrict b)[LANES] = W + (size_t)n * n, (*restrict col)[LANES] = b + n;
  /* in: each row's envelope up to its diagonal (all the scalar factor
   * reads), and the right-hand sides; the lanes past nl repeat the last */
  const double *a[LANES], *r[LANES];
  for (int u = 0; u < LANES; u++) a[u] = A[u < nl ? u : nl - 1], r[u] = rhs[u < nl ? u : nl - 1];
  for (int s = 0, i = 0; i < n; i++) {
    if (i == off[s] + dof[s]) s++;
    const size_t row = (size_t)i * n;
    const double *restrict a0 = a[0] + row, *restrict a1 = a[1] + row, *restrict a2 = a[2] + row,
                 *restrict a3 = a[3] + row;
    double (*restrict Wi)[LANES] = W + row;
    for (int k = off[env[s] - base]; k <= i; k++)
      Wi[k][0] = a0[k], Wi[k][1] = a1[k], Wi[k][2] = a2[k], Wi[k][3] = a3[k];
    for (int u = 0; u < LANES; u++) b[i][u] = r[u][i];
  }
  for (int sj = 0, j = 0; j < n; j++) { /* joint_envelope.c's factorisation, lane by lane */
    if (j == off[sj] + dof[sj]) sj++;
    const int rl = reach[sj] - base, last = off[rl] + dof[rl] - 1;
    double (*restrict Wj)[LANES] = W + (size_t)j * n;
    double inv[LANES];
    int pd = 1;
    for (int u = 0; u < LANES; u++) {
      const double djj = Wj[j][u];
      pd &= djj > 0;
      inv[u] = 1.0 / sqrt(djj);
      Wj[j][u] = inv[u];
    }
    if (!pd) return 0;
    for (int t = sj; t <= rl; t++) {
      const int inside = off[env[t] - base] <= j;
      for (int i = t == sj ? j + 1 : off[t]; i < off[t] + dof[t]; i++)
        for (int u = 0; u < LANES; u++) {
          col[i][u] = inside ? W[(size_t)i * n + j][u] * inv[u] : 0.0;
          W[(size_t)i * n + j][u] = Wj[i][u] = col[i][u];
        }
    }
    for (int i = j + 1; i <= last; i++) {
      int nonzero = 0;
      for (int u = 0; u < LANES; u++) nonzero += col[i][u] != 0.0;
      if (!nonzero) continue; /* nothing to take off row i in any lane */
      double (*restrict Wi)[LANES] = W + (size_t)i * n;
      const double *li = col[i];
      if (nonzero == LANES) { /* every lane: one vector operation an entry */
        take_off(Wi[j + 1], col[j + 1], li, i - j);
        continue;
      }
      for (int k = j + 1; k <= i; k++) /* a lane whose factor entry is 0 keeps its row */
        for (int u = 0; u < LANES; u++)
          Wi[k][u] = li[u] != 0.0 ? Wi[k][u] - li[u] * col[k][u] : Wi[k][u];
    }
  }
  for (int sj = 0, j = 0; j < n; j++) { /* L y = rhs, column by column */
    if (j == off[sj] + dof[sj]) sj++;
    const double (*restrict Lj)[LANES] = (const double (*)[LANES])W + (size_t)j * n;
    const int rl = reach[sj] - base, last = off[rl] + dof[rl] - 1;
    double y[LANES];
    for (int u = 0; u < LANES; u++) y[u] = b[j][u] = b[j][u] * Lj[j][u];
    for (int i = j + 1; i <= last; i++)
      for (int u = 0; u < LANES; u++) b[i][u] -= Lj[i][u] * y[u];
  }
  int si = 0; /* L^T x = y, column by column of L^T, from the last member */
  while (off[si] + dof[si] < n) si++;
  for (int i = n - 1; i >= 0; i--) {
    if (i < off[si]) si--;
    const double (*restrict Li)[LANES] = (const double (*)[LANES])W + (size_t)i * n;
    double x[LANES];
    for (int u = 0; u < LANES; u++) x[u] = b[i][u] = b[i][u] * Li[i][u];
    for (int k = off[env[si] - base]; k < i; k++)
      for (int u = 0; u < LANES; u++) b[k][u] -= Li[k][u] * x[u];
  }
  for (int u = 0; u < nl; u++) /* out: the solutions */
    for (int i = 0; i < n; i++) rhs[u][i] = b[i][u];
  return 1;
}
