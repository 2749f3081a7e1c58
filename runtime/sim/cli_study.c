/* cli_study.c — SIM --sweep, --optimize and --resume: the command line's side
 * of a study (study.c runs it); and --replay, one design of a study run again
 * as a run (cli.c runs it).
 *
 * Design.  cli_options.c reads the options; this file turns them and the model's
 * ranged params into swStudyOptions, and each evaluation into a run of the
 * model in this process (sw_evaluate: built from the design's params,
 * compiled, run for --duration without output, its objective sampled).  The
 * params a study varies are those with a range that --set does not fix; the
 * others keep their values.  CMA-ES starts at the params' values, or with
 * --start at another study's best design or a given value.  What an
 * evaluation depends on (the time step, duration and integrator, every
 * param's start value, the model's hash and the study's settings) is
 * recorded in the study's file, and --resume takes it all from there: a
 * setting given again must agree with the file's (but an optimisation's
 * --budget, which may grow), so a resumed study is the one that was
 * interrupted.  --replay takes the same record of the study, and one
 * evaluation's params in SI, bit for bit (/evaluations/params_si), so that
 * the run cli.c makes of them steps as that evaluation did and finds its
 * objective to the bit.  The study's report rechecks its RECHECK_BEST best
 * designs at dt/2 (study_recheck.c) unless --no-recheck: the evaluation is
 * then handed the design's step halved as a --dt, so that a run of the
 * design given that --dt reproduces the recheck's objective to the bit. */
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sinew.h"
#include "study/study.h"

#define RECHECK_BEST 3   /* the best designs a study rechecks at dt/2 (--help says 3) */

static int say(const swStudyCall *c, int rc, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int say(const swStudyCall *c, int rc, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "%s: ", c->prog);
  vfprintf(stderr, fmt, ap);
  fprintf(stderr, "\n");
  va_end(ap);
  return rc;
}

/* The step the study's evaluation of design P takes: --dt, else the
 * model's, else the one sw_program_compile chooses for P (half its stable
 * estimate, shortened to divide the frame interval); 0 when P gives no
 * scene. */
static double study_dt(const swStudyCall *c, const double *P) {
  if (c->dt_given) return c->dt;
  double stable;
  int status;
  char err[256];
  swModel *m = sw_program_compile(c->p, P, 0, c->integrator, c->p->every, &stable, &status, err,
                                  sizeof err);
  double dt = m ? m->dt : 0;
  sw_model_free(m);
  return dt;
}

/* One evaluation: the model run with the design's params, at the study's
 * step times dt_scale (the recheck at dt/2: the very step a run given
 * --dt with that value takes, so that the two agree to the bit). */
static void eval_model(void *ctx, const double *P, double dt_scale, swStudyEval *r) {
  const swStudyCall *c = ctx;
  swEvalResult e;
  double dt = c->dt_given ? c->dt : 0;
  if (dt_scale != 1 && !((dt = study_dt(c, P) * dt_scale) > 0)) {
    r->status = SW_EVAL_INVALID;
    r->objective = r->penalty = NAN;
    r->score = -INFINITY;
    snprintf(r->message, sizeof r->message, "the design gives no scene to find its step in");
    return;
  }
  int rc = sw_evaluate(c->p, P, c->duration, dt, c->integrator, &e);
  r->dt = e.dt;
  r->status = rc == SW_OK ? SW_EVAL_OK : rc == SW_EUNSTABLE ? SW_EVAL_UNSTABLE
              : rc == SW_EMODEL ? SW_EVAL_INVALID : SW_EVAL_FAILED;
  r->interrupted = rc == SW_EINTERRUPT;
  r->objective = e.objective;
  r->penalty = e.penalty;
  r->score = rc == SW_OK ? e.score : -INFINITY;
  r->sim_time = e.sim_time;
  snprintf(r->message, sizeof r->message, "%s", e.message);
}

/* "duration=...;dt=...;integrator=..." of this command line */
static void run_settings(const swStudyCall *c, char *buf, size_t len) {
  snprintf(buf, len, "duration=%.17g;dt=%.17g;integrator=%d", c->duration,
           c->dt_given ? c->dt : 0.0, c->integrator);
}

/* The settings of the study file `path` (for --resume or --replay: `opt`)
 * into s: a study of this model, else SW_EIO. */
static int read_settings(const swStudyCall *c, const char *opt, const char *path,
                         swStudySettings *s) {
  const swProgram *p = c->p;
  char err[512];
  if (access(path, R_OK) != 0)
    return say(c, SW_EIO, "%s: cannot read '%s': %s", opt, path, strerror(errno));
  if (sw_study_file_settings(path, s, err, sizeof err) != SW_OK)
    return say(c, SW_EIO, "%s: %s", opt, err);
  if (strcmp(s->model_sha256, p->sha256 ? p->sha256 : ""))
    return say(c, SW_EIO, "%s: %s is a study of another model (model_sha256 %.12s..., this "
               "model's %.12s...)", opt, path, s->model_sha256, p->sha256 ? p->sha256 : "");
  return SW_OK;
}

/* The run of each evaluation (the file's run_settings) into c, checked
 * against --duration, --dt and --integrator, which must agree or be left
 * out. */
static int take_run_settings(swStudyCall *c, const char *opt, const char *path,
                             const swStudySettings *s) {
  double duration = 0, dt = 0;
  int integrator = -1;
  if (sscanf(s->run_settings, "duration=%lf;dt=%lf;integrator=%d", &duration, &dt,
             &integrator) != 3)
    return say(c, SW_EIO, "%s: %s: unreadable run settings '%s'", opt, path, s->run_settings);
  if ((c->duration_given && c->duration != duration) || (c->dt_given && c->dt != dt) ||
      (c->integrator >= 0 && c->integrator != integrator))
    return say(c, SW_EUSAGE, "%s %s: its evaluations ran with %s; --duration, --dt and "
               "--integrator must agree or be left out", opt, path, s->run_settings);
  c->duration = duration;
  c->dt = dt;
  c->dt_given = dt > 0;
  c->integrator = integrator;
  return SW_OK;
}

/* --resume: the settings, params and run of the file, checked against the
 * options given again. */
static int take_resumed(swStudyCall *c, swStudyArgs *a, int *vary) {
  const swProgram *p = c->p;
  swStudySettings s;
  int rc = read_settings(c, "--resume", a->resume, &s);
  if (rc == SW_OK) rc = take_run_settings(c, "--resume", a->resume, &s);
  if (rc != SW_OK) return rc;
  /* the study's settings */
  if (a->kind_given || a->seed_given || a->popsize_given || a->sigma_given ||
      a->restarts_given || (a->budget_given && s.kind != SW_STUDY_CMAES))
    return say(c, SW_EUSAGE, "--resume %s: the study's settings are in the file; only an "
               "optimisation's --budget may be given again (to let it run longer)", a->resume);
  a->kind = s.kind;
  a->levels = s.levels;
  a->popsize = s.popsize;
  a->sigma = s.sigma;
  a->seed = s.seed;
  a->restarts = s.restarts;
  if (!a->budget_given) a->samples = s.samples;
  else if (a->samples < s.samples)
    return say(c, SW_EUSAGE, "--resume %s --budget %ld: the study already had a budget of %ld",
               a->resume, a->samples, s.samples);
  if (s.kind != SW_STUDY_CMAES) a->samples = s.samples;
  /* every param's start value, and which vary */
  for (char *item = strtok(s.fixed, ";"); item; item = strtok(NULL, ";")) {
    char *eq = strchr(item, '=');
    if (!eq) continue;
    *eq = 0;
    for (int i = 0; i < p->nparam; i++) {
      if (strcmp(p->param[i].name, item)) continue;
      double v = strtod(eq + 1, NULL);
      if (c->overridden[i] && c->P[i] != v)
        return say(c, SW_EUSAGE, "--resume %s: the study ran with %s = %.9g (SI); --set "
                   "must agree or be left out", a->resume, item, v);
      c->P[i] = v;
    }
  }
  for (int i = 0; i < p->nparam; i++) vary[i] = 0;
  for (char *item = strtok(s.varied, ";"); item; item = strtok(NULL, ";"))
    for (int i = 0; i < p->nparam; i++)
      if (!strcmp(p->param[i].name, item)) vary[i] = p->param[i].ranged;
  return SW_OK;
}

/* A start value v (SI) of param i outside its range: SW_EUSAGE, with the
 * message "HEAD NAME = V, outside ...'s range (LO, HI)" in the units shown. */
static int out_of_range(const swStudyCall *c, int i, double v, const double *lo,
                        const double *hi, const char *head, const char *whose) {
  const char *u = c->unit[i], *sp = u[0] ? " " : "";
  const double s = c->scale[i];
  return say(c, SW_EUSAGE, "%s %s = %.9g%s%s, outside %s range (%.9g%s%s, %.9g%s%s)", head,
             c->p->param[i].name, v / s, sp, u, whose, lo[i] / s, sp, u, hi[i] / s, sp, u);
}

/* --start: the varied params take the values of the best design the file
 * holds, where it has a param of the same name (the others keep theirs). */
static int take_start(swStudyCall *c, const char *path, const int *vary, const double *lo,
                      const double *hi, const char *const *name) {
  const swProgram *p = c->p;
  const int np = p->nparam;
  double *v = malloc(((size_t)np + 1) * sizeof *v);
  int *found = malloc(((size_t)np + 1) * sizeof *found);
  if (!v || !found) {
    free(v);
    free(found);
    return say(c, SW_EIO, "out of memory");
  }
  char err[512];
  swStudyDesign d;
  int rc = SW_OK, taken = 0, nvary = 0;
  if (sw_study_file_design(path, -1, np, name, c->unit, c->scale, v, found, &d, err,
                           sizeof err) != SW_OK)
    rc = say(c, SW_EIO, "--start: %s", err);
  for (int i = 0; i < np && rc == SW_OK; i++) {
    nvary += vary[i];
    if (!vary[i] || !found[i] || c->started[i]) continue; /* --start NAME=VALUE wins */
    if (!(v[i] >= lo[i] && v[i] <= hi[i])) {
      char head[320];
      snprintf(head, sizeof head, "--start %s: its best design has", path);
      rc = out_of_range(c, i, v[i], lo, hi, head, "this model's");
    } else {
      c->P[i] = v[i];
      taken++;
    }
  }
  if (rc == SW_OK && !taken)
    rc = say(c, SW_EUSAGE, "--start %s: none of the params this study varies is in that file",
             path);
  int rank = 0;
  sw_study_launched(&rank, NULL);
  if (rc == SW_OK && !c->quiet && rank == 0)
    fprintf(stderr, "%s: starting at the best design of %s (evaluation %ld, score %.6g): %d of "
            "the %d varied params\n", c->prog, path, d.index, d.score, taken, nvary);
  free(v);
  free(found);
  return rc;
}

int sw_study_cli(swStudyCall *c) {
  const swProgram *p = c->p;
  swStudyArgs a = c->args;
  const int np = p->nparam;
  int *vary = calloc((size_t)np + 1, sizeof *vary);
  const char **name = malloc(((size_t)np + 1) * sizeof *name);
  double *lo = malloc(((size_t)np + 1) * sizeof *lo), *hi = malloc(((size_t)np + 1) * sizeof *hi);
  if (!vary || !name || !lo || !hi) {
    free(vary);
    free(name);
    free(lo);
    free(hi);
    return say(c, SW_EIO, "out of memory");
  }
  int rc = SW_OK;
  for (int i = 0; i < np; i++) {
    name[i] = p->param[i].name;
    vary[i] = p->param[i].ranged && !c->overridden[i];
    lo[i] = p->param[i].lo;
    hi[i] = p->param[i].hi;
  }
  const char *path = a.resume ? a.resume : a.study;
  char default_path[300];
  if (!path) {
    snprintf(default_path, sizeof default_path, "%s_study.h5", p->name && p->name[0] ? p->name
                                                                                    : "sinew");
    path = default_path;
  }
  /* only rank 0 writes the file: the other ranks of an mpirun do not look
   * for it (rank 0 may have created it already) */
  int rank = 0;
  sw_study_launched(&rank, NULL);
  if (a.resume) rc = take_resumed(c, &a, vary);
  else if (rank == 0 && access(path, F_OK) == 0)
    rc = say(c, SW_EUSAGE, "the study file %s exists: continue it with --resume %s, or give "
             "another --study (or remove it)", path, path);
  if (rc == SW_OK && a.start) rc = take_start(c, a.start, vary, lo, hi, name);
  for (int i = 0; i < np && rc == SW_OK; i++) { /* --start NAME=VALUE */
    if (!c->started[i]) continue;
    if (!vary[i])
      rc = say(c, SW_EUSAGE, "--start %s: --set fixes it, so the study does not vary it",
               name[i]);
    else if (!(c->P[i] >= lo[i] && c->P[i] <= hi[i]))
      rc = out_of_range(c, i, c->P[i], lo, hi, "--start", "its");
  }
  char settings[256];
  run_settings(c, settings, sizeof settings);
  swStudyOptions o;
  memset(&o, 0, sizeof o);
  o.prog = c->prog;
  o.path = path;
  o.resume = a.resume != NULL;
  o.quiet = c->quiet;
  o.kind = a.kind;
  o.levels = a.levels;
  o.samples = a.samples;
  o.popsize = a.popsize;
  o.sigma = a.sigma;
  o.restarts = a.restarts;
  o.seed = a.seed;
  o.eval_timeout = a.eval_timeout;
  o.nparam = np;
  o.name = name;
  o.unit = c->unit;
  o.scale = c->scale;
  o.si_unit = c->si_unit;
  o.value = c->P;
  o.vary = vary;
  o.lo = lo;
  o.hi = hi;
  o.sense = p->sense;
  o.objective_text = p->objective_text ? p->objective_text : "";
  o.objective_unit = p->objective_unit ? p->objective_unit : "";
  o.objective_scale = p->objective_scale > 0 ? p->objective_scale : 1;
  o.model_name = p->name;
  o.model_sha256 = p->sha256 ? p->sha256 : "";
  o.run_settings = settings;
  o.recheck = RECHECK_BEST;
  o.no_recheck = a.no_recheck;
  o.eval = eval_model;
  o.ctx = c;
  if (rc == SW_OK) rc = sw_study_run(&o);
  free(vary);
  free(name);
  free(lo);
  free(hi);
  return rc;
}

/* ---- --replay ---- */

/* The varied params of the design (SI values v) in the units shown. */
static void print_design(const swStudyCall *c, const double *v, const int *vary) {
  for (int i = 0, n = 0; i < c->p->nparam; i++)
    if (vary[i])
      fprintf(stderr, "%s%s = %.9g%s%s", n++ ? ", " : "", c->p->param[i].name, v[i] / c->scale[i],
              c->unit[i][0] ? " " : "", c->unit[i]);
}

/* Every param of design `index` of the study path, as evaluated: the
 * varied ones from the design, the others (and all of them in a file
 * without params_si, whose start is exact, SI) as the study held them. */
static int take_design(swStudyCall *c, const char *path, long index, const swStudySettings *s,
                       int *vary, swStudyDesign *d) {
  const swProgram *p = c->p;
  const int np = p->nparam;
  double *v = malloc(((size_t)np + 1) * sizeof *v), *held = malloc(((size_t)np + 1) * sizeof *v);
  int *found = malloc(((size_t)np + 1) * sizeof *found);
  const char **name = malloc(((size_t)np + 1) * sizeof *name);
  char fixed[sizeof s->fixed], varied[sizeof s->varied], err[512];
  int rc = v && held && found && name ? SW_OK : say(c, SW_EIO, "out of memory");
  for (int i = 0; i < np && rc == SW_OK; i++) {
    name[i] = p->param[i].name;
    held[i] = NAN;
    vary[i] = 0;
  }
  memcpy(fixed, s->fixed, sizeof fixed);
  memcpy(varied, s->varied, sizeof varied);
  for (char *item = strtok(fixed, ";"); item && rc == SW_OK; item = strtok(NULL, ";")) {
    char *eq = strchr(item, '=');
    if (!eq) continue;
    *eq = 0;
    for (int i = 0; i < np; i++)
      if (!strcmp(name[i], item)) held[i] = strtod(eq + 1, NULL);
  }
  for (char *item = strtok(varied, ";"); item && rc == SW_OK; item = strtok(NULL, ";"))
    for (int i = 0; i < np; i++)
      if (!strcmp(name[i], item)) vary[i] = 1;
  if (rc == SW_OK &&
      (rc = sw_study_file_design(path, index, np, name, c->unit, c->scale, v, found, d, err,
                                 sizeof err)) != SW_OK)
    say(c, rc, "--replay: %s", err);
  else if (rc == SW_OK && d->status != SW_EVAL_OK)
    rc = say(c, SW_EUSAGE, "--replay %s: evaluation %ld %s%s: it has no objective to reproduce",
             path, d->index, d->status == SW_EVAL_PENDING ? "has not been evaluated" : "is ",
             d->status == SW_EVAL_PENDING ? "" : sw_eval_status_name(d->status));
  for (int i = 0; i < np && rc == SW_OK; i++) {
    double want = !d->exact && !vary[i] && !isnan(held[i]) ? held[i] : v[i];
    if (!found[i])
      rc = say(c, SW_EIO, "--replay %s: its study has no param %s", path, name[i]);
    else if (vary[i] && c->overridden[i])
      rc = say(c, SW_EUSAGE, "--replay %s: the study varied %s, so the design sets it: leave out "
               "--set %s", path, name[i], name[i]);
    else if (c->overridden[i] && c->P[i] != want)
      rc = say(c, SW_EUSAGE, "--replay %s: its evaluations ran with %s = %.17g (SI); --set must "
               "agree or be left out", path, name[i], want);
    else c->P[i] = want;
  }
  free(v);
  free(held);
  free(found);
  free(name);
  return rc;
}

int sw_study_replay(swStudyCall *c, const char *path, long index, swStudyDesign *d) {
  const swProgram *p = c->p;
  swStudySettings s;
  int rc = read_settings(c, "--replay", path, &s);
  if (rc == SW_OK) rc = take_run_settings(c, "--replay", path, &s);
  if (rc != SW_OK) return rc;
  if (!(c->duration > 0)) c->duration = p->duration;   /* as sw_evaluate takes it */
  int *vary = calloc((size_t)p->nparam + 1, sizeof *vary);
  if (!vary) return say(c, SW_EIO, "out of memory");
  rc = take_design(c, path, index, &s, vary, d);
  if (rc == SW_OK && !c->quiet) {
    const char *u = p->objective_unit ? p->objective_unit : "";
    fprintf(stderr, "%s: replaying evaluation %ld of %s%s (score %.9g%s%s): ", c->prog,
            d->index, path, index < 0 ? ", its best" : "", d->score, u[0] ? " " : "", u);
    print_design(c, c->P, vary);
    fprintf(stderr, "\n");
  }
  if (rc == SW_OK && !d->exact)
    fprintf(stderr, "%s: warning: --replay %s: the file has no /evaluations/params_si (it "
            "predates it): its params are the values shown, converted to SI, which may differ "
            "from those evaluated in the last bits, and the objective with them\n", c->prog, path);
  fflush(stderr);
  free(vary);
  return rc;
}
