/* study_recheck.c — a study's best designs evaluated again at dt/2, and the
 * report that says how much each objective moved.
 *
 * Design.  An optimiser keeps the design with the highest score.  When the
 * objective depends on the time step as much as on the design (a foot that
 * catches the ground or slips, a chaotic swing, a step near the stability
 * edge), the best is the luckiest sample, and nothing in the study shows it
 * (issue 30).  So once a study is complete, its best o->recheck distinct
 * designs (by score, the lower index first on a tie; a design proposed twice
 * counts once) are evaluated again with the step their evaluation took
 * halved, all else the same, on the study's workers (sw_pool_run, dt_scale
 * 0.5), and the report gives each one's objective at dt and at dt/2.  A
 * design is sensitive when the two differ by more than TOLERANCE of its
 * size, or when it fails at dt/2.  Its size is |objective at dt|, or FLOOR
 * times the median |objective| of the study's designs that ran, whichever
 * is larger: an objective near zero (a minimised error) is then judged
 * against the study's own scale and not against itself, where rounding
 * alone would be a large fraction.  docs/optimisation.md, "Rechecking the
 * best designs", says why 1%: with a second-order integrator the difference
 * is 3/4 of the error at dt, so a design that passes is within about 1.3%
 * of its converged objective.  Evaluations are deterministic, so a recheck
 * the file already holds (a resumed study) is taken and not redone; the
 * verdicts are made afresh, since the median may have moved.  The rechecks
 * are not part of the study: they do not count in its budget or change its
 * best, and CMA-ES never sees them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "study_recheck.h"

#define TOLERANCE 0.01   /* a design whose objective moves more is sensitive  */
#define FLOOR 0.1        /* sizes: at least this times the median |objective| */
#define DT_SCALE 0.5     /* the recheck's step, a fraction of the study's     */

typedef struct {
  swStudyRecheck row;    /* index, objective and score at dt; the rest when
                            rechecked                                         */
  double *P;             /* (nparam) the design, SI                           */
  int done;              /* 1: row holds its result at dt/2                   */
  int stored;            /* 1: taken from the file                            */
  char message[256];     /* why it failed at dt/2                             */
} swCandidate;

struct swRecheck {
  const swStudyOptions *o;
  int n;                 /* candidates held, at most o->recheck, best first   */
  swCandidate *best;
  double *size;          /* |objective| of each design that ran               */
  long nsize, capsize;
  swStudyRecheck *stored;   /* the file's /recheck (a resumed study)          */
  long nstored;
};

swRecheck *sw_recheck_new(const swStudyOptions *o) {
  if (o->recheck <= 0) return NULL;
  swRecheck *k = calloc(1, sizeof *k);
  if (!k) return NULL;
  k->o = o;
  k->best = calloc((size_t)o->recheck, sizeof *k->best);
  int ok = k->best != NULL;
  for (int i = 0; ok && i < o->recheck; i++)
    ok = (k->best[i].P = malloc(((size_t)o->nparam + 1) * sizeof(double))) != NULL;
  if (!ok) {
    sw_recheck_free(k);
    return NULL;
  }
  return k;
}

void sw_recheck_free(swRecheck *k) {
  if (!k) return;
  for (int i = 0; k->best && i < k->o->recheck; i++) free(k->best[i].P);
  free(k->best);
  free(k->size);
  free(k->stored);
  free(k);
}

/* ---- the best designs ---- */

static int better(double score, long index, const swStudyRecheck *than) {
  return score > than->score || (score == than->score && index < than->index);
}

void sw_recheck_offer(swRecheck *k, long index, const double *P, double score, double objective) {
  if (!k) return;
  if (k->nsize == k->capsize) {
    long cap = k->capsize ? 2 * k->capsize : 1024;
    double *grown = realloc(k->size, (size_t)cap * sizeof *grown);
    if (grown) {
      k->size = grown;
      k->capsize = cap;
    }
  }
  if (k->nsize < k->capsize) k->size[k->nsize++] = fabs(objective);
  const size_t bytes = (size_t)k->o->nparam * sizeof *P;
  int slot = -1;
  for (int i = 0; i < k->n && slot < 0; i++)
    if (!memcmp(k->best[i].P, P, bytes)) {   /* the same design: the same score */
      if (index > k->best[i].row.index) return;
      slot = i;
    }
  if (slot < 0 && k->n < k->o->recheck) slot = k->n++;
  else if (slot < 0 && better(score, index, &k->best[k->n - 1].row)) slot = k->n - 1;
  else if (slot < 0) return;
  swCandidate *c = &k->best[slot];
  c->row = (swStudyRecheck){.index = index, .objective = objective, .score = score,
                            .status_half = SW_EVAL_PENDING, .objective_half = NAN,
                            .score_half = NAN, .difference = NAN};
  memcpy(c->P, P, bytes);
  c->done = c->stored = 0;
  c->message[0] = 0;
  for (; slot > 0 && better(k->best[slot].row.score, k->best[slot].row.index,
                            &k->best[slot - 1].row); slot--) {
    swCandidate t = k->best[slot];
    k->best[slot] = k->best[slot - 1];
    k->best[slot - 1] = t;
  }
}

void sw_recheck_stored(swRecheck *k, const swStudyRecheck *rows, long n) {
  if (!k || n <= 0 || !(k->stored = malloc((size_t)n * sizeof *rows))) return;
  memcpy(k->stored, rows, (size_t)n * sizeof *rows);
  k->nstored = n;
}

/* ---- the rechecks ---- */

static int on_recheck(void *ctx, long index, const double *P, const swStudyEval *r) {
  (void)P;
  swRecheck *k = ctx;
  const double scale = k->o->objective_scale > 0 ? k->o->objective_scale : 1.0;
  for (int i = 0; i < k->n; i++) {
    swCandidate *c = &k->best[i];
    if (c->row.index != index) continue;
    c->row.dt = r->dt > 0 ? r->dt / DT_SCALE : 0;
    c->row.status_half = r->status;
    c->row.objective_half = r->status == SW_EVAL_OK ? r->objective / scale : NAN;
    c->row.score_half = r->status == SW_EVAL_OK ? r->score / scale : -INFINITY;
    snprintf(c->message, sizeof c->message, "%s", r->message);
    c->done = 1;
  }
  return SW_OK;
}

static int compare_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* FLOOR times the median |objective| of the designs that ran. */
static double size_floor(swRecheck *k) {
  if (k->nsize == 0) return 0;
  qsort(k->size, (size_t)k->nsize, sizeof *k->size, compare_double);
  long h = k->nsize / 2;
  double median = k->nsize % 2 ? k->size[h] : 0.5 * (k->size[h - 1] + k->size[h]);
  return FLOOR * median;
}

static void judge(swStudyRecheck *r, double floor) {
  if (r->status_half != SW_EVAL_OK) {
    r->difference = NAN;
    r->sensitive = 1;
    return;
  }
  double size = fmax(fabs(r->objective), floor);
  double diff = fabs(r->objective_half - r->objective);
  r->difference = diff == 0 ? 0 : size > 0 ? diff / size : INFINITY;
  r->sensitive = !(r->difference <= TOLERANCE);
}

/* ---- the report ---- */

/* "5.13 us": the unit that keeps the number readable (with the space) or
 * "5.13us" for the command line (without). */
static const char *time_text(char *buf, size_t len, double t, const char *space) {
  double a = fabs(t);
  const char *u = a == 0 || a >= 1 ? "s" : a >= 1e-3 ? "ms" : a >= 1e-6 ? "us" : "ns";
  double f = u[0] == 's' ? 1 : u[0] == 'm' ? 1e3 : u[0] == 'u' ? 1e6 : 1e9;
  snprintf(buf, len, "%.3g%s%s", t * f, space, u);
  return buf;
}

static const char *ordinal(char *buf, size_t len, int rank) {
  static const char *const th[] = {"th", "st", "nd", "rd"};
  int last = rank % 10, teen = rank % 100 >= 11 && rank % 100 <= 13;
  if (rank == 1) snprintf(buf, len, "best");
  else snprintf(buf, len, "%d%s best", rank, teen || last > 3 ? "th" : th[last]);
  return buf;
}

static void report_design(const swRecheck *k, int rank, const swCandidate *c, double floor) {
  const swStudyOptions *o = k->o;
  const swStudyRecheck *r = &c->row;
  const char *u = o->objective_unit, *sp = u[0] ? " " : "";
  char nth[32], dt[32], half[32];
  fprintf(stderr, "%s:   %s design %ld: %.6g%s%s at dt = %s, ", o->prog,
          ordinal(nth, sizeof nth, rank), r->index, r->objective, sp, u,
          r->dt > 0 ? time_text(dt, sizeof dt, r->dt, " ") : "the study's");
  if (r->dt > 0) time_text(half, sizeof half, r->dt * DT_SCALE, " ");
  if (r->status_half != SW_EVAL_OK) {
    fprintf(stderr, "%s at dt/2%s%s%s%s%s: sensitive to the step\n",
            sw_eval_status_name(r->status_half), r->dt > 0 ? " = " : "", r->dt > 0 ? half : "",
            c->message[0] ? " (" : "", c->message, c->message[0] ? ")" : "");
    return;
  }
  fprintf(stderr, "%.6g%s%s at dt/2: ", r->objective_half, sp, u);
  if (r->difference == 0) fprintf(stderr, "the same to the bit");
  else if (r->difference < 1) fprintf(stderr, "differs by %.2g%%", 100 * r->difference);
  else fprintf(stderr, "differs by %.0f%%", 100 * r->difference);
  if (r->difference != 0 && floor > fabs(r->objective))
    fprintf(stderr, " of %.3g%s%s (a tenth of the median size of the study's objectives, larger "
            "than this one)", floor, sp, u);
  if (r->sensitive) fprintf(stderr, ": sensitive to the step\n");
  else fprintf(stderr, ": insensitive to the step (within %g%%)\n", 100 * TOLERANCE);
}

/* The per-design lines (unless quiet: only the sensitive ones) and the
 * verdict. */
static void report(const swRecheck *k, const swStudyRecheck *rows, int nrows, double floor,
                   int evaluated) {
  const swStudyOptions *o = k->o;
  char which[64];
  if (nrows == k->n) snprintf(which, sizeof which, "the %d best design%s", nrows,
                              nrows == 1 ? "" : "s");
  else snprintf(which, sizeof which, "%d of the %d best designs", nrows, k->n);
  if (!o->quiet && nrows > 0) {
    fprintf(stderr, "%s: recheck at dt/2: %s, each evaluated again with its step halved and all "
            "else the same", o->prog, which);
    if (evaluated < nrows)
      fprintf(stderr, " (%d as the study file holds %s)", nrows - evaluated,
              nrows - evaluated == 1 ? "it" : "them");
    fprintf(stderr, ":\n");
  }
  int nsensitive = 0, nfailed = 0;
  double suggest = 0;
  char list[256] = "";
  for (int i = 0, row = 0; i < k->n; i++) {
    const swCandidate *c = &k->best[i];
    if (!c->done) continue;
    const swStudyRecheck *r = &rows[row++];
    if (!o->quiet || r->sensitive) report_design(k, i + 1, c, floor);
    if (!r->sensitive) continue;
    nfailed += r->status_half != SW_EVAL_OK;
    size_t used = strlen(list);
    snprintf(list + used, sizeof list - used, "%s%ld", nsensitive ? ", " : "", r->index);
    if (!nsensitive++ && r->dt > 0) suggest = r->dt * DT_SCALE;
  }
  if (nsensitive) {
    char dt[32] = "";
    if (suggest > 0) {
      char t[24];
      snprintf(dt, sizeof dt, " (--dt %s)", time_text(t, sizeof t, suggest, ""));
    }
    fprintf(stderr, "%s: warning: %d of %s (design%s %s) %s by more than %g%%%s when the step "
            "is halved: the study ranked them by the step as much as by the design, and its "
            "best may be a lucky sample; rerun it at a smaller --dt%s, see where a design's "
            "runs part with --replay STUDY N --accuracy, or make the scene less sensitive to "
            "the step (docs/optimisation.md, \"Rechecking the best designs\")\n",
            o->prog, nsensitive, which, nsensitive == 1 ? "" : "s", list,
            nsensitive == 1 ? "changes" : "change", 100 * TOLERANCE, nfailed ? " or fail" : "",
            dt);
  } else if (!o->quiet && nrows > 0) {
    fprintf(stderr, "%s: %s agree%s at dt and dt/2 within %g%%: %s objective%s converged in the "
            "step\n", o->prog, which, nrows == 1 ? "s" : "", 100 * TOLERANCE,
            nrows == 1 ? "its" : "their", nrows == 1 ? " is" : "s are");
  }
  fflush(stderr);
}

int sw_recheck_run(swRecheck *k, swPool *pool, swStudyFile *f) {
  const swStudyOptions *o = k->o;
  const int np = o->nparam;
  for (int i = 0; i < k->n; i++)   /* what a resumed file holds */
    for (long j = 0; j < k->nstored; j++) {
      const swStudyRecheck *s = &k->stored[j];
      swCandidate *c = &k->best[i];
      if (s->index != c->row.index || s->status_half == SW_EVAL_PENDING) continue;
      c->row.dt = s->dt;
      c->row.status_half = s->status_half;
      c->row.objective_half = s->objective_half;
      c->row.score_half = s->score_half;
      c->done = c->stored = 1;
    }
  long *index = malloc(((size_t)k->n + 1) * sizeof *index);
  double *P = malloc(((size_t)k->n + 1) * ((size_t)np + 1) * sizeof *P);
  swStudyRecheck *rows = calloc((size_t)k->n + 1, sizeof *rows);
  if (!index || !P || !rows) {
    free(index);
    free(P);
    free(rows);
    fprintf(stderr, "%s: out of memory for the recheck\n", o->prog);
    return SW_EIO;
  }
  long m = 0;
  for (int i = 0; i < k->n && !o->no_recheck; i++)
    if (!k->best[i].done) {
      index[m] = k->best[i].row.index;
      memcpy(P + m * np, k->best[i].P, (size_t)np * sizeof *P);
      m++;
    }
  if (m > 0 && !o->quiet) {
    fprintf(stderr, "%s: rechecking the %ld best design%s at dt/2...\n", o->prog, m,
            m == 1 ? "" : "s");
    fflush(stderr);
  }
  int rc = m > 0 ? sw_pool_run(pool, m, index, P, DT_SCALE, on_recheck, k) : SW_OK;
  double floor = size_floor(k);
  int nrows = 0, evaluated = 0;
  for (int i = 0; i < k->n; i++)
    if (k->best[i].done) {
      judge(&k->best[i].row, floor);
      rows[nrows++] = k->best[i].row;
      evaluated += !k->best[i].stored;
    }
  if (sw_study_file_recheck(f, rows, nrows, TOLERANCE, floor) != SW_OK) {
    fprintf(stderr, "%s: cannot write /recheck to %s\n", o->prog, o->path);
    if (rc == SW_OK) rc = SW_EIO;
  }
  if (o->no_recheck && nrows == 0 && !o->quiet)
    fprintf(stderr, "%s: no recheck of the best designs at dt/2 (--no-recheck)\n", o->prog);
  report(k, rows, nrows, floor, evaluated);
  if (rc == SW_EINTERRUPT)
    fprintf(stderr, "%s: the recheck at dt/2 was interrupted (%d of %d designs rechecked, in "
            "/recheck); continue it with: %s --resume %s\n", o->prog, nrows, k->n, o->prog,
            o->path);
  free(index);
  free(P);
  free(rows);
  return rc;
}
