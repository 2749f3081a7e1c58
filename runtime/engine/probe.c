/* probe.c — observables for /probes/NAME: the centre of mass of a set of
 * rods, its velocity, its mean velocity over a window, and one node.
 *
 * Design.  A probe is measured when a frame is written (io/output.c), never in
 * the step, so it costs nothing between frames.  The centre of mass is
 * weighted by the lumped node masses, X = sum m_i x_i / sum m_i (the same
 * masses the integrator uses, so X moves exactly as the total momentum
 * says), and its velocity likewise.  The mean velocity over a window w is
 *   V = (X(t) - X(t - w)) / w,
 * the displacement of the centre of mass over the last w seconds divided by
 * w — e.g. a snake's speed averaged over one undulation period, where the
 * centre of mass's sideways swing cancels.  X(t - w) comes from a ring of
 * SW_PROBE_RING samples (t, X) in swData, allocated with the state: a new
 * sample is kept when at least w / (SW_PROBE_RING - 1) has passed since the
 * last one, so the ring always spans the window, and X(t - w) is linearly
 * interpolated between the two samples around t - w (exact for uniform
 * motion; between frames the current state is the later point).  Until a
 * window has passed, V is the mean since the first frame; with w = 0 it is
 * the mean since the previous frame; on the very first frame, when there
 * is nothing to difference, it is the centre of mass's velocity.
 */
#include <stdlib.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

int sw_probe_data_new(const swModel *m, swData *d) {
  size_t P = (size_t)(m->nprobe ? m->nprobe : 1);
  d->probe_ring = calloc(P * SW_PROBE_RING * 4, sizeof(double));
  d->probe_head = calloc(P, sizeof(int));
  d->probe_count = calloc(P, sizeof(int));
  return d->probe_ring && d->probe_head && d->probe_count;
}

void sw_probe_data_free(swData *d) {
  free(d->probe_ring);
  free(d->probe_head);
  free(d->probe_count);
}

void sw_probe_reset(const swModel *m, swData *d) {
  for (int p = 0; p < m->nprobe; p++) d->probe_head[p] = d->probe_count[p] = 0;
}

/* Mass-weighted mean of the node positions (or velocities) of the rods. */
static void mass_mean(const swModel *m, const swProbeDesc *p, const double *field, double out[3]) {
  double sum[3] = {0, 0, 0}, mass = 0;
  for (int k = 0; k < p->nrods; k++) {
    const int r = p->rods[k], na = m->node_adr[r], nn = m->rod_nelem[r] + 1;
    for (int i = na; i < na + nn; i++) {
      for (int q = 0; q < 3; q++) sum[q] += m->mass[i] * SW_AT(m, field, i, q);
      mass += m->mass[i];
    }
  }
  sw_v3_scale(out, sum, 1.0 / mass);
}

/* Sample j (0 = oldest) of probe p's ring: time and centre of mass. */
static double *sample(const swData *d, int p, int j) {
  return d->probe_ring + 4 * ((size_t)p * SW_PROBE_RING + (size_t)((d->probe_head[p] + j) % SW_PROBE_RING));
}

/* (X(t) - X(t - w)) / w, or the fallbacks of the design note; keeps the
 * sample of this frame when it is due. */
static void mean_velocity(const swModel *m, swData *d, int p, double out[3]) {
  const swProbeDesc *pd = &m->probe[p];
  const double t = d->time, w = pd->window;
  double X[3];
  mass_mean(m, pd, d->x, X);
  int n = d->probe_count[p];
  if (n && sample(d, p, n - 1)[0] > t) n = d->probe_count[p] = 0; /* time went back */
  int older = n; /* samples strictly before t */
  while (older > 0 && !(sample(d, p, older - 1)[0] < t)) older--;
  if (older == 0) {
    mass_mean(m, pd, d->v, out);
  } else if (w > 0 && sample(d, p, 0)[0] <= t - w) {
    int j = older - 1; /* the newest sample at or before t - w */
    while (sample(d, p, j)[0] > t - w) j--;
    const double *a = sample(d, p, j), *b = j + 1 < older ? sample(d, p, j + 1) : NULL;
    const double tb = b ? b[0] : t, *Xb = b ? b + 1 : X;
    const double f = tb > a[0] ? (t - w - a[0]) / (tb - a[0]) : 0.0;
    for (int q = 0; q < 3; q++) out[q] = (X[q] - (a[1 + q] + f * (Xb[q] - a[1 + q]))) / w;
  } else {
    /* younger than the window: since the first frame; w = 0: since the last */
    const double *a = sample(d, p, w > 0 ? 0 : older - 1);
    for (int q = 0; q < 3; q++) out[q] = (X[q] - a[1 + q]) / (t - a[0]);
  }
  const double spacing = w / (SW_PROBE_RING - 1);
  if (n == 0 || t > sample(d, p, n - 1)[0] + spacing * (1 - 1e-9)) {
    double *slot;
    if (n < SW_PROBE_RING) {
      slot = sample(d, p, n);
      d->probe_count[p] = n + 1;
    } else {
      slot = sample(d, p, 0); /* the oldest gives way */
      d->probe_head[p] = (d->probe_head[p] + 1) % SW_PROBE_RING;
    }
    slot[0] = t;
    for (int q = 0; q < 3; q++) slot[1 + q] = X[q];
  }
}

void sw_probe_measure(const swModel *m, swData *d, int p, double out[3]) {
  const swProbeDesc *pd = &m->probe[p];
  switch (pd->kind) {
  case SW_PROBE_COM: mass_mean(m, pd, d->x, out); return;
  case SW_PROBE_COM_VELOCITY: mass_mean(m, pd, d->v, out); return;
  case SW_PROBE_MEAN_VELOCITY: mean_velocity(m, d, p, out); return;
  case SW_PROBE_NODE:
    sw_get3(m, d->x, m->node_adr[pd->rod] + pd->node, out);
    return;
  }
  out[0] = out[1] = out[2] = 0;
}

/* ---- Read at a held step (integrate.c, "Held steps") ----
 * Between held steps the nodes sit half a drift short of the whole step,
 * x_{n+1/2}, with the step's new velocities v_{n+1}; what the whole step
 * would show for a node of an elastic rod is the half drift's
 *   x_{n+1} = x_{n+1/2} + (h/2) v_{n+1}
 * (drift_nodes, drift.h: the same operation, rounded as it rounds;
 * nothing else of the half drift or of the step's end moves an elastic
 * node or its velocity).  So the centre of mass, its velocity and a node
 * of elastic rods are read there without making the whole step: the run
 * loop samples the objective's reductions so at every step instead of
 * saving, completing and restoring the state (the muscular snake's
 * max_over of its centre of mass's height: 10% of an evaluation). */
int sw_probe_held_ok(const swModel *m, int p) {
  const swProbeDesc *pd = &m->probe[p];
  if (pd->kind == SW_PROBE_MEAN_VELOCITY) return 0;
  const int nr = pd->kind == SW_PROBE_NODE ? 1 : pd->nrods;
  for (int k = 0; k < nr; k++) {
    const int r = pd->kind == SW_PROBE_NODE ? pd->rod : pd->rods[k];
    if (sw_rod_is_rigid(m, r) || m->node_adr[r] + m->rod_nelem[r] >= m->nslot_elastic) return 0;
  }
  return 1;
}

/* mass_mean of the positions half a drift on (the header's x_{n+1}). */
static void mass_mean_drifted(const swModel *m, const swData *d, const swProbeDesc *p, double hh,
                              double out[3]) {
  double sum[3] = {0, 0, 0}, mass = 0;
  for (int k = 0; k < p->nrods; k++) {
    const int r = p->rods[k], na = m->node_adr[r], nn = m->rod_nelem[r] + 1;
    for (int i = na; i < na + nn; i++) {
      for (int q = 0; q < 3; q++) {
        double x = SW_AT(m, d->x, i, q);
        x += hh * SW_AT(m, d->v, i, q);
        sum[q] += m->mass[i] * x;
      }
      mass += m->mass[i];
    }
  }
  sw_v3_scale(out, sum, 1.0 / mass);
}

void sw_probe_measure_held(const swModel *m, const swData *d, int p, double out[3]) {
  const swProbeDesc *pd = &m->probe[p];
  const double hh = 0.5 * m->dt;
  switch (pd->kind) {
  case SW_PROBE_COM: mass_mean_drifted(m, d, pd, hh, out); return;
  case SW_PROBE_COM_VELOCITY: mass_mean(m, pd, d->v, out); return;
  case SW_PROBE_NODE: {
    const int i = m->node_adr[pd->rod] + pd->node;
    for (int q = 0; q < 3; q++) {
      double x = SW_AT(m, d->x, i, q);
      x += hh * SW_AT(m, d->v, i, q);
      out[q] = x;
    }
    return;
  }
  case SW_PROBE_MEAN_VELOCITY: break; /* sw_probe_held_ok refuses it */
  }
  out[0] = out[1] = out[2] = 0;
}

const char *sw_probe_kind_name(swProbeKind kind) {
  switch (kind) {
  case SW_PROBE_COM: return "center_of_mass";
  case SW_PROBE_COM_VELOCITY: return "center_of_mass_velocity";
  case SW_PROBE_MEAN_VELOCITY: return "mean_velocity";
  case SW_PROBE_NODE: return "node_position";
  }
  return "probe";
}

const char *sw_probe_units(swProbeKind kind) {
  return kind == SW_PROBE_COM_VELOCITY || kind == SW_PROBE_MEAN_VELOCITY ? "m/s" : "m";
}
