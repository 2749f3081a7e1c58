/* test_probe.c — probes (probe.c) and their output /probes/NAME (output.c).
 *
 * Closed forms: the centre of mass of two straight rods of different mass
 * is the mass-weighted mean of their midpoints (for lumped node masses as
 * for the continuum), a node probe is that node; rods set in uniform motion
 * have that velocity as centre-of-mass velocity and as mean velocity over
 * any window, exactly; under gravity alone X = X0 + g t^2 / 2, so the mean
 * velocity over a window w is g (t - w / 2), and g t / 2 while the run is
 * younger than w; over a long window the ring of samples wraps and the
 * interpolation between samples errs by exactly g Delta^2 / (8 w).  The HDF5 datasets /probes/NAME are [frames, 3] with the
 * units and kind attributes, and hold what sw_probe_measure gives. */
#include <hdf5.h>
#include <unistd.h>

#include "testutil.h"
#include "h5read.h"
#include "internal.h"

/* Rod 0 ("body"): 1 m along x from the origin, r = 0.02 m, rho = 1000.
 * Rod 1 ("tail"): 0.5 m along y from (0, 1, 0), r = 0.01 m, rho = 3000. */
static swSpec *two_rods(void) {
  swSpec *s = sw_spec_new();
  swRodDesc a, b;
  sw_rod_desc_init(&a);
  a.name = "body";
  a.nelem = 10;
  a.length = 1.0;
  a.radius_start = a.radius_end = 0.02;
  a.density = 1000;
  a.direction[0] = 1; a.direction[2] = 0;
  a.normal[0] = 0; a.normal[2] = 1;
  sw_spec_add_rod(s, &a);
  sw_rod_desc_init(&b);
  b.name = "tail";
  b.nelem = 7;
  b.length = 0.5;
  b.radius_start = b.radius_end = 0.01;
  b.density = 3000;
  b.start[1] = 1.0;
  b.direction[1] = 1; b.direction[2] = 0;
  b.normal[0] = 1; b.normal[2] = 0;
  sw_spec_add_rod(s, &b);
  return s;
}

static int add_probe(swSpec *s, const char *name, swProbeKind kind, int nrods, const int *rods,
                     double window) {
  swProbeDesc p;
  sw_probe_desc_init(&p);
  p.name = name;
  p.kind = kind;
  p.nrods = nrods;
  p.rods = rods;
  p.window = window;
  return sw_spec_add_probe(s, &p);
}

static double dist3(const double *a, const double *b) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

static void test_center_of_mass(void **state) {
  (void)state;
  swSpec *s = two_rods();
  const int tail[1] = {1};
  add_probe(s, "com", SW_PROBE_COM, 0, NULL, 0);
  add_probe(s, "tail_com", SW_PROBE_COM, 1, tail, 0);
  swProbeDesc tip;
  sw_probe_desc_init(&tip);
  tip.name = "tip";
  tip.kind = SW_PROBE_NODE;
  tip.rod = 1; /* node -1: the last */
  sw_spec_add_probe(s, &tip);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double m0 = 1000 * M_PI * 0.02 * 0.02 * 1.0, m1 = 3000 * M_PI * 0.01 * 0.01 * 0.5;
  const double ref[3] = {m0 * 0.5 / (m0 + m1), m1 * 1.25 / (m0 + m1), 0};
  const double ref_tail[3] = {0, 1.25, 0}, ref_tip[3] = {0, 1.5, 0};
  double X[3];
  sw_probe_measure(m, d, 0, X);
  fprintf(stderr, "# masses %.5g kg and %.5g kg; centre of mass (%.6g, %.6g, %.6g) m\n", m0, m1,
          X[0], X[1], X[2]);
  SW_EXPECT_ABS("|centre of mass of both rods - closed form|, m", dist3(X, ref), 0.0, 1e-14);
  sw_probe_measure(m, d, 1, X);
  SW_EXPECT_ABS("|centre of mass of the tail - its midpoint|, m", dist3(X, ref_tail), 0.0, 1e-14);
  sw_probe_measure(m, d, 2, X);
  SW_EXPECT_ABS("|tip probe - last node of the tail|, m", dist3(X, ref_tip), 0.0, 0.0);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Every node of every rod moving with V. */
static void set_uniform_motion(const swModel *m, swData *d, const double V[3]) {
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
      sw_set3(m, d->v, i, V);
}

static void test_uniform_motion(void **state) {
  (void)state;
  swSpec *s = two_rods();
  add_probe(s, "v", SW_PROBE_COM_VELOCITY, 0, NULL, 0);
  add_probe(s, "mean_window", SW_PROBE_MEAN_VELOCITY, 0, NULL, 0.05);
  add_probe(s, "mean_frame", SW_PROBE_MEAN_VELOCITY, 0, NULL, 0);
  add_probe(s, "mean_short", SW_PROBE_MEAN_VELOCITY, 0, NULL, 0.003); /* < frame interval */
  sw_spec_set_dt(s, 1e-5);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double V[3] = {0.3, -0.2, 0.7};
  set_uniform_motion(m, d, V);
  double worst = 0, out[3];
  for (int frame = 0; frame <= 20; frame++) {
    if (frame) sw_test_run_to(m, d, 0.01 * frame);
    for (int p = 0; p < 4; p++) {
      sw_probe_measure(m, d, p, out);
      worst = fmax(worst, dist3(out, V));
    }
  }
  /* exact but for round-off: positions of ~1 m summed over 2e4 steps of h v
   * carry ~1e-13 m, divided by the shortest window (3 ms) */
  SW_EXPECT_ABS("max |probe - V| over 21 frames, 4 velocity probes, m/s", worst, 0.0, 1e-10);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_mean_velocity_under_gravity(void **state) {
  (void)state;
  swSpec *s = two_rods();
  const double w = 0.1, g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  add_probe(s, "mean", SW_PROBE_MEAN_VELOCITY, 0, NULL, w);
  add_probe(s, "last_frame", SW_PROBE_MEAN_VELOCITY, 0, NULL, 0);
  sw_spec_set_dt(s, 1e-4);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  double worst = 0, worst_frame = 0, out[3];
  const double every = 0.01;
  for (int frame = 0; frame <= 40; frame++) {
    if (frame) sw_test_run_to(m, d, every * frame);
    const double t = d->time;
    sw_probe_measure(m, d, 0, out);
    /* g (t - w/2) over a full window, g t / 2 before; COM velocity (0) at t = 0 */
    const double ref = t >= w - 1e-9 ? g[2] * (t - w / 2) : g[2] * t / 2;
    worst = fmax(worst, fabs(out[2] - ref) + fabs(out[0]) + fabs(out[1]));
    sw_probe_measure(m, d, 1, out);
    const double ref_frame = frame ? g[2] * (t - every / 2) : 0.0;
    worst_frame = fmax(worst_frame, fabs(out[2] - ref_frame));
  }
  fprintf(stderr, "# free fall, window %.2f s, frames every %.2f s, to t = %.2f s\n", w, every,
          d->time);
  SW_EXPECT_ABS("max |mean velocity - g (t - w/2)|, m/s", worst, 0.0, 1e-9);
  SW_EXPECT_ABS("max |mean velocity since last frame - g (t - dt_frame/2)|, m/s", worst_frame, 0.0,
                1e-9);
  /* sw_reset forgets the samples: the first frame after it gives V(0) = 0 */
  sw_reset(m, d);
  sw_probe_measure(m, d, 0, out);
  SW_EXPECT_ABS("mean velocity right after sw_reset, m/s", dist3(out, (double[3]){0, 0, 0}), 0.0,
                0.0);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* A long window over many frames: the ring (SW_PROBE_RING samples) keeps
 * one every w / (SW_PROBE_RING - 1) or more, here every second frame
 * (Delta = 2 ms), and wraps; X(t - w) is interpolated linearly between the
 * samples around it, which on the free-fall parabola errs by g s (Delta - s)
 * / 2 at a distance s from a sample: g Delta^2 / 8 when t - w falls midway
 * (every other frame), 0 when it falls on a sample.  So the largest error
 * of the mean velocity is exactly g Delta^2 / (8 w). */
static void test_mean_velocity_ring(void **state) {
  (void)state;
  swSpec *s = two_rods();
  const double g[3] = {0, 0, -9.81}, every = 1e-3, w = 0.2, delta = 2e-3;
  sw_spec_set_gravity(s, g);
  add_probe(s, "mean", SW_PROBE_MEAN_VELOCITY, 0, NULL, w);
  sw_spec_set_dt(s, 1e-4);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const int frames = sw_test_sanitized() ? 300 : 600;
  double worst = 0, out[3];
  for (int frame = 0; frame <= frames; frame++) {
    if (frame) sw_test_run_to(m, d, every * frame);
    const double t = d->time;
    sw_probe_measure(m, d, 0, out);
    if (t > w + 1e-9) worst = fmax(worst, fabs(out[2] - g[2] * (t - w / 2)));
  }
  fprintf(stderr, "# window %.2f s over %d frames of %.0f ms (the ring holds %d samples)\n", w,
          frames, every * 1e3, SW_PROBE_RING);
  SW_EXPECT_REL("max |mean velocity - g (t - w/2)| once the ring wraps, m/s", worst,
                9.81 * delta * delta / 8 / w, 1e-6);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_probe_output(void **state) {
  (void)state;
  swSpec *s = two_rods();
  add_probe(s, "com", SW_PROBE_COM, 0, NULL, 0);
  add_probe(s, "speed", SW_PROBE_MEAN_VELOCITY, 0, NULL, 0.02);
  swProbeDesc tip;
  sw_probe_desc_init(&tip);
  tip.name = "tip";
  tip.kind = SW_PROBE_NODE;
  tip.rod = 0;
  tip.node = 4;
  sw_spec_add_probe(s, &tip);
  sw_spec_set_dt(s, 1e-5);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double V[3] = {0.5, 0.1, 0};
  set_uniform_motion(m, d, V);
  char path[64];
  snprintf(path, sizeof path, "/tmp/sinew_test_probe_XXXXXX");
  int fd = mkstemp(path);
  assert_true(fd >= 0);
  close(fd);
  char err[256] = "";
  swOutputOptions opt = {.duration = 0.05};
  swOutput *out = sw_output_open(path, m, &opt, err, sizeof err);
  if (!out) fprintf(stderr, "# %s\n", err);
  assert_non_null(out);
  swRunOptions ro = {.duration = 0.05, .every = 0.01, .quiet = 1};
  assert_int_equal(sw_run(m, d, out, &ro), SW_OK);
  const long frames = sw_output_frames(out);
  assert_int_equal(sw_output_close(out, "complete"), SW_OK);

  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  assert_true(file >= 0);
  const char *names[3] = {"com", "speed", "tip"};
  const char *units[3] = {"m", "m/s", "m"};
  const char *kinds[3] = {"center_of_mass", "mean_velocity", "node_position"};
  double com0[3] = {0, 0, 0};
  sw_reset(m, d);
  sw_probe_measure(m, d, 0, com0);
  for (int k = 0; k < 3; k++) {
    char p[64];
    snprintf(p, sizeof p, "/probes/%s", names[k]);
    hid_t ds = H5Dopen2(file, p, H5P_DEFAULT);
    assert_true(ds >= 0);
    hid_t sp = H5Dget_space(ds);
    hsize_t dims[2];
    assert_int_equal(H5Sget_simple_extent_ndims(sp), 2);
    H5Sget_simple_extent_dims(sp, dims, NULL);
    assert_true(dims[0] == (hsize_t)frames && dims[1] == 3);
    double buf[3 * 16];
    assert_true(frames <= 16);
    assert_true(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0);
    char *u = read_string_attr(file, p, "units"), *kind = read_string_attr(file, p, "kind");
    fprintf(stderr, "# %s [%llu, 3], units '%s', kind '%s', last row (%.6g, %.6g, %.6g)\n", p,
            (unsigned long long)dims[0], u, kind, buf[3 * (frames - 1)], buf[3 * (frames - 1) + 1],
            buf[3 * (frames - 1) + 2]);
    assert_string_equal(u, units[k]);
    assert_string_equal(kind, kinds[k]);
    free(u);
    free(kind);
    /* every row against the closed form of the uniform motion */
    double worst = 0;
    for (long f = 0; f < frames; f++) {
      const double t = 0.01 * (double)f;
      double ref[3];
      for (int q = 0; q < 3; q++)
        ref[q] = k == 1 ? V[q] : k == 0 ? com0[q] + V[q] * t : (q == 0 ? 0.4 : 0) + V[q] * t;
      worst = fmax(worst, dist3(buf + 3 * f, ref));
    }
    SW_EXPECT_ABS("max |row - closed form of the uniform motion|", worst, 0.0, 1e-10);
    if (k == 1) SW_EXPECT_ABS("window attribute, s", read_double_attr_of(file, p, "window"), 0.02, 0);
    H5Sclose(sp);
    H5Dclose(ds);
  }
  H5Fclose(file);
  unlink(path);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_probe_errors(void **state) {
  (void)state;
  swSpec *s = two_rods();
  swProbeDesc p;
  sw_probe_desc_init(&p);
  p.name = "tip";
  p.kind = SW_PROBE_NODE;
  p.rod = 1;
  p.node = 8;
  sw_spec_add_probe(s, &p);
  char err[256] = "";
  assert_null(sw_compile(s, err, sizeof err));
  fprintf(stderr, "# error: %s\n", err);
  assert_string_equal(err, "probe 'tip': node 8 out of range for rod 'tail' (nodes 0..7, -1 = last)");
  sw_spec_free(s);
  s = two_rods();
  const int bad[1] = {5};
  add_probe(s, "com", SW_PROBE_COM, 1, bad, 0);
  assert_null(sw_compile(s, err, sizeof err));
  fprintf(stderr, "# error: %s\n", err);
  assert_string_equal(err, "probe 'com': rod 5 does not exist (the scene has 2)");
  sw_spec_free(s);
}

/* Probes read at a held step (probe.c, "Read at a held step") against the
 * same read from the whole step (sw_whole_begin): the body clamped at its
 * start and swinging under gravity, the tail falling, a probe of each kind
 * the held reading takes; every reading of 400 steps the same bits, and the
 * half drift it adds is not nothing.  A mean velocity, a rigid rod's
 * centre of mass, are refused. */
static void test_held_reading(void **state) {
  (void)state;
  swSpec *s = two_rods();
  const int body[1] = {0};
  add_probe(s, "com", SW_PROBE_COM, 0, NULL, 0);
  add_probe(s, "body_com", SW_PROBE_COM, 1, body, 0);
  add_probe(s, "com_v", SW_PROBE_COM_VELOCITY, 0, NULL, 0);
  swProbeDesc tip;
  sw_probe_desc_init(&tip);
  tip.name = "tip";
  tip.kind = SW_PROBE_NODE;
  tip.rod = 0;
  sw_spec_add_probe(s, &tip);
  add_probe(s, "mean_v", SW_PROBE_MEAN_VELOCITY, 0, NULL, 0.01);
  swBCDesc c = sw_test_clamp(0, 0);
  sw_spec_add_bc(s, &c);
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *held = sw_data_new(m), *whole = sw_data_new(m);
  for (int p = 0; p < 4; p++) assert_int_equal(sw_probe_held_ok(m, p), 1);
  assert_int_equal(sw_probe_held_ok(m, 4), 0); /* the mean velocity keeps a ring */
  long differ = 0;
  double moved = 0;
  const int steps = 400;
  for (int k = 0; k < steps; k++) {
    assert_int_equal(sw_steps_held(m, held, 1), SW_OK);
    assert_int_equal(sw_steps_held(m, whole, 1), SW_OK);
    for (int p = 0; p < 4; p++) {
      double a[3], b[3], before[3];
      sw_probe_measure(m, held, p, before); /* the held state itself */
      sw_probe_measure_held(m, held, p, a);
      assert_int_equal(sw_whole_begin(m, whole), SW_OK);
      sw_probe_measure(m, whole, p, b);
      sw_whole_end(m, whole);
      differ += memcmp(a, b, sizeof a) != 0;
      if (p == 3) moved = fmax(moved, dist3(before, b));
    }
  }
  fprintf(stderr, "# %s: %d steps of dt = %.3g s, 4 probes: %ld readings differ from the whole "
          "step's; the tip moves by up to %.3g m over the half drift\n", __func__, steps, m->dt,
          differ, moved);
  assert_int_equal(differ, 0);
  assert_true(moved > 0);
  sw_data_free(held);
  sw_data_free(whole);
  sw_model_free(m);
  sw_spec_free(s);
  /* a rigid rod's nodes follow its body's drift: refused */
  s = two_rods();
  add_probe(s, "com", SW_PROBE_COM, 0, NULL, 0);
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "bone";
  r.nelem = 3;
  r.length = 0.1;
  r.radius_start = r.radius_end = 0.01;
  r.start[1] = -1;
  r.rigid = 1;
  const int bone[1] = {sw_spec_add_rod(s, &r)};
  add_probe(s, "bone_com", SW_PROBE_COM, 1, bone, 0);
  m = sw_test_compile(s);
  assert_int_equal(sw_probe_held_ok(m, 0), 0);
  assert_int_equal(sw_probe_held_ok(m, 1), 0);
  sw_model_free(m);
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_center_of_mass),
    cmocka_unit_test(test_uniform_motion),
    cmocka_unit_test(test_mean_velocity_under_gravity),
    cmocka_unit_test(test_mean_velocity_ring),
    cmocka_unit_test(test_probe_output),
    cmocka_unit_test(test_probe_errors),
    cmocka_unit_test(test_held_reading),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
