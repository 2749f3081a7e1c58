/* muscle_implicit.c — the filaments' Hill damping, linearly implicit (SW_IMEX).
 *
 * Design.  muscle.c computes each filament's tension from its stretch and
 * strain rate; under imex the rate's part, the Hill damping, is taken at
 * the velocities the kick produces.
 *
 * The slope c = dT/d(dl/dt) of the law is
 * a dashpot across the whole filament, stiff at the small end masses of a
 * filament (it limits the elbow's explicit step to 1.34 us), and it is rank
 * one: dl/dt = b . v with b_i = t_{i-1} - t_i at node i, and the pull is
 * -T b.  So the kick of length h can take the tension at the velocities it
 * produces, linearised about the old ones (Rosenbrock-Euler, the linearly
 * implicit Euler method: Hairer & Wanner, Solving ODEs II, sec. IV.7):
 *   T* = T0 + c b . dv,   dv = h M^-1 (F - T* b)
 *   =>  T* = (T0 + c h p) / (1 + c h s),  p = b . M^-1 F,  s = b . M^-1 b,
 * F the filament nodes' other loads, summed before the pull.  This is
 * Sherman-Morrison on (M + h c b b^T) solved for the one unknown that
 * matters, so it costs two sums over the filament's nodes.  The damper's
 * amplification is 1 / (1 + c h s): L-stable, so the step no longer sees the
 * damping (sw_stable_dt_filament), and at c h s << 1 it is the explicit
 * tension to O(h).  T* is floored at 0 (the law never pushes).  A clamped
 * end node counts as an infinite mass (dv = 0); filaments with a prescribed
 * end velocity, with analytic damping, or rigid stay explicit (their kick is
 * not dv = h M^-1 F).
 *
 * A filament's via rings join the solve under imex (via_implicit.c: p
 * and s are taken through them, and their forces follow T).
 *
 * A filament whose ends are leaves of the joints' system (joint_ports.c),
 * or attachments in it (joint_groups.c, dense_ends), is solved in two
 * parts: sw_muscle_system_part before the system, with the interior nodes
 * only, and sw_muscle_system_tension after it, from the ends' velocity
 * changes.
 */
#include <math.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* dT/d(edot) of sw_muscle_tension (1/s -> N s): F_qs g'(u) du/d(edot), with
 * u = -edot, so -F_qs g'(u); 0 beyond u0, constant when lengthening. */
double sw_muscle_tension_slope(const swModel *m, int f, double eta, double edot, double a) {
  const double Fmax = m->fil_fmax[f];
  const double Fqs = a * sw_muscle_f_act(eta) * Fmax + Fmax * sw_muscle_f_pass(eta);
  const double k = m->fil_hill_a[f], u0 = m->fil_v_max[f], u = -edot;
  if (u >= u0) return 0;
  if (u >= 0) return Fqs * (1.0 + k) * k * u0 / ((u + k * u0) * (u + k * u0));
  return Fqs * (1.0 + k) / (k * u0);
}

/* The unit tangent t_i of element i of the filament whose first element
 * is lo (n elements); 0 past its last, so that b_n = t_{n-1}. */
static void tangent(const swModel *m, const swData *d, int lo, int i, int n, double *t) {
  t[0] = t[1] = t[2] = 0;
  if (i >= n) return;
  double xi[3];
  sw_get3(m, d->x, lo + i + 1, t);
  sw_get3(m, d->x, lo + i, xi);
  sw_v3_sub(t, t, xi);
  sw_v3_scale(t, t, 1.0 / d->length[lo + i]);
}

/* The implicit tension of filament f over a kick h (the header):
 * (T0 + c h p) / (1 + c h s), c = dT/d(dl/dt), floored at 0; with its via
 * rings taken implicitly too (via_implicit.c: p and s through the rings,
 * and the rings' force changes once T is known). */
double sw_muscle_implicit_tension(const swModel *m, swData *d, int f, double T0, double eta,
                                  double edot, double h) {
  const int r = m->fil_rod[f], lo = m->elem_adr[r], n = m->rod_nelem[r], bits = m->fil_implicit[f];
  const int rings = m->nring && m->fil_ring_adr[f] < m->fil_ring_adr[f + 1];
  const double c = sw_muscle_tension_slope(m, f, eta, edot, d->fil_activation[f]) / m->fil_l0[f];
  if (!(c > 0) && !rings) return T0;
  double p = 0, s = 0, t_before[3] = {0, 0, 0};
  for (int i = 0; i <= n; i++) { /* node lo + i: b_i = t_{i-1} - t_i */
    double t[3], b[3], F[3];
    tangent(m, d, lo, i, n, t);
    sw_v3_sub(b, t_before, t);
    sw_get3(m, d->force, lo + i, F);
    const int held = (i == 0 && (bits & SW_FIL_HELD_START)) || (i == n && (bits & SW_FIL_HELD_END));
    const double im = held ? 0.0 : m->inv_mass[lo + i];
    p += im * sw_v3_dot(b, F);
    s += im * sw_v3_dot(b, b);
    memcpy(t_before, t, sizeof t);
  }
  if (rings) sw_via_implicit_sums(m, d, f, h, &p, &s);
  double T = T0;
  if (c > 0) {
    T = (T0 + c * h * p) / (1.0 + c * h * s);
    if (!(T > 0)) T = 0;
  }
  if (rings) sw_via_implicit_force(m, d, f, T);
  return T;
}

/* A filament whose ends are leaves of the joints' system (joint_ports.c,
 * m->fil_system): the same solve with its two end nodes left out of p and
 * s, since their velocity changes come from that system, which takes the
 * rest of the tension, c' (b_ends . dv_ends), as a dashpot of its own:
 *   T = T_int + c' b_e . dv_e,  T_int = (T0 + c h p_int) / (1 + c h s_int),
 *   c' = c / (1 + c h s_int),
 * the elimination of the interior nodes' dv = h M^-1 (F - T b) from the
 * Rosenbrock-Euler equations above.  Stores T_int, c' and the ends' b in
 * d->fil_sys and returns T_int, pulled on every node until the system's
 * solve gives T (sw_muscle_system_tension). */
double sw_muscle_system_part(const swModel *m, swData *d, int f, double T0, double eta, double edot,
                             double h) {
  const int r = m->fil_rod[f], lo = m->elem_adr[r], n = m->rod_nelem[r];
  double c = h > 0 ? sw_muscle_tension_slope(m, f, eta, edot, d->fil_activation[f]) / m->fil_l0[f] : 0;
  if (!(c > 0)) c = 0;
  double p = 0, s = 0, t_before[3] = {0, 0, 0}, *sys = d->fil_sys + 8 * (size_t)f;
  for (int i = 0; i <= n; i++) { /* node lo + i: b_i = t_{i-1} - t_i */
    double t[3], b[3], F[3];
    tangent(m, d, lo, i, n, t);
    sw_v3_sub(b, t_before, t);
    memcpy(t_before, t, sizeof t);
    if (i == 0 || i == n) { /* the ends: the system's */
      memcpy(sys + (i ? 5 : 2), b, sizeof b);
      continue;
    }
    sw_get3(m, d->force, lo + i, F);
    p += m->inv_mass[lo + i] * sw_v3_dot(b, F);
    s += m->inv_mass[lo + i] * sw_v3_dot(b, b);
  }
  if (m->nring && m->fil_ring_adr[f] < m->fil_ring_adr[f + 1]) sw_via_implicit_sums(m, d, f, h, &p, &s);
  sys[0] = (T0 + c * h * p) / (1.0 + c * h * s);
  sys[1] = c / (1.0 + c * h * s);
  return sys[0];
}

/* The filament's tension once its ends' dv are known (the header of
 * system_part), floored at 0 as the law is, and the pull on its interior
 * nodes made that of T rather than T_int: node i gets -(T - T_int) b_i. */
void sw_muscle_system_tension(const swModel *m, swData *d, int f, const double *dv_start,
                              const double *dv_end) {
  const double *sys = d->fil_sys + 8 * (size_t)f;
  double T = sys[0];
  if (dv_start) T += sys[1] * sw_v3_dot(sys + 2, dv_start);
  if (dv_end) T += sys[1] * sw_v3_dot(sys + 5, dv_end);
  if (!(T > 0)) T = 0;
  const double dT = T - sys[0];
  d->fil_tension[f] = T;
  const int r = m->fil_rod[f], lo = m->elem_adr[r], n = m->rod_nelem[r];
  double t_before[3];
  tangent(m, d, lo, 0, n, t_before);
  for (int i = 1; i < n; i++) {
    double t[3];
    tangent(m, d, lo, i, n, t);
    for (int k = 0; k < 3; k++) { /* -dT b_i = dT (t_i - t_{i-1}) */
      const double dF = dT * (t[k] - t_before[k]);
      SW_AT(m, d->force, lo + i, k) += dF;
      SW_AT(m, d->ext_force, lo + i, k) += dF;
    }
    memcpy(t_before, t, sizeof t);
  }
  /* the rings' force changes at T, added by the joints' system once the
   * batch of groups the filament is in is solved (rigid_joint.c) */
  if (m->nring) sw_via_implicit_force(m, d, f, T);
}
