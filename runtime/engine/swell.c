/* swell.c — rods whose geometry changes in time: radius, stiffness, inertia,
 * mass and rest curvature following signals.
 *
 * Design.  The model stays immutable: it keeps every rod's geometry at t = 0
 * and, for each swelling rod (swRodDesc.swell), its signals r(t), c(t), w(t).
 * The state carries the geometry the step reads, as pointers (swData's
 * *_now): to the model's own arrays when no rod swells, so a scene without
 * the feature reads exactly what it read before (one pointer load a pass, no
 * branch in any loop), else to copies owned by the state, whose slots on the
 * swelling rods sw_swell_update rewrites at the time of each kick, without
 * allocating.  The kernels' loops are unchanged: they read the per-slot
 * arrays through these pointers.
 *
 * With g = r(t) / r(0) (the radius profile scales as a whole, a taper keeps
 * its ratio) and E, G fixed (a material property):
 *   A ~ g^2, I ~ g^4         S^ = diag(4GA/3, 4GA/3, EA) ~ g^2,
 *                            B^ = diag(EI1, EI2, GJ)      ~ g^4,
 *   mass conserved           rho ~ g^-2: node masses fixed, J^ = rho l^ I ~ g^2
 *   density fixed            node masses ~ g^2,           J^ ~ g^4
 *   rest curvature           kappa0_1,2 = kappa0_1,2(0) c(t)
 *   rest twist               kappa0_3 = kappa0_3(0) w(t), or r(0)/r(t) under
 *                            the reference's law (Zhang et al. 2019's code,
 *                            mattialab/elastica source/Polymer.cpp: k3 scaled
 *                            by r0/r each step; the mechanism of Charles,
 *                            Gazzola & Mahadevan, PRL 2019)
 * (Gazzola et al. 2018, eqs. 2.6-2.9: S^ and B^ from A and I.)  Velocities
 * and angular velocities are kept across a change of mass or inertia: new
 * mass arrives moving with the rod (docs/physics.md, "Geometry that changes
 * in time").  The stable-dt estimate (stability.c) covers the least and the
 * greatest g the signal takes, swell_range, set here once.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
#include "internal.h"
#include "model.h"

/* the state's copies, plane by plane (swData.swell_own) */
enum { P_RADIUS = 0, P_SHEAR = 1, P_BEND = 4, P_KAPPA0 = 7, P_INERTIA = 10, P_INV_INERTIA = 13,
       P_MASS = 16, P_INV_MASS = 17, P_WEIGHT = 18, P_CLAMP = 19, P_PLANES = 22 };

int sw_swell_setup(swModel *m, const swSpec *s) {
  int n = 0;
  for (int r = 0; r < s->nrod; r++) n += s->rod[r].swell != 0;
  m->nswell = n;
  if (!n) return 1;
  m->swell_rod = calloc((size_t)n, sizeof(int));
  m->swell_flags = calloc((size_t)n, sizeof(int));
  m->swell_sig = calloc(3 * (size_t)n, sizeof(swSignal));
  m->swell_range = sw_dalloc(2 * (size_t)n);
  if (!m->swell_rod || !m->swell_flags || !m->swell_sig || !m->swell_range) return 0;
  for (int r = 0, k = 0; r < s->nrod; r++) {
    const swRodDesc *rd = &s->rod[r];
    if (!rd->swell) continue;
    m->swell_rod[k] = r;
    m->swell_flags[k] = (rd->swell_twist_radius ? SW_SWELL_TWIST_RADIUS : 0) |
                        (rd->swell_mass_grows ? SW_SWELL_MASS_GROWS : 0);
    m->swell_sig[3 * k] = rd->swell_radius;
    m->swell_sig[3 * k + 1] = rd->swell_curvature;
    m->swell_sig[3 * k + 2] = rd->swell_twist;
    double lo, hi, r0 = sw_signal_eval(&rd->swell_radius, 0.0);
    sw_signal_range(&rd->swell_radius, &lo, &hi);
    /* the range holds r(0) (a FUNC signal is sampled from t0 = 0) */
    m->swell_range[2 * k] = fmin(lo, r0) / r0;
    m->swell_range[2 * k + 1] = fmax(hi, r0) / r0;
    k++;
  }
  return 1;
}

void sw_swell_free(swModel *m) {
  free(m->swell_rod); free(m->swell_flags); free(m->swell_sig); free(m->swell_range);
}

/* The swelling rod k of rod r, or -1. */
int sw_swell_of_rod(const swModel *m, int r) {
  for (int k = 0; k < m->nswell; k++)
    if (m->swell_rod[k] == r) return k;
  return -1;
}

/* Points the state's geometry at the model's arrays, or at copies of them
 * when some rod swells.  Returns 0 when out of memory. */
int sw_swell_data_new(const swModel *m, swData *d) {
  d->radius_now = m->radius; d->shear_now = m->shear_stiff; d->bend_now = m->bend_stiff;
  d->kappa0_now = m->rest_kappa; d->inertia_now = m->inertia; d->inv_inertia_now = m->inv_inertia;
  d->mass_now = m->mass; d->inv_mass_now = m->inv_mass; d->weight_now = m->weight;
  d->swell_time = NAN;
  if (!m->nswell) return 1;
  const size_t S = (size_t)m->stride;
  double *p = sw_palloc(m, P_PLANES);
  d->swell_g = sw_dalloc((size_t)m->nswell);
  if (!p || !d->swell_g) { free(p); return 0; }
  d->swell_own = p;
  memcpy(p + P_RADIUS * S, m->radius, S * sizeof(double));
  memcpy(p + P_SHEAR * S, m->shear_stiff, 3 * S * sizeof(double));
  memcpy(p + P_BEND * S, m->bend_stiff, 3 * S * sizeof(double));
  memcpy(p + P_KAPPA0 * S, m->rest_kappa, 3 * S * sizeof(double));
  memcpy(p + P_INERTIA * S, m->inertia, 3 * S * sizeof(double));
  memcpy(p + P_INV_INERTIA * S, m->inv_inertia, 3 * S * sizeof(double));
  memcpy(p + P_MASS * S, m->mass, S * sizeof(double));
  memcpy(p + P_INV_MASS * S, m->inv_mass, S * sizeof(double));
  if (m->weight) memcpy(p + P_WEIGHT * S, m->weight, S * sizeof(double));
  memcpy(p + P_CLAMP * S, m->clamp_bend, 3 * S * sizeof(double));
  d->radius_now = p + P_RADIUS * S; d->shear_now = p + P_SHEAR * S; d->bend_now = p + P_BEND * S;
  d->kappa0_now = p + P_KAPPA0 * S; d->inertia_now = p + P_INERTIA * S;
  d->inv_inertia_now = p + P_INV_INERTIA * S; d->mass_now = p + P_MASS * S;
  d->inv_mass_now = p + P_INV_MASS * S; d->weight_now = m->weight ? p + P_WEIGHT * S : NULL;
  return 1;
}

void sw_swell_data_free(swData *d) {
  free(d->swell_own);
  free(d->swell_g);
}

/* The bending stiffness the clamps read (model.c's clamp_bend), at the
 * current geometry. */
const double *sw_swell_clamp_bend(const swModel *m, const swData *d) {
  return d->swell_own ? d->swell_own + P_CLAMP * (size_t)m->stride : m->clamp_bend;
}

/* The swelling rods' geometry at time t: g = r(t)/r(0), then every slot of
 * each rod from its t = 0 value in the model (so round-off never builds up:
 * a rod back at g = 1 has the model's bits).  O(elements of those rods), no
 * allocation; once per time (a repeated t costs a comparison). */
void sw_swell_update(const swModel *m, swData *d, double t) {
  if (!m->nswell || t == d->swell_time) return;
  d->swell_time = t;
  const size_t S = (size_t)m->stride;
  double *p = d->swell_own;
  for (int k = 0; k < m->nswell; k++) {
    const int r = m->swell_rod[k], fl = m->swell_flags[k], n = m->rod_nelem[r];
    const int na = m->node_adr[r], ea = m->elem_adr[r], va = m->vor_adr[r];
    const swSignal *sig = &m->swell_sig[3 * k];
    const double g = sw_signal_eval(&sig[0], t) / sw_signal_eval(&sig[0], 0.0);
    d->swell_g[k] = g;
    const double g2 = g * g, g4 = g2 * g2;
    const double gm = fl & SW_SWELL_MASS_GROWS ? g2 : 1.0;   /* node masses  */
    const double gJ = fl & SW_SWELL_MASS_GROWS ? g4 : g2;    /* J^ = rho l^ I */
    const double c = sw_signal_eval(&sig[1], t);
    const double w = fl & SW_SWELL_TWIST_RADIUS ? 1.0 / g : sw_signal_eval(&sig[2], t);
    for (int e = ea; e < ea + n; e++) {
      p[P_RADIUS * S + e] = g * m->radius[e];
      for (int q = 0; q < 3; q++) {
        p[(P_SHEAR + q) * S + e] = g2 * SW_AT(m, m->shear_stiff, e, q);
        p[(P_INERTIA + q) * S + e] = gJ * SW_AT(m, m->inertia, e, q);
        p[(P_INV_INERTIA + q) * S + e] = SW_AT(m, m->inv_inertia, e, q) / gJ;
        p[(P_CLAMP + q) * S + e] = g4 * SW_AT(m, m->clamp_bend, e, q);
      }
    }
    for (int v = va; v < va + n - 1; v++) {
      for (int q = 0; q < 3; q++) p[(P_BEND + q) * S + v] = g4 * SW_AT(m, m->bend_stiff, v, q);
      p[P_KAPPA0 * S + v] = c * SW_AT(m, m->rest_kappa, v, 0);
      p[(P_KAPPA0 + 1) * S + v] = c * SW_AT(m, m->rest_kappa, v, 1);
      p[(P_KAPPA0 + 2) * S + v] = w * SW_AT(m, m->rest_kappa, v, 2);
    }
    for (int i = na; i <= na + n; i++) {
      p[P_MASS * S + i] = gm * m->mass[i];
      p[P_INV_MASS * S + i] = m->inv_mass[i] / gm;
      if (m->weight) p[P_WEIGHT * S + i] = gm * m->weight[i];
    }
  }
}

void sw_swell_range_over(const swModel *m, int k, double duration, double *lo, double *hi) {
  const swSignal *sig = &m->swell_sig[3 * k];
  const double r0 = sw_signal_eval(sig, 0.0);
  double a = 1.0, b = 1.0;
  const int samples = 4096;
  for (int q = 1; q <= samples; q++) {
    const double g = sw_signal_eval(sig, duration * q / samples) / r0;
    a = fmin(a, g);
    b = fmax(b, g);
  }
  *lo = a;
  *hi = b;
}
