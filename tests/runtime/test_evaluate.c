/* test_evaluate.c — sw_evaluate and the objective of a run (evaluate.c), on
 * scenes built here whose objectives have closed forms.
 *
 * Design.  The scene is a rigid rod dropped from rest at height P[0] under
 * gravity P[1]: its centre of mass falls as z(t) = z0 - g t^2 / 2, which
 * position Verlet reproduces at every step up to round-off (the update is
 * exact for a constant acceleration), so the reductions have closed forms:
 * at(z, T) = z(T); max_over and min_over of a falling body are its ends,
 * z(T0) and z(T1); and mean_over, the trapezoidal rule over the steps of
 * [T0, T1], is the exact time average plus h^2 f'' / 12 = -g h^2 / 12 for
 * a quadratic (the rule's error term is exact there), a correction a plain
 * mean of the samples would not match.  The test's objective() keeps the R
 * it was given, so every reduction is checked on its own, and the score
 * against its rule for maximize and for minimize.  A clamped cantilever at
 * 2.5 times its stable step must come back SW_EUNSTABLE with a score of
 * -INFINITY; params that give no valid scene SW_EMODEL; a run shorter than
 * the objective's last time SW_EUSAGE.  Repeated evaluations give the same
 * bits, and the objective a plain run of the simulator (sw_main) stores in
 * its HDF5 is, bit for bit, sw_evaluate's.  Under the sanitizer build the
 * whole file also runs leak-checked. */
#include <hdf5.h>
#include <unistd.h>

#include "testutil.h"
#include "h5read.h"

/* ---- the falling rod ---- */

static const swParam fall_params[] = {
  {"z0", 2.0, {0, 1, 0, 0}, "m", "fall.sinew:1", 1, 1.0, 3.0},
  {"g", 9.81, {0, 1, -2, 0}, "m/s^2", "fall.sinew:2", 0, 0, 0},
  {"weight", 0.5, {0, 0, 0, 0}, "", "fall.sinew:3", 1, 0.0, 1.0},
};

enum { T_AT = 250, T0 = 100, T1 = 300 };   /* steps of 1 ms */
static const double H = 1e-3;

/* R[0] at(z, 0.25 s), R[1] mean_over(z, 0.1 s, 0.3 s), R[2] max_over, R[3] min_over */
static void add_reduction(swSpec *s, int kind, double t0, double t1) {
  swExpectDesc e;
  sw_expect_desc_init(&e);
  e.text = "reduction";
  e.quantity = SW_EXPECT_PROBE;
  e.index = 0;
  e.component = 2;
  e.reduce = kind;
  e.window = kind != SW_REDUCE_AT;
  e.t0 = t0;
  e.t1 = t1;
  assert_true(sw_spec_add_expect(s, &e) >= 0);
}

static int build_fall(swSpec *s, const double *P, char *err, size_t errlen) {
  (void)err;
  (void)errlen;
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "bar";
  r.nelem = 4;
  r.start[0] = r.start[1] = 0, r.start[2] = P[0];
  r.direction[0] = 1, r.direction[1] = 0, r.direction[2] = 0;
  r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
  r.length = 0.1;
  r.radius_start = r.radius_end = 0.01;
  r.density = 1000;
  r.youngs = 1e6;
  r.rigid = 1;
  sw_spec_add_rod(s, &r);
  swProbeDesc probe;
  sw_probe_desc_init(&probe);
  probe.name = "com";
  probe.kind = SW_PROBE_COM;
  sw_spec_add_probe(s, &probe);
  const double g[3] = {0, 0, -P[1]};
  sw_spec_set_gravity(s, g);
  add_reduction(s, SW_REDUCE_AT, T_AT * H, T_AT * H);
  add_reduction(s, SW_REDUCE_MEAN, T0 * H, T1 * H);
  add_reduction(s, SW_REDUCE_MAX, T0 * H, T1 * H);
  add_reduction(s, SW_REDUCE_MIN, T0 * H, T1 * H);
  return SW_OK;
}

static double seen_R[4];

/* maximize at(z, 0.25 s); penalty weight * (max_over(z) - min_over(z)) */
static void fall_objective(const double *P, const double *R, double *value, double *penalty) {
  memcpy(seen_R, R, sizeof seen_R);
  *value = R[0];
  *penalty = P[2] * (R[2] - R[3]);
}

static swProgram fall_program(int sense) {
  swProgram p = {
    .name = "fall",
    .source = "# the falling rod of test_evaluate.c\n",
    .sha256 = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef",
    .nparam = 3,
    .param = fall_params,
    .build = build_fall,
    .dt = 1e-3,
    .duration = 0.4,
    .every = 0.01,
    .sense = sense,
    .objective_text = sense > 0 ? "maximize at(z(com), 0.25 s)" : "minimize at(z(com), 0.25 s)",
    .objective_where = "fall.sinew:20",
    .objective_unit = "cm",
    .objective_scale = 0.01,
    .objective_si_unit = "m",
    .npenalty = 1,
    .nreduce = 4,
    .objective = fall_objective,
  };
  return p;
}

static double z_of(double z0, double g, double t) { return z0 - 0.5 * g * t * t; }

/* Each reduction against its closed form, and the score's rule. */
static void test_reductions_closed_form(void **state) {
  (void)state;
  const double z0 = 2.5, g = 9.81, w = 0.25;
  const double P[3] = {z0, g, w};
  for (int sense = 1; sense >= -1; sense -= 2) {
    swProgram p = fall_program(sense);
    swEvalResult r;
    assert_int_equal(sw_evaluate(&p, P, 0, 0, -1, &r), SW_OK);
    assert_string_equal(r.message, "");
    const double t0 = T0 * H, t1 = T1 * H;
    const double at = z_of(z0, g, T_AT * H);
    /* time average of z0 - g t^2/2 over [t0, t1], and the trapezoidal
     * rule's exact error for a quadratic, h^2 f''/12 with f'' = -g */
    const double mean = z0 - g * (t1 * t1 * t1 - t0 * t0 * t0) / (6 * (t1 - t0));
    const double trapezoid = mean - g * H * H / 12;
    SW_EXPECT_ABS("at(z, 0.25 s) (m)", seen_R[0], at, 1e-12);
    SW_EXPECT_ABS("mean_over(z, 0.1 s, 0.3 s) (m)", seen_R[1], trapezoid, 1e-12);
    SW_EXPECT_ABS("max_over(z, 0.1 s, 0.3 s) (m)", seen_R[2], z_of(z0, g, t0), 1e-12);
    SW_EXPECT_ABS("min_over(z, 0.1 s, 0.3 s) (m)", seen_R[3], z_of(z0, g, t1), 1e-12);
    const double penalty = w * (z_of(z0, g, t0) - z_of(z0, g, t1));
    SW_EXPECT_ABS("objective (m)", r.objective, at, 1e-12);
    SW_EXPECT_ABS("penalty (m)", r.penalty, penalty, 1e-12);
    SW_EXPECT_ABS(sense > 0 ? "score, maximize (m)" : "score, minimize (m)", r.score,
                  sense > 0 ? at - penalty : -(at + penalty), 1e-12);
    SW_EXPECT_ABS("simulated time (s)", r.sim_time, 0.4, 1e-12);
    assert_int_equal(r.steps, 400);
  }
}

/* The same params give the same bits, every time. */
static void test_repeatable(void **state) {
  (void)state;
  swProgram p = fall_program(1);
  const double P[3] = {1.7, 9.81, 0.5};
  swEvalResult a, b;
  assert_int_equal(sw_evaluate(&p, P, 0, 0, -1, &a), SW_OK);
  for (int k = 0; k < 3; k++) {
    assert_int_equal(sw_evaluate(&p, P, 0, 0, -1, &b), SW_OK);
    assert_memory_equal(&a.objective, &b.objective, sizeof(double));
    assert_memory_equal(&a.penalty, &b.penalty, sizeof(double));
    assert_memory_equal(&a.score, &b.score, sizeof(double));
  }
  fprintf(stderr, "# %s: 4 evaluations, score %.17g m each time\n", __func__, a.score);
  /* NULL: the defaults */
  swEvalResult d;
  assert_int_equal(sw_evaluate(&p, NULL, 0, 0, -1, &d), SW_OK);
  SW_EXPECT_ABS("objective at the defaults (m)", d.objective, z_of(2.0, 9.81, 0.25), 1e-12);
}

/* What a plain run of the simulator stores is what sw_evaluate finds. */
static void test_plain_run_same_bits(void **state) {
  (void)state;
  char dir[] = "/tmp/sinew-evaluate.XXXXXX";
  assert_non_null(mkdtemp(dir));
  char out[128], set[64];
  snprintf(out, sizeof out, "%s/fall.h5", dir);
  snprintf(set, sizeof set, "z0=2.2m");
  swProgram p = fall_program(-1);
  char *argv[] = {"fall", "--quiet", "--out", out, "--set", set, NULL};
  assert_int_equal(sw_main(&p, 6, argv), SW_OK);
  hid_t f = H5Fopen(out, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(f >= 0);
  const double stored = read_double_attr(f, "objective"), penalty = read_double_attr(f, "penalty"),
               score = read_double_attr(f, "score");
  char *units = read_string_attr(f, "/", "objective_units");
  char *text = read_string_attr(f, "/", "objective_text");
  H5Fclose(f);
  const double P[3] = {2.2, 9.81, 0.5};
  swEvalResult r;
  assert_int_equal(sw_evaluate(&p, P, 0, 0, -1, &r), SW_OK);
  fprintf(stderr, "# %s: stored objective %.17g %s, sw_evaluate's %.17g; score %.17g, %.17g\n",
          __func__, stored, units, r.objective, score, r.score);
  assert_memory_equal(&stored, &r.objective, sizeof(double));
  assert_memory_equal(&penalty, &r.penalty, sizeof(double));
  assert_memory_equal(&score, &r.score, sizeof(double));
  assert_string_equal(units, "m");
  assert_string_equal(text, "minimize at(z(com), 0.25 s)");
  free(units);
  free(text);
  unlink(out);
  char xdmf[128];
  snprintf(xdmf, sizeof xdmf, "%s/fall.xdmf", dir);
  unlink(xdmf);
  assert_int_equal(rmdir(dir), 0);
}

/* A run shorter than the objective's last time is refused before it runs. */
static void test_too_short(void **state) {
  (void)state;
  swProgram p = fall_program(1);
  swEvalResult r;
  assert_int_equal(sw_evaluate(&p, NULL, 0.2, 0, -1, &r), SW_EUSAGE);
  fprintf(stderr, "# %s: %s\n", __func__, r.message);
  assert_non_null(strstr(r.message, "up to t = 0.3 s"));
  assert_true(isnan(r.objective));
  assert_true(r.score == -INFINITY);
  assert_int_equal(r.steps, 0);
  /* a model without an objective */
  p.sense = 0;
  p.objective = NULL;
  assert_int_equal(sw_evaluate(&p, NULL, 0, 0, -1, &r), SW_EUSAGE);
  fprintf(stderr, "# %s: %s\n", __func__, r.message);
}

/* ---- the cantilever: a bad param, and an unstable step ---- */

static int build_cantilever(swSpec *s, const double *P, char *err, size_t errlen) {
  if (!(P[0] < 10)) {   /* build() itself refuses */
    snprintf(err, errlen, "cantilever.sinew:1: length %g m is too long", P[0]);
    return SW_EMODEL;
  }
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "beam";
  r.nelem = 10;
  r.direction[0] = 1, r.direction[1] = 0, r.direction[2] = 0;
  r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
  r.length = P[0];   /* <= 0: sw_compile refuses */
  r.radius_start = r.radius_end = 0.01;
  r.density = 1000;
  r.youngs = 1e6;
  int beam = sw_spec_add_rod(s, &r);
  swBCDesc clamp = sw_test_clamp(beam, 0);
  sw_spec_add_bc(s, &clamp);
  swLoadDesc tip = sw_test_load(SW_LOAD_FORCE, beam, -1, 0, 0, -1e-2);
  sw_spec_add_load(s, &tip);
  swProbeDesc probe;
  sw_probe_desc_init(&probe);
  probe.name = "tip";
  probe.kind = SW_PROBE_NODE;
  probe.rod = beam;
  probe.node = -1;
  sw_spec_add_probe(s, &probe);
  add_reduction(s, SW_REDUCE_AT, 0.05, 0.05);
  return SW_OK;
}

static void cantilever_objective(const double *P, const double *R, double *value,
                                 double *penalty) {
  (void)P;
  *value = R[0];
  *penalty = 0;
}

static const swParam cantilever_params[] = {
  {"length", 0.5, {0, 1, 0, 0}, "m", "cantilever.sinew:1", 1, 0.1, 1.0},
};

static const swProgram cantilever = {
  .name = "cantilever",
  .nparam = 1,
  .param = cantilever_params,
  .build = build_cantilever,
  .duration = 0.05,
  .every = 1e-3,
  .sense = -1,
  .objective_text = "minimize at(z(tip), 50 ms)",
  .objective_where = "cantilever.sinew:9",
  .objective_unit = "m",
  .objective_scale = 1,
  .objective_si_unit = "m",
  .nreduce = 1,
  .objective = cantilever_objective,
};

static void test_unstable(void **state) {
  (void)state;
  /* the stable estimate of the default scene */
  char err[256];
  double stable;
  int status;
  const double P[1] = {0.5};
  swModel *m = sw_program_compile(&cantilever, P, 0, -1, cantilever.every, &stable, &status, err,
                         sizeof err);
  assert_non_null(m);
  assert_int_equal(status, SW_OK);
  fprintf(stderr, "# %s: stable estimate %.6g s, chosen dt %.6g s (a whole number of steps a "
          "frame: %.9g)\n", __func__, stable, m->dt, cantilever.every / m->dt);
  assert_true(m->dt <= 0.5 * stable);
  assert_true(fabs(cantilever.every / m->dt - round(cantilever.every / m->dt)) < 1e-9);
  sw_model_free(m);
  swEvalResult r;
  assert_int_equal(sw_evaluate(&cantilever, P, 0, 0, -1, &r), SW_OK);
  fprintf(stderr, "# %s: at half the estimate: tip z %.6g m after %ld steps\n", __func__,
          r.objective, r.steps);
  assert_int_equal(sw_evaluate(&cantilever, P, 0, 2.5 * stable, -1, &r), SW_EUNSTABLE);
  fprintf(stderr, "# %s: at 2.5x the estimate: status %d after %ld steps (t = %.3g s): %s\n",
          __func__, r.status, r.steps, r.sim_time, r.message);
  assert_true(r.score == -INFINITY);
  assert_true(isnan(r.objective));
  assert_true(r.message[0] != '\0');
  assert_true(r.sim_time < cantilever.duration);
}

static void test_bad_params(void **state) {
  (void)state;
  swEvalResult r;
  const double nan_length[1] = {NAN}, negative[1] = {-0.5}, too_long[1] = {20};
  assert_int_equal(sw_evaluate(&cantilever, nan_length, 0, 0, -1, &r), SW_EMODEL);
  fprintf(stderr, "# %s: NaN: %s\n", __func__, r.message);
  assert_true(r.score == -INFINITY);
  assert_int_equal(sw_evaluate(&cantilever, negative, 0, 0, -1, &r), SW_EMODEL);
  fprintf(stderr, "# %s: -0.5 m: %s\n", __func__, r.message);
  assert_true(r.score == -INFINITY && r.message[0]);
  assert_int_equal(sw_evaluate(&cantilever, too_long, 0, 0, -1, &r), SW_EMODEL);
  fprintf(stderr, "# %s: 20 m: %s\n", __func__, r.message);
  assert_string_equal(r.message, "cantilever.sinew:1: length 20 m is too long");
  assert_int_equal(sw_evaluate(&cantilever, negative, 0, 0, 7, &r), SW_EUSAGE);
}

int main(void) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_reductions_closed_form),
    cmocka_unit_test(test_repeatable),
    cmocka_unit_test(test_plain_run_same_bits),
    cmocka_unit_test(test_too_short),
    cmocka_unit_test(test_unstable),
    cmocka_unit_test(test_bad_params),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
