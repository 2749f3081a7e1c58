/* test_cli.c — tests of cli.c, the command line of generated simulators:
 * --help, --info, every usage error by its exact message and exit code, --set
 * with units and dimensions, the run writing HDF5, the automatic time step, a
 * step above the stable estimate, and an output file that cannot be created.
 *
 * Design.  The test is its own generated simulator: a swProgram with a
 * cantilever (a clamped rod with a tip load) and two params, one with a
 * dimension (the length) and one without (the load's strength), driven by
 * sw_main() with argv arrays as a shell would pass them.  sw_main() writes to
 * the process's stdout and stderr, so each call runs with file descriptors 1
 * and 2 redirected to temporary files, which are read back and compared; the
 * text is echoed as "# " lines so it shows in the test log.  Files written by
 * runs are read back with the plain HDF5 C API and go to a fresh directory
 * under /tmp, removed at the end. */
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include "testutil.h"
#include "h5read.h"

/* ---- the program under test ---- */

static const swParam cantilever_params[] = {
  {"length", 0.5, {0, 1, 0, 0}, "m", "cantilever.sinew:2", 0, 0, 0},
  {"strength", 1.0, {0, 0, 0, 0}, "", "cantilever.sinew:3", 0, 0, 0},
};

static int build_cantilever(swSpec *s, const double *P, char *err, size_t errlen) {
  if (!(P[0] > 0)) {
    snprintf(err, errlen, "cantilever.sinew:2: length must be positive, got %g m", P[0]);
    return SW_EMODEL;
  }
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "beam";
  r.nelem = 10;
  r.direction[0] = 1, r.direction[1] = 0, r.direction[2] = 0;
  r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
  r.length = P[0];
  r.radius_start = r.radius_end = 0.01;
  r.density = 1000;
  r.youngs = 1e6;
  int beam = sw_spec_add_rod(s, &r);
  swBCDesc clamp = sw_test_clamp(beam, 0);
  sw_spec_add_bc(s, &clamp);
  swLoadDesc tip = sw_test_load(SW_LOAD_FORCE, beam, -1, 0, 0, -1e-3 * P[1]);
  sw_spec_add_load(s, &tip);
  return SW_OK;
}

static const swProgram cantilever = {
  .name = "cantilever",
  .source = "param length = 0.5 m;\nparam strength = 1;\nrod beam { ... }\n",
  .sha256 = "5d41402abc4b2a76b9719d911017c592aaf4cbf1b3c5d9e7f00112233445566",
  .nparam = 2,
  .param = cantilever_params,
  .build = build_cantilever,
  .dt = 0,            /* half the stable estimate */
  .duration = 2e-3,
  .every = 1e-3,
  .out = NULL,        /* cantilever.h5 */
  .velocity = 1,
  .directors = 0,
};

/* ---- running sw_main with its output captured ---- */

static char tmpdir[64];

typedef struct {
  int rc;
  char out[16384], err[16384];
} swCliResult;

static void slurp(FILE *f, char *buf, size_t len) {
  rewind(f);
  size_t got = fread(buf, 1, len - 1, f);
  buf[got] = '\0';
  fclose(f);
}

static void echo(const char *what, const char *text) {
  const char *line = text;
  while (*line) {
    size_t n = strcspn(line, "\n");
    fprintf(stderr, "#   %s| %.*s\n", what, (int)n, line);
    line += n + (line[n] == '\n');
  }
}

/* args: NULL-terminated, without argv[0] (which is "/usr/local/bin/sim") */
static void run_cli(swCliResult *r, const char *const *args) {
  char *argv[64];
  int argc = 0;
  argv[argc++] = strdup("/usr/local/bin/sim");
  fprintf(stderr, "# $ sim");
  for (const char *const *a = args; *a; a++) {
    assert_true(argc < 63);
    argv[argc++] = strdup(*a);
    fprintf(stderr, " %s", *a);
  }
  fprintf(stderr, "\n");
  argv[argc] = NULL;

  FILE *out = tmpfile(), *err = tmpfile();
  assert_non_null(out);
  assert_non_null(err);
  fflush(stdout);
  fflush(stderr);
  int saved_out = dup(1), saved_err = dup(2);
  assert_true(saved_out >= 0 && saved_err >= 0);
  assert_true(dup2(fileno(out), 1) >= 0);
  assert_true(dup2(fileno(err), 2) >= 0);
  r->rc = sw_main(&cantilever, argc, argv);
  fflush(stdout);
  fflush(stderr);
  dup2(saved_out, 1);
  dup2(saved_err, 2);
  close(saved_out);
  close(saved_err);
  slurp(out, r->out, sizeof r->out);
  slurp(err, r->err, sizeof r->err);
  for (int i = 0; i < argc; i++) free(argv[i]);
  fprintf(stderr, "#   exit %d\n", r->rc);
  echo("stdout", r->out);
  echo("stderr", r->err);
}

static void expect_contains(const char *text, const char *piece) {
  if (!strstr(text, piece)) fprintf(stderr, "# missing: \"%s\"\n", piece);
  assert_non_null(strstr(text, piece));
}

/* ---- reading a file back ---- */

/* A root attribute, which sw_main writes as a variable-length string. */
static char *read_root_string(hid_t file, const char *name) {
  hid_t attr = H5Aopen_by_name(file, "/", name, H5P_DEFAULT, H5P_DEFAULT);
  assert_true(attr >= 0);
  hid_t type = H5Aget_type(attr);
  assert_true(H5Tis_variable_str(type) > 0);
  H5Tclose(type);
  H5Aclose(attr);
  return read_string_attr(file, "/", name);
}

/* Frames in the file, and the x coordinate of the last node in frame 0. */
static long read_frames(hid_t file, double *tip_x0) {
  hid_t dset = H5Dopen2(file, "/rods/beam/position", H5P_DEFAULT);
  assert_true(dset >= 0);
  hid_t space = H5Dget_space(dset);
  hsize_t dims[3];
  assert_int_equal(H5Sget_simple_extent_ndims(space), 3);
  H5Sget_simple_extent_dims(space, dims, NULL);
  assert_int_equal(dims[1], 11);
  double *x = malloc(dims[0] * dims[1] * dims[2] * sizeof *x);
  assert_non_null(x);
  assert_true(H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, x) >= 0);
  *tip_x0 = x[3 * 10];
  free(x);
  H5Sclose(space);
  H5Dclose(dset);
  return (long)dims[0];
}

/* A run's files: RUN.h5 and the XDMF description written beside it. */
static void unlink_run(const char *path) {
  char xdmf[600];
  size_t n = strlen(path);
  unlink(path);
  if (n > 3 && n < sizeof xdmf && !strcmp(path + n - 3, ".h5")) {
    snprintf(xdmf, sizeof xdmf, "%.*s.xdmf", (int)(n - 3), path);
    unlink(xdmf);
  }
}

static void temp_file(char *path, size_t len, const char *name) {
  snprintf(path, len, "%s/%s", tmpdir, name);
  unlink_run(path);
}

/* ---- tests ---- */

static void test_help(void **state) {
  (void)state;
  swCliResult r;
  run_cli(&r, (const char *[]){"--help", NULL});
  assert_int_equal(r.rc, 0);
  assert_string_equal(r.err, "");
  expect_contains(r.out, "usage: sim [options]\n");
  expect_contains(r.out, "--out FILE");
  expect_contains(r.out, "(default: cantilever.h5)");
  expect_contains(r.out, "--duration T");
  expect_contains(r.out, "(default: 2 ms)");
  expect_contains(r.out, "--dt DT");
  expect_contains(r.out, "(default: half the stable estimate)");
  expect_contains(r.out, "--every T");
  expect_contains(r.out, "--set NAME=VALUE");
  expect_contains(r.out, "--threads N");
  expect_contains(r.out, "--quiet");
  expect_contains(r.out, "--info");
  expect_contains(r.out, "  length   = 0.5 m        length (m)     cantilever.sinew:2\n");
  expect_contains(r.out, "  strength = 1            dimensionless  cantilever.sinew:3\n");
  /* -h too, and --help wins over the rest of a valid line */
  run_cli(&r, (const char *[]){"--dt", "1us", "-h", NULL});
  assert_int_equal(r.rc, 0);
  expect_contains(r.out, "usage: sim [options]\n");
}

static void test_info(void **state) {
  (void)state;
  char path[128];
  temp_file(path, sizeof path, "info.h5");
  swCliResult r;
  run_cli(&r, (const char *[]){"--info", "--out", path, "--set", "length=30 cm", "--threads",
                               "4", NULL});
  assert_int_equal(r.rc, 0);
  assert_string_equal(r.err, "");
  expect_contains(r.out, "model: cantilever\n");
  expect_contains(r.out, "sha256: 5d41402abc4b2a76b9719d911017c592aaf4cbf1b3c5d9e7f00112233445566\n");
  expect_contains(r.out, "rods: 1 (10 elements, 11 nodes)\n");
  expect_contains(r.out, "  beam: 10 elements, length 0.3 m, radius 10 mm, mass ");
  expect_contains(r.out, "joints: 0\n");
  expect_contains(r.out, "loads: 1 (1 point force, 0 point couples)\n");
  expect_contains(r.out, "boundary conditions: 1 (1 clamped end, 0 prescribed velocities");
  expect_contains(r.out, "gravity: none\n");
  expect_contains(r.out, "integrator: position Verlet\n");
  expect_contains(r.out, "(half the stable estimate, shortened so that 6 steps span the model's frame interval; stable estimate 386.25 us)");
  expect_contains(r.out, "memory: about ");
  expect_contains(r.out, "threads: 4 (--threads; ");
  expect_contains(r.out, "; results do not depend on it)\n");
  expect_contains(r.out, "  length = 0.3 m (--set; default 0.5 m)\n");
  expect_contains(r.out, "  strength = 1\n");
  /* the mass printed is rho A L */
  const char *mass = strstr(r.out, "mass ");
  SW_EXPECT_REL("rod mass in --info (kg)", atof(mass + 5), 1000 * 3.14159265358979 * 1e-4 * 0.3, 1e-5);
  /* nothing was run or written */
  struct stat st;
  assert_int_not_equal(stat(path, &st), 0);
}

static void test_usage_errors(void **state) {
  (void)state;
  static const struct {
    const char *args[6];
    const char *message;
  } cases[] = {
    {{"--dtt", "5ns"}, "sim: unknown option '--dtt' (did you mean '--dt'?)"},
    {{"-dt", "5ns"}, "sim: unknown option '-dt' (did you mean '--dt'?)"},
    {{"--durration=1s"}, "sim: unknown option '--durration' (did you mean '--duration'?)"},
    {{"--frobnicate"}, "sim: unknown option '--frobnicate' (see --help)"},
    {{"model.h5"}, "sim: unexpected argument 'model.h5' (options start with '--'; see --help)"},
    {{"--dt", "3 m"}, "sim: --dt: expected time (s), got length (m) in '3 m'"},
    {{"--dt=3 m"}, "sim: --dt: expected time (s), got length (m) in '3 m'"},
    {{"--dt"}, "sim: --dt: missing value (--dt DT)"},
    {{"--dt", "--quiet"}, "sim: --dt: missing value (--dt DT)"},
    {{"--dt", "0 ns"}, "sim: --dt: must be positive, got '0 ns'"},
    {{"--duration", "-1 s"}, "sim: --duration: must not be negative, got '-1 s'"},
    {{"--duration", "5 sec"}, "sim: --duration: unknown unit 'sec' in '5 sec'"},
    {{"--every", "1 Hz"}, "sim: --every: expected time (s), got frequency (Hz) in '1 Hz'"},
    {{"--out"}, "sim: --out: missing value (--out FILE)"},
    {{"--out="}, "sim: --out: empty file name"},
    {{"--threads", "0"}, "sim: --threads: expected a positive integer or 'auto', got '0'"},
    {{"--threads", "two"}, "sim: --threads: expected a positive integer or 'auto', got 'two'"},
    {{"--threads=2.5"}, "sim: --threads: expected a positive integer or 'auto', got '2.5'"},
    {{"--threads", "257"}, "sim: --threads: at most 256, got '257'"},
    {{"--quiet=yes"}, "sim: --quiet takes no value, got '--quiet=yes'"},
    {{"--set", "length"}, "sim: --set: expected NAME=VALUE, got 'length'"},
    {{"--set", "=3 m"}, "sim: --set: expected NAME=VALUE, got '=3 m'"},
    {{"--set", "lenght=1 m"}, "sim: --set: unknown param 'lenght' (did you mean 'length'?)"},
    {{"--set", "gain=2"}, "sim: --set: unknown param 'gain' (the params are: length, strength)"},
    {{"--set", "length=2 s"}, "sim: --set length: expected length (m), got time (s) in '2 s'"},
    {{"--set", "length=2"},
     "sim: --set length: expected length (m), got a number without a unit in '2' "
     "(write e.g. '2 m')"},
    {{"--set", "strength=2 m"},
     "sim: --set strength: expected dimensionless, got length (m) in '2 m'"},
    {{"--set", "strength=30 deg"},
     "sim: --set strength: expected dimensionless, got angle (rad) in '30 deg'"},
    {{"--set=length=1 parsec"}, "sim: --set length: unknown unit 'parsec' in '1 parsec'"},
    /* runs no machine would finish, or that take no step: refused before
     * anything is written (the step count once overflowed to 0 steps and
     * the run "completed") */
    {{"--duration", "1e20 s", "--dt", "1 us"},
     "sim: no run: a duration of 1e+20 s at dt = 1e-06 s is 1e+26 steps, more than the 1e+13 a "
     "run may take (dt: --dt; duration: --duration)"},
    {{"--dt", "1e-300 s"},
     "sim: no run: a duration of 0.002 s at dt = 1e-300 s is 2e+297 steps, more than the 1e+13 "
     "a run may take (dt: --dt; duration: from the model)"},
    {{"--dt", "1 s", "--info"},
     "sim: no run: dt = 1 s is longer than twice the duration 0.002 s: not one step would be "
     "taken (dt: --dt; duration: from the model)"},
    {{"--duration", "1e400 s"}, "sim: --duration: number out of range in '1e400 s'"},
    /* an error after a valid --set still fails */
    {{"--set", "length=1 m", "--every", "x"}, "sim: --every: expected a number in 'x'"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    swCliResult r;
    char expected[512];
    run_cli(&r, cases[i].args);
    snprintf(expected, sizeof expected, "%s\n", cases[i].message);
    assert_int_equal(r.rc, SW_EUSAGE);
    assert_string_equal(r.out, "");
    assert_string_equal(r.err, expected);
  }
}

/* A param value the model rejects is a model error (exit 1), in its words. */
static void test_model_error(void **state) {
  (void)state;
  swCliResult r;
  run_cli(&r, (const char *[]){"--set", "length=-1 m", NULL});
  assert_int_equal(r.rc, SW_EMODEL);
  assert_string_equal(r.err, "sim: cantilever.sinew:2: length must be positive, got -1 m\n");
}

/* A run with --set writes the frames asked for, the params, and the rod the
 * params describe; a later --set wins. */
static void test_run_writes_file(void **state) {
  (void)state;
  char path[128];
  temp_file(path, sizeof path, "run.h5");
  swCliResult r;
  run_cli(&r, (const char *[]){"--out", path, "--duration", "1ms", "--every=0.1 ms", "--dt",
                               "10us", "--set", "length=30 cm", "--set", "strength=2",
                               "--set=strength=3", NULL});
  assert_int_equal(r.rc, SW_OK);
  assert_string_equal(r.out, "");
  char summary[256];
  snprintf(summary, sizeof summary,
           "sim: done: 11 frames written to %s; simulated 1 ms in ", path);
  assert_true(strncmp(r.err, summary, strlen(summary)) == 0);
  expect_contains(r.err, " wall time (100 steps)\n");

  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  double tip_x0;
  long frames = read_frames(file, &tip_x0);
  fprintf(stderr, "# %s: %ld frames, tip at x = %.17g m in frame 0\n", __func__, frames, tip_x0);
  assert_int_equal(frames, 11);
  SW_EXPECT_ABS("rod length set by --set (m)", tip_x0, 0.3, 1e-15);
  char *params = read_root_string(file, "params");
  char *status = read_root_string(file, "status");
  char *sha = read_root_string(file, "model_sha256");
  char *source = read_root_string(file, "model_source");
  fprintf(stderr, "# %s: params \"%s\", status \"%s\"\n", __func__, params, status);
  assert_string_equal(params, "length=0.29999999999999999;strength=3");
  assert_string_equal(status, "complete");
  assert_string_equal(sha, cantilever.sha256);
  assert_string_equal(source, cantilever.source);
  assert_true(read_double_attr(file, "dt") == 1e-5);
  assert_true(read_double_attr(file, "duration") == 1e-3);
  assert_true(H5Lexists(file, "/rods/beam/velocity", H5P_DEFAULT) > 0);
  assert_true(H5Lexists(file, "/rods/beam/directors", H5P_DEFAULT) == 0);
  free(params);
  free(status);
  free(sha);
  free(source);
  H5Fclose(file);
  unlink_run(path);

  /* --quiet: no summary */
  run_cli(&r, (const char *[]){"--out", path, "--quiet", "--duration", "0.2 ms", NULL});
  assert_int_equal(r.rc, SW_OK);
  assert_string_equal(r.err, "");
  assert_string_equal(r.out, "");
  unlink_run(path);
}

/* Without --dt (and none in the model) the step is at most half the stable
 * estimate, shortened so that a whole number of steps spans the frame
 * interval (1 ms here): frames fall exactly on multiples of it. */
/* The stable dt estimate of the simulator's scene at its default params. */
static double cantilever_stable_dt(void) {
  swSpec *s = sw_spec_new();
  char err[256];
  const double P[2] = {0.5, 1};
  assert_int_equal(build_cantilever(s, P, err, sizeof err), SW_OK);
  swModel *m = sw_test_compile(s);
  const double stable = sw_stable_dt(m);
  sw_model_free(m);
  sw_spec_free(s);
  return stable;
}

static void test_automatic_dt(void **state) {
  (void)state;
  double half = 0.5 * cantilever_stable_dt();
  double expected = 1e-3 / ceil(1e-3 / half - 1e-9);

  char path[128];
  temp_file(path, sizeof path, "auto.h5");
  swCliResult r;
  run_cli(&r, (const char *[]){"--out", path, "--quiet", NULL});
  assert_int_equal(r.rc, SW_OK);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  double dt = read_double_attr(file, "dt");
  double tip_x0;
  long frames = read_frames(file, &tip_x0);
  long nsteps = llround(2e-3 / dt), every = llround(1e-3 / dt);
  fprintf(stderr, "# %s: dt = %.9g s (half the estimate: %.9g s; 1 ms / dt = %.12g), %ld frames\n",
          __func__, dt, half, 1e-3 / dt, frames);
  assert_true(dt == expected);
  assert_true(dt <= half);
  assert_int_equal(frames, 1 + nsteps / every + (nsteps % every != 0));
  SW_EXPECT_ABS("default rod length (m)", tip_x0, 0.5, 1e-15);
  H5Fclose(file);
  unlink_run(path);
}

/* A step above the estimate is warned about, not refused; this one is far
 * above it and the run says it became unstable (exit 3), in the file too. */
static void test_unstable_dt(void **state) {
  (void)state;
  char path[128];
  temp_file(path, sizeof path, "unstable.h5");
  swCliResult r;
  run_cli(&r, (const char *[]){"--out", path, "--dt", "1ms", "--duration", "2 s", "--every",
                               "10 ms", "--threads", "2", NULL});
  assert_int_equal(r.rc, SW_EUNSTABLE);
  expect_contains(r.err, "sim: warning: dt = 1 ms is above the stable estimate ");
  expect_contains(r.err, "; the run may become unstable\n");
  expect_contains(r.err, "sim: unstable: ");
  expect_contains(r.err, " of 2 s in ");
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  char *status = read_root_string(file, "status");
  fprintf(stderr, "# %s: status \"%s\"\n", __func__, status);
  assert_true(strncmp(status, "unstable: ", 10) == 0);
  free(status);
  H5Fclose(file);
  unlink_run(path);

  /* --info says the same without running */
  run_cli(&r, (const char *[]){"--info", "--dt", "1ms", "--quiet", NULL});
  assert_int_equal(r.rc, SW_OK);
  expect_contains(r.err, "sim: warning: dt = 1 ms is above the stable estimate ");
  expect_contains(r.out, "dt: 1 ms (--dt; stable estimate ");
}

/* dt at 0.5x and 0.9x the stable estimate runs clean; at 2x the run is
 * caught: exit 3, the message naming the rod, the time and the stable dt,
 * and an HDF5 file that opens and holds the frames written before, with the
 * status saying why it ended. */
static void test_dt_ladder(void **state) {
  (void)state;
  const double stable = cantilever_stable_dt();
  const double fracs[] = {0.5, 0.9, 2.0};
  for (int f = 0; f < 3; f++) {
    char path[128], dt[64];
    temp_file(path, sizeof path, "ladder.h5");
    snprintf(dt, sizeof dt, "%.17g s", fracs[f] * stable);
    swCliResult r;
    run_cli(&r, (const char *[]){"--out", path, "--dt", dt, "--duration", "0.5 s", "--every", "10 ms",
                                 NULL});
    hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(file >= 0);
    char *status = read_root_string(file, "status");
    double tip_x0;
    long frames = read_frames(file, &tip_x0);
    fprintf(stderr, "# %s: dt = %.2f x the estimate: exit %d, %ld frames, status \"%.60s\"\n", __func__,
            fracs[f], r.rc, frames, status);
    if (fracs[f] < 1) {
      assert_int_equal(r.rc, SW_OK);
      assert_string_equal(status, "complete");
      const long k = llround(0.01 / (fracs[f] * stable)), n = llround(0.5 / (fracs[f] * stable));
      assert_int_equal(frames, 1 + n / k + (n % k != 0)); /* frames every k steps, and the last */
    } else {
      assert_int_equal(r.rc, SW_EUNSTABLE);
      expect_contains(r.err, "rod 'beam' became unstable at element ");
      expect_contains(r.err, ", t = ");
      expect_contains(r.err, "stable dt estimate");
      expect_contains(r.err, "sim: unstable: ");
      assert_true(strncmp(status, "unstable: rod 'beam'", 20) == 0);
      assert_true(frames >= 1 && frames < 50);
      SW_EXPECT_ABS("first frame, tip x (m)", tip_x0, 0.5, 1e-15);
    }
    free(status);
    H5Fclose(file);
    unlink_run(path);
  }
}

static void test_unwritable_output(void **state) {
  (void)state;
  swCliResult r;
  run_cli(&r, (const char *[]){"--out", "/nonexistent-dir/x.h5", "--duration", "0", NULL});
  assert_int_equal(r.rc, SW_EIO);
  assert_true(strncmp(r.err, "sim: cannot create HDF5 file /nonexistent-dir/x.h5", 50) == 0);
}

static int make_tmpdir(void **state) {
  (void)state;
  snprintf(tmpdir, sizeof tmpdir, "/tmp/sinew_test_cli_XXXXXX");
  return mkdtemp(tmpdir) ? 0 : -1;
}

static int remove_tmpdir(void **state) {
  (void)state;
  return rmdir(tmpdir);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_help),
    cmocka_unit_test(test_info),
    cmocka_unit_test(test_usage_errors),
    cmocka_unit_test(test_model_error),
    cmocka_unit_test(test_run_writes_file),
    cmocka_unit_test(test_automatic_dt),
    cmocka_unit_test(test_unstable_dt),
    cmocka_unit_test(test_dt_ladder),
    cmocka_unit_test(test_unwritable_output),
  };
  return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
