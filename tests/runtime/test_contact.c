/* test_contact.c — rod-rod contact (contact.c) against closed forms: two rods
 * thrown at each other (crossing at right angles, and side by side) stop
 * within the overlap that the energy balance k_c delta^2 / 2 = kinetic energy
 * allows (below 1% of the radius) and bounce apart; without damping the
 * total energy is conserved to the integrator's O(dt^2) (the drift with and
 * without contact, at two steps); with damping the collision loses energy
 * (restitution of two rigid rods against the one-degree-of-freedom
 * spring-dashpot it reduces to); a rod folded into a hairpin does not pass
 * through itself, while neighbours along a rod never touch at rest (straight
 * rod, and the tightest hairpin the neighbour rule allows); the hash-grid
 * broad phase finds the same forces as the brute-force loop over all pairs
 * on a random scene of many rods; the stable step estimate against the step
 * at which two pressed rods really blow up; the validation messages (exact
 * text).
 *
 * Design.  Scenes are built through the public API (swContactDesc,
 * sw_spec_add_contact); the tests read the figures the runtime leaves in the
 * state (d->contact_pairs, d->contact_max_overlap) and call contact.c's
 * kernels directly (internal.h) only to compare the two broad phases.  The
 * long runs shrink under SW_SANITIZED (testutil.h). */
#include "testutil.h"
#include "internal.h"

/* Rods of a soft solid (E = 10 MPa, 1000 kg/m^3), L = 0.1 m, r = 5 mm. */
static const double RE = 1e7, RRHO = 1000, RL = 0.1, RR = 0.005;

/* ---- helpers ---- */

static swRodDesc rod_desc(const char *name, int n, double length, double radius,
                          const double start[3], const double dir[3], const double normal[3]) {
  swRodDesc r = sw_test_rod(name, n, length, radius, start, dir, normal);
  r.density = RRHO;
  r.youngs = RE;
  r.poisson = 0.5;
  return r;
}

static swContactDesc contact_desc(double k, double gamma) {
  swContactDesc c;
  sw_contact_desc_init(&c);
  c.name = "touch";
  c.stiffness = k;
  c.damping = gamma;
  return c;
}

static double rod_mass(const swModel *m, int r) {
  double M = 0;
  for (int i = 0; i <= m->rod_nelem[r]; i++) M += m->mass[m->node_adr[r] + i];
  return M;
}

/* Centre-of-mass velocity of rod r. */
static void rod_com_velocity(const swModel *m, const swData *d, int r, double V[3]) {
  double M = 0;
  V[0] = V[1] = V[2] = 0;
  for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
    M += m->mass[i];
    for (int k = 0; k < 3; k++) V[k] += m->mass[i] * SW_AT(m, d->v, i, k);
  }
  for (int k = 0; k < 3; k++) V[k] /= M;
}

static void set_rod_velocity(const swModel *m, swData *d, int r, const double v[3]) {
  for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
    sw_set3(m, d->v, i, v);
}

static double total_energy(const swModel *m, swData *d) {
  double E[3];
  sw_energy(m, d, E);
  return E[0] + E[1] - E[2];
}

/* ---- 1. two rods thrown at each other ---- */

/* Rod a along x below the plane y = 0, rod b above it, along z (crossing)
 * or along x (side by side), their surfaces GAP apart, thrown at each other
 * at V each along y.  n = 21 elements: the crossing point is the middle of
 * an element of each rod, so one pair of elements touches; side by side,
 * element i faces element i and touches i - 1 and i + 1 at their shared
 * nodes: 3n - 2 pairs.  k_c makes the energy estimate of the deepest overlap
 * OVERLAP_AIM of the radius:
 *   delta = sqrt(2 K / (pairs k_c)),  K = M V^2 the kinetic energy of the
 * relative motion (both rods of mass M at V towards each other). */
static const double V = 0.1, GAP = 0.2 * RR, OVERLAP_AIM = 0.005;
enum { NT = 21 };

typedef struct {
  int parallel;       /* side by side instead of crossing      */
  int contact;        /* 0: no contact description (pass through) */
  int rigid;          /* rigid rods                            */
  double gamma;       /* gamma_c                               */
  double bend;        /* amplitude of a bending velocity, m/s  */
  double gap;         /* surfaces apart at t = 0, m (0: GAP)   */
} Throw;

static int throw_pairs(const Throw *t) { return t->parallel ? 3 * NT - 2 : 1; }

static double throw_k(const Throw *t) {
  double M = M_PI * RR * RR * RL * RRHO, K = M * V * V, delta = OVERLAP_AIM * RR;
  return 2 * K / (throw_pairs(t) * delta * delta);
}

/* The scene, compiled at `dt` (0: half of its own stable estimate). */
static swModel *throw_model(const Throw *t, double dt) {
  swSpec *s = sw_spec_new();
  const double y = RR + 0.5 * (t->gap > 0 ? t->gap : GAP);
  const double sa[3] = {-0.5 * RL, -y, 0}, ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
  swRodDesc a = rod_desc("a", NT, RL, RR, sa, ex, ey);
  a.rigid = t->rigid;
  assert_int_equal(sw_spec_add_rod(s, &a), 0);
  const double sb_cross[3] = {0, y, -0.5 * RL}, ez[3] = {0, 0, 1};
  const double sb_par[3] = {-0.5 * RL, y, 0};
  swRodDesc b = t->parallel ? rod_desc("b", NT, RL, RR, sb_par, ex, ey)
                            : rod_desc("b", NT, RL, RR, sb_cross, ez, ey);
  b.rigid = t->rigid;
  assert_int_equal(sw_spec_add_rod(s, &b), 1);
  if (t->contact) {
    swContactDesc c = contact_desc(throw_k(t), t->gamma);
    assert_int_equal(sw_spec_add_contact(s, &c), 0);
  }
  swModel *m;
  if (dt > 0) {
    sw_spec_set_dt(s, dt);
    m = sw_test_compile(s);
  } else {
    m = sw_test_compile_at(s, 0.5);
  }
  sw_spec_free(s);
  return m;
}

static void throw_start(const swModel *m, swData *d, const Throw *t) {
  sw_reset(m, d);
  for (int r = 0; r < 2; r++) {
    const double v[3] = {0, r ? -V : V, 0};
    if (m->nrigid) {
      const double w0[3] = {0, 0, 0};
      assert_int_equal(sw_rigid_set_motion(m, d, r, v, w0), SW_OK);
      continue;
    }
    set_rod_velocity(m, d, r, v);
    /* a bending velocity, the same for both rods, for the energy test */
    for (int i = 0; i <= NT; i++)
      SW_AT(m, d->v, m->node_adr[r] + i, 1) += t->bend * sin(M_PI * i / NT);
  }
}

/* Relative velocity of the rods' centres along y, b minus a. */
static double approach_velocity(const swModel *m, const swData *d) {
  double va[3], vb[3];
  rod_com_velocity(m, d, 0, va);
  rod_com_velocity(m, d, 1, vb);
  return vb[1] - va[1];
}

typedef struct {
  double max_overlap;  /* deepest overlap seen, m                       */
  double restitution;  /* relative velocity after / before              */
  double drift;        /* max |E - E0| over the run, J                  */
  double drift_after;  /* max |E - E0| after the rods parted, J         */
  double t_parted;     /* time the last contact ended, s                */
  int pairs_end;       /* pairs in contact at the end                   */
  double gap_end;      /* y distance of the centrelines at the end - 2r */
  double K;            /* kinetic energy of the relative motion, J      */
} Outcome;

static Outcome throw_run(const swModel *m, const Throw *t, double duration, int energy) {
  swData *d = sw_data_new(m);
  assert_non_null(d);
  throw_start(m, d, t);
  Outcome o = {0};
  double u0 = approach_velocity(m, d);
  o.K = 0.25 * rod_mass(m, 0) * u0 * u0; /* reduced mass M/2 */
  double E0 = energy ? total_energy(m, d) : 0;
  int touched = 0;
  long steps = lround(duration / m->dt);
  for (long k = 0; k < steps; k++) {
    assert_int_equal(sw_step(m, d), SW_OK);
    o.max_overlap = fmax(o.max_overlap, d->contact_max_overlap);
    if (d->contact_pairs) touched = 1, o.t_parted = d->time;
    if (energy) {
      double err = fabs(total_energy(m, d) - E0);
      o.drift = fmax(o.drift, err);
      if (touched && d->contact_pairs == 0) o.drift_after = fmax(o.drift_after, err);
    }
  }
  o.restitution = -approach_velocity(m, d) / u0;
  o.pairs_end = d->contact_pairs;
  double ya = 0, yb = 0;
  for (int i = 0; i <= NT; i++) {
    ya += SW_AT(m, d->x, m->node_adr[0] + i, 1) / (NT + 1);
    yb += SW_AT(m, d->x, m->node_adr[1] + i, 1) / (NT + 1);
  }
  o.gap_end = yb - ya - 2 * RR;
  sw_data_free(d);
  return o;
}

static void check_throw(int parallel) {
  Throw t = {parallel, 1, 0, 0, 0, 0};
  swModel *m = throw_model(&t, 0);
  const double duration = 0.03;
  Outcome o = throw_run(m, &t, duration, 0);
  double k = throw_k(&t), estimate = sqrt(2 * o.K / (throw_pairs(&t) * k));
  double bound = sqrt(2 * o.K / k); /* all the energy in the deepest pair */
  fprintf(stderr, "# %s: %s, k_c = %.4g N/m, dt = %.3g s: deepest overlap %.4e m = %.3f%% of r "
                  "(energy estimate over %d pairs %.4e m = %.2f%%, one-pair bound %.4e m); "
                  "restitution %.4f; parted at t = %.4g s, gap at the end %.3e m\n",
          __func__, parallel ? "side by side" : "crossing", k, m->dt, o.max_overlap,
          100 * o.max_overlap / RR, throw_pairs(&t), estimate, 100 * estimate / RR, bound,
          o.restitution, o.t_parted, o.gap_end);
  assert_true(o.max_overlap > 0);               /* they did touch       */
  assert_true(o.max_overlap < 0.01 * RR);       /* less than 1% of r    */
  assert_true(o.max_overlap <= bound);          /* the energy balance   */
  assert_true(o.restitution > 0.5);             /* they bounced back    */
  assert_int_equal(o.pairs_end, 0);             /* and apart            */
  assert_true(o.gap_end > 0);
  sw_model_free(m);
}

static void test_throw_crossing(void **state) {
  (void)state;
  check_throw(0);
}

static void test_throw_parallel(void **state) {
  (void)state;
  check_throw(1);
}

/* ---- 2. energy: conservative without damping ---- */

/* gamma_c = 0: kinetic + elastic (contact springs included) - work is
 * conserved up to position Verlet's O(dt^2).  Both rods also carry a
 * bending velocity, so the run without contact (the rods pass through each
 * other) has an integrator drift of its own to compare with.  Measured:
 * the largest |E - E0| over the run at dt, dt/2, dt/4, dt/8 (dt = half the
 * stable estimate), and its order, the least-squares slope of log drift
 * against log dt; after the rods parted, the order between dt and dt/8.  A
 * force that is not the gradient of the energy (a leak) would leave a drift
 * that does not fall with dt.  The contact force is continuous but not
 * smooth (it switches on at delta = 0, and the distance of two segments has
 * a kink where they are parallel), so the error of each step where it bends
 * depends on where in the step that happens: the drift falls at order 2 on
 * the whole, not step by step of the refinement. */
static double fit_order(const double *drift, int n) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < n; i++) {
    double x = -i * log(2.0), y = log(drift[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

static void check_energy(int parallel) {
  enum { NDT = 4 };
  const double duration = 0.015;
  Throw t = {parallel, 1, 0, 0, 0.02, 0};
  swModel *m0 = throw_model(&t, 0);
  const double dt0 = m0->dt;
  sw_model_free(m0);
  double with[NDT], without[NDT], after[NDT], K = 0;
  for (int i = 0; i < NDT; i++) {
    for (int c = 0; c < 2; c++) {
      t.contact = c;
      swModel *m = throw_model(&t, dt0 / (1 << i));
      Outcome o = throw_run(m, &t, duration, 1);
      if (c) with[i] = o.drift, after[i] = o.drift_after, K = o.K;
      else without[i] = o.drift;
      sw_model_free(m);
    }
    fprintf(stderr, "# %s: %s, dt = %.3g s: max |E - E0| = %.3e J with contact (%.3e J after they "
                    "parted), %.3e J without; K = %.3e J\n",
            __func__, parallel ? "side by side" : "crossing", dt0 / (1 << i), with[i], after[i],
            without[i], K);
  }
  double p_with = fit_order(with, NDT), p_after = log2(after[0] / after[NDT - 1]) / (NDT - 1);
  double p_without = fit_order(without, NDT);
  fprintf(stderr, "# %s: order of the drift: %.2f with contact, %.2f after parting (dt to dt/8), "
                  "%.2f without (reference 2, position Verlet)\n",
          __func__, p_with, p_after, p_without);
  assert_true(p_without > 1.9 && p_without < 2.1);
  assert_true(p_with > 1.7 && p_with < 2.5);
  assert_true(p_after > 1.7);
  assert_true(with[NDT - 1] < 1e-3 * K);
  assert_true(after[NDT - 1] < 2e-4 * K); /* nothing left behind */
}

static void test_energy_crossing(void **state) {
  (void)state;
  check_energy(0);
}

static void test_energy_parallel(void **state) {
  (void)state;
  check_energy(1);
}

/* ---- 3. damping: restitution ---- */

/* Two rigid rods side by side: every pair has the same overlap delta, so the
 * relative motion is one damped oscillator, mu delta'' = -P max(0, k_c delta
 * + gamma_c delta') with mu = M / 2 and P = 3n - 2 pairs, from delta = 0 at
 * the approach speed u.  With w0^2 = P k_c / mu, beta = P gamma_c / (2 mu),
 * w^2 = w0^2 - beta^2, delta = (u / w) exp(-beta t) sin(w t) until the force
 * vanishes, w0^2 delta + 2 beta delta' = 0, i.e. at w t_e = pi -
 * atan2(2 beta w, w^2 - beta^2), where the speed is exactly -u exp(-beta t_e):
 *   e = exp(-(beta / w) (pi - atan2(2 beta w, w^2 - beta^2))).
 * The damper's force jumps to P gamma_c u at first touch, somewhere inside
 * a step: an O(dt) error of about beta dt in e, which w0 dt = 0.002 makes
 * 1e-3 at zeta = beta / w0 = 0.5 (the tolerance). */
static void test_restitution_rigid(void **state) {
  (void)state;
  const double zetas[] = {0.05, 0.2, 0.5};
  for (int z = 0; z < 3; z++) {
    Throw t = {1, 1, 1, 0, 0, 0.01 * RR};
    const double M = M_PI * RR * RR * RL * RRHO, mu = 0.5 * M, P = 3 * NT - 2;
    const double w0 = sqrt(P * throw_k(&t) / mu), beta = zetas[z] * w0;
    t.gamma = 2 * mu * beta / P;
    swModel *m = throw_model(&t, 0.002 / w0);
    const double w = sqrt(w0 * w0 - beta * beta);
    Outcome o = throw_run(m, &t, 0.5 * t.gap / V + 3 * M_PI / w, 0);
    const double e = exp(-beta / w * (M_PI - atan2(2 * beta * w, w * w - beta * beta)));
    fprintf(stderr, "# %s: zeta = %.2f (gamma_c = %.4g kg/s), dt = %.3g s, w0 dt = 0.002\n",
            __func__, zetas[z], t.gamma, m->dt);
    SW_EXPECT_REL("restitution", o.restitution, e, 1e-3);
    assert_true(o.restitution < 1);
    sw_model_free(m);
  }
}

/* Elastic crossing rods: the damper takes energy (restitution below the
 * undamped collision's), and the energy balance with the damper's work
 * booked still holds to the integrator's error. */
static void test_restitution_elastic(void **state) {
  (void)state;
  Throw t = {0, 1, 0, 0, 0, 0};
  swModel *m = throw_model(&t, 0);
  Outcome undamped = throw_run(m, &t, 0.03, 0);
  double dt = m->dt;
  sw_model_free(m);
  const double M = M_PI * RR * RR * RL * RRHO;
  t.gamma = 2 * 0.5 * M * 0.3 * sqrt(throw_k(&t) / (0.5 * M)); /* zeta 0.3 on the rods' mass */
  m = throw_model(&t, dt);
  Outcome damped = throw_run(m, &t, 0.03, 1);
  fprintf(stderr, "# %s: restitution %.4f undamped, %.4f with gamma_c = %.4g kg/s; energy balance "
                  "error %.3e J of K = %.3e J\n",
          __func__, undamped.restitution, damped.restitution, t.gamma, damped.drift, damped.K);
  assert_true(damped.restitution < undamped.restitution);
  assert_true(damped.restitution > 0);
  assert_true(damped.drift < 2e-3 * damped.K);
  sw_model_free(m);
}

/* ---- 4. self-contact ---- */

/* A hairpin: a leg along -x at y = -R, a half circle of radius R about the
 * origin on the side x < 0, and a leg back along +x at y = +R, every leg
 * LEG long; n elements of equal rest arc length, nodes on the path, element
 * frames d3 along the chord, d1 = z. */
static const double LEG = 0.05;

static int hairpin(swSpec *s, double R, double radius, int n, double youngs) {
  const double total = 2 * LEG + M_PI * R;
  double *x = malloc(sizeof(double) * 3 * (size_t)(n + 1)), *Q = malloc(sizeof(double) * 9 * (size_t)n);
  assert_non_null(x);
  assert_non_null(Q);
  for (int i = 0; i <= n; i++) {
    double a = total * i / n, *p = x + 3 * i;
    if (a <= LEG) p[0] = LEG - a, p[1] = -R;
    else if (a >= LEG + M_PI * R) p[0] = a - LEG - M_PI * R, p[1] = R;
    else p[0] = -R * sin((a - LEG) / R), p[1] = -R * cos((a - LEG) / R);
    p[2] = 0;
  }
  for (int i = 0; i < n; i++) {
    double t[3], len;
    for (int k = 0; k < 3; k++) t[k] = x[3 * i + 3 + k] - x[3 * i + k];
    len = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    double *q = Q + 9 * i;
    q[0] = 0, q[1] = 0, q[2] = 1;                          /* d1 = z        */
    q[6] = t[0] / len, q[7] = t[1] / len, q[8] = t[2] / len; /* d3 = tangent */
    q[3] = q[7] * q[2] - q[8] * q[1];                      /* d2 = d3 x d1  */
    q[4] = q[8] * q[0] - q[6] * q[2];
    q[5] = q[6] * q[1] - q[7] * q[0];
  }
  const double o[3] = {LEG, -R, 0}, ex[3] = {-1, 0, 0}, ez[3] = {0, 0, 1};
  swRodDesc r = rod_desc("hairpin", n, total, radius, o, ex, ez);
  r.youngs = youngs;
  int id = sw_spec_add_rod(s, &r);
  assert_int_equal(sw_spec_set_rest_shape(s, id, x, Q), SW_OK);
  free(x);
  free(Q);
  return id;
}

/* Contact loads alone of the state's configuration; returns the largest
 * |force| over the nodes. */
static double contact_force_only(const swModel *m, swData *d) {
  memset(d->force, 0, sizeof(double) * 3 * (size_t)m->stride);
  memset(d->ext_force, 0, sizeof(double) * 3 * (size_t)m->stride);
  sw_contact_loads(m, d);
  double worst = 0;
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
      for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(SW_AT(m, d->force, i, k)));
  return worst;
}

/* At rest, a straight rod and the tightest hairpin the neighbour rule allows
 * (R = 1.05 r: its legs 0.1 r apart, its bend turning at a radius a little
 * above r) feel no contact; a hairpin whose legs overlap (R = 0.95 r) does,
 * so the rule does not hide a real overlap. */
static void test_self_at_rest(void **state) {
  (void)state;
  const double radii[3] = {0, 1.05, 0.95};
  for (int c = 0; c < 3; c++) {
    swSpec *s = sw_spec_new();
    if (c == 0) {
      const double o[3] = {0, 0, 0}, ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
      swRodDesc r = rod_desc("straight", 40, RL, RR, o, ex, ey); /* l = 0.5 r */
      sw_spec_add_rod(s, &r);
    } else {
      hairpin(s, radii[c] * RR, RR, 64, RE);
    }
    swContactDesc cd = contact_desc(1e4, 1.0);
    cd.self = 1;
    assert_int_equal(sw_spec_add_contact(s, &cd), 0);
    swModel *m = sw_test_compile(s);
    sw_spec_free(s);
    swData *d = sw_data_new(m);
    double f = contact_force_only(m, d);
    fprintf(stderr, "# %s: %s: %d pairs in contact, largest contact force %.3e N, overlap %.3e m\n",
            __func__, c == 0 ? "straight rod (l = r/2)" : (c == 1 ? "hairpin R = 1.05 r" : "hairpin R = 0.95 r"),
            d->contact_pairs, f, d->contact_max_overlap);
    if (c < 2) {
      assert_int_equal(d->contact_pairs, 0);
      assert_true(f == 0);
    } else {
      assert_true(d->contact_pairs > 0);
      /* the legs overlap by 2 r - 2 R; where the bend meets them, its chords
       * cut inside the circle by up to the sagitta l^2 / (8 R) */
      double legs = 2 * RR - 2 * radii[c] * RR, l = (2 * LEG + M_PI * radii[c] * RR) / 64;
      double sagitta = l * l / (8 * radii[c] * RR);
      fprintf(stderr, "#   legs overlap by %.4e m, sagitta %.3e m\n", legs, sagitta);
      assert_true(d->contact_max_overlap >= legs * (1 - 1e-9));
      assert_true(d->contact_max_overlap <= legs + sagitta);
    }
    sw_data_free(d);
    sw_model_free(m);
  }
}

/* A soft hairpin (E = 1 MPa, R = 2 r: legs 2 r apart) whose legs are thrown
 * at each other at VS each: without self-contact they pass through each
 * other (the tips change sides); with it, the tips' centrelines never come
 * closer than 2 r less 1% of r.  k_c from the energy estimate over one pair
 * (the legs' kinetic energy all in one spring) at 0.5% of r. */
static void test_self_hairpin_throw(void **state) {
  (void)state;
  const double VS = 0.5, R = 2 * RR;
  const int n = 60;
  for (int self = 0; self < 2; self++) {
    swSpec *s = sw_spec_new();
    hairpin(s, R, RR, n, 1e6);
    const double total = 2 * LEG + M_PI * R, M = M_PI * RR * RR * total * RRHO;
    const double K = 0.5 * M * VS * VS, delta = OVERLAP_AIM * RR; /* all of it, a bound */
    swContactDesc cd = contact_desc(2 * K / (delta * delta), 0);
    const int only[1] = {0};
    cd.self = self;
    cd.nrods = 1;
    cd.rods = only;
    if (self) assert_int_equal(sw_spec_add_contact(s, &cd), 0);
    swModel *m = sw_test_compile_at(s, 0.5);
    sw_spec_free(s);
    swData *d = sw_data_new(m);
    /* the legs' nodes (outside the bend) move towards y = 0 */
    for (int i = m->node_adr[0]; i <= m->node_adr[0] + n; i++) {
      double y = SW_AT(m, d->x, i, 1), xx = SW_AT(m, d->x, i, 0);
      if (xx > 0) SW_AT(m, d->v, i, 1) = y < 0 ? VS : -VS;
    }
    double closest = INFINITY, deepest = 0;
    const double duration = 0.05;
    while (d->time < duration) {
      assert_int_equal(sw_step(m, d), SW_OK);
      closest = fmin(closest, SW_AT(m, d->x, m->node_adr[0] + n, 1) -
                                  SW_AT(m, d->x, m->node_adr[0], 1)); /* tip b - tip a, along y */
      deepest = fmax(deepest, d->contact_max_overlap);
    }
    fprintf(stderr, "# %s: self-contact %s: closest approach of the tips %.4e m (2 r = %.1e m), "
                    "deepest overlap %.3e m = %.3f%% of r, dt = %.3g s\n",
            __func__, self ? "on" : "off", closest, 2 * RR, deepest, 100 * deepest / RR, m->dt);
    if (self) assert_true(closest > 2 * RR - 0.01 * RR && deepest < 0.01 * RR);
    else assert_true(closest < 0); /* passed through */
    sw_data_free(d);
    sw_model_free(m);
  }
}

/* ---- 5. the broad phase against brute force ---- */

/* 300 rods of 8 elements (random directions, tapered radii 1-3 mm, lengths
 * 2-4 cm) in a 10 cm box, their nodes jiggled off the line so that rods
 * bend and touch themselves, random velocities; two contact descriptions
 * (all rods with self-contact, and every third rod with another k_c).  The
 * grid must find every pair the n^2 loop finds: the same forces to
 * round-off (the sums run in another order). */
static unsigned long long rng_state = 88172645463325252ull;
static double uniform(void) {
  rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
  return (double)(rng_state >> 11) / 9007199254740992.0;
}

static void test_broad_vs_brute(void **state) {
  (void)state;
  const int nrod = sw_test_sanitized() ? 120 : 300, n = 8;
  const double box = sw_test_sanitized() ? 0.07 : 0.1;
  swSpec *s = sw_spec_new();
  int *third = malloc(sizeof(int) * (size_t)nrod), nthird = 0;
  for (int r = 0; r < nrod; r++) {
    double o[3], dir[3], nrm[3], len = 0.02 + 0.02 * uniform();
    for (int k = 0; k < 3; k++) o[k] = box * uniform(), dir[k] = uniform() - 0.5;
    nrm[0] = -dir[1], nrm[1] = dir[0], nrm[2] = 0;
    swRodDesc rd = rod_desc("r", n, len, 0.001 + 0.002 * uniform(), o, dir, nrm);
    rd.radius_end = 0.001 + 0.002 * uniform();
    assert_int_equal(sw_spec_add_rod(s, &rd), r);
    if (r % 3 == 0) third[nthird++] = r;
  }
  swContactDesc all = contact_desc(1e4, 0.3);
  all.self = 1;
  assert_int_equal(sw_spec_add_contact(s, &all), 0);
  swContactDesc some = contact_desc(3e3, 0.1);
  some.nrods = nthird;
  some.rods = third;
  assert_int_equal(sw_spec_add_contact(s, &some), 1);
  swModel *m = sw_test_compile(s);
  sw_spec_free(s);
  free(third);
  swData *d = sw_data_new(m);
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
      for (int k = 0; k < 3; k++) {
        SW_AT(m, d->x, i, k) += 0.004 * (uniform() - 0.5);
        SW_AT(m, d->v, i, k) = uniform() - 0.5;
      }
  /* whole planar arrays: grid holds force, then ext_force, in their layout */
  const size_t N3 = 3 * (size_t)m->stride;
  double *grid = malloc(2 * N3 * sizeof(double));
  for (int phase = 0; phase < 2; phase++) {
    memset(d->force, 0, N3 * sizeof(double));
    memset(d->ext_force, 0, N3 * sizeof(double));
    sw_contact_loads_with(m, d, phase ? SW_CONTACT_BRUTE : SW_CONTACT_GRID);
    if (phase == 0) {
      memcpy(grid, d->force, N3 * sizeof(double));
      memcpy(grid + N3, d->ext_force, N3 * sizeof(double));
    }
  }
  int pairs_brute = d->contact_pairs;
  double scale = 0, diff = 0;
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
      for (int k = 0; k < 3; k++) {
        scale = fmax(scale, fabs(SW_AT(m, d->force, i, k)));
        diff = fmax(diff, fabs(SW_AT(m, grid, i, k) - SW_AT(m, d->force, i, k)));
        diff = fmax(diff, fabs(SW_AT(m, grid + N3, i, k) - SW_AT(m, d->ext_force, i, k)));
      }
  sw_contact_loads_with(m, d, SW_CONTACT_GRID);
  fprintf(stderr, "# %s: %d rods, %d elements: %d pairs in contact by both (grid %d); largest "
                  "force difference %.3e N of %.3e N (%.1e); contact energy %.6e J\n",
          __func__, nrod, m->nelem, pairs_brute, d->contact_pairs, diff, scale, diff / scale,
          sw_contact_energy(m, d));
  assert_int_equal(d->contact_pairs, pairs_brute);
  assert_true(pairs_brute > 100);
  assert_true(diff <= 1e-12 * scale);
  free(grid);
  sw_data_free(d);
  sw_model_free(m);
}

/* ---- 6. the stable step ---- */

/* Two stiff rods (E = 1 GPa) clamped at both ends, side by side, pressed
 * together by loads on every node that hold 0.05% of r of overlap, with a
 * contact spring k_c = 1e8 N/m that sets the step (the rods' own estimate is
 * some 20 times longer), lightly damped (gamma_c = 3 kg/s).  The estimate
 * (3 pairs on a node, docs/physics.md) must be stable, and not far from the
 * step at which the pressed pair really blows up: stable at 0.9 of it over
 * NSTEP steps, unstable at some step no longer than 1.5 of it. */
static int pressed_run(double frac, double *estimate, double *t_fail) {
  const double k = 1e8, delta = 0.0005 * RR, y = RR - 0.5 * delta;
  swSpec *s = sw_spec_new();
  const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
  for (int r = 0; r < 2; r++) {
    const double o[3] = {-0.5 * RL, r ? y : -y, 0};
    swRodDesc rd = rod_desc(r ? "b" : "a", NT, RL, RR, o, ex, ey);
    rd.youngs = 1e9;
    assert_int_equal(sw_spec_add_rod(s, &rd), r);
    for (int e = 0; e < 2; e++) {
      swBCDesc bc = sw_test_clamp(r, e);
      sw_spec_add_bc(s, &bc);
    }
    const double per_node = (3 * NT - 2) * k * delta / (NT + 1);
    for (int i = 0; i <= NT; i++) {
      swLoadDesc l = sw_test_load(SW_LOAD_FORCE, r, i, 0, r ? -per_node : per_node, 0);
      sw_spec_add_load(s, &l);
    }
  }
  swContactDesc c = contact_desc(k, 3.0);
  assert_int_equal(sw_spec_add_contact(s, &c), 0);
  swModel *m0 = sw_test_compile(s);
  *estimate = sw_stable_dt(m0);
  assert_true(sw_contact_stable_dt(m0) == *estimate); /* the contact sets it */
  sw_model_free(m0);
  sw_spec_set_dt(s, frac * *estimate);
  swModel *m = sw_test_compile(s);
  sw_spec_free(s);
  swData *d = sw_data_new(m);
  for (int r = 0; r < m->nrod; r++) /* a kick */
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++)
      SW_AT(m, d->v, i, 1) = 1e-3 * ((i * 7919) % 13 - 6);
  const long nstep = sw_test_sanitized() ? 5000 : 20000;
  int rc = sw_steps(m, d, nstep);
  *t_fail = rc == SW_OK ? INFINITY : d->time;
  sw_data_free(d);
  sw_model_free(m);
  return rc;
}

static void test_stable_dt_pressed(void **state) {
  (void)state;
  double est, t_fail;
  int rc = pressed_run(0.9, &est, &t_fail);
  fprintf(stderr, "# %s: estimate %.4g s; at 0.9 of it: %s\n", __func__, est,
          rc == SW_OK ? "stable" : "UNSTABLE");
  assert_int_equal(rc, SW_OK);
  const double fracs[] = {1.0, 1.1, 1.2, 1.3, 1.5};
  double first = INFINITY;
  for (int i = 0; i < 5 && !isfinite(first); i++) {
    rc = pressed_run(fracs[i], &est, &t_fail);
    fprintf(stderr, "#   at %.1f of it: %s", fracs[i], rc == SW_OK ? "stable\n" : "unstable");
    if (rc != SW_OK) fprintf(stderr, " at t = %.3g s\n", t_fail), first = fracs[i];
  }
  fprintf(stderr, "# %s: the pressed rods blow up from %.1f times the estimate\n", __func__, first);
  assert_true(first <= 1.5);
}

/* ---- 7. validation ---- */

static void expect_error(swContactDesc cd, int nrods_scene, const char *message) {
  swSpec *s = sw_spec_new();
  for (int r = 0; r < nrods_scene; r++) {
    const double o[3] = {0, 0.1 * r, 0}, ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
    swRodDesc rd = rod_desc("r", 4, RL, RR, o, ex, ey);
    sw_spec_add_rod(s, &rd);
  }
  assert_true(sw_spec_add_contact(s, &cd) >= 0);
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  fprintf(stderr, "# %s: \"%s\"\n", __func__, err);
  assert_null(m);
  assert_string_equal(err, message);
  sw_spec_free(s);
}

static void test_validation(void **state) {
  (void)state;
  expect_error(contact_desc(0, 0), 2, "contact 'touch': stiffness must be > 0");
  expect_error(contact_desc(-5, 0), 2, "contact 'touch': stiffness must be > 0");
  expect_error(contact_desc(NAN, 0), 2, "contact 'touch': stiffness must be > 0");
  expect_error(contact_desc(1e4, -1), 2, "contact 'touch': damping must be >= 0");
  swContactDesc c = contact_desc(1e4, 0);
  c.self = 2;
  expect_error(c, 2, "contact 'touch': self must be 0 or 1, got 2");
  const int one[1] = {0}, bad[2] = {0, 7};
  c = contact_desc(1e4, 0);
  c.nrods = 1;
  c.rods = one;
  expect_error(c, 2, "contact 'touch': one rod and no self-contact: nothing can touch");
  c.nrods = 2;
  c.rods = bad;
  expect_error(c, 2, "contact 'touch': rod 7 does not exist (the scene has 2)");
}

/* ---- main ---- */

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_throw_crossing),
      cmocka_unit_test(test_throw_parallel),
      cmocka_unit_test(test_energy_crossing),
      cmocka_unit_test(test_energy_parallel),
      cmocka_unit_test(test_restitution_rigid),
      cmocka_unit_test(test_restitution_elastic),
      cmocka_unit_test(test_self_at_rest),
      cmocka_unit_test(test_self_hairpin_throw),
      cmocka_unit_test(test_broad_vs_brute),
      cmocka_unit_test(test_stable_dt_pressed),
      cmocka_unit_test(test_validation),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
