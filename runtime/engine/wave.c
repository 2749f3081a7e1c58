/* wave.c — the travelling muscle-torque wave of a snake-like rod.
 *
 * Design.  Gazzola et al. 2018 (R. Soc. open sci. 5: 171628, sec. 4.3, the
 * continuum snake) drive a rod by a bending moment that travels along it,
 *   tau(s, t) = ramp(t) beta(s) sin(2 pi t / T - 2 pi s / lambda + phi),
 * with beta(s) a cubic B-spline whose coefficients an optimiser chose.  The
 * moment is internal: the muscles on one side of a cross-section pull on
 * those on the other, so the moment tau_i at interior node i turns the
 * element after the node by +tau_i m_i and the one before it by -tau_i m_i.
 * Each element therefore gets the difference of the moments at its two
 * ends, tau(start) m(start) - tau(end) m(end); the free ends carry none, so
 * the couples sum to zero and the rod's total angular momentum is untouched.
 * Its sign is the one under which a rod at rest settles at the curvature
 * kappa = tau / B (rod.c scatters the bending couple c_j as +c_j to element
 * j and -c_j to element j+1, and the balance c_j = tau_j follows node by
 * node from a free end).
 *
 * The axis turns with the body.  The muscles are attached to the body, so
 * the moment is about a body-fixed axis: each element carries the axis that
 * `direction` (lab frame) had in its material frame at t = 0, a_e = Q0_e
 * direction, and m_i is the normalised mean of the two elements' current
 * axes Q^T a.  PyElastica's MuscleTorques and Elastica's SplineMuscleTorques
 * keep the axis fixed in the lab instead; the two agree while the rod only
 * bends about that axis (a snake on flat ground: to round-off).  They part
 * on a terrain: on a rod curved in a vertical plane, a lab-fixed lateral
 * moment has a component sum_i tau_i z . (d3_i - d3_{i-1}) about the
 * elements' own axes that does not depend on how far they have rolled.  The
 * roll of a round, isotropic rod has no elastic stiffness, the ground's
 * friction acts at the element centre by default (no couple, ground.c) and the
 * mass-proportional damping lets it decay at only gamma / (rho A), so the
 * reference's snake on the barrier of Zhang 2019 Suppl. Fig. 11 spun up to
 * ~600 rad/s (100 J of the wave's work) and the explicit gyroscopic couple
 * (J^ w / e) x w then made it unstable (docs/physics.md, "Torque wave").  A
 * body-fixed moment turns with the roll, so its part about the axis goes as
 * cos(roll) and the roll stays a bounded swing (test_ground, the roll on a
 * curved terrain).
 *
 * Units.  beta and its coefficients are moments in N m, used as they are:
 * PyElastica's MuscleTorques multiplies the spline straight into the couple,
 * and Elastica's C++ snake (the source of Gazzola 2018's numbers) passes
 * {17.29, 48.54, 5.392, 14.74} N m unscaled.  For the reference's snake
 * (Zhang 2019, Suppl. Fig. 12: E = 1e7 Pa, r = 0.025 m, so E I = 3.07 N m^2)
 * the spline of {0, 17.4, 48.5, 5.4, 14.7, 0} peaks at 33.6 N m (s = 0.34 L,
 * test_wave.c), which would hold a curvature of 10.9 / m, a lateral
 * amplitude kappa / k^2 = 0.26 L for k = 2 pi / (0.97 L) — close to the
 * 0.20 L of PyElastica's own snake example (L = 0.35 m, E I = 1.7e-4 N m^2,
 * beta peaking at 3.8e-3 N m, lambda = L).  Both are plausible undulations,
 * so the reference's numbers need no normalisation.
 *
 * Cost.  beta is evaluated once, at setup, with GSL's B-splines; the step
 * only evaluates sin and cos of 2 pi t / T once per wave, because
 * sin(wt - theta_i) = sin(wt) cos(theta_i) - cos(wt) sin(theta_i) with
 * beta_i cos(theta_i) and beta_i sin(theta_i) stored per node (wave_amp).
 * The couples go into d->ext_torque and d->torque, so the kick books their
 * work (integrate.c).
 */
#include <gsl/gsl_bspline.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <stdlib.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* beta(s) of wave k at the nodes of its rod: the clamped cubic B-spline of
 * sinew.h over [0, L] (GSL: order 4, ncoef - 2 uniform breakpoints). */
static int wave_beta(const swWaveDesc *w, const double *s, double L, int nnode, double *beta) {
  gsl_bspline_workspace *bw = gsl_bspline_alloc(4, (size_t)(w->ncoef - 2));
  gsl_vector *B = gsl_vector_alloc((size_t)w->ncoef);
  if (!bw || !B) {
    if (bw) gsl_bspline_free(bw);
    if (B) gsl_vector_free(B);
    return 0;
  }
  gsl_bspline_knots_uniform(0.0, L, bw);
  for (int i = 0; i < nnode; i++) {
    double x = s[i] < 0 ? 0 : s[i] > L ? L : s[i]; /* round-off of the sum */
    gsl_bspline_eval(x, B, bw);
    double b = 0;
    for (int j = 0; j < w->ncoef; j++) b += w->coef[j] * gsl_vector_get(B, (size_t)j);
    beta[i] = b;
  }
  gsl_vector_free(B);
  gsl_bspline_free(bw);
  return 1;
}

int sw_wave_setup(swModel *m) {
  int rows = 0;
  for (int k = 0; k < m->nwave; k++) rows += m->rod_nelem[m->wave[k].rod] + 1;
  m->wave_node_adr = calloc((size_t)m->nwave + 1, sizeof(int));
  m->wave_s = calloc((size_t)(rows ? rows : 1), sizeof(double));
  m->wave_beta = calloc((size_t)(rows ? rows : 1), sizeof(double));
  m->wave_amp = calloc((size_t)(rows ? 2 * rows : 1), sizeof(double));
  if (!m->wave_node_adr || !m->wave_s || !m->wave_beta || !m->wave_amp) return 0;
  for (int k = 0, row = 0; k < m->nwave; k++) {
    swWaveDesc *w = &m->wave[k];
    const int r = w->rod, n = m->rod_nelem[r], ea = m->elem_adr[r];
    m->wave_node_adr[k] = row;
    sw_v3_scale(w->direction, w->direction, 1.0 / sw_v3_norm(w->direction));
    double *s = m->wave_s + row, *beta = m->wave_beta + row, *amp = m->wave_amp + 2 * row;
    double L = 0; /* arc length along the rest shape */
    s[0] = 0;
    for (int i = 0; i < n; i++) s[i + 1] = (L += m->rest_len[ea + i]);
    if (w->reverse)
      for (int i = 0; i <= n; i++) s[i] = L - s[i];
    if (!wave_beta(w, s, L, n + 1, beta)) return 0;
    beta[0] = beta[n] = 0; /* free ends hold no moment */
    for (int i = 0; i <= n; i++) {
      const double theta = 2.0 * SW_PI * s[i] / w->wavelength - w->phase;
      amp[2 * i] = beta[i] * cos(theta);
      amp[2 * i + 1] = beta[i] * sin(theta);
    }
    row += n + 1;
  }
  m->wave_node_adr[m->nwave] = rows;
  return 1;
}

void sw_wave_free(swModel *m) {
  free(m->wave_node_adr);
  free(m->wave_s);
  free(m->wave_beta);
  free(m->wave_amp);
  m->wave_node_adr = NULL;
  m->wave_s = m->wave_beta = m->wave_amp = NULL;
}

/* The body-fixed axis of element e in the lab frame: `direction` as the
 * element saw it at t = 0 (Q0 direction, material), turned with it (Q^T). */
static void body_axis(double out[3], const swModel *m, const swData *d, int e, const double dir[3]) {
  double Q0[9], Q[9], a[3];
  sw_getQ(m, m->Q0, e, Q0);
  sw_getQ(m, d->Q, e, Q);
  sw_mat_vec(a, Q0, dir);
  sw_matT_vec(out, Q, a);
}

/* The moment at every node of each wave's rod, and the couple it makes on
 * each element (sinew.h, "travelling muscle-torque wave"). */
void sw_wave_loads(const swModel *m, swData *d, int lo, int hi) {
  const double t = d->time;
  for (int k = 0; k < m->nwave; k++) {
    const swWaveDesc *w = &m->wave[k];
    if (m->node_adr[w->rod] < lo || m->node_adr[w->rod] >= hi) continue; /* another thread's rod */
    const double ramp = w->ramp > 0 && t < w->ramp ? (t > 0 ? t / w->ramp : 0.0) : 1.0;
    const double wt = 2.0 * SW_PI * t / w->period;
    const double sin_wt = ramp * sin(wt), cos_wt = ramp * cos(wt);
    const int n = m->rod_nelem[w->rod], ea = m->elem_adr[w->rod];
    const double *restrict amp = m->wave_amp + 2 * m->wave_node_adr[k];
    double tau_start = 0, m_start[3] = {0, 0, 0}; /* node 0: a free end, no moment */
    double axis[3], axis_next[3] = {0, 0, 0};
    body_axis(axis, m, d, ea, w->direction);
    for (int i = 0; i < n; i++) {
      /* tau at the element's end node, sin(wt - theta) expanded, about the
       * mean of the axes of the two elements that meet there */
      const double tau_end = sin_wt * amp[2 * (i + 1)] - cos_wt * amp[2 * (i + 1) + 1];
      double m_end[3] = {0, 0, 0};
      if (i + 1 < n) {
        body_axis(axis_next, m, d, ea + i + 1, w->direction);
        sw_v3_add(m_end, axis, axis_next);
        const double len = sw_v3_norm(m_end);
        if (len > 0) sw_v3_scale(m_end, m_end, 1.0 / len);
      }
      double lab[3], c[3];
      for (int q = 0; q < 3; q++) lab[q] = tau_start * m_start[q] - tau_end * m_end[q];
      double Q[9];
      sw_getQ(m, d->Q, ea + i, Q);
      sw_mat_vec(c, Q, lab); /* lab -> material frame of the element */
      sw_add3(m, d->ext_torque, ea + i, c);
      sw_add3(m, d->torque, ea + i, c);
      tau_start = tau_end;
      for (int q = 0; q < 3; q++) {
        m_start[q] = m_end[q];
        axis[q] = axis_next[q];
      }
    }
  }
}
