/* cli.c — the command line of every generated simulator (docs/language.md, "The simulator's command line"):
 *   SIM [--out F.h5] [--duration T] [--dt DT] [--every T] [--set NAME=VALUE]...
 *       [--threads N] [--quiet] [--info] [--help]
 * This file is sw_main and what it does once the options are read: building
 * the model, a run and its summary, the objective's report, the entry into a
 * study, the run of one of a study's designs (--replay).  The rest is by
 * what it does: cli_options.c reads the options (the table, values, "did
 * you mean", the checks that they agree), cli_info.c prints --help and
 * --info, cli_study.c is the command line's side of --sweep, --optimize,
 * --resume and --replay; cli.h holds what they share.
 *
 * Design.  Nothing is built until the whole command line has been read
 * (cli_options.c).  The scene is then built by the program's build() from the
 * param values and compiled; when neither --dt nor the model fixes the step,
 * the scene is compiled once to read its stable step estimate and again at
 * half of it (the damping factors of a model depend on dt, so dt cannot be
 * patched into a compiled model).  A step above the estimate is allowed, with
 * a warning: the estimate is conservative and the user may know better.
 * --info prints the compiled scene and stops; otherwise the run writes HDF5
 * through output.c, closes the file with a status that says how the run
 * ended, prints a one-line summary and returns sw_run()'s code as the exit
 * code.  A model with an objective (maximize, minimize) also gets it printed
 * and stored at the end of the run (evaluate.c), and its ranges and objective
 * shown by --info and --help.  --threads N runs each step on N OpenMP threads
 * ("auto": one per 8192 elastic slots of the model, rounded, up to the processors
 * this process may use); the default is 1, because most simulators run
 * beside others (a sweep, an optimiser, the test suite), where one process
 * per core beats threads that meet at a barrier several times a step, and
 * because the results are the same bits for any N, so asking for more is
 * only ever a question of speed.  --replay runs a study's design as a run:
 * the params, duration, dt and integrator its evaluation had, and the
 * model's frame interval, which shaped the evaluation's chunks of steps, so
 * that the objective the run prints is the one the study stored, to the
 * bit (it says so, or warns). */
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sinew.h"
#include "cli.h"
#include "engine/internal.h"
#include "io/params.h"
#include "study/study.h"

/* ---- complaints ---- */

int sw_cli_complain(const swCli *c, const char *fmt, ...) {
  va_list ap;
  fprintf(stderr, "%s: ", c->prog);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
  fflush(stderr);
  return SW_EUSAGE;
}

/* ---- --restart and --compare, once the options are read ---- */

/* --restart: the params (those not given with --set), the time step, the
 * frame interval and the integrator (unless --dt, --every, --integrator
 * are given) of the run being continued; an --integrator that is not the
 * file's is refused (its state would not be this run's). */
static int read_restart(swCli *c) {
  static const char *const file_names[] = {"position-verlet", "pefrl", "imex"};
  static const char *const cli_names[] = {"verlet", "pefrl", "imex"};
  char params[8192], sha256[65], integrator[16];
  double dt, every;
  if (access(c->restart, R_OK) != 0) {
    sw_cli_complain(c, "--restart: cannot read '%s': %s", c->restart, strerror(errno));
    return SW_EIO;
  }
  if (sw_output_read_run(c->restart, sha256, params, sizeof params, &dt, &every, integrator) !=
      SW_OK) {
    sw_cli_complain(c, "--restart: %s", sw_output_error());
    return SW_EIO;
  }
  if (strcmp(sha256, c->p->sha256 ? c->p->sha256 : "")) {
    sw_cli_complain(c, "--restart: %s was written by another model (model_sha256 %.12s..., this "
                    "model's %.12s...)", c->restart, sha256, c->p->sha256 ? c->p->sha256 : "");
    return SW_EIO;
  }
  for (int k = 0; k < 3; k++) {
    if (strcmp(integrator, file_names[k])) continue;
    if (c->integrator < 0) c->integrator = k;
    else if (c->integrator != k) {
      sw_cli_complain(c, "--restart: %s was run with --integrator %s, this run asks for %s", c->restart,
                      cli_names[k], cli_names[c->integrator]);
      return SW_EIO;
    }
  }
  if (!c->every_given && every >= 0) c->every = every;
  if (!c->dt_given && dt > 0) {
    c->dt = dt;
    c->dt_given = 1;
  }
  for (char *item = strtok(params, ";"); item; item = strtok(NULL, ";")) {
    char *eq = strchr(item, '=');
    if (!eq) continue;
    *eq = '\0';
    for (int i = 0; i < c->p->nparam; i++)
      if (!strcmp(c->p->param[i].name, item) && !c->overridden[i]) c->P[i] = strtod(eq + 1, NULL);
  }
  return SW_OK;
}

/* Whether two paths name the same file (the same path, or the same inode). */
static int same_file(const char *a, const char *b) {
  if (!strcmp(a, b)) return 1;
  struct stat sa, sb;
  return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/* ---- building ---- */

/* Builds and compiles the scene at the step asked for, or at half the stable
 * estimate.  Returns the model, or NULL with the exit code in *rc. */
static swModel *build_model(const swCli *c, double *stable, const char **dt_source, int *rc) {
  const swProgram *p = c->p;
  char err[512] = "";
  *dt_source = c->dt_given ? "--dt" : p->dt > 0 ? "from the model" : "half the stable estimate";
  /* the step sw_evaluate takes too (evaluate.c): shortened to divide the
   * model's frame interval, never --every's, so that --every changes what is
   * written and nothing else */
  swModel *m = sw_program_compile(p, c->P, c->dt_given ? c->dt : 0, c->integrator, p->every,
                                  stable, rc, err, sizeof err);
  if (!m) {
    sw_cli_complain(c, "%s", err);
    return NULL;
  }
  if (!c->dt_given && !(p->dt > 0) && m->dt < 0.5 * *stable * (1 - 1e-12)) {
    static char shortened[96];
    snprintf(shortened, sizeof shortened, "half the stable estimate, shortened so that %.0f steps "
             "span the model's frame interval", round(p->every / m->dt));
    *dt_source = shortened;
  }
  long nsteps;
  char why[256];
  if (sw_step_count(c->duration, m->dt, &nsteps, why, sizeof why) != SW_OK) {
    sw_cli_complain(c, "no run: %s (dt: %s; duration: %s)", why, *dt_source,
                    c->duration_given ? "--duration" : "from the model");
    sw_model_free(m);
    *rc = SW_EUSAGE;
    return NULL;
  }
  if (m->dt > *stable) {
    char dt_text[32], stable_text[32];
    fprintf(stderr, "%s: warning: dt = %s is above the stable estimate %s; the run may "
            "become unstable\n", c->prog, sw_cli_format_time(dt_text, sizeof dt_text, m->dt),
            sw_cli_format_time(stable_text, sizeof stable_text, *stable));
    fflush(stderr);
  }
  /* a swelling rod's estimate covers the radius over the compiled run (a
   * signal NAME(t) is sampled there, swell.c); a longer --duration may take
   * it further: check the radius this run reaches (docs/physics.md,
   * "Geometry that changes in time") */
  for (int k = 0; k < m->nswell; k++) {
    double lo, hi;
    sw_swell_range_over(m, k, c->duration, &lo, &hi);
    if (lo >= m->swell_range[2 * k] && hi <= m->swell_range[2 * k + 1]) continue;
    const int r = m->swell_rod[k];
    const double there = fmin(sw_stable_dt_elastic_at(m, r, lo), sw_stable_dt_elastic_at(m, r, hi));
    if (!(m->dt > there) || (m->nimplicit && m->rod_implicit[r])) continue;
    char dt_text[32], there_text[32];
    fprintf(stderr, "%s: warning: rod '%s': its radius reaches x%.4g to x%.4g of its t = 0 value "
            "over this run, beyond what the stable estimate covers; there the rod is stable below "
            "dt = %s, and dt = %s\n", c->prog, m->rod_name[r], lo, hi,
            sw_cli_format_time(there_text, sizeof there_text, there),
            sw_cli_format_time(dt_text, sizeof dt_text, m->dt));
    fflush(stderr);
  }
  /* an activation outside [0, 1] is clamped (muscle.c): say so, once a
   * muscle, since a param set here can push it there (the compiler warns
   * of what the model's own values do) */
  for (int mu = 0; mu < m->nmuscle; mu++) {
    double lo, hi;
    sw_signal_range(&m->muscle_activation[mu], &lo, &hi);
    if (lo < 0 || hi > 1)
      fprintf(stderr, "%s: warning: muscle '%s': its activation %s %g; it acts as %g "
              "(activations are clamped to [0, 1])\n", c->prog, m->muscle_name[mu],
              hi > 1 ? "reaches" : "goes down to", hi > 1 ? hi : lo, hi > 1 ? 1.0 : 0.0);
  }
  /* frames fall on steps (run.c): say where, when the interval asked for
   * is not a whole number of them */
  if (c->every > 0 && c->every < c->duration) {
    double k = round(c->every / m->dt);
    if (k < 1) k = 1;
    if (fabs(k * m->dt - c->every) > 1e-9 * c->every) {
      char every_text[32], dt_text[32], got_text[32];
      fprintf(stderr, "%s: note: a frame every %s (%s) is %.4g steps of dt = %s; frames come "
              "every %.0f steps, %s apart\n", c->prog,
              sw_cli_format_time(every_text, sizeof every_text, c->every),
              c->every_given ? "--every" : "the model's output", c->every / m->dt,
              sw_cli_format_time(dt_text, sizeof dt_text, m->dt), k,
              sw_cli_format_time(got_text, sizeof got_text, k * m->dt));
    }
  }
  fflush(stderr);
  *rc = SW_OK;
  return m;
}

static char *params_string(const swCli *c) {
  const swProgram *p = c->p;
  const char *names[p->nparam > 0 ? p->nparam : 1];
  for (int i = 0; i < p->nparam; i++) names[i] = p->param[i].name;
  return sw_params_text(p->nparam, names, c->P);
}

/* ---- the run ---- */

static const char *format_wall(char *buf, size_t len, double seconds) {
  if (seconds < 60) snprintf(buf, len, "%.3g s", seconds);
  else if (seconds < 3600)
    snprintf(buf, len, "%d min %02d s", (int)(seconds / 60), (int)fmod(seconds, 60));
  else snprintf(buf, len, "%d h %02d min", (int)(seconds / 3600), (int)fmod(seconds / 60, 60));
  return buf;
}

/* --threads auto: a thread per AUTO_SLOTS elastic slots, rounded to the
 * nearest, up to the processors: a second thread from 12288 slots.  Below
 * about 10^4 elements it does not pay on a two-core machine; the kinematic
 * wing's 16000 slots run 1.8 times faster on two (docs/performance.md,
 * "Threads"). */
#define AUTO_SLOTS 8192

static long auto_threads(const swModel *m) {
  long n = (m->nslot_elastic + AUTO_SLOTS / 2) / AUTO_SLOTS;
  if (n > omp_get_num_procs()) n = omp_get_num_procs();
  return n < 1 ? 1 : n;
}

long sw_cli_threads_for(const swCli *c, const swModel *m) {
  return c->threads_auto ? auto_threads(m) : c->threads;
}

/* The run's objective (evaluate.c) on one line of stderr, unless --quiet,
 * and in the root attributes of its file; a run that did not finish, or
 * ended before a time the objective reads, has none (NaN in the file). */
static int report_objective(const swCli *c, const swModel *m, const swExpectRun *x,
                            swOutput *o, int rc) {
  const swProgram *p = c->p;
  double value = NAN, penalty = NAN, score = NAN;
  char why[256] = "";
  if (rc == SW_OK) rc = sw_objective(p, m, x, c->P, &value, &penalty, &score, why, sizeof why);
  else snprintf(why, sizeof why, "%s", rc == SW_EUNSTABLE ? "the run became unstable"
                : rc == SW_EINTERRUPT ? "the run was interrupted" : "the run did not finish");
  const char *u = p->objective_unit, *space = u[0] ? " " : "";
  const double k = p->objective_scale > 0 ? p->objective_scale : 1;
  if (!c->quiet) {
    if (rc == SW_OK)
      fprintf(stderr, "%s: objective: %s = %.9g%s%s; penalty %.9g%s%s; score %.9g%s%s\n",
              c->prog, p->objective_text, value / k, space, u, penalty / k, space, u,
              score / k, space, u);
    else fprintf(stderr, "%s: objective: %s: not reached (%s)\n", c->prog, p->objective_text,
                 why);
    fflush(stderr);
  }
  if (c->replay) { /* the study stores it in its unit, as value / k */
    double here = value / k, there = c->replayed.objective;
    if (rc == SW_OK && !memcmp(&here, &there, sizeof here)) {
      if (!c->quiet)
        fprintf(stderr, "%s: the objective is evaluation %ld's of %s, bit for bit (%.17g%s%s)\n",
                c->prog, c->replayed.index, c->replay, here, space, u);
    } else {
      fprintf(stderr, "%s: warning: the objective %.17g%s%s is not evaluation %ld's of %s "
              "(%.17g%s%s)\n", c->prog, here, space, u, c->replayed.index, c->replay, there,
              space, u);
    }
  }
  if (rc != SW_OK) value = penalty = score = NAN;
  if (sw_output_objective(o, p->objective_text, value, penalty, score,
                          p->objective_si_unit) == SW_OK)
    return SW_OK;
  sw_cli_complain(c, "%s", sw_output_error());
  return SW_EIO;
}

int sw_cli_run(const swCli *c, const swModel *m, const char *out) {
  const swProgram *p = c->p;
  char err[512] = "";
  swData *d = sw_data_new(m);
  if (d) sw_set_threads(d, (int)sw_cli_threads_for(c, m));
  char *params = params_string(c);
  if (!d || !params) {
    sw_cli_complain(c, "out of memory");
    sw_data_free(d);
    free(params);
    return SW_EMODEL;
  }
  swOutputOptions oo = {.model_source = p->source,
                        .model_sha256 = p->sha256,
                        .params = params,
                        .duration = c->duration,
                        .every = c->every,
                        .velocity = p->velocity,
                        .directors = p->directors,
                        .rod_out = p->rod_out,
                        .muscle_out = p->muscle_out};
  /* the joints' selection by name (at most a few hundred joints) */
  unsigned joint_out[m->njoint > 0 ? m->njoint : 1];
  if (p->njoint_out > 0) {
    for (int j = 0; j < m->njoint; j++) {
      joint_out[j] = p->joint_out_rest;
      for (int k = 0; k < p->njoint_out; k++)
        if (!strcmp(m->joint_name[j], p->joint_out_name[k])) joint_out[j] = p->joint_out[k];
    }
    oo.joint_out = joint_out;
  }
  /* the params table: at most a few dozen rows */
  const int np = p->nparam;
  const char *pname[np > 0 ? np : 1], *punit[np > 0 ? np : 1];
  char unit[np > 0 ? np : 1][48];
  double pvalue[np > 0 ? np : 1], pdefault[np > 0 ? np : 1];
  for (int i = 0; i < np; i++) {
    pname[i] = p->param[i].name;
    pvalue[i] = sw_cli_param_in_unit(&p->param[i], c->P[i], unit[i], sizeof unit[i]);
    pdefault[i] = sw_cli_param_in_unit(&p->param[i], p->param[i].value, unit[i], sizeof unit[i]);
    punit[i] = unit[i];
  }
  oo.nparam = np;
  oo.param_name = pname;
  oo.param_value = pvalue;
  oo.param_default = pdefault;
  oo.param_unit = punit;
  swExpectRun *expect = m->nexpect ? sw_expect_run_new(m) : NULL;
  if (m->nexpect && !expect) {
    sw_cli_complain(c, "out of memory");
    sw_data_free(d);
    free(params);
    return SW_EMODEL;
  }
  swOutput *o = c->restart ? sw_output_resume(out, m, &oo, d, expect, err, sizeof err)
                           : sw_output_open(out, m, &oo, err, sizeof err);
  free(params);
  if (!o) {
    sw_cli_complain(c, "%s", err);
    sw_expect_run_free(expect);
    sw_data_free(d);
    return SW_EIO;
  }
  if (c->restart && !(sw_time(m, d) < c->duration - 0.5 * m->dt)) {
    sw_cli_complain(c, "--restart: %s already reaches t = %.9g s; give a longer --duration", out,
                    sw_time(m, d));
    sw_output_close(o, "complete");
    sw_expect_run_free(expect);
    sw_data_free(d);
    return SW_EUSAGE;
  }
  if (c->restart && !c->quiet)
    fprintf(stderr, "%s: continuing %s from t = %.9g s (frame %ld)\n", c->prog, out, sw_time(m, d),
            sw_output_frames(o));
  swRunOptions ro = {.duration = c->duration, .every = c->every, .quiet = c->quiet,
                     .expect = expect, .resumed = c->restart != NULL};
  double start = sw_wall_seconds();
  int rc = sw_run(m, d, o, &ro);
  double wall = sw_wall_seconds() - start;
  /* the model's expectations: reported whatever the run's end, and a
   * failure is the run's verdict only when nothing else went wrong */
  int failed = sw_expect_report(m, expect, stderr, c->prog, c->quiet);
  if (p->sense && report_objective(c, m, expect, o, rc) != SW_OK && rc == SW_OK) rc = SW_EIO;
  sw_expect_run_free(expect);
  if (failed && rc == SW_OK) rc = SW_EEXPECT;

  /* The file says how the run ended. */
  char status[1100];
  const char *verdict;
  switch (rc) {
  case SW_OK:
    verdict = "done";
    snprintf(status, sizeof status, "complete");
    break;
  case SW_EEXPECT:
    verdict = "done, an expectation failed";
    snprintf(status, sizeof status, "complete; %d expectation%s failed", failed,
             failed == 1 ? "" : "s");
    break;
  case SW_EUNSTABLE:
    verdict = "unstable";
    snprintf(status, sizeof status, "unstable: %s", d->error[0] ? d->error : "the step failed");
    break;
  case SW_EINTERRUPT:
    verdict = "interrupted";
    snprintf(status, sizeof status, "interrupted at t = %.9g s", d->time);
    break;
  case SW_EIO:
    verdict = "I/O error";
    snprintf(status, sizeof status, "io error: %s", sw_output_error());
    break;
  default:
    verdict = "failed";
    snprintf(status, sizeof status, "failed (code %d)", rc);
    break;
  }
  long frames = sw_output_frames(o);
  if (sw_output_close(o, status) != SW_OK) {
    sw_cli_complain(c, "%s", sw_output_error());
    if (rc == SW_OK) rc = SW_EIO;
  }
  /* --compare: the closed file against the stored one (a run that did not
   * finish is not compared: its file is shorter by design) */
  if (c->golden && (rc == SW_OK || rc == SW_EEXPECT)) {
    int differ = sw_compare_files(out, c->golden, c->rtol, stderr, c->prog);
    if (differ < 0) rc = SW_EIO;
    else if (differ > 0 && rc == SW_OK) rc = SW_EEXPECT;
  }
  if (!c->quiet) {
    char t[32], total[32], w[32];
    fprintf(stderr, "%s: %s: %ld frame%s written to %s; simulated %s", c->prog, verdict, frames,
            frames == 1 ? "" : "s", out, sw_cli_format_time(t, sizeof t, d->time));
    if (rc != SW_OK && rc != SW_EEXPECT)
      fprintf(stderr, " of %s", sw_cli_format_time(total, sizeof total, c->duration));
    fprintf(stderr, " in %s wall time (%ld steps)\n", format_wall(w, sizeof w, wall), d->step);
    if (rc == SW_OK || rc == SW_EEXPECT) sw_cli_rigidity_note(c, m, d);
    double fresh, kept;
    sw_implicit_counts(m, d, &fresh, &kept);
    if (fresh + kept > 0)
      fprintf(stderr, "%s: implicit rods: %.0f of %.0f kicks kept an earlier factorisation\n",
              c->prog, kept, fresh + kept);
    fflush(stderr);
  }
  sw_data_free(d);
  return rc;
}

int sw_cli_simulate(const swCli *c) {
  double stable = 0;
  const char *dt_source = "";
  int rc = SW_OK;
  swModel *m = build_model(c, &stable, &dt_source, &rc);
  if (!m) return rc;
  rc = sw_cli_run(c, m, c->out);
  sw_model_free(m);
  return rc;
}

/* ---- a sweep or an optimisation (cli_study.c, study.c), a replay ---- */

/* The SI unit of a dimension: "m", "Pa", "N m", "kg m^-1"; "" when
 * dimensionless (from the name units.c gives it, "pressure (Pa)"). */
static void si_unit_of(const signed char dim[SW_NDIM], char *buf, size_t len) {
  char what[48];
  sw_dim_describe(what, sizeof what, dim);
  const char *open = strchr(what, '('), *close = strrchr(what, ')');
  if (open && close > open) snprintf(buf, len, "%.*s", (int)(close - open - 1), open + 1);
  else snprintf(buf, len, "%s", strcmp(what, "dimensionless") ? what : "");
}

/* What cli_study.c is handed: each param in the unit the model shows it in
 * (1 unit = scale SI) and its SI unit, in arrays *mem holds (free it). */
static int study_call(swCli *c, swStudyCall *call, void **mem) {
  const swProgram *p = c->p;
  const size_t np = (size_t)p->nparam + 1;
  typedef char swUnitName[48];
  char *m = malloc(np * (2 * sizeof(char *) + 2 * sizeof(swUnitName) + sizeof(double)));
  *mem = m;
  if (!m) return sw_cli_complain(c, "out of memory");
  const char **unit = (const char **)m, **si_unit = unit + np;
  double *scale = (double *)(si_unit + np);
  swUnitName *units = (swUnitName *)(scale + np), *si_units = units + np;
  for (int i = 0; i < p->nparam; i++) {
    double one = sw_cli_param_in_unit(&p->param[i], 1.0, units[i], sizeof units[i]);
    scale[i] = one != 0 && isfinite(one) ? 1.0 / one : 1.0;
    unit[i] = units[i];
    si_unit_of(p->param[i].dim, si_units[i], sizeof si_units[i]);
    si_unit[i] = si_units[i];
  }
  *call = (swStudyCall){.p = p, .prog = c->prog, .P = c->P, .overridden = c->overridden,
                        .started = c->started, .unit = unit, .scale = scale,
                        .si_unit = si_unit, .duration = c->duration, .dt = c->dt,
                        .duration_given = c->duration_given, .dt_given = c->dt_given,
                        .integrator = c->integrator, .quiet = c->quiet, .args = c->study};
  return SW_OK;
}

static int study(swCli *c) {
  swStudyCall call;
  void *mem;
  int rc = study_call(c, &call, &mem);
  if (rc == SW_OK) rc = sw_study_cli(&call);
  free(mem);
  return rc;
}

/* --replay: the run of one design of a study, as sw_evaluate ran it: its
 * params (cli_study.c), duration, dt and integrator.  Any frame interval
 * gives its steps: the run loop's held steps (integrate.c) leave the bits
 * alone where it reads the state, and writing a frame changes nothing a step
 * reads (the strains and joint forces it recomputes are scratch the next step
 * computes afresh). */
static int take_replay(swCli *c) {
  swStudyCall call;
  void *mem;
  int rc = study_call(c, &call, &mem);
  if (rc == SW_OK) rc = sw_study_replay(&call, c->replay, c->replay_index, &c->replayed);
  if (rc == SW_OK) {
    c->duration = call.duration;
    c->dt = call.dt;
    c->dt_given = call.dt_given;
    c->integrator = call.integrator;
  }
  free(mem);
  return rc;
}

/* ---- main ---- */

int sw_main(const swProgram *p, int argc, char **argv) {
  swCli c;
  memset(&c, 0, sizeof c);
  c.p = p;
  c.prog = p && p->name ? p->name : "sinew";
  if (argc > 0 && argv && argv[0] && argv[0][0]) {
    const char *slash = strrchr(argv[0], '/');
    c.prog = slash && slash[1] ? slash + 1 : argv[0];
  }
  if (!p || p->nparam < 0 || (p->nparam > 0 && !p->param))
    return sw_cli_complain(&c, "sw_main: no program");
  c.duration = p->duration;
  c.every = p->every;
  c.threads = 1;
  c.integrator = -1;
  c.rtol = 1e-9;
  c.study.levels = 2;
  c.study.samples = 1000;
  c.study.sigma = 0.25;
  c.study.seed = 1;

  /* default output: the model's, or NAME.h5 */
  char default_out[256];
  snprintf(default_out, sizeof default_out, "%s.h5", p->name && p->name[0] ? p->name : "sinew");
  c.out = p->out && p->out[0] ? p->out : default_out;

  c.P = malloc(((size_t)p->nparam + 1) * sizeof *c.P);
  c.overridden = calloc((size_t)p->nparam + 1, 1);
  c.started = calloc((size_t)p->nparam + 1, 1);
  if (!c.P || !c.overridden || !c.started) {
    free(c.P);
    free(c.overridden);
    free(c.started);
    return sw_cli_complain(&c, "out of memory");
  }
  for (int i = 0; i < p->nparam; i++) c.P[i] = p->param[i].value;

  int rc = sw_cli_parse_args(&c, argc, argv);
  if (rc == SW_OK && c.restart) rc = read_restart(&c);
  if (rc == SW_OK && c.golden && access(c.golden, R_OK) != 0) {
    sw_cli_complain(&c, "--compare: cannot read '%s': %s", c.golden, strerror(errno));
    rc = SW_EIO;
  }
  if (rc == SW_OK && c.replay && !c.help) rc = take_replay(&c);
  if (rc == SW_OK && c.golden && same_file(c.out, c.golden))
    rc = sw_cli_complain(&c, "--compare %s: that is the file this run would write (--out); the run "
                         "would overwrite what it is compared with", c.golden);
  if (rc == SW_OK && c.help) {
    sw_cli_print_help(&c, p->out && p->out[0] ? p->out : default_out);
  } else if (rc == SW_OK && (c.study.mode || c.study.resume)) {
    rc = study(&c);
  } else if (rc == SW_OK) {
    if (c.threads > omp_get_num_procs() && !c.quiet && !c.info) {
      fprintf(stderr, "%s: note: %ld threads on %d processors: threads that wait for a "
              "processor slow every step down\n", c.prog, c.threads, omp_get_num_procs());
      fflush(stderr);
    }
    double stable = 0;
    const char *dt_source = "";
    swModel *m = build_model(&c, &stable, &dt_source, &rc);
    if (m && c.info) sw_cli_print_info(&c, m, stable, dt_source, c.out);
    else if (m && c.accuracy) rc = sw_cli_accuracy(&c, m);
    else if (m) rc = sw_cli_run(&c, m, c.out);
    sw_model_free(m);
  }
  free(c.P);
  free(c.overridden);
  free(c.started);
  return rc;
}
