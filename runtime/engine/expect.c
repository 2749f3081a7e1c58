/* expect.c — expectations: a model as its own golden test.
 *
 * Design.  A model states what its run must show (`expect angle(elbow) at
 * 0.5 s in (-155 deg, -150 deg);`); the compiler turns each into a
 * swExpectDesc and the simulator checks it while it runs.  An expectation at
 * a time is sampled at the step nearest it, k = round(t / dt), the same
 * counting run.c uses for frames, so it does not depend on the output's
 * `every`; one over a window [t0, t1] is sampled at every step whose time is
 * in it, and keeps the smallest and largest value.  run.c ends its chunks
 * of steps at those steps (sw_expect_next) and reads the whole step between
 * held ones (integrate.c, "Held steps"), so sampling costs a quantity
 * evaluation and a half drift per due step and leaves the trajectory's bits
 * as they are without it (until 2026-11 it moved them by round-off: the
 * pendulum's positions by 7e-15 m after 1.2 s, a frog's toe height by 2x;
 * tests/lang/test_invariance.sh).  The record of a run
 * (swExpectRun) is allocated before the run, never in a step.  The report
 * lists every expectation: passed with the value seen, failed with the
 * value and the bounds, or not reached when the run ended before its time
 * (a shortened --duration); only failures count.
 *
 * Quantities are read as the output reads them (io/output_datasets.c): joints through
 * sw_joint_measure, muscles through muscle.c's table (their filaments' last
 * force evaluation),
 * probes through sw_probe_measure.  A mean-velocity probe keeps a ring of
 * samples taken at frames, so it cannot also be sampled at other steps; the
 * compiler and sw_expect_setup refuse it.
 *
 * The reductions of a model's objective (maximize, minimize, penalty) are
 * entries of the same list with `reduce` set: sampled exactly as
 * expectations are, at the same steps, but never checked nor reported.
 * Besides the extremes, the record keeps the last value and the trapezoidal
 * sum of the samples, sum_k (v_{k-1} + v_k) / 2, so that a window's time
 * average is that sum over the number of steps between its first and last
 * sample (second order in dt; the plain mean of the samples would weigh
 * the two ends by a whole step each, first order).  sw_expect_reduced turns
 * the record into the values evaluate.c hands the objective. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "internal.h"

struct swExpectRun {
  int n;
  long *count;        /* samples taken                          */
  long *last;         /* step of the last sample                */
  double *min, *max;  /* over the samples                       */
  double *latest;     /* the last sample's value                */
  double *trapezoid;  /* sum of (previous + value) / 2 over the samples after the first */
};

void sw_expect_desc_init(swExpectDesc *e) {
  memset(e, 0, sizeof *e);
  e->text = "expect";
  e->where = "";
  e->scale = 1.0;
  e->unit = "";
}

static char *copy(const char *s) { return strdup(s ? s : ""); }

static void desc_free(swExpectDesc *e) {
  free((char *)e->text);
  free((char *)e->where);
  free((char *)e->unit);
}

int sw_spec_add_expect(swSpec *s, const swExpectDesc *e) {
  if (!s || !e) return -1;
  swExpectList *l = sw_spec_expects(s);
  if (!sw_grow((void **)&l->item, &l->cap, l->n, sizeof *l->item)) return -1;
  swExpectDesc c = *e;
  c.text = copy(e->text);
  c.where = copy(e->where);
  c.unit = copy(e->unit);
  if (!c.text || !c.where || !c.unit) {
    desc_free(&c);
    return -1;
  }
  l->item[l->n] = c;
  return l->n++;
}

void sw_expect_list_free(swExpectList *l) {
  for (int k = 0; k < l->n; k++) desc_free(&l->item[k]);
  free(l->item);
  l->item = NULL;
  l->n = l->cap = 0;
}

/* The checks that need the model: what the quantity refers to exists. */
static int check(const swModel *m, const swExpectDesc *e, char *err, size_t errlen) {
  const char *t = e->text;
  int count = -1;
  switch (e->quantity) {
  case SW_EXPECT_JOINT_ANGLE:
  case SW_EXPECT_JOINT_FORCE: count = m->njoint; break;
  case SW_EXPECT_MUSCLE_FORCE:
  case SW_EXPECT_MUSCLE_STRETCH: count = m->nmuscle; break;
  case SW_EXPECT_PROBE: count = m->nprobe; break;
  default: return sw_fail(err, errlen, "%s: unknown quantity %d", t, (int)e->quantity);
  }
  if (e->index < 0 || e->index >= count)
    return sw_fail(err, errlen, "%s: no such joint, muscle or probe (index %d)", t, e->index);
  if (e->quantity == SW_EXPECT_PROBE) {
    if (e->component < 0 || e->component > 3)
      return sw_fail(err, errlen, "%s: probe component %d is not 0-3", t, e->component);
    if (m->probe[e->index].kind == SW_PROBE_MEAN_VELOCITY)
      return sw_fail(err, errlen, "%s: a mean-velocity probe is sampled at frames only and "
                     "cannot be expected at other steps", t);
  }
  if (!(e->t0 >= 0) || !isfinite(e->t0) || (e->window && !(e->t1 >= e->t0 && isfinite(e->t1))))
    return sw_fail(err, errlen, "%s: time %g s (window end %g s) is not a time of the run", t,
                   e->t0, e->t1);
  if (e->reduce < SW_REDUCE_NONE || e->reduce > SW_REDUCE_MIN)
    return sw_fail(err, errlen, "%s: unknown reduction %d", t, e->reduce);
  if ((e->reduce == SW_REDUCE_AT && e->window) ||
      (e->reduce > SW_REDUCE_AT && !e->window))
    return sw_fail(err, errlen, "%s: at() reads one time, the others a window", t);
  if (!(e->lo <= e->hi))
    return sw_fail(err, errlen, "%s: lower bound %g above upper bound %g", t, e->lo, e->hi);
  if (!(e->scale > 0) || !isfinite(e->scale))
    return sw_fail(err, errlen, "%s: report scale %g is not positive", t, e->scale);
  return 1;
}

int sw_expect_setup(swModel *m, const swExpectList *l, char *err, size_t errlen) {
  m->nexpect = 0;
  m->expect = NULL;
  if (!l->n) return 1;
  for (int k = 0; k < l->n; k++)
    if (!check(m, &l->item[k], err, errlen)) return 0;
  m->expect = calloc((size_t)l->n, sizeof *m->expect);
  if (!m->expect) return sw_fail(err, errlen, "out of memory");
  for (int k = 0; k < l->n; k++) {
    swExpectDesc c = l->item[k];
    c.text = copy(c.text);
    c.where = copy(c.where);
    c.unit = copy(c.unit);
    m->expect[k] = c;
    m->nexpect = k + 1; /* freed by sw_expect_free from here on */
    if (!c.text || !c.where || !c.unit) return sw_fail(err, errlen, "out of memory");
  }
  return 1;
}

void sw_expect_free(swModel *m) {
  for (int k = 0; k < m->nexpect; k++) desc_free(&m->expect[k]);
  free(m->expect);
  m->expect = NULL;
  m->nexpect = 0;
}

/* The steps an expectation samples: [first, last]. */
static void steps_of(const swModel *m, const swExpectDesc *e, long *first, long *last) {
  if (!e->window) {
    *first = *last = lround(e->t0 / m->dt);
    return;
  }
  *first = (long)ceil(e->t0 / m->dt - 1e-9);
  *last = (long)floor(e->t1 / m->dt + 1e-9);
}

long sw_expect_next(const swModel *m, long step) {
  long next = LONG_MAX;
  for (int k = 0; k < m->nexpect; k++) {
    long first, last;
    steps_of(m, &m->expect[k], &first, &last);
    if (last <= step) continue;
    long due = first > step ? first : step + 1;
    if (due < next) next = due;
  }
  return next;
}

/* ---- quantities ---- */

/* A probe's component, or its size. */
static double probe_value(const swExpectDesc *e, const double row[3]) {
  if (e->component < 3) return row[e->component];
  return sqrt(row[0] * row[0] + row[1] * row[1] + row[2] * row[2]);
}

static double quantity(const swModel *m, swData *d, const swExpectDesc *e) {
  switch (e->quantity) {
  case SW_EXPECT_JOINT_ANGLE:
    sw_joint_measure(m, d, e->index);
    return d->joint_angle[e->index];
  case SW_EXPECT_JOINT_FORCE: {
    sw_joint_measure(m, d, e->index);
    const double *f = d->joint_force + 3 * (size_t)e->index;
    return sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  }
  case SW_EXPECT_MUSCLE_FORCE: return sw_muscle_ops(m)->force(m, d, e->index);
  case SW_EXPECT_MUSCLE_STRETCH: return sw_muscle_ops(m)->stretch(m, d, e->index);
  case SW_EXPECT_PROBE: {
    double row[3];
    sw_probe_measure(m, d, e->index, row);
    return probe_value(e, row);
  }
  }
  return NAN;
}

/* Whether every entry can be read at a held step (probe.c, "Read at a held
 * step"): probes of positions and velocities of elastic rods only. */
int sw_expect_held_ok(const swModel *m) {
  for (int k = 0; k < m->nexpect; k++)
    if (m->expect[k].quantity != SW_EXPECT_PROBE || !sw_probe_held_ok(m, m->expect[k].index))
      return 0;
  return m->nexpect > 0;
}

/* The entries due at d->step sampled: from the whole state, or (held) from
 * the held one, each probe as the whole step would show it. */
static void sample(const swModel *m, swData *d, swExpectRun *r, int held) {
  if (!r) return;
  for (int k = 0; k < m->nexpect; k++) {
    long first, last;
    steps_of(m, &m->expect[k], &first, &last);
    if (d->step < first || d->step > last) continue;
    double v, row[3];
    if (held) {
      sw_probe_measure_held(m, d, m->expect[k].index, row);
      v = probe_value(&m->expect[k], row);
    } else {
      v = quantity(m, d, &m->expect[k]);
    }
    if (!r->count[k] || !(v >= r->min[k])) r->min[k] = v; /* a NaN sticks */
    if (!r->count[k] || !(v <= r->max[k])) r->max[k] = v;
    if (r->count[k]) r->trapezoid[k] += 0.5 * (r->latest[k] + v);
    r->latest[k] = v;
    r->count[k]++;
    r->last[k] = d->step;
  }
}

void sw_expect_sample(const swModel *m, swData *d, swExpectRun *r) { sample(m, d, r, 0); }
void sw_expect_sample_held(const swModel *m, swData *d, swExpectRun *r) { sample(m, d, r, 1); }

/* ---- the record of a run and its report ---- */

swExpectRun *sw_expect_run_new(const swModel *m) {
  swExpectRun *r = calloc(1, sizeof *r);
  if (!r) return NULL;
  const size_t n = m->nexpect ? (size_t)m->nexpect : 1;
  r->n = m->nexpect;
  r->count = calloc(n, sizeof *r->count);
  r->last = calloc(n, sizeof *r->last);
  r->min = calloc(n, sizeof *r->min);
  r->max = calloc(n, sizeof *r->max);
  r->latest = calloc(n, sizeof *r->latest);
  r->trapezoid = calloc(n, sizeof *r->trapezoid);
  if (!r->count || !r->last || !r->min || !r->max || !r->latest || !r->trapezoid) {
    sw_expect_run_free(r);
    return NULL;
  }
  return r;
}

void sw_expect_run_save(const swModel *m, const swExpectRun *r, double *out) {
  for (int k = 0; k < m->nexpect; k++, out += SW_EXPECT_SAVED) {
    out[0] = r ? (double)r->count[k] : 0;
    out[1] = r ? (double)r->last[k] : 0;
    out[2] = r ? r->min[k] : 0;
    out[3] = r ? r->max[k] : 0;
    out[4] = r ? r->latest[k] : 0;
    out[5] = r ? r->trapezoid[k] : 0;
  }
}

void sw_expect_run_load(const swModel *m, swExpectRun *r, const double *in) {
  if (!r) return;
  for (int k = 0; k < m->nexpect && k < r->n; k++, in += SW_EXPECT_SAVED) {
    r->count[k] = (long)in[0];
    r->last[k] = (long)in[1];
    r->min[k] = in[2];
    r->max[k] = in[3];
    r->latest[k] = in[4];
    r->trapezoid[k] = in[5];
  }
}

int sw_expect_reduced(const swModel *m, const swExpectRun *r, double *R, char *why, size_t len) {
  int n = 0;
  for (int k = 0; k < m->nexpect; k++) {
    const swExpectDesc *e = &m->expect[k];
    if (!e->reduce) continue;
    long first, last;
    steps_of(m, e, &first, &last);
    R[n] = NAN;
    if (first > last) {
      if (why) snprintf(why, len, "%s: no step of dt = %g s falls in its window", e->text, m->dt);
      return SW_EUSAGE;
    }
    if (!r || !r->count[k] || r->last[k] != last) {
      if (why) snprintf(why, len, "%s: the run ended before t = %.6g s", e->text,
                        e->window ? e->t1 : e->t0);
      return SW_EUSAGE;
    }
    switch (e->reduce) {
    case SW_REDUCE_AT: R[n] = r->latest[k]; break;
    case SW_REDUCE_MEAN:
      R[n] = r->count[k] > 1 ? r->trapezoid[k] / (double)(r->count[k] - 1) : r->latest[k];
      break;
    case SW_REDUCE_MAX: R[n] = r->max[k]; break;
    default: R[n] = r->min[k]; break;
    }
    n++;
  }
  return SW_OK;
}

long sw_expect_reduced_last(const swModel *m) {
  long latest = 0;
  for (int k = 0; k < m->nexpect; k++) {
    long first, last;
    steps_of(m, &m->expect[k], &first, &last);
    if (m->expect[k].reduce && last > latest) latest = last;
  }
  return latest;
}

void sw_expect_run_free(swExpectRun *r) {
  if (!r) return;
  free(r->count);
  free(r->last);
  free(r->min);
  free(r->max);
  free(r->latest);
  free(r->trapezoid);
  free(r);
}

/* "-152.31 deg" */
static void shown(char *buf, size_t len, const swExpectDesc *e, double v) {
  snprintf(buf, len, "%.6g%s%s", v / e->scale, e->unit[0] ? " " : "", e->unit);
}

int sw_expect_report(const swModel *m, const swExpectRun *r, FILE *f, const char *prog,
                     int quiet) {
  int checks = 0;
  for (int k = 0; k < m->nexpect; k++) checks += !m->expect[k].reduce;
  if (!checks || !r) return 0;
  int failed = 0, passed = 0, missed = 0;
  for (int k = 0; k < m->nexpect; k++) {
    const swExpectDesc *e = &m->expect[k];
    if (e->reduce) continue;   /* the objective's: evaluate.c */
    char lo[64], hi[64], a[64], b[64];
    shown(lo, sizeof lo, e, e->lo);
    shown(hi, sizeof hi, e, e->hi);
    shown(a, sizeof a, e, r->min[k]);
    shown(b, sizeof b, e, r->max[k]);
    const char *verdict;
    long first, last;
    steps_of(m, e, &first, &last);
    const int whole = r->count[k] && r->last[k] == last;
    const int inside = !r->count[k] || (r->min[k] >= e->lo && r->max[k] <= e->hi);
    if (r->count[k] && !inside) { /* failed, even if the window was cut short */
      verdict = "FAILED";
      failed++;
    } else if (!whole) {
      verdict = "not reached";
      missed++;
    } else {
      verdict = "passed";
      passed++;
    }
    if (quiet && strcmp(verdict, "FAILED")) continue;
    fprintf(f, "%s: %s: %s%s%s\n", prog, verdict, e->text, e->where[0] ? "  # " : "", e->where);
    if (!whole && inside) {
      fprintf(f, "    the run ended before t = %.6g s%s\n", e->t1,
              r->count[k] ? ", within the window" : "");
    } else if (!e->window) {
      fprintf(f, "    value %s, expected in [%s, %s]\n", a, lo, hi);
    } else {
      fprintf(f, "    from %s to %s over %ld steps, expected in [%s, %s]\n", a, b, r->count[k],
              lo, hi);
    }
  }
  if (quiet && !failed) return 0;
  fprintf(f, "%s: expectations: %d passed, %d failed%s", prog, passed, failed,
          missed ? "" : "\n");
  if (missed) fprintf(f, ", %d not reached\n", missed);
  fflush(f);
  return failed;
}
