/* e2e.h — helpers shared by the end-to-end tests (test_e2e.c, test_elbow.c):
 * run a command, compile a model with sinewc into a temporary directory, run
 * the simulator, read its HDF5 output.  Each test binary includes it once. */
#ifndef SW_E2E_H
#define SW_E2E_H
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <spawn.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>
#include <hdf5.h>

#include "h5read.h"

extern char **environ;

static char tmpdir[] = "/tmp/sinew-e2e-XXXXXX";

/* Run argv; returns the exit code (or 128 + signal). */
static inline int run(const char *const *argv) {
  pid_t pid;
  if (posix_spawnp(&pid, argv[0], NULL, NULL, (char *const *)argv, environ) != 0) return -1;
  int status;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

static inline const char *sinewc(void) {
  const char *s = getenv("SINEWC");
  return s && *s ? s : "bin/sinewc";
}

/* Compile model into tmpdir/name with `compiler`; returns the simulator's path. */
static inline const char *compile_with(const char *compiler, const char *model, const char *name) {
  static char sim[512];
  snprintf(sim, sizeof sim, "%s/%s", tmpdir, name);
  const char *argv[] = {compiler, model, "-o", sim, NULL};
  int rc = run(argv);
  if (rc != 0) fprintf(stderr, "# sinewc %s exited with %d\n", model, rc);
  assert_int_equal(rc, 0);
  return sim;
}

static inline const char *compile(const char *model, const char *name) {
  return compile_with(sinewc(), model, name);
}

/* Run a simulator with extra arguments (NULL-terminated) writing out.h5. */
static inline void simulate(const char *sim, const char *out, ...) {
  const char *argv[32];
  int n = 0;
  argv[n++] = sim;
  argv[n++] = "--quiet";
  argv[n++] = "--out";
  argv[n++] = out;
  va_list ap;
  va_start(ap, out);
  const char *a;
  while ((a = va_arg(ap, const char *)) && n < 31) argv[n++] = a;
  va_end(ap);
  argv[n] = NULL;
  assert_int_equal(run(argv), 0);
}

/* A double attribute of object `obj` ("/" for the root) of the file at `path`. */
static inline double file_attr(const char *path, const char *obj, const char *name) {
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(f >= 0);
  double v = read_double_attr_of(f, obj, name);
  H5Fclose(f);
  return v;
}

/* Read a whole double dataset; *count = number of doubles. */
static inline double *read_dataset(const char *file, const char *path, size_t *count) {
  hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(f >= 0);
  hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
  assert_true(d >= 0);
  hid_t sp = H5Dget_space(d);
  hssize_t n = H5Sget_simple_extent_npoints(sp);
  double *buf = malloc((size_t)n * sizeof *buf);
  assert_non_null(buf);
  assert_true(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
  H5Sclose(sp);
  H5Dclose(d);
  H5Fclose(f);
  *count = (size_t)n;
  return buf;
}

/* A string attribute of the root group (caller frees). */
static inline char *read_root_attr(const char *file, const char *name) {
  hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(f >= 0);
  char *s = read_string_attr(f, "/", name);
  H5Fclose(f);
  return s;
}

#define EXPECT_REL(what, got, want, tol)                                                     \
  do {                                                                                       \
    double g_ = (got), w_ = (want), e_ = fabs(g_ - w_) / fabs(w_);                           \
    fprintf(stderr, "# %s: %s = %.9g, reference %.9g, rel. error %.2e (tolerance %.0e)\n",  \
            __func__, what, g_, w_, e_, (double)(tol));                                      \
    assert_true(e_ <= (tol));                                                                \
  } while (0)

static inline int setup(void **state) {
  (void)state;
  return mkdtemp(tmpdir) ? 0 : -1;
}

static inline int teardown(void **state) {
  (void)state;
  const char *argv[] = {"rm", "-rf", tmpdir, NULL};
  return run(argv) == 0 ? 0 : -1;
}
#endif
