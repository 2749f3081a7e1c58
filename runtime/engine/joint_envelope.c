/* joint_envelope.c — the joints' system's dense block, factored and solved
 * within its envelope.
 *
 * Design.  rigid_joint.c assembles each group of the joints' system into
 * one dense symmetric block whose members' rows are zero left of their
 * envelope (joint_groups.c orders the members, joint_order.c for the least
 * work); this is its scalar factorisation and solve, one group at a time
 * (joint_lanes.c does up to four groups of one shape at once, one per
 * vector lane, to the same bits).
 */
#include <math.h>
#include <stddef.h>
#include "sinew.h"
#include "internal.h"

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
int sw_envelope_cholesky_solve(double *restrict A, int n, double *restrict rhs,
                               double *restrict col, const int *env, const int *reach,
                               const int *off, const int *dof, int base) {
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
