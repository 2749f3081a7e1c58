/* test_study.c — the study driver (study.c, study_file.c, study_pool.c) on
 * functions with known optima, without a simulation and without MPI:
 *   - a grid sweep evaluates every combination of the levels, stores each
 *     design and score at its index and the best at /best;
 *   - a Latin hypercube uses each stratum of each param exactly once;
 *   - CMA-ES in the ranges' unit cube finds the maximum of a shifted,
 *     scaled sphere, and of one whose optimum lies on a bound;
 *   - designs whose evaluation fails rank last and the study goes on;
 *   - a study interrupted after some evaluations and resumed gives the
 *     datasets of one that never stopped, bit for bit; a resume against a
 *     changed study is refused;
 *   - every design is stored in SI too (/evaluations/params_si), the values
 *     the evaluation was handed, bit for bit; sw_study_file_design reads a
 *     row or the best from it, and from a file without it (written before
 *     it) the values shown, converted; --resume of such a file gives it
 *     params_si, equal to that of a study that had it all along;
 *   - bad settings are refused with a message, before anything runs. */
#include <hdf5.h>
#include <unistd.h>

#include "testutil.h"
#include "h5read.h"
#include "study.h"

static char dir[] = "/tmp/sinew-study-XXXXXX";

static void path_of(char *buf, size_t len, const char *name) {
  snprintf(buf, len, "%s/%s", dir, name);
}

/* ---- the problems ---- */

/* Two params, x in (0, 4) cm and y in (-1, 1) (plain), a third fixed. */
static const char *const names[] = {"x", "y", "fixed"};
static const char *const units[] = {"cm", "", "s"};
static const double scales[] = {0.01, 1, 1};
static const char *const si_units[] = {"m", "", "s"};
static const double lo[] = {0, -1, 0}, hi[] = {0.04, 1, 0};

typedef struct {
  int calls;
  int interrupt_after;     /* > 0: the call after this many is "Ctrl-C"      */
  int fail_left;           /* designs with y < -0.5 are unstable             */
  double cx, cy;           /* the optimum                                    */
  double (*seen)[3];       /* when set: every design handed to sphere()      */
  int nseen;
} swProblem;

/* score = -((x - cx)^2 + 10 (y - cy)^2), in m/s as the model would say */
static void sphere(void *ctx, const double *P, double dt_scale, swStudyEval *r) {
  (void)dt_scale;
  swProblem *p = ctx;
  p->calls++;
  if (p->seen) memcpy(p->seen[p->nseen++], P, sizeof p->seen[0]);
  if (p->interrupt_after > 0 && p->calls > p->interrupt_after) {
    r->interrupted = 1;
    return;
  }
  if (p->fail_left && P[1] < -0.5) {
    r->status = SW_EVAL_UNSTABLE;
    r->score = -INFINITY;
    r->objective = NAN;
    snprintf(r->message, sizeof r->message, "unstable at y = %g", P[1]);
    return;
  }
  double dx = P[0] - p->cx, dy = P[1] - p->cy;
  r->status = SW_EVAL_OK;
  r->objective = -(dx * dx + 10 * dy * dy);
  r->penalty = 0;
  r->score = r->objective;
  r->sim_time = P[2];
}

static swStudyOptions options(const char *file, swStudyKind kind, swProblem *p,
                              const double *value, const int *vary) {
  swStudyOptions o;
  memset(&o, 0, sizeof o);
  o.prog = "test_study";
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
  o.value = value;
  o.vary = vary;
  o.lo = lo;
  o.hi = hi;
  o.sense = 1;
  o.objective_text = "-(x^2 + 10 y^2)";
  o.objective_unit = "";
  o.objective_scale = 1;
  o.model_name = "test";
  o.model_sha256 = "0123";
  o.run_settings = "duration=1";
  o.eval = sphere;
  o.ctx = p;
  return o;
}

static const double start[] = {0.01, 0.2, 0.5};
static const int vary2[] = {1, 1, 0};

/* Reads a whole 1-D or 2-D double (or int) dataset; caller frees. */
static void *read_all(const char *file, const char *ds_path, hid_t type, size_t size, long *n) {
  hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(f >= 0);
  hid_t ds = H5Dopen2(f, ds_path, H5P_DEFAULT);
  assert_true(ds >= 0);
  hid_t sp = H5Dget_space(ds);
  hsize_t dims[2] = {0, 1};
  int rank = H5Sget_simple_extent_dims(sp, dims, NULL);
  size_t count = (size_t)dims[0] * (rank == 2 ? (size_t)dims[1] : 1);
  void *buf = malloc(count * size + size);
  assert_true(H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
  H5Sclose(sp);
  H5Dclose(ds);
  H5Fclose(f);
  *n = (long)dims[0];
  return buf;
}

/* ---- the tests ---- */

static void test_grid(void **state) {
  (void)state;
  char file[256];
  path_of(file, sizeof file, "grid.h5");
  swProblem p = {.cx = 0.02, .cy = 0.0};
  swStudyOptions o = options(file, SW_STUDY_GRID, &p, start, vary2);
  assert_int_equal(sw_study_run(&o), SW_OK);
  assert_int_equal(p.calls, 9);
  long n;
  double *P = read_all(file, "/evaluations/params", H5T_NATIVE_DOUBLE, 3 * sizeof(double), &n);
  double *score = read_all(file, "/evaluations/score", H5T_NATIVE_DOUBLE, sizeof(double), &n);
  assert_int_equal(n, 9);
  /* design i: x level i / 3, y level i % 3 (the last param fastest), in cm */
  double worst = 0;
  for (long i = 0; i < 9; i++) {
    double x = 0.02 * (double)(i / 3), y = -1 + (double)(i % 3);
    worst = fmax(worst, fabs(P[3 * i] - x / 0.01) + fabs(P[3 * i + 1] - y));
    assert_true(P[3 * i + 2] == 0.5);
    double want = -((x - 0.02) * (x - 0.02) + 10 * y * y);
    worst = fmax(worst, fabs(score[i] - want));
  }
  fprintf(stderr, "# test_grid: largest difference of a stored design or score from the grid's: "
          "%.3g\n", worst);
  assert_true(worst < 1e-12);
  hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  double best = read_double_attr_of(f, "/best", "score");
  char *status = read_string_attr(f, "/", "status");
  assert_string_equal(status, "complete");
  free(status);
  H5Fclose(f);
  assert_true(best == 0.0);   /* design 4: x = 2 cm, y = 0 */
  free(P);
  free(score);
}

static void test_lhs(void **state) {
  (void)state;
  char file[256];
  path_of(file, sizeof file, "lhs.h5");
  swProblem p = {.cx = 0.02};
  swStudyOptions o = options(file, SW_STUDY_LHS, &p, start, vary2);
  o.samples = 50;
  assert_int_equal(sw_study_run(&o), SW_OK);
  long n;
  double *P = read_all(file, "/evaluations/params", H5T_NATIVE_DOUBLE, 3 * sizeof(double), &n);
  assert_int_equal(n, 50);
  for (int v = 0; v < 2; v++) {
    int used[50] = {0};
    double a = v == 0 ? 0 : -1, b = v == 0 ? 4 : 1;
    for (long i = 0; i < n; i++) {
      double u = (P[3 * i + v] - a) / (b - a);
      int k = (int)floor(u * 50);
      assert_true(k >= 0 && k < 50);
      used[k]++;
    }
    for (int k = 0; k < 50; k++) assert_int_equal(used[k], 1);
  }
  fprintf(stderr, "# test_lhs: 50 designs, each of the 50 strata of both params used once\n");
  free(P);
}

static double best_of(const char *file, double *x, double *y) {
  hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  double best = read_double_attr_of(f, "/best", "score");
  H5Fclose(f);
  long n;
  double *P = read_all(file, "/best/params", H5T_NATIVE_DOUBLE, sizeof(double), &n);
  *x = P[0];
  *y = P[1];
  free(P);
  return best;
}

static void test_cmaes(void **state) {
  (void)state;
  char file[256];
  path_of(file, sizeof file, "cmaes.h5");
  /* optimum inside: x = 3 cm, y = 0.25 */
  swProblem p = {.cx = 0.03, .cy = 0.25};
  swStudyOptions o = options(file, SW_STUDY_CMAES, &p, start, vary2);
  o.samples = 600;
  assert_int_equal(sw_study_run(&o), SW_OK);
  double x, y, best = best_of(file, &x, &y);
  fprintf(stderr, "# test_cmaes: best score %.3e at x = %.9f cm, y = %.9f (optimum 0 at 3 cm, "
          "0.25) after %d evaluations\n", best, x, y, p.calls);
  assert_true(best > -1e-12);
  assert_true(fabs(x - 3) < 1e-4 && fabs(y - 0.25) < 1e-5);
  /* optimum beyond the upper bound of x: the best design sits on it */
  path_of(file, sizeof file, "cmaes_bound.h5");
  swProblem q = {.cx = 0.05, .cy = -0.1};
  o = options(file, SW_STUDY_CMAES, &q, start, vary2);
  o.samples = 600;
  assert_int_equal(sw_study_run(&o), SW_OK);
  best = best_of(file, &x, &y);
  fprintf(stderr, "# test_cmaes: optimum beyond x = 4 cm: best at x = %.9f cm, y = %.9f "
          "(bound 4 cm, -0.1), score %.6g (reference -1e-4)\n", x, y, best);
  assert_true(fabs(x - 4) < 1e-4 && fabs(y + 0.1) < 1e-4);
}

static void test_failures_rank_last(void **state) {
  (void)state;
  char file[256];
  path_of(file, sizeof file, "fail.h5");
  /* a quarter of the box is unstable; the optimum is beside it */
  swProblem p = {.cx = 0.01, .cy = -0.4, .fail_left = 1};
  swStudyOptions o = options(file, SW_STUDY_CMAES, &p, start, vary2);
  o.samples = 600;
  assert_int_equal(sw_study_run(&o), SW_OK);
  long n;
  int *status = read_all(file, "/evaluations/status", H5T_NATIVE_INT, sizeof(int), &n);
  int failed = 0;
  for (long i = 0; i < n; i++) failed += status[i] == SW_EVAL_UNSTABLE;
  double x, y, best = best_of(file, &x, &y);
  fprintf(stderr, "# test_failures_rank_last: %d of %ld designs unstable; best %.3e at "
          "x = %.6f cm, y = %.6f (optimum 1 cm, -0.4)\n", failed, n, best, x, y);
  assert_true(failed > 0);
  assert_true(fabs(x - 1) < 1e-3 && fabs(y + 0.4) < 1e-4);
  free(status);
}

/* Every dataset that says what was found (not wall_time and rank, which
 * say how) of two files, bit for bit. */
static void assert_same_results(const char *a, const char *b) {
  static const char *const ds[] = {"/evaluations/params", "/evaluations/params_si",
                                   "/evaluations/objective",
                                   "/evaluations/penalty", "/evaluations/score",
                                   "/evaluations/sim_time", "/cmaes/sigma", "/cmaes/mean",
                                   "/cmaes/best_score", "/best/params"};
  for (size_t k = 0; k < sizeof ds / sizeof *ds; k++) {
    long na, nb;
    double *x = read_all(a, ds[k], H5T_NATIVE_DOUBLE, 3 * sizeof(double), &na);
    double *y = read_all(b, ds[k], H5T_NATIVE_DOUBLE, 3 * sizeof(double), &nb);
    assert_int_equal(na, nb);
    /* widths: params and mean hold 3 and 2 columns, the rest 1 */
    size_t width = strstr(ds[k], "params") && strncmp(ds[k], "/best", 5) ? 3
                   : strstr(ds[k], "mean") ? 2 : 1;
    if (!strncmp(ds[k], "/best", 5)) width = (size_t)na, na = 1;
    assert_memory_equal(x, y, (size_t)na * width * sizeof(double));
    free(x);
    free(y);
  }
  long na, nb;
  int *sa = read_all(a, "/evaluations/status", H5T_NATIVE_INT, sizeof(int), &na);
  int *sb = read_all(b, "/evaluations/status", H5T_NATIVE_INT, sizeof(int), &nb);
  assert_int_equal(na, nb);
  assert_memory_equal(sa, sb, (size_t)na * sizeof(int));
  free(sa);
  free(sb);
}

static void test_resume(void **state) {
  (void)state;
  char whole[256], cut[256];
  path_of(whole, sizeof whole, "whole.h5");
  path_of(cut, sizeof cut, "cut.h5");
  swProblem p = {.cx = 0.03, .cy = 0.25, .fail_left = 1};
  swStudyOptions o = options(whole, SW_STUDY_CMAES, &p, start, vary2);
  o.samples = 120;
  assert_int_equal(sw_study_run(&o), SW_OK);
  int calls = p.calls;
  /* the same study, stopped in its fourth generation (6 a generation) */
  swProblem q = {.cx = 0.03, .cy = 0.25, .fail_left = 1, .interrupt_after = 21};
  o = options(cut, SW_STUDY_CMAES, &q, start, vary2);
  o.samples = 120;
  assert_int_equal(sw_study_run(&o), SW_EINTERRUPT);
  long n;
  int *status = read_all(cut, "/evaluations/status", H5T_NATIVE_INT, sizeof(int), &n);
  long done = 0;
  for (long i = 0; i < n; i++) done += status[i] != SW_EVAL_PENDING;
  free(status);
  hid_t f = H5Fopen(cut, H5F_ACC_RDONLY, H5P_DEFAULT);
  char *st = read_string_attr(f, "/", "status");
  assert_string_equal(st, "interrupted");
  free(st);
  H5Fclose(f);
  assert_int_equal(done, 21);
  /* resumed: only the designs the file lacks are evaluated */
  swProblem r = {.cx = 0.03, .cy = 0.25, .fail_left = 1};
  o = options(cut, SW_STUDY_CMAES, &r, start, vary2);
  o.samples = 120;
  o.resume = 1;
  assert_int_equal(sw_study_run(&o), SW_OK);
  fprintf(stderr, "# test_resume: interrupted after 21 of %d evaluations; the resumed study "
          "ran %d more, and its results equal the uninterrupted study's bit for bit\n", calls,
          r.calls);
  assert_int_equal(21 + r.calls, calls);
  assert_same_results(whole, cut);
  /* a resume with another seed regenerates other designs: refused */
  swProblem s = {.cx = 0.03, .cy = 0.25};
  o = options(cut, SW_STUDY_CMAES, &s, start, vary2);
  o.samples = 180;
  o.resume = 1;
  o.seed = 99;
  assert_int_equal(sw_study_run(&o), SW_EUSAGE);
  assert_int_equal(s.calls, 0);
}

/* Deletes /evaluations/params_si: the file of a study written before it. */
static void drop_params_si(const char *file) {
  hid_t f = H5Fopen(file, H5F_ACC_RDWR, H5P_DEFAULT);
  assert_true(f >= 0);
  assert_true(H5Ldelete(f, "/evaluations/params_si", H5P_DEFAULT) >= 0);
  H5Fclose(f);
}

static void test_params_si(void **state) {
  (void)state;
  char file[256];
  path_of(file, sizeof file, "si.h5");
  double seen[64][3];
  swProblem p = {.cx = 0.03, .cy = 0.25, .seen = seen};
  swStudyOptions o = options(file, SW_STUDY_CMAES, &p, start, vary2);
  o.samples = 60;
  assert_int_equal(sw_study_run(&o), SW_OK);
  long n, m;
  double *P = read_all(file, "/evaluations/params", H5T_NATIVE_DOUBLE, 3 * sizeof(double), &n);
  double *S = read_all(file, "/evaluations/params_si", H5T_NATIVE_DOUBLE, 3 * sizeof(double), &m);
  assert_int_equal(n, m);
  assert_int_equal(n, p.nseen);
  /* each row is a design sphere() was handed, and shown = SI / scale */
  int lost = 0;
  for (long i = 0; i < n; i++) {
    int found = 0;
    for (int k = 0; k < p.nseen && !found; k++) found = !memcmp(seen[k], S + 3 * i, sizeof seen[k]);
    assert_true(found);
    for (int j = 0; j < 3; j++) {
      double shown = S[3 * i + j] / scales[j];
      assert_memory_equal(&shown, P + 3 * i + j, sizeof shown);
      lost += P[3 * i + j] * scales[j] != S[3 * i + j];
    }
  }
  hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t ds = H5Dopen2(f, "/evaluations/params_si", H5P_DEFAULT);
  hid_t a = H5Aopen(ds, "units", H5P_DEFAULT), t = H5Aget_type(a);
  char *u[3] = {NULL, NULL, NULL};
  hid_t mt = H5Tget_native_type(t, H5T_DIR_ASCEND);
  assert_true(H5Aread(a, mt, u) >= 0);
  assert_string_equal(u[0], "m");
  assert_string_equal(u[1], "");
  assert_string_equal(u[2], "s");
  for (int j = 0; j < 3; j++) H5free_memory(u[j]);
  H5Tclose(mt), H5Tclose(t), H5Aclose(a), H5Dclose(ds);
  long best = (long)read_double_attr_of(f, "/best", "index");
  H5Fclose(f);
  fprintf(stderr, "# test_params_si: %ld designs, each stored in SI as evaluated; %d of %ld "
          "values shown in cm miss it when multiplied back\n", n, lost, 3 * n);
  /* reading a design: a row, the best, from params_si */
  double v[3];
  int got[3];
  swStudyDesign d;
  char err[256];
  assert_int_equal(sw_study_file_design(file, 7, 3, names, units, scales, v, got, &d, err,
                                        sizeof err), SW_OK);
  assert_true(d.exact && d.index == 7 && d.rows == n && d.status == SW_EVAL_OK);
  assert_memory_equal(v, S + 3 * 7, sizeof v);
  assert_int_equal(sw_study_file_design(file, -1, 3, names, units, scales, v, got, &d, err,
                                        sizeof err), SW_OK);
  assert_int_equal(d.index, best);
  assert_memory_equal(v, S + 3 * best, sizeof v);
  assert_int_equal(sw_study_file_design(file, n, 3, names, units, scales, v, got, &d, err,
                                        sizeof err), SW_EUSAGE);
  fprintf(stderr, "# test_params_si: row %ld: %s\n", n, err);
  /* a file of before params_si: the values shown, converted */
  drop_params_si(file);
  assert_int_equal(sw_study_file_design(file, 7, 3, names, units, scales, v, got, &d, err,
                                        sizeof err), SW_OK);
  assert_false(d.exact);
  for (int j = 0; j < 3; j++) assert_true(v[j] == P[3 * 7 + j] * scales[j] && got[j]);
  free(P);
  free(S);
}

/* A study whose file has no params_si, resumed: the file gets it, and is
 * then the file of the study that had it all along. */
static void test_resume_without_si(void **state) {
  (void)state;
  char whole[256], cut[256];
  path_of(whole, sizeof whole, "si_whole.h5");
  path_of(cut, sizeof cut, "si_cut.h5");
  swProblem p = {.cx = 0.03, .cy = 0.25, .fail_left = 1};
  swStudyOptions o = options(whole, SW_STUDY_CMAES, &p, start, vary2);
  o.samples = 60;
  assert_int_equal(sw_study_run(&o), SW_OK);
  swProblem q = {.cx = 0.03, .cy = 0.25, .fail_left = 1, .interrupt_after = 21};
  o = options(cut, SW_STUDY_CMAES, &q, start, vary2);
  o.samples = 60;
  assert_int_equal(sw_study_run(&o), SW_EINTERRUPT);
  drop_params_si(cut);
  swProblem r = {.cx = 0.03, .cy = 0.25, .fail_left = 1};
  o = options(cut, SW_STUDY_CMAES, &r, start, vary2);
  o.samples = 60;
  o.resume = 1;
  assert_int_equal(sw_study_run(&o), SW_OK);
  assert_same_results(whole, cut);
  fprintf(stderr, "# test_resume_without_si: a file without params_si, interrupted after 21 "
          "evaluations and resumed, holds the params_si of the study that never stopped\n");
  /* and a stored design that is not the regenerated one in SI is refused */
  hid_t f = H5Fopen(cut, H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t ds = H5Dopen2(f, "/evaluations/params_si", H5P_DEFAULT);
  hsize_t at[2] = {3, 0}, one[2] = {1, 1};
  hid_t fs = H5Dget_space(ds), ms = H5Screate_simple(2, one, NULL);
  double nudged = nextafter(r.cx, 1);  /* any finite value but the design's */
  H5Sselect_hyperslab(fs, H5S_SELECT_SET, at, NULL, one, NULL);
  assert_true(H5Dwrite(ds, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, &nudged) >= 0);
  H5Sclose(ms), H5Sclose(fs), H5Dclose(ds), H5Fclose(f);
  swProblem s = {.cx = 0.03, .cy = 0.25, .fail_left = 1};
  o = options(cut, SW_STUDY_CMAES, &s, start, vary2);
  o.samples = 66;
  o.resume = 1;
  assert_int_equal(sw_study_run(&o), SW_EUSAGE);
  assert_int_equal(s.calls, 0);
}

static void test_bad_settings(void **state) {
  (void)state;
  char file[256];
  path_of(file, sizeof file, "bad.h5");
  swProblem p = {0};
  static const int none[] = {0, 0, 0};
  swStudyOptions o = options(file, SW_STUDY_GRID, &p, start, none);
  assert_int_equal(sw_study_run(&o), SW_EUSAGE);
  o = options(file, SW_STUDY_GRID, &p, start, vary2);
  o.levels = 1;
  assert_int_equal(sw_study_run(&o), SW_EUSAGE);
  o = options(file, SW_STUDY_LHS, &p, start, vary2);
  o.samples = 0;
  assert_int_equal(sw_study_run(&o), SW_EUSAGE);
  o = options(file, SW_STUDY_CMAES, &p, start, vary2);
  o.sense = 0;
  assert_int_equal(sw_study_run(&o), SW_EUSAGE);
  o = options(file, SW_STUDY_CMAES, &p, start, vary2);
  o.sigma = -1;
  assert_int_equal(sw_study_run(&o), SW_EUSAGE);
  assert_int_equal(p.calls, 0);
  fprintf(stderr, "# test_bad_settings: 5 bad settings refused before any evaluation\n");
}

static int setup(void **state) {
  (void)state;
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
    cmocka_unit_test(test_grid),
    cmocka_unit_test(test_lhs),
    cmocka_unit_test(test_cmaes),
    cmocka_unit_test(test_failures_rank_last),
    cmocka_unit_test(test_resume),
    cmocka_unit_test(test_params_si),
    cmocka_unit_test(test_resume_without_si),
    cmocka_unit_test(test_bad_settings),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
