/* test_model.c — the model builder (model.c) and its checks.
 *
 * sw_compile must reject every invalid scene with a message that names the
 * rod (or the load / boundary condition) and the problem; accepted scenes
 * must get the documented layout (rods stored back to back in one space of
 * slots, a rod's node, element and Voronoi addresses equal) and constants:
 * lumped masses of a tapered rod, S^ = diag(4/3 G A, 4/3 G A, E A) and
 * B^ = diag(E I, E I, G J) with the hardening factors on G,
 * J^ = rho l^ diag(I, I, 2I), the rest-length weighted Voronoi average of
 * B^, and the rest curvature of a rest shape given as a quarter circle.
 * Also: the stable time step estimate and its scaling with E and element
 * length, the time signals at and outside their ends, sw_reset, and that an
 * unloaded free rod stays exactly at rest. */
#include "testutil.h"

/* A valid rod with every field set to something distinct. */
static swRodDesc good_rod(const char *name) {
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = name;
  r.nelem = 5;
  r.length = 0.5;
  r.radius_start = r.radius_end = 0.01;
  r.density = 1000;
  r.youngs = 1e6;
  r.poisson = 0.5;
  return r;
}

/* Compile a scene that must be rejected and free it (before asserting, so a
 * failing check leaks nothing under the sanitizers); the message is left in
 * err. */
static void expect_reject(swSpec *s, char *err, size_t errlen) {
  err[0] = 0;
  swModel *m = sw_compile(s, err, errlen);
  int accepted = m != NULL;
  sw_model_free(m);
  sw_spec_free(s);
  if (accepted) fprintf(stderr, "# scene accepted, should have been rejected\n");
  assert_false(accepted);
  assert_true(err[0] != 0);
}

static void expect_message(const char *err, const char *part) {
  if (!strstr(err, part))
    fprintf(stderr, "# message \"%s\" does not contain \"%s\"\n", err, part);
  assert_non_null(strstr(err, part));
}

static double max_abs_diff(const double *a, const double *b, int n) {
  double e = 0;
  for (int i = 0; i < n; i++) e = fmax(e, fabs(a[i] - b[i]));
  return e;
}

/* The same over per-slot planar arrays a and b (b NULL: largest |a|), the
 * first `planes` planes, at the real nodes (elem = 0) or real elements
 * (elem = 1) of every rod. */
static double max_abs_diff_slots(const swModel *m, const double *a, const double *b, int elem,
                                 int planes) {
  double e = 0;
  for (int r = 0; r < m->nrod; r++) {
    int first = elem ? m->elem_adr[r] : m->node_adr[r];
    int count = elem ? m->rod_nelem[r] : m->rod_nelem[r] + 1;
    for (int i = first; i < first + count; i++)
      for (int k = 0; k < planes; k++)
        e = fmax(e, fabs(SW_AT(m, a, i, k) - (b ? SW_AT(m, b, i, k) : 0)));
  }
  return e;
}

/* ---- rejected scenes ---- */

static void test_reject_no_rods(void **state) {
  (void)state;
  char err[256];
  swSpec *s = sw_spec_new();
  expect_reject(s, err, sizeof err);
  expect_message(err, "no rods");
  fprintf(stderr, "# %s: \"%s\"\n", __func__, err);
}

/* One bad field of rod 'arm', added after a valid rod 'base' so that the
 * message must name the right one. */
typedef struct {
  const char *what;   /* the mistake, for the log */
  const char *field;  /* a substring the message must contain */
} BadRod;

static BadRod spoil(int k, swRodDesc *r) {
  switch (k) {
  case 0: r->nelem = 1; return (BadRod){"nelem = 1", "at least 2 elements"};
  case 1: r->nelem = 0; return (BadRod){"nelem = 0", "at least 2 elements"};
  case 2: r->nelem = -3; return (BadRod){"nelem = -3", "at least 2 elements"};
  case 3: r->length = 0; return (BadRod){"length = 0", "length"};
  case 4: r->length = -1; return (BadRod){"length = -1", "length"};
  case 5: r->length = NAN; return (BadRod){"length = NaN", "length"};
  case 6: r->radius_start = 0; return (BadRod){"radius_start = 0", "radius"};
  case 7: r->radius_end = -0.01; return (BadRod){"radius_end < 0", "radius"};
  case 8: r->density = 0; return (BadRod){"density = 0", "density"};
  case 9: r->density = -1000; return (BadRod){"density < 0", "density"};
  case 10: r->youngs = 0; return (BadRod){"E = 0", "Young's modulus"};
  case 11: r->youngs = -1e6; return (BadRod){"E < 0", "Young's modulus"};
  case 12: r->youngs = INFINITY; return (BadRod){"E = inf", "Young's modulus"};
  case 13: r->poisson = 0.6; return (BadRod){"Poisson 0.6", "Poisson"};
  case 14: r->poisson = -1.0; return (BadRod){"Poisson -1", "Poisson"};
  case 15: r->poisson = -2.0; return (BadRod){"Poisson -2", "Poisson"};
  case 16: r->poisson = NAN; return (BadRod){"Poisson NaN", "Poisson"};
  case 17: r->shear_hardening = 0; return (BadRod){"shear hardening 0", "hardening"};
  case 18: r->shear_hardening = -2; return (BadRod){"shear hardening < 0", "hardening"};
  case 19: r->twist_hardening = 0; return (BadRod){"twist hardening 0", "hardening"};
  case 20: r->twist_hardening = -1; return (BadRod){"twist hardening < 0", "hardening"};
  case 21: r->gamma = -0.1; return (BadRod){"gamma < 0", "dissipation"};
  case 22: r->gamma = NAN; return (BadRod){"gamma NaN", "dissipation"};
  case 23:
    r->direction[0] = 0; r->direction[1] = 0; r->direction[2] = 2;
    r->normal[0] = 0; r->normal[1] = 0; r->normal[2] = -1;
    return (BadRod){"normal parallel to direction", "parallel to normal"};
  case 24:
    r->direction[0] = r->direction[1] = r->direction[2] = 0;
    return (BadRod){"zero direction", "direction"};
  case 25: r->shear_modulus = -5e5; return (BadRod){"G < 0", "shear modulus"};
  case 26: r->damping = (swDampingKind)7; return (BadRod){"damping kind 7", "damping"};
  }
  return (BadRod){NULL, NULL};
}

static void test_reject_bad_rods(void **state) {
  (void)state;
  int k;
  for (k = 0;; k++) {
    swSpec *s = sw_spec_new();
    swRodDesc base = good_rod("base"), arm = good_rod("arm");
    BadRod b = spoil(k, &arm);
    if (!b.what) { sw_spec_free(s); break; }
    sw_spec_add_rod(s, &base);
    sw_spec_add_rod(s, &arm);
    char err[256];
    expect_reject(s, err, sizeof err);
    fprintf(stderr, "# %s: %s -> \"%s\"\n", __func__, b.what, err);
    expect_message(err, "rod 'arm'");
    expect_message(err, b.field);
    assert_null(strstr(err, "'base'"));
  }
  assert_int_equal(k, 27);
}

/* The limits themselves are accepted: Poisson 0.5 and just above -1, and a
 * Poisson ratio out of range is ignored when G is given. */
static void test_accept_limits(void **state) {
  (void)state;
  const double nus[] = {0.5, -0.999, 0.0};
  for (int k = 0; k < 3; k++) {
    swSpec *s = sw_spec_new();
    swRodDesc r = good_rod("arm");
    r.poisson = nus[k];
    sw_spec_add_rod(s, &r);
    swModel *m = sw_test_compile(s);
    sw_model_free(m);
    sw_spec_free(s);
  }
  swSpec *s = sw_spec_new();
  swRodDesc r = good_rod("arm");
  r.poisson = 0.9;
  r.shear_modulus = 4e5;
  sw_spec_add_rod(s, &r);
  swModel *m = sw_test_compile(s);
  double A = M_PI * 1e-4;
  SW_EXPECT_REL("S11 with explicit G (N)", SW_AT(m, m->shear_stiff, m->elem_adr[0], 0),
                4.0 / 3.0 * 4e5 * A, 1e-15);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_reject_loads(void **state) {
  (void)state;
  struct {
    swLoadKind kind;
    int rod, index;
    const char *parts[3];
  } cases[] = {
      {SW_LOAD_FORCE, 2, 0, {"load 0", "rod index 2", "out of range"}},
      {SW_LOAD_FORCE, -1, 0, {"load 0", "rod index -1", "out of range"}},
      {SW_LOAD_FORCE, 1, 6, {"rod 'arm'", "node index 6", "out of range"}},
      {SW_LOAD_FORCE, 1, -2, {"rod 'arm'", "node index -2", "out of range"}},
      {SW_LOAD_TORQUE, 1, 5, {"rod 'arm'", "element index 5", "out of range"}},
      {SW_LOAD_TORQUE, 1, -7, {"rod 'arm'", "element index -7", "out of range"}},
  };
  for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
    swSpec *s = sw_spec_new();
    swRodDesc base = good_rod("base"), arm = good_rod("arm"); /* 5 elements, 6 nodes */
    sw_spec_add_rod(s, &base);
    sw_spec_add_rod(s, &arm);
    swLoadDesc l = sw_test_load(cases[k].kind, cases[k].rod, cases[k].index, 1, 0, 0);
    sw_spec_add_load(s, &l);
    char err[256];
    expect_reject(s, err, sizeof err);
    fprintf(stderr, "# %s: \"%s\"\n", __func__, err);
    for (int p = 0; p < 3; p++) expect_message(err, cases[k].parts[p]);
  }
  /* the last valid indices, and -1 for the last node / element, are accepted */
  swSpec *s = sw_spec_new();
  swRodDesc base = good_rod("base"), arm = good_rod("arm");
  sw_spec_add_rod(s, &base);
  sw_spec_add_rod(s, &arm);
  swLoadDesc l0 = sw_test_load(SW_LOAD_FORCE, 1, 5, 1, 0, 0);
  swLoadDesc l1 = sw_test_load(SW_LOAD_TORQUE, 1, 4, 1, 0, 0);
  swLoadDesc l2 = sw_test_load(SW_LOAD_FORCE, 1, -1, 1, 0, 0);
  swLoadDesc l3 = sw_test_load(SW_LOAD_TORQUE, 1, -1, 1, 0, 0);
  sw_spec_add_load(s, &l0);
  sw_spec_add_load(s, &l1);
  sw_spec_add_load(s, &l2);
  sw_spec_add_load(s, &l3);
  swModel *m = sw_test_compile(s);
  assert_int_equal(m->nload, 4);
  assert_int_equal(m->load[2].index, 5); /* -1 = last node */
  assert_int_equal(m->load[3].index, 4); /* -1 = last element */
  sw_model_free(m);
  sw_spec_free(s);
  /* a table signal with no points, or more than it can hold, is rejected */
  const int npts[] = {0, SW_SIGNAL_MAXPTS + 1};
  for (int k = 0; k < 2; k++) {
    swSpec *st = sw_spec_new();
    swRodDesc one = good_rod("arm");
    sw_spec_add_rod(st, &one);
    swLoadDesc lt = sw_test_load(SW_LOAD_FORCE, 0, 0, 1, 0, 0);
    lt.signal.kind = SW_SIG_TABLE;
    lt.signal.npts = npts[k];
    sw_spec_add_load(st, &lt);
    char err[256];
    expect_reject(st, err, sizeof err);
    fprintf(stderr, "# %s: npts = %d -> \"%s\"\n", __func__, npts[k], err);
    expect_message(err, "load 0");
    expect_message(err, "table");
  }
}

/* A boundary condition on a rod that does not exist, or of an unknown kind. */
static void test_reject_bc_rod_and_kind(void **state) {
  (void)state;
  for (int k = 0; k < 2; k++) {
    swSpec *s = sw_spec_new();
    swRodDesc arm = good_rod("arm");
    sw_spec_add_rod(s, &arm);
    swBCDesc b = sw_test_clamp(k == 0 ? 3 : 0, 0);
    if (k == 1) b.kind = (swBCKind)(SW_BC_SLEEVE + 1);   /* one past the last kind */
    sw_spec_add_bc(s, &b);
    char err[256];
    expect_reject(s, err, sizeof err);
    fprintf(stderr, "# %s: \"%s\"\n", __func__, err);
    expect_message(err, "boundary condition 0");
    expect_message(err, k == 0 ? "rod index 3" : "unknown kind 6");
  }
}

/* A boundary condition whose signal is a table with no points or more than
 * SW_SIGNAL_MAXPTS: as for loads, it must be rejected, since sw_signal_eval
 * reads times[npts - 1] and values[npts - 1]. */
static void test_reject_bc_table(void **state) {
  (void)state;
  const int npts[] = {0, SW_SIGNAL_MAXPTS + 1};
  for (int k = 0; k < 2; k++) {
    swSpec *s = sw_spec_new();
    swRodDesc arm = good_rod("arm");
    sw_spec_add_rod(s, &arm);
    swBCDesc b = sw_test_clamp(0, 1);
    b.kind = SW_BC_VELOCITY;
    b.vec[0] = 1;
    b.signal.kind = SW_SIG_TABLE;
    b.signal.npts = npts[k];
    sw_spec_add_bc(s, &b);
    fprintf(stderr, "# %s: velocity BC with a table of %d points\n", __func__, npts[k]);
    char err[256];
    expect_reject(s, err, sizeof err);
    fprintf(stderr, "# %s: npts = %d -> \"%s\"\n", __func__, npts[k], err);
    expect_message(err, "boundary condition 0");
    expect_message(err, "table");
  }
}

/* A boundary condition with end not 0 or 1 on rod 'arm' (the second rod):
 * the message must name the condition, the rod and the problem. */
static void test_reject_bc_end(void **state) {
  (void)state;
  const int ends[] = {2, -1};
  for (int k = 0; k < 2; k++) {
    swSpec *s = sw_spec_new();
    swRodDesc base = good_rod("base"), arm = good_rod("arm");
    sw_spec_add_rod(s, &base);
    sw_spec_add_rod(s, &arm);
    swBCDesc b = sw_test_clamp(1, ends[k]);
    sw_spec_add_bc(s, &b);
    char err[256];
    expect_reject(s, err, sizeof err);
    fprintf(stderr, "# %s: end = %d -> \"%s\"\n", __func__, ends[k], err);
    expect_message(err, "boundary condition 0");
    expect_message(err, "end");
    expect_message(err, "rod 'arm'");
  }
}

static void test_reject_dt_and_misc(void **state) {
  (void)state;
  const double dts[] = {0.0, -1e-5, NAN, INFINITY};
  for (int k = 0; k < 4; k++) {
    swSpec *s = sw_spec_new();
    swRodDesc arm = good_rod("arm");
    sw_spec_add_rod(s, &arm);
    sw_spec_set_dt(s, dts[k]);
    char err[256];
    expect_reject(s, err, sizeof err);
    fprintf(stderr, "# %s: dt = %g -> \"%s\"\n", __func__, dts[k], err);
    expect_message(err, "time step");
  }
  /* a rest shape with two coincident nodes */
  swSpec *s = sw_spec_new();
  swRodDesc arm = good_rod("arm");
  arm.nelem = 3;
  int id = sw_spec_add_rod(s, &arm);
  double x[12] = {0, 0, 0, 0, 0, 0.1, 0, 0, 0.1, 0, 0, 0.2};
  double Q[27];
  const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int i = 0; i < 3; i++) memcpy(Q + 9 * i, I, sizeof I);
  assert_int_equal(sw_spec_set_rest_shape(s, id, x, Q), SW_OK);
  assert_int_equal(sw_spec_set_rest_shape(s, 5, x, Q), SW_EUSAGE);
  /* no buffer, or a tiny one: still rejected, no overflow */
  swModel *m1 = sw_compile(s, NULL, 0);
  char small[8];
  memset(small, 'x', sizeof small);
  swModel *m2 = sw_compile(s, small, sizeof small);
  char err[256];
  expect_reject(s, err, sizeof err);
  fprintf(stderr, "# %s: coincident nodes -> \"%s\"\n", __func__, err);
  expect_message(err, "rod 'arm'");
  expect_message(err, "element 1");
  expect_message(err, "zero rest length");
  assert_null(m1);
  assert_null(m2);
  assert_int_equal(small[7], 0);
  assert_int_equal((int)strlen(small), 7);
}

/* ---- accepted models ---- */

static void test_layout_two_rods(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  swRodDesc a = good_rod("first"), b = good_rod("second");
  a.nelem = 3;
  b.nelem = 5;
  b.start[0] = 1; b.start[1] = 2; b.start[2] = 3;
  b.direction[0] = 1; b.direction[1] = 0; b.direction[2] = 0;
  b.normal[0] = 0; b.normal[1] = 1; b.normal[2] = 0;
  b.length = 1.0;
  assert_int_equal(sw_spec_add_rod(s, &a), 0);
  assert_int_equal(sw_spec_add_rod(s, &b), 1);
  swModel *m = sw_test_compile(s);
  assert_int_equal(m->nrod, 2);
  assert_int_equal(m->nnode, 10);
  assert_int_equal(m->nelem, 8);
  assert_int_equal(m->nvor, 6);
  /* one slot space: rod 'first' owns slots 0..3, 'second' 4..9 */
  assert_int_equal(m->nslot, 10);
  assert_int_equal(m->node_adr[0], 0); assert_int_equal(m->node_adr[1], 4);
  assert_int_equal(m->elem_adr[0], 0); assert_int_equal(m->elem_adr[1], 4);
  assert_int_equal(m->vor_adr[0], 0); assert_int_equal(m->vor_adr[1], 4);
  assert_int_equal(m->rod_nelem[0], 3); assert_int_equal(m->rod_nelem[1], 5);
  assert_string_equal(m->rod_name[0], "first");
  assert_string_equal(m->rod_name[1], "second");
  assert_int_equal(m->nload, 0);
  assert_int_equal(m->nbc, 0);
  /* rod 'second' starts at (1,2,3) and runs along x in steps of 0.2 m */
  for (int i = 0; i <= 5; i++) {
    double x[3];
    sw_get3(m, m->x0, m->node_adr[1] + i, x);
    assert_true(fabs(x[0] - (1 + 0.2 * i)) < 1e-15 && x[1] == 2 && x[2] == 3);
  }
  /* rod 'first' along z from the origin in steps of 0.5/3 */
  for (int i = 0; i <= 3; i++) {
    double x[3];
    sw_get3(m, m->x0, m->node_adr[0] + i, x);
    assert_true(x[0] == 0 && x[1] == 0 && fabs(x[2] - 0.5 * i / 3) < 1e-15);
  }
  /* directors: d1 = y, d2 = z, d3 = x for 'second' */
  const double Qb[9] = {0, 1, 0, 0, 0, 1, 1, 0, 0};
  for (int e = 0; e < 5; e++) {
    double Q[9];
    sw_getQ(m, m->Q0, m->elem_adr[1] + e, Q);
    assert_true(max_abs_diff(Q, Qb, 9) == 0);
  }
  for (int r = 0; r < 2; r++)
    for (int e = 0; e < m->rod_nelem[r]; e++)
      assert_true(fabs(m->rest_len[m->elem_adr[r] + e] - (r == 0 ? 0.5 / 3 : 0.2)) < 1e-15);
  /* the data follows the layout */
  swData *d = sw_data_new(m);
  assert_non_null(d);
  assert_true(max_abs_diff_slots(m, d->x, m->x0, 0, 3) == 0);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Tapered rod: the radius is linear in the element index from element 0
 * (radius_start) to element n-1 (radius_end), so the mass is
 * sum rho pi r_i^2 l, which is rho pi times the integral of r(s)^2 for the
 * linear taper through the element centres less n l^3 r'^2 / 12 (the
 * midpoint rule on a quadratic). */
static void test_mass_tapered(void **state) {
  (void)state;
  const int n = 7;
  const double L = 0.7, r0 = 0.02, r1 = 0.01, rho = 1200, l = L / n;
  swSpec *s = sw_spec_new();
  swRodDesc r = good_rod("cone");
  r.nelem = n;
  r.length = L;
  r.radius_start = r0;
  r.radius_end = r1;
  r.density = rho;
  sw_spec_add_rod(s, &r);
  swModel *m = sw_test_compile(s);
  double total = 0, expect = 0;
  for (int i = 0; i <= n; i++) total += m->mass[i];
  double worst_r = 0;
  for (int i = 0; i < n; i++) {
    double ri = r0 + (r1 - r0) * i / (n - 1);
    worst_r = fmax(worst_r, fabs(m->radius[i] / ri - 1));
    expect += rho * M_PI * ri * ri * l;
  }
  fprintf(stderr, "# %s: element radii linear from %g to %g m, worst rel. error %.3e\n",
          __func__, r0, r1, worst_r);
  assert_true(worst_r < 4e-16);
  SW_EXPECT_REL("total mass (kg)", total, expect, 1e-14);
  /* the same from the integral of the taper */
  double slope = (r1 - r0) / (L - l), rs = r0 - slope * 0.5 * l; /* r(s) = rs + slope s */
  double integral = (pow(rs + slope * L, 3) - pow(rs, 3)) / (3 * slope);
  SW_EXPECT_REL("total mass from rho pi int r^2 ds (kg)", total,
                rho * M_PI * (integral - n * l * l * l * slope * slope / 12), 1e-13);
  /* lumping: half an element at each end node, half of two inside */
  double m0 = rho * M_PI * r0 * r0 * l, mn = rho * M_PI * r1 * r1 * l;
  SW_EXPECT_REL("mass of node 0 (kg)", m->mass[0], 0.5 * m0, 4e-15);
  SW_EXPECT_REL("mass of node n (kg)", m->mass[n], 0.5 * mn, 4e-15);
  for (int i = 1; i < n; i++) {
    double ra = r0 + (r1 - r0) * (i - 1) / (n - 1), rb = r0 + (r1 - r0) * i / (n - 1);
    assert_true(fabs(m->mass[i] - 0.5 * rho * M_PI * l * (ra * ra + rb * rb)) < 1e-15 * m->mass[i]);
    assert_true(fabs(m->inv_mass[i] * m->mass[i] - 1) < 1e-15);
  }
  sw_model_free(m);
  sw_spec_free(s);
}

/* S^, B^ and J^ of a uniform rod with hardening on G. */
static void test_stiffness_and_inertia(void **state) {
  (void)state;
  const double E = 2e6, nu = 0.3, hs = 1.7, ht = 2.3, rad = 0.015, rho = 900, L = 0.6;
  const int n = 6;
  swSpec *s = sw_spec_new();
  swRodDesc r = good_rod("arm");
  r.nelem = n;
  r.length = L;
  r.radius_start = r.radius_end = rad;
  r.density = rho;
  r.youngs = E;
  r.poisson = nu;
  r.shear_hardening = hs;
  r.twist_hardening = ht;
  sw_spec_add_rod(s, &r);
  swModel *m = sw_test_compile(s);
  const double G = E / (2 * (1 + nu)), A = M_PI * rad * rad, I = M_PI * pow(rad, 4) / 4;
  const double l = L / n;
  const double S[3] = {4.0 / 3.0 * G * hs * A, 4.0 / 3.0 * G * hs * A, E * A};
  const double B[3] = {E * I, E * I, G * ht * 2 * I};
  const double J[3] = {rho * l * I, rho * l * I, rho * l * 2 * I};
  double worst = 0;
  const int e0 = m->elem_adr[0], v0 = m->vor_adr[0];
  for (int e = e0; e < e0 + n; e++)
    for (int k = 0; k < 3; k++) {
      worst = fmax(worst, fabs(SW_AT(m, m->shear_stiff, e, k) / S[k] - 1));
      worst = fmax(worst, fabs(SW_AT(m, m->inertia, e, k) / J[k] - 1));
      worst = fmax(worst, fabs(SW_AT(m, m->inv_inertia, e, k) * J[k] - 1));
      worst = fmax(worst, fabs(SW_AT(m, m->clamp_bend, e, k) / B[k] - 1));
      worst = fmax(worst, fabs(m->rest_len[e] / l - 1) + fabs(m->inv_rest_len[e] * l - 1));
    }
  for (int v = v0; v < v0 + n - 1; v++) {
    for (int k = 0; k < 3; k++)
      worst = fmax(worst, fabs(SW_AT(m, m->bend_stiff, v, k) / B[k] - 1));
    worst = fmax(worst, fabs(m->rest_vor_len[v] / l - 1));
  }
  fprintf(stderr,
          "# %s: S^ = (%.6g, %.6g, %.6g) N, B^ = (%.6g, %.6g, %.6g) N m^2, J^ = (%.6g, %.6g, "
          "%.6g) kg m^2; worst relative deviation %.3e (tol 1e-14)\n",
          __func__, SW_AT(m, m->shear_stiff, e0, 0), SW_AT(m, m->shear_stiff, e0, 1),
          SW_AT(m, m->shear_stiff, e0, 2), SW_AT(m, m->bend_stiff, v0, 0),
          SW_AT(m, m->bend_stiff, v0, 1), SW_AT(m, m->bend_stiff, v0, 2),
          SW_AT(m, m->inertia, e0, 0), SW_AT(m, m->inertia, e0, 1), SW_AT(m, m->inertia, e0, 2),
          worst);
  assert_true(worst < 1e-14);
  /* hardening touches G only in S11, S22 and B33: S33, B11, B22 and J^
   * are those of the unhardened rod */
  swSpec *s1 = sw_spec_new();
  r.shear_hardening = r.twist_hardening = 1.0;
  sw_spec_add_rod(s1, &r);
  swModel *m1 = sw_test_compile(s1);
  const int e1 = m1->elem_adr[0], v1 = m1->vor_adr[0];
  assert_true(SW_AT(m1, m1->shear_stiff, e1, 2) == SW_AT(m, m->shear_stiff, e0, 2));
  assert_true(SW_AT(m1, m1->bend_stiff, v1, 0) == SW_AT(m, m->bend_stiff, v0, 0) &&
              SW_AT(m1, m1->bend_stiff, v1, 1) == SW_AT(m, m->bend_stiff, v0, 1));
  SW_EXPECT_REL("S11 hardened / unhardened",
                SW_AT(m, m->shear_stiff, e0, 0) / SW_AT(m1, m1->shear_stiff, e1, 0), hs, 1e-15);
  SW_EXPECT_REL("B33 hardened / unhardened",
                SW_AT(m, m->bend_stiff, v0, 2) / SW_AT(m1, m1->bend_stiff, v1, 2), ht, 1e-15);
  for (int k = 0; k < 3; k++)
    assert_true(SW_AT(m1, m1->inertia, e1, k) == SW_AT(m, m->inertia, e0, k));
  sw_model_free(m1);
  sw_spec_free(s1);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Straight rest shape with uneven node spacing and a taper: B^ at Voronoi
 * domain j is (B_j l_j + B_{j+1} l_{j+1}) / (l_j + l_{j+1}) and
 * D^_j = (l_j + l_{j+1}) / 2. */
static void test_bend_stiffness_voronoi_average(void **state) {
  (void)state;
  const int n = 6;
  const double E = 3e6, nu = 0.25, r0 = 0.03, r1 = 0.01, ht = 1.5;
  swSpec *s = sw_spec_new();
  swRodDesc r = good_rod("arm");
  r.nelem = n;
  r.radius_start = r0;
  r.radius_end = r1;
  r.youngs = E;
  r.poisson = nu;
  r.twist_hardening = ht;
  int id = sw_spec_add_rod(s, &r);
  double x[3 * (n + 1)], Q[9 * n], len[n], z = 0;
  const double I9[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int i = 0; i < n; i++) len[i] = 0.05 * (1 + i * i); /* 0.05 .. 1.3 m */
  for (int i = 0; i <= n; i++) {
    x[3 * i] = 0; x[3 * i + 1] = 0; x[3 * i + 2] = z;
    if (i < n) { z += len[i]; memcpy(Q + 9 * i, I9, sizeof I9); }
  }
  assert_int_equal(sw_spec_set_rest_shape(s, id, x, Q), SW_OK);
  swModel *m = sw_test_compile(s);
  const double G = E / (2 * (1 + nu));
  double worst = 0;
  for (int j = 0; j < n - 1; j++) {
    double Bj[3], Bk[3];
    for (int side = 0; side < 2; side++) {
      double rad = r0 + (r1 - r0) * (j + side) / (n - 1), I = M_PI * pow(rad, 4) / 4;
      double *B = side ? Bk : Bj;
      B[0] = B[1] = E * I;
      B[2] = G * ht * 2 * I;
    }
    double la = len[j], lb = len[j + 1];
    const int v = m->vor_adr[id] + j;
    for (int k = 0; k < 3; k++) {
      double ref = (Bj[k] * la + Bk[k] * lb) / (la + lb);
      worst = fmax(worst, fabs(SW_AT(m, m->bend_stiff, v, k) / ref - 1));
    }
    worst = fmax(worst, fabs(m->rest_vor_len[v] / (0.5 * (la + lb)) - 1));
    for (int k = 0; k < 3; k++) assert_true(SW_AT(m, m->rest_kappa, v, k) == 0);
  }
  for (int i = 0; i < n; i++)
    worst = fmax(worst, fabs(m->rest_len[m->elem_adr[id] + i] / len[i] - 1));
  const int v0 = m->vor_adr[id];
  fprintf(stderr, "# %s: B^_0 = (%.6g, %.6g, %.6g) N m^2; worst relative deviation from the "
                  "rest-length weighted average %.3e (tol 1e-14)\n",
          __func__, SW_AT(m, m->bend_stiff, v0, 0), SW_AT(m, m->bend_stiff, v0, 1),
          SW_AT(m, m->bend_stiff, v0, 2), worst);
  assert_true(worst < 1e-14);
  sw_model_free(m);
  sw_spec_free(s);
}

/* A quarter circle of radius R in the x-z plane, from the origin along z
 * bending towards +x, with n chords.  Element i's frame has d3 along its
 * chord (the tangent at the mid angle b_i), d1 = (cos b, 0, -sin b) and
 * d2 = y, so neighbouring frames differ by a turn db = pi/(2n) about d2 and
 * the discrete rest curvature is (0, db / D, 0) with D the chord 2R sin(db/2):
 * 1/R (1 + db^2/24 + ...). */
static void arc_shape(int n, double R, double *x, double *Q) {
  const double db = 0.5 * M_PI / n;
  for (int i = 0; i <= n; i++) {
    double a = db * i;
    x[3 * i] = R * (1 - cos(a)); x[3 * i + 1] = 0; x[3 * i + 2] = R * sin(a);
  }
  for (int i = 0; i < n; i++) {
    double b = db * (i + 0.5), *q = Q + 9 * i;
    q[0] = cos(b); q[1] = 0; q[2] = -sin(b);
    q[3] = 0; q[4] = 1; q[5] = 0;
    q[6] = sin(b); q[7] = 0; q[8] = cos(b);
  }
}

static void test_rest_shape_arc(void **state) {
  (void)state;
  const int n = 16;
  const double R = 0.4, db = 0.5 * M_PI / n;
  swSpec *s = sw_spec_new();
  swRodDesc r = good_rod("hook");
  r.nelem = n;
  int id = sw_spec_add_rod(s, &r);
  double x[3 * (n + 1)], Q[9 * n];
  arc_shape(n, R, x, Q);
  assert_int_equal(sw_spec_set_rest_shape(s, id, x, Q), SW_OK);
  /* a second rod with the same shape and a given rest curvature, which wins */
  swRodDesc r2 = r;
  r2.name = "given";
  r2.rest_kappa[0] = 0.5;
  int id2 = sw_spec_add_rod(s, &r2);
  assert_int_equal(sw_spec_set_rest_shape(s, id2, x, Q), SW_OK);
  swModel *m = sw_test_compile(s);
  const double chord = 2 * R * sin(0.5 * db), kref = db / chord;
  double worst_disc = 0, worst_other = 0, worst_R = 0;
  for (int v = 0; v < n - 1; v++) {
    double k[3], k2[3];
    sw_get3(m, m->rest_kappa, m->vor_adr[id] + v, k);
    worst_disc = fmax(worst_disc, fabs(k[1] / kref - 1));
    worst_R = fmax(worst_R, fabs(k[1] * R - 1));
    worst_other = fmax(worst_other, fmax(fabs(k[0]), fabs(k[2])) * R);
    sw_get3(m, m->rest_kappa, m->vor_adr[id2] + v, k2);
    assert_true(k2[0] == 0.5 && k2[1] == 0 && k2[2] == 0);
  }
  for (int e = 0; e < n; e++)
    assert_true(fabs(m->rest_len[m->elem_adr[id] + e] / chord - 1) < 1e-14);
  for (int i = 0; i <= n; i++) {
    double xi[3];
    sw_get3(m, m->x0, m->node_adr[id] + i, xi);
    assert_true(max_abs_diff(xi, x + 3 * i, 3) == 0);
  }
  for (int e = 0; e < n; e++) {
    double Qe[9];
    sw_getQ(m, m->Q0, m->elem_adr[id] + e, Qe);
    assert_true(max_abs_diff(Qe, Q + 9 * e, 9) == 0);
  }
  fprintf(stderr,
          "# %s: n = %d, R = %g m: rest kappa_2 = %.12g 1/m; relative deviation from the "
          "discrete db/D %.3e (tol 1e-13), from 1/R %.3e (bound db^2/24 = %.3e); off-axis "
          "|kappa| R %.3e (tol 1e-13)\n",
          __func__, n, R, SW_AT(m, m->rest_kappa, m->vor_adr[id], 1), worst_disc, worst_R,
          db * db / 24, worst_other);
  assert_true(worst_disc < 1e-13);
  assert_true(worst_R < db * db / 24 * 1.01);
  assert_true(worst_other < 1e-13);
  /* the arc is its own rest state: no internal couples or forces at t = 0 */
  swData *d = sw_data_new(m);
  double cmax = 0, fmax_ = 0;
  for (int v = m->vor_adr[id]; v < m->vor_adr[id] + n - 1; v++)
    for (int k = 0; k < 3; k++) cmax = fmax(cmax, fabs(SW_AT(m, d->couple, v, k)));
  for (int i = m->node_adr[id]; i <= m->node_adr[id] + n; i++)
    for (int k = 0; k < 3; k++) fmax_ = fmax(fmax_, fabs(SW_AT(m, d->force, i, k)));
  double Bscale = SW_AT(m, m->bend_stiff, m->vor_adr[id], 0) / R;
  double Sscale = SW_AT(m, m->shear_stiff, m->elem_adr[id], 2);
  fprintf(stderr, "# %s: at rest, max |couple| / (EI/R) = %.3e, max |force| / EA = %.3e\n",
          __func__, cmax / Bscale, fmax_ / Sscale);
  assert_true(cmax < 1e-12 * Bscale);
  assert_true(fmax_ < 1e-13 * Sscale);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- the stable time step ---- */

static double stable_dt_of(int n, double L, double rad, double E) {
  swSpec *s = sw_spec_new();
  swRodDesc r = good_rod("probe");
  r.nelem = n;
  r.length = L;
  r.radius_start = r.radius_end = rad;
  r.youngs = E;
  sw_spec_add_rod(s, &r);
  swModel *m = sw_test_compile(s);
  double dt = sw_stable_dt(m);
  assert_true(dt == sw_stable_dt_rod(m, 0) && dt == m->rod_wave_dt[0]);
  sw_model_free(m);
  sw_spec_free(s);
  return dt;
}

/* The estimate is positive and finite; E enters only through the wave
 * speeds, so dt scales exactly as 1/sqrt(E); it is proportional to the
 * element length l while l is well below the radius, and it is below the
 * Verlet limit 2/w of the axial zig-zag mode (w = 2 sqrt(E/rho)/l), a mode
 * every rod has.  For l above the radius the element rotation/shear mode,
 * w^2 = 16 G / (3 rho r^2), sets the limit and dt no longer falls with l. */
static void test_stable_dt(void **state) {
  (void)state;
  const double rho = 1000, rad = 0.01, E = 1e6, c = sqrt(E / rho);
  double dt1 = stable_dt_of(50, 1.0, rad, E);
  assert_true(isfinite(dt1) && dt1 > 0);
  double dt4 = stable_dt_of(50, 1.0, rad, 4 * E);
  SW_EXPECT_REL("dt(E) / dt(4E)", dt1 / dt4, 2.0, 1e-12);
  double dt100 = stable_dt_of(50, 1.0, rad, 100 * E);
  SW_EXPECT_REL("dt(E) / dt(100E)", dt1 / dt100, 10.0, 1e-12);
  /* fine discretisation, l = r/10 and r/20: linear in l */
  double dta = stable_dt_of(100, 0.1, rad, E), dtb = stable_dt_of(200, 0.1, rad, E);
  SW_EXPECT_REL("dt(l = r/10) / dt(l = r/20)", dta / dtb, 2.0, 1e-2);
  double dtc = stable_dt_of(400, 0.1, rad, E);
  SW_EXPECT_REL("dt(l = r/20) / dt(l = r/40)", dtb / dtc, 2.0, 1e-2);
  /* bounds: never above the axial zig-zag limit l / c */
  const int ns[] = {5, 10, 50, 100, 200, 400};
  for (int k = 0; k < 6; k++) {
    double l = 0.1 / ns[k], dt = stable_dt_of(ns[k], 0.1, rad, E);
    double rot = 2.0 / sqrt(16.0 / 3.0 * (E / 3.0) / (rho * rad * rad));
    fprintf(stderr, "# %s: l/r = %-6g dt = %.4e s, axial limit l/c = %.4e s, "
                    "rotation/shear limit %.4e s\n",
            __func__, l / rad, dt, l / c, rot);
    assert_true(dt > 0 && dt <= l / c);
    assert_true(dt <= rot);
    assert_true(dt > 0.25 * fmin(l / c, rot)); /* not absurdly conservative */
  }
  /* two rods: the model's estimate is the smaller */
  swSpec *s = sw_spec_new();
  swRodDesc a = good_rod("coarse"), b = good_rod("fine");
  a.nelem = 5; a.length = 0.1;
  b.nelem = 200; b.length = 0.1;
  sw_spec_add_rod(s, &a);
  sw_spec_add_rod(s, &b);
  swModel *m = sw_test_compile(s);
  assert_true(sw_stable_dt(m) == fmin(sw_stable_dt_rod(m, 0), sw_stable_dt_rod(m, 1)));
  assert_true(sw_stable_dt_rod(m, 1) < sw_stable_dt_rod(m, 0));
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- time signals ---- */

static void test_signals(void **state) {
  (void)state;
  swSignal c = sw_signal_const(2.5);
  assert_true(sw_signal_eval(&c, -1e9) == 2.5 && sw_signal_eval(&c, 0) == 2.5 &&
              sw_signal_eval(&c, 1e9) == 2.5);

  /* ramp 1 -> 3 over [2, 6] */
  swSignal r = sw_signal_ramp(1.0, 3.0, 2.0, 4.0);
  assert_true(sw_signal_eval(&r, -5) == 1.0);
  assert_true(sw_signal_eval(&r, 2.0) == 1.0);
  assert_true(fabs(sw_signal_eval(&r, 3.0) - 1.5) < 1e-15);
  assert_true(fabs(sw_signal_eval(&r, 4.0) - 2.0) < 1e-15);
  assert_true(sw_signal_eval(&r, 6.0) == 3.0);
  assert_true(sw_signal_eval(&r, 100.0) == 3.0);
  assert_true(fabs(sw_signal_eval(&r, nextafter(6.0, 0)) - 3.0) < 1e-15);
  /* zero duration: a step at t0 */
  swSignal r0 = sw_signal_ramp(1.0, 3.0, 2.0, 0.0);
  assert_true(sw_signal_eval(&r0, 1.9) == 1.0 && sw_signal_eval(&r0, 2.1) == 3.0);

  /* sine: mean 1, amplitude 2, 5 Hz, phase pi/6, from t0 = 0.1 */
  swSignal sn = sw_signal_sine(1.0, 2.0, 5.0, M_PI / 6, 0.1);
  assert_true(fabs(sw_signal_eval(&sn, 0.1) - 2.0) < 1e-15);                    /* 1 + 2 sin(pi/6) */
  assert_true(fabs(sw_signal_eval(&sn, 0.1 + 1.0 / 30) - 3.0) < 1e-14);         /* phase pi/2 */
  assert_true(fabs(sw_signal_eval(&sn, 0.1 + 0.2) - 2.0) < 1e-14);              /* one period */
  assert_true(fabs(sw_signal_eval(&sn, 0.1 - 1.0 / 60) - 1.0) < 1e-14);         /* phase 0 */
  assert_true(fabs(sw_signal_eval(&sn, 0.1 + 0.1) - 0.0) < 1e-14);              /* phase 7pi/6 */
  double worst = 0;
  for (int k = 0; k <= 100; k++) {
    double t = -1 + 0.037 * k;
    worst = fmax(worst, fabs(sw_signal_eval(&sn, t) -
                             (1 + 2 * sin(2 * M_PI * 5 * (t - 0.1) + M_PI / 6))));
  }
  assert_true(worst < 1e-13);

  /* step 4 -> -1 at 0.5: the new value from t0 on */
  swSignal st = sw_signal_step(4.0, -1.0, 0.5);
  assert_true(sw_signal_eval(&st, 0.0) == 4.0);
  assert_true(sw_signal_eval(&st, nextafter(0.5, 0)) == 4.0);
  assert_true(sw_signal_eval(&st, 0.5) == -1.0);
  assert_true(sw_signal_eval(&st, 7.0) == -1.0);

  /* table through (0,0) (1,2) (3,2) (4,-2), clamped outside */
  swSignal tb;
  memset(&tb, 0, sizeof tb);
  tb.kind = SW_SIG_TABLE;
  const double ts[] = {0, 1, 3, 4}, vs[] = {0, 2, 2, -2};
  tb.npts = 4;
  memcpy(tb.times, ts, sizeof ts);
  memcpy(tb.values, vs, sizeof vs);
  const double probe[][2] = {{-10, 0}, {0, 0},   {0.25, 0.5}, {1, 2},  {2, 2},   {3, 2},
                             {3.5, 0}, {3.75, -1}, {4, -2},   {4.5, -2}, {1e9, -2}};
  for (size_t k = 0; k < sizeof probe / sizeof *probe; k++) {
    double v = sw_signal_eval(&tb, probe[k][0]);
    if (fabs(v - probe[k][1]) > 1e-15)
      fprintf(stderr, "# %s: table(%g) = %.17g, expected %g\n", __func__, probe[k][0], v,
              probe[k][1]);
    assert_true(fabs(v - probe[k][1]) <= 1e-15);
  }
  /* a long table: bisection lands in the right interval everywhere */
  tb.npts = SW_SIGNAL_MAXPTS;
  for (int k = 0; k < SW_SIGNAL_MAXPTS; k++) {
    tb.times[k] = 0.1 * k;
    tb.values[k] = (double)(k * k);
  }
  double worst_tab = 0;
  for (int k = 0; k < 10 * (SW_SIGNAL_MAXPTS - 1); k++) {
    double t = 0.01 * k + 0.0013;
    int j = (int)(t / 0.1);
    double f = (t - 0.1 * j) / 0.1, ref = j * j + f * ((j + 1) * (j + 1) - j * j);
    worst_tab = fmax(worst_tab, fabs(sw_signal_eval(&tb, t) - ref) / fmax(1.0, ref));
  }
  assert_true(worst_tab < 1e-12);
  /* one point: constant */
  tb.npts = 1;
  tb.values[0] = 7;
  assert_true(sw_signal_eval(&tb, -1) == 7 && sw_signal_eval(&tb, 1e3) == 7);
  fprintf(stderr, "# %s: worst sine deviation %.3e (tol 1e-13), 64-point table %.3e (tol 1e-12)\n",
          __func__, worst, worst_tab);
}

/* ---- data ---- */

static void test_reset(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  swRodDesc a = good_rod("a"), b = good_rod("b");
  b.nelem = 4;
  b.direction[0] = 1; b.direction[1] = 1; b.direction[2] = 0;
  b.normal[0] = 0; b.normal[1] = 0; b.normal[2] = 1;
  sw_spec_add_rod(s, &a);
  sw_spec_add_rod(s, &b);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  int q = 0; /* counts node components rod by rod, node by node */
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
      for (int k = 0; k < 3; k++, q++) {
        SW_AT(m, d->x, i, k) += 0.01 * q;
        SW_AT(m, d->v, i, k) = 1.0 + q;
      }
  for (int r = 0; r < m->nrod; r++)
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) {
      for (int k = 0; k < 9; k++) SW_AT(m, d->Q, e, k) = 0.5;
      for (int k = 0; k < 3; k++) SW_AT(m, d->omega, e, k) = -2.0;
    }
  d->time = 3.0;
  d->step = 17;
  d->work = 5.0;
  strcpy(d->error, "stale");
  sw_reset(m, d);
  assert_true(d->time == 0 && d->step == 0 && d->work == 0 && d->error[0] == 0);
  assert_true(max_abs_diff_slots(m, d->x, m->x0, 0, 3) == 0);
  assert_true(max_abs_diff_slots(m, d->Q, m->Q0, 1, 9) == 0);
  assert_true(max_abs_diff_slots(m, d->v, NULL, 0, 3) == 0);
  assert_true(max_abs_diff_slots(m, d->omega, NULL, 1, 3) == 0);
  /* derived quantities are those of the rest state */
  for (int r = 0; r < m->nrod; r++)
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++)
      assert_true(fabs(d->dilatation[e] - 1) < 1e-15);
  /* a step and another reset give back the same state */
  assert_int_equal(sw_step(m, d), SW_OK);
  sw_reset(m, d);
  assert_true(max_abs_diff_slots(m, d->x, m->x0, 0, 3) == 0 && d->time == 0);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* An unloaded, unconstrained straight rod is in equilibrium.  Along a
 * coordinate axis every strain is exactly zero and after 1000 steps of either
 * integrator nothing has moved, to the last bit.  Along an oblique direction
 * the node positions start + s d3 are rounded, which leaves rest strains of
 * about 2e-15; they drive a vibration at round-off level (element rotations
 * of about 6e-14 rad through the stiff shear/rotation mode), so positions
 * are held to 1e-14 there and frames to 1e-12. */
static void test_free_rod_stays_at_rest(void **state) {
  (void)state;
  const double dirs[2][3] = {{0, 0, 1}, {1, 2, 2}};
  const double nrms[2][3] = {{1, 0, 0}, {2, -1, 0}};
  for (int integ = 0; integ < 2; integ++)
    for (int k = 0; k < 2; k++) {
      swSpec *s = sw_spec_new();
      swRodDesc r = good_rod("free");
      r.nelem = 20;
      r.start[0] = 0.3; r.start[1] = -0.2; r.start[2] = 0.1;
      memcpy(r.direction, dirs[k], sizeof r.direction);
      memcpy(r.normal, nrms[k], sizeof r.normal);
      sw_spec_add_rod(s, &r);
      sw_spec_set_integrator(s, integ ? SW_PEFRL : SW_VERLET);
      swModel *m0 = sw_test_compile(s);
      sw_spec_set_dt(s, 0.5 * sw_stable_dt(m0));
      sw_model_free(m0);
      swModel *m = sw_test_compile(s);
      swData *d = sw_data_new(m);
      double sig0 = 0;
      sig0 = max_abs_diff_slots(m, d->sigma, NULL, 1, 3);
      for (int t = 0; t < 1000; t++) assert_int_equal(sw_step(m, d), SW_OK);
      double dx = max_abs_diff_slots(m, d->x, m->x0, 0, 3);
      double dQ = max_abs_diff_slots(m, d->Q, m->Q0, 1, 9);
      double vmax = max_abs_diff_slots(m, d->v, NULL, 0, 3);
      double wmax = max_abs_diff_slots(m, d->omega, NULL, 1, 3);
      double tol_x = k == 0 ? 0.0 : 1e-14, tol_Q = k == 0 ? 0.0 : 1e-12;
      fprintf(stderr,
              "# %s: %s, direction (%g,%g,%g): rest strain %.3e; after 1000 steps max "
              "|x - x0| = %.3e m (tol %.0e), |Q - Q0| = %.3e (tol %.0e), |v| = %.3e m/s, "
              "|w| = %.3e rad/s\n",
              __func__, integ ? "PEFRL" : "Verlet", dirs[k][0], dirs[k][1], dirs[k][2], sig0, dx,
              tol_x, dQ, tol_Q, vmax, wmax);
      assert_true(dx <= tol_x);
      assert_true(dQ <= tol_Q);
      if (k == 0) assert_true(vmax == 0 && wmax == 0);
      assert_true(fabs(d->time - 1000 * m->dt) <= 1e-12 * d->time);
      sw_data_free(d);
      sw_model_free(m);
      sw_spec_free(s);
    }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_reject_no_rods),
      cmocka_unit_test(test_reject_bad_rods),
      cmocka_unit_test(test_accept_limits),
      cmocka_unit_test(test_reject_loads),
      cmocka_unit_test(test_reject_bc_rod_and_kind),
      cmocka_unit_test(test_reject_bc_table),
      cmocka_unit_test(test_reject_bc_end),
      cmocka_unit_test(test_reject_dt_and_misc),
      cmocka_unit_test(test_layout_two_rods),
      cmocka_unit_test(test_mass_tapered),
      cmocka_unit_test(test_stiffness_and_inertia),
      cmocka_unit_test(test_bend_stiffness_voronoi_average),
      cmocka_unit_test(test_rest_shape_arc),
      cmocka_unit_test(test_stable_dt),
      cmocka_unit_test(test_signals),
      cmocka_unit_test(test_reset),
      cmocka_unit_test(test_free_rod_stays_at_rest),
  };
  return cmocka_run_group_tests_name("model", tests, NULL, NULL);
}
