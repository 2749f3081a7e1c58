/* test_cmaes.c — CMA-ES (cmaes.c) on the standard test functions against
 * the evaluation counts its authors published, and its contract: asks
 * inside the box, an optimum on a bound, failed candidates, bitwise replay,
 * termination reasons, and errors for bad options.
 *
 * Each case runs several seeds to f_stop and prints the median, min and
 * max evaluations beside the published figure, then asserts that every
 * seed reached f_stop and that the median is within the figure.  The
 * figures, all from CMA-ES/pycma (N. Hansen's reference implementation,
 * commit 8d16505 of 2025-09-24) since the tables of the papers (Hansen &
 * Ostermeier 2001, Hansen, Mueller & Koumoutsakos 2003, Hansen & Kern
 * 2004, Auger & Hansen 2005, BBOB) could not be read in the stored
 * corpus, are (docs/optimisation.md has the table):
 *   P1 purecma.py doctest: 4-D Rosenbrock, x0 = 0.5, sigma0 = 0.5, the
 *      tutorial's positive weights: 1712 evaluations (best at 1704), f < 1e-12.
 *   P2 evolution_strategy.py, fmin doctest: 10-D Rosenbrock, x0 = 0.1,
 *      sigma0 = 0.3: f < 1e-12 in < 8000 evaluations.
 *   P3 test.py doctest: 4-D sphere, x0 = 1, sigma0 = 2, ftarget 1e-8:
 *      < 1000 evaluations (an ES with step-size adaptation only, CMA off).
 *   P4 notebooks/notebook-usecases-basics.ipynb: 4-D ellipsoid
 *      (condition 1e6), x0 = 2, sigma0 = 1: 1505 and 1464 evaluations to
 *      termination (f < 1e-13); with the bound x_2 >= 1 (optimum on it,
 *      f* = 100) under BoundTransform: 1465 (best at 1428).
 *   P5 logger.py doctest: 7-D ellipsoid, x0 = 0.1, sigma0 = 1: f < 1e-9
 *      in < 4400 evaluations.
 *   P6 evolution_strategy.py doctest: 10-D ellipsoid, bounds [0, inf)
 *      (optimum on them), x0 = 0.2, sigma0 = 0.5, 10% of the candidates
 *      NaN: f < 1e-9 with evals_best < 9000.
 *   P7 evolution_strategy.py doctest, IPOP on the 4-D Rastrigin function
 *      (x0 uniform in [-2, 6]^4, sigma0 = 5, lambda = 10 2^k): "usually
 *      after five restarts the global optimum is located".
 *   P8 c-cmaes doc.txt (Hansen's C code): a single run on a considerably
 *      hard problem takes between 100 n and 300 n^2 evaluations; used as
 *      the ceiling where no closer figure was found (sphere and
 *      Rosenbrock in 2, 5 and 10-D).
 * pycma's default, like ours and the tutorial's, is the active update
 * (negative weights); P1 is purecma without it, and is checked both with
 * active = 0 (the same algorithm) and with the default.  P3 has no
 * covariance adaptation at all, so it bounds the sphere from above. */
#include "testutil.h"
#include "cmaes.h"
#include "rng.h"

typedef double (*objective)(const double *x, int n);

static double sphere(const double *x, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += x[i] * x[i];
  return s;
}

static double rosenbrock(const double *x, int n) {
  double s = 0;
  for (int i = 0; i < n - 1; i++) {
    const double a = x[i] * x[i] - x[i + 1], b = x[i] - 1;
    s += 100 * a * a + b * b;
  }
  return s;
}

/* pycma's cma.ff.elli: condition 1e6, coefficients 1e6^(i/(n-1)). */
static double ellipsoid(const double *x, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += pow(1e6, n > 1 ? (double)i / (n - 1) : 0) * x[i] * x[i];
  return s;
}

static double rastrigin(const double *x, int n) {
  double s = 10.0 * n;
  for (int i = 0; i < n; i++) s += x[i] * x[i] - 10 * cos(2 * M_PI * x[i]);
  return s;
}

/* The optimum (0, ..., 0) of the unit cube's corner. */
static double corner(const double *x, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += (x[i] + 0.5) * (x[i] + 0.5);
  return s - 0.25 * n;
}

typedef struct {
  long evals;      /* evaluations until f <= fstop (or all, if never)  */
  int reached;
  int restarts;
  int stop;
  double best;
} swRun;

/* One optimisation to fstop; `fail` > 0: that fraction of the candidates
 * (drawn from their own stream) fails with +INFINITY. */
static swRun run(swCmaesOptions o, objective f, double fstop, double fail, uint64_t seed) {
  char err[256];
  o.seed = seed;
  o.ftarget = fstop;
  if (o.maxfevals == 0) o.maxfevals = 3000000;
  swCmaes *c = sw_cmaes_new(&o, err, sizeof err);
  if (!c) fprintf(stderr, "# %s\n", err);
  assert_non_null(c);
  const int n = o.n;
  double *X = malloc((size_t)sw_cmaes_lambda_max(c) * n * sizeof *X);
  double *F = malloc((size_t)sw_cmaes_lambda_max(c) * sizeof *F);
  assert_true(X && F);
  swRng frng;
  sw_rng_stream(&frng, seed, 5);
  while (!sw_cmaes_stop(c, NULL, 0)) {
    const int lam = sw_cmaes_lambda(c);
    sw_cmaes_ask(c, X);
    for (int k = 0; k < lam; k++) {
      if (o.lo)
        for (int i = 0; i < n; i++) assert_true(X[k * n + i] >= o.lo[i] && X[k * n + i] <= o.hi[i]);
      F[k] = fail > 0 && sw_rng_uniform(&frng) < fail ? INFINITY : f(X + k * n, n);
    }
    sw_cmaes_tell(c, F);
  }
  swRun r;
  r.best = sw_cmaes_best_loss(c);
  r.reached = r.best <= fstop;
  r.evals = r.reached ? sw_cmaes_best_evaluation(c) : sw_cmaes_evaluations(c);
  r.restarts = sw_cmaes_restarts(c);
  r.stop = sw_cmaes_stop(c, NULL, 0);
  sw_cmaes_free(c);
  free(X);
  free(F);
  return r;
}

static int cmp_long(const void *a, const void *b) {
  const long x = *(const long *)a, y = *(const long *)b;
  return (x > y) - (x < y);
}

/* Runs `seeds` seeds, prints the figures beside the published one and
 * asserts success and median <= published.  x0 == NULL with x0_lo < x0_hi:
 * each seed starts uniformly in [x0_lo, x0_hi]^n.  Returns the median. */
static long validate(const char *what, swCmaesOptions o, objective f, double fstop, double fail,
                     double x0_lo, double x0_hi, long published, const char *source) {
  const int seeds = 11; /* the sanitizer build too: a median of fewer is too noisy to compare */
  long ev[11];
  int rs[11], ok = 0;
  double x0[64];
  for (int s = 0; s < seeds; s++) {
    if (x0_lo < x0_hi) {
      swRng r;
      sw_rng_stream(&r, 1000 + (uint64_t)s, 3);
      for (int i = 0; i < o.n; i++) x0[i] = x0_lo + (x0_hi - x0_lo) * sw_rng_uniform(&r);
      o.x0 = x0;
    }
    const swRun r = run(o, f, fstop, fail, 1 + (uint64_t)s);
    ev[s] = r.evals;
    rs[s] = r.restarts;
    ok += r.reached;
  }
  int rsorted[11];
  memcpy(rsorted, rs, sizeof rs);
  long sorted[11];
  memcpy(sorted, ev, sizeof ev);
  qsort(sorted, (size_t)seeds, sizeof *sorted, cmp_long);
  for (int i = 1; i < seeds; i++) /* insertion sort of the restarts */
    for (int j = i; j > 0 && rsorted[j - 1] > rsorted[j]; j--) {
      const int t = rsorted[j];
      rsorted[j] = rsorted[j - 1];
      rsorted[j - 1] = t;
    }
  const long med = sorted[seeds / 2];
  char lam[32];
  snprintf(lam, sizeof lam, "%d", o.lambda ? o.lambda : 4 + (int)floor(3 * log((double)o.n)));
  fprintf(stderr,
          "# %s: %s n=%d lambda=%s: %d/%d seeds reached f_stop=%g; evaluations median %ld "
          "(min %ld, max %ld), restarts median %d; published %ld (%s)\n",
          __func__, what, o.n, lam, ok, seeds, fstop, med, sorted[0], sorted[seeds - 1],
          rsorted[seeds / 2], published, source);
  assert_int_equal(ok, seeds);
  assert_true(med <= published);
  return med;
}

static swCmaesOptions opts(int n, const double *x0, double sigma0) {
  swCmaesOptions o;
  sw_cmaes_options_init(&o);
  o.n = n;
  o.x0 = x0;
  o.sigma0 = sigma0;
  return o;
}

static const double ONES[10] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
static const double TENTHS[10] = {0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1};
static const double HALVES[10] = {0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
static const double TWOS[10] = {2, 2, 2, 2, 2, 2, 2, 2, 2, 2};

/* ---- the test functions ---- */

static void test_sphere(void **state) {
  (void)state;
  validate("sphere", opts(4, ONES, 2), sphere, 1e-8, 0, 0, 0, 1000, "P3 pycma test.py");
  const int dims[3] = {2, 5, 10};
  for (int d = 0; d < 3; d++) {
    const int n = dims[d];
    validate("sphere", opts(n, ONES, 1), sphere, 1e-10, 0, 0, 0, 300L * n * n, "P8 300 n^2");
  }
}

/* For n >= 4 Rosenbrock has a local minimum (f ~ 3.99 near x_1 = -1) in
 * which some runs end; the runs here may restart (IPOP, two restarts), and
 * the evaluations count every run to the global optimum. */
static swCmaesOptions ros(int n, const double *x0, double sigma0) {
  swCmaesOptions o = opts(n, x0, sigma0);
  o.restarts = 2;
  return o;
}

static void test_rosenbrock(void **state) {
  (void)state;
  swCmaesOptions p1 = ros(4, HALVES, 0.5);
  p1.active = 0; /* purecma's default: positive weights */
  validate("Rosenbrock (positive weights)", p1, rosenbrock, 1e-12, 0, 0, 0, 1712,
           "P1 purecma doctest");
  validate("Rosenbrock", ros(4, HALVES, 0.5), rosenbrock, 1e-12, 0, 0, 0, 1712,
           "P1 purecma doctest (positive weights)");
  validate("Rosenbrock", ros(10, TENTHS, 0.3), rosenbrock, 1e-12, 0, 0, 0, 8000,
           "P2 pycma fmin doctest");
  const int dims[2] = {2, 5};
  for (int d = 0; d < 2; d++) {
    const int n = dims[d];
    validate("Rosenbrock", ros(n, TENTHS, 0.3), rosenbrock, 1e-12, 0, 0, 0, 300L * n * n,
             "P8 300 n^2");
  }
}

static void test_ellipsoid(void **state) {
  (void)state;
  validate("ellipsoid", opts(4, TWOS, 1), ellipsoid, 1e-13, 0, 0, 0, 1505, "P4 pycma notebook");
  validate("ellipsoid", opts(7, TENTHS, 1), ellipsoid, 1e-9, 0, 0, 0, 4400,
           "P5 pycma logger doctest");
}

/* IPOP on Rastrigin, from uniform starts in [-2, 6]^n with sigma0 = 5 as
 * in P7.  The published figure for 4-D is a number of restarts (five), so
 * the evaluations it allows are those of lambda = 10, 20, ..., 320 run to
 * their default maxiter; the other dimensions have no published count
 * that we could read, and check success with a budget of 1e5 n. */
static void test_rastrigin(void **state) {
  (void)state;
  double x0[10] = {0}; /* validate draws each seed's start into it */
  swCmaesOptions o = opts(4, x0, 5);
  o.lambda = 10;
  o.restarts = 9;
  long allowed = 0;
  for (int k = 0; k <= 5; k++) {
    const double lam = 10 << k;
    allowed += (long)lam * (long)(100 + 150 * 49 / sqrt(lam));
  }
  validate("Rastrigin IPOP", o, rastrigin, 1e-8, 0, -2, 6, allowed,
           "P7: lambda 10..320 to their maxiter");
  const int dims[3] = {2, 5, 10};
  for (int d = 0; d < 3; d++) {
    swCmaesOptions p = opts(dims[d], x0, 5);
    p.restarts = 9;
    validate("Rastrigin IPOP", p, rastrigin, 1e-8, 0, -2, 6, 100000L * dims[d],
             "none found; budget 1e5 n");
  }
}

/* ---- bounds ---- */

static void test_box_transformation(void **state) {
  (void)state;
  /* unit interval: al = 0.05, au = 0.1 */
  assert_true(sw_cmaes_box(0.3, 0, 1) == 0.3);
  assert_true(sw_cmaes_box(0.05, 0, 1) == 0.05);
  assert_true(sw_cmaes_box(0.9, 0, 1) == 0.9);
  SW_EXPECT_ABS("box(-0.05) (the lower bound, reached with zero slope)", sw_cmaes_box(-0.05, 0, 1), 0.0, 1e-15);
  SW_EXPECT_ABS("box(1.1) (the upper bound)", sw_cmaes_box(1.1, 0, 1), 1.0, 1e-15);
  /* continuity and slope 1 where the parabola meets the identity */
  const double h = 1e-7;
  SW_EXPECT_ABS("slope at lo + al", (sw_cmaes_box(0.05 + h, 0, 1) - sw_cmaes_box(0.05 - h, 0, 1)) / (2 * h),
                1.0, 1e-6);
  /* periodic with 2 (hi - lo + al + au) = 2.3, mirrored, always in the box */
  for (double x = -20; x <= 20; x += 0.0137) {
    const double y = sw_cmaes_box(x, 0, 1);
    assert_true(y >= 0 && y <= 1);
    assert_true(fabs(y - sw_cmaes_box(x + 2.3, 0, 1)) < 1e-12);
  }
  /* one-sided bounds; both infinite is the identity */
  assert_true(sw_cmaes_box(-3, -INFINITY, INFINITY) == -3);
  assert_true(sw_cmaes_box(-3, 1, INFINITY) >= 1);
  assert_true(sw_cmaes_box(7, -INFINITY, 1) <= 1);
  assert_true(sw_cmaes_box(5, 1, INFINITY) == 5);
}

/* The study's case: the unit cube, the optimum at a corner (on every
 * bound).  Asks stay in the box (checked in run) and the best point
 * converges to the corner. */
static void test_optimum_on_the_bounds(void **state) {
  (void)state;
  const int n = 5;
  double lo[5] = {0, 0, 0, 0, 0}, hi[5] = {1, 1, 1, 1, 1};
  swCmaesOptions o = opts(n, NULL, 0.3); /* x0: the centre */
  o.lo = lo;
  o.hi = hi;
  char err[128];
  swCmaes *c = sw_cmaes_new(&o, err, sizeof err);
  assert_non_null(c);
  double X[5 * 64], F[64];
  while (!sw_cmaes_stop(c, NULL, 0) && sw_cmaes_evaluations(c) < 20000) {
    sw_cmaes_ask(c, X);
    for (int k = 0; k < sw_cmaes_lambda(c); k++) F[k] = corner(X + k * n, n);
    sw_cmaes_tell(c, F);
  }
  double dist = 0;
  for (int i = 0; i < n; i++) dist = fmax(dist, fabs(sw_cmaes_best_x(c)[i]));
  char why[160];
  sw_cmaes_stop(c, why, sizeof why);
  fprintf(stderr, "# %s: unit cube, optimum at the corner: %ld evaluations, stopped by %s\n", __func__,
          sw_cmaes_evaluations(c), why);
  SW_EXPECT_ABS("max |x_best - corner|", dist, 0.0, 1e-6);
  sw_cmaes_free(c);
  /* P4: the 4-D ellipsoid with x_2 >= 1 (f* = 100, on the bound) */
  double blo[4] = {-INFINITY, 1, -INFINITY, -INFINITY};
  double bhi[4] = {INFINITY, INFINITY, INFINITY, INFINITY};
  swCmaesOptions b = opts(4, TWOS, 1);
  b.lo = blo;
  b.hi = bhi;
  validate("ellipsoid, x_2 >= 1", b, ellipsoid, 100 + 1e-11, 0, 0, 0, 1465, "P4 pycma notebook");
}

/* P6: failed candidates (+INFINITY) rank last and the run still converges,
 * here with 10% failures and the optimum on the bounds [0, inf). */
static void test_failures(void **state) {
  (void)state;
  double lo[10], hi[10], x0[10];
  for (int i = 0; i < 10; i++) lo[i] = 0, hi[i] = INFINITY, x0[i] = 0.2;
  swCmaesOptions o = opts(10, x0, 0.5);
  o.lo = lo;
  o.hi = hi;
  validate("ellipsoid on [0, inf)^10, 10% failed", o, ellipsoid, 1e-9, 0.1, 0, 0, 9000,
           "P6 pycma doctest");
  /* every candidate failing: the run ends (stagnation), it does not hang */
  swCmaesOptions a = opts(3, ONES, 1);
  char err[128], why[160];
  swCmaes *c = sw_cmaes_new(&a, err, sizeof err);
  double X[3 * 16], F[16];
  for (int k = 0; k < 16; k++) F[k] = INFINITY;
  while (!sw_cmaes_stop(c, why, sizeof why)) {
    sw_cmaes_ask(c, X);
    sw_cmaes_tell(c, F);
  }
  fprintf(stderr, "# %s: all candidates failed: stopped by %s after %ld generations\n", __func__, why,
          sw_cmaes_generation(c));
  assert_int_equal(sw_cmaes_stop(c, NULL, 0), SW_CMAES_STAGNATION);
  assert_true(isinf(sw_cmaes_best_loss(c)));
  sw_cmaes_free(c);
}

/* ---- determinism ---- */

/* A study resumes by replaying its stored losses: a second instance told
 * the same losses asks bitwise the same candidates, IPOP restarts and
 * failures included; another seed asks others; asking twice before a tell
 * gives the same candidates. */
static void test_replay(void **state) {
  (void)state;
  const int n = 3, G = 400;
  double lo[3] = {-5, -5, -5}, hi[3] = {5, 5, 5};
  swCmaesOptions o = opts(n, NULL, 2);
  o.lo = lo;
  o.hi = hi;
  o.restarts = 3;
  o.seed = 42;
  char err[128];
  swCmaes *a = sw_cmaes_new(&o, err, sizeof err);
  swCmaes *b = sw_cmaes_new(&o, err, sizeof err);
  o.seed = 43;
  swCmaes *c = sw_cmaes_new(&o, err, sizeof err);
  assert_true(a && b && c);
  const int lm = sw_cmaes_lambda_max(a);
  double *XA = malloc((size_t)lm * n * sizeof *XA), *XB = malloc((size_t)lm * n * sizeof *XB);
  double *XC = malloc((size_t)lm * n * sizeof *XC), *F = malloc((size_t)lm * sizeof *F);
  double *L = malloc((size_t)G * lm * sizeof *L); /* the stored losses */
  int gens = 0, differ = 0;
  for (; gens < G && !sw_cmaes_stop(a, NULL, 0); gens++) {
    const int lam = sw_cmaes_lambda(a);
    sw_cmaes_ask(a, XA);
    sw_cmaes_ask(a, XB);
    assert_memory_equal(XA, XB, (size_t)lam * n * sizeof *XA);
    for (int k = 0; k < lam; k++)
      L[(size_t)gens * lm + k] = k % 7 == 3 ? INFINITY : rastrigin(XA + k * n, n);
    sw_cmaes_tell(a, L + (size_t)gens * lm);
  }
  for (int g = 0; g < gens; g++) { /* the replay */
    sw_cmaes_ask(b, XB);
    sw_cmaes_ask(c, XC);
    differ += memcmp(XB, XC, (size_t)sw_cmaes_lambda(c) * n * sizeof *XC) != 0;
    sw_cmaes_tell(b, L + (size_t)g * lm);
    for (int k = 0; k < sw_cmaes_lambda(c); k++) F[k] = rastrigin(XC + k * n, n);
    sw_cmaes_tell(c, F);
  }
  fprintf(stderr, "# %s: %d generations replayed, %d restarts; the other seed differed in %d\n", __func__,
          gens, sw_cmaes_restarts(a), differ);
  assert_true(sw_cmaes_restarts(a) >= 1);
  assert_int_equal(sw_cmaes_generation(a), sw_cmaes_generation(b));
  assert_true(sw_cmaes_best_loss(a) == sw_cmaes_best_loss(b));
  assert_memory_equal(sw_cmaes_best_x(a), sw_cmaes_best_x(b), n * sizeof(double));
  const double sa = sw_cmaes_sigma(a), sb = sw_cmaes_sigma(b);
  assert_memory_equal(&sa, &sb, sizeof sa);
  assert_int_equal(sw_cmaes_stop(a, NULL, 0), sw_cmaes_stop(b, NULL, 0));
  assert_true(differ > 0);
  sw_cmaes_free(a);
  sw_cmaes_free(b);
  sw_cmaes_free(c);
  free(XA);
  free(XB);
  free(XC);
  free(F);
  free(L);
}

/* ---- termination and errors ---- */

static void expect_stop(swCmaesOptions o, objective f, int code, const char *why_start) {
  char err[128], why[160];
  swCmaes *c = sw_cmaes_new(&o, err, sizeof err);
  assert_non_null(c);
  double X[64 * 10], F[64];
  while (!sw_cmaes_stop(c, why, sizeof why)) {
    sw_cmaes_ask(c, X);
    for (int k = 0; k < sw_cmaes_lambda(c); k++) F[k] = f(X + k * o.n, o.n);
    sw_cmaes_tell(c, F);
  }
  fprintf(stderr, "# %s: stopped by %s\n", __func__, why);
  assert_int_equal(sw_cmaes_stop(c, NULL, 0), code);
  assert_string_equal(sw_cmaes_stop_name(code), why_start);
  assert_true(strncmp(why, why_start, strlen(why_start)) == 0);
  sw_cmaes_free(c);
}

static double flat(const double *x, int n) {
  (void)x;
  (void)n;
  return 1.0;
}

static void test_termination(void **state) {
  (void)state;
  swCmaesOptions o = opts(3, ONES, 1);
  expect_stop(o, flat, SW_CMAES_EQUALFUNVALS, "equalfunvals");
  o.maxiter = 5;
  expect_stop(o, sphere, SW_CMAES_MAXITER, "maxiter");
  o.maxiter = 0;
  o.maxfevals = 70;
  expect_stop(o, sphere, SW_CMAES_MAXFEVALS, "maxfevals");
  o.maxfevals = 0;
  o.ftarget = 1e-3;
  expect_stop(o, sphere, SW_CMAES_FTARGET, "ftarget");
  o.ftarget = -INFINITY;
  expect_stop(o, sphere, SW_CMAES_TOLFUN, "tolfun"); /* the sphere runs to its precision */
  o.tolfun = 0;
  o.tolx = 1e-6;
  expect_stop(o, sphere, SW_CMAES_TOLX, "tolx");
}

static void expect_error(const swCmaesOptions *o, const char *msg) {
  char err[256];
  swCmaes *c = sw_cmaes_new(o, err, sizeof err);
  assert_null(c);
  fprintf(stderr, "# %s: %s\n", __func__, err);
  assert_string_equal(err, msg);
}

static void test_bad_options(void **state) {
  (void)state;
  double lo[2] = {0, 0}, hi[2] = {1, 0}, x0[2] = {0.5, 2};
  swCmaesOptions o = opts(2, ONES, 1);
  o.n = 0;
  expect_error(&o, "cmaes: n must be 1 to 10000, is 0");
  o = opts(2, ONES, 0);
  expect_error(&o, "cmaes: sigma0 must be > 0 and finite, is 0");
  o = opts(2, ONES, 1);
  o.lambda = 1;
  expect_error(&o, "cmaes: lambda must be >= 2 (or 0 for the default), is 1");
  o = opts(2, NULL, 1);
  expect_error(&o, "cmaes: no x0 and no bounds: nowhere to start");
  o = opts(2, x0, 1);
  o.lo = lo;
  expect_error(&o, "cmaes: lo and hi go together (one is NULL)");
  o.hi = hi;
  expect_error(&o, "cmaes: coordinate 1: bounds [0, 0] need lo < hi");
  hi[1] = 1;
  expect_error(&o, "cmaes: x0[1] = 2 is outside its bounds [0, 1]");
  o = opts(2, ONES, 1);
  o.restarts = 31;
  expect_error(&o, "cmaes: restarts must be 0 to 30, is 31");
  o.restarts = 30;
  expect_error(&o, "cmaes: 30 restarts would reach lambda = 6442450944 in 2 dimensions: too large");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_sphere),
      cmocka_unit_test(test_rosenbrock),
      cmocka_unit_test(test_ellipsoid),
      cmocka_unit_test(test_rastrigin),
      cmocka_unit_test(test_box_transformation),
      cmocka_unit_test(test_optimum_on_the_bounds),
      cmocka_unit_test(test_failures),
      cmocka_unit_test(test_replay),
      cmocka_unit_test(test_termination),
      cmocka_unit_test(test_bad_options),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
