/* cmaes.c — the (mu/mu_w, lambda)-CMA-ES of Hansen's tutorial, ask/tell,
 * with Hansen's box transformation and IPOP restarts.
 *
 * Design.  The state is the tutorial's: mean m, step size sigma, the
 * covariance matrix C = B D^2 B^T with its eigenvectors B and the square
 * roots D of its eigenvalues, and the two evolution paths p_sigma and p_c.
 * A generation is (Hansen, "The CMA Evolution Strategy: A Tutorial",
 * arXiv:1604.00772, App. A; equation numbers are the tutorial's):
 *
 *   (38-40) z_k ~ N(0, I), y_k = B D z_k, x_k = m + sigma y_k, k = 1..lambda
 *   (41)    <y>_w = sum_{i<=mu} w_i y_{i:lambda}     (i:lambda: i-th best)
 *   (42)    m <- m + c_m sigma <y>_w,  c_m = 1
 *   (43)    p_s <- (1 - c_s) p_s + sqrt(c_s (2 - c_s) mu_eff) C^-1/2 <y>_w
 *   (44)    sigma <- sigma exp(c_s / d_s (|p_s| / E|N(0,I)| - 1))
 *   (45)    p_c <- (1 - c_c) p_c + h_s sqrt(c_c (2 - c_c) mu_eff) <y>_w
 *   (46)    w°_i = w_i, or w_i n / |C^-1/2 y_{i:lambda}|^2 where w_i < 0
 *   (47)    C <- (1 + c_1 delta(h_s) - c_1 - c_mu sum_j w_j) C + c_1 p_c p_c^T
 *                + c_mu sum_{i<=lambda} w°_i y_{i:lambda} y_{i:lambda}^T
 *
 * with h_s = 1 when |p_s| / sqrt(1 - (1 - c_s)^(2(g+1))) < (1.4 + 2/(n+1))
 * E|N(0,I)|, else 0, and delta(h_s) = (1 - h_s) c_c (2 - c_c).  The weights
 * are the tutorial's log weights w'_i = ln((lambda + 1) / 2) - ln i for all
 * lambda ranks (49): the first mu = floor(lambda / 2) are positive, sum to
 * 1 and alone move the mean; mu_eff = 1 / sum_{i<=mu} w_i^2.  The rest are
 * negative, scaled (53) so that C stays positive definite, and only update
 * C: the "active" update, which the tutorial's Table 1 makes the default
 * and which pycma uses.  `active = 0` sets them to zero (the (mu/mu_w,
 * lambda)-CMA-ES of Hansen & Kern 2004 and purecma).  Table 1:
 *   c_s = (mu_eff + 2) / (n + mu_eff + 5),
 *   d_s = 1 + 2 max(0, sqrt((mu_eff - 1) / (n + 1)) - 1) + c_s,
 *   c_c = (4 + mu_eff / n) / (n + 4 + 2 mu_eff / n),
 *   c_1 = 2 / ((n + 1.3)^2 + mu_eff),
 *   c_mu = min(1 - c_1, 2 (1/4 + mu_eff + 1/mu_eff - 2) / ((n + 2)^2 + mu_eff)),
 *   negative weights: w'_i min(1 + c_1/c_mu, 1 + 2 mu_eff^- / (mu_eff + 2),
 *                     (1 - c_1 - c_mu) / (n c_mu)) / sum_{j>mu} |w'_j|.
 * E|N(0,I)| = sqrt(n) (1 - 1/(4n) + 1/(21 n^2)).
 *
 * The eigendecomposition (GSL's gsl_eigen_symmv, eigenvalues ascending) is
 * lazy, as the tutorial's App. B.2 suggests: it is redone only when
 * max(1, floor(1 / (10 n (c_1 + c_mu)))) generations have passed since the
 * last, so a generation costs O(n^2) per candidate; between decompositions
 * samples and C^-1/2 use the last B and D.  C is kept exactly symmetric
 * (the upper triangle is updated and mirrored).
 *
 * Termination (tutorial App. B.3, with Auger & Hansen 2005 for the erratum
 * of NoEffectCoord: any coordinate, not each) is checked after each update;
 * `sw_cmaes_stop` names the criterion.  The histories it needs are rings
 * sized at sw_cmaes_new for the largest need (the stagnation window is at
 * most 20000 generations), so nothing is allocated afterwards.
 *
 * Bounds.  The study works in the unit cube, so ask() must return points
 * in the box.  The search runs unconstrained on a genotype x and each
 * coordinate is mapped into [lo, hi] by Hansen's BoundTransform (the
 * piecewise quadratic-linear map of his C and Python codes, sw_cmaes_box
 * below): the identity on [lo + al, hi - au], a parabola on each margin
 * that meets the bound with zero slope, and mirrored and periodic outside,
 * al = min((hi - lo)/2, (1 + |lo|)/20), au likewise with hi.  A bound may be
 * infinite: a coordinate bounded on one side is mirrored at that side only
 * (no period), one with both bounds infinite is not transformed.  The map is
 * continuous with a continuous slope, so the loss seen by the search stays
 * as smooth as it was, and an optimum on a bound is the bottom of a
 * parabola in the genotype, which CMA-ES finds like any other.  Candidates
 * are ranked by the loss of the mapped point; updates use the genotype.
 * Without bounds the map is the identity.
 *
 * Failures.  A loss of +INFINITY (or NaN) ranks after every finite loss,
 * and equal losses rank by index, so a generation's order is a total order
 * of (loss, index): the update is then bitwise reproducible and a study
 * survives runs that went unstable.  Failed candidates take the last ranks,
 * so with the active update they carry the most negative weights and the
 * distribution shrinks away from where runs fail.
 *
 * IPOP (Auger & Hansen, "A restart CMA evolution strategy with increasing
 * population size", CEC 2005): when a run stops for any criterion but
 * ftarget or maxfevals and restarts remain, the next run starts with lambda
 * multiplied by incpopsize (2), sigma0, C = I, empty paths and the mean
 * drawn uniformly in the box (x0's coordinate where a bound is infinite); the best-so-far
 * and the evaluation count carry over, and the random stream continues. */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

#include "cmaes.h"
#include "rng.h"

enum { STAG_MAX = 20000 }; /* longest stagnation window, generations (App. B.3) */

struct swCmaes {
  swCmaesOptions o;       /* copy; x0/lo/hi point at our own arrays below     */
  int n;
  int lambda0, lambda, lambda_max, mu;
  int restarts_done;
  swRng rng;

  /* strategy parameters of the current lambda (Table 1) */
  double *w;              /* (lambda_max) recombination weights, by rank      */
  double wsum;            /* sum of all lambda weights (1 without active)     */
  double mueff, cs, ds, cc, c1, cmu, chin;
  long eigen_gap;         /* generations between eigendecompositions          */
  long maxiter;           /* of this run                                      */

  /* distribution */
  double *m;              /* (n) mean, genotype                               */
  double sigma;
  double *C, *B, *D;      /* (n*n) covariance, eigenvectors (columns); (n) sqrt eigenvalues */
  double *ps, *pc;        /* (n) evolution paths                              */
  long g;                 /* generations of this run                          */
  long g_eigen;           /* g at the last eigendecomposition                 */

  /* the pending generation */
  int asked;              /* 1: X, Y, Xp hold candidates not yet told         */
  double *Xg, *Y, *Xp;    /* (lambda_max*n) genotypes, steps y_k, candidates in the box */
  double *loss;           /* (lambda_max) the last told losses                */
  int *idx;               /* (lambda_max) ranking                             */
  double *yw, *t1, *t2;   /* (n) scratch                                      */

  /* termination */
  int stop;               /* swCmaesStop of the whole optimisation            */
  char why[160];
  double *hist;           /* ring of the best loss of the last hist_cap generations */
  int hist_cap;
  double *stag_best, *stag_med; /* rings of STAG_MAX                          */
  double *scratch;        /* (STAG_MAX) for medians                           */

  /* results */
  double *best_x;         /* (n)                                              */
  double best_loss;
  long best_eval;
  long evals, gens_total;

  /* bounds and start (copies) */
  double *x0, *lo, *hi;

  /* eigendecomposition */
  gsl_eigen_symmv_workspace *ws;
  double *Ctmp, *eval;    /* (n*n), (n)                                       */
};

/* ---- Hansen's box transformation ---- */

static void box_margins(double lo, double hi, double *al, double *au) {
  *al = fmin((hi - lo) / 2, (1 + fabs(lo)) / 20); /* (hi - lo) / 2 is +inf one-sided */
  *au = fmin((hi - lo) / 2, (1 + fabs(hi)) / 20);
}

double sw_cmaes_box(double x, double lo, double hi) {
  if (isinf(lo) && isinf(hi)) return x; /* unbounded coordinate */
  double al, au;
  box_margins(lo, hi, &al, &au);
  if (x >= lo + al && x <= hi - au) return x; /* the identity part, the common case */
  if (isinf(hi)) { /* lower bound only: mirror at lo - al, then the parabola */
    if (x < lo - al) x = 2 * (lo - al) - x;
    if (x < lo + al) x = lo + (x - (lo - al)) * (x - (lo - al)) / (4 * al);
    return fmax(lo, x);
  }
  if (isinf(lo)) { /* upper bound only */
    if (x > hi + au) x = 2 * (hi + au) - x;
    if (x > hi - au) x = hi - (x - (hi + au)) * (x - (hi + au)) / (4 * au);
    return fmin(hi, x);
  }
  /* shift by whole periods into [xlow, xlow + r): the map is periodic with
   * period r = 2 (hi - lo + al + au) */
  const double xlow = lo - 2 * al - (hi - lo) / 2;
  const double r = 2 * (hi - lo + al + au);
  if (x < xlow || x >= xlow + r) x -= r * floor((x - xlow) / r);
  /* mirror at lo - al and hi + au into [lo - al, hi + au] */
  if (x < lo - al) x = 2 * (lo - al) - x;
  if (x > hi + au) x = 2 * (hi + au) - x;
  /* the parabolas: value lo with slope 0 at lo - al, value lo + al with
   * slope 1 at lo + al (and likewise at the top) */
  if (x < lo + al) x = lo + (x - (lo - al)) * (x - (lo - al)) / (4 * al);
  else if (x > hi - au) x = hi - (x - (hi + au)) * (x - (hi + au)) / (4 * au);
  return fmin(hi, fmax(lo, x)); /* round-off only */
}

/* A genotype that the box maps to y in [lo, hi] (the branch next to the
 * box), so a run started at x0 has its mean's image at x0. */
static double box_inverse(double y, double lo, double hi) {
  if (isinf(lo) && isinf(hi)) return y;
  double al, au;
  box_margins(lo, hi, &al, &au);
  if (isfinite(lo) && y < lo + al) return lo - al + sqrt(4 * al * (y - lo));
  if (isfinite(hi) && y > hi - au) return hi + au - sqrt(4 * au * (hi - y));
  return y;
}

static void to_box(const swCmaes *c, const double *x, double *out) {
  for (int i = 0; i < c->n; i++) out[i] = c->lo ? sw_cmaes_box(x[i], c->lo[i], c->hi[i]) : x[i];
}

/* ---- sorting without allocation (heapsort) ---- */

/* Candidate a ranks before b: smaller loss, failures (+inf, NaN) last,
 * ties by index. */
static int ranks_before(const double *f, int a, int b) {
  const double fa = isnan(f[a]) ? INFINITY : f[a], fb = isnan(f[b]) ? INFINITY : f[b];
  if (fa != fb) return fa < fb;
  return a < b;
}

static void rank_sift(const double *f, int *idx, int root, int end) {
  for (;;) {
    int child = 2 * root + 1;
    if (child >= end) return;
    if (child + 1 < end && ranks_before(f, idx[child], idx[child + 1])) child++;
    if (!ranks_before(f, idx[root], idx[child])) return;
    const int t = idx[root];
    idx[root] = idx[child];
    idx[child] = t;
    root = child;
  }
}

static void rank(const double *f, int *idx, int lam) {
  for (int k = 0; k < lam; k++) idx[k] = k;
  for (int k = lam / 2 - 1; k >= 0; k--) rank_sift(f, idx, k, lam);
  for (int end = lam - 1; end > 0; end--) {
    const int t = idx[0];
    idx[0] = idx[end];
    idx[end] = t;
    rank_sift(f, idx, 0, end);
  }
}

static void dsift(double *a, int root, int end) {
  for (;;) {
    int child = 2 * root + 1;
    if (child >= end) return;
    if (child + 1 < end && a[child] < a[child + 1]) child++;
    if (!(a[root] < a[child])) return;
    const double t = a[root];
    a[root] = a[child];
    a[child] = t;
    root = child;
  }
}

/* Median of k values, sorting a copy in scratch (NaN counts as +inf). */
static double median(double *scratch, const double *ring, int cap, long first, int k) {
  for (int i = 0; i < k; i++) {
    const double v = ring[(first + i) % cap];
    scratch[i] = isnan(v) ? INFINITY : v;
  }
  for (int i = k / 2 - 1; i >= 0; i--) dsift(scratch, i, k);
  for (int end = k - 1; end > 0; end--) {
    const double t = scratch[0];
    scratch[0] = scratch[end];
    scratch[end] = t;
    dsift(scratch, 0, end);
  }
  return k % 2 ? scratch[k / 2] : 0.5 * (scratch[k / 2 - 1] + scratch[k / 2]);
}

/* ---- parameters and (re)initialisation ---- */

static int default_lambda(int n) { return 4 + (int)floor(3 * log((double)n)); }

/* Table 1 of the tutorial for population size lambda: the log weights
 * w'_i = ln((lambda + 1) / 2) - ln i, i = 1..lambda (49), the positive ones
 * summing to 1, mu_eff of those; with `active`, the negative ones scaled by
 * min(alpha_mu^-, alpha_mueff^-, alpha_posdef^-) / sum |w'_j| (53), else 0. */
static void set_parameters(swCmaes *c, int lambda) {
  const int n = c->n;
  c->lambda = lambda;
  c->mu = lambda / 2;
  double pos = 0, pos2 = 0, neg = 0, neg2 = 0;
  for (int i = 0; i < lambda; i++) {
    c->w[i] = log((lambda + 1) / 2.0) - log(i + 1.0);
    if (i < c->mu) pos += c->w[i], pos2 += c->w[i] * c->w[i];
    else neg += fabs(c->w[i]), neg2 += c->w[i] * c->w[i];
  }
  c->mueff = pos * pos / pos2;
  const double me = c->mueff;
  c->cs = (me + 2) / (n + me + 5);                                    /* (55) */
  c->ds = 1 + 2 * fmax(0, sqrt((me - 1) / (n + 1)) - 1) + c->cs;      /* (55) */
  c->cc = (4 + me / n) / (n + 4 + 2 * me / n);                        /* (56) */
  c->c1 = 2 / ((n + 1.3) * (n + 1.3) + me);                           /* (57) */
  c->cmu = fmin(1 - c->c1, 2 * (0.25 + me + 1 / me - 2) / ((n + 2.0) * (n + 2.0) + me)); /* (58) */
  const double mueff_neg = neg > 0 ? neg * neg / neg2 : 0;
  const double a_mu = 1 + c->c1 / c->cmu;                             /* (50) */
  const double a_mueff = 1 + 2 * mueff_neg / (me + 2);                /* (51) */
  const double a_posdef = (1 - c->c1 - c->cmu) / (n * c->cmu);        /* (52) */
  const double scale_neg = c->o.active && neg > 0 ? fmin(a_mu, fmin(a_mueff, a_posdef)) / neg : 0;
  c->wsum = 0;
  for (int i = 0; i < lambda; i++) {
    c->w[i] *= i < c->mu ? 1 / pos : scale_neg;
    c->wsum += c->w[i];
  }
  c->chin = sqrt((double)n) * (1 - 1 / (4.0 * n) + 1 / (21.0 * n * n));
  c->eigen_gap = (long)floor(1 / (10 * n * (c->c1 + c->cmu)));
  if (c->eigen_gap < 1) c->eigen_gap = 1;
  c->maxiter = c->o.maxiter > 0 ? c->o.maxiter
                                : (long)(100 + 150 * (n + 3.0) * (n + 3.0) / sqrt((double)lambda));
}

/* A fresh run: m from `mean` (a point in the box), sigma0, C = B = I. */
static void start_run(swCmaes *c, const double *mean) {
  const int n = c->n;
  for (int i = 0; i < n; i++) {
    c->m[i] = c->lo ? box_inverse(mean[i], c->lo[i], c->hi[i]) : mean[i];
    c->ps[i] = c->pc[i] = 0;
    c->D[i] = 1;
    for (int j = 0; j < n; j++) c->C[i * n + j] = c->B[i * n + j] = (i == j);
  }
  c->sigma = c->o.sigma0;
  c->g = 0;
  c->g_eigen = 0;
  c->asked = 0;
}

/* ---- creation ---- */

void sw_cmaes_options_init(swCmaesOptions *o) {
  memset(o, 0, sizeof *o);
  o->ftarget = -INFINITY;
  o->tolfun = 1e-12;
  o->tolxup = 1e4;
  o->condition_max = 1e14;
  o->incpopsize = 2;
  o->active = 1;
}

static int check_options(const swCmaesOptions *o, char *err, size_t errlen) {
#define BAD(...) (snprintf(err, errlen, __VA_ARGS__), 0)
  if (o->n < 1 || o->n > 10000) return BAD("cmaes: n must be 1 to 10000, is %d", o->n);
  if (!(o->sigma0 > 0) || !isfinite(o->sigma0))
    return BAD("cmaes: sigma0 must be > 0 and finite, is %g", o->sigma0);
  if (o->lambda != 0 && o->lambda < 2)
    return BAD("cmaes: lambda must be >= 2 (or 0 for the default), is %d", o->lambda);
  if (!o->lo != !o->hi) return BAD("cmaes: lo and hi go together (one is NULL)");
  if (!o->x0 && !o->lo) return BAD("cmaes: no x0 and no bounds: nowhere to start");
  for (int i = 0; i < o->n; i++) {
    if (o->lo && !(o->lo[i] < o->hi[i] && o->lo[i] < INFINITY && o->hi[i] > -INFINITY))
      return BAD("cmaes: coordinate %d: bounds [%g, %g] need lo < hi", i, o->lo[i], o->hi[i]);
    if (!o->x0 && !(isfinite(o->lo[i]) && isfinite(o->hi[i])))
      return BAD("cmaes: no x0 and coordinate %d's bounds [%g, %g] have no centre", i, o->lo[i],
                 o->hi[i]);
    if (o->x0 && !isfinite(o->x0[i])) return BAD("cmaes: x0[%d] = %g is not finite", i, o->x0[i]);
    if (o->x0 && o->lo && !(o->x0[i] >= o->lo[i] && o->x0[i] <= o->hi[i]))
      return BAD("cmaes: x0[%d] = %g is outside its bounds [%g, %g]", i, o->x0[i], o->lo[i],
                 o->hi[i]);
  }
  if (isnan(o->ftarget)) return BAD("cmaes: ftarget is NaN");
  if (o->maxfevals < 0 || o->maxiter < 0) return BAD("cmaes: maxfevals and maxiter must be >= 0");
  if (!(o->tolfun >= 0) || !(o->tolx >= 0) || !(o->tolxup > 0) || !(o->condition_max > 1))
    return BAD("cmaes: tolfun and tolx must be >= 0, tolxup > 0 and condition_max > 1");
  if (o->restarts < 0 || o->restarts > 30) return BAD("cmaes: restarts must be 0 to 30, is %d", o->restarts);
  if (!(o->incpopsize >= 1) || !isfinite(o->incpopsize))
    return BAD("cmaes: incpopsize must be >= 1, is %g", o->incpopsize);
#undef BAD
  return 1;
}

/* lambda of restart k: lambda0 incpopsize^k, rounded down. */
static double lambda_of(const swCmaes *c, int k) {
  return floor(c->lambda0 * pow(c->o.incpopsize, k) + 1e-9);
}

swCmaes *sw_cmaes_new(const swCmaesOptions *o, char *err, size_t errlen) {
  if (err && errlen) err[0] = 0;
  if (!o) {
    snprintf(err, errlen, "cmaes: no options");
    return NULL;
  }
  if (!check_options(o, err, errlen)) return NULL;
  swCmaes *c = calloc(1, sizeof *c);
  if (!c) goto oom;
  const int n = o->n;
  c->o = *o;
  c->n = n;
  c->lambda0 = o->lambda ? o->lambda : default_lambda(n);
  const double lmax = lambda_of(c, o->restarts);
  if (lmax > 1e7 || lmax * n > 1e8) {
    snprintf(err, errlen, "cmaes: %d restarts would reach lambda = %.0f in %d dimensions: too large",
             o->restarts, lmax, n);
    free(c);
    return NULL;
  }
  c->lambda_max = (int)lmax;
  const size_t nn = (size_t)n * n, ln = (size_t)c->lambda_max * n, lm = (size_t)c->lambda_max;
  c->hist_cap = 10 + (int)ceil(30.0 * n / c->lambda0); /* the longest: smallest lambda */
#define ALLOC(p, k) if (!((p) = calloc((k), sizeof *(p)))) goto oom
  ALLOC(c->w, lm);
  ALLOC(c->m, n); ALLOC(c->ps, n); ALLOC(c->pc, n); ALLOC(c->D, n);
  ALLOC(c->C, nn); ALLOC(c->B, nn); ALLOC(c->Ctmp, nn); ALLOC(c->eval, n);
  ALLOC(c->Xg, ln); ALLOC(c->Y, ln); ALLOC(c->Xp, ln);
  ALLOC(c->loss, lm); ALLOC(c->idx, lm);
  ALLOC(c->yw, n); ALLOC(c->t1, n); ALLOC(c->t2, n);
  ALLOC(c->hist, c->hist_cap);
  ALLOC(c->stag_best, STAG_MAX); ALLOC(c->stag_med, STAG_MAX); ALLOC(c->scratch, STAG_MAX);
  ALLOC(c->best_x, n); ALLOC(c->x0, n);
  if (o->lo) {
    ALLOC(c->lo, n);
    ALLOC(c->hi, n);
    memcpy(c->lo, o->lo, n * sizeof *c->lo);
    memcpy(c->hi, o->hi, n * sizeof *c->hi);
  }
#undef ALLOC
  if (!(c->ws = gsl_eigen_symmv_alloc((size_t)n))) goto oom;
  for (int i = 0; i < n; i++) c->x0[i] = o->x0 ? o->x0[i] : 0.5 * (c->lo[i] + c->hi[i]);
  c->o.x0 = c->x0;
  c->o.lo = c->lo;
  c->o.hi = c->hi;
  if (!(c->o.tolx > 0)) c->o.tolx = 1e-12 * o->sigma0;
  sw_rng_stream(&c->rng, o->seed, 0);
  memcpy(c->best_x, c->x0, n * sizeof *c->best_x);
  c->best_loss = INFINITY;
  set_parameters(c, c->lambda0);
  start_run(c, c->x0);
  return c;
oom:
  snprintf(err, errlen, "cmaes: out of memory");
  sw_cmaes_free(c);
  return NULL;
}

void sw_cmaes_free(swCmaes *c) {
  if (!c) return;
  if (c->ws) gsl_eigen_symmv_free(c->ws);
  free(c->w); free(c->m); free(c->ps); free(c->pc); free(c->D);
  free(c->C); free(c->B); free(c->Ctmp); free(c->eval);
  free(c->Xg); free(c->Y); free(c->Xp); free(c->loss); free(c->idx);
  free(c->yw); free(c->t1); free(c->t2);
  free(c->hist); free(c->stag_best); free(c->stag_med); free(c->scratch);
  free(c->best_x); free(c->x0); free(c->lo); free(c->hi);
  free(c);
}

/* ---- ask ---- */

void sw_cmaes_ask(swCmaes *c, double *X) {
  const int n = c->n, lam = c->lambda;
  if (!c->asked) {
    for (int k = 0; k < lam; k++) {
      double *y = c->Y + (size_t)k * n, *x = c->Xg + (size_t)k * n;
      for (int j = 0; j < n; j++) c->t1[j] = c->D[j] * sw_rng_normal(&c->rng); /* D z, (38) */
      for (int i = 0; i < n; i++) {                                              /* (39)  */
        double s = 0;
        for (int j = 0; j < n; j++) s += c->B[i * n + j] * c->t1[j];
        y[i] = s;
        x[i] = c->m[i] + c->sigma * s;                                           /* (40)  */
      }
      to_box(c, x, c->Xp + (size_t)k * n);
    }
    c->asked = 1;
  }
  memcpy(X, c->Xp, (size_t)lam * n * sizeof *X);
}

/* ---- tell ---- */

static void eigen(swCmaes *c) {
  const int n = c->n;
  memcpy(c->Ctmp, c->C, (size_t)n * n * sizeof *c->C);
  gsl_matrix_view A = gsl_matrix_view_array(c->Ctmp, (size_t)n, (size_t)n);
  gsl_matrix_view V = gsl_matrix_view_array(c->B, (size_t)n, (size_t)n);
  gsl_vector_view e = gsl_vector_view_array(c->eval, (size_t)n);
  gsl_eigen_symmv(&A.matrix, &e.vector, &V.matrix, c->ws);
  gsl_eigen_symmv_sort(&e.vector, &V.matrix, GSL_EIGEN_SORT_VAL_ASC);
  /* C is positive definite in exact arithmetic (the negative weights are
   * bounded by alpha_posdef, (53)); a round-off eigenvalue <= 0 is lifted
   * to where conditioncov stops. */
  const double emax = fmax(c->eval[n - 1], DBL_MIN);
  for (int i = 0; i < n; i++) c->D[i] = sqrt(fmax(c->eval[i], emax * 1e-20));
  c->g_eigen = c->g;
}

static void set_stop(swCmaes *c, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void set_stop(swCmaes *c, int code, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  c->stop = code;
  int k = snprintf(c->why, sizeof c->why, "%s (", sw_cmaes_stop_name(code));
  if (k < 0 || (size_t)k >= sizeof c->why) k = (int)sizeof c->why - 1;
  vsnprintf(c->why + k, sizeof c->why - (size_t)k, fmt, ap);
  va_end(ap);
  const size_t len = strlen(c->why);
  snprintf(c->why + len, sizeof c->why - len, ")");
}

/* The run's termination criteria (App. B.3); sets c->stop, returns it. */
static int check_run(swCmaes *c) {
  const int n = c->n, lam = c->lambda;
  const double *f = c->loss;
  /* the histories are full for hist_len generations of this lambda */
  const int hist_len = 10 + (int)ceil(30.0 * n / lam);
  if (c->g >= c->maxiter) {
    set_stop(c, SW_CMAES_MAXITER, "%ld generations", c->g);
    return c->stop;
  }
  if (c->g >= hist_len) {
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < hist_len; k++) {
      const double v = c->hist[(c->g - 1 - k) % c->hist_cap];
      lo = fmin(lo, v);
      hi = fmax(hi, v);
    }
    if (hi - lo == 0) {
      set_stop(c, SW_CMAES_EQUALFUNVALS, "best losses of the last %d generations equal", hist_len);
      return c->stop;
    }
    for (int k = 0; k < lam; k++) {
      lo = fmin(lo, f[k]);
      hi = fmax(hi, isnan(f[k]) ? INFINITY : f[k]);
    }
    if (hi - lo < c->o.tolfun) {
      set_stop(c, SW_CMAES_TOLFUN, "range %.3g < %.3g", hi - lo, c->o.tolfun);
      return c->stop;
    }
  }
  /* TolX: every coordinate's sd and sigma p_c below tolx */
  int small = 1;
  for (int i = 0; i < n && small; i++)
    small = c->sigma * sqrt(c->C[i * n + i]) < c->o.tolx && c->sigma * fabs(c->pc[i]) < c->o.tolx;
  if (small) {
    set_stop(c, SW_CMAES_TOLX, "sd < %.3g in every coordinate", c->o.tolx);
    return c->stop;
  }
  /* TolXUp: sigma sqrt(max eig) grew by more than tolxup (D0 = I) */
  if (c->sigma * c->D[n - 1] > c->o.tolxup * c->o.sigma0) {
    set_stop(c, SW_CMAES_TOLXUP, "sigma sqrt(max eig C) = %.3g > %.3g sigma0", c->sigma * c->D[n - 1],
             c->o.tolxup);
    return c->stop;
  }
  /* NoEffectAxis: 0.1 sd along principal axis g mod n leaves m unchanged */
  {
    const int a = (int)(c->g % n);
    int same = 1;
    for (int i = 0; i < n && same; i++)
      same = c->m[i] + 0.1 * c->sigma * c->D[a] * c->B[i * n + a] == c->m[i];
    if (same) {
      set_stop(c, SW_CMAES_NOEFFECTAXIS, "axis %d", a);
      return c->stop;
    }
  }
  /* NoEffectCoord: 0.2 sd in some coordinate leaves m unchanged */
  for (int i = 0; i < n; i++)
    if (c->m[i] + 0.2 * c->sigma * sqrt(c->C[i * n + i]) == c->m[i]) {
      set_stop(c, SW_CMAES_NOEFFECTCOORD, "coordinate %d", i);
      return c->stop;
    }
  /* ConditionCov */
  {
    const double cond = (c->D[n - 1] / c->D[0]) * (c->D[n - 1] / c->D[0]);
    if (cond > c->o.condition_max) {
      set_stop(c, SW_CMAES_CONDITIONCOV, "condition %.3g > %.3g", cond, c->o.condition_max);
      return c->stop;
    }
  }
  /* Stagnation: over the last 20% of the generations (at least
   * 120 + 30 n / lambda, at most STAG_MAX) the median of the newest 30% of
   * the best and of the median losses is no better than that of the
   * oldest 30%. */
  {
    long win = (long)(0.2 * c->g);
    const long wmin = 120 + (long)ceil(30.0 * n / lam);
    if (win < wmin) win = wmin;
    if (win > STAG_MAX) win = STAG_MAX;
    if (c->g >= win) {
      const int k = (int)(0.3 * win);
      const long old = c->g - win, recent = c->g - k;
      const double bo = median(c->scratch, c->stag_best, STAG_MAX, old, k);
      const double br = median(c->scratch, c->stag_best, STAG_MAX, recent, k);
      const double mo = median(c->scratch, c->stag_med, STAG_MAX, old, k);
      const double mr = median(c->scratch, c->stag_med, STAG_MAX, recent, k);
      if (br >= bo && mr >= mo) {
        set_stop(c, SW_CMAES_STAGNATION, "no progress in %ld generations", win);
        return c->stop;
      }
    }
  }
  return 0;
}

void sw_cmaes_tell(swCmaes *c, const double *loss) {
  if (c->stop || !c->asked) return;
  const int n = c->n, lam = c->lambda, mu = c->mu;
  for (int k = 0; k < lam; k++) c->loss[k] = isnan(loss[k]) ? INFINITY : loss[k];
  rank(c->loss, c->idx, lam);
  for (int k = 0; k < lam; k++) { /* best so far, in telling order */
    c->evals++;
    if (c->loss[k] < c->best_loss) {
      c->best_loss = c->loss[k];
      c->best_eval = c->evals;
      memcpy(c->best_x, c->Xp + (size_t)k * n, n * sizeof *c->best_x);
    }
  }

  /* (41), (42) */
  for (int i = 0; i < n; i++) c->yw[i] = 0;
  for (int r = 0; r < mu; r++) {
    const double *y = c->Y + (size_t)c->idx[r] * n;
    for (int i = 0; i < n; i++) c->yw[i] += c->w[r] * y[i];
  }
  for (int i = 0; i < n; i++) c->m[i] += c->sigma * c->yw[i];

  /* (43): C^-1/2 <y>_w = B D^-1 B^T <y>_w */
  for (int j = 0; j < n; j++) {
    double s = 0;
    for (int i = 0; i < n; i++) s += c->B[i * n + j] * c->yw[i];
    c->t1[j] = s / c->D[j];
  }
  const double as = sqrt(c->cs * (2 - c->cs) * c->mueff);
  double psn = 0;
  for (int i = 0; i < n; i++) {
    double s = 0;
    for (int j = 0; j < n; j++) s += c->B[i * n + j] * c->t1[j];
    c->ps[i] = (1 - c->cs) * c->ps[i] + as * s;
    psn += c->ps[i] * c->ps[i];
  }
  psn = sqrt(psn);

  /* h_sigma, (45) */
  const double norm = psn / sqrt(1 - pow(1 - c->cs, 2.0 * (c->g + 1)));
  const int hs = norm < (1.4 + 2.0 / (n + 1)) * c->chin;
  const double ac = hs * sqrt(c->cc * (2 - c->cc) * c->mueff);
  for (int i = 0; i < n; i++) c->pc[i] = (1 - c->cc) * c->pc[i] + ac * c->yw[i];

  /* (46): the negative weights act on y scaled to the length sqrt(n) in
   * the metric of C, w°_i = w_i n / |C^-1/2 y_i|^2; Y is not needed after
   * this generation, so the scaling is done in place. */
  for (int r = c->mu; r < lam; r++) {
    if (!(c->w[r] < 0)) continue; /* w'_i = 0 at i = (lambda + 1) / 2 for odd lambda */
    double *y = c->Y + (size_t)c->idx[r] * n;
    for (int j = 0; j < n; j++) {
      double s = 0;
      for (int i = 0; i < n; i++) s += c->B[i * n + j] * y[i];
      c->t1[j] = s / c->D[j];
    }
    double q = 0;
    for (int j = 0; j < n; j++) q += c->t1[j] * c->t1[j]; /* |C^-1/2 y|^2 = |D^-1 B^T y|^2 */
    const double f = q > 0 ? sqrt(n / q) : 0;
    for (int i = 0; i < n; i++) y[i] *= f;
  }
  /* (47), upper triangle, then mirrored */
  const int nw = c->o.active ? lam : mu;
  const double dh = (1 - hs) * c->cc * (2 - c->cc);
  const double keep = 1 + c->c1 * dh - c->c1 - c->cmu * c->wsum;
  for (int i = 0; i < n; i++)
    for (int j = i; j < n; j++) {
      double rmu = 0;
      for (int r = 0; r < nw; r++) {
        const double *y = c->Y + (size_t)c->idx[r] * n;
        rmu += c->w[r] * y[i] * y[j];
      }
      const double v = keep * c->C[i * n + j] + c->c1 * c->pc[i] * c->pc[j] + c->cmu * rmu;
      c->C[i * n + j] = c->C[j * n + i] = v;
    }

  /* (44) */
  c->sigma *= exp(c->cs / c->ds * (psn / c->chin - 1));

  /* histories: best and median loss of this generation */
  const double fbest = c->loss[c->idx[0]];
  const double fmed = c->loss[c->idx[lam / 2]];
  c->hist[c->g % c->hist_cap] = fbest;
  c->stag_best[c->g % STAG_MAX] = fbest;
  c->stag_med[c->g % STAG_MAX] = fmed;
  c->g++;
  c->gens_total++;
  c->asked = 0;
  if (c->g - c->g_eigen >= c->eigen_gap) eigen(c);

  /* termination: the optimisation's own criteria first, then the run's */
  if (c->best_loss <= c->o.ftarget) {
    set_stop(c, SW_CMAES_FTARGET, "best %.6g <= %.6g", c->best_loss, c->o.ftarget);
    return;
  }
  if (c->o.maxfevals > 0 && c->evals >= c->o.maxfevals) {
    set_stop(c, SW_CMAES_MAXFEVALS, "%ld evaluations", c->evals);
    return;
  }
  if (!check_run(c)) return;
  if (c->restarts_done >= c->o.restarts) {
    if (c->restarts_done > 0) {
      const size_t len = strlen(c->why);
      snprintf(c->why + len, sizeof c->why - len, " after %d restarts", c->restarts_done);
    }
    return;
  }
  /* IPOP restart */
  c->restarts_done++;
  c->stop = 0;
  set_parameters(c, (int)lambda_of(c, c->restarts_done));
  for (int i = 0; i < n; i++) /* one uniform per coordinate, bounded or not */
    c->t2[i] = c->lo && isfinite(c->lo[i]) && isfinite(c->hi[i])
                   ? c->lo[i] + (c->hi[i] - c->lo[i]) * sw_rng_uniform(&c->rng)
                   : (sw_rng_uniform(&c->rng), c->x0[i]);
  start_run(c, c->t2);
}

/* ---- queries ---- */

static const char *const stop_names[SW_CMAES_NSTOP] = {
    "running",       "ftarget",     "maxfevals",     "maxiter",   "tolfun",
    "tolx",          "noeffectaxis", "noeffectcoord", "conditioncov", "equalfunvals",
    "stagnation",    "tolxup"};

const char *sw_cmaes_stop_name(int code) {
  return code >= 0 && code < SW_CMAES_NSTOP ? stop_names[code] : "unknown";
}

int sw_cmaes_stop(const swCmaes *c, char *why, size_t len) {
  if (why && len) snprintf(why, len, "%s", c->stop ? c->why : "running");
  return c->stop;
}

int sw_cmaes_n(const swCmaes *c) { return c->n; }
int sw_cmaes_lambda(const swCmaes *c) { return c->lambda; }
int sw_cmaes_lambda_max(const swCmaes *c) { return c->lambda_max; }
const double *sw_cmaes_best_x(const swCmaes *c) { return c->best_x; }
double sw_cmaes_best_loss(const swCmaes *c) { return c->best_loss; }
long sw_cmaes_best_evaluation(const swCmaes *c) { return c->best_eval; }
long sw_cmaes_generation(const swCmaes *c) { return c->gens_total; }
long sw_cmaes_evaluations(const swCmaes *c) { return c->evals; }
int sw_cmaes_restarts(const swCmaes *c) { return c->restarts_done; }
double sw_cmaes_sigma(const swCmaes *c) { return c->sigma; }
void sw_cmaes_mean(const swCmaes *c, double *m) { to_box(c, c->m, m); }
double sw_cmaes_axis_ratio(const swCmaes *c) { return c->D[c->n - 1] / c->D[0]; }
