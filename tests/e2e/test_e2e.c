/* test_e2e.c — end-to-end: models written in sinew, compiled by sinewc into
 * simulators, run, and their HDF5 output checked against closed forms.
 *
 * The runtime's validation scenes (tests/runtime/test_statics.c and
 * test_dynamics.c) are repeated here as .sinew models (tests/e2e/), so the
 * whole chain -- parser, units, checker, generated C, simulator command line,
 * output -- is held to the same physics.  The pendulum example (a rod on a
 * hinge) is checked against the physical pendulum's period.  Each test
 * prints the figure it measured.  The compiler used is $SINEWC (the Makefile
 * passes the sanitizer build) and simulators are built in a temporary
 * directory removed at the end.
 */
#include "e2e.h"

static void test_cantilever_model(void **state) {
  (void)state;
  const char *sim = compile("tests/e2e/cantilever.sinew", "cantilever");
  char out[512];
  snprintf(out, sizeof out, "%s/cantilever.h5", tmpdir);
  simulate(sim, out, NULL);
  size_t n;
  double *x = read_dataset(out, "/rods/beam/position", &n);
  const int nodes = 51;
  double tip_z = x[n - 3 * nodes + 3 * (nodes - 1) + 2];
  free(x);
  const double L = 3, r = 0.25, E = 1e6, G = 1e4, F = 0.15;
  double A = M_PI * r * r, I = A * r * r / 4;
  double ref = F * L * L * L / (3 * E * I) + F * L / (4.0 / 3.0 * G * A);
  EXPECT_REL("tip deflection (m)", -tip_z, ref, 1e-2);
}

static void test_stretch_model(void **state) {
  (void)state;
  const char *sim = compile("tests/e2e/stretch.sinew", "stretch");
  char out[512];
  snprintf(out, sizeof out, "%s/stretch.h5", tmpdir);
  simulate(sim, out, NULL);
  size_t n;
  double *x = read_dataset(out, "/rods/bar/position", &n);
  double tip_z = x[n - 1];
  free(x);
  const double L = 0.5, r = 0.01, E = 1e6;
  double A = M_PI * r * r, F = 1e-5 * E * A;
  EXPECT_REL("extension (m)", tip_z - L, F * L / (E * A), 1e-3);
}

/* Mean frequency between the first and last upward zero crossing after t0. */
static double crossing_frequency(const double *t, const double *y, size_t stride, size_t frames,
                                 double t0, int want) {
  double first = 0, last = 0;
  int nc = 0;
  for (size_t k = 1; k < frames && nc < want; k++) {
    double y0 = y[(k - 1) * stride], y1 = y[k * stride];
    if (t[k - 1] < t0 || !(y0 < 0 && y1 >= 0)) continue;
    double tc = t[k - 1] + (t[k] - t[k - 1]) * (-y0) / (y1 - y0);
    if (nc == 0) first = tc;
    last = tc;
    nc++;
  }
  assert_int_equal(nc, want);
  return (nc - 1) / (last - first);
}

static void test_vibration_model(void **state) {
  (void)state;
  const char *sim = compile("tests/e2e/vibration.sinew", "vibration");
  char out[512];
  snprintf(out, sizeof out, "%s/vibration.h5", tmpdir);
  simulate(sim, out, NULL);
  size_t nt, nx;
  double *t = read_dataset(out, "/time", &nt);
  double *x = read_dataset(out, "/rods/reed/position", &nx);
  const size_t nodes = 41, stride = 3 * nodes;
  assert_int_equal(nx, nt * stride);
  double f = crossing_frequency(t, x + 3 * (nodes - 1) + 1, stride, nt, 3.01, 5);
  free(t);
  free(x);
  const double L = 0.2, r = 0.005, E = 1e6, rho = 1000, beta1 = 1.8751040687119611;
  double ref = beta1 * beta1 / (2 * M_PI * L * L) * sqrt(E * r * r / 4 / rho);
  EXPECT_REL("first eigenfrequency (Hz)", f, ref, 1e-2);
}

/* A rod on a hinge swinging under gravity: the small-amplitude period of a
 * physical pendulum pivoting at its end is 2 pi sqrt(2 L / (3 g)); at an
 * amplitude theta0 the period grows by the factor 1 + theta0^2/16 + ... */
static void test_pendulum_example(void **state) {
  (void)state;
  const char *sim = compile("examples/pendulum.sinew", "pendulum");
  char out[512];
  snprintf(out, sizeof out, "%s/pendulum.h5", tmpdir);
  simulate(sim, out, NULL);
  size_t nt, na;
  double *t = read_dataset(out, "/time", &nt);
  double *angle = read_dataset(out, "/joints/pivot/angle", &na);
  assert_int_equal(na, nt);
  /* the hinge angle swings about the vertical: find its zero crossings */
  const double L = 0.5, g = 9.81, theta0 = 10 * M_PI / 180;
  double amp = 0;
  for (size_t k = 0; k < na; k++) amp = fmax(amp, fabs(angle[k]));
  double mean = 0;
  for (size_t k = 0; k < na; k++) mean += angle[k] / (double)na;
  for (size_t k = 0; k < na; k++) angle[k] -= mean;
  double f = crossing_frequency(t, angle, 1, nt, 0, 3);
  free(t);
  free(angle);
  fprintf(stderr, "# %s: hinge angle swings %.4f rad about %.4f rad\n", __func__, amp, mean);
  double T = 2 * M_PI * sqrt(2 * L / (3 * g)) * (1 + theta0 * theta0 / 16);
  EXPECT_REL("pendulum period (s)", 1 / f, T, 5e-3);
}

/* --set changes a param at run time, and the output records it, the model
 * source and its sha256. */
static void test_set_param_and_provenance(void **state) {
  (void)state;
  const char *sim = compile("examples/cantilever.sinew", "cantilever_example");
  char out[512];
  snprintf(out, sizeof out, "%s/example.h5", tmpdir);
  simulate(sim, out, "--set", "load=250 mN", "--duration", "10 ms", NULL);
  char *params = read_root_attr(out, "params");
  fprintf(stderr, "# %s: params attribute \"%s\"\n", __func__, params);
  assert_non_null(strstr(params, "load=0.25"));
  free(params);
  char *src = read_root_attr(out, "model_source");
  char *sha = read_root_attr(out, "model_sha256");
  FILE *f = fopen("examples/cantilever.sinew", "rb");
  assert_non_null(f);
  char text[8192];
  size_t len = fread(text, 1, sizeof text - 1, f);
  fclose(f);
  text[len] = 0;
  assert_string_equal(src, text);
  /* the digest of the same bytes by the system's sha256sum */
  FILE *p = popen("sha256sum examples/cantilever.sinew", "r");
  assert_non_null(p);
  char digest[65] = "";
  assert_int_equal(fscanf(p, "%64s", digest), 1);
  pclose(p);
  fprintf(stderr, "# %s: model_sha256 %s, sha256sum %s\n", __func__, sha, digest);
  assert_string_equal(sha, digest);
  free(src);
  free(sha);
}

int main(void) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_cantilever_model),
    cmocka_unit_test(test_stretch_model),
    cmocka_unit_test(test_vibration_model),
    cmocka_unit_test(test_pendulum_example),
    cmocka_unit_test(test_set_param_and_provenance),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
