/* cmaes.h — CMA-ES, ask and tell, with box bounds and IPOP restarts (an
 * internal runtime header, not part of sinew.h; the study driver uses it).
 *
 * The algorithm is Hansen's (μ/μ_w, λ)-CMA-ES as "The CMA Evolution
 * Strategy: A Tutorial" (arXiv:1604.00772) states it, with its default
 * negative weights (active CMA) or, as an option, positive ones only;
 * cmaes.c gives the equations and docs/optimisation.md the defaults, the
 * bounds, the restarts and the validation.  Losses are minimised; +INFINITY (or NaN) marks a failed
 * candidate, which ranks after every finite one.
 *
 * A generation:
 *     double *X = malloc(sw_cmaes_lambda_max(c) * n * sizeof *X), *f = ...;
 *     while (!sw_cmaes_stop(c, why, sizeof why)) {
 *       int lam = sw_cmaes_lambda(c);        // may grow at an IPOP restart
 *       sw_cmaes_ask(c, X);                  // lam x n, row-major
 *       for (int k = 0; k < lam; k++) f[k] = loss(X + k * n);
 *       sw_cmaes_tell(c, f);
 *     }
 *
 * Determinism: the same options (seed included) and the same sequence of
 * tell() values give bitwise the same asks, so a study resumes by replaying
 * the losses it stored, and its result does not depend on how many ranks
 * evaluated them.  Nothing is allocated after sw_cmaes_new. */
#ifndef SINEW_CMAES_H
#define SINEW_CMAES_H
#include <stddef.h>
#include <stdint.h>

/* Why a run stopped (sw_cmaes_stop); SW_CMAES_RUNNING is 0. */
typedef enum {
  SW_CMAES_RUNNING = 0,
  SW_CMAES_FTARGET,       /* best loss <= ftarget                              */
  SW_CMAES_MAXFEVALS,     /* evaluations (over all restarts) >= maxfevals      */
  SW_CMAES_MAXITER,       /* generations of one run >= maxiter                 */
  SW_CMAES_TOLFUN,        /* losses of the recent generations within tolfun    */
  SW_CMAES_TOLX,          /* every coordinate's standard deviation < tolx      */
  SW_CMAES_NOEFFECTAXIS,  /* a 0.1-sd step along a principal axis leaves m     */
  SW_CMAES_NOEFFECTCOORD, /* a 0.2-sd step in a coordinate leaves m            */
  SW_CMAES_CONDITIONCOV,  /* condition number of C > condition_max             */
  SW_CMAES_EQUALFUNVALS,  /* the recent generations' best losses all equal     */
  SW_CMAES_STAGNATION,    /* no progress of the best and median losses         */
  SW_CMAES_TOLXUP,        /* sigma sqrt(max eig C) grew by > tolxup: sigma0 too small */
  SW_CMAES_NSTOP
} swCmaesStop;

typedef struct {
  int n;                  /* dimension, >= 1                                        */
  const double *x0;       /* (n) initial mean; NULL: the centre of the box           */
  double sigma0;          /* initial step size, > 0, in the units of x               */
  int lambda;             /* population size; 0: 4 + floor(3 ln n) (>= 2 if given)   */
  uint64_t seed;          /* the run's random numbers: sw_rng_stream(seed, 0)        */
  int active;             /* 1: the tutorial's negative weights (active CMA, its
                           * default); 0: positive weights only                     */
  const double *lo, *hi;  /* (n) box bounds, lo < hi, both arrays or neither (NULL);
                           * -INFINITY / INFINITY leave a side unbounded            */
  /* termination; sw_cmaes_options_init sets the defaults given here */
  double ftarget;         /* stop at best loss <= ftarget; -INFINITY                 */
  long maxfevals;         /* over all restarts; 0: no limit                          */
  long maxiter;           /* per run; 0: 100 + 150 (n+3)^2 / sqrt(lambda)            */
  double tolfun;          /* 1e-12                                                   */
  double tolx;            /* 0: 1e-12 sigma0                                         */
  double tolxup;          /* 1e4                                                     */
  double condition_max;   /* 1e14                                                    */
  /* IPOP restarts (Auger & Hansen 2005): when a run stops for any reason but
   * ftarget or maxfevals, start again with lambda times incpopsize, sigma0,
   * C = I and the mean drawn uniformly in the box (x0's coordinate where a
   * bound is infinite). */
  int restarts;           /* how many; 0                                             */
  double incpopsize;      /* 2                                                       */
} swCmaesOptions;

typedef struct swCmaes swCmaes;

/* Fills o with the defaults above (n 0, x0/lo/hi NULL, sigma0 0, seed 0,
 * active 1). */
void sw_cmaes_options_init(swCmaesOptions *o);
/* NULL with the reason in err when the options are bad or memory is out. */
swCmaes *sw_cmaes_new(const swCmaesOptions *o, char *err, size_t errlen);
void sw_cmaes_free(swCmaes *c);

int sw_cmaes_n(const swCmaes *c);
/* Candidates the next ask() returns; grows at each IPOP restart. */
int sw_cmaes_lambda(const swCmaes *c);
/* The largest lambda any restart can reach: size the caller's buffers by it. */
int sw_cmaes_lambda_max(const swCmaes *c);
/* Writes lambda candidates, row-major (lambda x n), every one in the box.
 * Asking again before tell() returns the same candidates. */
void sw_cmaes_ask(swCmaes *c, double *X);
/* The losses of the last ask's candidates, in its order: smaller is better,
 * +INFINITY or NaN failed.  Updates the distribution, checks termination
 * and, when the run stopped and restarts remain, restarts. */
void sw_cmaes_tell(swCmaes *c, const double *loss);
/* 0 while running; else the swCmaesStop code, and why (if non-NULL) gets
 * its name and the figures that stopped it, e.g. "tolfun (range 8e-13 <
 * 1e-12) after 2 restarts". */
int sw_cmaes_stop(const swCmaes *c, char *why, size_t len);
/* "tolfun", "maxiter", ...: the names options and reports use. */
const char *sw_cmaes_stop_name(int code);

/* The best candidate told so far (over all restarts) and its loss; before
 * any finite loss, x0 (or the box centre) and +INFINITY. */
const double *sw_cmaes_best_x(const swCmaes *c);
double sw_cmaes_best_loss(const swCmaes *c);
long sw_cmaes_best_evaluation(const swCmaes *c);  /* 1-based; 0: none yet */
long sw_cmaes_generation(const swCmaes *c);       /* tells, all restarts  */
long sw_cmaes_evaluations(const swCmaes *c);      /* candidates told      */
int sw_cmaes_restarts(const swCmaes *c);          /* restarts so far      */
double sw_cmaes_sigma(const swCmaes *c);
/* The current mean, mapped into the box like a candidate. */
void sw_cmaes_mean(const swCmaes *c, double *m);
/* sqrt(max eig C / min eig C) at the last eigendecomposition. */
double sw_cmaes_axis_ratio(const swCmaes *c);

/* The box transformation ask() applies (Hansen's piecewise
 * quadratic-linear BoundTransform, cmaes.c): genotype x to a value in
 * [lo, hi], the identity inside [lo + al, hi - au].  Exposed for tests. */
double sw_cmaes_box(double x, double lo, double hi);
#endif
