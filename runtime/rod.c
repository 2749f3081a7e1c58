/* rod.c — strains, internal forces and internal couples of Cosserat rods.
 *
 * Design.  One pass over the elements of a rod computes the shear/stretch
 * strain, the internal force n and everything that lives on an element; one
 * pass over the Voronoi domains computes curvature and the bending couple and
 * scatters it to the two neighbouring elements.  The difference operator
 * Delta^h and the averaging operator A^h of the discretisation (Gazzola et al.
 * 2018, eqs. 3.1-3.4, with zero padding at both ends) are done in the same
 * passes by carrying the previous element's or domain's value, so no extra
 * array or pass is needed.  Results: d->force (lab frame, per node) and
 * d->torque (material frame, per element), both overwritten.  Arrays are
 * planar (sinew.h, "Layout"): component k of slot i is a[k * stride + i].
 *
 * Discrete equations (Gazzola 2018, eq. 3.7, with the notation of sinew.h):
 *   sigma_i  = Q_i (x_{i+1} - x_i) / l^_i - d3               shear/stretch strain
 *   n_i      = S^_i (sigma_i - sigma0_i) / e_i                internal force (material)
 *   F_node   = Delta^h( Q_i^T n_i )
 *   kappa_j  = log(Q_{j+1} Q_j^T) / D^_j                      curvature (material)
 *   c_j      = B^_j (kappa_j - kappa0_j) / eps_j^3            bending couple
 *   tau_i    = Delta^h(c) + A^h(kappa x c D^) + (Q_i x_s,i x n_i) l^_i
 *              + (J^_i w_i / e_i) x w_i + (J^_i w_i / e_i) de_i/dt / e_i
 * The last term is not formed here: integrate.c integrates it exactly by
 * holding the angular momentum J^ w / e constant through each drift.
 * Q_i x_s,i l^_i = Q_i (x_{i+1} - x_i) = l^_i (sigma_i + d3), which is how the
 * shear couple is formed below.  The same constitutive law (S = S^/e,
 * B = B^/eps^3 at the Voronoi domains) is used by PyElastica.
 */
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* Element pass: strains, internal force, shear couple and the two inertial
 * couples.  Writes force on nodes 0..n (node n last) and torque on elements. */
static void rod_elements(const swModel *m, swData *d, int r) {
  const int n = m->rod_nelem[r], a = m->elem_adr[r];
  const size_t S_ = (size_t)m->stride;
  const double *restrict x = d->x + a;
  const double *restrict Qs = d->Q + a;
  const double *restrict w = d->omega + a;
  const double *restrict rl = m->rest_len + a, *restrict irl = m->inv_rest_len + a;
  const double *restrict S = m->shear_stiff + a;
  const double *restrict s0 = m->rest_sigma + a;
  const double *restrict J = m->inertia + a;
  double *restrict F = d->force + a;
  double *restrict T = d->torque + a;
  double *restrict len = d->length + a, *restrict dil = d->dilatation + a;
  double *restrict sig = d->sigma + a, *restrict str = d->stress + a;
  double fprev[3] = {0, 0, 0};
  for (int i = 0; i < n; i++) {
    double Q[9];
    for (int k = 0; k < 9; k++) Q[k] = Qs[k * S_ + i];
    double dx[3];
    for (int k = 0; k < 3; k++) dx[k] = x[k * S_ + i + 1] - x[k * S_ + i];
    const double l = sw_v3_norm(dx), inv_l = 1.0 / l, inv_rl = irl[i];
    const double e = l * inv_rl, inv_e = rl[i] * inv_l;
    double Qdx[3], nm[3], f[3];
    sw_mat_vec(Qdx, Q, dx);
    for (int k = 0; k < 3; k++) {
      sig[k * S_ + i] = Qdx[k] * inv_rl - (k == 2);
      nm[k] = S[k * S_ + i] * (sig[k * S_ + i] - s0[k * S_ + i]) * inv_e;
      str[k * S_ + i] = nm[k];
    }
    len[i] = l;
    dil[i] = e;
    /* node force: Delta^h(Q^T n) */
    sw_matT_vec(f, Q, nm);
    for (int k = 0; k < 3; k++) {
      F[k * S_ + i] = f[k] - fprev[k];
      fprev[k] = f[k];
    }
    /* shear couple (Q dx) x n, inertial couples of the rotating element */
    double sc[3], Jw[3], tr[3], wi[3];
    sw_v3_cross(sc, Qdx, nm);
    for (int k = 0; k < 3; k++) wi[k] = w[k * S_ + i];
    for (int k = 0; k < 3; k++) Jw[k] = J[k * S_ + i] * wi[k] * inv_e;
    sw_v3_cross(tr, Jw, wi);
    /* The dilatation-rate couple (J^ w / e) de/dt / e is integrated by the
     * drift (integrate.c), which keeps J^ w / e constant while e changes. */
    for (int k = 0; k < 3; k++) T[k * S_ + i] = sc[k] + tr[k];
  }
  for (int k = 0; k < 3; k++) F[k * S_ + n] = -fprev[k];
}

/* Voronoi pass: curvature, bending couple, and its scatter to the elements.
 * Domain j lies between elements j and j+1; with Q_{j+1} = exp(-D^ [k]x) Q_j,
 * Delta^h(c) gives +c_j to element j and -c_j to element j+1 (the derivative
 * of the bending energy with respect to each frame's rotation), and
 * A^h(kappa x c D^) gives half of h_j = kappa_j x c_j D^_j to each. */
static void rod_voronoi(const swModel *m, swData *d, int r) {
  const int n = m->rod_nelem[r], a = m->elem_adr[r];
  const size_t S_ = (size_t)m->stride;
  const double *restrict Qs = d->Q + a;
  const double *restrict len = d->length + a;
  const double *restrict D = m->rest_vor_len + a;
  const double *restrict B = m->bend_stiff + a;
  const double *restrict k0 = m->rest_kappa + a;
  double *restrict kap = d->kappa + a, *restrict cpl = d->couple + a;
  double *restrict vdil = d->vor_dilatation + a;
  double *restrict T = d->torque + a;
  double Qa[9], Qb[9];
  for (int k = 0; k < 9; k++) Qb[k] = Qs[k * S_];
  for (int j = 0; j < n - 1; j++) {
    for (int k = 0; k < 9; k++) {
      Qa[k] = Qb[k];
      Qb[k] = Qs[k * S_ + j + 1];
    }
    const double inv_D = 1.0 / D[j];
    const double eps = 0.5 * (len[j] + len[j + 1]) * inv_D;
    const double inv_eps3 = 1.0 / (eps * eps * eps);
    double phi[3], c[3], h[3], kj[3];
    sw_frame_log(phi, Qa, Qb);
    for (int k = 0; k < 3; k++) {
      kj[k] = phi[k] * inv_D;
      kap[k * S_ + j] = kj[k];
      c[k] = B[k * S_ + j] * (kj[k] - k0[k * S_ + j]) * inv_eps3;
      cpl[k * S_ + j] = c[k];
    }
    vdil[j] = eps;
    sw_v3_cross(h, kj, c);
    for (int k = 0; k < 3; k++) {
      const double half_h = 0.5 * h[k] * D[j];
      T[k * S_ + j] += c[k] + half_h;
      T[k * S_ + j + 1] += -c[k] + half_h;
    }
  }
}

void sw_internal_loads(const swModel *m, swData *d) {
  for (int r = 0; r < m->nrod; r++) {
    if (sw_rod_is_rigid(m, r)) { /* no deformation, no internal loads (rigid.c) */
      sw_rigid_internal(m, d, r);
      continue;
    }
    rod_elements(m, d, r);
    rod_voronoi(m, d, r);
  }
}
