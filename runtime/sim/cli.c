/* cli.c — the command line of every generated simulator (docs/language.md, "The simulator's command line"):
 *   SIM [--out F.h5] [--duration T] [--dt DT] [--every T] [--set NAME=VALUE]...
 *       [--threads N] [--quiet] [--info] [--help]
 *
 * Design.  The options are one table (name, argument, help), from which both
 * the parser and --help are made, so they cannot disagree.  An option takes its
 * value as "--dt 50ns" or "--dt=50ns"; times and param values are quantities
 * of units.c and are checked by dimension, and every complaint is one line on
 * stderr, prefixed with the program's name, that quotes what was written, names
 * what was expected, suggests the nearest option or param for a misspelling,
 * and exits with SW_EUSAGE.  Nothing is built until the whole command line has
 * been read.  The scene is then built by the program's build() from the param
 * values and compiled; when neither --dt nor the model fixes the step, the
 * scene is compiled once to read its stable step estimate and again at half of
 * it (the damping factors of a model depend on dt, so dt cannot be patched into
 * a compiled model).  A step above the estimate is allowed, with a warning: the
 * estimate is conservative and the user may know better.  --info prints the
 * compiled scene and stops; otherwise the run writes HDF5 through output.c,
 * closes the file with a status that says how the run ended, prints a one-line
 * summary and returns sw_run()'s code as the exit code.  A model with an
 * objective (maximize, minimize) also gets it printed and stored at the end
 * of the run (evaluate.c), and its ranges and objective shown by --info
 * and --help.  --threads N runs each
 * step on N OpenMP threads ("auto": one per 8192 elastic slots of the model,
 * up to the processors this process may use);
 * the default is 1, because most simulators run beside others (a sweep, an
 * optimiser, the test suite), where one process per core beats threads that
 * meet at a barrier several times a step, and because the results are the
 * same bits for any N, so asking for more is only ever a question of speed. */
#include <ctype.h>
#include <omp.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <unistd.h>
#include <sys/stat.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sinew.h"
#include "engine/internal.h"
#include "io/params.h"
#include "study/study.h"

/* ---- the options ---- */

typedef enum {
  OPT_OUT, OPT_DURATION, OPT_DT, OPT_INTEGRATOR, OPT_EVERY, OPT_SET, OPT_THREADS, OPT_COMPARE,
  OPT_RTOL, OPT_RESTART, OPT_SWEEP, OPT_OPTIMIZE, OPT_BUDGET, OPT_POPSIZE, OPT_SIGMA,
  OPT_RESTARTS, OPT_START, OPT_SEED, OPT_STUDY, OPT_RESUME, OPT_EVAL_TIMEOUT, OPT_QUIET, OPT_INFO,
  OPT_HELP
} swOptionId;

typedef struct {
  swOptionId id;
  const char *name;
  const char *arg;           /* what the value is called; NULL for a flag   */
  const char *help;
} swOption;

static const swOption options[] = {
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
  {OPT_EVAL_TIMEOUT, "--eval-timeout", "T", "under mpirun: re-queue an evaluation a rank holds "
   "longer than T"},
  {OPT_QUIET, "--quiet", NULL, "no progress line, notes or summary"},
  {OPT_INFO, "--info", NULL, "print the compiled scene and exit"},
  {OPT_HELP, "--help", NULL, "print this help and exit"},
};
#define NOPTIONS (sizeof options / sizeof options[0])

static const signed char DIM_NONE[SW_NDIM] = {0, 0, 0, 0};
static const signed char DIM_TIME[SW_NDIM] = {0, 0, 1, 0};

/* What the command line asked for. */
typedef struct {
  const swProgram *p;
  const char *prog;          /* basename of argv[0], prefix of messages     */
  const char *out;           /* output path                                 */
  double duration, every, dt;
  int dt_given;              /* --dt was given                              */
  int duration_given;        /* --duration was given                        */
  int integrator;            /* --integrator, or -1: the model's            */
  long threads;
  int threads_set;           /* given on the command line */
  int threads_auto;          /* --threads auto: chosen for the model */
  int quiet, info, help;
  const char *golden;        /* --compare: the stored run, or NULL          */
  double rtol;               /* its tolerance (--rtol; default 1e-9)        */
  int rtol_given;
  const char *restart;       /* --restart: the run to continue, or NULL     */
  int out_given, every_given;
  double *P;                 /* (nparam) param values, SI                   */
  char *overridden;          /* (nparam) set by --set                       */
  char *started;             /* (nparam) given a start by --start NAME=VALUE */
  swStudyArgs study;         /* --sweep, --optimize, --resume and theirs     */
} swCli;

static int complain(const swCli *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int complain(const swCli *c, const char *fmt, ...) {
  va_list ap;
  fprintf(stderr, "%s: ", c->prog);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
  fflush(stderr);
  return SW_EUSAGE;
}

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

/* ---- values ---- */

/* "50 ns", "1.5 ms", "2 s": the unit that keeps the number readable. */
static const char *format_time(char *buf, size_t len, double t) {
  double a = fabs(t);
  if (a == 0 || !isfinite(a) || a >= 1) snprintf(buf, len, "%.6g s", t);
  else if (a >= 1e-3) snprintf(buf, len, "%.6g ms", t * 1e3);
  else if (a >= 1e-6) snprintf(buf, len, "%.6g us", t * 1e6);
  else snprintf(buf, len, "%.6g ns", t * 1e9);
  return buf;
}

static const char *format_bytes(char *buf, size_t len, double bytes) {
  if (bytes < 1024) snprintf(buf, len, "%.0f B", bytes);
  else if (bytes < 1024 * 1024) snprintf(buf, len, "%.1f KiB", bytes / 1024);
  else if (bytes < 1024.0 * 1024 * 1024) snprintf(buf, len, "%.1f MiB", bytes / (1024 * 1024));
  else snprintf(buf, len, "%.2f GiB", bytes / (1024.0 * 1024 * 1024));
  return buf;
}

static const char *format_wall(char *buf, size_t len, double seconds) {
  if (seconds < 60) snprintf(buf, len, "%.3g s", seconds);
  else if (seconds < 3600)
    snprintf(buf, len, "%d min %02d s", (int)(seconds / 60), (int)fmod(seconds, 60));
  else snprintf(buf, len, "%d h %02d min", (int)(seconds / 3600), (int)fmod(seconds / 60, 60));
  return buf;
}

/* A param's value in the unit the model wrote it in, or in SI when that unit
 * cannot be read or does not fit the param's dimension; the unit's name in
 * *unit ("" when dimensionless).  For --help, --info and /params. */
static double param_in_unit(const swParam *q, double value, char *unit, size_t len) {
  if (q->unit && q->unit[0]) {
    char text[96];
    double scale;
    signed char dim[SW_NDIM];
    snprintf(text, sizeof text, "1 %s", q->unit);
    if (!sw_parse_quantity(text, &scale, dim, NULL, 0) && !memcmp(dim, q->dim, SW_NDIM) &&
        scale != 0) {
      snprintf(unit, len, "%s", q->unit);
      return value / scale;
    }
  }
  unit[0] = '\0';
  if (memcmp(q->dim, DIM_NONE, SW_NDIM)) {
    /* "length (m)" -> "m"; "kg m^-1 s^-2" as it is */
    char what[64];
    const char *d = sw_dim_describe(what, sizeof what, q->dim), *open = strchr(d, '(');
    if (open) snprintf(unit, len, "%.*s", (int)strcspn(open + 1, ")"), open + 1);
    else snprintf(unit, len, "%s", d);
  }
  return value;
}

/* "0.3 m", "0.3 (SI, length (m))", "2" */
static const char *format_param(char *buf, size_t len, const swParam *q, double value) {
  char unit[48], what[64];
  double v = param_in_unit(q, value, unit, sizeof unit);
  if (q->unit && q->unit[0] && !strcmp(unit, q->unit)) snprintf(buf, len, "%.6g %s", v, unit);
  else if (unit[0])
    snprintf(buf, len, "%.6g (SI, %s)", v, sw_dim_describe(what, sizeof what, q->dim));
  else snprintf(buf, len, "%.6g", v);
  return buf;
}

/* "in (0 N, 50 N)": a param's range in its unit ("" without one). */
static const char *format_range(char *buf, size_t len, const swParam *q) {
  char lo[48], hi[48], unit[48];
  if (!q->ranged) {
    snprintf(buf, len, "%s", "");
    return buf;
  }
  snprintf(lo, sizeof lo, "%.6g", param_in_unit(q, q->lo, unit, sizeof unit));
  snprintf(hi, sizeof hi, "%.6g", param_in_unit(q, q->hi, unit, sizeof unit));
  if (unit[0]) snprintf(buf, len, "in (%s %s, %s %s)", lo, unit, hi, unit);
  else snprintf(buf, len, "in (%s, %s)", lo, hi);
  return buf;
}

/* The model's objective, for --help and --info. */
static void print_objective(const swProgram *p) {
  printf("objective: %s  # %s\n", p->objective_text, p->objective_where);
  printf("  shown in %s; %d penalt%s; score = %s\n",
         p->objective_unit[0] ? p->objective_unit : "no unit (a plain number)", p->npenalty,
         p->npenalty == 1 ? "y" : "ies",
         p->sense > 0 ? "objective - penalties" : "-(objective + penalties)");
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
  if (!c->quiet) {
    const char *u = p->objective_unit, *space = u[0] ? " " : "";
    const double k = p->objective_scale > 0 ? p->objective_scale : 1;
    if (rc == SW_OK)
      fprintf(stderr, "%s: objective: %s = %.9g%s%s; penalty %.9g%s%s; score %.9g%s%s\n",
              c->prog, p->objective_text, value / k, space, u, penalty / k, space, u,
              score / k, space, u);
    else fprintf(stderr, "%s: objective: %s: not reached (%s)\n", c->prog, p->objective_text,
                 why);
    fflush(stderr);
  }
  if (rc != SW_OK) value = penalty = score = NAN;
  if (sw_output_objective(o, p->objective_text, value, penalty, score,
                          p->objective_si_unit) == SW_OK)
    return SW_OK;
  complain(c, "%s", sw_output_error());
  return SW_EIO;
}

/* ---- reading the command line ---- */

/* --duration, --dt, --every: a time, or a bare number of seconds. */
static int read_time(const swCli *c, const char *opt, const char *value, int positive,
                     double *seconds) {
  char err[256], expected[64], got[64];
  double t;
  signed char dim[SW_NDIM];
  if (sw_parse_quantity(value, &t, dim, err, sizeof err))
    return complain(c, "%s: %s", opt, err);
  if (memcmp(dim, DIM_TIME, SW_NDIM) && memcmp(dim, DIM_NONE, SW_NDIM))
    return complain(c, "%s: expected %s, got %s in '%s'", opt,
                    sw_dim_describe(expected, sizeof expected, DIM_TIME),
                    sw_dim_describe(got, sizeof got, dim), value);
  if (positive && !(t > 0)) return complain(c, "%s: must be positive, got '%s'", opt, value);
  if (!(t >= 0)) return complain(c, "%s: must not be negative, got '%s'", opt, value);
  *seconds = t + 0.0; /* no -0 */
  return SW_OK;
}

#define MAX_THREADS 256
/* --threads auto: a thread per AUTO_SLOTS elastic slots, up to the
 * processors: below about 10^4 elements a second thread does not pay on a
 * two-core machine (docs/performance.md, "Threads"). */
#define AUTO_SLOTS 8192

static long auto_threads(const swModel *m) {
  long n = m->nslot_elastic / AUTO_SLOTS;
  if (n > omp_get_num_procs()) n = omp_get_num_procs();
  return n < 1 ? 1 : n;
}

static long threads_for(const swCli *c, const swModel *m) {
  return c->threads_auto ? auto_threads(m) : c->threads;
}

static int read_threads(swCli *c, const char *value) {
  if (!strcmp(value, "auto")) {
    c->threads_auto = 1;
    return SW_OK;
  }
  char *end;
  errno = 0;
  long n = strtol(value, &end, 10);
  if (!isdigit((unsigned char)value[0]) || *end || errno || n < 1)
    return complain(c, "--threads: expected a positive integer or 'auto', got '%s'", value);
  if (n > MAX_THREADS)
    return complain(c, "--threads: at most %d, got '%s'", MAX_THREADS, value);
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
      return complain(c, "--integrator: unknown integrator '%s' (did you mean '%s'?)", value,
                      integrator_names[k]);
  return complain(c, "--integrator: unknown integrator '%s' (verlet, pefrl or imex)", value);
}

/* --set NAME=VALUE (start 0: the param is fixed at VALUE) or --start
 * NAME=VALUE (start 1: a study starts it there and varies it): VALUE must
 * have the param's dimension. */
static int read_param_value(swCli *c, int start, const char *value) {
  const swProgram *p = c->p;
  const char *opt = start ? "--start" : "--set";
  const char *eq = strchr(value, '=');
  if (!eq || eq == value) return complain(c, "%s: expected NAME=VALUE, got '%s'", opt, value);
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
      return complain(c, "%s: unknown param '%.*s' (did you mean '%s'?)", opt, (int)len, value,
                      p->param[best].name);
    if (p->nparam == 0)
      return complain(c, "%s: unknown param '%.*s' (the model has no params)", opt, (int)len,
                      value);
    char list[512] = "";
    size_t used = 0;
    for (int i = 0; i < p->nparam && used < sizeof list; i++) {
      int n = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", p->param[i].name);
      if (n < 0) break;
      used += (size_t)n;
    }
    return complain(c, "%s: unknown param '%.*s' (the params are: %s)", opt, (int)len, value,
                    list);
  }

  const swParam *q = &p->param[k];
  const char *text = eq + 1;
  char err[256], expected[64], got[64];
  double v;
  signed char dim[SW_NDIM];
  if (sw_parse_quantity(text, &v, dim, err, sizeof err))
    return complain(c, "%s %s: %s", opt, q->name, err);
  if (memcmp(dim, q->dim, SW_NDIM)) {
    sw_dim_describe(expected, sizeof expected, q->dim);
    if (!memcmp(dim, DIM_NONE, SW_NDIM)) {
      if (q->unit && q->unit[0])
        return complain(c, "%s %s: expected %s, got a number without a unit in '%s' "
                        "(write e.g. '%s %s')", opt, q->name, expected, text, text, q->unit);
      return complain(c, "%s %s: expected %s, got a number without a unit in '%s'", opt,
                      q->name, expected, text);
    }
    return complain(c, "%s %s: expected %s, got %s in '%s'", opt, q->name, expected,
                    sw_dim_describe(got, sizeof got, dim), text);
  }
  if (start) {
    if (!q->ranged)
      return complain(c, "--start %s: the param has no range, so no study varies it (--set "
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
    return complain(c, "%s: expected a whole number from %ld to %ld, got '%s'", opt, lo, hi,
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
  return complain(c, "--sweep: expected grid:K (K points per ranged param) or lhs:N (N "
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
      return complain(c, "--seed: expected a whole number from 0 to 2^64 - 1, got '%s'", value);
    a->seed = (uint64_t)v;
    a->seed_given = 1;
    return SW_OK;
  }
  case OPT_SIGMA: {
    char *end = NULL;
    a->sigma = strtod(value, &end);
    a->sigma_given = 1;
    if (end == value || *end || !(a->sigma > 0 && a->sigma <= 1))
      return complain(c, "--sigma: expected a fraction of each param's range in (0, 1], got "
                      "'%s'", value);
    return SW_OK;
  }
  case OPT_START: {
    a->start_given = 1;
    /* NAME=VALUE when what precedes '=' is a name, else a file's path */
    size_t name_len = strspn(value, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                    "0123456789_");
    if (name_len && value[name_len] == '=') return read_param_value(c, 1, value);
    if (!value[0]) return complain(c, "--start: empty file name");
    if (a->start)
      return complain(c, "--start %s: a study starts from one file, and --start %s was given",
                      value, a->start);
    a->start = value;
    return SW_OK;
  }
  case OPT_STUDY:
    if (!value[0]) return complain(c, "--study: empty file name");
    a->study = value;
    return SW_OK;
  case OPT_RESUME:
    if (!value[0]) return complain(c, "--resume: empty file name");
    a->resume = value;
    return SW_OK;
  case OPT_EVAL_TIMEOUT:
    return read_time(c, "--eval-timeout", value, 1, &a->eval_timeout);
  default:
    return SW_OK;
  }
}

/* The study options, together: which belong to which, and what cannot mix. */
static int check_study_args(const swCli *c) {
  const swStudyArgs *a = &c->study;
  int optimize_only = a->budget_given || a->popsize_given || a->sigma_given || a->restarts_given ||
                      a->start_given;
  if (a->resume && a->study)
    return complain(c, "--resume %s continues that file: --study %s cannot name another",
                    a->resume, a->study);
  if (a->resume && a->start_given)
    return complain(c, "--resume %s starts where that study stopped: leave out --start",
                    a->resume);
  if (a->resume && a->kind_given)
    return complain(c, "--resume takes the sweep or optimisation from its file: leave out "
                    "--sweep and --optimize");
  if (!a->mode && !a->resume) {
    if (optimize_only || a->seed_given || a->study || a->eval_timeout > 0)
      return complain(c, "--budget, --popsize, --sigma, --restarts, --start, --seed, --study "
                      "and --eval-timeout belong to --sweep or --optimize, which was not given");
    return SW_OK;
  }
  if (a->mode == 1 && optimize_only)
    return complain(c, "--budget, --popsize, --sigma, --restarts and --start belong to "
                    "--optimize, not --sweep");
  if (c->restart || c->golden || c->out_given || c->every_given || c->info)
    return complain(c, "a sweep or optimisation writes its study file (--study), not a run: "
                    "leave out --out, --every, --restart, --compare and --info");
  return SW_OK;
}

static int unknown_option(const swCli *c, const char *arg, size_t len) {
  const char *bare = arg;             /* compared without its dashes */
  while (*bare == '-' && (size_t)(bare - arg) < len) bare++;
  size_t bare_len = len - (size_t)(bare - arg);
  const swOption *best = NULL;
  int best_distance = INT_MAX;
  for (size_t i = 0; i < NOPTIONS; i++) {
    int distance = sw_edit_distance(bare, bare_len, options[i].name + 2);
    if (distance < best_distance) best = &options[i], best_distance = distance;
  }
  if (best && bare_len && close_enough(best_distance, bare_len))
    return complain(c, "unknown option '%.*s' (did you mean '%s'?)", (int)len, arg, best->name);
  return complain(c, "unknown option '%.*s' (see --help)", (int)len, arg);
}

static int parse_args(swCli *c, int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    const char *arg = argv[i];
    if (arg[0] != '-' || !arg[1])
      return complain(c, "unexpected argument '%s' (options start with '--'; see --help)", arg);
    if (!strcmp(arg, "-h")) {
      c->help = 1;
      continue;
    }
    const char *eq = strchr(arg, '=');
    size_t len = eq ? (size_t)(eq - arg) : strlen(arg);
    const swOption *opt = NULL;
    for (size_t k = 0; k < NOPTIONS && !opt; k++)
      if (strlen(options[k].name) == len && !strncmp(options[k].name, arg, len))
        opt = &options[k];
    if (!opt) return unknown_option(c, arg, len);

    const char *value = NULL;
    if (opt->arg) {
      if (eq) value = eq + 1;
      else if (i + 1 < argc && strncmp(argv[i + 1], "--", 2)) value = argv[++i];
      else return complain(c, "%s: missing value (%s %s)", opt->name, opt->name, opt->arg);
    } else if (eq) {
      return complain(c, "%s takes no value, got '%s'", opt->name, arg);
    }

    int rc = SW_OK;
    switch (opt->id) {
    case OPT_OUT:
      if (!value[0]) rc = complain(c, "--out: empty file name");
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
      if (!value[0]) rc = complain(c, "--restart: empty file name");
      c->restart = value;
      break;
    case OPT_SET: rc = read_param_value(c, 0, value); break;
    case OPT_THREADS: rc = read_threads(c, value); c->threads_set = 1; break;
    case OPT_COMPARE:
      if (!value[0]) rc = complain(c, "--compare: empty file name");
      c->golden = value;
      break;
    case OPT_RTOL: {
      char *end = NULL;
      c->rtol = strtod(value, &end);
      c->rtol_given = 1;
      if (end == value || *end || !(c->rtol >= 0) || !isfinite(c->rtol))
        rc = complain(c, "--rtol: expected a number >= 0 (a fraction: 1e-6), got '%s'", value);
      break;
    }
    case OPT_SWEEP: rc = read_sweep(c, value); break;
    case OPT_OPTIMIZE: case OPT_BUDGET: case OPT_POPSIZE: case OPT_SIGMA: case OPT_RESTARTS:
    case OPT_START: case OPT_SEED: case OPT_STUDY: case OPT_RESUME: case OPT_EVAL_TIMEOUT:
      rc = read_study_option(c, opt->id, value);
      break;
    case OPT_QUIET: c->quiet = 1; break;
    case OPT_INFO: c->info = 1; break;
    case OPT_HELP: c->help = 1; break;
    }
    if (rc != SW_OK) return rc;
  }
  if (c->rtol_given && !c->golden) return complain(c, "--rtol is the tolerance of --compare, "
                                                  "which was not given");
  if (c->restart && c->out_given && strcmp(c->out, c->restart))
    return complain(c, "--restart %s continues that file: --out %s cannot name another",
                    c->restart, c->out);
  if (c->restart) c->out = c->restart;
  return check_study_args(c);
}

/* --restart: the params (those not given with --set), the time step and
 * the frame interval (unless --dt, --every are given) of the run being
 * continued. */
static int read_restart(swCli *c) {
  char params[8192], sha256[65];
  double dt, every;
  if (access(c->restart, R_OK) != 0) {
    complain(c, "--restart: cannot read '%s': %s", c->restart, strerror(errno));
    return SW_EIO;
  }
  if (sw_output_read_run(c->restart, sha256, params, sizeof params, &dt, &every) != SW_OK) {
    complain(c, "--restart: %s", sw_output_error());
    return SW_EIO;
  }
  if (strcmp(sha256, c->p->sha256 ? c->p->sha256 : "")) {
    complain(c, "--restart: %s was written by another model (model_sha256 %.12s..., this "
             "model's %.12s...)", c->restart, sha256, c->p->sha256 ? c->p->sha256 : "");
    return SW_EIO;
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

/* ---- --help ---- */

static void print_help(const swCli *c, const char *default_out) {
  const swProgram *p = c->p;
  char buf[128];
  printf("usage: %s [options]\n\n", c->prog);
  printf("Simulates the sinew model '%s' and writes its output as HDF5.\n\n", p->name);
  printf("options:\n");
  for (size_t i = 0; i < NOPTIONS; i++) {
    const swOption *o = &options[i];
    char head[64];
    snprintf(head, sizeof head, "%s%s%s", o->name, o->arg ? " " : "", o->arg ? o->arg : "");
    const char *def = NULL;
    switch (o->id) {
    case OPT_OUT: def = default_out; break;
    case OPT_DURATION: def = format_time(buf, sizeof buf, p->duration); break;
    case OPT_DT:
      def = p->dt > 0 ? format_time(buf, sizeof buf, p->dt) : "half the stable estimate";
      break;
    case OPT_EVERY: def = p->every > 0 ? format_time(buf, sizeof buf, p->every) : "every step";
      break;
    case OPT_THREADS: def = "1; the results are the same for any N"; break;
    case OPT_INTEGRATOR: def = "the model's"; break;
    case OPT_RTOL: def = "1e-9"; break;
    case OPT_BUDGET: def = "1000"; break;
    case OPT_POPSIZE: def = "4 + floor(3 ln n), n the ranged params"; break;
    case OPT_SIGMA: def = "0.25"; break;
    case OPT_RESTARTS: def = "0"; break;
    case OPT_START: def = "each param's value: its default, or --set"; break;
    case OPT_SEED: def = "1"; break;
    case OPT_STUDY: def = buf, snprintf(buf, sizeof buf, "%s_study.h5", p->name); break;
    case OPT_EVAL_TIMEOUT: def = "20 times the slowest evaluation, at least 60 s"; break;
    default: break;
    }
    printf("  %-18s %s", head, o->help);
    if (def) printf(" (default: %s)", def);
    printf("\n");
  }
  printf("An option takes its value as '--dt 50ns' or '--dt=50ns'. Times take a unit\n"
         "(s, ms, us, ns, min, h); a number without one is in seconds.\n\n");

  if (p->nparam) {
    int width = 4, what_width = 0;
    char what[64];
    for (int i = 0; i < p->nparam; i++) {
      int n = (int)strlen(p->param[i].name);
      int w = (int)strlen(sw_dim_describe(what, sizeof what, p->param[i].dim));
      if (n > width) width = n;
      if (w > what_width) what_width = w;
    }
    int range_width = 0;
    for (int i = 0; i < p->nparam; i++) {
      int n = (int)strlen(format_range(buf, sizeof buf, &p->param[i]));
      if (n > range_width) range_width = n;
    }
    printf("params (--set NAME=VALUE, VALUE in the dimension shown%s):\n",
           range_width ? "; a study varies those with a range" : "");
    for (int i = 0; i < p->nparam; i++) {
      const swParam *q = &p->param[i];
      char value[96], range[200];
      format_param(value, sizeof value, q, q->value);
      format_range(range, sizeof range, q);
      sw_dim_describe(what, sizeof what, q->dim);
      printf("  %-*s = %-12s ", width, q->name, value);
      if (range_width) printf("%-*s ", range_width, range);
      if (q->where && q->where[0]) printf("%-*s  %s\n", what_width, what, q->where);
      else printf("%s\n", what);
    }
    printf("\n");
  } else {
    printf("The model has no params.\n\n");
  }
  if (p->sense) {
    print_objective(p);
    printf("\n");
  }
  printf("exit status: 0 ok, 1 model error, 2 usage error, 3 the simulation became\n"
         "unstable, 4 I/O error, 5 an expect of the model (or --compare) failed, 130\n"
         "interrupted (the file holds every frame written).\n");
  fflush(stdout);
}

/* ---- building ---- */

/* Builds and compiles the scene at the step asked for, or at half the stable
 * estimate.  Returns the model, or NULL with the exit code in *rc. */
static swModel *build_model(const swCli *c, double *stable, const char **dt_source, int *rc) {
  const swProgram *p = c->p;
  char err[512] = "";
  *dt_source = c->dt_given ? "--dt" : p->dt > 0 ? "from the model" : "half the stable estimate";
  /* the step sw_evaluate takes too (evaluate.c) */
  swModel *m = sw_program_compile(p, c->P, c->dt_given ? c->dt : 0, c->integrator, c->every,
                                  stable, rc, err, sizeof err);
  if (!m) {
    complain(c, "%s", err);
    return NULL;
  }
  long nsteps;
  char why[256];
  if (sw_step_count(c->duration, m->dt, &nsteps, why, sizeof why) != SW_OK) {
    complain(c, "no run: %s (dt: %s; duration: %s)", why, *dt_source,
             c->duration_given ? "--duration" : "from the model");
    sw_model_free(m);
    *rc = SW_EUSAGE;
    return NULL;
  }
  if (m->dt > *stable) {
    char dt_text[32], stable_text[32];
    fprintf(stderr, "%s: warning: dt = %s is above the stable estimate %s; the run may "
            "become unstable\n", c->prog, format_time(dt_text, sizeof dt_text, m->dt),
            format_time(stable_text, sizeof stable_text, *stable));
    fflush(stderr);
  }
  *rc = SW_OK;
  return m;
}

static char *params_string(const swCli *c) {
  const swProgram *p = c->p;
  const char *names[p->nparam > 0 ? p->nparam : 1];
  for (int i = 0; i < p->nparam; i++) names[i] = p->param[i].name;
  return sw_params_text(p->nparam, names, c->P);
}

/* ---- --info ---- */

/* Approximate bytes of the model's and the state's arrays (sinew.h lists
 * them with their shapes: per slot, joint, filament, body).  A per-slot
 * array is planar (sinew.h, "Layout"): one plane of m->stride doubles per
 * scalar, three per vector, nine per frame, whatever the slot holds. */
static double model_bytes(const swModel *m) {
  double b = sizeof *m;
  b += (double)m->nrod * (sizeof(char *) + 4 * sizeof(int) + sizeof(double) + sizeof(swDampingKind));
  for (int r = 0; r < m->nrod; r++) b += m->rod_name[r] ? (double)strlen(m->rod_name[r]) + 1 : 0;
  /* planes of the node (8), element (36) and Voronoi (7) arrays */
  b += sizeof(double) * ((8.0 + 36.0 + 7.0) * m->stride);
  b += (double)m->nload * sizeof(swLoadDesc) + (double)m->nbc * sizeof(swBCDesc);
  /* per joint: description, name, 4 indices, axes (2x3), rest rotation (9),
   * initial angle and stable dt */
  b += (double)m->njoint * (sizeof(swJointDesc) + sizeof(char *) + 4 * sizeof(int) +
                            17 * sizeof(double));
  /* per muscle: name, first filament, activation signal; per filament: 2
   * ints and 10 doubles */
  b += (double)m->nmuscle * (sizeof(char *) + sizeof(int) + sizeof(swSignal));
  b += (double)m->nfil * (2 * sizeof(int) + 10 * sizeof(double));
  /* rigid rods: per rod its body, per body 4 indices and 16 numbers, per
   * node of a body p (3), per element B (9) */
  b += (double)m->nrod * sizeof(int) + (double)m->nrigid * (4 * sizeof(int) + 16 * sizeof(double));
  for (int k = 0; k < m->nrigid; k++)
    b += sizeof(double) * (3.0 * (m->rod_nelem[m->rigid_rod[k]] + 1) + 9.0 * m->rod_nelem[m->rigid_rod[k]]);
  /* torque waves: per node of each wave's rod s, beta and 2 phase terms */
  if (m->nwave) b += 4.0 * sizeof(double) * m->wave_node_adr[m->nwave];
  return b;
}

static double data_bytes(const swModel *m) {
  /* planes of the node (12), element (26) and Voronoi (7) arrays */
  return sizeof(swData) + sizeof(double) * ((12.0 + 26.0 + 7.0) * m->stride +
                                            4.0 * m->njoint + 4.0 * m->nfil + 21.0 * m->nrigid) +
         (double)m->nprobe * (4.0 * SW_PROBE_RING * sizeof(double) + 2 * sizeof(int));
}

/* Frames a run of nsteps steps writes (run.c: step 0, every k steps, the last). */
static long frame_count(long nsteps, double every, double dt) {
  const double k_steps = every > 0 ? round(every / dt) : 1;
  long k = k_steps > (double)nsteps ? nsteps + 1 : (long)k_steps;
  if (k < 1) k = 1;
  return 1 + nsteps / k + (nsteps % k != 0);
}

/* The rods an environment acts on: "all rods" or "rods a, b". */
static const char *rod_list(char *buf, size_t len, const swModel *m, int nrods, const int *rods) {
  if (nrods == m->nrod) return "all rods";
  size_t used = (size_t)snprintf(buf, len, "rod%s", nrods == 1 ? "" : "s");
  for (int k = 0; k < nrods && used < len; k++)
    used += (size_t)snprintf(buf + used, len - used, "%s %s", k ? "," : "", m->rod_name[rods[k]]);
  return buf;
}

/* Grounds, fluids, contacts, torque waves and probes, one line each. */
static void print_environments(const swModel *m) {
  char a[256], b[64];
  printf("environments: %d grounds, %d fluids, %d contacts, %d torque waves, %d probes\n",
         m->nground, m->nfluid, m->ncontact, m->nwave, m->nprobe);
  for (int k = 0; k < m->nground; k++) {
    const swGroundDesc *g = &m->ground[k];
    printf("  ground %s: %s, stiffness %g N/m, damping %g kg/s, kinetic friction %g/%g/%g "
           "(forward/backward/sideways), static %g/%g/%g, %s\n", g->name,
           g->height ? "terrain" : "plane", g->stiffness, g->damping, g->mu_kinetic[0],
           g->mu_kinetic[1], g->mu_kinetic[2], g->mu_static[0], g->mu_static[1], g->mu_static[2],
           rod_list(a, sizeof a, m, g->nrods, g->rods));
  }
  for (int k = 0; k < m->nfluid; k++) {
    const swFluidDesc *f = &m->fluid[k];
    if (f->model == SW_FLUID_STOKES)
      printf("  fluid %s: Stokes drag, viscosity %g Pa s", f->name, f->viscosity);
    else
      printf("  fluid %s: quadratic drag, density %g kg/m^3, C_d %g", f->name, f->density,
             f->drag_coefficient);
    printf("%s, %s\n", f->buoyancy ? ", buoyancy" : "", rod_list(a, sizeof a, m, f->nrods, f->rods));
  }
  for (int k = 0; k < m->ncontact; k++) {
    const swContactDesc *c = &m->contact[k];
    printf("  contact %s: stiffness %g N/m, damping %g kg/s%s, %s\n", c->name, c->stiffness,
           c->damping, c->self ? ", self-contact" : "", rod_list(a, sizeof a, m, c->nrods, c->rods));
  }
  for (int k = 0; k < m->nwave; k++) {
    const swWaveDesc *w = &m->wave[k];
    double peak = 0;
    for (int i = m->wave_node_adr[k]; i < m->wave_node_adr[k + 1]; i++)
      if (fabs(m->wave_beta[i]) > fabs(peak)) peak = m->wave_beta[i];
    printf("  torque wave %s: rod %s, %d coefficients (peak beta %g N m), wavelength %g m, "
           "period %g s, about (%g, %g, %g), from the rod's %s\n", w->name, m->rod_name[w->rod],
           w->ncoef, peak, w->wavelength, w->period, w->direction[0], w->direction[1],
           w->direction[2], w->reverse ? "end" : "start");
  }
  for (int k = 0; k < m->nprobe; k++) {
    const swProbeDesc *p = &m->probe[k];
    if (p->kind == SW_PROBE_NODE)
      printf("  probe %s: node_position, node %d of rod %s\n", p->name, p->node,
             m->rod_name[p->rod]);
    else if (p->kind == SW_PROBE_MEAN_VELOCITY)
      printf("  probe %s: mean_velocity over %s (%s)\n", p->name,
             p->window > 0 ? format_time(b, sizeof b, p->window) : "the frame interval",
             rod_list(a, sizeof a, m, p->nrods, p->rods));
    else
      printf("  probe %s: %s (%s)\n", p->name, sw_probe_kind_name(p->kind),
             rod_list(a, sizeof a, m, p->nrods, p->rods));
  }
}

/* What the scheme treats apart from the explicit kick: rods held rigid and
 * (imex) the implicit terms, the filaments' Hill damping and the joints
 * between rigid bodies; filaments a scene could make implicit but whose
 * scheme keeps explicit are named with the step they cost. */
static void print_stiff_parts(const swModel *m) {
  char a[64];
  int nrigid = 0, nimplicit = 0;
  for (int r = 0; r < m->nrod; r++) nrigid += m->nrigid && m->rod_rigid[r] >= 0;
  for (int f = 0; f < m->nfil; f++) nimplicit += (m->fil_implicit[f] & SW_FIL_IMPLICIT) != 0;
  if (nrigid) {
    printf("  held rigid (one body each, no elastic waves): %d rod%s:", nrigid, nrigid == 1 ? "" : "s");
    for (int r = 0, k = 0; r < m->nrod && k < 8; r++)
      if (m->rod_rigid[r] >= 0) printf("%s %s", k++ ? "," : "", m->rod_name[r]);
    printf("%s\n", nrigid > 8 ? ", ..." : "");
  }
  if (nimplicit)
    printf("  linearly implicit: the Hill damping of %d of %d muscle filaments\n", nimplicit, m->nfil);
  int nrod_implicit = 0;
  for (int r = 0; r < m->nrod; r++) nrod_implicit += m->rod_implicit[r];
  if (nrod_implicit) {
    printf("  %s: the elasticity and linear damping of %d rod%s:",
           m->nimplicit ? "trapezoidal (implicit)" : "explicit, implicit only under imex",
           nrod_implicit, nrod_implicit == 1 ? "" : "s");
    for (int r = 0, k = 0; r < m->nrod && k < 8; r++)
      if (m->rod_implicit[r]) printf("%s %s", k++ ? "," : "", m->rod_name[r]);
    printf("%s\n", nrod_implicit > 8 ? ", ..." : "");
  }
  int njimplicit = 0;
  for (int j = 0; j < m->njoint; j++) njimplicit += m->joint_implicit[j];
  if (njimplicit)
    printf("  trapezoidal (implicit): %d of %d joints, those between rigid bodies (%d bod%s "
           "in %d independent group%s)\n", njimplicit, m->njoint, m->nrigid_block,
           m->nrigid_block == 1 ? "y" : "ies", m->nrigid_group, m->nrigid_group == 1 ? "" : "s");
  if (m->nfil > nimplicit) {
    double worst = INFINITY;
    for (int f = 0; f < m->nfil; f++)
      if (!(m->fil_implicit[f] & SW_FIL_IMPLICIT))
        worst = fmin(worst, 0.95 * sw_muscle_ops(m)->stable_dt_filament(m, f));
    printf("  explicit: the Hill damping of %d muscle filament%s (alone it limits dt to %s%s)\n",
           m->nfil - nimplicit, m->nfil - nimplicit == 1 ? "" : "s", format_time(a, sizeof a, worst),
           m->integrator == SW_IMEX ? "; a prescribed velocity or analytic damping keeps it explicit"
                                    : "; integrator = imex makes it implicit");
  }
}

/* The rods' constitutive law (rod.c): Gazzola's unless a material says
 * variational; the elastic ones of each law are named (rigid rods have
 * none). */
static void print_law(const swModel *m) {
  int nelastic = 0;
  for (int r = 0; r < m->nrod; r++) nelastic += !(m->nrigid && m->rod_rigid[r] >= 0);
  if (!m->nvariational) {
    printf("constitutive law: Gazzola et al. 2018 (n = S^ s / e, c = B^ k / eps^3), all %d elastic rod%s\n",
           nelastic, nelastic == 1 ? "" : "s");
    return;
  }
  printf("constitutive law: variational (loads the gradient of the elastic energy) on %d of %d "
         "elastic rod%s:", m->nvariational, nelastic, nelastic == 1 ? "" : "s");
  for (int r = 0, k = 0; r < m->nrod && k < 8; r++)
    if (m->rod_law[r] == SW_LAW_VARIATIONAL && !(m->nrigid && m->rod_rigid[r] >= 0))
      printf("%s %s", k++ ? "," : "", m->rod_name[r]);
  printf("%s%s\n", m->nvariational > 8 ? ", ..." : "",
         m->nvariational < nelastic ? "; Gazzola et al. 2018 on the others" : "");
}

/* The part whose bound is the stable estimate: a rod, a joint, or the
 * environments. */
static void print_step_limit(const swModel *m, double stable) {
  char a[64];
  if (!isfinite(stable)) return;
  for (int r = 0; r < m->nrod; r++)
    if (m->rod_wave_dt[r] == stable) {
      printf("  set by rod %s (%s)\n", m->rod_name[r], format_time(a, sizeof a, stable));
      return;
    }
  for (int j = 0; j < m->njoint; j++)
    if (m->joint_wave_dt[j] == stable) {
      printf("  set by joint %s (%s)\n", m->joint_name[j], format_time(a, sizeof a, stable));
      return;
    }
  printf("  set by the environments (%s)\n", format_time(a, sizeof a, stable));
}

static void print_info(const swCli *c, const swModel *m, double stable, const char *dt_source,
                       const char *out) {
  const swProgram *p = c->p;
  char a[64], b[64], e[64];
  printf("model: %s\n", p->name ? p->name : "(unnamed)");
  printf("  sha256: %s\n", p->sha256 && p->sha256[0] ? p->sha256 : "(none)");
  printf("rods: %d (%d elements, %d nodes)\n", m->nrod, m->nelem, m->nnode);
  for (int r = 0; r < m->nrod; r++) {
    int n = m->rod_nelem[r], ea = m->elem_adr[r], na = m->node_adr[r];
    double length = 0, mass = 0;
    for (int i = 0; i < n; i++) length += m->rest_len[ea + i];
    for (int i = 0; i <= n; i++) mass += m->mass[na + i];
    double r0 = m->radius[ea], r1 = m->radius[ea + n - 1];
    printf("  %s: %d elements, length %.6g m, radius %.4g mm", m->rod_name[r], n, length,
           r0 * 1e3);
    if (r1 != r0) printf(" to %.4g mm", r1 * 1e3);
    printf(", mass %.6g kg, stable dt %s%s%s%s\n", mass,
           isinf(m->rod_wave_dt[r]) ? "none" : format_time(a, sizeof a, m->rod_wave_dt[r]),
           m->rod_damping[r] == SW_DAMP_ANALYTIC ? ", analytic damping"
           : m->rod_damping[r] == SW_DAMP_LINEAR ? ", linear damping" : "",
           m->nrigid && m->rod_rigid[r] >= 0 ? ", rigid" : m->nimplicit && m->rod_implicit[r] ? ", implicit" : "",
           m->weight && m->weight[na] == 0 && m->mass[na] > 0 ? ", weightless (no gravity)" : "");
  }
  printf("joints: %d\n", m->njoint);
  for (int j = 0; j < m->njoint; j++) {
    const char *name = m->joint_name && m->joint_name[j] ? m->joint_name[j]
                       : m->joint && m->joint[j].name ? m->joint[j].name : "(unnamed)";
    printf("  %s: %s\n", name, m->joint ? sw_joint_kind_name(m->joint[j].kind) : "joint");
  }
  printf("muscles: %d\n", m->nmuscle);
  for (int i = 0; i < m->nmuscle; i++) {
    const int f0 = m->muscle_fil_adr[i], f1 = m->muscle_fil_adr[i + 1];
    double fmax = 0, area = 0, fibres = 0;
    int passive = 0;
    for (int f = f0; f < f1; f++) {
      fmax += m->fil_fmax[f];
      area += m->fil_area[f];
      fibres += m->fil_fibres[f];
      passive += m->fil_passive[f];
    }
    printf("  %s: %d filaments (%.4g to %.4g mm^2, %.0f fibres), F_max %.6g N, l0 %.6g m, "
           "twitch %s to %s", m->muscle_name[i], f1 - f0, m->fil_area[f0] * 1e6,
           m->fil_area[f1 - 1] * 1e6, fibres, fmax, m->fil_l0[f0],
           format_time(a, sizeof a, m->fil_tau[f0]), format_time(b, sizeof b, m->fil_tau[f1 - 1]));
    if (passive) printf(", %d passive", passive);
    printf("\n");
    (void)area;
  }
  print_environments(m);
  int nforce = 0, ntorque = 0, nclamp = 0, nvel = 0, nomega = 0;
  for (int k = 0; k < m->nload; k++) {
    if (m->load[k].kind == SW_LOAD_TORQUE) ntorque++;
    else nforce++;
  }
  for (int k = 0; k < m->nbc; k++)
    switch (m->bc[k].kind) {
    case SW_BC_CLAMP: nclamp++; break;
    case SW_BC_VELOCITY: nvel++; break;
    case SW_BC_OMEGA: nomega++; break;
    }
  printf("loads: %d (%d point force%s, %d point couple%s)\n", m->nload, nforce,
         nforce == 1 ? "" : "s", ntorque, ntorque == 1 ? "" : "s");
  printf("boundary conditions: %d (%d clamped end%s, %d prescribed velocit%s, "
         "%d prescribed angular velocit%s)\n", m->nbc, nclamp, nclamp == 1 ? "" : "s", nvel,
         nvel == 1 ? "y" : "ies", nomega, nomega == 1 ? "y" : "ies");
  if (m->has_gravity)
    printf("gravity: (%g, %g, %g) m/s^2\n", m->gravity[0], m->gravity[1], m->gravity[2]);
  else printf("gravity: none\n");
  printf("forces in use: elasticity (stretch, shear, bend, twist)%s%s%s%s%s%s%s%s%s%s\n",
         m->has_gravity ? ", gravity" : "", m->nload ? ", point loads" : "",
         m->nbc ? ", boundary conditions" : "", m->njoint ? ", joints" : "",
         m->nmuscle ? ", muscles" : "", m->nwave ? ", torque waves" : "",
         m->nground ? ", ground contact and friction" : "", m->nfluid ? ", fluid" : "",
         m->ncontact ? ", rod-rod contact" : "", m->has_damping ? ", damping" : "");
  print_law(m);
  printf("integrator: %s\n", m->integrator == SW_PEFRL ? "PEFRL"
                             : m->integrator == SW_IMEX ? "position Verlet, stiff terms linearly implicit (imex)"
                                                        : "position Verlet");
  print_stiff_parts(m);
  printf("dt: %s (%s; stable estimate %s)\n", format_time(a, sizeof a, m->dt), dt_source,
         isfinite(stable) ? format_time(b, sizeof b, stable) : "none: nothing in the scene bounds it");
  print_step_limit(m, stable);
  long nsteps = 0;
  char why[256];
  sw_step_count(c->duration, m->dt, &nsteps, why, sizeof why); /* checked by build_model */
  long frames = frame_count(nsteps, c->every, m->dt);
  printf("duration: %s, %ld steps; a frame every %s: %ld frames\n",
         format_time(a, sizeof a, c->duration), nsteps,
         c->every > 0 ? format_time(b, sizeof b, c->every) : "step", frames);
  printf("output: %s (position%s%s, energy%s)\n", out, p->velocity ? ", velocity" : "",
         p->directors ? ", directors" : "", m->nmuscle ? ", muscles" : "");
  double mb = model_bytes(m), db = data_bytes(m);
  printf("memory: about %s (model %s, state %s)\n", format_bytes(a, sizeof a, mb + db),
         format_bytes(b, sizeof b, mb), format_bytes(e, sizeof e, db));
  printf("threads: %ld (%s; %d processor%s available; results do not depend on it)\n",
         threads_for(c, m), c->threads_auto ? "--threads auto: one per 8192 slots, up to the processors"
                            : c->threads_set ? "--threads" : "default",
         omp_get_num_procs(), omp_get_num_procs() == 1 ? "" : "s");
  if (p->nparam) {
    printf("params:\n");
    for (int i = 0; i < p->nparam; i++) {
      const swParam *q = &p->param[i];
      char range[200];
      printf("  %s = %s", q->name, format_param(a, sizeof a, q, c->P[i]));
      if (q->ranged) printf(" %s", format_range(range, sizeof range, q));
      if (c->overridden[i]) printf(" (--set; default %s)", format_param(b, sizeof b, q, q->value));
      printf("\n");
    }
  } else {
    printf("params: none\n");
  }
  if (p->sense) print_objective(p);
  fflush(stdout);
}

/* ---- the run ---- */

static int run(const swCli *c, const swModel *m, const char *out) {
  const swProgram *p = c->p;
  char err[512] = "";
  swData *d = sw_data_new(m);
  if (d) sw_set_threads(d, (int)threads_for(c, m));
  char *params = params_string(c);
  if (!d || !params) {
    complain(c, "out of memory");
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
    pvalue[i] = param_in_unit(&p->param[i], c->P[i], unit[i], sizeof unit[i]);
    pdefault[i] = param_in_unit(&p->param[i], p->param[i].value, unit[i], sizeof unit[i]);
    punit[i] = unit[i];
  }
  oo.nparam = np;
  oo.param_name = pname;
  oo.param_value = pvalue;
  oo.param_default = pdefault;
  oo.param_unit = punit;
  swExpectRun *expect = m->nexpect ? sw_expect_run_new(m) : NULL;
  if (m->nexpect && !expect) {
    complain(c, "out of memory");
    sw_data_free(d);
    free(params);
    return SW_EMODEL;
  }
  swOutput *o = c->restart ? sw_output_resume(out, m, &oo, d, expect, err, sizeof err)
                           : sw_output_open(out, m, &oo, err, sizeof err);
  free(params);
  if (!o) {
    complain(c, "%s", err);
    sw_expect_run_free(expect);
    sw_data_free(d);
    return SW_EIO;
  }
  if (c->restart && !(d->time < c->duration - 0.5 * m->dt)) {
    complain(c, "--restart: %s already reaches t = %.9g s; give a longer --duration", out,
             d->time);
    sw_output_close(o, "complete");
    sw_expect_run_free(expect);
    sw_data_free(d);
    return SW_EUSAGE;
  }
  if (c->restart && !c->quiet)
    fprintf(stderr, "%s: continuing %s from t = %.9g s (frame %ld)\n", c->prog, out, d->time,
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
  char status[600];
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
    complain(c, "%s", sw_output_error());
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
            frames == 1 ? "" : "s", out, format_time(t, sizeof t, d->time));
    if (rc != SW_OK && rc != SW_EEXPECT)
      fprintf(stderr, " of %s", format_time(total, sizeof total, c->duration));
    fprintf(stderr, " in %s wall time (%ld steps)\n", format_wall(w, sizeof w, wall), d->step);
    fflush(stderr);
  }
  sw_data_free(d);
  return rc;
}

/* ---- a sweep or an optimisation (cli_study.c, study.c) ---- */

static int study(swCli *c) {
  const swProgram *p = c->p;
  const int np = p->nparam;
  const char **unit = malloc(((size_t)np + 1) * sizeof *unit);
  char (*units)[48] = malloc(((size_t)np + 1) * sizeof *units);
  double *scale = malloc(((size_t)np + 1) * sizeof *scale);
  if (!unit || !units || !scale) {
    free(unit);
    free(units);
    free(scale);
    return complain(c, "out of memory");
  }
  /* each param in the unit the model shows it in: 1 unit = scale SI */
  for (int i = 0; i < np; i++) {
    double one = param_in_unit(&p->param[i], 1.0, units[i], sizeof units[i]);
    scale[i] = one != 0 && isfinite(one) ? 1.0 / one : 1.0;
    unit[i] = units[i];
  }
  swStudyCall call = {.p = p, .prog = c->prog, .P = c->P, .overridden = c->overridden,
                      .started = c->started,
                      .unit = unit, .scale = scale, .duration = c->duration, .dt = c->dt,
                      .duration_given = c->duration_given, .dt_given = c->dt_given,
                      .integrator = c->integrator, .quiet = c->quiet, .args = c->study};
  int rc = sw_study_cli(&call);
  free(unit);
  free(units);
  free(scale);
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
    return complain(&c, "sw_main: no program");
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
    return complain(&c, "out of memory");
  }
  for (int i = 0; i < p->nparam; i++) c.P[i] = p->param[i].value;

  int rc = parse_args(&c, argc, argv);
  if (rc == SW_OK && c.restart) rc = read_restart(&c);
  if (rc == SW_OK && c.golden && access(c.golden, R_OK) != 0) {
    complain(&c, "--compare: cannot read '%s': %s", c.golden, strerror(errno));
    rc = SW_EIO;
  }
  if (rc == SW_OK && c.golden && same_file(c.out, c.golden))
    rc = complain(&c, "--compare %s: that is the file this run would write (--out); the run "
                  "would overwrite what it is compared with", c.golden);
  if (rc == SW_OK && c.help) {
    print_help(&c, p->out && p->out[0] ? p->out : default_out);
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
    if (m && c.info) print_info(&c, m, stable, dt_source, c.out);
    else if (m) rc = run(&c, m, c.out);
    sw_model_free(m);
  }
  free(c.P);
  free(c.overridden);
  free(c.started);
  return rc;
}
