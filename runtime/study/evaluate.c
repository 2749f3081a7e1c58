/* evaluate.c — a model's objective: one evaluation in process (sw_evaluate),
 * the objective of a finished run (sw_objective), and the model a program
 * compiles to at given params (sw_program_compile), which the command line
 * (cli.c) uses too.
 *
 * Design.  A study runs one program thousands of times with other params;
 * each evaluation builds the scene from P, compiles it with the step the
 * command line would take (sw_program_compile: the one place that choice is
 * made), runs it silently with no output file, and reads the objective from
 * the reductions its run sampled.  The reductions (at, mean_over, max_over,
 * min_over) are entries of the model's expectations with `reduce` set, so
 * expect.c samples them at the steps they name and the run loop ends its
 * calls of the step there, held (integrate.c, "Held steps"), so that the
 * steps are those of a plain run of the same params with any frames and
 * the objective it finds is, bit for bit, the one that run prints.  The
 * generated program supplies the arithmetic: objective(P, R, &value,
 * &penalty) over the params and the reductions' values.  The score (larger
 * is better) is value - penalty for maximize and -(value + penalty) for
 * minimize.  Nothing here prints or exits: a failure is a status and a
 * message, and its score is -INFINITY, last in any ranking, never the end of
 * a study.  Everything is allocated before the run and freed after it. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "engine/internal.h"

swModel *sw_program_compile(const swProgram *p, const double *P, double dt, int integrator,
                            double every, double *stable, int *status, char *err, size_t errlen) {
  *status = SW_EMODEL;
  *stable = 0;
  if (errlen) err[0] = '\0';
  if (!p || !p->build) {
    snprintf(err, errlen, "the program has no scene to build");
    return NULL;
  }
  swSpec *s = sw_spec_new();
  if (!s) {
    snprintf(err, errlen, "out of memory");
    return NULL;
  }
  int built = p->build(s, P, err, errlen);
  if (built != SW_OK) {
    if (errlen && !err[0]) snprintf(err, errlen, "the scene could not be built");
    sw_spec_free(s);
    *status = built > 0 ? built : SW_EMODEL;
    return NULL;
  }
  if (integrator >= 0) sw_spec_set_integrator(s, (swIntegrator)integrator);
  if (!(dt > 0)) dt = p->dt;
  if (dt > 0) sw_spec_set_dt(s, dt);
  swModel *m = sw_compile(s, err, errlen);
  if (m) {
    *stable = sw_stable_dt(m);
    if (!(dt > 0)) {
      sw_model_free(m);
      m = NULL;
      if (!(*stable > 0) || !isfinite(*stable)) {
        snprintf(err, errlen, "the scene has no finite stable time step estimate; give one "
                 "with --dt");
      } else {
        /* half the estimate, shortened so that a whole number of steps
         * spans the frame interval: frames then fall on the times asked for */
        double auto_dt = 0.5 * *stable;
        if (every > 0 && isfinite(every)) {
          double k = ceil(every / auto_dt - 1e-9);
          if (k >= 1 && k < 1e12) auto_dt = every / k;
        }
        sw_spec_set_dt(s, auto_dt);
        m = sw_compile(s, err, errlen);
      }
    }
  }
  sw_spec_free(s);
  if (m) *status = SW_OK;
  return m;
}

/* A message into why[len] and the status back. */
static int failure(char *why, size_t len, int status, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int failure(char *why, size_t len, int status, const char *fmt, ...) {
  if (why && len) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, len, fmt, ap);
    va_end(ap);
  }
  return status;
}

int sw_objective(const swProgram *p, const swModel *m, const swExpectRun *x, const double *P,
                 double *objective, double *penalty, double *score, char *why, size_t len) {
  *objective = *penalty = NAN;
  *score = -INFINITY;
  if (!p || !p->sense || !p->objective)
    return failure(why, len, SW_EUSAGE, "the model has no objective (maximize or minimize)");
  int n = 0;
  for (int k = 0; k < m->nexpect; k++) n += m->expect[k].reduce != SW_REDUCE_NONE;
  if (n != p->nreduce)
    return failure(why, len, SW_EMODEL, "the model samples %d reductions, its objective reads %d",
                   n, p->nreduce);
  double *R = malloc((size_t)(n > 0 ? n : 1) * sizeof *R);
  if (!R) return failure(why, len, SW_EMODEL, "out of memory");
  int rc = sw_expect_reduced(m, x, R, why, len);
  if (rc == SW_OK) p->objective(P, R, objective, penalty);
  free(R);
  if (rc != SW_OK) return rc;
  if (!isfinite(*objective) || !isfinite(*penalty))
    return failure(why, len, SW_EMODEL, "the objective (%g) or the penalty (%g) is not a "
                   "finite number", *objective, *penalty);
  *score = p->sense > 0 ? *objective - *penalty : -(*objective + *penalty);
  return SW_OK;
}

/* The result of an evaluation that failed before its objective. */
static int eval_failed(swEvalResult *r, int status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int eval_failed(swEvalResult *r, int status, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(r->message, sizeof r->message, fmt, ap);
  va_end(ap);
  r->status = status;
  r->objective = r->penalty = NAN;
  r->score = -INFINITY;
  return status;
}

/* The run of a compiled model: its steps, then its objective. */
static int evaluate_model(const swProgram *p, const swModel *m, const double *P,
                          double duration, swEvalResult *r) {
  long nsteps;
  char why[256];
  if (sw_step_count(duration, m->dt, &nsteps, why, sizeof why) != SW_OK)
    return eval_failed(r, SW_EUSAGE, "%s", why);
  if (sw_expect_reduced_last(m) > nsteps)
    return eval_failed(r, SW_EUSAGE, "the objective reads the run up to t = %.6g s, but it "
                       "lasts %.6g s", (double)sw_expect_reduced_last(m) * m->dt, duration);
  swData *d = sw_data_new(m);
  swExpectRun *x = sw_expect_run_new(m);
  if (!d || !x) {
    sw_expect_run_free(x);
    sw_data_free(d);
    return eval_failed(r, SW_EMODEL, "out of memory");
  }
  sw_set_threads(d, 1);
  swRunOptions ro = {.duration = duration, .every = p->every, .quiet = 1, .silent = 1,
                     .expect = x};
  int rc = sw_run(m, d, NULL, &ro);
  if (rc == SW_OK) {
    rc = sw_objective(p, m, x, P, &r->objective, &r->penalty, &r->score, r->message,
                      sizeof r->message);
    r->status = rc;
  } else if (rc == SW_EUNSTABLE) {
    eval_failed(r, rc, "%s", d->error[0] ? d->error : "the simulation became unstable");
  } else if (rc == SW_EINTERRUPT) {
    eval_failed(r, rc, "interrupted at t = %.9g s", d->time);
  } else {
    eval_failed(r, rc, "the run failed (code %d)", rc);
  }
  r->sim_time = d->time;
  r->steps = d->step;
  sw_expect_run_free(x);
  sw_data_free(d);
  return rc;
}

int sw_evaluate(const swProgram *p, const double *P, double duration, double dt, int integrator,
                swEvalResult *r) {
  memset(r, 0, sizeof *r);
  if (!p || p->nparam < 0 || (p->nparam > 0 && !p->param))
    return eval_failed(r, SW_EUSAGE, "no program");
  if (!p->sense || !p->objective)
    return eval_failed(r, SW_EUSAGE, "the model '%s' has no objective (maximize or minimize)",
                       p->name ? p->name : "");
  if (integrator < -1 || integrator > SW_IMEX)
    return eval_failed(r, SW_EUSAGE, "unknown integrator %d", integrator);
  double *values = malloc(((size_t)p->nparam + 1) * sizeof *values);
  if (!values) return eval_failed(r, SW_EMODEL, "out of memory");
  for (int i = 0; i < p->nparam; i++) values[i] = P ? P[i] : p->param[i].value;
  for (int i = 0; i < p->nparam; i++)
    if (!isfinite(values[i])) {
      eval_failed(r, SW_EMODEL, "param %s = %g is not a finite number", p->param[i].name,
                  values[i]);
      free(values);
      return r->status;
    }
  double stable;
  int status;
  char err[512];
  swModel *m = sw_program_compile(p, values, dt, integrator, p->every, &stable, &status, err,
                                  sizeof err);
  if (!m) {
    free(values);
    return eval_failed(r, status, "%s", err);
  }
  evaluate_model(p, m, values, duration > 0 ? duration : p->duration, r);
  r->dt = m->dt;
  sw_model_free(m);
  free(values);
  return r->status;
}
