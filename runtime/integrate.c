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
 */
#include <math.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* All loads of the current configuration: internal, clamp couples, external,
 * joints (whose damping joint.c adds to the external loads, so that the kick
 * books its work, and whose springs count as elastic energy), muscles (active:
 * their tensions count as external loads, muscle.c).  Muscle activations
 * advance once a step, before its first kick (sw_muscle_advance). */
static void compute_loads(const swModel *m, swData *d) {
  sw_internal_loads(m, d);
  if (m->nbc) sw_bc_loads(m, d);
  sw_external_loads(m, d);
  if (m->njoint) sw_joint_loads(m, d);
  if (m->nmuscle) sw_muscle_loads(m, d);
  if (sw_has_env(m)) sw_env_loads(m, d); /* last: the ground balances the rest */
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
  const int simpson = m->integrator == SW_PEFRL;
  const size_t S = (size_t)m->stride;
  for (int r = 0; r < m->nrod; r++) {
    if (sw_rod_is_rigid(m, r)) continue;
    const int n = m->rod_nelem[r], a = m->node_adr[r];
    double *restrict x = d->x + a;
    const double *restrict v = d->v + a;
    double *restrict w = d->omega + a, *restrict Qs = d->Q + a;
    double *restrict dil = d->dilatation + a;
    const double *restrict irl = m->inv_rest_len + a;
    for (int k = 0; k < 3; k++)
      for (int i = 0; i <= n; i++) x[k * S + i] += h * v[k * S + i];
    for (int i = 0; i < n; i++) {
      double dx[3], dv[3];
      for (int k = 0; k < 3; k++) {
        dx[k] = x[k * S + i + 1] - x[k * S + i];
        dv[k] = v[k * S + i + 1] - v[k * S + i];
      }
      const double inv_e_old = 1.0 / dil[i], e_new = sw_v3_norm(dx) * irl[i];
      const double ratio = e_new * inv_e_old;
      double mean; /* (1/h) integral of e dt over the drift, in units of e_old */
      if (simpson) {
        double mid[3] = {dx[0] - 0.5 * h * dv[0], dx[1] - 0.5 * h * dv[1], dx[2] - 0.5 * h * dv[2]};
        mean = (1.0 + 4.0 * sw_v3_norm(mid) * irl[i] * inv_e_old + ratio) * (1.0 / 6.0);
      } else {
        mean = 0.5 * (1.0 + ratio);
      }
      const double hm = h * mean;
      double phi[3], Q[9];
      for (int k = 0; k < 3; k++) phi[k] = hm * w[k * S + i];
      for (int k = 0; k < 9; k++) Q[k] = Qs[k * S + i];
      sw_rotate_frame(Q, phi);
      for (int k = 0; k < 9; k++) Qs[k * S + i] = Q[k];
      for (int k = 0; k < 3; k++) w[k * S + i] *= ratio;
      dil[i] = e_new;
    }
  }
  if (m->nrigid) sw_rigid_drift(m, d, h);
  d->time += h;
}

/* Velocities change under the loads of the current configuration.  `span`
 * is the length of drift that the new velocities will be used for before
 * the next kick: prescribed velocities are taken at its midpoint, so that
 * a prescribed end moves by the midpoint rule's integral of its profile
 * (position Verlet's v_{n+1} is the velocity at t_{n+1} = t_kick + h/2). */
static void kick(const swModel *m, swData *d, double h, double span) {
  compute_loads(m, d);
  double *restrict v = d->v, *restrict w = d->omega;
  const double *restrict F = d->force, *restrict T = d->torque;
  const double *restrict ef = d->ext_force, *restrict et = d->ext_torque;
  const double *restrict im = m->inv_mass, *restrict iJ = m->inv_inertia;
  const double *restrict e = d->dilatation;
  const size_t S = (size_t)m->stride;
  double work = 0, exact_work = 0;
  for (int r = 0; r < m->nrod; r++) {
    if (sw_rod_is_rigid(m, r)) continue;
    const int n0 = m->node_adr[r], n1 = n0 + m->rod_nelem[r] + 1;
    const int e0 = m->elem_adr[r], e1 = e0 + m->rod_nelem[r];
    if (m->rod_damping[r] == SW_DAMP_ANALYTIC && m->integrator == SW_VERLET) {
      /* exact for dv/dt = a - c v (model.c); the work of loads and
       * dissipation together is the non-internal impulse times the mean
       * velocity */
      for (int i = n0; i < n1; i++)
        for (int k = 0; k < 3; k++) {
          size_t q = k * S + i;
          double vo = v[q], vn = vo * m->node_decay[i] + F[q] * im[i] * m->node_kick[i];
          exact_work += (m->mass[i] * (vn - vo) - h * (F[q] - ef[q])) * (vo + vn);
          v[q] = vn;
        }
      for (int i = e0; i < e1; i++)
        for (int k = 0; k < 3; k++) {
          size_t q = k * S + i;
          double Je = m->inertia[q] / e[i];
          double wo = w[q], wn = wo * m->elem_decay[q] + T[q] * iJ[q] * e[i] * m->elem_kick[q];
          exact_work += (Je * (wn - wo) - h * (T[q] - et[q])) * (wo + wn);
          w[q] = wn;
        }
      continue;
    }
    for (int i = n0; i < n1; i++)
      for (int k = 0; k < 3; k++) {
        size_t q = k * S + i;
        double vo = v[q], vn = vo + h * F[q] * im[i];
        work += ef[q] * (vo + vn);
        v[q] = vn;
      }
    /* (J^/e) dw/dt = tau  (Gazzola 2018, eq. 3.7b, the couples of rod.c
     * without the dilatation-rate term, which the drift integrates) */
    for (int i = e0; i < e1; i++)
      for (int k = 0; k < 3; k++) {
        size_t q = k * S + i;
        double wo = w[q], wn = wo + h * T[q] * iJ[q] * e[i];
        work += et[q] * (wo + wn);
        w[q] = wn;
      }
  }
  d->work += 0.5 * h * work + 0.5 * exact_work;
  if (m->nrigid) sw_rigid_kick(m, d, h);
  if (m->nbc) sw_bc_kick(m, d, h, d->time + 0.5 * span);
}

/* Exact decay of the analytically damped rods over half a step (PEFRL). */
static void analytic_decay(const swModel *m, swData *d) {
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
      lost += 0.5 * m->mass[i] * v2 * (1 - f * f);
    }
    for (int e = ea; e < ea + n; e++)
      for (int k = 0; k < 3; k++) {
        double w = SW_AT(m, d->omega, e, k), f = SW_AT(m, m->elem_decay, e, k);
        SW_AT(m, d->omega, e, k) = f * w;
        lost += 0.5 * SW_AT(m, m->inertia, e, k) / d->dilatation[e] * w * w * (1 - f * f);
      }
  }
  d->work -= lost;
}

/* PEFRL coefficients, Omelyan et al. 2002, eq. 20. */
static const double PEFRL_XI = 0.1786178958448091;
static const double PEFRL_LAMBDA = -0.2123418310626054;
static const double PEFRL_CHI = -0.06626458266981849;

/* The stability check runs every 8 steps and on each of the first 8. */
static int check_due(long step) { return (step & 7) == 0 || step < 8; }

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

/* k steps.  Position Verlet is drift h/2, kick h, drift h/2 (with analytic
 * damping inside the kick); the last half drift of a step and the first of the next are
 * fused into one drift h, which is the same flow (the director rotation and
 * the angular-momentum rescaling of two half drifts compose to that of one
 * drift to the scheme's order), so k steps cost k kicks and k + 1 drifts.
 * Between fused steps the state sits at the half step, t = (step + 1/2) h;
 * it is at a whole step when sw_steps returns. */
int sw_steps(const swModel *m, swData *d, long k) {
  const double h = m->dt;
  if (k <= 0) return SW_OK;
  if (m->integrator == SW_PEFRL) {
    for (long i = 0; i < k; i++) {
      if (m->nmuscle) sw_muscle_advance(m, d, (double)d->step * h, h);
      pefrl_step(m, d);
      d->step++;
      d->time = (double)d->step * h; /* no accumulated round-off in t */
      if (check_due(d->step) && sw_check_finite(m, d) != SW_OK) return SW_EUNSTABLE;
    }
    return SW_OK;
  }
  drift(m, d, 0.5 * h);
  for (long i = 0; i < k; i++) {
    if (m->nmuscle) sw_muscle_advance(m, d, (double)d->step * h, h);
    kick(m, d, h, h);
    d->step++;
    const int last = i == k - 1;
    drift(m, d, last ? 0.5 * h : h);
    d->time = ((double)d->step + (last ? 0.0 : 0.5)) * h;
    if (check_due(d->step) && sw_check_finite(m, d) != SW_OK) return SW_EUNSTABLE;
  }
  return SW_OK;
}

int sw_step(const swModel *m, swData *d) { return sw_steps(m, d, 1); }
