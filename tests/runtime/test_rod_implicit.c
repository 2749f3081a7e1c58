/* test_rod_implicit.c — rods with linearly implicit elasticity under imex
 * (rod_implicit.c), against independent references:
 *   tangent: on a stress-free helix (rest shape = current shape, so every
 *     load-times-lever term of the exact Jacobian vanishes) the assembled
 *     stiffness equals the central-difference Jacobian of rod.c's loads
 *     (variational law; Gazzola's differs by its missing beta term);
 *   energy: a free rod hardened x25 and x100 in shear and twist, given
 *     random small velocities, keeps its energy to the trapezoidal rule's
 *     error at 10 and 100 times the explicit stable step, where explicit
 *     Verlet blows up;
 *   statics: the damped Timoshenko cantilever (the closed form of
 *     test_statics) relaxes to its tip deflection at 30 times the explicit
 *     step;
 *   order: the undamped cantilever's tip under a smoothly growing load
 *     converges at second order in dt, all steps above the explicit limit;
 *   kept factorisations: with the factorisation kept over many kicks, the
 *     same cantilever still converges at second order below the explicit
 *     limit (where nearly every kick keeps it), a free rod turning at 3
 *     rad/s keeps it against making it every kick at second order too,
 *     and the free rod's energy at 10 times the explicit step stays near
 *     its start over 20000 steps without drifting;
 *   an explicit joint on implicit rods: its estimate is its own row (the
 *     rods' stiffness cancels), stable below it and not above;
 *   threads: one and two threads give the same bits. */
#include "testutil.h"
#include "internal.h"
#include "vec.h"

/* A straight rod along x, normal z, of the snake's section (r = 25 mm, E =
 * 10 MPa, G = 2E/3, rho = 1000), hardened by `hard` in shear and twist. */
static swRodDesc snake_rod(int n, double hard, int implicit) {
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "body";
  r.nelem = n;
  r.length = 1.0;
  r.radius_start = r.radius_end = 0.025;
  r.density = 1000;
  r.youngs = 1e7;
  r.shear_modulus = 2e7 / 3;
  r.shear_hardening = r.twist_hardening = hard;
  r.implicit = implicit;
  r.direction[0] = 1, r.direction[1] = 0, r.direction[2] = 0;
  r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
  return r;
}

/* The generalized loads of rod 0: node forces (lab), element couples
 * (material), in the unknowns' order v_0, w_0, v_1, ... */
static void loads(const swModel *m, swData *d, int n, double *f) {
  sw_internal_loads(m, d);
  for (int i = 0; i <= n; i++)
    for (int k = 0; k < 3; k++) f[6 * i + k] = SW_AT(m, d->force, i, k);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) f[6 * i + 3 + k] = SW_AT(m, d->torque, i, k);
}

/* Turn element e by a about material axis k, the drift's convention
 * Q <- exp(-a [e_k]x) Q (integrate.c). */
static void turn(const swModel *m, swData *d, int e, int k, double a) {
  double Q[9], phi[3] = {0, 0, 0};
  sw_getQ(m, d->Q, e, Q);
  phi[k] = a;
  sw_rotate_frame(Q, phi);
  for (int p = 0; p < 9; p++) SW_AT(m, d->Q, e, p) = Q[p];
}

/* Largest |K_pq - J_pq| / sqrt(K_pp K_qq) on a helix turned phi per
 * element (material axes), J the central differences of the loads, under
 * constitutive law `law`, its nodes stretched by `stretch` (0: at rest). */
static double tangent_error(swLaw law, const double *turn_by, double stretch) {
  const int n = 8, N = 3 * (2 * n + 1), B = SW_IMPLICIT_BAND;
  swSpec *s = sw_spec_new();
  swRodDesc r = snake_rod(n, 25, 1);
  r.length = 0.16;
  r.law = law;
  const int id = sw_spec_add_rod(s, &r);
  /* a helix: each frame turned from the last by phi = (0.3, 0.1, 0.25) rad
   * about material axes, each node one rest length along its element's d3 */
  double x[3 * 9], Q[9 * 8], phi[3] = {turn_by[0], turn_by[1], turn_by[2]};
  sw_frame_from(Q, r.direction, r.normal);
  for (int i = 1; i < n; i++) {
    memcpy(Q + 9 * i, Q + 9 * (i - 1), sizeof(double) * 9);
    sw_rotate_frame(Q + 9 * i, phi);
  }
  memset(x, 0, sizeof x);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) x[3 * (i + 1) + k] = x[3 * i + k] + r.length / n * Q[9 * i + 6 + k];
  assert_int_equal(sw_spec_set_rest_shape(s, id, x, Q), SW_OK);
  sw_spec_set_integrator(s, SW_IMEX);
  sw_spec_set_dt(s, 1e-5);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  double *K = calloc((size_t)N * (B + 1), sizeof(double)), *fp = calloc(N, sizeof(double)),
         *fm = calloc(N, sizeof(double));
  assert_true(d && K && fp && fm);
  for (int i = 0; i <= n; i++) /* taut: every node moved out from node 0 */
    for (int k = 0; k < 3; k++) SW_AT(m, d->x, i, k) *= 1 + stretch;
  loads(m, d, n, fp); /* the strains K is taken at */
  sw_implicit_stiffness(m, d, id, K);
  double worst = 0, largest = 0, rest = 0, diag[3 * (2 * 8 + 1)];
  for (int q = 0; q < N; q++) diag[q] = K[(size_t)q * (B + 1) + B];
  loads(m, d, n, fp);
  for (int q = 0; q < N; q++) rest = fmax(rest, fabs(fp[q]));
  const double dx = 1e-7, da = 1e-6;
  for (int p = 0; p < N; p++) { /* column p of -df/du by central differences */
    const int slot = p / 6, k = p % 3, is_rot = p % 6 >= 3;
    const double del = is_rot ? da : dx;
    if (is_rot) turn(m, d, slot, k, del); else SW_AT(m, d->x, slot, k) += del;
    loads(m, d, n, fp);
    if (is_rot) turn(m, d, slot, k, -2 * del); else SW_AT(m, d->x, slot, k) -= 2 * del;
    loads(m, d, n, fm);
    if (is_rot) turn(m, d, slot, k, del); else SW_AT(m, d->x, slot, k) += del;
    for (int q = 0; q < N; q++) {
      const double fd = -(fp[q] - fm[q]) / (2 * del);
      const int i = q > p ? q : p, j = q > p ? p : q;
      const double ours = i - j <= B ? K[(size_t)i * (B + 1) + (size_t)(B - (i - j))] : 0.0;
      /* against the entry's natural scale sqrt(K_pp K_qq): the bending
       * entries are 1e5 times smaller than the stretching ones */
      worst = fmax(worst, fabs(fd - ours) / sqrt(diag[p] * diag[q]));
      largest = fmax(largest, fabs(fd));
    }
  }
  if (stretch == 0) assert_true(rest < 1e-9 * largest * r.length);
  free(K), free(fp), free(fm);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return worst;
}

static void test_tangent_helix(void **state) {
  (void)state;
  /* the variational law's loads are the energy's exact gradient (rod.c),
   * so at rest K is their exact Jacobian; Gazzola's bending couple lacks
   * the beta phi x (phi x c) term, so its Jacobian differs from K by about
   * beta theta^2 = theta^2/12 (and is not symmetric) */
  const double th2 = 0.3 * 0.3 + 0.1 * 0.1 + 0.25 * 0.25;
  const double helix[3] = {0.3, 0.1, 0.25};
  const double var = tangent_error(SW_LAW_VARIATIONAL, helix, 0);
  const double gaz = tangent_error(SW_LAW_GAZZOLA, helix, 0);
  fprintf(stderr, "# %s: helix turned (0.3, 0.1, 0.25) rad per element, x25, at rest: largest "
          "|K_pq - finite-difference Jacobian_pq| / sqrt(K_pp K_qq) = %.3e (variational law), "
          "%.3e (Gazzola's; theta^2/12 = %.3e)\n", __func__, var, gaz, th2 / 12);
  assert_true(var < 1e-6);
  assert_true(gaz < th2 / 6);
}

/* A straight rod stretched 1e-3 carries a tension T = E A 1e-3: the
 * tension's turn with each element (rod_implicit.c, the geometric terms of
 * shear_block) is then part of the loads' Jacobian, and of K.  Under the
 * variational law the loads are the energy's gradient, so K matches the
 * finite differences to their own precision: 2.9e-11 of the entries'
 * scale; without the terms it is their size, 4.5e-5 (measured with them
 * switched off). */
static void test_tangent_tension(void **state) {
  (void)state;
  const double straight[3] = {0, 0, 0};
  const double taut = tangent_error(SW_LAW_VARIATIONAL, straight, 1e-3);
  fprintf(stderr, "# %s: straight rod stretched 1e-3 (variational law): largest |K_pq - "
          "finite-difference Jacobian_pq| / sqrt(K_pp K_qq) = %.3e\n", __func__, taut);
  assert_true(taut < 1e-6);
}

/* Kinetic + elastic energy of a free rod started with random small
 * velocities, after `steps` steps at `frac` times the explicit estimate;
 * rc the first non-OK step's code. */
/* Random small velocities on the 50-element rod: up to 0.5 mm/s on the
 * nodes, 5 mrad/s on the elements (a fixed seed). */
static void random_velocities(const swModel *m, swData *d) {
  unsigned seed = 12345;
  for (int i = 0; i <= 50; i++)
    for (int k = 0; k < 3; k++) {
      seed = seed * 1103515245u + 12345u;
      SW_AT(m, d->v, i, k) = 1e-3 * ((seed >> 8) / 16777216.0 - 0.5);
    }
  for (int i = 0; i < 50; i++)
    for (int k = 0; k < 3; k++) {
      seed = seed * 1103515245u + 12345u;
      SW_AT(m, d->omega, i, k) = 1e-2 * ((seed >> 8) / 16777216.0 - 0.5);
    }
}

static double free_rod_energy(double hard, int implicit, double frac, int steps, double *e0,
                              int *rc) {
  swSpec *s = sw_spec_new();
  swRodDesc r = snake_rod(50, hard, implicit);
  sw_spec_add_rod(s, &r);
  swModel *m0 = sw_test_compile(s);
  const double explicit_dt = sw_stable_dt(m0);
  sw_model_free(m0);
  sw_spec_set_integrator(s, SW_IMEX);
  sw_spec_set_dt(s, frac * explicit_dt);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  random_velocities(m, d);
  double e[3];
  sw_energy(m, d, e);
  *e0 = e[0] + e[1];
  *rc = SW_OK;
  for (int k = 0; k < steps && *rc == SW_OK; k++) *rc = sw_step(m, d);
  sw_energy(m, d, e);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return e[0] + e[1];
}

static void test_free_rod_energy(void **state) {
  (void)state;
  const double hards[2] = {25, 100}, fracs[2] = {10, 100};
  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2; b++) {
      double e0;
      int rc;
      const double e1 = free_rod_energy(hards[a], 1, fracs[b], 2000, &e0, &rc);
      fprintf(stderr, "# %s: x%.0f at %.0f x the explicit step, 2000 steps: energy %.6e -> %.6e "
              "(drift %.2e)\n", __func__, hards[a], fracs[b], e0, e1, e1 / e0 - 1);
      assert_int_equal(rc, SW_OK);
      assert_true(fabs(e1 / e0 - 1) < 1e-2);
      if (b == 0) { /* explicit Verlet at the same step does not survive */
        const double ex = free_rod_energy(hards[a], 0, fracs[b], 2000, &e0, &rc);
        fprintf(stderr, "#   explicit at the same step: rc %d, energy %.3e\n", rc, ex);
        assert_int_not_equal(rc, SW_OK);
      }
    }
}

/* The Timoshenko cantilever of test_statics (L = 3 m, r = 0.25 m, E = 1
 * MPa, G = 10 kPa, tip load 0.15 N), with linear damping near critical
 * for the first mode, relaxed at `frac` times its explicit step. */
static const double TL = 3.0, TR = 0.25, TE = 1e6, TG = 1e4, TF = 0.15;

static swSpec *cantilever(int n, double gamma, double load, swSignal signal) {
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "beam";
  r.nelem = n;
  r.direction[0] = 1, r.direction[1] = 0, r.direction[2] = 0;
  r.normal[0] = 0, r.normal[1] = 0, r.normal[2] = 1;
  r.length = TL;
  r.radius_start = r.radius_end = TR;
  r.density = 1000;
  r.youngs = TE;
  r.shear_modulus = TG;
  r.damping = SW_DAMP_LINEAR;
  r.gamma = gamma;
  r.implicit = 1;
  int id = sw_spec_add_rod(s, &r);
  swBCDesc c = sw_test_clamp(id, 0);
  sw_spec_add_bc(s, &c);
  swLoadDesc f = sw_test_load(SW_LOAD_FORCE, id, -1, 0, -load, 0);
  f.signal = signal;
  sw_spec_add_load(s, &f);
  return s;
}

static void test_timoshenko_implicit(void **state) {
  (void)state;
  const int n = sw_test_sanitized() ? 20 : 100;
  const double A = M_PI * TR * TR, I = A * TR * TR / 4.0;
  const double w1 = 1.8751 * 1.8751 / (TL * TL) * sqrt(TE * I / (1000 * A));
  swSpec *s = cantilever(n, 2.0 * w1 * 1000 * A, TF, sw_signal_const(1.0));
  swModel *m0 = sw_test_compile(s); /* Verlet: the explicit estimate */
  const double explicit_dt = sw_stable_dt(m0);
  sw_model_free(m0);
  sw_spec_set_integrator(s, SW_IMEX);
  sw_spec_set_dt(s, 30 * explicit_dt);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double *tip_y = &SW_AT(m, d->x, n, 1);
  const double y = sw_test_relax(m, d, tip_y, 2.0, 400.0, 1e-9);
  const double exact = TF * TL * TL * TL / (3.0 * TE * I) + TF * TL / (4.0 / 3.0 * TG * A);
  fprintf(stderr, "# %s: n = %d, dt = 30 x the explicit %.3e s\n", __func__, n, explicit_dt);
  SW_EXPECT_REL("tip deflection (m)", -y, exact, sw_test_sanitized() ? 2e-2 : 1e-2);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Tip of the undamped cantilever at t = 2 s under the tip load
 * 0.05 N (1 - cos(2 pi t / 10 s)) / 2, at dt = h.  The load starts with no
 * jump in value or rate and varies slowly against the first mode (period
 * 4 s), so the modes the large steps cannot resolve follow it
 * quasi-statically, which the trapezoidal rule reproduces, and the error is
 * the resolved modes'. */
static double cantilever_tip_counts(double h, int n, double *explicit_dt, double *fresh,
                                   double *kept);
static double cantilever_tip(double h, int n, double *explicit_dt) {
  return cantilever_tip_counts(h, n, explicit_dt, NULL, NULL);
}
static double cantilever_tip_counts(double h, int n, double *explicit_dt, double *fresh,
                                   double *kept) {
  swSpec *s = cantilever(n, 0, 0.05, sw_signal_sine(0.5, 0.5, 0.1, -M_PI / 2, 0.0));
  if (explicit_dt) {
    swModel *m0 = sw_test_compile(s);
    *explicit_dt = sw_stable_dt(m0);
    sw_model_free(m0);
  }
  sw_spec_set_integrator(s, SW_IMEX);
  sw_spec_set_dt(s, h);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  sw_test_run_to(m, d, 2.0);
  const double y = SW_AT(m, d->x, n, 1);
  if (fresh) sw_implicit_counts(m, d, fresh, kept);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return y;
}

static void test_second_order(void **state) {
  (void)state;
  const int n = 20;
  double explicit_dt;
  /* 2 s in 32, 64, 128 and 256 steps, and a reference in 8192 */
  const double ref = cantilever_tip(2.0 / 8192, n, &explicit_dt);
  double err[4], h[4];
  for (int k = 0; k < 4; k++) {
    h[k] = 2.0 / (32 << k);
    err[k] = cantilever_tip(h[k], n, NULL) - ref;
  }
  fprintf(stderr, "# %s: explicit step %.3e s; dt = %.3g .. %.3g s (%.0f .. %.0f x it): tip errors "
          "%.3e %.3e %.3e %.3e m (tip %.4e m)\n", __func__, explicit_dt, h[0], h[3],
          h[0] / explicit_dt, h[3] / explicit_dt, err[0], err[1], err[2], err[3], ref);
  assert_true(h[3] > 1.5 * explicit_dt);
  /* every halving gains at least second order; the finest pair, in the
   * asymptotic range, is second order */
  for (int k = 0; k < 3; k++) {
    const double order = sw_test_order(err, k);
    fprintf(stderr, "#   order %.2f\n", order);
    assert_true(order > 1.8);
    if (k == 2) assert_true(fabs(order - 2.0) < 0.2);
  }
}

static void test_kept_second_order(void **state) {
  (void)state;
  const int n = 20;
  double explicit_dt, fresh, kept;
  cantilever_tip(1.0, n, &explicit_dt);
  /* 2 s at 1/2 .. 1/16 of the explicit step, and a reference at 1/128 */
  const double href = explicit_dt / 128;
  const double ref = cantilever_tip(2.0 / ceil(2.0 / href), n, NULL);
  double err[4], h[4];
  for (int k = 0; k < 4; k++) {
    h[k] = 2.0 / ceil(2.0 / (explicit_dt / (2 << k)));
    err[k] = cantilever_tip_counts(h[k], n, NULL, &fresh, &kept) - ref;
    fprintf(stderr, "# %s: dt = %.3e s: tip error %.3e m; %.0f kicks factored, %.0f kept the "
            "factorisation\n", __func__, h[k], err[k], fresh, kept);
    assert_true(kept > 10 * fresh); /* the factorisation is kept */
  }
  for (int k = 0; k < 3; k++) {
    const double order = sw_test_order(err, k);
    fprintf(stderr, "#   order %.2f\n", order);
    assert_true(fabs(order - 2.0) < 0.2);
  }
}

/* The free rod of free_rod_energy, x25, at 10 times the explicit step:
 * the largest |E / E0 - 1| over `blocks` of 2000 steps, and the kicks that
 * factored and kept; keep = 0 makes every kick factor (a rod's explicit
 * bound of 0 leaves no turn to keep a factorisation over). */
static double kept_energy(int blocks, int keep, double *fresh, double *kept) {
  swSpec *s = sw_spec_new();
  swRodDesc r = snake_rod(50, 25, 1);
  sw_spec_add_rod(s, &r);
  swModel *m0 = sw_test_compile(s);
  const double explicit_dt = sw_stable_dt(m0);
  sw_model_free(m0);
  sw_spec_set_integrator(s, SW_IMEX);
  sw_spec_set_dt(s, 10 * explicit_dt);
  swModel *m = sw_test_compile(s);
  if (!keep) m->implicit_wave_dt[0] = 0;
  swData *d = sw_data_new(m);
  random_velocities(m, d);
  double e[3], worst = 0;
  sw_energy(m, d, e);
  const double e0 = e[0] + e[1];
  for (int b = 0; b < blocks; b++) {
    assert_int_equal(sw_steps(m, d, 2000), SW_OK);
    sw_energy(m, d, e);
    worst = fmax(worst, fabs((e[0] + e[1]) / e0 - 1));
  }
  sw_implicit_counts(m, d, fresh, kept);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return worst;
}

static void test_kept_energy(void **state) {
  (void)state;
  const int blocks = sw_test_sanitized() ? 2 : 10;
  double fresh, kept, fresh0, kept0;
  const double with = kept_energy(blocks, 1, &fresh, &kept);
  const double without = kept_energy(blocks, 0, &fresh0, &kept0);
  fprintf(stderr, "# %s: x25 at 10 x the explicit step, %d steps: largest energy change %.2e "
          "keeping the factorisation (%.0f kicks factored, %.0f kept), %.2e factoring every "
          "kick (%.0f, %.0f)\n", __func__, blocks * 2000, with, fresh, kept, without, fresh0,
          kept0);
  assert_true(kept > 10 * fresh);
  assert_true(kept0 == 0);
  /* the kept kicks move the energy more, boundedly (rod_implicit.c: each
   * frozen W keeps an energy near the exact rule's, without drift) */
  assert_true(without < 1e-4);
  assert_true(with < 5e-3);
}

static void test_threads_same_bits(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  for (int k = 0; k < 3; k++) { /* three implicit rods side by side */
    swRodDesc r = snake_rod(40, 25, 1);
    r.start[1] = 0.1 * k;
    sw_spec_add_rod(s, &r);
  }
  const double g[3] = {0, 0, -9.81};
  sw_spec_set_gravity(s, g);
  swLoadDesc c = sw_test_load(SW_LOAD_TORQUE, 1, 10, 0, 0.5, 1.0);
  sw_spec_add_load(s, &c);
  sw_spec_set_integrator(s, SW_IMEX);
  sw_spec_set_dt(s, 2e-4);
  swModel *m = sw_test_compile(s);
  swData *d1 = sw_data_new(m), *d2 = sw_data_new(m);
  assert_int_equal(sw_set_threads(d2, 2), 2);
  assert_int_equal(sw_steps(m, d1, 500), SW_OK);
  assert_int_equal(sw_steps(m, d2, 500), SW_OK);
  const size_t S = (size_t)m->stride;
  assert_memory_equal(d1->x, d2->x, 3 * S * sizeof(double));
  assert_memory_equal(d1->Q, d2->Q, 9 * S * sizeof(double));
  assert_memory_equal(d1->v, d2->v, 3 * S * sizeof(double));
  assert_memory_equal(d1->omega, d2->omega, 3 * S * sizeof(double));
  fprintf(stderr, "# %s: 3 implicit rods, 500 steps at 200 us: 1 and 2 threads agree to the bit\n",
          __func__);
  sw_data_free(d1);
  sw_data_free(d2);
  sw_model_free(m);
  sw_spec_free(s);
}

/* The free 50-element rod (x25) turning as one body about z through its
 * middle at 3 rad/s, with random_velocities on top, for T = 0.2 s (0.1 s
 * under the sanitizers) at the
 * step h under imex, its factorisation kept when it holds (keep) or made
 * at every kick; its nodes' positions into x (3 (n + 1) numbers), and the
 * kicks factored and kept. */
static void turning_rod(double h, int keep, double *x, double *fresh, double *kept) {
  swSpec *s = sw_spec_new();
  swRodDesc r = snake_rod(50, 25, 1);
  sw_spec_add_rod(s, &r);
  sw_spec_set_integrator(s, SW_IMEX);
  sw_spec_set_dt(s, h);
  swModel *m = sw_test_compile(s);
  if (!keep) m->implicit_wave_dt[0] = 0;
  swData *d = sw_data_new(m);
  assert_non_null(d);
  random_velocities(m, d);
  const double W = 3.0;
  for (int i = 0; i <= 50; i++) { /* v += W z x (x - c) */
    SW_AT(m, d->v, i, 0) += -W * SW_AT(m, d->x, i, 1);
    SW_AT(m, d->v, i, 1) += W * (SW_AT(m, d->x, i, 0) - 0.5);
  }
  for (int e = 0; e < 50; e++) { /* w += Q (0, 0, W), material */
    double Q[9];
    sw_getQ(m, d->Q, e, Q);
    for (int k = 0; k < 3; k++) SW_AT(m, d->omega, e, k) += Q[3 * k + 2] * W;
  }
  sw_test_run_to(m, d, sw_test_sanitized() ? 0.1 : 0.2);
  for (int i = 0; i <= 50; i++)
    for (int k = 0; k < 3; k++) x[3 * i + k] = SW_AT(m, d->x, i, k);
  sw_implicit_counts(m, d, fresh, kept);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* A rod alone keeping its factorisation while its frames turn (rod_implicit.c,
 * keep_theta: a fixed turn below the rod's explicit bound dt_w).  Kept
 * against made at every kick, D(h) = the largest distance between the
 * two runs' nodes after 0.2 s, at h = dt_w / 2, / 4 and / 8: the W-method's
 * error, O(theta (h / dt_w)^2) of a kick's update (the rod's own stiffness
 * is all that W holds), must fall at least at second order, as the
 * trapezoidal rule's own error does. */
static void test_kept_turning(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  swRodDesc r = snake_rod(50, 25, 1);
  sw_spec_add_rod(s, &r);
  swModel *m0 = sw_test_compile(s);
  const double dt_w = sw_stable_dt_elastic(m0, 0);
  sw_model_free(m0);
  sw_spec_free(s);
  double xk[153], xf[153], D[3], nf, nk, nf0, nk0;
  for (int c = 0; c < 3; c++) {
    const double h = 0.2 / ceil(0.2 / (dt_w / (2 << c)));
    turning_rod(h, 1, xk, &nf, &nk);
    turning_rod(h, 0, xf, &nf0, &nk0);
    D[c] = 0;
    for (int i = 0; i <= 50; i++) {
      const double dx = xk[3 * i] - xf[3 * i], dy = xk[3 * i + 1] - xf[3 * i + 1];
      const double dz = xk[3 * i + 2] - xf[3 * i + 2];
      D[c] = fmax(D[c], sqrt(dx * dx + dy * dy + dz * dz));
    }
    fprintf(stderr, "# %s: h = dt_w / %d (%.3g s): kept - made every kick %.3e m; %.0f kicks "
            "factored, %.0f kept\n", __func__, 2 << c, h, D[c], nf, nk);
    assert_true(nk > 10 * nf); /* it keeps */
    assert_true(nk0 == 0);
  }
  for (int c = 0; c < 2; c++) {
    const double order = log(D[c] / D[c + 1]) / log(2.0);
    fprintf(stderr, "#   order %.2f\n", order);
    assert_true(order > 1.8);
  }
}

/* Two implicit bones (E = 15 GPa, r = 2.5 mm, 10 elements of 1 cm, the
 * first clamped) tied end to start by an explicit joint of k = 8e4 N/m
 * with an arm of 0.1 mm (an arm keeps it out of the joints' system), undamped,
 * under imex at the step dt: the largest |E / E0 - 1| (E the bones' energy
 * and the tie's) over `steps` steps from small random velocities on the
 * second bone, and over the last tenth of them (late), or 1e30 when the
 * step fails. */
static swSpec *tied_bones(void) {
  swSpec *s = sw_spec_new();
  const double x0[3] = {0, 0, 0}, x1[3] = {0.1, 1e-4, 0}, dx[3] = {1, 0, 0};
  swRodDesc a = sw_test_rod("bone_a", 10, 0.1, 2.5e-3, x0, dx, NULL);
  swRodDesc b = sw_test_rod("bone_b", 10, 0.1, 2.5e-3, x1, dx, NULL);
  a.youngs = b.youngs = 15e9, a.shear_modulus = b.shear_modulus = 1e10;
  a.density = b.density = 875, a.implicit = b.implicit = 1;
  const int ia = sw_spec_add_rod(s, &a), ib = sw_spec_add_rod(s, &b);
  swBCDesc c = sw_test_clamp(ia, 0);
  sw_spec_add_bc(s, &c);
  swJointDesc j;
  sw_joint_desc_init(&j);
  j.name = "tie";
  j.kind = SW_JOINT_SPHERICAL;
  j.rod_a = ia, j.node_a = 10, j.rod_b = ib, j.node_b = 0;
  j.arm_a[1] = 1e-4;
  j.stiffness = 8e4;
  j.undamped = 1; /* the bound of the undamped tie: the energy is the check */
  sw_spec_add_joint(s, &j);
  sw_spec_set_integrator(s, SW_IMEX);
  return s;
}

/* The bones' kinetic and elastic energy and the tie's, 0.5 k |gap|^2 with
 * side a's point at node a plus its arm turned with element a. */
static double tied_energy(const swModel *m, swData *d) {
  double e[3], Q[9], arm[3], xa[3], xb[3];
  sw_energy(m, d, e);
  sw_getQ(m, d->Q, m->joint_elem_a[0], Q);
  sw_matT_vec(arm, Q, m->joint_arm_a);
  sw_get3(m, d->x, m->joint_node_a[0], xa);
  sw_get3(m, d->x, m->joint_node_b[0], xb);
  double g2 = 0;
  for (int k = 0; k < 3; k++) g2 += (xb[k] - xa[k] - arm[k]) * (xb[k] - xa[k] - arm[k]);
  return e[0] + e[1] + 0.5 * m->joint[0].stiffness * g2;
}

static double tied_bones_energy(double dt, int steps, double *early, double *late) {
  swSpec *s = tied_bones();
  sw_spec_set_dt(s, dt);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  assert_non_null(d);
  unsigned seed = 7;
  for (int i = m->node_adr[1]; i <= m->node_adr[1] + 10; i++)
    for (int k = 0; k < 3; k++) {
      seed = seed * 1103515245u + 12345u;
      SW_AT(m, d->v, i, k) = 1e-2 * ((seed >> 8) / 16777216.0 - 0.5);
    }
  double worst = 0;
  const double e0 = tied_energy(m, d);
  const int tenth = steps / 10;
  *early = *late = 0; /* the mean |E / E0 - 1| over the first and the last tenth */
  for (int k = 0; k < steps && worst < 1e30; k++) {
    if (sw_step(m, d) != SW_OK) worst = 1e30;
    const double change = worst < 1e30 ? fabs(tied_energy(m, d) / e0 - 1) : 1e30;
    worst = fmax(worst, change);
    if (k < tenth) *early += change / tenth;
    if (k >= steps - tenth) *late += change / tenth;
  }
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return worst;
}

/* An explicit joint's bound on implicit rods (stability.c, joint_node_dt):
 * the rods' own stiffness cancels from the imex kick's stability, so the
 * joint's node row alone, w^2 = 2 k / m_i, bounds the step, 77 times the
 * bones' own explicit bound here (which the estimate used to count).  At
 * 0.9 of it (h w = 1.7 in the tie's mode) the energy swings, as position
 * Verlet's near its bound does (measured at whole steps, a mode's energy
 * moves by up to (h w / 2)^2 / (1 - (h w / 2)^2) of itself), but does not
 * grow: its mean swing over the last 2000 of 20000 steps is about that
 * over the first 2000; at 1.3 of it (h w = 2.5, |lambda| = 3.8 a step)
 * the run fails within 2000 steps. */
static void test_joint_on_implicit_bound(void **state) {
  (void)state;
  swSpec *s = tied_bones();
  swModel *m = sw_test_compile(s);
  const double est = sw_stable_dt(m), own = sw_stable_dt_elastic(m, 0);
  const int node = m->node_adr[0] + 10;
  const double lim = sw_integrator_stability_limit(m->integrator, 0.0); /* h w at the bound */
  const double tie = 0.95 * lim / sqrt(2 * 8e4 * m->inv_mass[node]);
  sw_model_free(m);
  sw_spec_free(s);
  double early, late, early_above, late_above;
  const int steps = sw_test_sanitized() ? 10000 : 20000;
  const double below = tied_bones_energy(0.9 * est, steps, &early, &late);
  const double above = tied_bones_energy(1.3 * est, 2000, &early_above, &late_above);
  fprintf(stderr, "# %s: estimate %.4g s (the tie's node row %.4g s; the bones' own explicit "
          "bound %.4g s, %.0f times less); at 0.9 of it, %d steps: largest energy swing %.3f, "
          "mean swing over the first tenth %.3f and the last %.3f; at 1.3 of it, 2000 steps: "
          "%.2e\n", __func__, est, tie, own, est / own, steps, below, early, late, above);
  assert_true(fabs(est / tie - 1) < 1e-12); /* the joint's row, not the bones' */
  assert_true(est > 10 * own);
  assert_true(below < 0.5 && late < 1.5 * early); /* bounded: it swings, it does not grow */
  assert_true(above > 1e3);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_tangent_helix),
    cmocka_unit_test(test_tangent_tension),
    cmocka_unit_test(test_free_rod_energy),
    cmocka_unit_test(test_timoshenko_implicit),
    cmocka_unit_test(test_second_order),
    cmocka_unit_test(test_kept_second_order),
    cmocka_unit_test(test_kept_turning),
    cmocka_unit_test(test_joint_on_implicit_bound),
    cmocka_unit_test(test_kept_energy),
    cmocka_unit_test(test_threads_same_bits),
  };
  return cmocka_run_group_tests_name("rod_implicit", tests, NULL, NULL);
}
