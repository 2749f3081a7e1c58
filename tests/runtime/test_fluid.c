/* test_fluid.c — fluids (fluid.c) against closed forms: a rod sedimenting in
 * Stokes flow broadside and lengthwise (terminal velocities w / c and
 * 2 w / c of Zhang 2019, Suppl. eq. 1), quadratic drag's terminal velocity
 * broadside, lengthwise and oblique (Suppl. eq. 2 with the projected area),
 * a neutrally buoyant rod that stays put and a light one that rises, a rod
 * carried by a uniform flow (the discrete relaxation exactly, the continuous
 * one at first order), a fluid acting only on the rods it lists, the energy
 * balance with drag (kinetic + elastic - work), the Stokes drag's stable
 * step against the step at which a rod really blows up, quadratic drag's
 * instability caught by the check, quadratic drag on each of its three
 * areas (silhouette, cross section, broadside) against -(1/2) rho C_d A |w| w
 * and the silhouette against the figures fluid.c gave before the areas
 * existed, the speed limit of quadratic drag on each area, and the
 * validation messages (exact text).
 *
 * Design.  Scenes are built through the public API (swFluidDesc,
 * sw_spec_add_fluid), so these are also the examples of how a fluid is
 * declared.  Rods are straight and uniform, so a rod translating as a whole
 * has no internal stress and the closed forms of a point body apply to it
 * exactly; the lengthwise and oblique quadratic cases use rigid rods, whose
 * drag is carried by the end caps alone lengthwise.  Runs are a few thousand
 * steps of ten-element rods; under SW_SANITIZED only the stable-step runs shrink. */
#include "testutil.h"
#include "internal.h"

static const double GRAV = 9.81;

/* ---- helpers ---- */

static double norm3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

static swRodDesc rod_along(const char *name, int n, double length, double radius, double density,
                           double youngs, const double start[3], const double dir[3]) {
  swRodDesc r = sw_test_rod(name, n, length, radius, start, dir, NULL);
  r.density = density;
  r.youngs = youngs;
  r.poisson = 0.5;
  return r;
}

static swFluidDesc stokes_fluid(double mu, double rho_f, int buoyancy) {
  swFluidDesc f;
  sw_fluid_desc_init(&f);
  f.name = "water";
  f.model = SW_FLUID_STOKES;
  f.viscosity = mu;
  f.density = rho_f;
  f.buoyancy = buoyancy;
  return f;
}

static swFluidDesc quadratic_fluid(double rho_f, double cd, int buoyancy) {
  swFluidDesc f;
  sw_fluid_desc_init(&f);
  f.name = "air";
  f.model = SW_FLUID_QUADRATIC;
  f.density = rho_f;
  f.drag_coefficient = cd;
  f.buoyancy = buoyancy;
  return f;
}

static void set_gravity_z(swSpec *s) {
  const double g[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, g);
}

/* Mass-weighted mean velocity of rod r (its centre of mass). */
static void com_velocity(const swModel *m, const swData *d, int r, double out[3]) {
  double M = 0;
  out[0] = out[1] = out[2] = 0;
  for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
    M += m->mass[i];
    for (int k = 0; k < 3; k++) out[k] += m->mass[i] * SW_AT(m, d->v, i, k);
  }
  for (int k = 0; k < 3; k++) out[k] /= M;
}

/* Height of the centre of mass of rod r. */
static double com_height(const swModel *m, const swData *d, int r) {
  double M = 0, z = 0;
  for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
    M += m->mass[i];
    z += m->mass[i] * SW_AT(m, d->x, i, 2);
  }
  return z / M;
}

/* Largest difference between a node velocity of rod r and the mean. */
static double velocity_spread(const swModel *m, const swData *d, int r) {
  double V[3], worst = 0;
  com_velocity(m, d, r, V);
  for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
    double dv[3] = {SW_AT(m, d->v, i, 0) - V[0], SW_AT(m, d->v, i, 1) - V[1],
                    SW_AT(m, d->v, i, 2) - V[2]};
    worst = fmax(worst, norm3(dv));
  }
  return worst;
}

/* The scene of the Stokes tests: a rod of L = 0.1 m, r = 1 mm, E = 1 MPa in
 * a fluid of mu = 1 Pa s (glycerol-like), rho_f = 1000 kg/m^3. */
static const double SL = 0.1, SR = 1e-3, SE = 1e6, SMU = 1.0, SRHOF = 1000;
static const int SN = 10;

/* c = 4 pi mu / ln(L / r), Suppl. eq. 1 */
static double stokes_c(void) { return 4 * M_PI * SMU / log(SL / SR); }

/* One rod of density rho along dir in the Stokes fluid (buoyant), gravity -z,
 * at 0.9 of the stable step. */
static swModel *stokes_scene(double rho, const double dir[3], swSpec **sout) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0};
  swRodDesc r = rod_along("rod", SN, SL, SR, rho, SE, o, dir);
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  swFluidDesc f = stokes_fluid(SMU, SRHOF, 1);
  assert_int_equal(sw_spec_add_fluid(s, &f), 0);
  set_gravity_z(s);
  *sout = s;
  return sw_test_compile_at(s, 0.9);
}

/* ---- 1. sedimentation in Stokes flow ---- */

/* Claim: a straight rod sinking in Stokes flow reaches the terminal velocity
 * Suppl. eq. 1 implies: net weight per length w = (rho - rho_f) A g against
 * drag c v broadside and c v / 2 lengthwise, so v = w / c and v = 2 w / c,
 * within 1%.  The approach is exponential with time constant rho A / c
 * (broadside) and twice that lengthwise; the run lasts 20 of the longer. */
static void test_stokes_sedimentation(void **state) {
  (void)state;
  const double rho = 2000, A = M_PI * SR * SR, c = stokes_c();
  const double w = (rho - SRHOF) * A * GRAV, tau = rho * A / c;
  const double dirs[2][3] = {{1, 0, 0}, {0, 0, 1}};
  const char *what[2] = {"broadside", "lengthwise"};
  const double expect[2] = {w / c, 2 * w / c};
  for (int k = 0; k < 2; k++) {
    swSpec *s;
    swModel *m = stokes_scene(rho, dirs[k], &s);
    swData *d = sw_data_new(m);
    sw_test_run_to(m, d, 40 * tau);
    double V[3];
    com_velocity(m, d, 0, V);
    fprintf(stderr, "# %s: %s, dt = %.3g s, %ld steps, tau = %.3g s\n", __func__, what[k], m->dt,
            d->step, tau);
    char label[64];
    snprintf(label, sizeof label, "%s sinking speed (m/s)", what[k]);
    SW_EXPECT_REL(label, -V[2], expect[k], 1e-2);
    SW_EXPECT_ABS("horizontal speed (m/s)", hypot(V[0], V[1]), 0.0, 1e-12);
    /* the rod translates as a whole: no node lags */
    SW_EXPECT_ABS("largest node velocity off the mean (m/s)", velocity_spread(m, d, 0), 0.0,
                  1e-9 * expect[k]);
    sw_data_free(d);
    sw_model_free(m);
    sw_spec_free(s);
  }
}

/* ---- 2. quadratic drag ---- */

/* Claim: with F = -(1/2) rho_f C_d A |v| v and A the silhouette
 * 2 r L |sin a| + pi r^2 |cos a| (a between the axis and the velocity), a
 * rod falls at v = sqrt(2 W / (rho_f C_d A)), W its net weight, within 1%.
 * A rod of r = 1 mm, L = 0.1 m, density 1100 kg/m^3 in water (C_d = 1.2):
 * broadside (elastic rod, A = 2 r L), lengthwise (A = pi r^2, the end caps
 * only) and at 30 degrees from the vertical (rigid rods: lengthwise the
 * whole weight hangs on the end caps, which would buckle an elastic rod).
 * The approach is v_t tanh(g' t / v_t), g' = W / M; the run lasts 6 of
 * v_t / g', tanh(6) = 1 - 1.2e-5. */
static void test_quadratic_terminal(void **state) {
  (void)state;
  const double rho = 1100, rho_f = 1000, cd = 1.2, A = M_PI * SR * SR;
  const double W = (rho - rho_f) * A * SL * GRAV, gp = GRAV * (rho - rho_f) / rho;
  const double angle[3] = {M_PI / 2, 0, M_PI / 6};
  const char *what[3] = {"broadside", "lengthwise", "30 degrees"};
  for (int k = 0; k < 3; k++) {
    const double dir[3] = {sin(angle[k]), 0, cos(angle[k])}, o[3] = {0, 0, 0};
    const double area = 2 * SR * SL * fabs(sin(angle[k])) + A * fabs(cos(angle[k]));
    const double vt = sqrt(2 * W / (rho_f * cd * area));
    swSpec *s = sw_spec_new();
    swRodDesc r = rod_along("rod", SN, SL, SR, rho, SE, o, dir);
    r.rigid = k > 0;
    assert_int_equal(sw_spec_add_rod(s, &r), 0);
    swFluidDesc f = quadratic_fluid(rho_f, cd, 1);
    assert_int_equal(sw_spec_add_fluid(s, &f), 0);
    set_gravity_z(s);
    swModel *m;
    if (r.rigid) {
      /* a rigid rod has no elastic step limit: resolve the fall, v_t/g' in 400 steps */
      sw_spec_set_dt(s, vt / gp / 400);
      m = sw_test_compile(s);
    } else {
      m = sw_test_compile_at(s, 0.9);
    }
    swData *d = sw_data_new(m);
    sw_test_run_to(m, d, 6 * vt / gp);
    double V[3];
    com_velocity(m, d, 0, V);
    fprintf(stderr, "# %s: %s, dt = %.3g s, %ld steps\n", __func__, what[k], m->dt, d->step);
    char label[64];
    snprintf(label, sizeof label, "%s falling speed (m/s)", what[k]);
    SW_EXPECT_REL(label, -V[2], vt, 1e-2);
    /* drag along the velocity: no gliding sideways */
    SW_EXPECT_ABS("horizontal speed (m/s)", hypot(V[0], V[1]), 0.0, 1e-9 * vt);
    sw_data_free(d);
    sw_model_free(m);
    sw_spec_free(s);
  }
}

/* Quadratic drag has no term in the stable step (fluid.c): far above the
 * speed S m / (h rho_f C_d A) the velocity grows without bound, and the
 * check must report it, not run on. */
static void test_quadratic_instability_reported(void **state) {
  (void)state;
  const double o[3] = {0, 0, 0}, dir[3] = {1, 0, 0};
  swSpec *s = sw_spec_new();
  swRodDesc r = rod_along("rod", SN, SL, SR, 1100, SE, o, dir);
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  swFluidDesc f = quadratic_fluid(1000, 1.2, 0);
  assert_int_equal(sw_spec_add_fluid(s, &f), 0);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);
  /* rate rho_f C_d 2 r |v| / (rho pi r^2) (fluid.c) times dt = 10 */
  const double rate_per_speed = 1000 * 1.2 * 2 * SR / (1100 * M_PI * SR * SR);
  const double v0 = 10.0 / (m->dt * rate_per_speed);
  for (int i = 0; i <= SN; i++) SW_AT(m, d->v, m->node_adr[0] + i, 2) = v0;
  int rc = sw_steps(m, d, 200);
  fprintf(stderr, "# %s: v0 = %.3g m/s, dt = %.3g s: %s\n", __func__, v0, m->dt, d->error);
  assert_int_equal(rc, SW_EUNSTABLE);
  assert_non_null(strstr(d->error, "rod 'rod' became unstable"));
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* The fluid's loads alone (drag and buoyancy, sw_fluid_loads) of the
 * state, into d->ext_force. */
static void fluid_loads_only(const swModel *m, swData *d) {
  memset(d->force, 0, sizeof(double) * 3 * (size_t)m->stride);
  memset(d->ext_force, 0, sizeof(double) * 3 * (size_t)m->stride);
  sw_fluid_loads(m, d, 0, m->stride);
}

static const swFluidArea AREAS[3] = {SW_FLUID_SILHOUETTE, SW_FLUID_CROSS_SECTION,
                                     SW_FLUID_BROADSIDE};
static const char *const AREA_NAME[3] = {"silhouette", "cross_section", "broadside"};

/* Claim: a straight rod of n elements translating at w, at the angle a to
 * its axis, feels -(1/2) rho_f C_d A |w| w, element by element and in all.
 * An element's A is 2 r l |sin a| + cap |cos a| (silhouette; cap = pi r^2 / 2
 * on the rod's two end elements, 0 between), pi r^2 (cross section) or
 * 2 r l (broadside); the rod's, their sum, is 2 r L |sin a| + pi r^2 |cos a|,
 * n pi r^2 or 2 r L.  Each element's force is shared half and half by its
 * nodes, so the first element's force is twice its first node's.  Rods of
 * two and ten elements, a = 0, 30, 45, 60 and 90 degrees, to 1e-12 relative
 * (the largest error over the angles is printed). */
static void test_quadratic_areas(void **state) {
  (void)state;
  const double rho_f = 1000, cd = 1.2, speed = 0.7, o[3] = {0, 0, 0}, dir[3] = {1, 0, 0};
  const double angle_deg[5] = {0, 30, 45, 60, 90};
  const int nelem[2] = {2, SN};
  for (int k = 0; k < 3; k++) {
    for (int j = 0; j < 2; j++) {
      const int n = nelem[j];
      const double l = SL / n, cap = M_PI * SR * SR;
      swSpec *s = sw_spec_new();
      swRodDesc r = rod_along("rod", n, SL, SR, 1100, SE, o, dir);
      assert_int_equal(sw_spec_add_rod(s, &r), 0);
      swFluidDesc f = quadratic_fluid(rho_f, cd, 0);
      f.area = AREAS[k];
      assert_int_equal(sw_spec_add_fluid(s, &f), 0);
      sw_spec_set_dt(s, 1e-6);
      swModel *m = sw_test_compile(s);
      swData *d = sw_data_new(m);
      double worst_rod = 0, worst_elem = 0, F_rod = 0, F_elem = 0;
      for (int q = 0; q < 5; q++) {
        const double a = angle_deg[q] * M_PI / 180, sa = fabs(sin(a)), ca = fabs(cos(a));
        const double w[3] = {speed * cos(a), 0, speed * sin(a)};
        for (int i = 0; i <= n; i++)
          for (int c = 0; c < 3; c++) SW_AT(m, d->v, i, c) = w[c];
        fluid_loads_only(m, d);
        double A_rod, A_elem; /* the rod's and its first element's */
        if (AREAS[k] == SW_FLUID_SILHOUETTE) {
          A_rod = 2 * SR * SL * sa + cap * ca;
          A_elem = 2 * SR * l * sa + 0.5 * cap * ca;
        } else if (AREAS[k] == SW_FLUID_CROSS_SECTION) {
          A_rod = n * cap;
          A_elem = cap;
        } else {
          A_rod = 2 * SR * SL;
          A_elem = 2 * SR * l;
        }
        double F[3] = {0, 0, 0}, Fe[3], diff[3], diff_e[3], expect[3], expect_e[3];
        for (int i = 0; i <= n; i++)
          for (int c = 0; c < 3; c++) F[c] += SW_AT(m, d->ext_force, i, c);
        for (int c = 0; c < 3; c++) {
          Fe[c] = 2 * SW_AT(m, d->ext_force, 0, c);
          expect[c] = -0.5 * rho_f * cd * A_rod * speed * w[c];
          expect_e[c] = -0.5 * rho_f * cd * A_elem * speed * w[c];
          diff[c] = F[c] - expect[c];
          diff_e[c] = Fe[c] - expect_e[c];
        }
        worst_rod = fmax(worst_rod, norm3(diff) / norm3(expect));
        worst_elem = fmax(worst_elem, norm3(diff_e) / norm3(expect_e));
        if (q == 2) F_rod = norm3(F), F_elem = norm3(Fe);
      }
      fprintf(stderr, "# %s: %s, %d elements, |w| = %g m/s: at 45 degrees |F| = %.9g N on the "
              "rod, %.9g N on its first element; largest rel. error over 0-90 degrees %.3e (rod), "
              "%.3e (element)\n", __func__, AREA_NAME[k], n, speed, F_rod, F_elem, worst_rod,
              worst_elem);
      assert_true(worst_rod <= 1e-12);
      assert_true(worst_elem <= 1e-12);
      sw_data_free(d);
      sw_model_free(m);
      sw_spec_free(s);
    }
  }
}

/* Claim: the silhouette, the default area, is the quadratic drag fluid.c
 * computed before the areas existed, bit for bit.  A rod of four elements
 * at an angle, its nodes moving unevenly in a flow (so the sides, the end
 * caps and the mean velocities all count): the forces on its nodes are the
 * ones fluid.c gave at commit 7555385 (-std=c11 keeps the arithmetic free of
 * fused multiply-adds, so optimised and sanitizer builds agree), with the
 * area left at its default and set to SW_FLUID_SILHOUETTE. */
static void test_silhouette_unchanged(void **state) {
  (void)state;
  static const double before[5][3] = {
      {-0x1.d8b5616fe91bep-12, 0x1.b931d268732b3p-14, -0x1.f0580cb581908p-12},
      {-0x1.d388d9e9ea454p-9, 0x1.edb61de9ad6ddp-9, -0x1.cd0dcf4ed0d33p-10},
      {-0x1.acaf1b25c56f6p-7, 0x1.dabcd2ac8b67p-6, -0x1.9f586980823b4p-10},
      {-0x1.0cf9187ec0642p-5, 0x1.e9462f0e34975p-4, 0x1.3d997746ee15fp-8},
      {-0x1.76a8e9221bb4cp-6, 0x1.81965eddc50c3p-4, 0x1.51319e9eb289p-8},
  };
  for (int given = 0; given < 2; given++) {
    swSpec *s = sw_spec_new();
    const double o[3] = {0.01, -0.02, 0.03}, dir[3] = {0.6, 0.0, 0.8};
    swRodDesc r = sw_test_rod("rod", 4, 0.1, 1e-3, o, dir, NULL);
    r.density = 1100;
    r.youngs = 1e6;
    r.poisson = 0.5;
    assert_int_equal(sw_spec_add_rod(s, &r), 0);
    swFluidDesc f = quadratic_fluid(1000, 1.2, 0);
    if (given) f.area = SW_FLUID_SILHOUETTE;
    f.velocity[0] = 0.05;
    f.velocity[1] = -0.03;
    f.velocity[2] = 0.01;
    assert_int_equal(sw_spec_add_fluid(s, &f), 0);
    sw_spec_set_dt(s, 1e-6);
    swModel *m = sw_test_compile(s);
    swData *d = sw_data_new(m);
    for (int i = 0; i <= 4; i++) {
      SW_AT(m, d->v, i, 0) = 0.3 + 0.1 * i;
      SW_AT(m, d->v, i, 1) = -0.2 * i * i;
      SW_AT(m, d->v, i, 2) = 0.4 - 0.15 * i;
    }
    fluid_loads_only(m, d);
    double worst = 0, largest = 0;
    for (int i = 0; i <= 4; i++)
      for (int c = 0; c < 3; c++) {
        worst = fmax(worst, fabs(SW_AT(m, d->ext_force, i, c) - before[i][c]));
        largest = fmax(largest, fabs(before[i][c]));
      }
    fprintf(stderr, "# %s: area %s: largest node force %.17g N, largest difference from before "
            "%.3e N\n", __func__, given ? "= SW_FLUID_SILHOUETTE" : "left at its default", largest,
            worst);
    assert_true(worst == 0.0);
    sw_data_free(d);
    sw_model_free(m);
    sw_spec_free(s);
  }
}

/* Claim: quadratic drag's speed limit (fluid.c, "Step limit") holds with
 * each area's A_e: a rod moving broadside as a whole at v has the secant
 * rate k v = rho_f C_d A_e v / (2 m_e) (m_e = rho pi r^2 l an element's
 * mass; A_e = 2 r l for the silhouette and broadside, pi r^2 for the cross
 * section), and position Verlet's kick multiplies v by 1 - h k v exactly.
 * The Jacobian's bound puts the limit at h k v = S / 2 = 1; the velocity
 * really grows past h k v = S = 2.  So at h k v = 1.9 the first kick
 * multiplies v by -0.9 (to 1e-12) and the run stays stable over 200 steps,
 * decaying; at h k v = 2.1 the check reports the rod unstable. */
static void test_quadratic_speed_limit(void **state) {
  (void)state;
  const double rho = 1100, rho_f = 1000, cd = 1.2, o[3] = {0, 0, 0}, dir[3] = {1, 0, 0};
  const double l = SL / SN, m_e = rho * M_PI * SR * SR * l;
  for (int k = 0; k < 3; k++) {
    const double A_e = AREAS[k] == SW_FLUID_CROSS_SECTION ? M_PI * SR * SR : 2 * SR * l;
    for (int over = 0; over < 2; over++) {
      const double hkv = over ? 2.1 : 1.9;
      swSpec *s = sw_spec_new();
      swRodDesc r = rod_along("rod", SN, SL, SR, rho, SE, o, dir);
      assert_int_equal(sw_spec_add_rod(s, &r), 0);
      swFluidDesc f = quadratic_fluid(rho_f, cd, 0);
      f.area = AREAS[k];
      assert_int_equal(sw_spec_add_fluid(s, &f), 0);
      swModel *m = sw_test_compile_at(s, 0.9);
      swData *d = sw_data_new(m);
      const double v0 = hkv / (m->dt * rho_f * cd * A_e / (2 * m_e));
      for (int i = 0; i <= SN; i++) SW_AT(m, d->v, m->node_adr[0] + i, 2) = v0;
      if (!over) {
        assert_int_equal(sw_steps(m, d, 1), SW_OK);
        double V[3];
        com_velocity(m, d, 0, V);
        fprintf(stderr, "# %s: %s, dt = %.3g s, v0 = %.4g m/s (h k v0 = 1.9; the Jacobian's "
                "limit %.4g m/s)\n", __func__, AREA_NAME[k], m->dt, v0, v0 / 1.9);
        SW_EXPECT_REL("first kick: v1 / v0", V[2] / v0, 1 - hkv, 1e-12);
        assert_int_equal(sw_steps(m, d, 199), SW_OK);
        com_velocity(m, d, 0, V);
        fprintf(stderr, "# %s: %s: |v| / v0 after 200 steps %.3e\n", __func__, AREA_NAME[k],
                fabs(V[2]) / v0);
        assert_true(fabs(V[2]) < 0.1 * v0);
      } else {
        int rc = sw_steps(m, d, 200);
        fprintf(stderr, "# %s: %s, v0 = %.4g m/s (h k v0 = 2.1): %s after %ld steps: %s\n",
                __func__, AREA_NAME[k], v0, rc == SW_OK ? "stable" : "unstable", d->step, d->error);
        assert_int_equal(rc, SW_EUNSTABLE);
        assert_non_null(strstr(d->error, "rod 'rod' became unstable"));
      }
      sw_data_free(d);
      sw_model_free(m);
      sw_spec_free(s);
    }
  }
}

/* ---- 3. buoyancy ---- */

/* Claim: a rod as dense as the fluid stays put.  Weight and buoyancy of each
 * element are the same product rho pi r^2 l^ g formed in two orders, so they
 * cancel to a rounding, 1e-16 of the weight; the bound asks that the rod
 * move less than a rod whose density differs from the fluid's by 1e-10 would
 * (at its terminal velocity, from the start), a hundred thousand times the
 * rounding and a million times below any density a model would state.
 * Then a rod of half the fluid's density rises broadside at
 * (rho_f - rho) A g / c within 1%. */
static void test_buoyancy(void **state) {
  (void)state;
  const double A = M_PI * SR * SR, c = stokes_c(), dir[3] = {1, 0, 0};
  swSpec *s;
  swModel *m = stokes_scene(SRHOF, dir, &s);
  swData *d = sw_data_new(m);
  const double T = 20 * SRHOF * A / c;
  sw_test_run_to(m, d, T);
  double moved = 0;
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
      for (int k = 0; k < 3; k++)
        moved = fmax(moved, fabs(SW_AT(m, d->x, i, k) - SW_AT(m, m->x0, i, k)));
  const double bound = 1e-10 * SRHOF * A * GRAV / c * T;
  fprintf(stderr, "# %s: neutral rod over %.3g s (%ld steps): largest displacement %.3e m, "
          "bound %.3e m\n", __func__, T, d->step, moved, bound);
  assert_true(moved <= bound);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);

  const double rho = 0.5 * SRHOF, tau = rho * A / c;
  m = stokes_scene(rho, dir, &s);
  d = sw_data_new(m);
  sw_test_run_to(m, d, 40 * tau);
  double V[3];
  com_velocity(m, d, 0, V);
  SW_EXPECT_REL("rising speed (m/s)", V[2], (SRHOF - rho) * A * GRAV / c, 1e-2);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 4. a uniform flow ---- */

/* Claim: a rod at rest in a uniform Stokes flow u is carried at u.  With no
 * gravity the rod translates as a whole, and its velocity relaxes towards u
 * componentwise, at the rate k = c / (rho A) across its axis and k / 2 along
 * it.  Position Verlet's kick sees the velocity from before it, so the
 * relaxation is v_n = u (1 - (1 - h k)^n) exactly (checked to rounding), and
 * the continuous u (1 - exp(-k t)) at first order in h (measured at t = 1/k
 * for h and h/2).  At the end (30 / k along the axis) v = u within 1e-6. */
static double carried(double frac, double u[3], double t_end, double *err_discrete,
                      double *err_continuous, double V[3], double *dt) {
  const double o[3] = {0, 0, 0}, dir[3] = {1, 0, 0}, rho = 1200, A = M_PI * SR * SR;
  const double k = stokes_c() / (rho * A);
  swSpec *s = sw_spec_new();
  swRodDesc r = rod_along("rod", SN, SL, SR, rho, SE, o, dir);
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  swFluidDesc f = stokes_fluid(SMU, SRHOF, 0);
  for (int q = 0; q < 3; q++) f.velocity[q] = u[q];
  assert_int_equal(sw_spec_add_fluid(s, &f), 0);
  swModel *m = sw_test_compile_at(s, frac);
  swData *d = sw_data_new(m);
  const long n1 = lround(ceil(1.0 / (k * m->dt)));
  assert_int_equal(sw_steps(m, d, n1), SW_OK);
  com_velocity(m, d, 0, V);
  /* across (x is the axis): y, z at rate k; along: x at k / 2 */
  const double rate[3] = {0.5 * k, k, k};
  *err_discrete = 0;
  *err_continuous = 0;
  for (int q = 0; q < 3; q++) {
    double exact_n = u[q] * (1 - pow(1 - m->dt * rate[q], (double)n1));
    double exact_t = u[q] * (1 - exp(-rate[q] * d->time));
    *err_discrete = fmax(*err_discrete, fabs(V[q] - exact_n) / norm3(u));
    *err_continuous = fmax(*err_continuous, fabs(V[q] - exact_t) / norm3(u));
  }
  sw_test_run_to(m, d, t_end);
  com_velocity(m, d, 0, V);
  *dt = m->dt;
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return k;
}

static void test_uniform_flow_carries(void **state) {
  (void)state;
  double u[3] = {0.02, -0.01, 0.005}, V[3], ed[2], ec[2], dt[2];
  double k = carried(0.9, u, 0, &ed[0], &ec[0], V, &dt[0]);
  carried(0.45, u, 30 * 2 / k, &ed[1], &ec[1], V, &dt[1]);
  fprintf(stderr, "# %s: k = %.4g 1/s, h k = %.3g and %.3g\n", __func__, k, dt[0] * k, dt[1] * k);
  SW_EXPECT_ABS("velocity vs the discrete relaxation, h (rel. to |u|)", ed[0], 0.0, 1e-12);
  SW_EXPECT_ABS("velocity vs the discrete relaxation, h/2 (rel. to |u|)", ed[1], 0.0, 1e-12);
  fprintf(stderr, "# %s: error vs exp relaxation at t = 1/k: %.3e (h), %.3e (h/2)\n", __func__,
          ec[0], ec[1]);
  SW_EXPECT_REL("order of the relaxation in h", log(ec[0] / ec[1]) / log(2.0), 1.0, 0.1);
  double dv[3] = {V[0] - u[0], V[1] - u[1], V[2] - u[2]};
  SW_EXPECT_ABS("|v - u| / |u| at the end", norm3(dv) / norm3(u), 0.0, 1e-6);
}

/* ---- 5. rod lists ---- */

/* A fluid acts on the rods it lists and no others: of two rods side by side,
 * the listed one sinks at w / c, the other falls freely (v = g t). */
static void test_fluid_rod_list(void **state) {
  (void)state;
  const double rho = 2000, A = M_PI * SR * SR, c = stokes_c(), tau = rho * A / c;
  swSpec *s = sw_spec_new();
  const double o0[3] = {0, 0, 0}, o1[3] = {0, 0.05, 0}, dir[3] = {1, 0, 0};
  swRodDesc r0 = rod_along("free", SN, SL, SR, rho, SE, o0, dir);
  swRodDesc r1 = rod_along("immersed", SN, SL, SR, rho, SE, o1, dir);
  assert_int_equal(sw_spec_add_rod(s, &r0), 0);
  assert_int_equal(sw_spec_add_rod(s, &r1), 1);
  swFluidDesc f = stokes_fluid(SMU, SRHOF, 1);
  const int only[1] = {1};
  f.nrods = 1;
  f.rods = only;
  assert_int_equal(sw_spec_add_fluid(s, &f), 0);
  set_gravity_z(s);
  swModel *m = sw_test_compile_at(s, 0.9);
  swData *d = sw_data_new(m);
  sw_test_run_to(m, d, 40 * tau);
  double V0[3], V1[3];
  com_velocity(m, d, 0, V0);
  com_velocity(m, d, 1, V1);
  SW_EXPECT_REL("unlisted rod: falling speed (m/s)", -V0[2], GRAV * d->time, 1e-9);
  SW_EXPECT_REL("listed rod: sinking speed (m/s)", -V1[2], (rho - SRHOF) * A * GRAV / c, 1e-2);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 6. energy ---- */

/* Claim: drag and buoyancy are external loads whose work the kick books, so
 * kinetic + elastic - work stays constant to the integrator's error while
 * the fluid takes energy out.  A free rod, bent into its first mode by an
 * initial velocity (sin profile across it), sinks and vibrates in a Stokes
 * fluid (with a flow and buoyancy) under position Verlet, and in a
 * quadratic one under PEFRL.  The kick books the work of the fluid's loads
 * as exactly the kinetic energy they add in it (midpoint rule), so the
 * fluid adds no error of its own: the largest balance drift over the run
 * must fall with the step at the scheme's order (2 for Verlet, 4 for PEFRL,
 * measured between 0.8 and 0.4 of the stable step), and stay below 1e-3 of
 * the work the fluid did. */
static double energy_drift(swFluidModel model, swIntegrator integ, double frac, double *fluid_work) {
  const double o[3] = {0, 0, 0}, dir[3] = {1, 0, 0}, rho = 1500;
  swSpec *s = sw_spec_new();
  swRodDesc r = rod_along("rod", SN, SL, SR, rho, SE, o, dir);
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  swFluidDesc f = model == SW_FLUID_STOKES ? stokes_fluid(0.05, SRHOF, 1)
                                           : quadratic_fluid(SRHOF, 1.2, 1);
  f.velocity[0] = 0.01;
  f.velocity[1] = 0.02;
  assert_int_equal(sw_spec_add_fluid(s, &f), 0);
  set_gravity_z(s);
  sw_spec_set_integrator(s, integ);
  swModel *m = sw_test_compile_at(s, frac);
  swData *d = sw_data_new(m);
  for (int i = 0; i <= SN; i++) SW_AT(m, d->v, m->node_adr[0] + i, 2) = 0.2 * sin(M_PI * i / SN);
  double e0[3], e1[3], drift = 0;
  sw_energy(m, d, e0);
  const double z0 = com_height(m, d, 0);
  /* the largest drift at 50 instants (the balance error oscillates with the
   * vibration, so one instant could fall near a zero of it) */
  for (int j = 1; j <= 50; j++) {
    sw_test_run_to(m, d, 0.02 * j / 50);
    sw_energy(m, d, e1);
    double dj = (e1[0] + e1[1] - e1[2]) - (e0[0] + e0[1] - e0[2]);
    if (fabs(dj) > fabs(drift)) drift = dj;
  }
  const double z1 = com_height(m, d, 0);
  /* the work of weight and buoyancy is the net weight times the drop of the
   * centre of mass; the rest is the drag's */
  double M = 0;
  for (int i = 0; i <= SN; i++) M += m->mass[m->node_adr[0] + i];
  *fluid_work = (e1[2] - e0[2]) - M * (1 - SRHOF / rho) * GRAV * (z0 - z1);
  fprintf(stderr, "#   dt = %.3g s, %ld steps: kinetic %.4e -> %.4e J, elastic %.3e J, "
          "drag work %.4e J, largest balance drift %.3e J\n", m->dt, d->step, e0[0], e1[0], e1[1],
          *fluid_work, drift);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return drift;
}

static void test_energy_balance(void **state) {
  (void)state;
  const swFluidModel model[2] = {SW_FLUID_STOKES, SW_FLUID_QUADRATIC};
  const swIntegrator integ[2] = {SW_VERLET, SW_PEFRL};
  const char *what[2] = {"Stokes, Verlet", "quadratic, PEFRL"};
  const double order[2] = {2, 4};
  for (int k = 0; k < 2; k++) {
    fprintf(stderr, "# %s: %s\n", __func__, what[k]);
    double wf, wf2;
    double e = energy_drift(model[k], integ[k], 0.8, &wf);
    double e2 = energy_drift(model[k], integ[k], 0.4, &wf2);
    assert_true(wf < 0); /* the fluid takes energy out */
    SW_EXPECT_ABS("balance drift / drag work at h", fabs(e / wf), 0.0, 1e-3);
    SW_EXPECT_ABS("balance drift / drag work at h/2", fabs(e2 / wf2), 0.0, 1e-3);
    SW_EXPECT_REL("order of the balance drift", log(fabs(e / e2)) / log(2.0), order[k], 0.25);
  }
}

/* ---- 7. stable step ---- */

/* Claim: the Stokes drag's step limit is 0.95 S rho A / c for a uniform rod
 * (S = 2 for position Verlet; for PEFRL the root of
 * (1 - a s)(1 + b s) = -1 with the kick lengths a = (1 - 2 lambda)/2 and
 * -b = lambda of Omelyan et al. 2002, eq. 20), and it is real: a thin rod
 * (r = 0.1 mm, L = 2 cm, E = 0.1 MPa) in a viscous fluid (mu = 10 Pa s, so
 * the drag's limit is a fifth of the rod's elastic one) runs at the
 * estimate and blows up 3% above the limit itself.  Where the two limits
 * meet (mu chosen so that S rho A / c equals the elastic estimate / 0.95),
 * drag and elastic waves together are still stable at the estimate: the
 * drag, taken on each element's mean velocity, does not damp the zig-zag
 * modes that set the elastic limit (fluid.c). */
static double pefrl_damper_limit(void) {
  const double lambda = -0.2123418310626054, a = 0.5 * (1 - 2 * lambda), b = -lambda;
  /* a b s^2 + (a - b) s - 2 = 0 */
  return (-(a - b) + sqrt((a - b) * (a - b) + 8 * a * b)) / (2 * a * b);
}

static int run_thread(swSpec *s, double dt, long steps, const char *what) {
  sw_spec_set_dt(s, dt);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  int rc = sw_steps(m, d, steps);
  fprintf(stderr, "#   %s: %s after %ld steps%s%s\n", what, rc == SW_OK ? "stable" : "unstable",
          d->step, rc == SW_OK ? "" : ": ", d->error);
  sw_data_free(d);
  sw_model_free(m);
  return rc;
}

static void test_stokes_stable_dt(void **state) {
  (void)state;
  const double r = 1e-4, L = 0.02, rho = 1000, A = M_PI * r * r, o[3] = {0, 0, 0}, dir[3] = {1, 0, 0};
  const swIntegrator integ[2] = {SW_VERLET, SW_PEFRL};
  const double S[2] = {2.0, pefrl_damper_limit()};
  const long steps = sw_test_sanitized() ? 5000 : 20000;
  for (int k = 0; k < 2; k++) {
    for (int crossover = 0; crossover < 2; crossover++) {
      swSpec *s = sw_spec_new();
      swRodDesc rd = rod_along("thread", SN, L, r, rho, 1e5, o, dir);
      assert_int_equal(sw_spec_add_rod(s, &rd), 0);
      sw_spec_set_integrator(s, integ[k]);
      double mu = 10;
      if (crossover) { /* the viscosity whose drag limit is the elastic one */
        swModel *me = sw_test_compile(s);
        double rate = S[k] / (me->rod_wave_dt[0] / 0.95);
        mu = rate * rho * A * log(L / r) / (4 * M_PI);
        sw_model_free(me);
      }
      const double c = 4 * M_PI * mu / log(L / r), limit = S[k] / (c / (rho * A));
      swFluidDesc f = stokes_fluid(mu, 1200, 1);
      f.velocity[1] = 0.01;
      assert_int_equal(sw_spec_add_fluid(s, &f), 0);
      set_gravity_z(s);
      swModel *m0 = sw_test_compile(s);
      const double est = sw_stable_dt(m0);
      fprintf(stderr, "# %s: %s, mu = %.4g Pa s: elastic estimate %.4g s, drag limit S rho A / c "
              "= %.4g s (S = %.6f)\n", __func__, k ? "PEFRL" : "Verlet", mu, m0->rod_wave_dt[0],
              limit, S[k]);
      /* the runtime takes S from the damped oscillator's limit at a damping
       * ratio of 1e4, within 1e-8 of the pure damper's (fluid.c) */
      SW_EXPECT_REL("stable dt estimate (s)", est, 0.95 * limit, 1e-7);
      if (!crossover) assert_true(m0->rod_wave_dt[0] > 4 * est); /* the drag sets the step */
      sw_model_free(m0);
      assert_int_equal(run_thread(s, est, steps, "dt = the estimate"), SW_OK);
      assert_int_equal(run_thread(s, 1.03 * limit, steps, "dt = 1.03 of the limit"), SW_EUNSTABLE);
      sw_spec_free(s);
    }
  }
}

/* ---- 8. validation ---- */

static void expect_error(const swFluidDesc *f, double rod_length, const char *message) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, dir[3] = {1, 0, 0};
  swRodDesc r = rod_along("stub", 4, rod_length, 2e-3, 1000, 1e6, o, dir);
  assert_int_equal(sw_spec_add_rod(s, &r), 0);
  assert_int_equal(sw_spec_add_fluid(s, f), 0);
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  fprintf(stderr, "# %s\n", err);
  assert_null(m);
  assert_string_equal(err, message);
  sw_spec_free(s);
}

static void test_validation(void **state) {
  (void)state;
  swFluidDesc f = stokes_fluid(0, SRHOF, 0);
  f.name = "water";
  expect_error(&f, 0.1, "fluid 'water': Stokes drag needs a viscosity > 0");
  f = quadratic_fluid(0, 1.2, 0);
  expect_error(&f, 0.1, "fluid 'air': quadratic drag needs a density > 0");
  f = quadratic_fluid(1.2, 0, 0);
  expect_error(&f, 0.1, "fluid 'air': quadratic drag needs a drag coefficient > 0");
  f = stokes_fluid(1, 0, 1);
  expect_error(&f, 0.1, "fluid 'water': buoyancy needs a density > 0");
  f = stokes_fluid(1, SRHOF, 0);
  f.name = "goo";
  f.body_length = 1e-3;
  expect_error(&f, 0.1, "fluid 'goo': slender-body drag on rod 'stub' needs the body length "
                        "(0.001 m) to exceed the radius of element 0 (0.002 m)");
  /* the rod's own length when body_length is 0 */
  f.body_length = 0;
  expect_error(&f, 1.5e-3, "fluid 'goo': slender-body drag on rod 'stub' needs the body length "
                           "(0.0015 m) to exceed the radius of element 0 (0.002 m)");
  const int bad[1] = {3};
  f = stokes_fluid(1, SRHOF, 0);
  f.nrods = 1;
  f.rods = bad;
  expect_error(&f, 0.1, "fluid 'water': rod 3 does not exist (the scene has 1)");
  /* a rod listed twice would be dragged twice */
  const int twice[2] = {0, 0};
  f.nrods = 2;
  f.rods = twice;
  expect_error(&f, 0.1, "fluid 'water': rod 0 is listed twice");
  f = quadratic_fluid(1.2, 1.2, 0);
  f.area = (swFluidArea)3;
  expect_error(&f, 0.1, "fluid 'air': unknown drag area 3");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_validation),
      cmocka_unit_test(test_stokes_sedimentation),
      cmocka_unit_test(test_quadratic_terminal),
      cmocka_unit_test(test_quadratic_instability_reported),
      cmocka_unit_test(test_quadratic_areas),
      cmocka_unit_test(test_silhouette_unchanged),
      cmocka_unit_test(test_quadratic_speed_limit),
      cmocka_unit_test(test_buoyancy),
      cmocka_unit_test(test_uniform_flow_carries),
      cmocka_unit_test(test_fluid_rod_list),
      cmocka_unit_test(test_energy_balance),
      cmocka_unit_test(test_stokes_stable_dt),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
