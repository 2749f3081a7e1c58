/* rigid.c — rigid rods: a rod that moves as one rigid body (a bone whose
 * deformation the scene does not need).
 *
 * Design.  A rigid rod keeps its nodes and elements in the per-slot arrays
 * (its slots come after all elastic rods'; sinew.h, "Layout"), so
 * loads, gravity, joints and the output see an ordinary rod, but its motion is
 * that of one body b: centre of mass X, velocity V, rotation R (body frame ->
 * lab) and angular momentum L about X (lab).  Node i sits at X + R p_i and
 * element e has the frame Q_e = B_e R^T, with p_i and B_e fixed at t = 0; the
 * body frame is the principal frame of the inertia tensor, which is built from
 * the rod's own lumped node masses (parallel-axis sum about X) and element
 * inertias J^ (rotated into the lab by Q_e^T J^ Q_e), so a rigid rod has
 * exactly the mass and inertia its elastic twin has.  rod.c computes no
 * internal loads for it (sw_rigid_internal sets the rest strains).
 *
 * The rigid bodies share the drift/kick splitting of integrate.c (position
 * Verlet or PEFRL), with H = T(V, L) + U(X, R):
 *   kick h:  V += h F / M,  L += h tau,  F = sum f_i (lab) and
 *            tau = sum (x_i - X) x f_i + sum Q_e^T c_e (element couples are
 *            in each element's material frame); the work of the external
 *            part is booked with the midpoint rule on the node and element
 *            velocities, as for elastic rods, which makes it the exact change
 *            of M V^2/2 + L . w / 2 over the kick;
 *   drift h: X += h V and the free rotation of the body under T = sum
 *            pi_k^2 / (2 I_k), pi = R^T L (lab L is constant in a drift).
 * The free rotation is split into flows that are exact rotations: with I_a
 * the middle principal moment,
 *   T = |pi|^2 / (2 I_a) + sum_{k != a} (1/I_k - 1/I_a) pi_k^2 / 2.
 * The first flow turns R about pi by h |pi| / I_a and commutes with the
 * others (|pi|^2 is a Casimir); each of the others turns R about the body
 * axis e_k by h (1/I_k - 1/I_a) pi_k and pi the opposite way (Dullweber,
 * Leimkuhler & McLachlan, J. Chem. Phys. 107 (1997) 5840; this splitting
 * with the Casimir is among those compared by Fasso, J. Comput. Phys. 189
 * (2003) 527).  The two axis flows are composed symmetrically (Strang, second
 * order) for position Verlet, and by Yoshida's triple jump (Phys. Lett. A 150
 * (1990) 262, fourth order) inside PEFRL, so each scheme keeps its order.  Every
 * piece is an exact rotation, so the drift is symplectic, |L| and lab L are
 * conserved to round-off, the energy error stays bounded, and the shape of
 * the body never drifts: x_i - X = R p_i with R re-orthonormalised after each
 * drift.  For a body with two equal moments (a straight rod of circular
 * section) the axis flow that is left vanishes and the drift is exact.
 *
 * After every drift and kick the nodes and elements are set from the body
 * (x_i, v_i = V + w x (x_i - X), Q_e, w_e = Q_e w), so everything that reads
 * them (joints, damping, energy, output, the stability check) sees the
 * body's motion.  A clamped rigid rod never moves (rigid_fixed).
 */
#include <math.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* ---- 3x3 algebra that vec.h does not have ---- */

/* C = A^T B */
static inline void mat_T_mul(double *C, const double *A, const double *B) {
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * i + j] = A[i] * B[j] + A[3 + i] * B[3 + j] + A[6 + i] * B[6 + j];
  memcpy(C, T, sizeof T);
}

static double det3(const double *A) {
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
         A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* Eigen-decomposition A = V diag(ev) V^T of a symmetric 3x3 matrix by cyclic
 * Jacobi rotations (Golub & Van Loan, sec. 8.5), eigenvalues ascending, V
 * orthonormal with det V = +1 (a rotation). */
static void sym3_eigen(const double *A, double ev[3], double *V) {
  double a[9];
  memcpy(a, A, sizeof a);
  for (int k = 0; k < 9; k++) V[k] = (k % 4 == 0);
  for (int sweep = 0; sweep < 64; sweep++) {
    double off = a[1] * a[1] + a[2] * a[2] + a[5] * a[5];
    double diag = a[0] * a[0] + a[4] * a[4] + a[8] * a[8];
    if (!(off > 1e-36 * diag)) break;
    for (int p = 0; p < 2; p++)
      for (int q = p + 1; q < 3; q++) {
        double apq = a[3 * p + q];
        if (apq == 0) continue;
        /* the rotation in the (p, q) plane that zeroes a_pq */
        double theta = (a[3 * q + q] - a[3 * p + p]) / (2 * apq);
        double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1));
        double c = 1 / sqrt(t * t + 1), s = t * c;
        double J[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        J[3 * p + p] = c, J[3 * q + q] = c, J[3 * p + q] = s, J[3 * q + p] = -s;
        double aJ[9];
        sw_mat_mul(aJ, a, J);
        mat_T_mul(a, J, aJ);
        sw_mat_mul(V, V, J);
      }
  }
  int idx[3] = {0, 1, 2};
  for (int i = 0; i < 3; i++) /* sort ascending */
    for (int j = i + 1; j < 3; j++)
      if (a[4 * idx[j]] < a[4 * idx[i]]) { int t = idx[i]; idx[i] = idx[j]; idx[j] = t; }
  double W[9];
  for (int k = 0; k < 3; k++) {
    ev[k] = a[4 * idx[k]];
    for (int i = 0; i < 3; i++) W[3 * i + k] = V[3 * i + idx[k]];
  }
  if (det3(W) < 0)
    for (int i = 0; i < 3; i++) W[3 * i + 2] = -W[3 * i + 2];
  memcpy(V, W, sizeof W);
}

/* R <- R (3 I - R^T R) / 2: one Newton step towards the nearest rotation
 * (Bjorck & Bowie 1971), which removes the round-off a product of rotations
 * accumulates, quadratically. */
static void reorthonormalise(double *R) {
  double RtR[9], S[9];
  mat_T_mul(RtR, R, R);
  for (int k = 0; k < 9; k++) S[k] = 0.5 * ((k % 4 == 0) * 3.0 - RtR[k]);
  sw_mat_mul(R, R, S);
}

/* w = R diag(1/I) R^T L: the lab angular velocity of the body. */
static inline void angular_velocity(double *w, const double *R, const double *I, const double *L) {
  double pi[3];
  sw_matT_vec(pi, R, L);
  for (int k = 0; k < 3; k++) pi[k] /= I[k];
  sw_mat_vec(w, R, pi);
}

/* ---- the free rotation (drift) ---- */

/* R <- R exp(theta [e_k]x), pi <- exp(-theta [e_k]x) pi: body axis k turns R
 * by theta and the body-frame momentum the other way (lab L = R pi kept). */
static void turn_about_axis(double *R, double *pi, int k, double theta) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const double c = cos(theta), s = sin(theta);
  for (int row = 0; row < 3; row++) {
    double ri = R[3 * row + i], rj = R[3 * row + j];
    R[3 * row + i] = c * ri + s * rj;
    R[3 * row + j] = -s * ri + c * rj;
  }
  double pii = pi[i], pij = pi[j];
  pi[i] = c * pii + s * pij;
  pi[j] = -s * pii + c * pij;
}

/* The flows of the two axis terms (axes 0 and 2, the moments being
 * ascending), composed symmetrically over a time tau. */
static void axis_flows(double *R, double *pi, const double *c, double tau) {
  turn_about_axis(R, pi, 0, 0.5 * tau * c[0] * pi[0]);
  turn_about_axis(R, pi, 2, tau * c[2] * pi[2]);
  turn_about_axis(R, pi, 0, 0.5 * tau * c[0] * pi[0]);
}

/* Yoshida 1990, eq. 5.3: x1 = 1 / (2 - 2^(1/3)), x0 = 1 - 2 x1. */
static const double YOSHIDA_X1 = 1.3512071919596578;
static const double YOSHIDA_X0 = -1.7024143839193153;

/* The free rotation of a body with principal moments I (ascending) over h:
 * R and the body-frame momentum pi move, lab L = R pi stays. */
static void free_rotation(double *R, double *pi, const double *I, double h, int fourth_order) {
  /* Casimir flow: R <- R exp([phi]x), phi = h pi / I_1, about pi, which it
   * leaves alone; row r of R becomes r + a r x phi + b (r x phi) x phi. */
  double phi[3], a, b;
  sw_v3_scale(phi, pi, h / I[1]);
  sw_rodrigues_coeffs(sw_v3_dot(phi, phi), &a, &b);
  for (int row = 0; row < 3; row++) {
    double *r = R + 3 * row, rp[3], rpp[3];
    sw_v3_cross(rp, r, phi);
    sw_v3_cross(rpp, rp, phi);
    for (int k = 0; k < 3; k++) r[k] += a * rp[k] + b * rpp[k];
  }
  const double c[3] = {1 / I[0] - 1 / I[1], 0, 1 / I[2] - 1 / I[1]};
  if (c[0] == 0 || c[2] == 0) {
    /* two equal moments (setup makes them exactly equal): one axis flow is
     * left, and it is exact over the whole drift */
    int k = c[0] == 0 ? 2 : 0;
    if (c[k] != 0) turn_about_axis(R, pi, k, h * c[k] * pi[k]);
  } else if (fourth_order) {
    axis_flows(R, pi, c, YOSHIDA_X1 * h);
    axis_flows(R, pi, c, YOSHIDA_X0 * h);
    axis_flows(R, pi, c, YOSHIDA_X1 * h);
  } else {
    axis_flows(R, pi, c, h);
  }
}

/* ---- nodes and elements from the body ---- */

/* Node and element velocities from V and w; with `place`, positions and
 * frames from X and R first. */
static void body_to_rod(const swModel *m, swData *d, int b, int place) {
  const int r = m->rigid_rod[b], n = m->rod_nelem[r];
  const int na = m->node_adr[r], ea = m->elem_adr[r];
  const double *X = d->rigid_X + 3 * b, *V = d->rigid_V + 3 * b, *R = d->rigid_R + 9 * b;
  const double *w = d->rigid_omega + 3 * b;
  const double *p = m->rigid_p + 3 * m->rigid_node_adr[b];
  const double *B = m->rigid_B + 9 * m->rigid_elem_adr[b];
  for (int i = 0; i <= n; i++) {
    double x[3], v[3], rel[3], wr[3];
    if (place) {
      sw_mat_vec(rel, R, p + 3 * i);
      sw_v3_add(x, X, rel);
      sw_set3(m, d->x, na + i, x);
    } else {
      sw_get3(m, d->x, na + i, x);
      sw_v3_sub(rel, x, X);
    }
    sw_v3_cross(wr, w, rel);
    sw_v3_add(v, V, wr);
    sw_set3(m, d->v, na + i, v);
  }
  for (int e = 0; e < n; e++) {
    double Q[9], om[3];
    if (place) { /* Q = B R^T: Q_jk = B_j . R_k (rows) */
      for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++) Q[3 * j + k] = sw_v3_dot(B + 9 * e + 3 * j, R + 3 * k);
      sw_setQ(m, d->Q, ea + e, Q);
    } else {
      sw_getQ(m, d->Q, ea + e, Q);
    }
    sw_mat_vec(om, Q, w);
    sw_set3(m, d->omega, ea + e, om);
  }
}

/* ---- model ---- */

void sw_rigid_setup(swModel *m) {
  for (int b = 0; b < m->nrigid; b++) {
    const int r = m->rigid_rod[b], n = m->rod_nelem[r];
    const int na = m->node_adr[r], ea = m->elem_adr[r];
    double M = 0, X[3] = {0, 0, 0}, I[9] = {0};
    for (int i = na; i <= na + n; i++) {
      M += m->mass[i];
      for (int k = 0; k < 3; k++) X[k] += m->mass[i] * SW_AT(m, m->x0, i, k);
    }
    sw_v3_scale(X, X, 1 / M);
    /* parallel-axis sum of the node masses, m (|r|^2 1 - r r^T) */
    for (int i = na; i <= na + n; i++) {
      double rel[3], xi[3];
      sw_get3(m, m->x0, i, xi);
      sw_v3_sub(rel, xi, X);
      double r2 = sw_v3_dot(rel, rel);
      for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++) I[3 * j + k] += m->mass[i] * ((j == k) * r2 - rel[j] * rel[k]);
    }
    /* the elements' own rotational inertia, Q^T diag(J^) Q (lab) */
    for (int e = ea; e < ea + n; e++) {
      double Q[9], J[3];
      sw_getQ(m, m->Q0, e, Q);
      sw_get3(m, m->inertia, e, J);
      for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++)
          for (int c = 0; c < 3; c++) I[3 * j + k] += Q[3 * c + j] * J[c] * Q[3 * c + k];
    }
    double *R0 = m->rigid_R0 + 9 * b, *Ip = m->rigid_inertia + 3 * b;
    sym3_eigen(I, Ip, R0);
    /* moments equal to round-off are equal (a straight rod of circular
     * section is a symmetric top, whose free rotation the drift does exactly) */
    for (int k = 0; k < 2; k++)
      if (Ip[k + 1] - Ip[k] <= 1e-12 * Ip[k + 1]) Ip[k + 1] = Ip[k];
    m->rigid_mass[b] = M;
    memcpy(m->rigid_X0 + 3 * b, X, sizeof X);
    double *p = m->rigid_p + 3 * m->rigid_node_adr[b];
    for (int i = 0; i <= n; i++) {
      double rel[3], xi[3];
      sw_get3(m, m->x0, na + i, xi);
      sw_v3_sub(rel, xi, X);
      sw_matT_vec(p + 3 * i, R0, rel);
    }
    double *B = m->rigid_B + 9 * m->rigid_elem_adr[b];
    for (int e = 0; e < n; e++) {
      double Q[9];
      sw_getQ(m, m->Q0, ea + e, Q);
      sw_mat_mul(B + 9 * e, Q, R0);
    }
    m->rigid_fixed[b] = 0;
    for (int k = 0; k < m->nbc; k++)
      if (m->bc[k].rod == r && m->bc[k].kind == SW_BC_CLAMP) m->rigid_fixed[b] = 1;
  }
}

/* ---- state ---- */

void sw_rigid_reset(const swModel *m, swData *d) {
  for (int b = 0; b < m->nrigid; b++) {
    memcpy(d->rigid_X + 3 * b, m->rigid_X0 + 3 * b, 3 * sizeof(double));
    memcpy(d->rigid_R + 9 * b, m->rigid_R0 + 9 * b, 9 * sizeof(double));
    memset(d->rigid_V + 3 * b, 0, 3 * sizeof(double));
    memset(d->rigid_L + 3 * b, 0, 3 * sizeof(double));
    memset(d->rigid_omega + 3 * b, 0, 3 * sizeof(double));
    body_to_rod(m, d, b, 0); /* nodes stay at x0 exactly, at rest */
  }
}

int sw_rigid_set_motion(const swModel *m, swData *d, int rod, const double V[3],
                        const double omega[3]) {
  if (rod < 0 || rod >= m->nrod || !m->nrigid || m->rod_rigid[rod] < 0) return SW_EUSAGE;
  const int b = m->rod_rigid[rod];
  if (m->rigid_fixed[b]) return SW_EUSAGE;
  const double *R = d->rigid_R + 9 * b, *I = m->rigid_inertia + 3 * b;
  double Om[3];
  sw_matT_vec(Om, R, omega);
  for (int k = 0; k < 3; k++) Om[k] *= I[k];
  sw_mat_vec(d->rigid_L + 3 * b, R, Om); /* L = R I R^T w */
  memcpy(d->rigid_V + 3 * b, V, 3 * sizeof(double));
  angular_velocity(d->rigid_omega + 3 * b, R, I, d->rigid_L + 3 * b);
  body_to_rod(m, d, b, 0);
  return SW_OK;
}

/* No internal loads; the strains stay at their rest values, so the elastic
 * energy (energy.c) is zero and whatever divides by a length or a dilatation
 * sees the rest geometry, which is the rod's real geometry. */
void sw_rigid_internal(const swModel *m, swData *d, int r) {
  const int n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r], va = m->vor_adr[r];
  for (int k = 0; k < 3; k++) { /* plane by plane (sinew.h, "Layout") */
    memset(&SW_AT(m, d->force, na, k), 0, (size_t)(n + 1) * sizeof(double));
    memset(&SW_AT(m, d->torque, ea, k), 0, (size_t)n * sizeof(double));
    memset(&SW_AT(m, d->stress, ea, k), 0, (size_t)n * sizeof(double));
    memcpy(&SW_AT(m, d->sigma, ea, k), &SW_AT(m, m->rest_sigma, ea, k), (size_t)n * sizeof(double));
  }
  memcpy(d->length + ea, m->rest_len + ea, (size_t)n * sizeof(double));
  for (int e = ea; e < ea + n; e++) d->dilatation[e] = 1.0;
  if (n > 1) {
    for (int k = 0; k < 3; k++) {
      memset(&SW_AT(m, d->couple, va, k), 0, (size_t)(n - 1) * sizeof(double));
      memcpy(&SW_AT(m, d->kappa, va, k), &SW_AT(m, m->rest_kappa, va, k), (size_t)(n - 1) * sizeof(double));
    }
    for (int j = va; j < va + n - 1; j++) d->vor_dilatation[j] = 1.0;
  }
}

/* sw_rigid_internal as a step needs it: the internal loads of every rigid
 * rod, zero, in one pass over their slots, [nslot_elastic, nslot) (model.c
 * lays them out after the elastic rods'), instead of a rod at a time.  That
 * range holds the rods' nodes, all of them, and their elements with one
 * ghost each, whose torque is zero already (nothing acts on a ghost:
 * loads.c adds a zero there) and stays so.  The rest strains are left
 * alone: sw_internal_loads (sw_reset) set them and nothing in a step changes
 * them on a rigid rod.  A step used to write them again, 14 to 20 calls of
 * memset and memcpy on a few doubles per rod and kick, which cost the
 * muscular snake's 24 bodies about 2.5% of its step (docs/benchmarks.md,
 * "The muscular snake's step"). */
void sw_rigid_clear_loads(const swModel *m, swData *d) {
  const size_t S = (size_t)m->stride, lo = (size_t)m->nslot_elastic;
  const size_t bytes = (size_t)(m->nslot - m->nslot_elastic) * sizeof(double);
  for (int k = 0; k < 3; k++) {
    memset(d->force + k * S + lo, 0, bytes);
    memset(d->torque + k * S + lo, 0, bytes);
  }
}

/* ---- the step ---- */

void sw_rigid_drift(const swModel *m, swData *d, double h) {
  const int fourth = m->integrator == SW_PEFRL;
  for (int b = 0; b < m->nrigid; b++) {
    if (m->rigid_fixed[b]) continue;
    double *X = d->rigid_X + 3 * b, *R = d->rigid_R + 9 * b;
    const double *V = d->rigid_V + 3 * b, *L = d->rigid_L + 3 * b, *I = m->rigid_inertia + 3 * b;
    for (int k = 0; k < 3; k++) X[k] += h * V[k];
    double pi[3];
    sw_matT_vec(pi, R, L);
    free_rotation(R, pi, I, h, fourth);
    reorthonormalise(R);
    angular_velocity(d->rigid_omega + 3 * b, R, I, L);
    body_to_rod(m, d, b, 1);
  }
}

/* The loads on body b: F = sum of the node forces, tau = their moments about
 * X plus the element couples (in the lab), into load[0..5]. */
static void body_loads(const swModel *m, const swData *d, int b, double *load) {
  const int r = m->rigid_rod[b], n = m->rod_nelem[r];
  const int na = m->node_adr[r], ea = m->elem_adr[r];
  const double *X = d->rigid_X + 3 * b;
  double *F = load, *tau = load + 3;
  memset(load, 0, 6 * sizeof(double));
  for (int i = na; i <= na + n; i++) {
    double f[3], xi[3], rel[3], mom[3];
    sw_get3(m, d->force, i, f);
    sw_get3(m, d->x, i, xi);
    sw_v3_sub(rel, xi, X);
    sw_v3_cross(mom, rel, f);
    sw_v3_add(F, F, f);
    sw_v3_add(tau, tau, mom);
  }
  for (int e = ea; e < ea + n; e++) {
    double c[3], Q[9], t[3];
    sw_getQ(m, d->Q, e, Q);
    sw_get3(m, d->torque, e, t);
    sw_matT_vec(c, Q, t);
    sw_v3_add(tau, tau, c);
  }
}

void sw_rigid_loads(const swModel *m, swData *d, double h) {
  for (int b = 0; b < m->nrigid; b++)
    if (!m->rigid_fixed[b]) body_loads(m, d, b, d->rigid_load + 6 * b);
  /* imex: the loads that give the trapezoidal step of the stiff joints; a
   * system that cannot be factored has a non-finite state, which the
   * step's check reports, so the explicit loads stand */
  if (m->nrigid_block) sw_rigid_joints_kick(m, d, h, d->rigid_load);
}

void sw_rigid_kick(const swModel *m, swData *d, double h) {
  double work = 0;
  for (int b = 0; b < m->nrigid; b++) {
    if (m->rigid_fixed[b]) continue;
    const int r = m->rigid_rod[b], n = m->rod_nelem[r];
    const int na = m->node_adr[r], ea = m->elem_adr[r];
    double *V = d->rigid_V + 3 * b, *L = d->rigid_L + 3 * b, *w = d->rigid_omega + 3 * b;
    const double *X = d->rigid_X + 3 * b, *F = d->rigid_load + 6 * b, *tau = F + 3;
    const double hM = h / m->rigid_mass[b];
    for (int k = 0; k < 3; k++) {
      V[k] += hM * F[k];
      L[k] += h * tau[k];
    }
    angular_velocity(w, d->rigid_R + 9 * b, m->rigid_inertia + 3 * b, L);
    /* new node and element velocities; the external loads' work with the
     * midpoint rule, as integrate.c books it for elastic rods */
    double vold[3], wold[3];
    for (int i = na; i <= na + n; i++) {
      sw_get3(m, d->v, i, vold);
      double xi[3], vi[3], rel[3], wr[3];
      sw_get3(m, d->x, i, xi);
      sw_v3_sub(rel, xi, X);
      sw_v3_cross(wr, w, rel);
      sw_v3_add(vi, V, wr);
      sw_set3(m, d->v, i, vi);
      for (int k = 0; k < 3; k++) work += SW_AT(m, d->ext_force, i, k) * (vold[k] + vi[k]);
    }
    for (int e = ea; e < ea + n; e++) {
      double Q[9], we[3];
      sw_get3(m, d->omega, e, wold);
      sw_getQ(m, d->Q, e, Q);
      sw_mat_vec(we, Q, w);
      sw_set3(m, d->omega, e, we);
      for (int k = 0; k < 3; k++) work += SW_AT(m, d->ext_torque, e, k) * (wold[k] + we[k]);
    }
  }
  d->work += 0.5 * h * work;
}

/* ---- stable time step ---- */

/* Largest h c for which the scheme's kicks keep v' = -c v bounded: position
 * Verlet |1 - x| <= 1; PEFRL (1 - a x)(1 - lambda x) >= -1 with its kick
 * coefficients a = (1 - 2 lambda)/2 and lambda (Omelyan et al. 2002). */
static double damping_limit(swIntegrator integ) {
  if (integ != SW_PEFRL) return 2.0;
  const double la = -0.2123418310626054, a = 0.5 * (1 - 2 * la), p = a * la;
  return (0.5 - sqrt(0.25 - 8 * p)) / (2 * p); /* root of p x^2 - x/2 + 2 = 0 */
}

/* The largest linear damping rate of the body: the rod's dissipation is
 * mass-proportional element by element, so the body's damping matrix is
 * bounded by max c_i times its mass matrix. */
static double damping_rate(const swModel *m, int b) {
  const int r = m->rigid_rod[b];
  if (m->rod_damping[r] != SW_DAMP_LINEAR) return 0;
  const int n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
  double c = 0;
  for (int i = na; i <= na + n; i++) c = fmax(c, m->node_gamma[i] * m->inv_mass[i]);
  for (int e = ea; e < ea + n; e++)
    for (int k = 0; k < 3; k++)
      c = fmax(c, SW_AT(m, m->elem_gamma, e, k) * SW_AT(m, m->inv_inertia, e, k));
  return c;
}

double sw_rigid_stable_dt(const swModel *m, int b) {
  double c = damping_rate(m, b);
  if (m->rigid_fixed[b] || !(c > 0)) return INFINITY;
  return 0.95 * damping_limit(m->integrator) / c;
}

/* 1 / (smallest effective mass) of body b at its node i: the largest
 * eigenvalue of the mobility K = 1/M - [r]x I^-1 [r]x, r = x_i - X (what a
 * unit impulse at the node does to the node's velocity). */
static double node_mobility(const swModel *m, int b, int i) {
  const int r = m->rigid_rod[b];
  const double *p = m->rigid_p + 3 * (m->rigid_node_adr[b] + i - m->node_adr[r]);
  const double *I = m->rigid_inertia + 3 * b; /* body frame: I diagonal */
  double K[9], ev[3], V[9];
  for (int j = 0; j < 3; j++)
    for (int k = 0; k < 3; k++) {
      /* -([p]x diag(1/I) [p]x)_jk = sum_c e_jcm e_kcn p_m p_n / I_c */
      double s = 0;
      for (int c = 0; c < 3; c++) {
        double pj[3] = {0, 0, 0}, pk[3] = {0, 0, 0}, ej[3] = {0, 0, 0}, ek[3] = {0, 0, 0};
        ej[j] = 1, ek[k] = 1;
        sw_v3_cross(pj, p, ej); /* ([p]x e_j)_c */
        sw_v3_cross(pk, p, ek);
        s += pj[c] * pk[c] / I[c];
      }
      K[3 * j + k] = (j == k) / m->rigid_mass[b] + s;
    }
  sym3_eigen(K, ev, V);
  return ev[2];
}

/* The joints' bound on a rigid body (stability.c calls it for each joint
 * with a rigid side).  Every joint on the body adds a spring to the same six
 * degrees of freedom, so the body's highest frequency is bounded by the sum
 * over its joints: w^2 <= sum s (k mob_i + k_t / I_min), with mob_i the
 * node mobility above, I_min the smallest principal moment (the couple's
 * mobility), s = 2 when the other side moves, 1 when anchored; damping
 * c = sum s (nu mob_i + c_t / I_min) + the rod's own rate.  The rod's
 * stiffness does not enter: a rigid rod has none. */
double sw_rigid_joint_dt(const swModel *m, int b) {
  if (m->rigid_fixed[b]) return INFINITY;
  const int r = m->rigid_rod[b];
  const double Imin = m->rigid_inertia[3 * b];
  double w2 = 0, c = damping_rate(m, b);
  for (int j = 0; j < m->njoint; j++) {
    if (m->joint_implicit[j]) continue; /* rigid_joint.c: no step limit */
    const swJointDesc *jd = &m->joint[j];
    const int s = jd->rod_b >= 0 ? 2 : 1;
    for (int side = 0; side < 2; side++) {
      int rod = side ? jd->rod_b : jd->rod_a;
      int node = side ? m->joint_node_b[j] : m->joint_node_a[j];
      if (rod != r) continue;
      double mob = node_mobility(m, b, node);
      w2 += s * jd->stiffness * mob;
      c += s * jd->damping * mob;
      if (jd->kind != SW_JOINT_SPHERICAL || sw_joint_limited(jd)) { /* with its limit */
        w2 += s * sw_joint_rot_bound_stiffness(jd) / Imin;
        c += s * sw_joint_rot_bound_damping(jd) / Imin;
      }
    }
  }
  if (!(w2 > 0)) return c > 0 ? 0.95 * damping_limit(m->integrator) / c : INFINITY;
  double w = sqrt(w2);
  return 0.95 * sw_integrator_stability_limit(m->integrator, c / (2 * w)) / w;
}
