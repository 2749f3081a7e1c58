/* rod.c — strains, internal forces and internal couples of Cosserat rods.
 *
 * Design.  The rods' slots are one block (sinew.h, "Layout"): elastic rods
 * back to back in [0, nslot_elastic), each followed by its ghost element and
 * ghost domains, which hold zero stiffness and unit lengths.  So every kernel
 * here is a plain loop over a range of slots with no branch on where a rod
 * starts or ends, and the compiler vectorizes it (`#pragma omp simd`; the
 * frame logarithm takes its small-angle series in the loop, and the few
 * domains past it are redone after the loop with the exact one).  Two passes:
 *   sw_rod_pass    element i and Voronoi domain i of every slot, block by
 *                  block (an element loop, then a Voronoi loop): strain,
 *                  internal force n and its lab-frame image f_i = Q_i^T n_i,
 *                  the element's own couples; curvature, bending couple c_i
 *                  and the half transport term;
 *   sw_rod_gather  the difference and averaging operators Delta^h and A^h of
 *                  the discretisation (Gazzola et al. 2018, eqs. 3.1-3.4)
 *                  applied to those: F_i = f_i - f_{i-1} on nodes, and the
 *                  couples of domains i-1 and i on element i.
 * A ghost contributes exact zeros to its neighbours, which is the zero
 * padding of Delta^h and A^h at both ends of a rod.  The two passes read each
 * other's neighbours, so a threaded run puts a barrier between them; within
 * a pass slots are independent and any split of the range gives the same
 * bits.  Results: d->force (lab frame, per node) and d->torque (material
 * frame, per element), both overwritten on the elastic slots.
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
 *
 * The variational law (SW_LAW_VARIATIONAL, per rod) makes every internal
 * load the exact negative gradient of the energy sw_energy reports,
 *   U = sum_i l^_i (s_i - s0_i).S^_i (s_i - s0_i) / 2
 *     + sum_j D^_j (k_j - k0_j).B^_j (k_j - k0_j) / 2:
 *   n_i  = S^_i (sigma_i - sigma0_i)              (no 1/e)
 *   c_j  = B^_j (kappa_j - kappa0_j)              (no 1/eps^3)
 * and, with phi_j = kappa_j D^_j and Q_{j+1} Q_j^T = exp(-[phi_j]x), a turn
 * of element j or j+1 by a small b (material frame) moves phi_j by
 * -J_l^-1(phi_j) b or J_r^-1(phi_j) b (the inverse Jacobians of the SO(3)
 * exponential, vec.h), so the couples are
 *   tau_j     += J_l^-T c_j =  c_j + phi_j x c_j / 2 + beta phi_j x (phi_j x c_j)
 *   tau_{j+1} -= J_r^-T c_j = -c_j + phi_j x c_j / 2 - beta phi_j x (phi_j x c_j).
 * Gazzola's Delta^h(c) + A^h(kappa x c D^) is this without the beta term (it
 * is O(phi^2) smaller), so the gather stays one: the pass stores
 * c + beta phi x (phi x c) where it stored c.  The force and shear couple
 * keep their form.  The kinetic energy that goes with it is Simo's (Simo,
 * Comput. Methods Appl. Mech. Eng. 49 (1985) 55): the rotational inertia
 * J^ per element is that of the rest section and does not follow e, so
 * the drift turns a variational element at w = J^-1 L and the kick divides
 * by J^ (integrate.c, sw_inertia_dilatation); with Gazzola's J^ / e the
 * rotational kinetic energy would depend on the positions and push on them.
 */
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* The arrays of the Voronoi pass, as restrict pointers so that the
 * compiler knows the stores of a slot do not feed the loads of another. */
typedef struct {
  const double *restrict x, *restrict ghost, *restrict D, *restrict iD, *restrict B, *restrict k0;
  const double *restrict len;                                        /* scratch, at i - so */
  double *restrict kap, *restrict cpl, *restrict vdil, *restrict hh; /* scratch, at i - so */
  int so;
} vorArrays;

/* Length of element i for the passes: a ghost's two nodes belong to two
 * rods and may coincide, so it counts as unit length. */
static inline double elem_length(vorArrays a, size_t S, int i) {
  const sw3 dx = sw3_sub(sw3_load(a.x, S, i + 1), sw3_load(a.x, S, i));
  return sw_select(a.ghost[i] != 0.0, 1.0, sqrt(sw3_dot(dx, dx)));
}

/* Domain i from its curvature kv = kappa (1/m) and the lengths l, l1 of its
 * two elements.  Gazzola (law 0): c = B^ (kappa - kappa0) / eps^3 with
 * eps = (l + l1) / (2 D^); variational (law 1 and var != 0):
 * c = B^ (kappa - kappa0), stored as c + beta phi x (phi x c) with
 * phi = kappa D^ and beta from vec.h (the caller's: series or exact).  Both
 * store half the transport couple, kappa x c D^ / 2. */
static inline void domain_couple(vorArrays a, size_t S, int i, sw3 kv, double l, double l1, int law,
                                 int var, double beta) {
  const double inv_D = a.iD[i];
  const double eps = 0.5 * (l + l1) * inv_D;
  const double inv_eps3 = sw_select(law && var, 1.0, 1.0 / (eps * eps * eps));
  const sw3 Bi = sw3_load(a.B, S, i), kv0 = sw3_load(a.k0, S, i);
  const sw3 c = {Bi.x * (kv.x - kv0.x) * inv_eps3, Bi.y * (kv.y - kv0.y) * inv_eps3,
                 Bi.z * (kv.z - kv0.z) * inv_eps3};
  const int j = i - a.so; /* scratch */
  sw3_store(a.kap, S, j, kv);
  a.vdil[j] = eps;
  const sw3 h = sw3_cross(kv, c);
  sw3_store(a.hh, S, j, (sw3){0.5 * h.x * a.D[i], 0.5 * h.y * a.D[i], 0.5 * h.z * a.D[i]});
  if (law) {
    /* beta phi x (phi x c) = beta D^2 kappa x (kappa x c), zero on Gazzola's domains */
    const double b = sw_select(var, beta * a.D[i] * a.D[i], 0.0);
    const sw3 kkc = sw3_cross(kv, h);
    sw3_store(a.cpl, S, j, (sw3){c.x + b * kkc.x, c.y + b * kkc.y, c.z + b * kkc.z});
  } else {
    sw3_store(a.cpl, S, j, c);
  }
}

/* Element pass and Voronoi pass over slots [lo, hi): element i, then the
 * domain between elements i and i+1.  Loop bodies hold vectors and frames
 * as values (vec.h, sw3 and swFrame), so that the loop vectorizes.  The
 * curvature is taken from the small-angle series of the frame logarithm;
 * the real domains bent by more than that allows (sin theta > 0.25, about
 * 14.5 degrees between neighbouring frames) are counted and redone after the
 * loop with the exact logarithm, which gives every domain the bits of
 * vec.h's sw_frame_log. */
/* Element pass over slots [lo, hi): strain, internal force, Q^T n, the
 * element's own couples (scratch at i - so, internal.h "Scratch windows").
 * law = 0: Gazzola's law on every slot; law = 1: each slot by its rod's
 * (elem_variational).  Called with a constant law, so each is compiled
 * apart and Gazzola's loop does none of the variational law's work. */
static inline __attribute__((always_inline)) void element_pass_law(const swModel *m, swData *d, int lo,
                                                                   int hi, int so, const int law) {
  const size_t S = (size_t)m->stride;
  const double *restrict x = d->x, *restrict Q = d->Q;
  const double *restrict rl = m->rest_len, *restrict irl = m->inv_rest_len;
  const double *restrict ghost = m->elem_ghost, *restrict var = m->elem_variational;
  const double *restrict Sh = d->shear_now, *restrict s0 = m->rest_sigma;
  double *restrict len = d->length, *restrict dil = d->dilatation;
  double *restrict sig = d->sigma, *restrict str = d->stress, *restrict T = d->torque;
  double *restrict fl = d->scratch_f; /* Q^T n, lab */
#pragma omp simd
  for (int i = lo; i < hi; i++) {
    const sw3 dx = sw3_sub(sw3_load(x, S, i + 1), sw3_load(x, S, i));
    const double l = sw_select(ghost[i] != 0.0, 1.0, sqrt(sw3_dot(dx, dx)));
    const double inv_l = 1.0 / l, inv_rl = irl[i];
    const double e = l * inv_rl, inv_e = rl[i] * inv_l;
    const int v = law && var[i] != 0.0;
    const double inv_e_law = sw_select(v, 1.0, inv_e);
    const swFrame Qi = sw_frame_load(Q, S, i);
    const sw3 Qdx = sw_frame_apply(Qi, dx);
    /* sigma = Q dx / l^ - d3,  n = S^ (sigma - sigma0) / e (variational: no 1/e) */
    const sw3 sg = {Qdx.x * inv_rl, Qdx.y * inv_rl, Qdx.z * inv_rl - 1.0};
    const sw3 S_ = sw3_load(Sh, S, i), sg0 = sw3_load(s0, S, i);
    const sw3 nm = {S_.x * (sg.x - sg0.x) * inv_e_law, S_.y * (sg.y - sg0.y) * inv_e_law,
                    S_.z * (sg.z - sg0.z) * inv_e_law};
    const int j = i - so;
    sw3_store(sig, S, j, sg);
    sw3_store(str, S, j, nm);
    len[j] = l;
    dil[i] = e;
    sw3_store(fl, S, j, sw_frame_apply_t(Qi, nm));
    /* shear couple (Q dx) x n.  The inertial couple (J^ w / e) x w and the
     * dilatation-rate couple (J^ w / e) de/dt / e are integrated by the
     * drift (integrate.c), as the exact free rotation of the element */
    sw3_store(T, S, j, sw3_cross(Qdx, nm));
  }
}

/* Domain i of the Voronoi pass, first part: w and t of the frame logarithm
 * (vec.h, sw_frame_log_parts), held in the domain's scratch (w in kappa's
 * planes, t in eps's) until the last part.  Returns 1, and flags it in
 * flag[i - so], if it is a real domain bent past the logarithm's series,
 * else 0. */
static inline __attribute__((always_inline)) int voronoi_log(vorArrays va, const double *restrict Q, size_t S,
                                                             int i, double *restrict flag) {
  const swLogParts lg = sw_frame_log_parts(sw_frame_load(Q, S, i), sw_frame_load(Q, S, i + 1));
  const int redo = (lg.small == 0) & (va.ghost[i] == 0.0) & (va.ghost[i + 1] == 0.0);
  const int j = i - va.so;
  sw3_store(va.kap, S, j, lg.w);
  va.vdil[j] = lg.t;
  flag[j] = redo;
  return redo;
}

/* Domain i of the Voronoi pass, last part, l1 being the length of element
 * i + 1: phi = theta / (2 sin theta) w from the first part's w and the
 * series' value f (in eps's scratch), kappa = phi / D^ (a ghost domain's is
 * never used: its stiffness is zero), the bending couple and the transport
 * term.  law as for the element pass. */
static inline __attribute__((always_inline)) void voronoi_domain(vorArrays va, const double *restrict var,
                                                                 size_t S, int i, double l1, const int law) {
  const int j = i - va.so;
  const sw3 w = sw3_load(va.kap, S, j);
  const double f = va.vdil[j];
  const sw3 phi = {f * w.x, f * w.y, f * w.z};
  const sw3 kv = sw3_scale(phi, va.iD[i]);
  const double beta = law ? sw_dexpinv_beta_small(sw3_dot(phi, phi)) : 0.0;
  domain_couple(va, S, i, kv, va.len[j], l1, law, law && var[i] != 0.0, beta);
}

/* Voronoi pass over slots [lo, hi), after the element pass of [lo, hi),
 * whose lengths it reads; the last domain's second element is the next
 * range's, so its length is computed here (elem_length).  Three loops: the
 * frames' products (w, t), the series of the logarithm, the couples.  The
 * series is a chain of 28 dependent operations per domain; alone in its
 * loop, the processor overlaps the chains of many domains, where inside
 * the whole domain's work it could overlap those of one or two vector
 * iterations and waited on the chain (docs/performance.md, "AVX2 and
 * AVX-512").  The operations and their order per domain are those of one
 * loop.  Returns how many real domains were bent past the logarithm's
 * series. */
static inline __attribute__((always_inline)) int voronoi_pass_law(const swModel *m, swData *d, int lo, int hi,
                                                                  int so, double *restrict flag,
                                                                  const int law) {
  const size_t S = (size_t)m->stride;
  const double *restrict Q = d->Q, *restrict var = m->elem_variational;
  const vorArrays va = {d->x, m->elem_ghost, m->rest_vor_len, m->inv_rest_vor_len, d->bend_now, d->kappa0_now,
                        d->length, d->kappa, d->couple, d->vor_dilatation, d->scratch_h, so};
  if (lo >= hi) return 0;
  int bent = 0;
#pragma omp simd reduction(+ : bent)
  for (int i = lo; i < hi; i++) bent += voronoi_log(va, Q, S, i, flag);
  double *restrict t = d->vor_dilatation;
#pragma omp simd
  for (int j = lo - so; j < hi - so; j++) t[j] = sw_log_series(t[j]);
#pragma omp simd
  for (int i = lo; i < hi - 1; i++) voronoi_domain(va, var, S, i, va.len[i + 1 - so], law);
  voronoi_domain(va, var, S, hi - 1, elem_length(va, S, hi), law);
  return bent;
}

static void element_pass(const swModel *m, swData *d, int lo, int hi, int so) {
  if (m->nvariational) element_pass_law(m, d, lo, hi, so, 1);
  else element_pass_law(m, d, lo, hi, so, 0);
}

static int voronoi_pass(const swModel *m, swData *d, int lo, int hi, int so, double *restrict flag) {
  return m->nvariational ? voronoi_pass_law(m, d, lo, hi, so, flag, 1)
                         : voronoi_pass_law(m, d, lo, hi, so, flag, 0);
}

/* Element pass and Voronoi pass over slots [lo, hi), block by block, so
 * that the second loop finds the first's results in the cache and neither
 * loop streams more arrays at once than the prefetchers follow.  The
 * curvature is taken from the small-angle series of the frame logarithm;
 * the real domains bent by more than that allows (sin theta > 0.25, about
 * 14.5 degrees between neighbouring frames) are counted and redone after the
 * loop with the exact logarithm, which gives every domain the bits of
 * vec.h's sw_frame_log. */
#define ROD_BLOCK 512
void sw_rod_pass(const swModel *m, swData *d, int lo, int hi, int so, double *flag) {
  int bent = 0;
  for (int b = lo; b < hi; b += ROD_BLOCK) {
    const int e = b + ROD_BLOCK < hi ? b + ROD_BLOCK : hi;
    element_pass(m, d, b, e, so);
    bent += voronoi_pass(m, d, b, e, so, flag);
  }
  if (!bent) return;
  const size_t S = (size_t)m->stride;
  const vorArrays va = {d->x, m->elem_ghost, m->rest_vor_len, m->inv_rest_vor_len, d->bend_now, d->kappa0_now,
                        d->length, d->kappa, d->couple, d->vor_dilatation, d->scratch_h, so};
  for (int i = lo; i < hi && bent > 0; i++) { /* up to the last one flagged */
    if (flag[i - so] == 0.0) continue;
    bent--;
    double Qa[9], Qb[9], phi[3];
    sw_getQ(m, d->Q, i, Qa);
    sw_getQ(m, d->Q, i + 1, Qb);
    sw_frame_log(phi, Qa, Qb);
    const double inv_D = m->inv_rest_vor_len[i];
    const sw3 kv = {phi[0] * inv_D, phi[1] * inv_D, phi[2] * inv_D};
    const int var = m->nvariational && m->elem_variational[i] != 0.0;
    const double beta = var ? sw_dexpinv_beta(sw_v3_dot(phi, phi)) : 0.0;
    domain_couple(va, S, i, kv, va.len[i - so], elem_length(va, S, i + 1), var, var, beta);
  }
}

/* Delta^h and A^h over slots [lo, hi): node force F_i = f_i - f_{i-1} and
 * element couple tau_i += (-c_{i-1} + h_{i-1}) + (c_i + h_i), in this order
 * (the order the couples of domains i-1 and i were once added in); slot -1
 * counts as a ghost. */
void sw_rod_gather(const swModel *m, swData *d, int lo, int hi, int so) {
  const size_t S = (size_t)m->stride;
  const double *restrict fl = d->scratch_f, *restrict c = d->couple, *restrict hh = d->scratch_h;
  double *restrict F = d->force, *restrict T = d->torque;
  if (lo == 0 && hi > 0) {
    const int j = -so; /* slot 0 */
    for (int k = 0; k < 3; k++) {
      F[k * S + j] = fl[k * S + j] - 0.0;
      T[k * S + j] = (T[k * S + j] + (-0.0 + 0.0)) + (c[k * S + j] + hh[k * S + j]);
    }
    lo = 1;
  }
  /* only scratch here: slot i at j = i - so */
  for (int k = 0; k < 3; k++) {
    const double *restrict fk = fl + k * S, *restrict ck = c + k * S, *restrict hk = hh + k * S;
    double *restrict Fk = F + k * S, *restrict Tk = T + k * S;
#pragma omp simd
    for (int j = lo - so; j < hi - so; j++) {
      Fk[j] = fk[j] - fk[j - 1];
      Tk[j] = (Tk[j] + (-ck[j - 1] + hk[j - 1])) + (ck[j] + hk[j]);
    }
  }
}

void sw_internal_loads(const swModel *m, swData *d) {
  int lo, hi;
  if (m->nswell) { /* the geometry of now (swell.c) */
    if (sw_team_leader(d)) sw_swell_update(m, d, d->time);
    sw_team_barrier(d);
  }
  sw_share_slots(m, d, m->nslot_elastic, &lo, &hi);
  sw_rod_pass(m, d, lo, hi, 0, d->scratch_flag);
  sw_team_barrier(d); /* the gather reads the pass of the slot before */
  sw_rod_gather(m, d, lo, hi, 0);
  if (m->nrigid && sw_team_leader(d)) /* rigid slots: no thread's chunks touch them */
    for (int b = 0; b < m->nrigid; b++) /* no deformation, no internal loads (rigid.c) */
      sw_rigid_internal(m, d, m->rigid_rod[b]);
  sw_team_barrier(d);
}
