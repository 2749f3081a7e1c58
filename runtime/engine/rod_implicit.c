/* rod_implicit.c — elastic rods with linearly implicit elasticity (SW_IMEX).
 *
 * Design.  An explicit kick is stable while h w < 2 for the highest
 * frequency w of the rod (stability.c).  On a soft, thick rod hardened in
 * shear (Zhang et al. 2019, Suppl. Figs. 10-12: G x 25 and x 100) that
 * frequency is the shear-rotation zig-zag, w^2 ~ (16/3) G/rho (1/l^2 + 1/r^2),
 * which cuts the step 4 and 8 times below the unhardened rod's (121 us to
 * 31 and 15.7 us) although the motion of interest is the same slow crawl.  A rod with swRodDesc.implicit
 * under integrator = imex is kicked instead with the trapezoidal rule in its
 * elastic loads and its linear damping, as rigid_joint.c does for joints
 * between rigid bodies: with u = (v_0, w_0, v_1, w_1, ..., v_n) the rod's
 * node velocities (lab) and element angular velocities (material), M the
 * lumped masses and the kick's inertias J^/e, C the linear damping and K
 * the tangent stiffness of the internal loads, all at the kick's
 * configuration (the midpoint of position Verlet's step),
 *   (M + h/2 C + h^2/4 K) du = h F,
 * F the kick's total loads.  For a linear spring this is the implicit
 * midpoint rule (rigid_joint.c shows why), unconditionally stable and
 * second order; the loads themselves stay the exact ones of rod.c, only
 * the correction is linearised, so a converged state is the explicit
 * scheme's.  The step then sees only what stays explicit: friction,
 * contact, joints, waves.
 *
 * K is the Gauss-Newton part of the rod's internal loads (terms of the load
 * times a turn of the lever are dropped, as in rigid_joint.c: they are the
 * strain smaller than what is kept):
 *   shear/stretch of element i (Gazzola 2018, eq. 3.7), rate of the strain
 *     sigma' = Q (v_{i+1} - v_i) / l^ + t x w_i,  t = Q (x_{i+1} - x_i) / l^,
 *     so with G = [-Q/l^, [t]x, Q/l^] on (v_i, w_i, v_{i+1}):
 *     K += l^ G^T (S^/e) G          (S^ without 1/e on variational rods);
 *   bending/twist of domain j, rate phi' = J_r^-1 w_{j+1} - J_l^-1 w_j
 *     (phi = kappa D^, the inverse Jacobians of the SO(3) exponential),
 *     H = [-J_l^-1, J_r^-1] / D^ on (w_j, w_{j+1}):
 *     K += D^ H^T (B^/eps^3) H      (B^ on variational rods);
 *   the clamp domain of boundary.c on a clamped end element: B^/(eps^3 D)
 *     with D = l^/2 on its diagonal;
 *   and, of the dropped terms, the one a taut rod needs (issue 31): the
 *     tension's turn with its element (shear_block), whose absence left a
 *     taut tendon's string waves explicit.
 * Ordering the unknowns node, element, node, ... makes every element's
 * nine unknowns contiguous and the matrix banded with half-bandwidth 8
 * (element i reaches element i+1 through bending), so the system of a rod
 * of n elements, N = 3 (2n + 1) unknowns, is factored and solved by a
 * banded L D L^T in O(n) every kick: about N (BAND^2/2 + 2 BAND)
 * multiply-adds, 1.5e4 for the 50-element snake.  L D L^T rather than
 * Cholesky's L L^T (issue 31): no square root on the chain of dependent
 * operations that runs from each row's pivot to the next, which is what
 * bounds the factorisation's time once its loops are unrolled (the
 * inverse and the square root were a sixth of the implicit step).  The
 * factorisation is our own short loop rather than GSL's
 * gsl_linalg_cholesky_band_decomp: it runs inside the step, where GSL's
 * error handler (abort by default, or a global switch to turn it off)
 * has no place, and it needs nothing GSL adds.
 *
 * The new velocities replace the loads the rod's slots would have had
 * (F_eff = m dv / h, tau_eff = J^/e dw / h), so integrate.c's kick, its work
 * booking and everything after it go on unchanged.  The ends a boundary
 * condition holds are fixed in the system (du = 0 there) and sw_bc_kick
 * sets them after, as for every rod.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

#define BAND SW_IMPLICIT_BAND /* half-bandwidth: element i's rotation reaches element i+1's */

/* Unknowns of a rod of n elements: three per node and per element. */
static size_t unknowns(int n) { return 3 * (2 * (size_t)n + 1); }

/* Doubles of one rod's system: the band (BAND + 1 per row) with BAND rows
 * of zeros before and after it, the right-hand side with BAND zeros before
 * and after, and the factor's inverse diagonal with BAND zeros before
 * (band_ldlt_solve); then what the factorisation was made of (below). */
static size_t system_len(int n) { return (unknowns(n) + 2 * BAND) * (BAND + 3) - BAND; }
enum { KEPT_H, KEPT_FRESH, KEPT_REUSED, KEPT_BAND, KEPT_HEAD }; /* KEPT_BAND: with ports' blocks */
static size_t rod_scratch(int n) { return system_len(n) + KEPT_HEAD + 12 * (size_t)n; }

int sw_implicit_setup(swModel *m, const int *wanted) {
  m->rod_implicit = calloc((size_t)m->nrod, sizeof(int));
  m->implicit_rod = calloc((size_t)m->nrod, sizeof(int));
  m->implicit_adr = calloc((size_t)m->nrod + 1, sizeof(size_t));
  m->implicit_wave_dt = calloc((size_t)m->nrod + 1, sizeof(double));
  if (!m->rod_implicit || !m->implicit_rod || !m->implicit_adr || !m->implicit_wave_dt) return 0;
  m->nimplicit = 0;
  for (int r = 0; r < m->nrod; r++) {
    if (!wanted[r] || sw_rod_is_rigid(m, r)) continue;
    m->rod_implicit[r] = 1; /* asked for; kicked implicitly under imex only */
    if (m->integrator != SW_IMEX) continue;
    m->implicit_rod[m->nimplicit] = r;
    m->implicit_wave_dt[m->nimplicit] = sw_stable_dt_elastic(m, r);
    m->implicit_adr[m->nimplicit + 1] = m->implicit_adr[m->nimplicit] + rod_scratch(m->rod_nelem[r]);
    m->nimplicit++;
  }
  return 1;
}

void sw_implicit_free(swModel *m) {
  free(m->rod_implicit);
  free(m->implicit_rod);
  free(m->implicit_adr);
  free(m->implicit_wave_dt);
}

size_t sw_implicit_scratch(const swModel *m) {
  return m->implicit_adr ? m->implicit_adr[m->nimplicit] : 0;
}

/* The band stores row i's A(i, j), i - BAND <= j <= i, left to right in
 * A[i (BAND + 1) + BAND - (i - j)], the diagonal last; the first rows'
 * places left of column 0 stay zero.  Each row is a contiguous window, so
 * the factorisation's dot products run over consecutive doubles. */
static inline double *at(double *A, size_t i, size_t j) { return A + i * (BAND + 1) + BAND - (i - j); }

/* In place: A = L D L^T (L unit lower triangular and banded, D diagonal),
 * inv[i] = 1 / D(i) (band_ldlt_factor, which returns 0 if A is not
 * positive definite: a non-finite state); then A x = b into b
 * (band_ldlt_solve).  Row i's window R_i holds
 * L(i, i - BAND + c) at c and D(i) at BAND; with g(i, j) = L(i, j) D(j),
 * for j = i - BAND + c
 *   g(i, j) = A(i, j) - sum_{t < c} g(i, i - BAND + t) L(j, i - BAND + t),
 *   L(i, j) = g(i, j) / D(j),
 *   D(i) = A(i, i) - sum_{t < BAND} g(i, i - BAND + t) L(i, i - BAND + t).
 * The sums are formed the other way round: as soon as g(i, i - BAND + t)
 * is known it is taken off every later place of the row (acc).  No square
 * root (L L^T's would be L D^1/2): the chain from one row's pivot to the
 * next is one division, one multiplication and one multiply-subtract.  The
 * solves, L y = b, then L^T x = D^-1 y, are the sums of the rows,
 *   y_i = b_i - sum_{t < BAND} L(i, i - BAND + t) y_{i - BAND + t},
 *   x_i = y_i / D(i) - sum_{k = i + BAND .. i + 1} L(k, i) x_k,
 * the unknown just found carried to the next row (prev) rather than read
 * back from memory.  Every row runs the same BAND places: A has BAND rows
 * of zeros before row 0 and after row N - 1, b BAND zeros before and after,
 * inv BAND before, so the places left of column 0 and right of N - 1 add
 * zeros and the loops have fixed counts, fully unrolled: acc then lives in
 * registers (with a variable count it was a stack array, and each of its
 * updates a store and a load on the chain). */
static int band_ldlt_factor(double *restrict A, size_t N, double *restrict inv) {
  const size_t W = BAND + 1;
  for (size_t i = 0; i < N; i++) {
    double *restrict Ri = A + i * W;
    double acc[BAND], dg = Ri[BAND];
#pragma GCC unroll 8
    for (size_t c = 0; c < BAND; c++) acc[c] = Ri[c];
#pragma GCC unroll 8
    for (size_t t = 0; t < BAND; t++) {
      const double g = acc[t], l = g * inv[i - BAND + t];
      Ri[t] = l;
      dg -= g * l;
#pragma GCC unroll 8
      for (size_t c = t + 1; c < BAND; c++) acc[c] -= g * A[(i - BAND + c) * W + t + BAND - c];
    }
    if (!(dg > 0)) return 0;
    Ri[BAND] = dg;
    inv[i] = 1.0 / dg;
  }
  return 1;
}

static void band_ldlt_solve(const double *restrict A, size_t N, double *restrict b,
                            const double *restrict inv) {
  const size_t W = BAND + 1;
  double prev = 0;
  for (size_t i = 0; i < N; i++) { /* L y = b */
    const double *restrict Ri = A + i * W;
    double y = b[i];
#pragma GCC unroll 8
    for (size_t t = 0; t < BAND - 1; t++) y -= Ri[t] * b[i - BAND + t];
    b[i] = prev = y - Ri[BAND - 1] * prev;
  }
  prev = 0;
  for (size_t i = N; i-- > 0;) { /* L^T x = D^-1 y */
    double x = b[i] * inv[i];
#pragma GCC unroll 8
    for (size_t k = i + BAND; k > i + 1; k--) x -= A[k * W + BAND - (k - i)] * b[k];
    b[i] = prev = x - A[(i + 1) * W + BAND - 1] * prev;
  }
}

/* The same solves for several right-hand sides at once: X row-major with
 * ld doubles per row (a multiple of SW_SOLVE_BLOCK; row i's right-hand
 * sides contiguous, so each step of the sums is one vector operation
 * across them: the ports of joint_ports.c), BAND rows of zeros before row 0
 * and after row N - 1 as in the band, so every row runs the same BAND
 * places.  Each row's sum goes into two accumulators, even and odd places,
 * which halves the chain of dependent multiply-adds from one row to the
 * next (the solve is bound by it, not by the arithmetic). */
static void band_ldlt_solve_many(const double *restrict A, size_t N, double *restrict X, size_t ld,
                                 const double *restrict inv) {
  const size_t W = BAND + 1, CB = SW_SOLVE_BLOCK;
  for (size_t i = 0; i < N; i++) { /* L Y = X */
    const double *restrict Ri = A + i * W;
    for (size_t cb = 0; cb < ld; cb += CB) {
      double *restrict Xi = X + i * ld + cb;
      double a0[SW_SOLVE_BLOCK], a1[SW_SOLVE_BLOCK];
#pragma GCC unroll 8
      for (size_t c = 0; c < CB; c++) a0[c] = Xi[c], a1[c] = 0;
#pragma GCC unroll 8
      for (size_t t = 0; t < BAND; t += 2) {
        const double *restrict X0 = X + (i - BAND + t) * ld + cb, *restrict X1 = X0 + ld;
        const double l0 = Ri[t], l1 = Ri[t + 1];
#pragma GCC unroll 8
        for (size_t c = 0; c < CB; c++) a0[c] -= l0 * X0[c], a1[c] -= l1 * X1[c];
      }
#pragma GCC unroll 8
      for (size_t c = 0; c < CB; c++) Xi[c] = a0[c] + a1[c];
    }
  }
  for (size_t i = N; i-- > 0;) { /* L^T X = D^-1 Y */
    for (size_t cb = 0; cb < ld; cb += CB) {
      double *restrict Xi = X + i * ld + cb;
      double a0[SW_SOLVE_BLOCK], a1[SW_SOLVE_BLOCK];
#pragma GCC unroll 8
      for (size_t c = 0; c < CB; c++) a0[c] = Xi[c] * inv[i], a1[c] = 0;
#pragma GCC unroll 8
      for (size_t t = 1; t <= BAND; t += 2) {
        const double *restrict X0 = X + (i + t) * ld + cb, *restrict X1 = X0 + ld;
        const double l0 = A[(i + t) * W + BAND - t], l1 = A[(i + t + 1) * W + BAND - t - 1];
#pragma GCC unroll 8
        for (size_t c = 0; c < CB; c++) a0[c] -= l0 * X0[c], a1[c] -= l1 * X1[c];
      }
#pragma GCC unroll 8
      for (size_t c = 0; c < CB; c++) Xi[c] = a0[c] + a1[c];
    }
  }
}

/* Shear/stretch of element e into the block of its
 * nine unknowns at o: l^ G^T S G with G = [-Q/l^, [t]x, Q/l^] (the header),
 * S = w S^/e (w S^ on variational rods), which is, with P = Q^T S Q / l^
 * and C = Q^T S [t]x,
 *   [ P    -C           -P ]
 *   [ -C^T  l^[t]x^T S [t]x  C^T ]
 *   [ -P    C            P ].
 * t = sigma + d3 and e come from the rod pass of this kick (d->sigma,
 * d->dilatation: the phased step's planes, so = 0). */
static void shear_block(const swModel *m, const swData *d, int law, int e, double w, double *A,
                        size_t o) {
  double Q[9];
  sw_getQ(m, d->Q, e, Q);
  const double l = m->rest_len[e], il = m->inv_rest_len[e];
  const double t[3] = {SW_AT(m, d->sigma, e, 0), SW_AT(m, d->sigma, e, 1), SW_AT(m, d->sigma, e, 2) + 1.0};
  const double f = law ? w : w / d->dilatation[e];
  const double S[3] = {f * SW_AT(m, d->shear_now, e, 0), f * SW_AT(m, d->shear_now, e, 1),
                       f * SW_AT(m, d->shear_now, e, 2)};
  /* [t]x rows, Q rows scaled by S, and S [t]x */
  const double T[9] = {0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0};
  double QS[9], ST[9], P[9], C[9], R[9];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) QS[3 * a + b] = Q[3 * a + b] * S[a], ST[3 * a + b] = S[a] * T[3 * a + b];
  for (int p = 0; p < 3; p++)
    for (int q = 0; q < 3; q++) {
      double sp = 0, sc = 0, sr = 0;
      for (int a = 0; a < 3; a++) {
        sp += QS[3 * a + p] * Q[3 * a + q];
        sc += Q[3 * a + p] * ST[3 * a + q];
        if (q <= p) sr += T[3 * a + p] * ST[3 * a + q]; /* R: its lower triangle */
      }
      P[3 * p + q] = sp * il, C[3 * p + q] = sc, R[3 * p + q] = sr * l;
    }
  /* The tension's turn with the element (the header's geometric terms), in
   * tension only: with n = S sigma the internal force and a = l^ t the
   * element (both material), a turn b of the frame turns the force on the
   * nodes, F_i = Q^T n (+b x), and the couple a x n by its lever, so
   *   K(v_i, w) = Q^T [n]x,  K(v_{i+1}, w) = -Q^T [n]x,
   *   K(w, w) += sym([n]x [a]x) = (a n^T + n a^T)/2 - (a . n) I.
   * Without them a taut rod's string waves, w = 2 c / l with c^2 = T / mu,
   * stay explicit: 230 us on the arm's distal tendons at 50 N.
   * Compression softens: left out (QN and G zero), as stability.c leaves
   * it. */
  const double tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
  const double nt = S[0] * t[0] * t[0] + S[1] * t[1] * t[1] + S[2] * (t[2] - 1.0) * t[2];
  const int taut = nt > 0;
  double QN[9] = {0}, G[9] = {0}; /* Q^T [n]x, and sym([n]x [a]x) (lower triangle) */
  if (taut) {
    const double n[3] = {nt / tt * t[0], nt / tt * t[1], nt / tt * t[2]}; /* its tension part */
    const double a[3] = {l * t[0], l * t[1], l * t[2]};
    const double an = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
    const double NX[9] = {0, -n[2], n[1], n[2], 0, -n[0], -n[1], n[0], 0};
    for (int p = 0; p < 3; p++)
      for (int q = 0; q < 3; q++) {
        double qn = 0;
        for (int c = 0; c < 3; c++) qn += Q[3 * c + p] * NX[3 * c + q];
        QN[3 * p + q] = qn;
        if (q <= p) G[3 * p + q] = 0.5 * (a[p] * n[q] + n[p] * a[q]) - (p == q ? an : 0.0);
      }
  }
  /* Each place of the band once: the elastic term, then the geometric one
   * (K(w, v_i) = K(v_i, w)^T). */
  for (size_t p = 0; p < 3; p++)
    for (size_t q = 0; q < 3; q++) {
      if (q <= p) {
        *at(A, o + p, o + q) += P[3 * p + q];
        double *ww = at(A, o + 3 + p, o + 3 + q);
        *ww += R[3 * p + q];
        if (taut) *ww += G[3 * p + q];
        *at(A, o + 6 + p, o + 6 + q) += P[3 * p + q];
      }
      double *wv = at(A, o + 3 + p, o + q), *vw = at(A, o + 6 + p, o + 3 + q);
      *wv -= C[3 * q + p];
      if (taut) *wv += QN[3 * q + p];
      *at(A, o + 6 + p, o + q) -= P[3 * p + q];
      *vw += C[3 * p + q];
      if (taut) *vw -= QN[3 * p + q];
    }
}

/* J^-1 = I + sgn [phi]x / 2 + beta [phi]x^2, row-major: the inverse Jacobian
 * of the SO(3) exponential, right (sgn +1) or left (sgn -1) (vec.h). */
static void dexpinv(const double *phi, double beta, double sgn, double *Jm) {
  const double P[9] = {0, -phi[2], phi[1], phi[2], 0, -phi[0], -phi[1], phi[0], 0};
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      double p2 = 0;
      for (int c = 0; c < 3; c++) p2 += P[3 * a + c] * P[3 * c + b];
      Jm[3 * a + b] = (a == b) + 0.5 * sgn * P[3 * a + b] + beta * p2;
    }
}

/* Bending/twist of domain v, between elements e and e + 1, whose rotations
 * are at o and o + 6.  With phi = kappa D^ the domain's rotation vector,
 * Q_{e+1} = exp(-[phi]x) Q_e, a turn b of element e moves
 * phi by -J_l^-1 b and one of element e + 1 by J_r^-1 b (rod.c, the
 * variational law), so H = [-J_l^-1, J_r^-1] / D^ and the block is
 * D^ H^T B' H, B' = B^/eps^3 (B^ on variational rods).  The frames' turn
 * matters: on a bent rod with a hardened twist, dropping it (H = [-I, I])
 * puts a twist stiffness of phi times G I3 / D^ on the pitch.  kappa and
 * eps come from the rod pass of this kick (d->kappa, d->vor_dilatation). */
static void bend_block(const swModel *m, const swData *d, int law, int v, double w, double *A,
                       size_t o) {
  const double Dv = m->rest_vor_len[v], iD = m->inv_rest_vor_len[v];
  const double phi[3] = {SW_AT(m, d->kappa, v, 0) * Dv, SW_AT(m, d->kappa, v, 1) * Dv,
                         SW_AT(m, d->kappa, v, 2) * Dv};
  double Jl[9], Jr[9];
  const double beta = sw_dexpinv_beta(sw_v3_dot(phi, phi));
  dexpinv(phi, beta, -1.0, Jl);
  dexpinv(phi, beta, 1.0, Jr);
  const double eps = d->vor_dilatation[v];
  const double inv_eps3 = law ? 1.0 : 1.0 / (eps * eps * eps);
  double Bk[3];
  for (int k = 0; k < 3; k++) Bk[k] = w * SW_AT(m, d->bend_now, v, k) * inv_eps3 * iD;
  double JlB[9], JrB[9]; /* the Jacobians' rows scaled by B */
  for (int k = 0; k < 3; k++)
    for (int p = 0; p < 3; p++) JlB[3 * k + p] = Jl[3 * k + p] * Bk[k], JrB[3 * k + p] = Jr[3 * k + p] * Bk[k];
  for (size_t p = 0; p < 3; p++)
    for (size_t q = 0; q < 3; q++) {
      double ll = 0, rl = 0, rr = 0; /* (Jl^T B Jl), -(Jr^T B Jl), (Jr^T B Jr) at (p, q) */
      for (int k = 0; k < 3; k++) {
        if (q <= p) ll += JlB[3 * k + p] * Jl[3 * k + q];
        rl -= JrB[3 * k + p] * Jl[3 * k + q];
        if (q <= p) rr += JrB[3 * k + p] * Jr[3 * k + q];
      }
      if (q <= p) {
        *at(A, o + p, o + q) += ll;
        *at(A, o + 6 + p, o + 6 + q) += rr;
      }
      *at(A, o + 6 + p, o + q) += rl;
    }
}

/* The first of the three unknowns condition b holds on a rod of n
 * elements (its end node's velocity, or its end element's rotation), or
 * SIZE_MAX when it holds none of them. */
static size_t held(const swBCDesc *b, int n) {
  if (b->kind == SW_BC_CLAMP || b->kind == SW_BC_VELOCITY) return b->end ? 6 * (size_t)n : 0;
  if (b->kind == SW_BC_OMEGA) return b->end ? 6 * (size_t)n - 3 : 3;
  return SIZE_MAX;
}

/* Unknowns [o, o + 3) held by a boundary condition: du = 0 there (their
 * right-hand side is zeroed by rod_rhs). */
static void hold(double *A, size_t N, size_t o) {
  for (size_t i = o; i < o + 3; i++) {
    for (size_t j = i > BAND ? i - BAND : 0; j < i; j++) *at(A, i, j) = 0;
    for (size_t k = i + 1; k <= i + BAND && k < N; k++) *at(A, k, i) = 0;
    *at(A, i, i) = 1;
  }
}

/* The clamp domain of boundary.c on a clamped end element of rod r:
 * B^/(eps^3 D), D = l^/2, on its diagonal. */
static void clamp_blocks(const swModel *m, const swData *d, int r, double *A) {
  const int n = m->rod_nelem[r], law = m->rod_law[r] == SW_LAW_VARIATIONAL;
  for (int k = 0; k < m->nbc; k++) {
    const swBCDesc *b = &m->bc[k];
    if (b->rod != r || b->kind != SW_BC_CLAMP) continue;
    const size_t oe = b->end ? 6 * (size_t)n - 3 : 3;
    const int e = m->elem_adr[r] + (b->end ? n - 1 : 0);
    const double eps = d->dilatation[e], D = 0.5 * m->rest_len[e];
    const double inv_eps3 = law ? 1.0 : 1.0 / (eps * eps * eps);
    for (int c = 0; c < 3; c++)
      *at(A, oe + (size_t)c, oe + (size_t)c) += SW_AT(m, sw_swell_clamp_bend(m, d), e, c) * inv_eps3 / D;
  }
}

/* The unknowns the boundary conditions on rod r hold, in its matrix. */
static void rod_holds(const swModel *m, int r, double *A, size_t N) {
  for (int k = 0; k < m->nbc; k++) {
    const size_t o = m->bc[k].rod == r ? held(&m->bc[k], m->rod_nelem[r]) : SIZE_MAX;
    if (o != SIZE_MAX) hold(A, N, o);
  }
}

void sw_implicit_stiffness(const swModel *m, const swData *d, int r, double *A) {
  const int n = m->rod_nelem[r], ea = m->elem_adr[r], va = m->vor_adr[r];
  const int law = m->rod_law[r] == SW_LAW_VARIATIONAL;
  memset(A, 0, unknowns(n) * (BAND + 1) * sizeof(double));
  for (int i = 0; i < n; i++) {
    shear_block(m, d, law, ea + i, 1.0, A, 6 * (size_t)i);
    if (i < n - 1) bend_block(m, d, law, va + i, 1.0, A, 6 * (size_t)i + 3);
  }
  clamp_blocks(m, d, r, A);
}

/* ---- keeping a factorisation (issue 31) ----
 *
 * The system's matrix W = M + h/2 C + h^2/4 K changes with the rod's
 * configuration only through K (its frames, which turn the node blocks,
 * and its strains, which scale them and the tension's terms) and the
 * inertias' dilatation; M and C are constant.  The kick only needs W to be
 * near this configuration's: with W = A + E, the update du = W^-1 h F
 * differs from the exact trapezoidal one by h^2/4 (K_W - K) du = O(h^2 du),
 * a local error O(h^3) that keeps the scheme second order (the linearly
 * implicit W-methods: Hairer and Wanner, Solving ODEs II, sec. IV.7).  The
 * stiff modes stay stable: in a mode of stiffness k and mass m kicked with
 * k' = k (1 + delta) in W, position Verlet's map of (x, v) has determinant
 * 1 and trace 2 - a h, a = h k / (m + h^2 k' / 4), so it is stable, and
 * keeps an energy near the exact rule's with no drift, for
 * delta > -(2 / (w h))^2 = -(dt_w / h)^2, dt_w the rod's explicit bound
 * (sw_stable_dt_elastic).  A turn theta of a frame changes the turned
 * blocks by at most 2 theta of the stiffest, and a strain moved by theta
 * scales them by about theta.  So a rod keeps its factorisation, and a
 * kick is one band solve, while every element's frame has turned by at
 * most theta and every strain has moved by at most theta since it was
 * made,
 *   theta = min(KEEP_CAP, KEEP_SHARE (dt_w / h)^2),
 * KEEP_SHARE = 0.02 keeping |delta| 25 times inside the bound, and factors
 * afresh (assembly and L D L^T, three quarters of the implicit kick on the
 * hardened snake) otherwise, or when h changes.  On the arm's tendons and
 * bones at 125 us (dt_w of a few us) theta is below 1e-5 rad, and only a
 * rod that hardly moves keeps it (14% of the demo's implicit kicks); at
 * the hardened snake's 25 us (dt_w 31 us) the factorisation is kept while
 * the frames turn by 0.02 rad.  A fixed turn below dt_w keeps the second
 * order: W holds the rod's own stiffness alone, so its error is O(theta
 * (h / dt_w)^2) of a kick's update (test_rod_implicit, test_kept_turning:
 * a rod turning at 3 rad/s, kept against made every kick, orders 2.03 and
 * 2.38); a member's band, which holds its ports' stiffer blocks too, needs
 * the turn to shrink with h (sw_implicit_band_kept). */
#define KEEP_SHARE 0.02
#define KEEP_CAP 0.02

/* Whether rod r's kept factorisation (kept: its head, frames and strains)
 * holds for this kick. */
static double keep_theta(double h, double wave_dt) {
  const double ratio = wave_dt / h;
  return fmin(KEEP_CAP, KEEP_SHARE * ratio * ratio);
}
static int kept_holds(const swModel *m, const swData *d, int r, const double *kept, double h,
                      double theta) {
  if (kept[KEPT_H] != h) return 0;
  const int n = m->rod_nelem[r], ea = m->elem_adr[r];
  const double *Qk = kept + KEPT_HEAD, *sk = Qk + 9 * (size_t)n;
  /* the turn of element e's frame: 3 - tr(Q Q_k^T) = 4 sin^2(angle / 2) */
  double turn2 = 0, strain = 0;
  for (int i = 0; i < n; i++) {
    double tr = 0, ds = 0;
    for (int k = 0; k < 9; k++) tr += SW_AT(m, d->Q, ea + i, k) * Qk[(size_t)k * (size_t)n + (size_t)i];
    for (int k = 0; k < 3; k++)
      ds = sw_max(ds, fabs(SW_AT(m, d->sigma, ea + i, k) - sk[(size_t)k * (size_t)n + (size_t)i]));
    turn2 = sw_max(turn2, 3.0 - tr);
    strain = sw_max(strain, ds);
  }
  return turn2 <= theta * theta && strain <= theta;
}

/* What rod r's factorisation is made of, kept beside it. */
static void keep(const swModel *m, const swData *d, int r, double *kept, double h) {
  const int n = m->rod_nelem[r], ea = m->elem_adr[r];
  double *Qk = kept + KEPT_HEAD, *sk = Qk + 9 * (size_t)n;
  kept[KEPT_H] = h;
  kept[KEPT_BAND] = 0;
  for (int k = 0; k < 9; k++)
    for (int i = 0; i < n; i++) Qk[(size_t)k * (size_t)n + (size_t)i] = SW_AT(m, d->Q, ea + i, k);
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < n; i++) sk[(size_t)k * (size_t)n + (size_t)i] = SW_AT(m, d->sigma, ea + i, k);
}

/* The right-hand side h F of rod r's kick, zero where a boundary condition
 * holds the rod. */
static void rod_rhs(const swModel *m, const swData *d, int r, double h, double *rhs) {
  const int n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
  for (int i = 0; i <= n; i++)
    for (int k = 0; k < 3; k++) rhs[6 * i + k] = h * SW_AT(m, d->force, na + i, k);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) rhs[6 * i + 3 + k] = h * SW_AT(m, d->torque, ea + i, k);
  for (int k = 0; k < m->nbc; k++) {
    const size_t o = m->bc[k].rod == r ? held(&m->bc[k], n) : SIZE_MAX;
    if (o != SIZE_MAX) rhs[o] = rhs[o + 1] = rhs[o + 2] = 0;
  }
}

/* The workspace of implicit rod k (rod_scratch): zeros, band, zeros,
 * zeros, rhs, zeros, zeros, inv, what the factorisation was made of.  Its
 * band A, right-hand side and inverse diagonal. */
static double *rod_ws(const swModel *m, const swData *d, int k, double **rhs, double **inv) {
  const size_t N = unknowns(m->rod_nelem[m->implicit_rod[k]]), PB = BAND * (BAND + 1);
  double *ws = d->implicit_sys + m->implicit_adr[k], *A = ws + PB;
  *rhs = A + N * (BAND + 1) + PB + BAND;
  *inv = *rhs + N + 2 * BAND;
  return A;
}

/* Rod k's matrix of this kick, A = M + h/2 C + h^2/4 K, assembled afresh
 * into its band (and the zeros around the band and the right-hand side). */
static void rod_assemble(const swModel *m, const swData *d, int k, double h) {
  const int r = m->implicit_rod[k], n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
  const int damped = m->rod_damping[r] == SW_DAMP_LINEAR;
  const size_t N = unknowns(n), NB = N * (BAND + 1), PB = BAND * (BAND + 1);
  double *rhs, *inv, *A = rod_ws(m, d, k, &rhs, &inv);
  memset(A - PB, 0, PB * sizeof(double));
  memset(A + NB, 0, (PB + BAND) * sizeof(double));
  memset(rhs + N, 0, 2 * BAND * sizeof(double));
  const double c = damped ? 0.5 * h : 0.0;
  /* A = M + h/2 C + h^2/4 K */
  sw_implicit_stiffness(m, d, r, A);
  for (size_t q = 0; q < NB; q++) A[q] *= 0.25 * h * h;
  for (int i = 0; i <= n; i++) { /* masses and damping on the nodes */
    const int s = na + i;
    for (int c3 = 0; c3 < 3; c3++)
      *at(A, 6 * (size_t)i + (size_t)c3, 6 * (size_t)i + (size_t)c3) += d->mass_now[s] + c * m->node_gamma[s];
  }
  for (int i = 0; i < n; i++) { /* inertias J^/e and damping on the elements */
    const int e = ea + i;
    const double dil = sw_inertia_dilatation(m, d, e);
    for (int c3 = 0; c3 < 3; c3++) {
      const size_t q = 6 * (size_t)i + 3 + (size_t)c3;
      *at(A, q, q) += SW_AT(m, d->inertia_now, e, c3) / dil + c * SW_AT(m, m->elem_gamma, e, c3);
    }
  }
  rod_holds(m, r, A, N);
}

/* Rod r's system of this kick, A = M + h/2 C + h^2/4 K and rhs = h F, in
 * its workspace (rod_ws); *rhs_out and *inv_out point into it.  The
 * factorisation of an earlier kick is kept when it holds (above), else A is
 * assembled and factored.  Returns 0 if A could not be factored. */
static int rod_factor(const swModel *m, const swData *d, int k, double *ws, double h,
                      double **rhs_out, double **inv_out) {
  const int r = m->implicit_rod[k], n = m->rod_nelem[r];
  double *rhs, *inv, *A = rod_ws(m, d, k, &rhs, &inv);
  double *kept = ws + system_len(n);
  *rhs_out = rhs, *inv_out = inv;
  rod_rhs(m, d, r, h, rhs);
  /* a rod whose stiffness and inertia change in time (swell.c) factors
   * afresh at every kick: a kept system would hold an earlier geometry's */
  const int swells = m->nswell && sw_swell_of_rod(m, r) >= 0;
  if (!swells && kept[KEPT_BAND] == 0 &&
      kept_holds(m, d, r, kept, h, keep_theta(h, m->implicit_wave_dt[k]))) {
    kept[KEPT_REUSED] += 1;
    return 1;
  }
  rod_assemble(m, d, k, h);
  kept[KEPT_H] = 0; /* no factorisation kept unless this one succeeds */
  if (!band_ldlt_factor(A, unknowns(n), inv)) return 0;
  keep(m, d, r, kept, h);
  kept[KEPT_FRESH] += 1;
  return 1;
}

/* The implicit rods' number of rod r, or nimplicit. */
static int implicit_of(const swModel *m, int r) {
  int k = 0;
  while (k < m->nimplicit && m->implicit_rod[k] != r) k++;
  return k;
}

double *sw_implicit_band_begin(const swModel *m, swData *d, int r, double h, double **rhs) {
  const int k = implicit_of(m, r);
  if (k == m->nimplicit) return NULL;
  double *inv, *A = rod_ws(m, d, k, rhs, &inv);
  double *kept = d->implicit_sys + m->implicit_adr[k] + system_len(m->rod_nelem[r]);
  rod_rhs(m, d, r, h, *rhs);
  rod_assemble(m, d, k, h);
  kept[KEPT_H] = 0; /* the band will hold more than the rod's own system: nothing kept */
  return A;
}

/* Rod r's band as sw_implicit_band_begin and its callers left it, factored
 * afresh (and counted so): the matrix, with its right-hand side, inverse
 * pivots and size; NULL when it is not positive definite. */
static double *band_factor(const swModel *m, swData *d, int r, double **rhs, double **inv, size_t *N) {
  const int k = implicit_of(m, r);
  double *A = rod_ws(m, d, k, rhs, inv);
  double *kept = d->implicit_sys + m->implicit_adr[k] + system_len(m->rod_nelem[r]);
  *N = unknowns(m->rod_nelem[r]);
  if (!band_ldlt_factor(A, *N, *inv)) return NULL;
  kept[KEPT_FRESH] += 1;
  return A;
}

int sw_implicit_band_solve(const swModel *m, swData *d, int r) {
  double *rhs, *inv;
  size_t N;
  const double *A = band_factor(m, d, r, &rhs, &inv, &N);
  if (!A) return 0;
  band_ldlt_solve(A, N, rhs, inv);
  return 1;
}

int sw_implicit_band_solve_many(const swModel *m, swData *d, int r, double *X, int ld) {
  double *rhs, *inv;
  size_t N;
  const double *A = band_factor(m, d, r, &rhs, &inv, &N);
  if (!A) return 0;
  for (size_t i = 0; i < N; i++) X[i * (size_t)ld] = rhs[i];
  band_ldlt_solve_many(A, N, X, (size_t)ld, inv);
  return 1;
}

/* A member's band path keeping its band (issue 32): the band factored at
 * an earlier kick with its band ports' blocks is solved again while the
 * rod's frames and strains have moved by at most theta (kept_holds) and
 * the ports' blocks by at most theta of themselves (joint_ports.c checks
 * those); the kick then assembles its right-hand side alone: the matrix is
 * an earlier configuration's, the right-hand side and the ports' maps this
 * one's.  Here theta is the rod's own (above) times h / dt_w below dt_w:
 * kept for a fixed turn, the matrix is off by O(1) of theta whatever the
 * step, an error of theta h a kick, first order (measured on
 * test_joint_alias's digits: the feathers' mean fall 0.24%, 0.77% and
 * 0.12% off at 1, 1/2 and 1/4 us), where a turn proportional to h keeps
 * the W-method's O(h) and the trapezoidal rule's second order. */
double *sw_implicit_band_kept(const swModel *m, swData *d, int r, double h, double *theta) {
  const int k = implicit_of(m, r);
  if (k == m->nimplicit || (m->nswell && sw_swell_of_rod(m, r) >= 0)) return NULL;
  double *rhs, *inv;
  (void)rod_ws(m, d, k, &rhs, &inv);
  const double *kept = d->implicit_sys + m->implicit_adr[k] + system_len(m->rod_nelem[r]);
  const double dt_w = m->implicit_wave_dt[k];
  *theta = keep_theta(h, dt_w) * fmin(1.0, h / dt_w);
  if (kept[KEPT_BAND] != 1 || !kept_holds(m, d, r, kept, h, *theta)) return NULL;
  rod_rhs(m, d, r, h, rhs);
  return rhs;
}

void sw_implicit_band_keep(const swModel *m, swData *d, int r, double h) {
  const int k = implicit_of(m, r);
  if (k == m->nimplicit) return;
  double *kept = d->implicit_sys + m->implicit_adr[k] + system_len(m->rod_nelem[r]);
  keep(m, d, r, kept, h);
  kept[KEPT_BAND] = 1;
}

void sw_implicit_band_solve_kept(const swModel *m, swData *d, int r, double *X, int ld, int all) {
  const int k = implicit_of(m, r);
  double *rhs, *inv;
  const double *A = rod_ws(m, d, k, &rhs, &inv);
  double *kept = d->implicit_sys + m->implicit_adr[k] + system_len(m->rod_nelem[r]);
  const size_t N = unknowns(m->rod_nelem[r]);
  if (all) { /* every column */
    for (size_t i = 0; i < N; i++) X[i * (size_t)ld] = rhs[i];
    band_ldlt_solve_many(A, N, X, (size_t)ld, inv);
  } else { /* one right-hand side: a chain of one multiply-add a row */
    band_ldlt_solve(A, N, rhs, inv);
    for (size_t i = 0; i < N; i++) X[i * (size_t)ld] = rhs[i];
  }
  kept[KEPT_REUSED] += 1;
}

void sw_implicit_kept_frame(const swModel *m, const swData *d, int r, int e, double *Q) {
  const int k = implicit_of(m, r), n = m->rod_nelem[r];
  const double *Qk = d->implicit_sys + m->implicit_adr[k] + system_len(n) + KEPT_HEAD;
  for (int c = 0; c < 9; c++) Q[c] = Qk[(size_t)c * (size_t)n + (size_t)(e - m->elem_adr[r])];
}

void sw_implicit_apply(const swModel *m, swData *d, int r, const double *du, size_t stride,
                       double h) {
  const int n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
  const double ih = 1.0 / h; /* one division, not one per unknown (a sixth of the kept kick) */
  for (int i = 0; i <= n; i++)
    for (int k = 0; k < 3; k++)
      SW_AT(m, d->force, na + i, k) = d->mass_now[na + i] * du[(6 * (size_t)i + (size_t)k) * stride] * ih;
  for (int i = 0; i < n; i++) {
    const int e = ea + i;
    const double s = ih / sw_inertia_dilatation(m, d, e);
    for (int k = 0; k < 3; k++)
      SW_AT(m, d->torque, e, k) = SW_AT(m, d->inertia_now, e, k) * du[(6 * (size_t)i + 3 + (size_t)k) * stride] * s;
  }
}

/* Implicit rod k's kick: its system (rod_factor), solved, and the
 * effective loads into d->force and d->torque.  Returns 0 if the system
 * could not be factored. */
static int rod_kick(const swModel *m, swData *d, int k, double h) {
  double *rhs, *inv, *ws = d->implicit_sys + m->implicit_adr[k];
  const int r = m->implicit_rod[k];
  if (!rod_factor(m, d, k, ws, h, &rhs, &inv)) return 0;
  const size_t PB = BAND * (BAND + 1);
  band_ldlt_solve(ws + PB, unknowns(m->rod_nelem[r]), rhs, inv);
  sw_implicit_apply(m, d, r, rhs, 1, h);
  return 1;
}

int sw_implicit_solve_many(const swModel *m, swData *d, int r, double h, double *X, int ld) {
  const int k = implicit_of(m, r);
  double *rhs, *inv, *ws = k < m->nimplicit ? d->implicit_sys + m->implicit_adr[k] : NULL;
  if (!ws || !rod_factor(m, d, k, ws, h, &rhs, &inv)) return 0;
  const size_t N = unknowns(m->rod_nelem[r]), PB = BAND * (BAND + 1);
  for (size_t i = 0; i < N; i++) X[i * (size_t)ld] = rhs[i];
  band_ldlt_solve_many(ws + PB, N, X, (size_t)ld, inv);
  return 1;
}

void sw_implicit_reset(const swModel *m, swData *d) {
  for (int k = 0; k < m->nimplicit; k++) {
    double *kept = d->implicit_sys + m->implicit_adr[k] + system_len(m->rod_nelem[m->implicit_rod[k]]);
    kept[KEPT_H] = kept[KEPT_FRESH] = kept[KEPT_REUSED] = 0;
  }
}

void sw_implicit_counts(const swModel *m, const swData *d, double *fresh, double *kept_count) {
  *fresh = *kept_count = 0;
  for (int k = 0; k < m->nimplicit; k++) {
    const double *kept =
        d->implicit_sys + m->implicit_adr[k] + system_len(m->rod_nelem[m->implicit_rod[k]]);
    *fresh += kept[KEPT_FRESH];
    *kept_count += kept[KEPT_REUSED];
  }
}

size_t sw_implicit_unknowns(const swModel *m, int r) { return unknowns(m->rod_nelem[r]); }

/* Every thread calls it after the loads of a kick, and solves the rods of
 * its rank (rod k on thread k mod team): each rod's solve is its own, so
 * the bits do not depend on the team.  A system that cannot be factored
 * leaves the explicit loads, and the instability check reports the rod. */
void sw_implicit_kick(const swModel *m, swData *d, double h) {
  if (!m->nimplicit) return;
  sw_team_barrier(d); /* every load of every slot is in */
  const int size = d->team_size > 1 ? d->team_size : 1, rank = sw_team_rank(d);
  for (int k = rank; k < m->nimplicit; k += size)
    if (m->rod_block[m->implicit_rod[k]] < 0) /* else a member of rigid_joint.c's system */
      (void)rod_kick(m, d, k, h);
  sw_team_barrier(d); /* the effective loads, before any thread's kick reads them */
}
