/* test_output.c — tests of output.c and run.c: the HDF5 schema written by a
 * run, the frame schedule, Ctrl-C leaving a valid file, an unstable run, time
 * arguments, the error message for a file that cannot be created, the
 * XDMF description beside the file (names escaped, node radii), and the
 * two ways frames reach the datasets (whole chunks as stored, or frames by a
 * selection) giving the same datasets.
 *
 * Design.  The file written by sw_run() is read back with the plain HDF5 C API
 * (not through output.c), so the test checks what a user's h5py script would
 * see: paths, shapes, `units`, root attributes and values equal to the state
 * the run ended in.  The Ctrl-C test forks a child that runs a long simulation
 * with its progress log on a pipe; the parent waits (bounded) for the first
 * progress line, which the run prints only after a second, so by then the
 * SIGINT handler is installed and frame 0 is on disk, and then sends SIGINT. */
#include <errno.h>
#include <hdf5.h>
#include <poll.h>
#include <signal.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "testutil.h"
#include "h5read.h"
#include "output.h" /* white box: swOutput's write path */

/* A free rod of 4 elements falling under gravity. */
static swModel *falling_rod(double dt) {
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "filament";
  r.nelem = 4;
  r.start[0] = 0, r.start[1] = 0, r.start[2] = 1;
  r.direction[0] = 1, r.direction[1] = 0, r.direction[2] = 0;
  r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
  r.length = 1.0;
  r.radius_start = r.radius_end = 0.01;
  r.density = 1000;
  r.youngs = 1e6;
  r.poisson = 0.5;
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  sw_spec_set_dt(s, dt);
  swModel *m = sw_test_compile(s);
  sw_spec_free(s);
  return m;
}

/* An output file and the XDMF description beside it (PATH.xdmf: the
 * temporary names have no .h5 ending). */
static void remove_outputs(const char *path) {
  char xdmf[80];
  snprintf(xdmf, sizeof xdmf, "%s.xdmf", path);
  unlink(path);
  unlink(xdmf);
}

static void temp_path(char *path, size_t len) {
  snprintf(path, len, "/tmp/sinew_test_output_XXXXXX");
  int fd = mkstemp(path);
  assert_true(fd >= 0);
  close(fd);
}

/* ---- reading the file back ---- */

static int read_dims(hid_t file, const char *path, hsize_t *dims, hsize_t *maxdims) {
  hid_t dset = H5Dopen2(file, path, H5P_DEFAULT);
  if (dset < 0) fprintf(stderr, "# missing dataset %s\n", path);
  assert_true(dset >= 0);
  hid_t space = H5Dget_space(dset);
  int rank = H5Sget_simple_extent_ndims(space);
  assert_true(rank >= 1 && rank <= 4);
  H5Sget_simple_extent_dims(space, dims, maxdims);
  H5Sclose(space);
  H5Dclose(dset);
  return rank;
}

static double *read_doubles(hid_t file, const char *path) {
  hsize_t dims[4], maxdims[4];
  int rank = read_dims(file, path, dims, maxdims);
  size_t n = 1;
  for (int k = 0; k < rank; k++) n *= (size_t)dims[k];
  double *buf = malloc((n ? n : 1) * sizeof *buf);
  assert_non_null(buf);
  hid_t dset = H5Dopen2(file, path, H5P_DEFAULT);
  assert_true(H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
  H5Dclose(dset);
  return buf;
}

static void expect_string_attr(hid_t file, const char *obj_path, const char *name,
                               const char *expected) {
  char *value = read_string_attr(file, obj_path, name);
  if (strcmp(value, expected))
    fprintf(stderr, "# %s@%s = \"%.80s\", expected \"%.80s\"\n", obj_path, name, value, expected);
  assert_string_equal(value, expected);
  free(value);
}

/* ---- (a) the schema of a complete run ---- */

static void test_output_schema(void **state) {
  (void)state;
  const double dt = 1e-4, duration = 0.0105, every = 1e-3;
  /* 105 steps, a frame every 10: steps 0, 10, ..., 100, and the last, 105 */
  const long expected_frames = 12;
  char path[64];
  temp_path(path, sizeof path);

  swModel *m = falling_rod(dt);
  swData *d = sw_data_new(m);
  assert_non_null(d);
  sw_reset(m, d);

  /* A model source far beyond HDF5's 64 KiB limit for compact attributes. */
  size_t source_len = 200000;
  char *source = malloc(source_len + 1);
  assert_non_null(source);
  for (size_t i = 0; i < source_len; i++) source[i] = i % 64 == 63 ? '\n' : (char)('a' + i % 26);
  source[source_len] = '\0';
  const char *sha = "0b3c6f6c2e1f9d6a3e7b9c1d2f4a5b6c7d8e9f00112233445566778899aabbcc";
  swOutputOptions opt = {.model_source = source, .model_sha256 = sha, .params = "strength=1;gain=2", .duration = duration, .velocity = 1, .directors = 1};
  char err[256] = "";
  swOutput *out = sw_output_open(path, m, &opt, err, sizeof err);
  if (!out) fprintf(stderr, "# %s\n", err);
  assert_non_null(out);

  swRunOptions ro = {.duration = duration, .every = every, .quiet = 1};
  assert_int_equal(sw_run(m, d, out, &ro), SW_OK);
  fprintf(stderr, "# %s: %ld frames written, t = %.9g s after %ld steps\n", __func__,
          sw_output_frames(out), d->time, d->step);
  assert_int_equal(sw_output_frames(out), expected_frames);
  SW_EXPECT_ABS("final time (s)", d->time, duration, 1e-12);
  double energy[3];
  sw_energy(m, d, energy);
  assert_int_equal(sw_output_close(out, "complete"), SW_OK);

  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);

  /* shapes: [F], [F, n+1, 3], [F, n, 3, 3], [F, 3]; first dimension unlimited */
  static const struct {
    const char *path;
    int rank;
    hsize_t frame_dims[3];
    const char *units;
  } expected[] = {
    {"/time", 1, {0}, "s"},
    {"/rods/filament/position", 3, {5, 3}, "m"},
    {"/rods/filament/velocity", 3, {5, 3}, "m/s"},
    {"/rods/filament/directors", 4, {4, 3, 3}, "-"},
    {"/diagnostics/energy", 2, {3}, "J"},
  };
  for (size_t i = 0; i < sizeof expected / sizeof expected[0]; i++) {
    hsize_t dims[4], maxdims[4];
    int rank = read_dims(file, expected[i].path, dims, maxdims);
    fprintf(stderr, "# %s: %s rank %d, dims [%llu", __func__, expected[i].path, rank,
            (unsigned long long)dims[0]);
    for (int k = 1; k < rank; k++) fprintf(stderr, ", %llu", (unsigned long long)dims[k]);
    fprintf(stderr, "]\n");
    assert_int_equal(rank, expected[i].rank);
    assert_int_equal(dims[0], expected_frames);
    assert_true(maxdims[0] == H5S_UNLIMITED);
    for (int k = 1; k < rank; k++) assert_int_equal(dims[k], expected[i].frame_dims[k - 1]);
    expect_string_attr(file, expected[i].path, "units", expected[i].units);
  }

  /* columns of the energy */
  hid_t attr = H5Aopen_by_name(file, "/diagnostics/energy", "columns", H5P_DEFAULT, H5P_DEFAULT);
  assert_true(attr >= 0);
  hid_t space = H5Aget_space(attr);
  hsize_t ncol = 0;
  assert_int_equal(H5Sget_simple_extent_ndims(space), 1);
  H5Sget_simple_extent_dims(space, &ncol, NULL);
  assert_int_equal(ncol, 3);
  char *columns[3] = {NULL, NULL, NULL};
  hid_t type = H5Aget_type(attr), mem = H5Tget_native_type(type, H5T_DIR_ASCEND);
  assert_true(H5Tis_variable_str(type) > 0);
  assert_true(H5Aread(attr, mem, columns) >= 0);
  fprintf(stderr, "# %s: energy columns = %s, %s, %s\n", __func__, columns[0], columns[1],
          columns[2]);
  assert_string_equal(columns[0], "kinetic");
  assert_string_equal(columns[1], "elastic");
  assert_string_equal(columns[2], "work_done");
  for (int k = 0; k < 3; k++) H5free_memory(columns[k]);
  H5Tclose(mem);
  H5Tclose(type);
  H5Sclose(space);
  H5Aclose(attr);

  /* frame times: multiples of 10 steps, then the last step */
  double *time = read_doubles(file, "/time");
  for (long f = 0; f < expected_frames; f++) {
    double t = f < expected_frames - 1 ? (double)f * 10 * dt : duration;
    assert_true(fabs(time[f] - t) <= 1e-12);
  }
  SW_EXPECT_ABS("last frame time (s)", time[expected_frames - 1], duration, 1e-12);
  free(time);

  /* values: frame 0 is the initial state, the last frame the final state */
  double *position = read_doubles(file, "/rods/filament/position");
  double *velocity = read_doubles(file, "/rods/filament/velocity");
  double *directors = read_doubles(file, "/rods/filament/directors");
  double *energies = read_doubles(file, "/diagnostics/energy");
  double max_diff = 0;
  const double *last_x = position + (expected_frames - 1) * 15;
  const double *last_v = velocity + (expected_frames - 1) * 15;
  const double *last_Q = directors + (expected_frames - 1) * 36;
  /* the file holds rows per node (3) and per element (9); the state is planar */
  for (int i = 0; i < 15; i++) {
    const int node = m->node_adr[0] + i / 3, k = i % 3;
    max_diff = fmax(max_diff, fabs(position[i] - SW_AT(m, m->x0, node, k)));
    max_diff = fmax(max_diff, fabs(last_x[i] - SW_AT(m, d->x, node, k)));
    max_diff = fmax(max_diff, fabs(last_v[i] - SW_AT(m, d->v, node, k)));
  }
  for (int i = 0; i < 36; i++) {
    const int e = m->elem_adr[0] + i / 9, k = i % 9;
    max_diff = fmax(max_diff, fabs(directors[i] - SW_AT(m, m->Q0, e, k)));
    max_diff = fmax(max_diff, fabs(last_Q[i] - SW_AT(m, d->Q, e, k)));
  }
  for (int k = 0; k < 3; k++)
    max_diff = fmax(max_diff, fabs(energies[(expected_frames - 1) * 3 + k] - energy[k]));
  fprintf(stderr, "# %s: max |file - state| over first/last frames = %.3g\n", __func__, max_diff);
  assert_true(max_diff == 0);
  fprintf(stderr, "# %s: node 0 fell %.9g m in %.4g s\n", __func__, position[2] - last_x[2],
          duration);
  free(position);
  free(velocity);
  free(directors);
  free(energies);

  /* how the file was made */
  expect_string_attr(file, "/", "sinew_version", SW_VERSION);
  expect_string_attr(file, "/", "model_sha256", sha);
  expect_string_attr(file, "/", "model_source", source);
  expect_string_attr(file, "/", "params", "strength=1;gain=2");
  expect_string_attr(file, "/", "integrator", "position-verlet");
  expect_string_attr(file, "/", "status", "complete");
  assert_true(read_double_attr(file, "dt") == dt);
  assert_true(read_double_attr(file, "duration") == duration);
  assert_true(read_double_attr(file, "n_rods") == 1);
  fprintf(stderr, "# %s: root attributes checked, model_source of %zu bytes round-tripped\n",
          __func__, source_len);

  H5Fclose(file);
  free(source);
  remove_outputs(path);
  sw_data_free(d);
  sw_model_free(m);
}

/* every = 0 writes every step; without output the run still runs. */
static void test_frame_schedule(void **state) {
  (void)state;
  char path[64];
  temp_path(path, sizeof path);
  swModel *m = falling_rod(1e-4);
  swData *d = sw_data_new(m);
  sw_reset(m, d);
  swOutputOptions opt = {.duration = 1e-3};
  char err[256] = "";
  swOutput *out = sw_output_open(path, m, &opt, err, sizeof err);
  assert_non_null(out);
  swRunOptions ro = {.duration = 1e-3, .quiet = 1};
  assert_int_equal(sw_run(m, d, out, &ro), SW_OK);
  fprintf(stderr, "# %s: every = 0: %ld frames for 10 steps\n", __func__, sw_output_frames(out));
  assert_int_equal(sw_output_frames(out), 11);
  assert_int_equal(sw_output_close(out, NULL), SW_OK);

  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  assert_true(H5Lexists(file, "/rods/filament/velocity", H5P_DEFAULT) == 0);
  assert_true(H5Lexists(file, "/rods/filament/directors", H5P_DEFAULT) == 0);
  expect_string_attr(file, "/", "status", "complete");
  expect_string_attr(file, "/", "model_sha256", "");
  H5Fclose(file);
  remove_outputs(path);

  sw_reset(m, d);
  ro.duration = 2e-3;
  assert_int_equal(sw_run(m, d, NULL, &ro), SW_OK);
  SW_EXPECT_ABS("time after a run without output (s)", d->time, 2e-3, 1e-12);
  sw_data_free(d);
  sw_model_free(m);
}

/* ---- (b) Ctrl-C ---- */

static void run_child(const char *path, int log_fd) {
  alarm(120); /* never outlive a broken parent */
  FILE *log_file = fdopen(log_fd, "w");
  if (!log_file) _exit(90);
  swModel *m = falling_rod(1e-4);
  swData *d = sw_data_new(m);
  sw_reset(m, d);
  swOutputOptions opt = {.model_source = "rod filament {}", .model_sha256 = "00", .params = "", .duration = 1e4, .velocity = 1};
  char err[256];
  swOutput *out = sw_output_open(path, m, &opt, err, sizeof err);
  if (!out) {
    fprintf(log_file, "child: %s\n", err);
    fclose(log_file);
    _exit(91);
  }
  swRunOptions ro = {.duration = 1e4, .every = 1e-2, .log = log_file};
  int rc = sw_run(m, d, out, &ro);
  char status[128];
  snprintf(status, sizeof status, "interrupted at t = %.9g s", d->time);
  int close_rc = sw_output_close(out, rc == SW_EINTERRUPT ? status : "complete");
  fclose(log_file);
  _exit(close_rc != SW_OK ? close_rc : rc);
}

/* Read what the child logs until `until` appears, EOF, or the deadline. */
static void read_log(int fd, char *text, size_t len, const char *until, double seconds) {
  size_t used = strlen(text);
  for (int waited_ms = 0; waited_ms < seconds * 1000;) {
    if (until && strstr(text, until)) return;
    struct pollfd pfd = {fd, POLLIN, 0};
    int ready = poll(&pfd, 1, 100);
    if (ready == 0) {
      waited_ms += 100;
      continue;
    }
    if (ready < 0 && errno == EINTR) continue;
    assert_true(ready > 0);
    char chunk[256];
    ssize_t got = read(fd, chunk, sizeof chunk);
    if (got <= 0) return; /* EOF: the child has exited */
    size_t take = (size_t)got < len - 1 - used ? (size_t)got : len - 1 - used;
    memcpy(text + used, chunk, take);
    used += take;
    text[used] = '\0';
  }
}

static void test_sigint_leaves_valid_file(void **state) {
  (void)state;
  char path[64];
  temp_path(path, sizeof path);
  int pipefd[2];
  assert_int_equal(pipe(pipefd), 0);
  fflush(stderr);
  pid_t child = fork();
  assert_true(child >= 0);
  if (child == 0) {
    close(pipefd[0]);
    run_child(path, pipefd[1]);
  }
  close(pipefd[1]);

  /* The first progress line comes after 1 s of running: handler in place,
   * frame 0 and about a hundred more on disk. */
  static char child_log[16384];
  child_log[0] = '\0';
  read_log(pipefd[0], child_log, sizeof child_log, "\r", 60);
  int saw_progress = strchr(child_log, '\r') != NULL;
  if (!saw_progress) {
    fprintf(stderr, "# %s: no progress line from the child; log: %s\n", __func__, child_log);
    kill(child, SIGKILL);
  } else {
    kill(child, SIGINT);
  }
  read_log(pipefd[0], child_log, sizeof child_log, NULL, 60);
  close(pipefd[0]);
  int wstatus = 0;
  assert_int_equal(waitpid(child, &wstatus, 0), child);
  assert_true(saw_progress);
  const char *msg = strstr(child_log, "sinew: interrupted at t = ");
  fprintf(stderr, "# %s: child %s %d; its last message: %s", __func__,
          WIFEXITED(wstatus) ? "exited with" : "killed by signal",
          WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : WTERMSIG(wstatus), msg ? msg : "(none)\n");
  assert_true(WIFEXITED(wstatus));
  assert_int_equal(WEXITSTATUS(wstatus), 130);
  assert_non_null(msg);
  assert_non_null(strstr(msg, "frames written to output"));
  double t_stop = atof(msg + strlen("sinew: interrupted at t = "));
  long frames_logged = atol(strchr(msg, ';') + 1);

  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  hsize_t dims[4], maxdims[4];
  read_dims(file, "/time", dims, maxdims);
  long frames = (long)dims[0];
  double *time = read_doubles(file, "/time");
  char *status = read_string_attr(file, "/", "status");
  fprintf(stderr, "# %s: file holds %ld frames (log says %ld), last t = %.9g s, status \"%s\"\n",
          __func__, frames, frames_logged, time[frames - 1], status);
  assert_true(frames >= 1);
  assert_int_equal(frames, frames_logged);
  assert_non_null(strstr(status, "interrupted"));
  /* the last frame is the state the run stopped in */
  SW_EXPECT_REL("last frame time vs. interruption time", time[frames - 1], t_stop, 1e-8);
  read_dims(file, "/rods/filament/position", dims, maxdims);
  assert_int_equal((long)dims[0], frames);
  free(status);
  free(time);
  H5Fclose(file);
  remove_outputs(path);
}

/* ---- an unstable run keeps the frames written so far ---- */

static void test_unstable_run_stops(void **state) {
  (void)state;
  char path[64];
  temp_path(path, sizeof path);
  swModel *m = falling_rod(1e-4);
  double dt = 50 * sw_stable_dt(m); /* far beyond the stable step */
  sw_model_free(m);
  m = falling_rod(dt);
  swData *d = sw_data_new(m);
  sw_reset(m, d);
  /* kink the middle node so the instability has a seed */
  SW_AT(m, d->x, m->node_adr[0] + 2, 2) += 1e-3;
  swOutputOptions opt = {.duration = 2000 * dt};
  char err[256] = "";
  swOutput *out = sw_output_open(path, m, &opt, err, sizeof err);
  assert_non_null(out);
  FILE *log_file = tmpfile();
  assert_non_null(log_file);
  swRunOptions ro = {.duration = 2000 * dt, .quiet = 1, .log = log_file};
  int rc = sw_run(m, d, out, &ro);
  char text[1024] = "";
  rewind(log_file);
  size_t got = fread(text, 1, sizeof text - 1, log_file);
  text[got] = '\0';
  fclose(log_file);
  long frames = sw_output_frames(out);
  fprintf(stderr, "# %s: dt = %.3g s: rc %d after %ld steps, %ld frames; log: %s", __func__, dt,
          rc, d->step, frames, text);
  assert_int_equal(rc, SW_EUNSTABLE);
  assert_true(strncmp(text, "sinew: ", 7) == 0);
  assert_non_null(strstr(text, d->error));
  char status[1100];   /* "unstable: " and d->error */
  snprintf(status, sizeof status, "unstable: %s", d->error);
  assert_int_equal(sw_output_close(out, status), SW_OK);

  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  double *time = read_doubles(file, "/time");
  hsize_t dims[4], maxdims[4];
  read_dims(file, "/time", dims, maxdims);
  assert_int_equal((long)dims[0], frames);
  /* every frame written is finite: nothing after the failing step */
  double *position = read_doubles(file, "/rods/filament/position");
  for (long i = 0; i < frames * 15; i++) assert_true(isfinite(position[i]));
  char *st = read_string_attr(file, "/", "status");
  assert_true(strncmp(st, "unstable: ", 10) == 0);
  free(st);
  free(position);
  free(time);
  H5Fclose(file);
  remove_outputs(path);
  sw_data_free(d);
  sw_model_free(m);
}

/* ---- (c) time arguments ---- */

static void test_parse_time(void **state) {
  (void)state;
  static const struct {
    const char *text;
    double seconds;
  } good[] = {
    {"50ns", 50e-9}, {"0.5 s", 0.5}, {"2ms", 2e-3}, {"1e-3", 1e-3}, {"10us", 10e-6},
    {"2 min", 120}, {" 3s ", 3}, {"0", 0}, {"1.5e2 ms", 0.15}, {"7\xc2\xb5s", 7e-6},
  };
  static const char *const bad[] = {
    "5 kg", "-1s", "abc", "", "   ", "inf", "nan", "1e999", "5 s s", "s", "5 m", "0x10",
    "2ms3", "5 sec", "+-1", "1,5 s",
  };
  for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
    double t = -1;
    int rc = sw_parse_time(good[i].text, &t);
    fprintf(stderr, "# %s: \"%s\" -> rc %d, %.9g s\n", __func__, good[i].text, rc, t);
    assert_int_equal(rc, 0);
    assert_true(fabs(t - good[i].seconds) <= 1e-15 * fmax(1, good[i].seconds));
  }
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    double t = -1;
    int rc = sw_parse_time(bad[i], &t);
    fprintf(stderr, "# %s: \"%s\" -> rc %d (rejected)\n", __func__, bad[i], rc);
    assert_int_not_equal(rc, 0);
    assert_true(t == -1); /* untouched on error */
  }
  double t;
  assert_int_not_equal(sw_parse_time(NULL, &t), 0);
}

/* ---- (d) a file that cannot be created ---- */

static void test_unwritable_path(void **state) {
  (void)state;
  swModel *m = falling_rod(1e-4);
  swOutputOptions opt = {.duration = 1};
  char err[256] = "";
  const char *path = "/nonexistent-dir/x.h5";
  swOutput *out = sw_output_open(path, m, &opt, err, sizeof err);
  fprintf(stderr, "# %s: error = \"%s\"\n", __func__, err);
  assert_null(out);
  assert_non_null(strstr(err, path));
  assert_non_null(strstr(err, "No such file or directory"));
  assert_string_equal(sw_output_error(), err);
  sw_model_free(m);
}

/* ---- (e) the XDMF description ---- */

static char *read_text(const char *path) {
  FILE *f = fopen(path, "rb");
  assert_non_null(f);
  fseek(f, 0, SEEK_END);
  long len = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *text = malloc((size_t)len + 1);
  assert_non_null(text);
  assert_int_equal(fread(text, 1, (size_t)len, f), (size_t)len);
  text[len] = '\0';
  fclose(f);
  return text;
}

static int count_of(const char *text, const char *what) {
  int n = 0;
  for (const char *p = strstr(text, what); p; p = strstr(p + 1, what)) n++;
  return n;
}

/* A rod whose name has every character XML gives meaning to, tapered from
 * 1 cm to 3 cm over 6 elements: the description carries the name escaped
 * (the raw name nowhere), lists each frame of the run once, and
 * /rods/NAME/node_radius is the mean of the elements on either side of each
 * node (elements taper linearly between the end elements' centres, model.c:
 * r_i = r0 + (r1 - r0) i / (n - 1), so node k has r0 + (r1 - r0)
 * clamp((k - 1/2) / (n - 1), 0, 1)).  A name with a control character,
 * which XML cannot hold, is refused with a message. */
static void test_xdmf_names_and_radius(void **state) {
  (void)state;
  const char *name = "a<b&\"c'>d", *escaped = "a&lt;b&amp;&quot;c&apos;&gt;d";
  const int n = 6;
  const double r0 = 0.01, r1 = 0.03;
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = name;
  r.nelem = n;
  r.direction[0] = 1, r.direction[1] = 0, r.direction[2] = 0;
  r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
  r.length = 1.0;
  r.radius_start = r0, r.radius_end = r1;
  r.density = 1000, r.youngs = 1e6, r.poisson = 0.5;
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  sw_spec_set_dt(s, 1e-4);
  swModel *m = sw_test_compile(s);
  sw_spec_free(s);
  char path[64], xdmf[80];
  temp_path(path, sizeof path);
  snprintf(xdmf, sizeof xdmf, "%s.xdmf", path);
  swData *d = sw_data_new(m);
  sw_reset(m, d);
  swOutputOptions opt = {.duration = 1e-3};
  char err[256] = "";
  swOutput *out = sw_output_open(path, m, &opt, err, sizeof err);
  assert_non_null(out);
  swRunOptions ro = {.duration = 1e-3, .every = 2e-4, .quiet = 1};
  assert_int_equal(sw_run(m, d, out, &ro), SW_OK);
  long frames = sw_output_frames(out);
  assert_int_equal(sw_output_close(out, NULL), SW_OK);

  char *text = read_text(xdmf);
  char want[160];
  snprintf(want, sizeof want, "<Grid Name=\"%s\" GridType=\"Uniform\">", escaped);
  int grids = count_of(text, want), times = count_of(text, "<Time Value=");
  snprintf(want, sizeof want, ":/rods/%s/position</DataItem>", escaped);
  int positions = count_of(text, want);
  /* the rod's one position item, the domain's second DataItem (after its
   * node_radius), which every frame's geometry refers to */
  int refs = count_of(text, "<DataItem Reference=\"/Xdmf/Domain/DataItem[2]\"/>");
  fprintf(stderr, "# %s: %ld frames; the description has %d grids named %s, %d times, %d "
          "position items and %d references to it; the raw name %d times\n", __func__, frames,
          grids, escaped, times, positions, refs, count_of(text, name));
  assert_int_equal(frames, 6);
  assert_int_equal(grids, frames);
  assert_int_equal(times, frames);
  assert_int_equal(positions, 1);
  assert_int_equal(refs, frames);
  assert_int_equal(count_of(text, name), 0);
  free(text);

  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  snprintf(want, sizeof want, "/rods/%s/node_radius", name);
  double *node = read_doubles(file, want);
  double worst = 0;
  for (int k = 0; k <= n; k++) {
    double f = ((double)k - 0.5) / (n - 1);
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    double e = fabs(node[k] - (r0 + (r1 - r0) * f));
    if (e > worst) worst = e;
  }
  fprintf(stderr, "# %s: node radii against the closed form: largest difference %.3g m\n",
          __func__, worst);
  assert_true(worst <= 1e-15);
  expect_string_attr(file, want, "units", "m");
  free(node);
  H5Fclose(file);
  remove_outputs(path);

  /* a control character */
  m->rod_name[0][1] = '\x01';
  out = sw_output_open(path, m, &opt, err, sizeof err);
  fprintf(stderr, "# %s: error = \"%s\"\n", __func__, err);
  assert_null(out);
  assert_non_null(strstr(err, "control character"));
  remove_outputs(path);
  sw_data_free(d);
  sw_model_free(m);
}

/* ---- (f) chunks written as stored, or frames by a selection ---- */

/* Runs the falling rod for 151 frames (two whole chunks of 64 and a partial
 * one) into path, by either write path; returns the chunk's frames. */
static hsize_t run_chunked(const char *path, int direct) {
  swModel *m = falling_rod(1e-4);
  swData *d = sw_data_new(m);
  sw_reset(m, d);
  swOutputOptions opt = {.duration = 15e-3, .velocity = 1, .directors = 1};
  char err[256] = "";
  swOutput *out = sw_output_open(path, m, &opt, err, sizeof err);
  assert_non_null(out);
  hsize_t chunk = (hsize_t)out->chunk_frames;
  if (!direct) out->direct = 0;
  swRunOptions ro = {.duration = 15e-3, .every = 1e-4, .quiet = 1};
  assert_int_equal(sw_run(m, d, out, &ro), SW_OK);
  assert_int_equal(sw_output_frames(out), 151);
  assert_int_equal(sw_output_close(out, NULL), SW_OK);
  sw_data_free(d);
  sw_model_free(m);
  return chunk;
}

static void test_chunk_paths(void **state) {
  (void)state;
  char direct[64], selected[64];
  temp_path(direct, sizeof direct);
  temp_path(selected, sizeof selected);
  hsize_t chunk = run_chunked(direct, 1);
  assert_int_equal(run_chunked(selected, 0), chunk);
  hid_t a = H5Fopen(direct, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t b = H5Fopen(selected, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(a >= 0 && b >= 0);
  const char *paths[] = {"/time", "/rods/filament/position", "/rods/filament/velocity",
                         "/rods/filament/directors", "/diagnostics/energy"};
  for (size_t p = 0; p < sizeof paths / sizeof paths[0]; p++) {
    hsize_t da[4], db[4], maxdims[4], stored[4];
    int rank = read_dims(a, paths[p], da, maxdims);
    assert_int_equal(read_dims(b, paths[p], db, maxdims), rank);
    size_t n = 1;
    for (int k = 0; k < rank; k++) {
      assert_int_equal(da[k], db[k]);
      n *= (size_t)da[k];
    }
    hid_t dset = H5Dopen2(a, paths[p], H5P_DEFAULT), dcpl = H5Dget_create_plist(dset);
    assert_int_equal(H5Pget_chunk(dcpl, 4, stored), rank);
    H5Pclose(dcpl);
    H5Dclose(dset);
    double *va = read_doubles(a, paths[p]), *vb = read_doubles(b, paths[p]);
    size_t differ = 0;
    for (size_t i = 0; i < n; i++) differ += memcmp(&va[i], &vb[i], sizeof va[i]) != 0;
    fprintf(stderr, "# %s: %s: %llu frames in chunks of %llu; %zu of %zu values differ between "
            "the two paths\n", __func__, paths[p], (unsigned long long)da[0],
            (unsigned long long)stored[0], differ, n);
    assert_int_equal(da[0], 151);
    assert_int_equal(stored[0], chunk);
    assert_int_equal(differ, 0);
    free(va);
    free(vb);
  }
  assert_int_equal(chunk, 64);
  H5Fclose(a);
  H5Fclose(b);
  remove_outputs(direct);
  remove_outputs(selected);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_output_schema),
    cmocka_unit_test(test_frame_schedule),
    cmocka_unit_test(test_sigint_leaves_valid_file),
    cmocka_unit_test(test_unstable_run_stops),
    cmocka_unit_test(test_parse_time),
    cmocka_unit_test(test_unwritable_path),
    cmocka_unit_test(test_xdmf_names_and_radius),
    cmocka_unit_test(test_chunk_paths),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
