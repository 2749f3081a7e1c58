/* leaf_plain.c — a lone leaf's elimination in closed form.
 *
 * Design.  A leaf (joint_ports.c) is a free node of an explicit rod whose
 * implicit joints all reach one port: a barb on its rachis, a filament's
 * end on a tendon.  Both sides of each such joint sit on their nodes (no
 * lever), so the joints' rate maps are J = [I, 0] on the position and
 * [0, P] on the rotation, and a lone leaf (no partner, no filament's
 * dashpot) has, whatever its joints' kinds,
 *
 *   A_uu = [ a I   0 ]     C = [ c I   0 ]     (c I alone when du = 3;
 *          [  0    B ],        [  0   -D ]      dQ = 6: C's last three
 *                                               columns zero then)
 *
 * with a = m + sum w_p, c = -sum w_p, D = sum (w_r P^T P + w_l g g^T) and
 * B = I_lab + D (rigid_joint.c's assembly, add_pair): C = -W with W =
 * [w_p I, 0; 0, D] the joints' weights, which the port's own block takes
 * as well.  The
 * general elimination (joint_ports.c, condense: a 6x6 Cholesky, X =
 * A_uu^-1 C with six right-hand sides, C^T X) spends its flops on those
 * zero blocks, and what the port is left with, W - W A_uu^-1 W, is a
 * difference of two nearly equal numbers wherever the joint is far stiffer
 * than the leaf is heavy (a barb's tie: w_r / I_lab ~ 1e4), so its
 * round-off is that of W, not of the result.  Here the port's own block
 * of these joints is left out of the assembly and the leaf adds, with
 * M = diag(m, I_lab) = A_uu - W,
 *
 *   W - W A_uu^-1 W = W A_uu^-1 M = [ (w_p m / a) I  0 ; 0  D B^-1 I_lab ]
 *
 * (the joints in series with the leaf's inertia; symmetric, as
 * (W^-1 + M^-1)^-1 where both are invertible, whose lower triangle is
 * used), and
 *
 *   X = [ (c / a) I   0 ; 0  -B^-1 D ],   b_Q -= C^T A_uu^-1 b_u,
 *   u = A_uu^-1 b_u - X u_Q,
 *
 * a 3x3 Cholesky and about 200 flops in all (the resolved wing eliminates
 * 3072 barbs a kick).  X and A_uu^-1 b_u are stored where condense stores
 * them (sw_unit_X, sw_unit_b), zeros included, so what reads
 * a unit after the solve reads either path's alike; m and I_lab are the
 * assembly's (sw_unit_M).
 */
#include <math.h>
#include <string.h>
#include "sinew.h"
#include "internal.h"

/* B = L L^T (3x3, its lower triangle from rows ld apart) into L (its
 * lower triangle, row-major 3x3).  Returns 0 if B is not positive
 * definite. */
static int chol3(const double *B, int ld, double *L) {
  const double l00s = B[0];
  if (!(l00s > 0)) return 0;
  L[0] = sqrt(l00s);
  L[3] = B[ld] / L[0], L[6] = B[2 * ld] / L[0];
  const double l11s = B[ld + 1] - L[3] * L[3];
  if (!(l11s > 0)) return 0;
  L[4] = sqrt(l11s);
  L[7] = (B[2 * ld + 1] - L[6] * L[3]) / L[4];
  const double l22s = B[2 * ld + 2] - L[6] * L[6] - L[7] * L[7];
  if (!(l22s > 0)) return 0;
  L[8] = sqrt(l22s);
  return 1;
}

/* L L^T y = y for the ncol columns of Y (rows ys apart) in place. */
static void chol3_solve(const double *L, double *Y, int ncol, int ys) {
  for (int c = 0; c < ncol; c++) {
    double *y0 = Y + c, *y1 = y0 + ys, *y2 = y1 + ys;
    const double z0 = *y0 / L[0], z1 = (*y1 - L[3] * z0) / L[4];
    const double z2 = (*y2 - L[6] * z0 - L[7] * z1) / L[8];
    *y2 = z2 / L[8];
    *y1 = (z1 - L[7] * *y2) / L[4];
    *y0 = (z0 - L[3] * *y1 - L[6] * *y2) / L[0];
  }
}

int sw_leaf_condense_plain(double *ws, int du, int dQ, int qoff, double *A, int n, double *rhs) {
  double *Auu = ws, *C = sw_unit_C(ws, du), *X = sw_unit_X(ws, du, dQ), *b = sw_unit_b(ws, du, dQ);
  const double *Mu = sw_unit_M(ws, du, dQ); /* the leaf's mass and lab inertia */
  const double a = Auu[0], c = C[0];
  if (!(a > 0)) return 0;
  memset(X, 0, (size_t)(du * dQ) * sizeof(double));
  const double x = c / a, k = -c * (Mu[0] / a); /* W M / a: the joints in series with the mass */
  for (int i = 0; i < 3; i++) {
    X[i * dQ + i] = x;
    b[i] /= a;
    double *Ai = A + (size_t)(qoff + i) * (size_t)n + qoff;
    Ai[i] += k;
    rhs[qoff + i] -= c * b[i];
  }
  if (du < 6) return 1;
  /* the rotation: X's block B^-1 C_r (= -B^-1 D), y = B^-1 b_r into b,
   * and Z = B^-1 I_lab, whose product with W's D = -C_r is the port's */
  double Z[9];
  for (int i = 0; i < 3; i++)
    for (int k3 = 0; k3 < 3; k3++) {
      X[(3 + i) * dQ + 3 + k3] = C[(3 + i) * dQ + 3 + k3];
      Z[3 * i + k3] = Mu[1 + 3 * i + k3];
    }
  double L[9];
  if (!chol3(Auu + 3 * du + 3, du, L)) return 0;
  chol3_solve(L, X + 3 * dQ + 3, 3, dQ);
  chol3_solve(L, b + 3, 1, 1);
  chol3_solve(L, Z, 3, 3);
  for (int i = 0; i < 3; i++) { /* A_QQ += W B^-1 I_lab (lower triangle), rhs -= C^T y */
    double *Ai = A + (size_t)(qoff + 3 + i) * (size_t)n + qoff + 3;
    for (int k3 = 0; k3 <= i; k3++) {
      double s = 0;
      for (int r = 0; r < 3; r++) s -= C[(3 + r) * dQ + 3 + i] * Z[3 * r + k3];
      Ai[k3] += s;
    }
    double s = 0;
    for (int r = 0; r < 3; r++) s += C[(3 + r) * dQ + 3 + i] * b[3 + r];
    rhs[qoff + 3 + i] -= s;
  }
  return 1;
}

void sw_leaf_recover_plain(double *ws, int du, int dQ, int qoff, const double *u) {
  const double *X = sw_unit_X(ws, du, dQ), *uq = u + qoff;
  double *b = sw_unit_b(ws, du, dQ);
  for (int i = 0; i < 3; i++) b[i] -= X[i * dQ + i] * uq[i];
  if (du < 6) return;
  double w[3];
  for (int i = 0; i < 3; i++)
    w[i] = X[(3 + i) * dQ + 3] * uq[3] + X[(3 + i) * dQ + 4] * uq[4] + X[(3 + i) * dQ + 5] * uq[5];
  for (int i = 0; i < 3; i++) b[3 + i] -= w[i];
}
