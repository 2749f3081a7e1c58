/* test_study_recheck.c — the recheck of a study's best designs at dt/2
 * (study_recheck.c), on a function of the design and of the step, without
 * a simulation and without MPI:
 *   - a grid sweep rechecks its 3 best designs, best first, each at half the
 *     step of its evaluation, and /recheck holds the objective at dt and at
 *     dt/2, their difference relative to max(|objective|, floor) (the floor
 *     a tenth of the median |objective|) and the verdict: a design the step
 *     moves by 7.5% is sensitive, one that does not move insensitive, and
 *     one near zero that the step moves by 75% of itself but by 0.0075% of
 *     the floor insensitive;
 *   - a design that fails at dt/2 is sensitive;
 *   - the best designs are taken by score, the lower index first on a tie
 *     (a CMA-ES run that converges on a corner of the box, where many
 *     designs tie); a design offered twice is one design, its lower index;
 *   - a resumed study takes the rechecks its file holds and evaluates only
 *     the best designs it lacks (a study run on to a larger budget gives the
 *     /recheck of one run with that budget); no_recheck evaluates none;
 *   - a recheck interrupted leaves the study complete, the rechecks that
 *     arrived in /recheck, and --resume does the rest. */
#include <hdf5.h>
#include <unistd.h>

#include "testutil.h"
#include "h5read.h"
#include "study.h"
#include "study_file.h"
#include "study_recheck.h"

static char dir[] = "/tmp/sinew-recheck-XXXXXX";

static void path_of(char *buf, size_t len, const char *name) {
  snprintf(buf, len, "%s/%s", dir, name);
}

static const char *const names[] = {"x", "y", "fixed"};
static const char *const units[] = {"cm", "", "s"};
static const double scales[] = {0.01, 1, 1};
static const char *const si_units[] = {"m", "", "s"};
static const double lo[] = {0, -1, 0}, hi[] = {0.04, 1, 0};
static const double start[] = {0.01, 0.2, 0.5};
static const int vary2[] = {1, 1, 0};

typedef struct {
  int calls, rechecks;     /* evaluations at dt, at dt/2                     */
  double cx, cy;           /* the optimum                                    */
  int interrupt_recheck;   /* > 0: the recheck after this many is "Ctrl-C"   */
  int fail_half_at_x4;     /* the designs at x = 4 cm are unstable at dt/2   */
  int plain;               /* no error of the step (A = 0)                   */
} swProblem;

/* objective = -((x - cx)^2 + 10 (y - cy)^2) + A (dt/dt0)^2, a second-order
 * error of the step: A = 1e-4 at x = 2 cm, y = 0 (the best on the grid,
 * near zero), -0.1 at x = 4 cm, else 0; the step 1 ms times dt_scale */
static void stepped(void *ctx, const double *P, double dt_scale, swStudyEval *r) {
  swProblem *p = ctx;
  if (dt_scale == 1) p->calls++;
  else p->rechecks++;
  if (dt_scale != 1 && p->interrupt_recheck > 0 && p->rechecks > p->interrupt_recheck) {
    r->interrupted = 1;
    return;
  }
  r->dt = 1e-3 * dt_scale;
  if (dt_scale != 1 && p->fail_half_at_x4 && P[0] == 0.04) {
    r->status = SW_EVAL_UNSTABLE;
    r->objective = NAN;
    r->score = -INFINITY;
    snprintf(r->message, sizeof r->message, "unstable at dt/2");
    return;
  }
  double dx = P[0] - p->cx, dy = P[1] - p->cy;
  double A = p->plain ? 0 : P[0] == 0.02 && P[1] == 0 ? 1e-4 : P[0] == 0.04 ? -0.1 : 0;
  r->status = SW_EVAL_OK;
  r->objective = -(dx * dx + 10 * dy * dy) + A * dt_scale * dt_scale;
  r->penalty = 0;
  r->score = r->objective;
  r->sim_time = P[2];
}

static swStudyOptions options(const char *file, swStudyKind kind, swProblem *p) {
  swStudyOptions o;
  memset(&o, 0, sizeof o);
  o.prog = "test_study_recheck";
  o.path = file;
  o.quiet = 1;
  o.kind = kind;
  o.levels = 3;
  o.samples = 10;
  o.sigma = 0.3;
  o.seed = 12345;
  o.nparam = 3;
  o.name = names;
  o.unit = units;
  o.scale = scales;
  o.si_unit = si_units;
  o.value = start;
  o.vary = vary2;
  o.lo = lo;
  o.hi = hi;
  o.sense = 1;
  o.objective_text = "-(x^2 + 10 y^2)";
  o.objective_unit = "";
  o.objective_scale = 1;
  o.model_name = "test";
  o.model_sha256 = "0123";
  o.run_settings = "duration=1";
  o.recheck = 3;
  o.eval = stepped;
  o.ctx = p;
  return o;
}

/* /recheck of a file: its rows (at most 8) and its floor. */
typedef struct {
  long n;
  long index[8];
  double dt[8], objective[8], objective_half[8], score_half[8], difference[8];
  int status_half[8], sensitive[8];
  double floor, tolerance;
} swRecheckRead;

static void read_column(hid_t f, const char *name, hid_t type, void *buf, long *n) {
  hid_t ds = H5Dopen2(f, name, H5P_DEFAULT);
  assert_true(ds >= 0);
  hid_t sp = H5Dget_space(ds);
  hsize_t len = 0;
  H5Sget_simple_extent_dims(sp, &len, NULL);
  assert_true(len <= 8);
  *n = (long)len;
  assert_true(len == 0 || H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
  H5Sclose(sp);
  H5Dclose(ds);
}

static int read_recheck(const char *file, swRecheckRead *r) {
  memset(r, 0, sizeof *r);
  hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(f >= 0);
  if (H5Lexists(f, "/recheck", H5P_DEFAULT) <= 0) {
    H5Fclose(f);
    return 0;
  }
  long n;
  read_column(f, "/recheck/index", H5T_NATIVE_LONG, r->index, &r->n);
  read_column(f, "/recheck/dt", H5T_NATIVE_DOUBLE, r->dt, &n);
  read_column(f, "/recheck/objective", H5T_NATIVE_DOUBLE, r->objective, &n);
  read_column(f, "/recheck/objective_half", H5T_NATIVE_DOUBLE, r->objective_half, &n);
  read_column(f, "/recheck/score_half", H5T_NATIVE_DOUBLE, r->score_half, &n);
  read_column(f, "/recheck/difference", H5T_NATIVE_DOUBLE, r->difference, &n);
  read_column(f, "/recheck/sensitive", H5T_NATIVE_INT, r->sensitive, &n);
  hid_t ds = H5Dopen2(f, "/recheck/status_half", H5P_DEFAULT);
  hid_t t = H5Dget_type(ds);
  assert_true(H5Dread(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, r->status_half) >= 0);
  H5Tclose(t);
  H5Dclose(ds);
  r->floor = read_double_attr_of(f, "/recheck", "floor");
  r->tolerance = read_double_attr_of(f, "/recheck", "tolerance");
  H5Fclose(f);
  return 1;
}

static void assert_same_recheck(const swRecheckRead *a, const swRecheckRead *b) {
  assert_int_equal(a->n, b->n);
  size_t n = (size_t)a->n;
  assert_memory_equal(a->index, b->index, n * sizeof *a->index);
  assert_memory_equal(a->dt, b->dt, n * sizeof *a->dt);
  assert_memory_equal(a->objective_half, b->objective_half, n * sizeof(double));
  assert_memory_equal(a->difference, b->difference, n * sizeof(double));
  assert_memory_equal(a->sensitive, b->sensitive, n * sizeof(int));
  assert_memory_equal(&a->floor, &b->floor, sizeof(double));
}

/* ---- the tests ---- */

static void test_grid_verdicts(void **state) {
  (void)state;
  char file[256];
  path_of(file, sizeof file, "grid.h5");
  swProblem p = {.cx = 0.02, .cy = 0};
  swStudyOptions o = options(file, SW_STUDY_GRID, &p);
  assert_int_equal(sw_study_run(&o), SW_OK);
  assert_int_equal(p.calls, 9);
  assert_int_equal(p.rechecks, 3);
  swRecheckRead r;
  assert_true(read_recheck(file, &r));
  /* design i: x level i / 3, y level i % 3; the best: (2 cm, 0) = 4, then
   * (0, 0) = 1 at -4e-4, then (4 cm, 0) = 7 at -0.1004; the median |objective|
   * of the nine is 10 (at (2 cm, +-1)), so the floor is 1 */
  for (long i = 0; i < r.n; i++)
    fprintf(stderr, "# test_grid_verdicts: design %ld: %.6g at dt = %g s, %.6g at dt/2: "
            "difference %.3g of max(|objective|, floor %g): %s\n", r.index[i], r.objective[i],
            r.dt[i], r.objective_half[i], r.difference[i], r.floor,
            r.sensitive[i] ? "sensitive" : "insensitive");
  assert_int_equal(r.n, 3);
  assert_true(r.index[0] == 4 && r.index[1] == 1 && r.index[2] == 7);
  assert_true(r.dt[0] == 1e-3 && r.dt[1] == 1e-3 && r.dt[2] == 1e-3);
  assert_true(fabs(r.floor - 1) < 1e-12 && r.tolerance == 0.01);
  for (int i = 0; i < 3; i++) assert_int_equal(r.status_half[i], SW_EVAL_OK);
  assert_true(r.objective[0] == 1e-4 && r.objective_half[0] == 0.25e-4);
  assert_true(fabs(r.difference[0] - 0.75e-4) < 1e-15);   /* 75% of itself */
  assert_int_equal(r.sensitive[0], 0);
  assert_true(r.objective_half[1] == r.objective[1] && r.difference[1] == 0);
  assert_int_equal(r.sensitive[1], 0);
  assert_true(fabs(r.difference[2] - 0.075) < 1e-12);
  assert_int_equal(r.sensitive[2], 1);
  assert_true(r.score_half[2] == r.objective_half[2]);
}

static void test_failure_at_half(void **state) {
  (void)state;
  char file[256];
  path_of(file, sizeof file, "fail_half.h5");
  swProblem p = {.cx = 0.02, .cy = 0, .fail_half_at_x4 = 1};
  swStudyOptions o = options(file, SW_STUDY_GRID, &p);
  assert_int_equal(sw_study_run(&o), SW_OK);
  swRecheckRead r;
  assert_true(read_recheck(file, &r));
  fprintf(stderr, "# test_failure_at_half: design %ld: status %d at dt/2, objective %g, score "
          "%g, sensitive %d\n", r.index[2], r.status_half[2], r.objective_half[2],
          r.score_half[2], r.sensitive[2]);
  assert_int_equal(r.index[2], 7);
  assert_int_equal(r.status_half[2], SW_EVAL_UNSTABLE);
  assert_true(isnan(r.objective_half[2]) && isinf(r.score_half[2]) && r.score_half[2] < 0);
  assert_int_equal(r.sensitive[2], 1);
  assert_int_equal(r.sensitive[0] + r.sensitive[1], 0);
}

/* The rechecked designs of a CMA-ES run that converges on a corner of the
 * box, where many designs tie on the score stored: the best three by score,
 * the lower index first on a tie. */
static void test_ties(void **state) {
  (void)state;
  char file[256];
  path_of(file, sizeof file, "corner.h5");
  swProblem p = {.cx = 0.06, .cy = 1.5, .plain = 1};
  swStudyOptions o = options(file, SW_STUDY_CMAES, &p);
  o.samples = 600;
  assert_int_equal(sw_study_run(&o), SW_OK);
  swRecheckRead r;
  assert_true(read_recheck(file, &r));
  assert_int_equal(r.n, 3);
  hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t ds = H5Dopen2(f, "/evaluations/score", H5P_DEFAULT);
  double score[600];
  assert_true(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, score) >= 0);
  H5Dclose(ds);
  H5Fclose(f);
  long want[3] = {-1, -1, -1};
  int tied = 0;
  for (int k = 0; k < 3; k++)
    for (long i = 0; i < 600; i++) {
      if ((k > 0 && (i == want[0] || i == want[1])) || !isfinite(score[i])) continue;
      if (want[k] < 0 || score[i] > score[want[k]]) want[k] = i;
    }
  for (long i = 0; i < 600; i++) tied += score[i] == score[want[0]];
  fprintf(stderr, "# test_ties: %d designs tie on the best score %.17g; rechecked: designs %ld, "
          "%ld, %ld (expected %ld, %ld, %ld)\n", tied, score[want[0]], r.index[0], r.index[1],
          r.index[2], want[0], want[1], want[2]);
  assert_true(tied >= 3);
  for (int k = 0; k < 3; k++) assert_int_equal(r.index[k], want[k]);
}

/* The same design offered again is one design (the lowest index kept);
 * with no_recheck, only the rechecks the file holds are reported. */
static void test_distinct(void **state) {
  (void)state;
  char file[256], err[256];
  path_of(file, sizeof file, "distinct.h5");
  swProblem p = {.plain = 1};
  swStudyOptions o = options(file, SW_STUDY_GRID, &p);
  o.no_recheck = 1;
  static const char *const dname[] = {"x", "y"}, *const dunit[] = {"cm", ""};
  static const double dlo[] = {0, -1}, dhi[] = {4, 1};
  swStudyFileInfo in = {&o, "12345", "x=0.01;y=0.2;fixed=0.5", "x;y", 2, dname, dunit, dlo, dhi};
  swStudyFile *f = sw_study_file_create(&in, err, sizeof err);
  assert_non_null(f);
  swRecheck *k = sw_recheck_new(&o);
  assert_non_null(k);
  const double A[3] = {0.01, 0.5, 0.5}, B[3] = {0.02, 0.5, 0.5}, C[3] = {0.03, 0.5, 0.5},
               D[3] = {0.04, 0.5, 0.5};
  sw_recheck_offer(k, 5, A, -1, -1);
  sw_recheck_offer(k, 2, A, -1, -1);      /* A again, earlier: it is design 2 */
  sw_recheck_offer(k, 9, A, -1, -1);      /* and again, later: still design 2 */
  sw_recheck_offer(k, 3, B, -1, -1);      /* a tie with A, after it          */
  sw_recheck_offer(k, 7, C, -0.5, -0.5);  /* the best                        */
  sw_recheck_offer(k, 8, D, -2, -2);      /* fourth: not rechecked           */
  swStudyRecheck held[5];
  const long index[5] = {8, 5, 3, 2, 7};
  for (int i = 0; i < 5; i++)
    held[i] = (swStudyRecheck){.index = index[i], .dt = 1e-3, .status_half = SW_EVAL_OK,
                               .objective_half = -1, .score_half = -1};
  held[0].status_half = SW_EVAL_PENDING;
  sw_recheck_stored(k, held, 5);
  assert_int_equal(sw_recheck_run(k, NULL, f), SW_OK);
  sw_recheck_free(k);
  assert_int_equal(sw_study_file_close(f, "complete"), SW_OK);
  swRecheckRead r;
  assert_true(read_recheck(file, &r));
  fprintf(stderr, "# test_distinct: A offered as designs 5, 2, 9; rechecked: %ld, %ld, %ld\n",
          r.index[0], r.index[1], r.index[2]);
  assert_int_equal(r.n, 3);
  assert_true(r.index[0] == 7 && r.index[1] == 2 && r.index[2] == 3);
  assert_true(r.objective_half[0] == -1 && r.difference[0] == 1);   /* 0.5 of 0.5 */
  assert_int_equal(p.calls + p.rechecks, 0);
}

static void test_resume(void **state) {
  (void)state;
  char whole[256], grown[256];
  path_of(whole, sizeof whole, "whole.h5");
  path_of(grown, sizeof grown, "grown.h5");
  swProblem p = {.cx = 0.03, .cy = 0.25};
  swStudyOptions o = options(whole, SW_STUDY_CMAES, &p);
  o.samples = 120;
  assert_int_equal(sw_study_run(&o), SW_OK);
  swRecheckRead a, b;
  assert_true(read_recheck(whole, &a));
  /* a complete study resumed: nothing evaluated, /recheck the same */
  swProblem q = {.cx = 0.03, .cy = 0.25};
  o = options(whole, SW_STUDY_CMAES, &q);
  o.samples = 120;
  o.resume = 1;
  assert_int_equal(sw_study_run(&o), SW_OK);
  assert_int_equal(q.calls + q.rechecks, 0);
  assert_true(read_recheck(whole, &b));
  assert_same_recheck(&a, &b);
  /* run on to a larger budget: the rechecks of designs still among the
   * best are taken from the file; /recheck is that of a study of 240 */
  path_of(whole, sizeof whole, "whole240.h5");
  swProblem s = {.cx = 0.03, .cy = 0.25};
  o = options(whole, SW_STUDY_CMAES, &s);
  o.samples = 240;
  assert_int_equal(sw_study_run(&o), SW_OK);
  swProblem t = {.cx = 0.03, .cy = 0.25};
  o = options(grown, SW_STUDY_CMAES, &t);
  o.samples = 120;
  assert_int_equal(sw_study_run(&o), SW_OK);
  swRecheckRead before;
  assert_true(read_recheck(grown, &before));
  swProblem u = {.cx = 0.03, .cy = 0.25};
  o = options(grown, SW_STUDY_CMAES, &u);
  o.samples = 240;
  o.resume = 1;
  assert_int_equal(sw_study_run(&o), SW_OK);
  assert_true(read_recheck(whole, &a));
  assert_true(read_recheck(grown, &b));
  int kept = 0;
  for (long i = 0; i < b.n; i++)
    for (long j = 0; j < before.n; j++) kept += b.index[i] == before.index[j];
  fprintf(stderr, "# test_resume: run on from 120 to 240 evaluations: %d rechecked now, %d "
          "taken from the file; /recheck equals that of a study of 240\n", u.rechecks, kept);
  assert_int_equal(u.rechecks + kept, 3);
  assert_same_recheck(&a, &b);
  /* no_recheck: nothing evaluated; a file without /recheck gets none */
  path_of(whole, sizeof whole, "none.h5");
  swProblem v = {.cx = 0.03, .cy = 0.25};
  o = options(whole, SW_STUDY_GRID, &v);
  o.no_recheck = 1;
  assert_int_equal(sw_study_run(&o), SW_OK);
  assert_int_equal(v.rechecks, 0);
  assert_false(read_recheck(whole, &a));
}

static void test_interrupted(void **state) {
  (void)state;
  char cut[256], whole[256];
  path_of(cut, sizeof cut, "cut.h5");
  path_of(whole, sizeof whole, "grid2.h5");
  swProblem p = {.cx = 0.02, .cy = 0, .interrupt_recheck = 1};
  swStudyOptions o = options(cut, SW_STUDY_GRID, &p);
  assert_int_equal(sw_study_run(&o), SW_EINTERRUPT);
  hid_t f = H5Fopen(cut, H5F_ACC_RDONLY, H5P_DEFAULT);
  char *st = read_string_attr(f, "/", "status");
  assert_string_equal(st, "complete");
  free(st);
  H5Fclose(f);
  swRecheckRead a, b;
  assert_true(read_recheck(cut, &a));
  assert_int_equal(a.n, 1);
  swProblem q = {.cx = 0.02, .cy = 0};
  o = options(cut, SW_STUDY_GRID, &q);
  o.resume = 1;
  assert_int_equal(sw_study_run(&o), SW_OK);
  fprintf(stderr, "# test_interrupted: the recheck stopped after 1 of 3 designs; --resume "
          "evaluated %d designs and %d rechecks\n", q.calls, q.rechecks);
  assert_int_equal(q.calls, 0);
  assert_int_equal(q.rechecks, 2);
  swProblem r = {.cx = 0.02, .cy = 0};
  o = options(whole, SW_STUDY_GRID, &r);
  assert_int_equal(sw_study_run(&o), SW_OK);
  assert_true(read_recheck(cut, &a));
  assert_true(read_recheck(whole, &b));
  assert_same_recheck(&a, &b);
}

static int setup(void **state) {
  (void)state;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  return system(cmd) == 0 ? 0 : -1;
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_grid_verdicts),
    cmocka_unit_test(test_failure_at_half),
    cmocka_unit_test(test_ties),
    cmocka_unit_test(test_distinct),
    cmocka_unit_test(test_resume),
    cmocka_unit_test(test_interrupted),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
