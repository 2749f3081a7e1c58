/* cli_options.c — reading the simulator's command line: the table of
 * options, each option's value (times, threads, the integrator, --set and
 * --start param values, counts, sweep specs, the study options, --replay's
 * study and design), "did you mean" for a misspelt option, and the checks
 * that the options agree.
 *
 * Design.  The options are one table (name, argument, help), from which both
 * the parser and --help (cli_info.c) are made, so they cannot disagree.  An
 * option takes its value as "--dt 50ns" or "--dt=50ns"; times and param
 * values are quantities of units.c and are checked by dimension, and every
 * complaint is one line on stderr, prefixed with the program's name, that
 * quotes what was written, names what was expected, suggests the nearest
 * option or param for a misspelling (sw_edit_distance, public: the
 * compiler's "did you mean" uses it too), and exits with SW_EUSAGE.  Reading
 * only fills the swCli: nothing is built until the whole command line has
 * been read, and the options are checked against each other (--rtol without
 * --compare, a study's options without a study) once all are read. */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "cli.h"
#include "study/study.h"

/* ---- the options ---- */

const swOption sw_cli_options[] = {
  {OPT_OUT, "--out", "FILE", "HDF5 file to write"},
  {OPT_DURATION, "--duration", "T", "simulated time"},
  {OPT_DT, "--dt", "DT", "time step"},
  {OPT_INTEGRATOR, "--integrator", "NAME", "verlet, pefrl or imex (Verlet, stiff terms implicit)"},
  {OPT_EVERY, "--every", "T", "simulated time between frames, 0 = every step"},
  {OPT_SET, "--set", "NAME=VALUE", "override a param, VALUE with its unit (repeatable)"},
  {OPT_THREADS, "--threads", "N", "threads of each step, or 'auto' (by the model's size)"},
  {OPT_COMPARE, "--compare", "FILE", "after the run, compare each dataset with a stored run's"},
  {OPT_RTOL, "--rtol", "R", "tolerance of --compare, relative to each dataset's largest value"},
  {OPT_RESTART, "--restart", "FILE", "continue the run FILE holds from its last checkpoint"},
  {OPT_SWEEP, "--sweep", "grid:K|lhs:N", "evaluate the ranged params on a grid of K points each, "
   "or N Latin-hypercube designs"},
  {OPT_OPTIMIZE, "--optimize", NULL, "optimise the ranged params for the objective (CMA-ES)"},
  {OPT_BUDGET, "--budget", "N", "--optimize: at most N evaluations"},
  {OPT_POPSIZE, "--popsize", "L", "--optimize: designs per generation"},
  {OPT_SIGMA, "--sigma", "F", "--optimize: initial step, a fraction of each range"},
  {OPT_RESTARTS, "--restarts", "K", "--optimize: restarts with doubled populations (IPOP)"},
  {OPT_START, "--start", "FILE|NAME=VALUE", "--optimize: start at the best design of the "
   "study FILE, param by param of the same name, or start a param at VALUE (repeatable)"},
  {OPT_SEED, "--seed", "S", "random seed of --sweep lhs and --optimize"},
  {OPT_STUDY, "--study", "FILE", "HDF5 file of the sweep or optimisation"},
  {OPT_RESUME, "--resume", "FILE", "continue the sweep or optimisation FILE holds"},
  {OPT_REPLAY, "--replay", "FILE [best|N]", "run one design of the study FILE, its best or "
   "evaluation N (from 0), as evaluated (params, duration, dt, integrator) into a run file"},
  {OPT_EVAL_TIMEOUT, "--eval-timeout", "T", "under mpirun: re-queue an evaluation a rank holds "
   "longer than T"},
  {OPT_NO_RECHECK, "--no-recheck", NULL, "a study: skip the recheck of its 3 best designs at "
   "dt/2 (how much the time step moves their objectives)"},
  {OPT_ACCURACY, "--accuracy", NULL, "run again at dt/2 and report how much each probe, hinge "
   "angle and the objective moved, and where the two runs part"},
  {OPT_TOLERANCE, "--tolerance", "R", "--accuracy: halve dt until the observables of two runs "
   "agree within R of their ranges (1% or 0.01), at most 4 times"},
  {OPT_QUIET, "--quiet", NULL, "no progress line, notes or summary"},
  {OPT_INFO, "--info", NULL, "print the compiled scene and exit"},
  {OPT_HELP, "--help", NULL, "print this help and exit"},
};
const size_t sw_cli_noptions = sizeof sw_cli_options / sizeof sw_cli_options[0];

static const signed char DIM_TIME[SW_NDIM] = {0, 0, 1, 0};

/* ---- did you mean ---- */

/* Edit distance with transpositions ("lenght" is one edit from "length");
 * names longer than 63 characters are never close.  Public: the compiler's
 * "did you mean" uses it too. */
int sw_edit_distance(const char *a, size_t la, const char *b) {
  size_t lb = strlen(b);
  if (la > 63 || lb > 63) return INT_MAX;
  int d[64][64];
  for (size_t i = 0; i <= la; i++) d[i][0] = (int)i;
  for (size_t j = 0; j <= lb; j++) d[0][j] = (int)j;
  for (size_t i = 1; i <= la; i++)
    for (size_t j = 1; j <= lb; j++) {
      int cost = a[i - 1] != b[j - 1];
      int best = d[i - 1][j] + 1;
      if (d[i][j - 1] + 1 < best) best = d[i][j - 1] + 1;
      if (d[i - 1][j - 1] + cost < best) best = d[i - 1][j - 1] + cost;
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
          d[i - 2][j - 2] + 1 < best)
        best = d[i - 2][j - 2] + 1;
      d[i][j] = best;
    }
  return d[la][lb];
}

/* Close enough to suggest: one edit for short names, two for longer ones. */
static int close_enough(int distance, size_t len) { return distance <= (len <= 3 ? 1 : 2); }

/* ---- reading the command line ---- */

/* --duration, --dt, --every: a time, or a bare number of seconds. */
static int read_time(const swCli *c, const char *opt, const char *value, int positive,
                     double *seconds) {
  char err[256], expected[64], got[64];
  double t;
  signed char dim[SW_NDIM];
  if (sw_parse_quantity(value, &t, dim, err, sizeof err))
    return sw_cli_complain(c, "%s: %s", opt, err);
  if (memcmp(dim, DIM_TIME, SW_NDIM) && memcmp(dim, DIM_NONE, SW_NDIM))
    return sw_cli_complain(c, "%s: expected %s, got %s in '%s'", opt,
                           sw_dim_describe(expected, sizeof expected, DIM_TIME),
                           sw_dim_describe(got, sizeof got, dim), value);
  if (positive && !(t > 0)) return sw_cli_complain(c, "%s: must be positive, got '%s'", opt, value);
  if (!(t >= 0)) return sw_cli_complain(c, "%s: must not be negative, got '%s'", opt, value);
  *seconds = t + 0.0; /* no -0 */
  return SW_OK;
}

#define MAX_THREADS 256

static int read_threads(swCli *c, const char *value) {
  if (!strcmp(value, "auto")) {
    c->threads_auto = 1;
    return SW_OK;
  }
  char *end;
  errno = 0;
  long n = strtol(value, &end, 10);
  if (!isdigit((unsigned char)value[0]) || *end || errno || n < 1)
    return sw_cli_complain(c, "--threads: expected a positive integer or 'auto', got '%s'", value);
  if (n > MAX_THREADS)
    return sw_cli_complain(c, "--threads: at most %d, got '%s'", MAX_THREADS, value);
  c->threads = n;
  c->threads_auto = 0;
  return SW_OK;
}

/* The integrators by the names the language gives them. */
static const char *const integrator_names[] = {"verlet", "pefrl", "imex"};

/* --integrator NAME. */
static int read_integrator(swCli *c, const char *value) {
  for (int k = 0; k < 3; k++)
    if (!strcmp(value, integrator_names[k])) {
      c->integrator = k;
      return SW_OK;
    }
  for (int k = 0; k < 3; k++)
    if (close_enough(sw_edit_distance(value, strlen(value), integrator_names[k]), strlen(value)))
      return sw_cli_complain(c, "--integrator: unknown integrator '%s' (did you mean '%s'?)", value,
                             integrator_names[k]);
  return sw_cli_complain(c, "--integrator: unknown integrator '%s' (verlet, pefrl or imex)", value);
}

/* --set NAME=VALUE (start 0: the param is fixed at VALUE) or --start
 * NAME=VALUE (start 1: a study starts it there and varies it): VALUE must
 * have the param's dimension. */
static int read_param_value(swCli *c, int start, const char *value) {
  const swProgram *p = c->p;
  const char *opt = start ? "--start" : "--set";
  const char *eq = strchr(value, '=');
  if (!eq || eq == value) return sw_cli_complain(c, "%s: expected NAME=VALUE, got '%s'", opt, value);
  size_t len = (size_t)(eq - value);
  int k = -1;
  for (int i = 0; i < p->nparam && k < 0; i++)
    if (strlen(p->param[i].name) == len && !memcmp(p->param[i].name, value, len)) k = i;
  if (k < 0) {
    int best = -1, best_distance = INT_MAX;
    for (int i = 0; i < p->nparam; i++) {
      int distance = sw_edit_distance(value, len, p->param[i].name);
      if (distance < best_distance) best = i, best_distance = distance;
    }
    if (best >= 0 && close_enough(best_distance, len))
      return sw_cli_complain(c, "%s: unknown param '%.*s' (did you mean '%s'?)", opt, (int)len, value,
                             p->param[best].name);
    if (p->nparam == 0)
      return sw_cli_complain(c, "%s: unknown param '%.*s' (the model has no params)", opt, (int)len,
                             value);
    char list[512] = "";
    size_t used = 0;
    for (int i = 0; i < p->nparam && used < sizeof list; i++) {
      int n = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", p->param[i].name);
      if (n < 0) break;
      used += (size_t)n;
    }
    return sw_cli_complain(c, "%s: unknown param '%.*s' (the params are: %s)", opt, (int)len, value,
                           list);
  }

  const swParam *q = &p->param[k];
  const char *text = eq + 1;
  char err[256], expected[64], got[64];
  double v;
  signed char dim[SW_NDIM];
  if (sw_parse_quantity(text, &v, dim, err, sizeof err))
    return sw_cli_complain(c, "%s %s: %s", opt, q->name, err);
  if (memcmp(dim, q->dim, SW_NDIM)) {
    sw_dim_describe(expected, sizeof expected, q->dim);
    if (!memcmp(dim, DIM_NONE, SW_NDIM)) {
      if (q->unit && q->unit[0])
        return sw_cli_complain(c, "%s %s: expected %s, got a number without a unit in '%s' "
                               "(write e.g. '%s %s')", opt, q->name, expected, text, text, q->unit);
      return sw_cli_complain(c, "%s %s: expected %s, got a number without a unit in '%s'", opt,
                             q->name, expected, text);
    }
    return sw_cli_complain(c, "%s %s: expected %s, got %s in '%s'", opt, q->name, expected,
                           sw_dim_describe(got, sizeof got, dim), text);
  }
  if (start) {
    if (!q->ranged)
      return sw_cli_complain(c, "--start %s: the param has no range, so no study varies it (--set "
                             "fixes a param)", q->name);
    c->P[k] = v;
    c->started[k] = 1;
    return SW_OK;
  }
  c->P[k] = v;
  c->overridden[k] = 1;
  return SW_OK;
}

/* A whole number in [lo, hi] for an option. */
static int read_count(const swCli *c, const char *opt, const char *value, long lo, long hi,
                      long *out) {
  char *end = NULL;
  errno = 0;
  long v = strtol(value, &end, 10);
  if (end == value || *end || errno || v < lo || v > hi)
    return sw_cli_complain(c, "%s: expected a whole number from %ld to %ld, got '%s'", opt, lo, hi,
                           value);
  *out = v;
  return SW_OK;
}

/* --sweep grid:K | lhs:N */
static int read_sweep(swCli *c, const char *value) {
  swStudyArgs *a = &c->study;
  a->mode = 1;
  a->kind_given = 1;
  if (!strncmp(value, "grid:", 5)) {
    a->kind = SW_STUDY_GRID;
    return read_count(c, "--sweep grid", value + 5, 2, 1000000, &a->levels);
  }
  if (!strncmp(value, "lhs:", 4)) {
    a->kind = SW_STUDY_LHS;
    return read_count(c, "--sweep lhs", value + 4, 1, 100000000, &a->samples);
  }
  return sw_cli_complain(c, "--sweep: expected grid:K (K points per ranged param) or lhs:N (N "
                         "Latin-hypercube designs), got '%s'", value);
}

static int read_study_option(swCli *c, swOptionId id, const char *value) {
  swStudyArgs *a = &c->study;
  switch (id) {
  case OPT_OPTIMIZE:
    a->mode = 2;
    a->kind = SW_STUDY_CMAES;
    a->kind_given = 1;
    return SW_OK;
  case OPT_BUDGET:
    a->budget_given = 1;
    return read_count(c, "--budget", value, 2, 1000000000, &a->samples);
  case OPT_POPSIZE:
    a->popsize_given = 1;
    return read_count(c, "--popsize", value, 2, 100000, &a->popsize);
  case OPT_RESTARTS:
    a->restarts_given = 1;
    return read_count(c, "--restarts", value, 0, 20, &a->restarts);
  case OPT_SEED: {
    char *end = NULL;
    errno = 0;
    unsigned long long v = strtoull(value, &end, 10);
    if (end == value || *end || errno || value[0] == '-')
      return sw_cli_complain(c, "--seed: expected a whole number from 0 to 2^64 - 1, got '%s'", value);
    a->seed = (uint64_t)v;
    a->seed_given = 1;
    return SW_OK;
  }
  case OPT_SIGMA: {
    char *end = NULL;
    a->sigma = strtod(value, &end);
    a->sigma_given = 1;
    if (end == value || *end || !(a->sigma > 0 && a->sigma <= 1))
      return sw_cli_complain(c, "--sigma: expected a fraction of each param's range in (0, 1], got "
                             "'%s'", value);
    return SW_OK;
  }
  case OPT_START: {
    a->start_given = 1;
    /* NAME=VALUE when what precedes '=' is a name, else a file's path */
    size_t name_len = strspn(value, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                    "0123456789_");
    if (name_len && value[name_len] == '=') return read_param_value(c, 1, value);
    if (!value[0]) return sw_cli_complain(c, "--start: empty file name");
    if (a->start)
      return sw_cli_complain(c, "--start %s: a study starts from one file, and --start %s was given",
                             value, a->start);
    a->start = value;
    return SW_OK;
  }
  case OPT_STUDY:
    if (!value[0]) return sw_cli_complain(c, "--study: empty file name");
    a->study = value;
    return SW_OK;
  case OPT_RESUME:
    if (!value[0]) return sw_cli_complain(c, "--resume: empty file name");
    a->resume = value;
    return SW_OK;
  case OPT_EVAL_TIMEOUT:
    return read_time(c, "--eval-timeout", value, 1, &a->eval_timeout);
  case OPT_NO_RECHECK:
    a->no_recheck = 1;
    return SW_OK;
  default:
    return SW_OK;
  }
}

/* --replay FILE [best|N]: the design, when the next word names one. */
static int read_replay(swCli *c, const char *value, int *i, int argc, char **argv) {
  if (!value[0]) return sw_cli_complain(c, "--replay: empty file name");
  c->replay = value;
  c->replay_index = -1;
  const char *next = *i + 1 < argc ? argv[*i + 1] : "";
  if (!strcmp(next, "best")) ++*i;
  else if (isdigit((unsigned char)next[0])) {
    ++*i;
    return read_count(c, "--replay FILE N: the evaluation", next, 0, 100000000, &c->replay_index);
  }
  return SW_OK;
}

/* The study options, together: which belong to which, and what cannot mix. */
static int check_study_args(const swCli *c) {
  const swStudyArgs *a = &c->study;
  int optimize_only = a->budget_given || a->popsize_given || a->sigma_given || a->restarts_given ||
                      a->start_given;
  if (c->replay && (a->mode || a->resume || a->study || optimize_only || a->seed_given ||
                    a->eval_timeout > 0 || a->no_recheck || c->restart))
    return sw_cli_complain(c, "--replay %s runs one design of that study as a new run: leave out "
                           "--sweep, --optimize, --resume, --study, --budget, --popsize, --sigma, "
                           "--restarts, --start, --seed, --eval-timeout, --no-recheck and "
                           "--restart", c->replay);
  if (a->resume && a->study)
    return sw_cli_complain(c, "--resume %s continues that file: --study %s cannot name another",
                           a->resume, a->study);
  if (a->resume && a->start_given)
    return sw_cli_complain(c, "--resume %s starts where that study stopped: leave out --start",
                           a->resume);
  if (a->resume && a->kind_given)
    return sw_cli_complain(c, "--resume takes the sweep or optimisation from its file: leave out "
                           "--sweep and --optimize");
  if (!a->mode && !a->resume) {
    if (optimize_only || a->seed_given || a->study || a->eval_timeout > 0 || a->no_recheck)
      return sw_cli_complain(c, "--budget, --popsize, --sigma, --restarts, --start, --seed, --study, "
                             "--eval-timeout and --no-recheck belong to --sweep or --optimize, "
                             "which was not given");
    return SW_OK;
  }
  if (a->mode == 1 && optimize_only)
    return sw_cli_complain(c, "--budget, --popsize, --sigma, --restarts and --start belong to "
                           "--optimize, not --sweep");
  if (c->restart || c->golden || c->out_given || c->every_given || c->info)
    return sw_cli_complain(c, "a sweep or optimisation writes its study file (--study), not a run: "
                           "leave out --out, --every, --restart, --compare and --info");
  return SW_OK;
}

/* --tolerance: a fraction (0.01) or a percentage (1%), in (0, 1). */
static int read_tolerance(swCli *c, const char *value) {
  char *end;
  double t = strtod(value, &end);
  if (end != value && *end == '%' && !end[1]) t /= 100, end++;
  if (end == value || *end || !(t > 0 && t < 1))
    return sw_cli_complain(c, "--tolerance: expected a fraction in (0, 1) or a percentage "
                           "(0.01 or 1%%), got '%s'", value);
  c->tolerance = t;
  return SW_OK;
}

static int unknown_option(const swCli *c, const char *arg, size_t len) {
  const char *bare = arg;             /* compared without its dashes */
  while (*bare == '-' && (size_t)(bare - arg) < len) bare++;
  size_t bare_len = len - (size_t)(bare - arg);
  const swOption *best = NULL;
  int best_distance = INT_MAX;
  for (size_t i = 0; i < sw_cli_noptions; i++) {
    int distance = sw_edit_distance(bare, bare_len, sw_cli_options[i].name + 2);
    if (distance < best_distance) best = &sw_cli_options[i], best_distance = distance;
  }
  if (best && bare_len && close_enough(best_distance, bare_len))
    return sw_cli_complain(c, "unknown option '%.*s' (did you mean '%s'?)", (int)len, arg, best->name);
  return sw_cli_complain(c, "unknown option '%.*s' (see --help)", (int)len, arg);
}

int sw_cli_parse_args(swCli *c, int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    const char *arg = argv[i];
    if (arg[0] != '-' || !arg[1])
      return sw_cli_complain(c, "unexpected argument '%s' (options start with '--'; see --help)", arg);
    if (!strcmp(arg, "-h")) {
      c->help = 1;
      continue;
    }
    const char *eq = strchr(arg, '=');
    size_t len = eq ? (size_t)(eq - arg) : strlen(arg);
    const swOption *opt = NULL;
    for (size_t k = 0; k < sw_cli_noptions && !opt; k++)
      if (strlen(sw_cli_options[k].name) == len && !strncmp(sw_cli_options[k].name, arg, len))
        opt = &sw_cli_options[k];
    if (!opt) return unknown_option(c, arg, len);

    const char *value = NULL;
    if (opt->arg) {
      if (eq) value = eq + 1;
      else if (i + 1 < argc && strncmp(argv[i + 1], "--", 2)) value = argv[++i];
      else return sw_cli_complain(c, "%s: missing value (%s %s)", opt->name, opt->name, opt->arg);
    } else if (eq) {
      return sw_cli_complain(c, "%s takes no value, got '%s'", opt->name, arg);
    }

    int rc = SW_OK;
    switch (opt->id) {
    case OPT_OUT:
      if (!value[0]) rc = sw_cli_complain(c, "--out: empty file name");
      c->out = value;
      c->out_given = 1;
      break;
    case OPT_DURATION:
      rc = read_time(c, opt->name, value, 0, &c->duration);
      c->duration_given = 1;
      break;
    case OPT_DT:
      rc = read_time(c, opt->name, value, 1, &c->dt);
      c->dt_given = 1;
      break;
    case OPT_INTEGRATOR: rc = read_integrator(c, value); break;
    case OPT_EVERY:
      rc = read_time(c, opt->name, value, 0, &c->every);
      c->every_given = 1;
      break;
    case OPT_RESTART:
      if (!value[0]) rc = sw_cli_complain(c, "--restart: empty file name");
      c->restart = value;
      break;
    case OPT_SET: rc = read_param_value(c, 0, value); break;
    case OPT_THREADS: rc = read_threads(c, value); c->threads_set = 1; break;
    case OPT_COMPARE:
      if (!value[0]) rc = sw_cli_complain(c, "--compare: empty file name");
      c->golden = value;
      break;
    case OPT_RTOL: {
      char *end = NULL;
      c->rtol = strtod(value, &end);
      c->rtol_given = 1;
      if (end == value || *end || !(c->rtol >= 0) || !isfinite(c->rtol))
        rc = sw_cli_complain(c, "--rtol: expected a number >= 0 (a fraction: 1e-6), got '%s'", value);
      break;
    }
    case OPT_SWEEP: rc = read_sweep(c, value); break;
    case OPT_OPTIMIZE: case OPT_BUDGET: case OPT_POPSIZE: case OPT_SIGMA: case OPT_RESTARTS:
    case OPT_START: case OPT_SEED: case OPT_STUDY: case OPT_RESUME: case OPT_EVAL_TIMEOUT:
    case OPT_NO_RECHECK:
      rc = read_study_option(c, opt->id, value);
      break;
    case OPT_REPLAY: rc = read_replay(c, value, &i, argc, argv); break;
    case OPT_ACCURACY: c->accuracy = 1; break;
    case OPT_TOLERANCE: rc = read_tolerance(c, value); break;
    case OPT_QUIET: c->quiet = 1; break;
    case OPT_INFO: c->info = 1; break;
    case OPT_HELP: c->help = 1; break;
    }
    if (rc != SW_OK) return rc;
  }
  if (c->rtol_given && !c->golden) return sw_cli_complain(c, "--rtol is the tolerance of --compare, "
                                                  "which was not given");
  if (c->restart && c->out_given && strcmp(c->out, c->restart))
    return sw_cli_complain(c, "--restart %s continues that file: --out %s cannot name another",
                           c->restart, c->out);
  if (c->restart) c->out = c->restart;
  if (c->tolerance > 0) c->accuracy = 1;
  if (c->accuracy && (c->restart || c->study.mode || c->study.resume))
    return sw_cli_complain(c, "--accuracy runs the model afresh at two steps: leave out --restart, "
                           "--sweep, --optimize and --resume");
  return check_study_args(c);
}
