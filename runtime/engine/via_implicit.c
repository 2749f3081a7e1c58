/* via_implicit.c — the via rings of an implicit filament, linearly implicit (SW_IMEX).
 *
 * Design.  A via ring (muscle_via.c) is a spring k and damper nu across the
 * filament at its contact c = (1 - s) x_j + s x_{j+1}, normal to the
 * filament's tangent tau there.  At a filament's light nodes it bounds an
 * explicit step (the muscular snake's rings: 57 us, against 77 us for its
 * backbone).  Under imex the kick takes it as rigid_joint.c takes a joint,
 * by the trapezoidal rule, together with the Hill damping of
 * muscle_implicit.c.  The filament's velocity change dv over a kick h then
 * solves
 *   (M + sum_q beta_q U_q P_q U_q^T + h c b b^T) dv = h (F - T0 b),
 *   beta_q = h nu_q / 2 + h^2 k_q / 4,
 * with U_q the contact's weights (1 - s on node j, s on node j + 1), P_q =
 * I - tau tau^T = n1 n1^T + n2 n2^T its normal projector, and h c b b^T the
 * Hill damping's rank one (muscle_implicit.c; F holds every other load, the
 * rings' own as evaluated).  The ring's point p, on the bone, stays
 * explicit: a bone is heavy next to a filament's node (the snake's backbone
 * node: 20 g against 0.8 g), and the step still sees the ring on the bone's
 * side (sw_via_stable_dt).
 *
 * With V the columns U_q n1, U_q n2 of the filament's R implicit rings (2 R
 * of them) and D = M^-1, Woodbury's identity (Golub and Van Loan, Matrix
 * Computations, 4th ed., sec. 2.1.4) gives
 *   A_R^-1 = D - D V S^-1 V^T D,   S = diag(1 / beta_q) + V^T D V,
 * for A_R = M + sum beta U P U^T, so the Hill solve keeps its form with
 *   p = b . A_R^-1 F = b.D F - y_b . S^-1 y_F,
 *   s = b . A_R^-1 b = b.D b - y_b . S^-1 y_b,      y_x = V^T D x,
 * and, T the tension the solve gives (dv = h A_R^-1 (F - T b)), each ring's
 * force changes by
 *   df = -(beta / h) P U^T dv = -(S^-1 (y_F - T y_b))_q   (along n1, n2),
 * exactly, since V^T A_R^-1 = diag(1 / beta) S^-1 V^T D.  The change goes
 * where the ring's own load goes (sw_via_add): to the filament's two nodes
 * with the weights, and its opposite to the bone at the same point, so
 * momentum and angular momentum are kept; like the ring's load it is an
 * external load, whose work the kick books.
 *
 * Nodes whose dv is not the filament's own take D = 0 there: a clamped end
 * (dv = 0), and an end that is a leaf of the joints' system (rigid_joint.c
 * solves it; muscle_implicit.c's system_part eliminates the interior nodes
 * and leaves the ends to the system, whose tension T arrives in
 * system_tension).  The ring's share on such an end stays explicit, so the
 * step bound keeps the ring's explicit bound when its contact at rest is on
 * an element touching one (sw_via_stable_dt).  For a filament in the
 * system the change is applied after the system's solve, so its bone must
 * be an explicit elastic rod or space: a rigid body has gathered its loads
 * and an implicit rod solved its system by then (sw_via_ring_implicit).
 * Cost: a Cholesky factorisation of S, 2 R unknowns (R <= 8), per filament
 * and kick; each ring's rows are its two contact nodes.
 */
#include <math.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* The transient row of ring q in d->ring_imp (SW_RING_IMP doubles): the
 * normals n1, n2; z_F = S^-1 y_F and z_b = S^-1 y_b (two each); the force
 * change df; whether this evaluation took the ring implicitly. */
enum { IMP_N1 = 0, IMP_N2 = 3, IMP_ZF = 6, IMP_ZB = 8, IMP_DF = 10, IMP_ON = 13 };

int sw_via_ring_implicit(const swModel *m, int f, int q) {
  if (m->integrator != SW_IMEX || !m->fil_implicit || !(m->fil_implicit[f] & SW_FIL_IMPLICIT)) return 0;
  if (!(m->ring_stiffness[q] > 0) && !(m->ring_damping[q] > 0)) return 0;
  if (!m->fil_system || !m->fil_system[f] || m->ring_elem[q] < 0) return 1;
  const int r = sw_rod_of_elem(m, m->ring_elem[q]);
  return !sw_rod_is_rigid(m, r) && !(m->nimplicit && m->rod_implicit[r]);
}

/* D at node i (0..n) of filament f's rod: its inverse mass, 0 where its dv
 * is not the filament's own (the header). */
static double node_D(const swModel *m, int f, int i, int n) {
  const int bits = m->fil_implicit[f], sys = m->fil_system && m->fil_system[f];
  if ((i == 0 || i == n) && sys) return 0;
  if ((i == 0 && (bits & SW_FIL_HELD_START)) || (i == n && (bits & SW_FIL_HELD_END))) return 0;
  return m->inv_mass[m->node_adr[m->fil_rod[f]] + i];
}

/* b_i = t_{i-1} - t_i at node i of the filament (muscle_implicit.c's b):
 * the unit tangents of the elements before and after it, 0 past an end. */
static void hill_b(const swModel *m, const swData *d, int f, int i, int n, double *b) {
  const int na = m->node_adr[m->fil_rod[f]], lo = m->elem_adr[m->fil_rod[f]];
  b[0] = b[1] = b[2] = 0;
  for (int e = i - 1; e <= i; e++) {
    if (e < 0 || e >= n) continue;
    double xa[3], xb[3];
    sw_get3(m, d->x, na + e, xa);
    sw_get3(m, d->x, na + e + 1, xb);
    const double sign = e < i ? 1.0 / d->length[lo + e] : -1.0 / d->length[lo + e];
    for (int k = 0; k < 3; k++) b[k] += sign * (xb[k] - xa[k]);
  }
}

/* Two unit normals to tau. */
static void normals(const double *tau, double *n1, double *n2) {
  const double a[3] = {fabs(tau[0]) < 0.6 ? 1.0 : 0.0, fabs(tau[0]) < 0.6 ? 0.0 : 1.0, 0.0};
  const double ta = sw_v3_dot(tau, a);
  for (int k = 0; k < 3; k++) n1[k] = a[k] - ta * tau[k];
  sw_v3_scale(n1, n1, 1.0 / sw_v3_norm(n1));
  sw_v3_cross(n2, tau, n1);
}

#define VMAX (2 * SW_MUSCLE_MAX_VIA)

void sw_via_implicit_sums(const swModel *m, swData *d, int f, double h, double *p, double *s) {
  const int r = m->fil_rod[f], na = m->node_adr[r], n = m->rod_nelem[r];
  int q0 = m->fil_ring_adr[f], nq = 0, node[VMAX][2];
  double w[VMAX][2], col[VMAX][3], beta[VMAX], yF[VMAX], yb[VMAX];
  /* the columns of V: each implicit ring's two normals at its two nodes */
  for (int q = q0; q < m->fil_ring_adr[f + 1]; q++) {
    double *imp = d->ring_imp + SW_RING_IMP * (size_t)q;
    imp[IMP_ON] = 0;
    if (!(h > 0) || !sw_via_ring_implicit(m, f, q)) continue;
    int a;
    double sj, tau[3];
    sw_via_contact(m, d, f, q, &a, &sj, tau);
    normals(tau, imp + IMP_N1, imp + IMP_N2);
    imp[IMP_ON] = 1;
    for (int c = 0; c < 2; c++, nq++) {
      node[nq][0] = a - na, node[nq][1] = a - na + 1;
      w[nq][0] = 1 - sj, w[nq][1] = sj;
      memcpy(col[nq], imp + (c ? IMP_N2 : IMP_N1), sizeof col[nq]);
      beta[nq] = 0.5 * h * m->ring_damping[q] + 0.25 * h * h * m->ring_stiffness[q];
    }
  }
  if (!nq) return;
  /* y_F, y_b and S = diag(1 / beta) + V^T D V (lower triangle) */
  double S[VMAX * VMAX];
  for (int i = 0; i < nq; i++) {
    yF[i] = yb[i] = 0;
    for (int t = 0; t < 2; t++) {
      const int ni = node[i][t];
      const double Dw = w[i][t] * node_D(m, f, ni, n);
      if (Dw == 0) continue;
      double F[3], b[3];
      sw_get3(m, d->force, na + ni, F);
      hill_b(m, d, f, ni, n, b);
      yF[i] += Dw * sw_v3_dot(col[i], F);
      yb[i] += Dw * sw_v3_dot(col[i], b);
    }
    for (int j = 0; j <= i; j++) {
      double g = 0;
      for (int t = 0; t < 2; t++)
        for (int u = 0; u < 2; u++)
          if (node[i][t] == node[j][u])
            g += w[i][t] * w[j][u] * node_D(m, f, node[i][t], n) * sw_v3_dot(col[i], col[j]);
      S[i * nq + j] = g + (i == j ? 1.0 / beta[i] : 0.0);
    }
  }
  /* Cholesky of S (positive definite: diag(1 / beta) > 0 plus a Gram
   * matrix), then z_F and z_b */
  for (int j = 0; j < nq; j++) {
    double djj = S[j * nq + j];
    for (int k = 0; k < j; k++) djj -= S[j * nq + k] * S[j * nq + k];
    S[j * nq + j] = sqrt(djj);
    for (int i = j + 1; i < nq; i++) {
      double v = S[i * nq + j];
      for (int k = 0; k < j; k++) v -= S[i * nq + k] * S[j * nq + k];
      S[i * nq + j] = v / S[j * nq + j];
    }
  }
  for (int v = 0; v < 2; v++) { /* forward and back substitution, in place */
    double *y = v ? yb : yF, z[VMAX];
    for (int i = 0; i < nq; i++) {
      z[i] = y[i];
      for (int k = 0; k < i; k++) z[i] -= S[i * nq + k] * z[k];
      z[i] /= S[i * nq + i];
    }
    for (int i = nq - 1; i >= 0; i--) {
      for (int k = i + 1; k < nq; k++) z[i] -= S[k * nq + i] * z[k];
      z[i] /= S[i * nq + i];
    }
    if (v) { /* y_b . z_b and y_b . z_F from the two: s and p lose them */
      double sb = 0;
      for (int i = 0; i < nq; i++) sb += yb[i] * z[i];
      *s -= sb;
    } else {
      double pb = 0;
      for (int i = 0; i < nq; i++) pb += yb[i] * z[i];
      *p -= pb;
    }
    for (int q = q0, i = 0; q < m->fil_ring_adr[f + 1]; q++) {
      double *imp = d->ring_imp + SW_RING_IMP * (size_t)q;
      if (!imp[IMP_ON]) continue;
      imp[(v ? IMP_ZB : IMP_ZF) + 0] = z[i++];
      imp[(v ? IMP_ZB : IMP_ZF) + 1] = z[i++];
    }
  }
}

void sw_via_implicit_force(const swModel *m, swData *d, int f, double T) {
  for (int q = m->fil_ring_adr[f]; q < m->fil_ring_adr[f + 1]; q++) {
    double *imp = d->ring_imp + SW_RING_IMP * (size_t)q;
    if (!imp[IMP_ON]) continue;
    const double a1 = -(imp[IMP_ZF] - T * imp[IMP_ZB]), a2 = -(imp[IMP_ZF + 1] - T * imp[IMP_ZB + 1]);
    for (int k = 0; k < 3; k++) imp[IMP_DF + k] = a1 * imp[IMP_N1 + k] + a2 * imp[IMP_N2 + k];
  }
}

void sw_via_implicit_clear(const swModel *m, swData *d, int f) {
  for (int q = m->fil_ring_adr[f]; q < m->fil_ring_adr[f + 1]; q++)
    d->ring_imp[SW_RING_IMP * (size_t)q + IMP_ON] = 0;
}

void sw_via_implicit_add(const swModel *m, swData *d, int f, int lo, int hi) {
  for (int q = m->fil_ring_adr[f]; q < m->fil_ring_adr[f + 1]; q++) {
    const double *imp = d->ring_imp + SW_RING_IMP * (size_t)q;
    if (imp[IMP_ON]) sw_via_add(m, d, f, q, imp + IMP_DF, lo, hi);
  }
}
