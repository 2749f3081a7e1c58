/* integrate.c — symplectic time stepping of rods.
 *
 * Design.  A step is a palindromic sequence of drifts (positions and
 * directors move with the current velocities) and kicks (velocities change
 * under the loads of the current configuration), as in Gazzola et al. 2018,
 * sec. 3.3.  Two schemes:
 *   position Verlet (second order, one load evaluation per step):
 *     drift h/2, kick h, drift h/2;
 *   PEFRL, the position-extended Forest-Ruth-like scheme of Omelyan, Mryglod
 *     & Folk, Comput. Phys. Commun. 146 (2002) 188, eq. 20 (fourth order,
 *     four load evaluations per step).
 * A drift moves each node by h v and rotates each frame exactly by
 * exp(-h [w]x) (Rodrigues); simulated time is advanced by the drifts, so the
 * loads of a kick see the time of the configuration they act on.  Analytic
 * damping is integrated exactly with the kick's loads held constant
 * (Verlet: v <- v exp(-c h) + a (1 - exp(-c h)) / c, stable for any damping
 * constant and right in the overdamped limit), or, for PEFRL, as the decay
 * exp(-c h/2) before and after the step (Strang splitting).
 *
 * sw_steps() fuses the trailing half drift of one Verlet step with the
 * leading half drift of the next (see there).
 *
 * Every kick books the work of the external loads over the kick with the
 * midpoint rule, h F . (v_old + v_new)/2, so that kinetic + elastic - work is
 * conserved up to the integrator's error (the energy diagnostic).
 *
 * Rigid rods are skipped by the node and element loops here: each drift and
 * kick ends with rigid.c's, which moves them as rigid bodies.
 *
 * Threads (internal.h, "Threads"): sw_steps runs its k steps in one OpenMP
 * parallel region when d->threads > 1.  Every thread runs the functions
 * below; the slot loops take the thread's share of the model's chunks, the
 * parts that are not shared run on the leader, and the phases meet at
 * sw_team_wait, a barrier of our own (docs/performance.md says why).
 */
#include <math.h>
#include <sched.h>
#include <stdio.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"
#include "drift.h"

/* All loads of the current configuration: internal, clamp couples, external,
 * joints (whose damping joint.c adds to the external loads, so that the kick
 * books its work, and whose springs count as elastic energy), muscles (active:
 * their tensions count as external loads, muscle.c), environments.  Muscle
 * activations advance once a step, before its first kick (sw_muscle_advance).
 *
 * In phases, each on a thread's own slots, with a barrier only where a phase
 * reads what another thread wrote: (A) from the state alone, the rod pass,
 * the joints' rows and the muscles' rates; (B) the gather, the clamp
 * couples, the external loads, the joints' rows added and the filaments'
 * tensions; (C, in kick()) the muscles' pull, then the environments.  Every
 * slot gets its loads in the same order as on one thread.  h is the kick
 * they are for: an implicit filament's tension depends on it (SW_IMEX,
 * muscle.c). */
static void compute_loads(const swModel *m, swData *d, double h) {
  const swMuscleOps *mu = sw_muscle_ops(m);
  int lo, hi;
  if (m->nkinematic) { /* the imposed frames first: every load sees them (kinematic.c) */
    sw_team_barrier(d);
    sw_kinematic_impose(m, d); /* level by level, a barrier after each */
  }
  if (m->nswell) { /* the swelling rods' geometry at the kick's time (swell.c) */
    sw_team_barrier(d);
    if (sw_team_leader(d)) sw_swell_update(m, d, d->time);
    sw_team_barrier(d);
  }
  sw_share_slots(m, d, m->nslot_elastic, &lo, &hi);
  sw_rod_pass(m, d, lo, hi, 0, d->scratch_flag); /* (A) */
  if (m->njoint) sw_joint_rows(m, d);
  if (m->nmuscle) mu->rates(m, d);
  sw_team_barrier(d);
  sw_rod_gather(m, d, lo, hi, 0); /* (B) */
  if (m->nkinematic) { /* the imposed frames' energy, from the internal couples alone */
    sw_team_barrier(d);
    sw_kinematic_book(m, d); /* ends in a barrier */
  }
  if (m->nrigid) { /* no deformation, no internal loads (rigid.c) */
    if (sw_team_leader(d)) sw_rigid_clear_loads(m, d);
    sw_team_barrier(d);
  }
  if (m->nbc) {
    int olo, ohi;
    sw_owned_slots(m, d, &olo, &ohi);
    sw_bc_loads(m, d, olo, ohi, 0);
  }
  sw_external_loads(m, d); /* on this thread's slots, no barrier inside */
  if (m->njoint) sw_joint_apply(m, d);
  if (m->nmuscle) {
    if (m->nring) mu->rings(m, d); /* via rings (muscle_via.c), from (A)'s rows */
    /* an implicit filament reads the loads on all its nodes (muscle.c) */
    if (m->muscle_implicit) sw_team_barrier(d);
    mu->tensions(m, d, h);
  }
  sw_team_barrier(d);
  if (m->nmuscle) mu->pull(m, d); /* (C) */
  if (m->nkinematic) { /* the ties read nodes of any thread's */
    sw_team_barrier(d);
    sw_kinematic_loads(m, d);
    sw_team_barrier(d);
  }
  if (sw_has_env(m)) { /* last: the ground balances the rest */
    sw_team_barrier(d);
    sw_env_ops(m)->loads(m, d);
    sw_team_barrier(d);
  }
}

/* Component k of the velocities of the elastic slots [lo, hi) under the
 * loads (scratch, at i - so), and the work booked over the kick (see
 * kick()) slot by slot into work[i]: the first component (`first`) starts
 * it, the others add theirs.  One loop per kind of model: with `exact_any`
 * 0 (no rod integrates its damping exactly, the common case) the loop
 * carries no exact path at all. */
static inline __attribute__((always_inline)) void kick_component(const swModel *m, swData *d, double h,
                                                               int lo, int hi, int so, double *restrict work,
                                                               int k, const int first, const int exact_any,
                                                               const int law) {
  const size_t S = (size_t)m->stride;
  const double *restrict im = d->inv_mass_now, *restrict mass = d->mass_now;
  const double *restrict ndec = m->node_decay, *restrict nkick = m->node_kick;
  const double *restrict exact = m->kick_exact, *restrict dil = d->dilatation;
  const double *restrict var = m->elem_variational;
  double *restrict v = d->v + k * S, *restrict w = d->omega + k * S;
  const double *restrict F = d->force + k * S, *restrict T = d->torque + k * S;
  const double *restrict ef = d->ext_force + k * S, *restrict et = d->ext_torque + k * S;
  const double *restrict iJ = d->inv_inertia_now + k * S, *restrict J = d->inertia_now + k * S;
  const double *restrict edec = m->elem_decay + k * S, *restrict ekick = m->elem_kick + k * S;
#pragma omp simd
  for (int i = lo; i < hi; i++) {
    /* nodes: m dv/dt = F; analytically damped rods (Verlet) integrate
     * dv/dt = a - c v exactly with a held (model.c), and book the work of
     * loads and dissipation together as the non-internal impulse times the
     * mean velocity */
    const int ex = exact_any && exact[i] != 0.0;
    const double Fi = F[i - so], Ti = T[i - so], efi = ef[i - so], eti = et[i - so];
    const double vo = v[i];
    const double vd = vo * ndec[i] + Fi * im[i] * nkick[i], vp = vo + h * Fi * im[i];
    const double vn = sw_select(ex, vd, vp);
    v[i] = vn;
    /* elements: (J^/e) dw/dt = tau (Gazzola 2018, eq. 3.7b, the couples of
     * rod.c without the dilatation-rate term, which the drift integrates);
     * J^ dw/dt = tau on variational rods (rod.c) */
    const double wo = w[i], e = sw_select(law && var[i] != 0.0, 1.0, dil[i]); /* sw_inertia_dilatation */
    const double wd = wo * edec[i] + Ti * iJ[i] * e * ekick[i], wp = wo + h * Ti * iJ[i] * e;
    const double wn = sw_select(ex, wd, wp);
    w[i] = wn;
    /* the midpoint rule, h F . (v_old + v_new) / 2 */
    const double booked = sw_select(ex, 0.5 * ((mass[i] * (vn - vo) - h * (Fi - efi)) * (vo + vn) +
                                               (J[i] / e * (wn - wo) - h * (Ti - eti)) * (wo + wn)),
                                    0.5 * h * (efi * (vo + vn) + eti * (wo + wn)));
    work[i] = first ? booked : work[i] + booked;
  }
}

/* The three components of the kick over slots [lo, hi) (kick_component),
 * the work of each slot summed in component order into work[i] (and by
 * chunk in kick(), so that the sum does not depend on the threads). */
static inline __attribute__((always_inline)) void kick_slots_law(const swModel *m, swData *d, double h,
                                                               int lo, int hi, int so, double *restrict work,
                                                               const int exact_any, const int law) {
  kick_component(m, d, h, lo, hi, so, work, 0, 1, exact_any, law);
  kick_component(m, d, h, lo, hi, so, work, 1, 0, exact_any, law);
  kick_component(m, d, h, lo, hi, so, work, 2, 0, exact_any, law);
}

static inline __attribute__((always_inline)) void kick_slots(const swModel *m, swData *d, double h,
                                                           int lo, int hi, int so, double *restrict work,
                                                           const int exact_any) {
  if (m->nvariational) kick_slots_law(m, d, h, lo, hi, so, work, exact_any, 1);
  else kick_slots_law(m, d, h, lo, hi, so, work, exact_any, 0);
}

/* Sum of work[lo, hi). */
static double chunk_work(const double *restrict work, int lo, int hi) {
  double sum = 0;
#pragma omp simd reduction(+ : sum)
  for (int i = lo; i < hi; i++) sum += work[i];
  return sum;
}

/* On the leader, at the drift after a kick: the kick's work, in chunk order,
 * then condition order, and the rigid bodies' kick. */
static void finish_kick(const swModel *m, swData *d) {
  if (!d->kick_pending) return;
  const int n = m->nslot_elastic;
  for (int c = 0; c < sw_nchunk(m, n); c++) d->work += d->chunk_sum[c];
  for (int k = 0; k < m->nbc; k++) d->work += d->bc_work[k];
  if (m->nrigid) sw_rigid_kick(m, d, d->kick_h); /* its loads: sw_rigid_loads in kick() */
  d->kick_pending = 0;
}

/* Positions and frames move with the current velocities for a time h.
 * What a drift holds constant is the momentum: v for nodes and the angular
 * momentum L = J^ w / e for elements (Gazzola 2018, eq. 2.12: d/dt(J^ w / e)
 * = couples).  As the nodes move, e changes, so w = e J^-1 L changes with it:
 * w is rescaled by e_new / e_old, and the frame turns by the exact rotation
 * J^-1 L * integral of e dt, the integral taken with Simpson's rule (exact to
 * O(h^5) for e(t) = |dx + t dv| / l^) for PEFRL and the trapezoidal rule
 * (O(h^3)) for position Verlet.  This is how the dilatation-rate couple
 * (J^ w / e) de/dt / e of the rotational balance is integrated: keeping it
 * as an explicit couple in the kick would cap both schemes at first order. */
static void drift(const swModel *m, swData *d, double h) {
  int lo, hi;
  sw_share_slots(m, d, m->nslot_elastic, &lo, &hi);
  drift_nodes(m, d, h, lo, hi);
  sw_team_barrier(d); /* a frame reads the node after its element's */
  if (m->integrator == SW_PEFRL) /* one loop per scheme: Simpson's rule or not */
    drift_frames(m, d, h, lo, hi, 0, 1);
  else
    drift_frames(m, d, h, lo, hi, 0, 0);
  sw_team_barrier(d); /* the last elastic slot read the first rigid node */
  if (sw_team_leader(d)) {
    finish_kick(m, d);
    if (m->nrigid) sw_rigid_drift(m, d, h);
    d->time += h;
  }
  sw_team_barrier(d);
}

/* Velocities change under the loads of the current configuration.  `span`
 * is the length of drift that the new velocities will be used for before
 * the next kick: prescribed velocities are taken at its midpoint, so that
 * a prescribed end moves by the midpoint rule's integral of its profile
 * (position Verlet's v_{n+1} is the velocity at t_{n+1} = t_kick + h/2). */
static void kick(const swModel *m, swData *d, double h, double span) {
  const int n = m->nslot_elastic;
  if (m->nbc && sw_bc_release_due(m, d, d->time)) { /* a hold lets go (boundary.c); rare */
    sw_team_barrier(d);
    if (sw_team_leader(d)) sw_bc_release(m, d, d->time);
    sw_team_barrier(d);
  }
  compute_loads(m, d, h);
  if (m->nimplicit) sw_implicit_kick(m, d, h); /* the implicit rods' loads (rod_implicit.c) */
  if (m->nrigid || m->nrigid_block) { /* the bodies' loads, and the implicit joints'
                      (rigid_joint.c), which replace those of the elastic nodes joined
                      to bodies and of the implicit rods they join (joint_ports.c) */
    sw_team_barrier(d);
    if (sw_team_leader(d)) sw_rigid_loads(m, d, h);
    sw_team_barrier(d);
  }
  int lo, hi;
  sw_share_slots(m, d, n, &lo, &hi);
  if (m->has_exact_kick) /* the flags are free between the passes */
    kick_slots(m, d, h, lo, hi, 0, d->scratch_flag, 1);
  else
    kick_slots(m, d, h, lo, hi, 0, d->scratch_flag, 0);
  SW_FOR_CHUNKS(m, d, c, n) d->chunk_sum[c] = chunk_work(d->scratch_flag, sw_chunk_lo(m, c), sw_chunk_hi(m, c, n));
  if (m->nbc) { /* the prescribed ends, after every free kick (an end's node and
                  element may have been kicked by two threads) */
    sw_team_barrier(d);
    sw_owned_slots(m, d, &lo, &hi);
    sw_bc_kick(m, d, h, d->time + 0.5 * span, lo, hi, 0, d->bc_work);
  }
  if (m->nkinematic) { /* followers turn at their leaders' new rates (kinematic.c) */
    sw_team_barrier(d);
    sw_kinematic_follow(m, d); /* level by level, a barrier after each */
  }
  /* the work and the rigid bodies' kick are the next drift's leader's; the
   * nodes of the drift are this thread's own, so no barrier here */
  if (sw_team_leader(d)) {
    d->kick_pending = 1;
    d->kick_h = h;
  }
}

/* The fused sweep's block of slots.  Its scratch windows take the first
 * SWEEP_BLOCK + 1 entries of each scratch plane. */
#define SWEEP_BLOCK 512

int sw_sweep_fits(const swModel *m) {
  return m->integrator != SW_PEFRL && m->nslot_elastic > SWEEP_BLOCK && !m->njoint && !m->nmuscle &&
         !m->nkinematic &&
         !m->nrigid && !m->nimplicit && !sw_has_env(m) && !m->nswell;
}

/* The window's last entries (the block's last slot) become its entry 0 (the
 * slot before the next block): what the gather and the boundary kick of
 * the next block read of the slot before theirs. */
static void carry_window(const swModel *m, swData *d) {
  const size_t S = (size_t)m->stride;
  double *const planes[] = {d->scratch_f, d->couple, d->scratch_h, d->torque, d->ext_torque};
  for (size_t p = 0; p < sizeof planes / sizeof *planes; p++)
    for (int k = 0; k < 3; k++) planes[p][k * S] = planes[p][k * S + SWEEP_BLOCK];
}

/* kick(h, span) then drift(hd) as one pass over the slots, block by block,
 * each stage on the block its inputs are ready for: the loads and the kick
 * of block j (they read the element and the frame after the block, not yet
 * moved), the drift of its nodes, and the drift of the frames of block j-1
 * (they read the first node of block j, moved).  Every slot gets the
 * operations of kick() and drift() in their order, so the bits are those
 * of the phased step; what changes is the memory traffic.  The scratch
 * arrays live in windows (internal.h, "Scratch windows") that stay in the
 * cache, and the state and model are read once a step instead of once per
 * phase.  The kick's work goes slot by slot into the whole of scratch_flag
 * (the rod pass flags its bent domains in a window of scratch_phi), and
 * each chunk is summed, as kick() sums it, once all its slots are kicked. */
static inline __attribute__((always_inline)) void sweep_slots(const swModel *m, swData *d, double h,
                                                            double span, double hd, const int exact_any) {
  const int n = m->nslot_elastic, nc = sw_nchunk(m, n);
  int c = 0; /* the next chunk to sum */
  for (int b = 0; b < n + SWEEP_BLOCK; b += SWEEP_BLOCK) {
    const int e = b + SWEEP_BLOCK < n ? b + SWEEP_BLOCK : n, so = b - 1;
    if (b < n) {
      sw_rod_pass(m, d, b, e, so, d->scratch_phi);
      sw_rod_gather(m, d, b, e, so);
      if (m->nbc) sw_bc_loads(m, d, b, e, so);
      sw_external_loads_slots(m, d, b, e, so);
      kick_slots(m, d, h, b, e, so, d->scratch_flag, exact_any);
      for (; c < nc && sw_chunk_hi(m, c, n) <= e; c++)
        d->chunk_sum[c] = chunk_work(d->scratch_flag, sw_chunk_lo(m, c), sw_chunk_hi(m, c, n));
      if (m->nbc) sw_bc_kick(m, d, h, d->time + 0.5 * span, b, e, so, d->bc_work);
      drift_nodes(m, d, hd, b, e);
    }
    if (b > 0) drift_frames(m, d, hd, b - SWEEP_BLOCK, b < n ? b : n, b - SWEEP_BLOCK - 1, 0);
    carry_window(m, d);
  }
  sw_external_loads_slots(m, d, n, m->stride, 0); /* the padding's, as kick() does */
  d->kick_pending = 1;
  d->kick_h = h;
  finish_kick(m, d);
  d->time += hd;
}

static void sweep(const swModel *m, swData *d, double h, double span, double hd) {
  if (m->nbc && sw_bc_release_due(m, d, d->time)) sw_bc_release(m, d, d->time); /* one thread */
  if (m->has_exact_kick)
    sweep_slots(m, d, h, span, hd, 1);
  else
    sweep_slots(m, d, h, span, hd, 0);
}

/* Exact decay of the analytically damped rods over half a step (PEFRL). */
static void analytic_decay_serial(const swModel *m, swData *d) {
  double lost = 0;
  for (int r = 0; r < m->nrod; r++) {
    if (m->rod_damping[r] != SW_DAMP_ANALYTIC || sw_rod_is_rigid(m, r)) continue;
    int na = m->node_adr[r], ea = m->elem_adr[r], n = m->rod_nelem[r];
    for (int i = na; i <= na + n; i++) {
      double vi[3], f = m->node_decay[i];
      sw_get3(m, d->v, i, vi);
      double v2 = sw_v3_dot(vi, vi);
      sw_v3_scale(vi, vi, f);
      sw_set3(m, d->v, i, vi);
      lost += 0.5 * d->mass_now[i] * v2 * (1 - f * f);
    }
    for (int e = ea; e < ea + n; e++)
      for (int k = 0; k < 3; k++) {
        double w = SW_AT(m, d->omega, e, k), f = SW_AT(m, m->elem_decay, e, k);
        SW_AT(m, d->omega, e, k) = f * w;
        lost += 0.5 * SW_AT(m, d->inertia_now, e, k) / sw_inertia_dilatation(m, d, e) * w * w * (1 - f * f);
      }
  }
  d->work -= lost;
}

static void analytic_decay(const swModel *m, swData *d) {
  if (sw_team_leader(d)) analytic_decay_serial(m, d);
  sw_team_barrier(d);
}

/* PEFRL coefficients, Omelyan et al. 2002, eq. 20. */
static const double PEFRL_XI = 0.1786178958448091;
static const double PEFRL_LAMBDA = -0.2123418310626054;
static const double PEFRL_CHI = -0.06626458266981849;

/* The stability check runs every 8 steps and on each of the first 8. */
static int check_due(long step) { return (step & 7) == 0 || step < 8; }

/* The frames of slots [lo, hi) one Newton step nearer to rotations (vec.h,
 * sw_frame_orthonormalize), when the check is due (every 8 steps): the two
 * turns of each drift leave an error of order 1e-16 in Q Q^T - I, which
 * would add up over millions of steps (4.7e-12 after 10^7); this keeps it at
 * round-off (2e-16).  Cheaper every 8 steps than in every drift (3-8 ns per
 * element-step there on rods of 100-1000 elements). */
static void orthonormalize_frames(const swModel *m, swData *d, int lo, int hi) {
  const size_t S = (size_t)m->stride;
  double *restrict Q = d->Q;
#pragma omp simd
  for (int i = lo; i < hi; i++) sw_frame_store(Q, S, i, sw_frame_orthonormalize(sw_frame_load(Q, S, i)));
}

/* PEFRL step (with analytic damping around it). */
static void pefrl_step(const swModel *m, swData *d) {
  const double h = m->dt;
  if (m->has_damping) analytic_decay(m, d);
  const double mid = (1 - 2 * (PEFRL_CHI + PEFRL_XI)) * h;
  drift(m, d, PEFRL_XI * h);
  kick(m, d, 0.5 * (1 - 2 * PEFRL_LAMBDA) * h, PEFRL_CHI * h);
  drift(m, d, PEFRL_CHI * h);
  kick(m, d, PEFRL_LAMBDA * h, mid);
  drift(m, d, mid);
  kick(m, d, PEFRL_LAMBDA * h, PEFRL_CHI * h);
  drift(m, d, PEFRL_CHI * h);
  /* the last kick's velocities serve this step's final drift and the next
   * step's first one */
  kick(m, d, 0.5 * (1 - 2 * PEFRL_LAMBDA) * h, 2 * PEFRL_XI * h);
  drift(m, d, PEFRL_XI * h);
  if (m->has_damping) analytic_decay(m, d);
}

/* The end of a step: its count and time (at the whole step, or, between
 * fused Verlet steps, half a step on; recomputed from the count, so no
 * round-off accumulates in t), on the leader; and when the check is `due`
 * (every 8 steps), the stability check: each thread counts the suspect slots
 * of its chunks, and the full check, which names the rod, runs on every rod
 * only when one is found, else on the rigid bodies alone, which it alone
 * covers (sw_check_rods).  SW_EUNSTABLE goes
 * into *rc, which every thread reads after the barrier, so the whole team
 * leaves the loop together.  Then, if `more` steps follow, the muscles'
 * activations for the next one. */
static void end_step(const swModel *m, swData *d, int count, int whole, int due, int more, int *rc) {
  const int n = m->nslot_elastic;
  if (due) { /* a count: any cut gives the same; one per thread, in its last chunk */
    int lo, hi;
    sw_share_slots(m, d, n, &lo, &hi);
    orthonormalize_frames(m, d, lo, hi);
    SW_FOR_CHUNKS(m, d, c, n) d->chunk_sum[c] = c == c_end - 1 ? sw_check_slots(m, d, lo, hi) : 0;
    sw_team_barrier(d);
  }
  if (sw_team_leader(d)) {
    d->step += count;
    d->time = ((double)d->step + (whole ? 0.0 : 0.5)) * m->dt;
    double suspect = 0; /* elastic slots the vector check flagged */
    if (due)
      for (int c = 0; c < sw_nchunk(m, n); c++) suspect += d->chunk_sum[c];
    if (due && (suspect > 0 || m->nrigid) && sw_check_rods(m, d, suspect == 0) != SW_OK) *rc = SW_EUNSTABLE;
    if (more && *rc == SW_OK && m->nmuscle)
      sw_muscle_ops(m)->advance(m, d, (double)d->step * m->dt, m->dt);
  }
  sw_team_barrier(d);
}

/* k steps.  Position Verlet is drift h/2, kick h, drift h/2 (with analytic
 * damping inside the kick); the last half drift of a step and the first of the next are
 * fused into one drift h, which is the same flow (the director rotation and
 * the angular-momentum rescaling of two half drifts compose to that of one
 * drift to the scheme's order), so k steps cost k kicks and k + 1 drifts.
 * Between fused steps the state sits at the half step, t = (step + 1/2) h;
 * it is at a whole step when sw_steps returns.  With `hold` (sw_steps_held)
 * the last step ends at its kick, its trailing half drift held back, and a
 * call that starts held runs that half drift fused with its own first one
 * and the held step's end (see "Held steps" below).  Run by every thread of
 * the team (or by the caller alone); *rc is shared. */
static void steps(const swModel *m, swData *d, long k, int hold, int *rc) {
  const double h = m->dt;
  const int held = d->held; /* read by all before the leader clears it */
  sw_team_barrier(d);
  if (held) { /* the held step's trailing half drift and our first: one drift h */
    drift(m, d, h);
    end_step(m, d, 0, 0, check_due(d->step), 1, rc);
    if (sw_team_leader(d)) d->held = 0;
  }
  const long step0 = d->step; /* read by all before the leader moves it */
  sw_team_barrier(d);
  if (m->nmuscle && !held) { /* activations of the first step (end_step does the rest) */
    if (sw_team_leader(d)) sw_muscle_ops(m)->advance(m, d, (double)step0 * h, h);
    sw_team_barrier(d);
  }
  if (m->integrator == SW_PEFRL) { /* whole steps: nothing to hold */
    for (long i = 0; i < k && *rc == SW_OK; i++) {
      pefrl_step(m, d);
      end_step(m, d, 1, 1, check_due(step0 + i + 1), i < k - 1, rc);
    }
    return;
  }
  if (!held) drift(m, d, 0.5 * h);
  const int fused = d->team_size <= 1 && sw_sweep_fits(m);
  for (long i = 0; i < k && *rc == SW_OK; i++) {
    const int last = i == k - 1;
    if (last && hold) { /* the kick alone, its work and rigid part booked */
      kick(m, d, h, h);
      sw_team_barrier(d);
      if (sw_team_leader(d)) {
        finish_kick(m, d);
        d->step++;
        d->time = ((double)d->step - 0.5) * h; /* where the positions are */
        d->held = 1;
      }
      sw_team_barrier(d);
      break;
    }
    if (fused) {
      sweep(m, d, h, h, last ? 0.5 * h : h);
    } else {
      kick(m, d, h, h);
      drift(m, d, last ? 0.5 * h : h);
    }
    end_step(m, d, 1, last, check_due(step0 + i + 1), !last, rc);
  }
}

static int run_steps(const swModel *m, swData *d, long k, int hold) {
  if (k <= 0) return SW_OK;
  if (d->whole) {
    snprintf(d->error, sizeof d->error, "a step was asked for between sw_whole_begin and sw_whole_end");
    return SW_EUSAGE;
  }
  int rc = SW_OK;
  if (d->threads <= 1) {
    steps(m, d, k, hold, &rc);
    return rc;
  }
#pragma omp parallel num_threads(d->threads)
  {
#pragma omp single
    d->team_size = omp_get_num_threads(); /* the runtime may give fewer */
    steps(m, d, k, hold, &rc);
  }
  d->team_size = 1;
  return rc;
}

int sw_steps(const swModel *m, swData *d, long k) { return run_steps(m, d, k, 0); }

/* ---- Held steps ----
 * Fusing the half drifts of two steps into one drift h saves a pass over
 * the state every step (unfused steps took 1.7x as long on rods of 25 to
 * 800 elements, docs/runtime.md, "Held steps"), but one drift h is not the same floating-point operations as
 * two drifts h/2: where a call of sw_steps ends, the trajectory's bits
 * change.  The run loop ends its calls where it must read the state (a
 * frame, an expectation's sample, 256 steps for Ctrl-C), so before
 * 2026-11 `--every`, an `expect` line or an objective moved a sensitive
 * outcome (a frog's toe height, by 2x).  Held steps keep the fusion across
 * calls: sw_steps_held stops after the last step's kick; sw_whole_begin
 * copies what a half drift moves (x, v, Q, omega, the dilatation, the rigid
 * bodies' pose, the hinge angles' unwrapping), runs the half drift and the
 * step's end, so that the state is exactly the one sw_steps would have
 * returned, and sw_whole_end puts the copy back.  Whatever reads the whole
 * state in between changes nothing a step reads (the strains and joint
 * forces a frame recomputes are scratch the next kick computes afresh).
 * PEFRL's steps are whole already: they are never held. */

/* The hold's parts: per-slot planes, then per-body and per-joint rows. */
#define HOLD_PLANES 19 /* x 3, v 3, Q 9, omega 3, dilatation 1 */
size_t sw_hold_size(const swModel *m) {
  return (size_t)HOLD_PLANES * (size_t)m->stride + 15 * (size_t)m->nrigid + (size_t)m->njoint +
         (size_t)sw_nchunk(m, m->stride);
}

/* Copies the hold's arrays between d and the hold: `save` 1 into it, 0 back. */
static void hold_copy(const swModel *m, swData *d, int save) {
  const size_t S = (size_t)m->stride, B = (size_t)m->nrigid;
  struct { double *a; size_t n; } part[] = {
      {d->x, 3 * S}, {d->v, 3 * S}, {d->Q, 9 * S}, {d->omega, 3 * S}, {d->dilatation, S},
      {d->rigid_X, 3 * B}, {d->rigid_R, 9 * B}, {d->rigid_omega, 3 * B},
      {d->joint_angle, (size_t)m->njoint}, {d->chunk_sum, (size_t)sw_nchunk(m, m->stride)}};
  double *p = d->hold;
  for (size_t k = 0; k < sizeof part / sizeof *part; k++) {
    if (part[k].n) memcpy(save ? p : part[k].a, save ? part[k].a : p, part[k].n * sizeof *p);
    p += part[k].n;
  }
}

int sw_steps_held(const swModel *m, swData *d, long k) {
  return run_steps(m, d, k, m->integrator != SW_PEFRL);
}

/* The held step's trailing half drift and its end, as sw_steps ends. */
static int complete_held(const swModel *m, swData *d) {
  int rc = SW_OK;
  drift(m, d, 0.5 * m->dt);
  end_step(m, d, 0, 1, check_due(d->step), 0, &rc);
  return rc;
}

int sw_whole_begin(const swModel *m, swData *d) {
  if (!d->held || d->whole) return SW_OK;
  hold_copy(m, d, 1);
  d->whole = 1;
  int rc = complete_held(m, d);
  if (rc != SW_OK) d->whole = d->held = 0; /* left whole, for the diagnosis */
  return rc;
}

void sw_whole_end(const swModel *m, swData *d) {
  if (!d->whole) return;
  hold_copy(m, d, 0);
  d->time = ((double)d->step - 0.5) * m->dt;
  d->whole = 0;
}

double sw_time(const swModel *m, const swData *d) {
  return d->held && !d->whole ? (double)d->step * m->dt : d->time;
}

int sw_settle(const swModel *m, swData *d) {
  if (!d->held || d->whole) return SW_OK;
  d->held = 0;
  const int rc = complete_held(m, d);
  /* the joints as a reading of the whole step measured them (a frame's), so
   * that the state a run ends in is the one its last frame shows */
  for (int j = 0; rc == SW_OK && j < m->njoint; j++) sw_joint_measure(m, d, j);
  return rc;
}

int sw_step(const swModel *m, swData *d) { return sw_steps(m, d, 1); }

/* A spin-wait hint to the processor (x86 PAUSE; nothing elsewhere). */
static inline void sw_cpu_relax(void) {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

void sw_team_wait(swTeam *t, int size) {
  const int g = atomic_load_explicit(&t->generation, memory_order_acquire);
  if (atomic_fetch_add_explicit(&t->count, 1, memory_order_acq_rel) == size - 1) {
    atomic_store_explicit(&t->count, 0, memory_order_relaxed);
    atomic_store_explicit(&t->generation, g + 1, memory_order_release);
    return;
  }
  for (long spins = 0; atomic_load_explicit(&t->generation, memory_order_acquire) == g; spins++) {
    if (spins < 256) sw_cpu_relax();
    else sched_yield();
  }
}

int sw_set_threads(swData *d, int n) {
  d->threads = n < 1 ? 1 : n;
  return d->threads;
}
