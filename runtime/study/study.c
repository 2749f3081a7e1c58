/* study.c — sweeps and optimisations of a model's ranged params.
 *
 * Design.  A study is a deterministic sequence of designs, numbered from 0:
 * a grid (every combination of `levels` points per varied param, the last
 * param varying fastest), a Latin hypercube (McKay, Beckman & Conover 1979:
 * `samples` designs, each param's range cut into `samples` strata, each
 * stratum used once, in an order and at a point drawn from the seed), or
 * CMA-ES generations (cmaes.c; Hansen 2016) in the unit cube of the ranges.
 * The designs depend only on the settings and the seed, and the next
 * generation only on the scores of the last, so the study is the same
 * whoever evaluates it: study_pool.c hands the designs to a thread and to
 * the other MPI ranks, and each result is written at its index as it
 * arrives (study_file.c).  The optimiser sees the scores as the file stores
 * them (in the objective's unit; ranking is all it uses), so that
 * --resume, which replays the stored scores through a fresh optimiser of
 * the same seed and evaluates only the designs the file lacks, continues
 * exactly where the interrupted study was: the designs it regenerates are
 * checked against the stored ones, bit for bit, before anything runs (as
 * shown, and in SI where the file has params_si; a file written before
 * params_si gets the SI values of the designs so checked).  Every design is
 * written in SI beside the units shown, so that --replay runs the very
 * values evaluated.  Every status but ok scores -infinity: an unstable design ranks last and
 * the study goes on.  Once the study is complete, its best designs are
 * evaluated again at dt/2 and the report says how far each objective moved
 * (study_recheck.c, fed every result as it is taken). */
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sinew.h"
#include "io/params.h"
#include "cmaes.h"
#include "rng.h"
#include "study.h"
#include "study_file.h"
#include "study_pool.h"
#include "study_recheck.h"

extern char **environ;

#define MAX_DESIGNS 100000000L    /* a grid larger than this is refused     */
#define MAX_PARAMS 4096           /* study_mpi.c's message size              */

typedef struct {
  const swStudyOptions *o;
  swStudyFile *file;
  int nvar;
  int *var;                 /* (nvar) param index of each varied param       */
  long total;               /* designs in the study (cmaes: the budget)       */
  long done;                /* results in the file                            */
  double *shown;            /* (nparam) scratch: a design in the units shown  */
  int generation;           /* of the designs being evaluated (-1: a sweep)   */
  double *gen_score;        /* (lambda) the generation's scores, as stored    */
  long gen_first;           /* index of its first design                      */
  double best_score;
  long best_index;
  double *best_shown;       /* (nparam) the best design, units shown          */
  int failures;
  swRecheck *recheck;       /* its best designs at dt/2 (NULL: no recheck)     */
} swStudy;

static double shown_value(const swStudyOptions *o, int i, double si) {
  return o->scale && o->scale[i] > 0 ? si / o->scale[i] : si;
}

static double objective_scale(const swStudyOptions *o) {
  return o->objective_scale > 0 ? o->objective_scale : 1.0;
}

/* ---- the designs ---- */

/* Design i of a grid: digit v of i in base `levels` (the last param the
 * fastest) picks point lo + (hi - lo) * digit / (levels - 1). */
static void grid_design(const swStudy *s, long i, double *P) {
  const swStudyOptions *o = s->o;
  for (int v = s->nvar - 1; v >= 0; v--) {
    int p = s->var[v];
    long digit = i % o->levels;
    i /= o->levels;
    P[p] = o->lo[p] + (o->hi[p] - o->lo[p]) * (double)digit / (double)(o->levels - 1);
  }
}

/* A Latin hypercube of n designs: for each param, a uniform random
 * permutation of the n strata (Fisher-Yates on a stream of its own) and a
 * uniform point in each stratum. P: n rows of nparam, pre-filled. */
static int lhs_designs(const swStudy *s, double *P) {
  const swStudyOptions *o = s->o;
  long n = s->total;
  long *perm = malloc((size_t)n * sizeof *perm);
  if (!perm) return SW_EIO;
  for (int v = 0; v < s->nvar; v++) {
    int p = s->var[v];
    swRng rng;
    sw_rng_stream(&rng, o->seed, (unsigned)v);
    for (long k = 0; k < n; k++) perm[k] = k;
    for (long k = n - 1; k > 0; k--) {
      long j = (long)(sw_rng_uniform(&rng) * (double)(k + 1));
      if (j > k) j = k;
      long t = perm[k];
      perm[k] = perm[j];
      perm[j] = t;
    }
    for (long k = 0; k < n; k++) {
      double u = ((double)perm[k] + sw_rng_uniform(&rng)) / (double)n;
      P[k * o->nparam + p] = o->lo[p] + (o->hi[p] - o->lo[p]) * u;
    }
  }
  free(perm);
  return SW_OK;
}

/* ---- results ---- */

/* The varied params of a design given in the units shown. */
static void print_design(const swStudyOptions *o, const swStudy *s, const double *shown, FILE *f) {
  for (int v = 0; v < s->nvar; v++) {
    int p = s->var[v];
    fprintf(f, "%s%s = %.6g%s%s", v ? ", " : "", o->name[p], shown[p], o->unit[p][0] ? " " : "",
            o->unit[p]);
  }
}

static int on_result(void *ctx, long index, const double *P, const swStudyEval *r) {
  swStudy *s = ctx;
  const swStudyOptions *o = s->o;
  for (int i = 0; i < o->nparam; i++) s->shown[i] = shown_value(o, i, P[i]);
  double scale = objective_scale(o);
  if (sw_study_file_write(s->file, index, s->generation, s->shown, P, r, scale) != SW_OK) {
    fprintf(stderr, "%s: cannot write evaluation %ld to %s\n", o->prog, index, o->path);
    return SW_EIO;
  }
  s->done++;
  double score = r->status == SW_EVAL_OK ? r->score / scale : -INFINITY;
  if (s->gen_score) s->gen_score[index - s->gen_first] = score;
  if (r->status != SW_EVAL_OK) s->failures++;
  else sw_recheck_offer(s->recheck, index, P, score, r->objective / scale);
  int better = score > s->best_score || (score == s->best_score && index < s->best_index);
  if (r->status == SW_EVAL_OK && better) {
    s->best_score = score;
    s->best_index = index;
    memcpy(s->best_shown, s->shown, (size_t)o->nparam * sizeof *s->shown);
    if (sw_study_file_best(s->file, index, s->shown, score, r->objective / scale,
                           r->penalty / scale) != SW_OK)
      return SW_EIO;
  }
  if (!o->quiet) {
    fprintf(stderr, "%s: [%ld/%ld] ", o->prog, s->done, s->total);
    if (r->status == SW_EVAL_OK)
      fprintf(stderr, "score %.6g%s%s", score, o->objective_unit[0] ? " " : "", o->objective_unit);
    else
      fprintf(stderr, "%s%s%s", sw_eval_status_name(r->status), r->message[0] ? ": " : "",
              r->message);
    fprintf(stderr, "  (design %ld", index);
    if (s->generation >= 0) fprintf(stderr, ", generation %d", s->generation);
    fprintf(stderr, ", rank %d, %.2f s)%s\n", r->rank, r->wall, better && r->status == SW_EVAL_OK ?
            "  best so far" : "");
    fflush(stderr);
  }
  return SW_OK;
}

/* A stored row: the design regenerated must be the one stored (in the units
 * shown, and in SI where the file has it, bit for bit), or the file is
 * another study's. */
static int check_stored(const swStudy *s, const swStudyRows *rows, long i, const double *P) {
  const swStudyOptions *o = s->o;
  const double *si = rows->Psi && !isnan(rows->Psi[i * o->nparam]) ? rows->Psi + i * o->nparam
                                                                    : NULL;
  for (int k = 0; k < 2 * o->nparam; k++) {
    int p = k % o->nparam;
    if (k >= o->nparam && !si) break;
    double want = k < o->nparam ? shown_value(o, p, P[p]) : P[p];
    double have = k < o->nparam ? rows->P[i * o->nparam + p] : si[p];
    if (memcmp(&want, &have, sizeof want)) {
      fprintf(stderr, "%s: --resume %s: design %ld of the file has %s = %.17g%s, this study "
              "makes it %.17g: the file holds another study (another seed, range, start or "
              "model)\n", o->prog, o->path, i, o->name[p], have, k < o->nparam ? "" : " (SI)",
              want);
      return SW_EUSAGE;
    }
  }
  return SW_OK;
}

/* The stored row counts as this run's result (best, generation scores); a
 * file that predates params_si (or lacks the row) gets the design's SI
 * values, the ones check_stored has just found stored in the units shown. */
static int take_stored(swStudy *s, const swStudyRows *rows, long i, const double *P) {
  if ((!rows->Psi || isnan(rows->Psi[i * s->o->nparam])) &&
      sw_study_file_params_si(s->file, i, P) != SW_OK) {
    fprintf(stderr, "%s: cannot write evaluation %ld to %s\n", s->o->prog, i, s->o->path);
    return SW_EIO;
  }
  double score = rows->status[i] == SW_EVAL_OK ? rows->score[i] : -INFINITY;
  if (s->gen_score) s->gen_score[i - s->gen_first] = score;
  if (rows->status[i] != SW_EVAL_OK) s->failures++;
  else sw_recheck_offer(s->recheck, i, P, score, rows->objective[i]);
  if (rows->status[i] == SW_EVAL_OK &&
      (score > s->best_score || (score == s->best_score && i < s->best_index))) {
    s->best_score = score;
    s->best_index = i;
    memcpy(s->best_shown, rows->P + i * s->o->nparam, (size_t)s->o->nparam * sizeof *s->best_shown);
  }
  s->done++;
  return SW_OK;
}

/* Evaluates designs first..first+n-1 (rows of P) that the file does not
 * hold yet. */
static int evaluate_batch(swStudy *s, swPool *pool, const swStudyRows *rows, long first, long n,
                          const double *P) {
  const swStudyOptions *o = s->o;
  long *index = malloc(((size_t)n + 1) * sizeof *index);
  double *todo = malloc(((size_t)n + 1) * (size_t)o->nparam * sizeof *todo);
  if (!index || !todo) {
    free(index);
    free(todo);
    return SW_EIO;
  }
  long m = 0;
  int rc = SW_OK;
  for (long k = 0; k < n && rc == SW_OK; k++) {
    long i = first + k;
    const double *Pi = P + k * o->nparam;
    if (rows && i < rows->n && rows->status[i] != SW_EVAL_PENDING) {
      rc = check_stored(s, rows, i, Pi);
      if (rc == SW_OK) rc = take_stored(s, rows, i, Pi);
      continue;
    }
    index[m] = i;
    memcpy(todo + m * o->nparam, Pi, (size_t)o->nparam * sizeof *Pi);
    m++;
  }
  if (rc == SW_OK && m > 0) rc = sw_pool_run(pool, m, index, todo, 1.0, on_result, s);
  free(index);
  free(todo);
  return rc;
}

/* ---- the three kinds ---- */

static int run_sweep(swStudy *s, swPool *pool, const swStudyRows *rows) {
  const swStudyOptions *o = s->o;
  const long batch = 4096;
  double *P = malloc((size_t)(o->kind == SW_STUDY_LHS ? s->total : batch) * (size_t)o->nparam *
                     sizeof *P);
  if (!P) return SW_EIO;
  int rc = SW_OK;
  if (o->kind == SW_STUDY_LHS) {
    for (long k = 0; k < s->total; k++)
      memcpy(P + k * o->nparam, o->value, (size_t)o->nparam * sizeof *P);
    rc = lhs_designs(s, P);
    if (rc == SW_OK) rc = evaluate_batch(s, pool, rows, 0, s->total, P);
  } else {
    for (long first = 0; first < s->total && rc == SW_OK; first += batch) {
      long n = s->total - first < batch ? s->total - first : batch;
      for (long k = 0; k < n; k++) {
        memcpy(P + k * o->nparam, o->value, (size_t)o->nparam * sizeof *P);
        grid_design(s, first + k, P + k * o->nparam);
      }
      rc = evaluate_batch(s, pool, rows, first, n, P);
    }
  }
  free(P);
  return rc;
}

static int run_cmaes(swStudy *s, swPool *pool, const swStudyRows *rows, char *why, size_t len) {
  const swStudyOptions *o = s->o;
  const int n = s->nvar;
  double *x0 = malloc((size_t)n * sizeof *x0), *lo = malloc((size_t)n * sizeof *lo),
         *hi = malloc((size_t)n * sizeof *hi);
  if (!x0 || !lo || !hi) {
    free(x0);
    free(lo);
    free(hi);
    return SW_EIO;
  }
  for (int v = 0; v < n; v++) {
    int p = s->var[v];
    x0[v] = (o->value[p] - o->lo[p]) / (o->hi[p] - o->lo[p]);
    lo[v] = 0;
    hi[v] = 1;
  }
  swCmaesOptions co;
  sw_cmaes_options_init(&co);
  co.n = n;
  co.x0 = x0;
  co.sigma0 = o->sigma;
  co.lambda = (int)o->popsize;
  co.seed = o->seed;
  co.lo = lo;
  co.hi = hi;
  co.maxfevals = o->samples;
  co.restarts = (int)o->restarts;
  char err[256] = "";
  swCmaes *c = sw_cmaes_new(&co, err, sizeof err);
  free(x0);
  if (!c) {
    free(lo);
    free(hi);
    fprintf(stderr, "%s: CMA-ES: %s\n", o->prog, err);
    return SW_EUSAGE;
  }
  const int lmax = sw_cmaes_lambda_max(c);
  double *X = malloc((size_t)lmax * (size_t)n * sizeof *X);
  double *P = malloc((size_t)lmax * (size_t)o->nparam * sizeof *P);
  double *loss = malloc((size_t)lmax * sizeof *loss);
  double *mean = malloc((size_t)n * sizeof *mean);
  s->gen_score = malloc((size_t)lmax * sizeof *s->gen_score);
  int rc = X && P && loss && mean && s->gen_score ? SW_OK : SW_EIO;
  snprintf(why, len, "the budget of %ld evaluations", o->samples);
  long next = 0;   /* index of the next design */
  for (int g = 0; rc == SW_OK; g++) {
    const int lambda = sw_cmaes_lambda(c);
    if (next + lambda > o->samples) break;
    char stop[128] = "";
    if (sw_cmaes_stop(c, stop, sizeof stop)) {
      snprintf(why, len, "%s", stop);
      break;
    }
    sw_cmaes_ask(c, X);
    for (int k = 0; k < lambda; k++) {
      double *Pk = P + (size_t)k * o->nparam;
      memcpy(Pk, o->value, (size_t)o->nparam * sizeof *Pk);
      for (int v = 0; v < n; v++) {
        int p = s->var[v];
        Pk[p] = o->lo[p] + (o->hi[p] - o->lo[p]) * X[k * n + v];
      }
    }
    s->generation = g;
    s->gen_first = next;
    for (int k = 0; k < lambda; k++) s->gen_score[k] = -INFINITY;
    rc = evaluate_batch(s, pool, rows, next, lambda, P);
    if (rc != SW_OK) break;
    next += lambda;
    for (int k = 0; k < lambda; k++) loss[k] = -s->gen_score[k];   /* +inf: failed */
    sw_cmaes_tell(c, loss);
    sw_cmaes_mean(c, mean);
    rc = sw_study_file_generation(s->file, g, sw_cmaes_sigma(c), mean, n, s->best_score, next);
  }
  free(mean);
  free(X);
  free(P);
  free(loss);
  free(s->gen_score);
  s->gen_score = NULL;
  free(lo);
  free(hi);
  sw_cmaes_free(c);
  return rc;
}

/* ---- the summary plot ---- */

/* `sinew-plot study FILE -o FILE.png`, when sinew-plot is on the PATH (or
 * SINEW_PLOT names it); the runtime itself draws nothing. */
static void plot(const swStudyOptions *o) {
  const char *tool = getenv("SINEW_PLOT");
  if (!tool || !*tool) tool = "sinew-plot";
  char png[4096];
  snprintf(png, sizeof png, "%s", o->path);
  size_t len = strlen(png);
  if (len > 3 && !strcmp(png + len - 3, ".h5")) png[len - 3] = 0;
  strncat(png, ".png", sizeof png - strlen(png) - 1);
  char *argv[] = {(char *)tool, "study", (char *)o->path, "-o", png, NULL};
  pid_t pid;
  if (posix_spawnp(&pid, tool, NULL, NULL, argv, environ) != 0) {
    if (!o->quiet)
      fprintf(stderr, "%s: plot it with: sinew-plot study %s -o %s (sinew-plot is not on the "
              "PATH)\n", o->prog, o->path, png);
    return;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (!o->quiet) {
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
      fprintf(stderr, "%s: summary plot %s\n", o->prog, png);
    else
      fprintf(stderr, "%s: %s study %s failed; the study file is complete\n", o->prog, tool,
              o->path);
  }
}

/* ---- the study ---- */

/* The line that ends a study: how it ended, how many evaluations, the best. */
static void report(const swStudy *s, const char *status, int rc) {
  const swStudyOptions *o = s->o;
  if (o->quiet && rc == SW_OK) return;
  fprintf(stderr, "%s: %s: %ld of %ld evaluations in %s (%d failed)", o->prog, status, s->done,
          s->total, o->path, s->failures);
  if (s->best_index >= 0) {
    fprintf(stderr, "; best: design %ld, score %.6g%s%s, at ", s->best_index, s->best_score,
            o->objective_unit[0] ? " " : "", o->objective_unit);
    print_design(o, s, s->best_shown, stderr);
  }
  fprintf(stderr, "\n");
  if (rc == SW_EINTERRUPT)
    fprintf(stderr, "%s: continue it with: %s --resume %s\n", o->prog, o->prog, o->path);
  fflush(stderr);
}


static char *join_varied(const swStudyOptions *o) {
  size_t size = 1;
  for (int i = 0; i < o->nparam; i++) size += strlen(o->name[i]) + 1;
  char *s = malloc(size), *w = s;
  if (!s) return NULL;
  *w = 0;
  for (int i = 0; i < o->nparam; i++)
    if (o->vary[i]) w += sprintf(w, "%s%s", w > s ? ";" : "", o->name[i]);
  return s;
}

static int check_options(const swStudyOptions *o, int nvar, long *total) {
  if (nvar == 0) {
    fprintf(stderr, "%s: nothing to vary: no param has a range (write 'param NAME = VALUE in "
            "(LOW, HIGH);') or every ranged param is fixed by --set\n", o->prog);
    return SW_EUSAGE;
  }
  for (int i = 0; i < o->nparam; i++)
    if (o->vary[i] && !(o->lo[i] < o->hi[i] && o->value[i] >= o->lo[i] && o->value[i] <= o->hi[i])) {
      fprintf(stderr, "%s: param %s: its value %.9g is not in its range (%.9g, %.9g) (SI)\n",
              o->prog, o->name[i], o->value[i], o->lo[i], o->hi[i]);
      return SW_EUSAGE;
    }
  if (o->nparam > MAX_PARAMS) {
    fprintf(stderr, "%s: %d params: a study handles at most %d\n", o->prog, o->nparam,
            MAX_PARAMS);
    return SW_EUSAGE;
  }
  if (!o->sense) {
    fprintf(stderr, "%s: the model states no objective: add 'maximize EXPR;' or 'minimize "
            "EXPR;' to it\n", o->prog);
    return SW_EUSAGE;
  }
  switch (o->kind) {
  case SW_STUDY_GRID: {
    double t = pow((double)o->levels, nvar);
    if (o->levels < 2 || t > (double)MAX_DESIGNS) {
      fprintf(stderr, "%s: --sweep grid:%ld over %d params is %.3g designs; a grid takes 2 "
              "or more points per param and at most %ld designs\n", o->prog, o->levels, nvar, t,
              MAX_DESIGNS);
      return SW_EUSAGE;
    }
    *total = (long)llround(t);
    break;
  }
  case SW_STUDY_LHS:
    if (o->samples < 1 || o->samples > MAX_DESIGNS) {
      fprintf(stderr, "%s: --sweep lhs:%ld: the number of designs must be 1 to %ld\n", o->prog,
              o->samples, MAX_DESIGNS);
      return SW_EUSAGE;
    }
    *total = o->samples;
    break;
  case SW_STUDY_CMAES:
    if (!(o->sigma > 0 && o->sigma <= 1)) {
      fprintf(stderr, "%s: --sigma %g: the initial step is a fraction of each param's range, "
              "in (0, 1] (default 0.25)\n", o->prog, o->sigma);
      return SW_EUSAGE;
    }
    if (o->samples < 2 || o->popsize < 0 || o->popsize == 1 || o->restarts < 0) {
      fprintf(stderr, "%s: --budget %ld, --popsize %ld, --restarts %ld: the budget is at least "
              "2 evaluations, the population 0 (automatic) or at least 2, the restarts 0 or "
              "more\n", o->prog, o->samples, o->popsize, o->restarts);
      return SW_EUSAGE;
    }
    *total = o->samples;
    break;
  }
  return SW_OK;
}

int sw_study_run(const swStudyOptions *o) {
  swStudy s;
  memset(&s, 0, sizeof s);
  s.o = o;
  s.generation = -1;
  s.best_score = -INFINITY;
  s.best_index = -1;
  for (int i = 0; i < o->nparam; i++) s.nvar += o->vary[i] != 0;
  int rc = check_options(o, s.nvar, &s.total);
  if (rc != SW_OK) return rc;

  char err[512] = "";
  int rank = 0;
  swPool *pool = sw_pool_open(o, &rank, err, sizeof err);
  if (!pool) {
    fprintf(stderr, "%s: %s\n", o->prog, err);
    return SW_EUSAGE;
  }
  if (rank != 0) {
    rc = sw_pool_serve(pool);
    sw_pool_close(pool, 0);
    return rc;
  }

  s.var = malloc((size_t)s.nvar * sizeof *s.var);
  s.shown = malloc((size_t)o->nparam * sizeof *s.shown);
  s.best_shown = malloc((size_t)o->nparam * sizeof *s.best_shown);
  const char **dname = malloc((size_t)s.nvar * sizeof *dname);
  const char **dunit = malloc((size_t)s.nvar * sizeof *dunit);
  double *dlo = malloc((size_t)s.nvar * sizeof *dlo), *dhi = malloc((size_t)s.nvar * sizeof *dhi);
  char *start = sw_params_text(o->nparam, o->name, o->value), *varied = join_varied(o);
  char seed[32];
  snprintf(seed, sizeof seed, "%" PRIu64, o->seed);
  if (!s.var || !s.shown || !s.best_shown || !dname || !dunit || !dlo || !dhi || !start || !varied) {
    fprintf(stderr, "%s: out of memory\n", o->prog);
    rc = SW_EIO;
    goto done;
  }
  for (int i = 0, v = 0; i < o->nparam; i++)
    if (o->vary[i]) {
      s.var[v] = i;
      dname[v] = o->name[i];
      dunit[v] = o->unit[i];
      dlo[v] = shown_value(o, i, o->lo[i]);
      dhi[v] = shown_value(o, i, o->hi[i]);
      v++;
    }
  swStudyFileInfo info = {o, seed, start, varied, s.nvar, dname, dunit, dlo, dhi};
  swStudyRows rows;
  memset(&rows, 0, sizeof rows);
  s.file = o->resume ? sw_study_file_reopen(&info, &rows, err, sizeof err)
                     : sw_study_file_create(&info, err, sizeof err);
  if (!s.file) {
    fprintf(stderr, "%s: %s\n", o->prog, err);
    rc = SW_EIO;
    goto done;
  }
  if (!o->quiet) {
    const char *what[] = {"grid sweep", "Latin-hypercube sweep", "CMA-ES optimisation"};
    fprintf(stderr, "%s: %s %s of %d param%s (", o->prog, o->resume ? "continuing the" : "a",
            what[o->kind], s.nvar, s.nvar == 1 ? "" : "s");
    for (int v = 0; v < s.nvar; v++) fprintf(stderr, "%s%s", v ? ", " : "", dname[v]);
    fprintf(stderr, "), %s %ld evaluations on %d worker%s; writing %s\n",
            o->kind == SW_STUDY_CMAES ? "at most" : "", s.total, sw_pool_size(pool),
            sw_pool_size(pool) == 1 ? "" : "s", o->path);
    fflush(stderr);
  }

  char why[160] = "";
  s.recheck = sw_recheck_new(o);
  rc = o->kind == SW_STUDY_CMAES ? run_cmaes(&s, pool, o->resume ? &rows : NULL, why, sizeof why)
                                 : run_sweep(&s, pool, o->resume ? &rows : NULL);
  sw_recheck_stored(s.recheck, rows.recheck, rows.nrecheck);
  sw_study_rows_free(&rows);
  char status[256];
  if (rc == SW_OK && o->kind == SW_STUDY_CMAES) snprintf(status, sizeof status, "complete: %s", why);
  else if (rc == SW_OK) snprintf(status, sizeof status, "complete");
  else if (rc == SW_EINTERRUPT) snprintf(status, sizeof status, "interrupted");
  else snprintf(status, sizeof status, "failed (code %d)", rc);
  report(&s, status, rc);
  /* the study is complete: its best designs at dt/2, whose interruption
   * leaves the study complete (--resume does the rest of the recheck) */
  int recheck_rc = rc == SW_OK && s.recheck ? sw_recheck_run(s.recheck, pool, s.file) : SW_OK;
  if (sw_study_file_close(s.file, status) != SW_OK && rc == SW_OK) {
    fprintf(stderr, "%s: cannot write the study file %s as it closes\n", o->prog, o->path);
    rc = SW_EIO;
  }
  s.file = NULL;
  if (rc == SW_OK) rc = recheck_rc;
  if (rc == SW_OK) plot(o);
done:
  sw_pool_close(pool, rc == SW_OK ? SW_OK : rc);
  sw_recheck_free(s.recheck);
  free(s.var);
  free(s.shown);
  free(s.best_shown);
  free(dname);
  free(dunit);
  free(dlo);
  free(dhi);
  free(start);
  free(varied);
  return rc;
}
