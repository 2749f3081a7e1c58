/* drift.h — the drift's slot loops: nodes move with their velocities and
 * frames turn with their angular momentum held (integrate.c's drift, and
 * the fused sweep's).
 *
 * Design.  Only integrate.c includes this file: the loops are static and
 * always inlined, so that each caller's constant arguments (the scheme, the
 * constitutive law, whether a block has a frame past the series) compile
 * to a loop of their own without the others' work, and the fused sweep
 * runs them block by block on the slots it has just kicked.  They hold
 * vectors and frames as values (vec.h's sw3 and swFrame), so that they
 * vectorize; the few frames that turn too far for Rodrigues' series in one
 * drift are turned after the loop by the exact formulas. */
#ifndef SW_DRIFT_H
#define SW_DRIFT_H

#include <math.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* Nodes move with their velocities: x += h v over slots [lo, hi). */
static void drift_nodes(const swModel *m, swData *d, double h, int lo, int hi) {
  const size_t S = (size_t)m->stride;
  for (int k = 0; k < 3; k++) {
    double *restrict x = d->x + k * S;
    const double *restrict v = d->v + k * S;
#pragma omp simd
    for (int i = lo; i < hi; i++) x[i] += h * v[i];
  }
}

/* The frame turned about its own d3 by the angle whose cosine and sine are
 * c and sn: d1 <- c d1 + sn d2, d2 <- c d2 - sn d1 (drift_frames). */
static inline swFrame turn_about_d3(swFrame Q, double c, double sn) {
  return (swFrame){sw3_add(sw3_scale(Q.d1, c), sw3_scale(Q.d2, sn)),
                   sw3_sub(sw3_scale(Q.d2, c), sw3_scale(Q.d1, sn)), Q.d3};
}

/* Column k of the frame of slot i, (d1_k, d2_k, d3_k), through the drift's
 * two turns, exp(-[phi]x) by Rodrigues' series r (vec.h) and then
 * turn_about_d3's, where `small`; else left as it is (drift_frames).  The
 * frame is turned a column at a time, so that the loop body holds three of
 * its entries at once rather than the old and the new frame, eighteen,
 * which it spilled to the stack (most with AVX2's sixteen vector
 * registers; docs/performance.md). */
static inline __attribute__((always_inline)) void drift_column(double *restrict Q, size_t S, int i, int k,
                                                              int small, sw3 phi, swRodrigues r, double c,
                                                              double sn) {
  const sw3 col = {Q[k * S + i], Q[(3 + k) * S + i], Q[(6 + k) * S + i]};
  const sw3 q = sw_rodrigues_column(col, phi, r.a, r.b);
  const sw3 turned = {q.x * c + q.y * sn, q.y * c - q.x * sn, q.z}; /* turn_about_d3 */
  const sw3 out = sw3_select(small, turned, col);
  Q[k * S + i] = out.x;
  Q[(3 + k) * S + i] = out.y;
  Q[(6 + k) * S + i] = out.z;
}

/* Frames turn with the angular momentum held (integrate.c's drift()) over
 * the element slots [lo, hi), after the nodes have moved.  The drift is the exact free
 * rotation of each element, an axisymmetric body (J^ = J1 (1, 1, 2), a
 * circular section; model.c): its kinetic energy splits as
 *   T = e |L|^2 / (2 J1) + e (1/J3 - 1/J1) L3^2 / 2,
 * two flows that commute (|L|^2 is a Casimir; the splitting of the rigid
 * bodies, docs/physics.md): the frame turns about L by the body rotation
 * s a, a = L e / J1 = (w1, w2, 2 w3), then about its own d3 by
 * psi = s (1 - J3/J1) w3 = -s w3, while L turns about d3 by psi as well
 * (Euler's equations: (w1, w2) precess at w3), with s the drift's integral
 * of e dt over e_old.  This is the inertial couple (J^ w / e) x w of
 * Gazzola 2018 eq. 2.12 integrated exactly: kept as a couple in the kick,
 * it made a spinning rod's energy grow without bound near the stable step
 * (docs/physics.md, "Inertial couple").  The loop turns frames with the
 * small-angle series of Rodrigues' formula (vec.h); the few that turn by
 * more in one drift (|s a| > 0.1 rad) keep their frame and w and are turned
 * after it with the exact formulas, so every frame gets the bits of
 * sw_rotate_frame.  The rotations s a are scratch, at i - so (internal.h,
 * "Scratch windows"); psi = -(s a)_3 / 2 is recovered from them.  The
 * round-off of the two turns is taken out every few steps (end_step). */
/* The drift's scratch: d->scratch_phi's planes (data.c), s a (DRIFT_PHI, 3
 * planes) of slot i at i - so as before, which the checkpoint saves
 * (restart.c), the other values at i - wo, a block's window. */
enum { DRIFT_PHI = 0, DRIFT_SCALE = 3, DRIFT_A = 4, DRIFT_B = 5, DRIFT_C = 6, DRIFT_SN = 7 };

/* drift_frames_block's third loop: the two turns of each frame and of its
 * w, by the coefficients of the second.  With `some_past` a frame turning by
 * more than the series allows keeps its old value (and its w unturned) here
 * and is turned after the loop; without (nearly every block), the loop has
 * no choice to make per slot: the same bits, a third fewer operations. */
static inline __attribute__((always_inline)) void drift_turns(
    double *restrict Q, double *restrict w, const double *restrict rot, const double *restrict ca,
    const double *restrict cb, const double *restrict cc, const double *restrict cs,
    const double *restrict scl, size_t S, int lo, int hi, int so, int wo, const int some_past) {
#pragma omp simd
  for (int i = lo; i < hi; i++) {
    const int j = i - wo;
    const sw3 phi = sw3_load(rot, S, i - so);
    const int small = !some_past || sw_frame_small_turn(phi);
    const swRodrigues rot_phi = {ca[j], cb[j]};
    const double c = cc[j], sn = cs[j];
    drift_column(Q, S, i, 0, small, phi, rot_phi, c, sn);
    drift_column(Q, S, i, 1, small, phi, rot_phi, c, sn);
    drift_column(Q, S, i, 2, small, phi, rot_phi, c, sn);
    const sw3 wi = sw3_load(w, S, i);
    const double cw = sw_select(small, c, 1.0), sw = sw_select(small, sn, 0.0);
    sw3_store(w, S, i, sw3_scale((sw3){cw * wi.x + sw * wi.y, cw * wi.y - sw * wi.x, wi.z}, scl[j]));
  }
}

/* drift_frames_law on slots [lo, hi) of one block, in three loops: (1) the
 * rotation s a, psi and w's rescaling; (2) the coefficients of the two
 * turns, Rodrigues' series in |s a|^2 and in psi^2; (3) the turns.  Each
 * slot gets the operations and the order of one loop; cut so, each loop is
 * short enough that the processor overlaps many slots' chains of dependent
 * operations (a square root and a division, then the two series, then the
 * turns), where one loop over the whole work spilled and waited on them at
 * AVX2's 16 registers (docs/performance.md, "AVX2 and AVX-512").  Their
 * values pass through the block's scratch (DRIFT_*, psi where c goes). */
static inline __attribute__((always_inline)) void drift_frames_block(const swModel *m, swData *d, double h,
                                                                   int lo, int hi, int so, int wo,
                                                                   const int simpson, const int law) {
  const size_t S = (size_t)m->stride;
  const double *restrict x = d->x, *restrict v = d->v;
  double *restrict w = d->omega, *restrict Q = d->Q, *restrict dil = d->dilatation;
  const double *restrict irl = m->inv_rest_len, *restrict ghost = m->elem_ghost;
  const double *restrict var = m->elem_variational;
  double *restrict rot = d->scratch_phi, *restrict scl = d->scratch_phi + DRIFT_SCALE * S;
  double *restrict ca = d->scratch_phi + DRIFT_A * S, *restrict cb = d->scratch_phi + DRIFT_B * S;
  double *restrict cc = d->scratch_phi + DRIFT_C * S, *restrict cs = d->scratch_phi + DRIFT_SN * S;
#pragma omp simd
  for (int i = lo; i < hi; i++) {
    const sw3 dx = sw3_sub(sw3_load(x, S, i + 1), sw3_load(x, S, i));
    const sw3 dv = sw3_sub(sw3_load(v, S, i + 1), sw3_load(v, S, i));
    const double inv_e_old = 1.0 / dil[i];
    const double e_new = sw_select(ghost[i] != 0.0, 1.0, sqrt(sw3_dot(dx, dx)) * irl[i]);
    const double ratio = e_new * inv_e_old;
    /* (1/h) integral of e dt over the drift, in units of e_old: Simpson's
     * rule (PEFRL) or the trapezoidal rule (Verlet) */
    const sw3 mid = {dx.x - 0.5 * h * dv.x, dx.y - 0.5 * h * dv.y, dx.z - 0.5 * h * dv.z};
    const double mean_e = simpson ? (1.0 + 4.0 * sqrt(sw3_dot(mid, mid)) * irl[i] * inv_e_old + ratio) * (1.0 / 6.0)
                                  : 0.5 * (1.0 + ratio);
    /* a variational rod's inertia is J^, not J^ / e: w = J^-1 L stays */
    const int fixed_inertia = law && var[i] != 0.0;
    const double mean = sw_select(fixed_inertia, 1.0, mean_e), scale = sw_select(fixed_inertia, 1.0, ratio);
    const double sh = h * mean;
    const sw3 wi = sw3_load(w, S, i), phi = {sh * wi.x, sh * wi.y, 2.0 * sh * wi.z};
    const int j = i - wo;
    sw3_store(rot, S, i - so, phi);
    cc[j] = -sh * wi.z; /* psi; |psi| <= |phi| / 2: small with phi */
    scl[j] = scale;
    dil[i] = e_new;
  }
  int turned = 0; /* frames past the series */
#pragma omp simd reduction(+ : turned)
  for (int i = lo; i < hi; i++) {
    const int j = i - wo;
    const sw3 phi = sw3_load(rot, S, i - so);
    const double psi = cc[j];
    const swRodrigues rot_phi = sw_rodrigues_series(sw3_dot(phi, phi)), r = sw_rodrigues_series(psi * psi);
    ca[j] = rot_phi.a;
    cb[j] = rot_phi.b;
    cc[j] = 1.0 - r.b * psi * psi; /* cos psi */
    cs[j] = r.a * psi;             /* sin psi */
    turned += !sw_frame_small_turn(phi);
  }
  if (turned) drift_turns(Q, w, rot, ca, cb, cc, cs, scl, S, lo, hi, so, wo, 1);
  else drift_turns(Q, w, rot, ca, cb, cc, cs, scl, S, lo, hi, so, wo, 0);
  for (int i = lo; i < hi && turned > 0; i++) { /* up to the last one past the series */
    if (sw_frame_small_turn(sw3_load(rot, S, i - so))) continue;
    turned--;
    double Qe[9], phi[3];
    sw_getQ(m, d->Q, i, Qe);
    sw_get3(m, rot, i - so, phi);
    sw_rotate_frame(Qe, phi);
    sw_setQ(m, d->Q, i, Qe);
    const double psi = -0.5 * phi[2], c = cos(psi), sn = sin(psi);
    sw_frame_store(d->Q, S, i, turn_about_d3(sw_frame_load(d->Q, S, i), c, sn));
    const double w1 = SW_AT(m, d->omega, i, 0), w2 = SW_AT(m, d->omega, i, 1);
    SW_AT(m, d->omega, i, 0) = c * w1 + sn * w2;
    SW_AT(m, d->omega, i, 1) = c * w2 - sn * w1;
  }
}

/* The frames' drift over slots [lo, hi) (drift_frames_block), block by
 * block, so that the scratch between its loops stays in the cache: each
 * block's at the range's first entries of the window (where i - so is for
 * i from lo), which are this thread's. */
#define DRIFT_BLOCK 256
static inline __attribute__((always_inline)) void drift_frames_law(const swModel *m, swData *d, double h,
                                                                 int lo, int hi, int so, const int simpson,
                                                                 const int law) {
  for (int b = lo; b < hi; b += DRIFT_BLOCK)
    drift_frames_block(m, d, h, b, b + DRIFT_BLOCK < hi ? b + DRIFT_BLOCK : hi, so, b - (lo - so), simpson,
                       law);
}

/* drift_frames_law for the model's laws: a model without variational rods
 * runs a loop that has no trace of them. */
static inline __attribute__((always_inline)) void drift_frames(const swModel *m, swData *d, double h,
                                                             int lo, int hi, int so, const int simpson) {
  if (m->nvariational) drift_frames_law(m, d, h, lo, hi, so, simpson, 1);
  else drift_frames_law(m, d, h, lo, hi, so, simpson, 0);
}

#endif
