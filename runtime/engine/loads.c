/* loads.c — time signals, and the external loads on rods: gravity, point
 * forces and couples with time profiles, and internal dissipation.
 *
 * Design.  sw_external_loads() fills d->ext_force (lab frame, per node) and
 * d->ext_torque (material frame, per element) and adds them into d->force and
 * d->torque, which rod.c has just filled with the internal loads.  Keeping the
 * external part separate lets the integrator account for the work it does
 * (the third column of /diagnostics/energy).  Linear dissipation lives here
 * because it is a load: f = -gamma v per unit length (Zhang et al. 2019,
 * "dissipation constant gamma", kg m^-1 s^-1) and a couple density
 * -gamma (I_k / A) w_k, so that translation and rotation decay at the same
 * rate gamma / (rho A).  The analytical variant is applied by integrate.c as
 * an exact exponential decay instead.
 */
#include <string.h>
#include <math.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

swSignal sw_signal_const(double value) {
  swSignal s;
  memset(&s, 0, sizeof s);
  s.kind = SW_SIG_CONST;
  s.a = value;
  return s;
}

swSignal sw_signal_ramp(double from, double to, double t0, double duration) {
  swSignal s = sw_signal_const(from);
  s.kind = SW_SIG_RAMP;
  s.b = to;
  s.t0 = t0;
  s.T = duration;
  return s;
}

swSignal sw_signal_sine(double mean, double amplitude, double freq_hz, double phase, double t0) {
  swSignal s = sw_signal_const(mean);
  s.kind = SW_SIG_SINE;
  s.b = amplitude;
  s.freq = freq_hz;
  s.phase = phase;
  s.t0 = t0;
  return s;
}

swSignal sw_signal_step(double before, double after, double t0) {
  swSignal s = sw_signal_const(before);
  s.kind = SW_SIG_STEP;
  s.b = after;
  s.t0 = t0;
  return s;
}

swSignal sw_signal_bspline(const double *c, int n, double t0, double duration) {
  swSignal s = sw_signal_const(n > 0 ? c[0] : 0.0);
  s.kind = SW_SIG_BSPLINE;
  s.t0 = t0;
  s.T = duration;
  s.npts = n;
  for (int k = 0; k < n && k < SW_SIGNAL_MAXPTS; k++) s.values[k] = c[k];
  return s;
}

swSignal sw_signal_func(swSignalFn fn, const void *ctx, double t0, double span) {
  swSignal s = sw_signal_const(1.0);
  s.kind = SW_SIG_FUNC;
  s.fn = fn;
  s.fn_ctx = ctx;
  s.t0 = t0;
  s.T = span;
  return s;
}

swSignal sw_signal_periodic(swSignal s, double period) {
  s.period = period;
  return s;
}

/* The clamped cubic B-spline with coefficients c[0..n) on the uniform knot
 * vector of [0, 1] (four-fold end knots, n - 4 interior knots at j / (n - 3)),
 * at u in [0, 1], by de Boor's algorithm (de Boor, A Practical Guide to
 * Splines, 1978, ch. X): no allocation, four coefficients touched. */
static double bspline_uniform(const double *c, int n, double u) {
  const int spans = n - 3;
  int i = (int)(u * spans); /* span [i, i+1) / spans, clamped to the last */
  if (i < 0) i = 0;
  if (i > spans - 1) i = spans - 1;
  double knot[6], dj[4]; /* knots t_{i+1..i+6} of the clamped vector, in spans */
  for (int k = 0; k < 6; k++) {
    int kk = i + k - 2; /* knot index relative to the first interior breakpoint */
    knot[k] = (kk < 0 ? 0 : kk > spans ? spans : kk) / (double)spans;
  }
  for (int k = 0; k < 4; k++) dj[k] = c[i + k];
  for (int r = 1; r <= 3; r++)
    for (int k = 3; k >= r; k--) {
      const double lo = knot[k - 1], hi = knot[k + 3 - r];
      const double a = hi > lo ? (u - lo) / (hi - lo) : 0.0;
      dj[k] = (1.0 - a) * dj[k - 1] + a * dj[k];
    }
  return dj[3];
}

double sw_signal_eval(const swSignal *s, double t) {
  if (s->period > 0 && t > s->t0) t = s->t0 + fmod(t - s->t0, s->period);
  switch (s->kind) {
  case SW_SIG_CONST:
    return s->a;
  case SW_SIG_RAMP:
    if (t <= s->t0) return s->a;
    if (s->T <= 0 || t >= s->t0 + s->T) return s->b;
    return s->a + (s->b - s->a) * (t - s->t0) / s->T;
  case SW_SIG_SINE:
    return s->a + s->b * sin(2.0 * SW_PI * s->freq * (t - s->t0) + s->phase);
  case SW_SIG_STEP:
    return t < s->t0 ? s->a : s->b;
  case SW_SIG_TABLE: {
    int n = s->npts;
    if (n <= 0) return 0.0;
    if (t <= s->times[0]) return s->values[0];
    if (t >= s->times[n - 1]) return s->values[n - 1];
    int lo = 0, hi = n - 1; /* bisection: times[lo] <= t < times[hi] */
    while (hi - lo > 1) {
      int mid = (lo + hi) / 2;
      if (s->times[mid] <= t) lo = mid; else hi = mid;
    }
    double f = (t - s->times[lo]) / (s->times[hi] - s->times[lo]);
    return s->values[lo] + f * (s->values[hi] - s->values[lo]);
  }
  case SW_SIG_BSPLINE:
    if (s->npts < 4) return s->npts > 0 ? s->values[0] : 0.0;
    if (t <= s->t0 || !(s->T > 0)) return s->values[0];
    if (t >= s->t0 + s->T) return s->values[s->npts - 1];
    return bspline_uniform(s->values, s->npts, (t - s->t0) / s->T);
  case SW_SIG_FUNC:
    return s->fn ? s->a * s->fn(t, s->fn_ctx) : 0.0;
  }
  return 0.0;
}

/* The values a signal takes over all t (its period changes none of them):
 * the ends of a ramp or a step, a sine's mean -+ its amplitude, a table's
 * extreme values.  A clamped B-spline stays inside the hull of its
 * coefficients but rarely touches it, so it is sampled, 64 points a knot
 * span, which finds its extremes to about 1e-4 of their spread. */
void sw_signal_range(const swSignal *s, double *lo, double *hi) {
  double a = s->a, b = s->b;
  switch (s->kind) {
  case SW_SIG_CONST:
    *lo = *hi = a;
    return;
  case SW_SIG_SINE:
    if (s->freq == 0) a = b = s->a + s->b * sin(s->phase);
    else { b = s->a + fabs(s->b); a = s->a - fabs(s->b); }
    break;
  case SW_SIG_TABLE:
  case SW_SIG_BSPLINE: {
    int n = s->npts;
    if (n <= 0) { *lo = *hi = 0.0; return; }
    a = b = s->values[0];
    if (s->kind == SW_SIG_TABLE || n < 4) {  /* the values themselves */
      for (int k = 1; k < n; k++) {
        a = fmin(a, s->values[k]);
        b = fmax(b, s->values[k]);
      }
      break;
    }
    int samples = 64 * (n - 3);              /* n - 3 knot spans */
    for (int k = 0; k <= samples; k++) {
      double v = bspline_uniform(s->values, n, (double)k / samples);
      a = fmin(a, v);
      b = fmax(b, v);
    }
    break;
  }
  case SW_SIG_FUNC: {   /* sampled: exact at the samples, not between them */
    const int samples = 4096;
    const double span = s->T > 0 ? s->T : 1.0;
    a = b = sw_signal_eval(s, s->t0);
    for (int k = 1; k <= samples; k++) {
      double v = sw_signal_eval(s, s->t0 + span * k / samples);
      a = fmin(a, v);
      b = fmax(b, v);
    }
    break;
  }
  case SW_SIG_RAMP:
  case SW_SIG_STEP:
    break;
  }
  *lo = fmin(a, b);
  *hi = fmax(a, b);
}

/* Gravity into ext_force and zero into ext_torque over slots [lo, hi) of the
 * planes (padding included, where both stay zero); the loads are scratch, at
 * i - so (internal.h, "Scratch windows").  Gravity acts on m->weight, the
 * mass but on weightless rods, when some rod is weightless. */
/* What gravity acts with over slots [lo, hi): the masses it weighs, the
 * slots under it, [lo, top) ([top, hi) not: the padding, or no gravity; two
 * loops rather than a condition per slot, vec.h, sw_select), and its
 * signal's factor now. */
typedef struct {
  const double *mass;
  int top;
  double scale;
} GravitySpan;

static GravitySpan gravity_span(const swModel *m, const swData *d, int lo, int hi) {
  GravitySpan g = {m->weight ? d->weight_now : d->mass_now,
                   m->has_gravity ? (hi < m->nslot ? hi : m->nslot) : lo,
                   m->gravity_signal.kind == SW_SIG_CONST ? m->gravity_signal.a
                                                          : sw_signal_eval(&m->gravity_signal, d->time)};
  if (g.top < lo) g.top = lo;
  return g;
}

static void base_loads(const swModel *m, swData *d, int lo, int hi, int so) {
  const size_t S = (size_t)m->stride;
  const GravitySpan gs = gravity_span(m, d, lo, hi);
  const double *restrict mass = gs.mass;
  const int top = gs.top;
  const double scale = gs.scale;
  for (int k = 0; k < 3; k++) {
    double *restrict ef = d->ext_force + k * S, *restrict et = d->ext_torque + k * S;
    const double g = m->gravity[k] * scale;
#pragma omp simd
    for (int i = lo; i < top; i++) {
      ef[i - so] = mass[i] * g;
      et[i - so] = 0.0;
    }
#pragma omp simd
    for (int i = top; i < hi; i++) {
      ef[i - so] = 0.0;
      et[i - so] = 0.0;
    }
  }
}

/* Point forces and couples of the scene on this thread's slots, in load
 * order (each by the owner of its slot, so the base loads of that slot are
 * already there). */
static void point_loads(const swModel *m, swData *d, int lo, int hi, int so) {
  for (int l = 0; l < m->nload; l++) {
    const swLoadDesc *ld = &m->load[l];
    const int slot = (ld->kind == SW_LOAD_FORCE ? m->node_adr[ld->rod] : m->elem_adr[ld->rod]) + ld->index;
    if (slot < lo || slot >= hi) continue;
    double g = sw_signal_eval(&ld->signal, d->time);
    if (ld->kind == SW_LOAD_FORCE) {
      int i = slot;
      for (int k = 0; k < 3; k++) SW_AT(m, d->ext_force, i - so, k) += g * ld->vec[k];
    } else {
      int e = slot;
      double tl[3] = {g * ld->vec[0], g * ld->vec[1], g * ld->vec[2]}, tm[3], Q[9];
      sw_getQ(m, d->Q, e, Q);
      sw_mat_vec(tm, Q, tl); /* couples act in the material frame */
      for (int k = 0; k < 3; k++) SW_AT(m, d->ext_torque, e - so, k) += tm[k];
    }
  }
}

/* Linear dissipation on the rods that have it (nodes, and elements but not
 * ghosts), then the external loads into the totals, slots [lo, hi). */
static void finish_loads(const swModel *m, swData *d, int lo, int hi, int so) {
  const size_t S = (size_t)m->stride;
  const double *restrict lin = m->damp_linear, *restrict ghost = m->elem_ghost;
  const double *restrict ng = m->node_gamma;
  for (int k = 0; k < 3; k++) {
    double *restrict ef = d->ext_force + k * S, *restrict et = d->ext_torque + k * S;
    double *restrict F = d->force + k * S, *restrict T = d->torque + k * S;
    const double *restrict v = d->v + k * S, *restrict w = d->omega + k * S;
    const double *restrict eg = m->elem_gamma + k * S;
    if (m->has_damping) {
#pragma omp simd
      for (int i = lo; i < hi; i++) {
        const int node = lin[i] != 0.0, elem = (lin[i] != 0.0) & (ghost[i] == 0.0);
        ef[i - so] = sw_select(node, ef[i - so] - ng[i] * v[i], ef[i - so]);
        et[i - so] = sw_select(elem, et[i - so] - eg[i] * w[i], et[i - so]);
      }
    }
#pragma omp simd
    for (int i = lo; i < hi; i++) {
      F[i - so] += ef[i - so];
      T[i - so] += et[i - so];
    }
  }
}

/* Gravity, the point loads, linear damping and the sum into the totals, on
 * this thread's slots: no slot needs another thread's, so no barrier. */
void sw_external_loads(const swModel *m, swData *d) {
  int lo, hi;
  sw_owned_slots(m, d, &lo, &hi); /* [0, stride): padding and rigid slots too */
  sw_external_loads_slots(m, d, lo, hi, 0);
}

/* base_loads and finish_loads in one pass, for models without point
 * loads: each slot gets the same operations in the same order (ext_force =
 * m g, ext_torque = 0, less the linear damping where it acts, then each
 * added into the totals), one loop instead of three for each component:
 * the wing's 20,000 slots are read and written once a step, not three
 * times.  damped: the model has linear damping (a constant of the call, so
 * each specialisation's loop is as plain as the other). */
static inline __attribute__((always_inline)) void
one_pass_loads(const swModel *m, swData *d, int lo, int hi, int so, int damped) {
  const size_t S = (size_t)m->stride;
  const GravitySpan gs = gravity_span(m, d, lo, hi);
  const double *restrict mass = gs.mass;
  const int top = gs.top;
  const double scale = gs.scale;
  const double *restrict lin = m->damp_linear, *restrict ghost = m->elem_ghost;
  const double *restrict ng = m->node_gamma;
  for (int k = 0; k < 3; k++) {
    double *restrict ef = d->ext_force + k * S, *restrict et = d->ext_torque + k * S;
    double *restrict F = d->force + k * S, *restrict T = d->torque + k * S;
    const double *restrict v = d->v + k * S, *restrict w = d->omega + k * S;
    const double *restrict eg = m->elem_gamma + k * S;
    const double g = m->gravity[k] * scale;
    /* gravity on [lo, top) (its elastic slots), none on the rest */
#define SW_ONE_PASS(first, last, weight)                                                       \
  _Pragma("omp simd") for (int i = (first); i < (last); i++) {                                 \
    double f = (weight), t = 0.0;                                                                \
    if (damped) { /* finish_loads' damping */                                                    \
      const int node = lin[i] != 0.0, elem = (lin[i] != 0.0) & (ghost[i] == 0.0);                \
      f = sw_select(node, f - ng[i] * v[i], f);                                                  \
      t = sw_select(elem, t - eg[i] * w[i], t);                                                  \
    }                                                                                            \
    ef[i - so] = f, et[i - so] = t;                                                              \
    F[i - so] += f, T[i - so] += t;                                                              \
  }
    SW_ONE_PASS(lo, top, mass[i] * g)
    SW_ONE_PASS(top, hi, 0.0)
#undef SW_ONE_PASS
  }
}

void sw_external_loads_slots(const swModel *m, swData *d, int lo, int hi, int so) {
  if (!m->nload) {
    if (m->has_damping) one_pass_loads(m, d, lo, hi, so, 1);
    else one_pass_loads(m, d, lo, hi, so, 0);
    return;
  }
  base_loads(m, d, lo, hi, so);
  if (m->nload) point_loads(m, d, lo, hi, so); /* onto the base loads, before the damping reads them */
  finish_loads(m, d, lo, hi, so);
}
