/* test_ground.c — grounds and terrains (ground.c) against closed forms:
 * a rod on a slope held by static friction below its friction angle, and
 * sliding with acceleration g (sin a - mu_k cos a) above it for each of the
 * forward, backward and sideways coefficients; an inclined plane written as a
 * terrain height field behaving as the same plane given by origin and normal;
 * a rod settling on the barrier of Zhang et al. 2019, Supplementary Fig. 11,
 * at the height the contact law gives; the penetration of a rod at rest; the
 * energy balance of a rod bouncing on a frictionless, undamped ground; the
 * rolling-resistance couple spinning a rod down at 2 mu_rolling g / r; a
 * lateral muscle moment on a rod draped over a valley swinging its roll
 * within the work bound of a body-fixed moment instead of spinning it (the
 * reference snake's instability on the barrier); and the validation
 * messages (exact text).
 *
 * Design.  Scenes are built through the public API.  The rods are short and
 * coarse (8 elements), so every run is a few thousand steps; the ground's
 * damper is set above critical (gamma_w > 2 sqrt(k_w m_e)), so that an element
 * pressed into the ground returns to the surface without leaving it, and each
 * rod starts 1e-7 m into the ground, so it is in contact from the first step
 * (a rod starting a round-off above the surface would fall freely for one
 * step and keep that slip below the tolerance, where static friction only
 * balances loads).  Durations shrink under SW_SANITIZED (testutil.h). */
#include "testutil.h"

static const double GRAV = 9.81;
/* rod: L = 0.4 m, r = 1 cm, water density, E = 1 MPa; element mass
 * m_e = rho pi r^2 L / N = 0.0157 kg; ground k_w = 100 N/m (w = 80 rad/s),
 * gamma_w = 5 kg/s (2 x critical) */
static const double RL = 0.4, RR = 0.01, RHO = 1000, KW = 100, GW = 5, PEN0 = 1e-7;
static const int RN = 8;

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static swRodDesc rod_at(const double start[3], const double dir[3], const double normal[3],
                        double radius) {
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "rod";
  r.nelem = RN;
  r.length = RL;
  r.radius_start = r.radius_end = radius;
  r.density = RHO;
  r.youngs = 1e6;
  r.poisson = 0.5;
  for (int k = 0; k < 3; k++) {
    r.start[k] = start[k];
    r.direction[k] = dir[k];
    r.normal[k] = normal[k];
  }
  return r;
}

static swGroundDesc ground_of(double kw, double gw, const double mu_k[3], const double mu_s[3]) {
  swGroundDesc g;
  sw_ground_desc_init(&g);
  g.name = "floor";
  g.stiffness = kw;
  g.damping = gw;
  for (int k = 0; k < 3; k++) {
    g.mu_kinetic[k] = mu_k[k];
    g.mu_static[k] = mu_s[k];
  }
  return g;
}

/* A rod along x lying PEN0 into the flat ground z = 0 (ground g), under
 * gravity -z, compiled at half its stable step; the spec goes to *sout. */
static swModel *flat_scene(const swGroundDesc *g, swSpec **sout) {
  const double start[3] = {0, 0, RR - PEN0}, dir[3] = {1, 0, 0}, nrm[3] = {0, 0, 1};
  swSpec *s = sw_spec_new();
  swRodDesc r = rod_at(start, dir, nrm, RR);
  sw_spec_add_rod(s, &r);
  sw_spec_add_ground(s, g);
  const double grav[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, grav);
  *sout = s;
  return sw_test_compile_at(s, 0.5);
}

/* Mass-weighted mean of a per-node field (x or v) over all rods. */
static void com(const swModel *m, const double *field, double out[3]) {
  double M = 0;
  out[0] = out[1] = out[2] = 0;
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
      M += m->mass[i];
      for (int k = 0; k < 3; k++) out[k] += m->mass[i] * SW_AT(m, field, i, k);
    }
  for (int k = 0; k < 3; k++) out[k] /= M;
}

/* ---- slopes ---- */

/* The plane z = x tan(a) through the origin as a terrain height field. */
static double incline(double x, double y, double grad[2], const void *ctx) {
  (void)y;
  double slope = *(const double *)ctx;
  grad[0] = slope;
  grad[1] = 0;
  return slope * x;
}

enum { FORWARD = 0, BACKWARD = 1, SIDEWAYS = 2 };
static const char *const ORIENT[3] = {"forward (tangent downhill)", "backward (tangent uphill)",
                                      "sideways (tangent across)"};

/* A rod lying on the plane through the origin with normal (-sin a, 0, cos a)
 * (rising along +x), gravity -z; its tangent downhill, uphill or across,
 * centred on the origin and PEN0 into the plane.  flags: TERRAIN, the same
 * plane as a height field; CONTACT_POINT, sideways friction at the contact
 * point. */
enum { TERRAIN = 1, CONTACT_POINT = 2 };
static swModel *slope_scene(double angle, int orient, const double mu_k[3], const double mu_s[3],
                            int flags, double *slope_store, swSpec **sout) {
  const double nrm[3] = {-sin(angle), 0, cos(angle)}, down[3] = {-cos(angle), 0, -sin(angle)};
  double dir[3];
  for (int k = 0; k < 3; k++)
    dir[k] = orient == FORWARD ? down[k] : orient == BACKWARD ? -down[k] : (k == 1 ? 1.0 : 0.0);
  double start[3];
  for (int k = 0; k < 3; k++) start[k] = -0.5 * RL * dir[k] + (RR - PEN0) * nrm[k];
  swSpec *s = sw_spec_new();
  swRodDesc r = rod_at(start, dir, nrm, RR);
  sw_spec_add_rod(s, &r);
  swGroundDesc g = ground_of(KW, GW, mu_k, mu_s);
  g.name = "slope";
  g.contact_point = (flags & CONTACT_POINT) != 0;
  if (flags & TERRAIN) {
    *slope_store = tan(angle);
    g.height = incline;
    g.height_ctx = slope_store;
  } else {
    for (int k = 0; k < 3; k++) g.normal[k] = 3.0 * nrm[k]; /* normalised by sw_compile */
  }
  assert_int_equal(sw_spec_add_ground(s, &g), 0);
  const double grav[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, grav);
  *sout = s;
  return sw_test_compile_at(s, 0.5);
}

/* Claim: below its static friction angle (tan a < mu_s) a rod on a slope
 * stays put, whichever way it points.  a = 25 deg, tan a = 0.466, between
 * the kinetic coefficients (0.2, 0.3, 0.35), which alone could not hold it,
 * and the static ones (0.6, 0.7, 0.8).  Bound: static friction cancels the
 * element's tangential load exactly while its slip is below v_eps = 1e-4 m/s,
 * so only round-off can move it; a rod held by kinetic friction alone (the
 * slip function switches it off below v_eps) would creep at up to v_eps, i.e.
 * 1e-4 m in 1 s.  1e-6 m after 1 s is 1% of that. */
static void test_static_slope(void **state) {
  (void)state;
  const double a = 25.0 * M_PI / 180.0, mu_k[3] = {0.2, 0.3, 0.35}, mu_s[3] = {0.6, 0.7, 0.8};
  const double T = sw_test_sanitized() ? 0.25 : 1.0;
  const double nrm[3] = {-sin(a), 0, cos(a)};
  for (int o = 0; o < 3; o++) {
    swSpec *s;
    double slope;
    swModel *m = slope_scene(a, o, mu_k, mu_s, 0, &slope, &s);
    swData *d = sw_data_new(m);
    double c0[3], c1[3], v1[3], disp[3];
    com(m, d->x, c0);
    sw_test_run_to(m, d, T);
    com(m, d->x, c1);
    com(m, d->v, v1);
    for (int k = 0; k < 3; k++) disp[k] = c1[k] - c0[k];
    double dn = dot3(disp, nrm);
    for (int k = 0; k < 3; k++) disp[k] -= dn * nrm[k];
    double vn = dot3(v1, nrm), vt2 = dot3(v1, v1) - vn * vn;
    fprintf(stderr, "# %s: %s, dt = %.3g s, t = %.2f s: slip speed %.3e m/s, normal shift %.3e m\n",
            __func__, ORIENT[o], m->dt, T, sqrt(fmax(vt2, 0)), dn);
    SW_EXPECT_ABS("displacement along the slope (m)", sqrt(dot3(disp, disp)), 0.0, 1e-6);
    sw_data_free(d);
    sw_model_free(m);
    sw_spec_free(s);
  }
}

/* Claim: above the static friction angle a rod slides down with acceleration
 * g (sin a - mu_k cos a), mu_k the coefficient of the direction it slips in:
 * forward when its tangent points downhill, backward when it points uphill,
 * sideways when it lies across.  a = 30 deg (tan a = 0.577), kinetic
 * (0.2, 0.3, 0.4) and static (0.3, 0.4, 0.5) coefficients, so the three
 * accelerations differ by 25% and more: each coefficient is checked on its
 * own.  Measured from the centre-of-mass velocity along the slope between
 * t = 0.1 s and 0.3 s, when the slip (> 0.15 m/s) is far above 2 v_eps and
 * the friction purely kinetic. */
static void test_sliding_slope(void **state) {
  (void)state;
  const double a = 30.0 * M_PI / 180.0, mu_k[3] = {0.2, 0.3, 0.4}, mu_s[3] = {0.3, 0.4, 0.5};
  const double down[3] = {-cos(a), 0, -sin(a)};
  const double t1 = 0.1, t2 = sw_test_sanitized() ? 0.15 : 0.3;
  for (int o = 0; o < 3; o++) {
    swSpec *s;
    double slope;
    swModel *m = slope_scene(a, o, mu_k, mu_s, 0, &slope, &s);
    swData *d = sw_data_new(m);
    double v[3];
    sw_test_run_to(m, d, t1);
    com(m, d->v, v);
    double u1 = dot3(v, down), ta = d->time;
    sw_test_run_to(m, d, t2);
    com(m, d->v, v);
    double u2 = dot3(v, down), tb = d->time;
    double expect = GRAV * (sin(a) - mu_k[o] * cos(a));
    fprintf(stderr, "# %s: %s, mu_k = %.2f, slip %.3f -> %.3f m/s\n", __func__, ORIENT[o], mu_k[o],
            u1, u2);
    SW_EXPECT_REL("acceleration down the slope (m/s^2)", (u2 - u1) / (tb - ta), expect, 1e-2);
    sw_data_free(d);
    sw_model_free(m);
    sw_spec_free(s);
  }
}

/* Claim: a plane written as a terrain height field, z = x tan a, is the same
 * ground as the plane given by origin and normal: its normal from the
 * gradient, (-h_x, -h_y, 1)/sqrt(1 + |grad h|^2), and its gap (z - h)/s are
 * the plane's to round-off, so a rod sliding down both (the forward slide of
 * test_sliding_slope, 0.3 s) ends at the same positions to round-off. */
static void test_terrain_plane(void **state) {
  (void)state;
  const double a = 30.0 * M_PI / 180.0, mu_k[3] = {0.2, 0.3, 0.4}, mu_s[3] = {0.3, 0.4, 0.5};
  const double T = sw_test_sanitized() ? 0.1 : 0.3;
  swSpec *sp, *st;
  double slope_p, slope_t;
  swModel *mp = slope_scene(a, FORWARD, mu_k, mu_s, 0, &slope_p, &sp);
  swModel *mt = slope_scene(a, FORWARD, mu_k, mu_s, TERRAIN, &slope_t, &st);
  assert_true(mp->dt == mt->dt);
  swData *dp = sw_data_new(mp), *dt = sw_data_new(mt);
  sw_test_run_to(mp, dp, T);
  sw_test_run_to(mt, dt, T);
  double diff = 0, travel = 0;
  for (int r = 0; r < mp->nrod; r++)
    for (int i = mp->node_adr[r]; i <= mp->node_adr[r] + mp->rod_nelem[r]; i++)
      for (int k = 0; k < 3; k++) {
        diff = fmax(diff, fabs(SW_AT(mp, dp->x, i, k) - SW_AT(mt, dt->x, i, k)));
        travel = fmax(travel, fabs(SW_AT(mp, dp->x, i, k) - SW_AT(mp, mp->x0, i, k)));
      }
  fprintf(stderr, "# %s: travel %.3f m in %.2f s\n", __func__, travel, T);
  SW_EXPECT_ABS("largest node position difference, terrain vs plane (m)", diff, 0.0, 1e-12);
  sw_data_free(dp);
  sw_data_free(dt);
  sw_model_free(mp);
  sw_model_free(mt);
  sw_spec_free(sp);
  sw_spec_free(st);
}

/* ---- the barrier of Zhang 2019, Supplementary Fig. 11 ---- */

/* z = 0 for x < 3, -0.4 (x-3)^3 + 0.6 (x-3)^2 for 3 <= x <= 4, 0.2 beyond
 * (C1 at both joins). */
static double barrier(double x, double y, double grad[2], const void *ctx) {
  (void)y;
  (void)ctx;
  grad[1] = 0;
  if (x < 3) { grad[0] = 0; return 0; }
  if (x > 4) { grad[0] = 0; return 0.2; }
  double u = x - 3;
  grad[0] = -1.2 * u * u + 1.2 * u;
  return -0.4 * u * u * u + 0.6 * u * u;
}

/* Distance from (x, z) to the barrier's curve, by golden-section search over
 * the curve's abscissa within 2r. */
static double distance_to_barrier(double x, double z, double r) {
  double lo = x - 2 * r, hi = x + 2 * r, g[2];
  const double phi = 0.5 * (sqrt(5.0) - 1);
  for (int it = 0; it < 200; it++) {
    double p = hi - phi * (hi - lo), q = lo + phi * (hi - lo);
    double hp = barrier(p, 0, g, NULL), hq = barrier(q, 0, g, NULL);
    double dp = (p - x) * (p - x) + (hp - z) * (hp - z), dq = (q - x) * (q - x) + (hq - z) * (hq - z);
    if (dp < dq) hi = q; else lo = p;
  }
  double s = 0.5 * (lo + hi), hs = barrier(s, 0, g, NULL);
  return sqrt((s - x) * (s - x) + (hs - z) * (hs - z));
}

/* Claim: a rod dropped onto the barrier settles where its elements' gap to
 * the terrain along the normal, (z - h(x)) / sqrt(1 + h'^2), equals its
 * radius: at rest z = h(x) + r sqrt(1 + h'(x)^2).  The rod (r = 25 mm, the
 * reference snake's) lies across the slope (along y) at x = 3.5 (the
 * inflection, slope 0.3) and x = 3.2 (slope 0.19, curvature 0.72 1/m),
 * dropped from 5 mm above; the reference's k_w = 1000 N/m with an overdamped
 * gamma_w = 40 kg/s, and static (sideways) friction 0.5 holds it on the
 * slope.  The true distance to the curve differs from r by the terrain
 * approximation (design note of ground.c): asserted against its expansion. */
static void test_barrier(void **state) {
  (void)state;
  const double R = 0.025, xs[2] = {3.5, 3.2};
  const double mu_k[3] = {0.3, 0.3, 0.4}, mu_s[3] = {0.5, 0.5, 0.5};
  const double T = 1.5; /* the rest height needs the whole relaxation, sanitized or not */
  for (int p = 0; p < 2; p++) {
    double g2[2], h = barrier(xs[p], 0, g2, NULL);
    const double start[3] = {xs[p], -0.5 * RL, h + R * sqrt(1 + g2[0] * g2[0]) + 0.005};
    const double dir[3] = {0, 1, 0}, nrm[3] = {0, 0, 1};
    swSpec *s = sw_spec_new();
    swRodDesc r = rod_at(start, dir, nrm, R);
    sw_spec_add_rod(s, &r);
    swGroundDesc g = ground_of(1000, 40, mu_k, mu_s);
    g.name = "barrier";
    g.height = barrier;
    sw_spec_add_ground(s, &g);
    const double grav[3] = {0, 0, -GRAV};
    sw_spec_set_gravity(s, grav);
    swModel *m = sw_test_compile_at(s, 0.5);
    swData *d = sw_data_new(m);
    sw_test_run_to(m, d, T);
    double c[3], v[3];
    com(m, d->x, c);
    com(m, d->v, v);
    double gc[2], hc = barrier(c[0], 0, gc, NULL);
    double expect = hc + R * sqrt(1 + gc[0] * gc[0]);
    fprintf(stderr, "# %s: x = %.4f m (dropped at %.4f), speed %.2e m/s, h(x) = %.6f m, h' = %.4f\n",
            __func__, c[0], xs[p], sqrt(dot3(v, v)), hc, gc[0]);
    /* the law puts the axis anywhere in the contact band, r + [0, 1e-6 r]
     * along the normal; and a rod creeping at a slip below v_eps (where only
     * static friction acts, which balances loads but leaves the slip) moves
     * its approximate gap (z - h)/s at r d(1/s)/dt, which the damper lags by
     * gamma_w / k_w times that rate */
    double h2 = fabs(1.2 - 2.4 * (c[0] - 3)) * (c[0] > 3 && c[0] < 4); /* |h''| */
    double sc = sqrt(1 + gc[0] * gc[0]);
    double lag = g.damping / g.stiffness * g.slip_velocity * R * fabs(gc[0]) * h2 / (sc * sc);
    SW_EXPECT_ABS("rest height of the axis (m)", c[2], expect, sc * (1e-6 * R + lag));
    /* The law's gap (z - h)/s = r is the true distance d to second order:
     * d = r - r^2 h'^2 h'' / (2 s^3) (the distance to the curve expanded
     * about the point below), up to third-order terms of size
     * r^3 (|h'''| h'^2 + h''^2 |h'|), plus the band and the lag above. */
    const int on_slope = c[0] > 3 && c[0] < 4;
    double hp = fabs(gc[0]), h2s = (1.2 - 2.4 * (c[0] - 3)) * on_slope, h3 = 2.4 * on_slope;
    double second = R * R * gc[0] * gc[0] * h2s / (2 * sc * sc * sc);
    double third = R * R * R * (h3 * hp * hp + h2s * h2s * hp);
    fprintf(stderr, "# %s: second-order offset of the true distance r^2 h'^2 h''/(2 s^3) = %.3e m\n",
            __func__, second);
    SW_EXPECT_ABS("true distance of the axis to the curve (m)", distance_to_barrier(c[0], c[2], R),
                  R - second, 1e-6 * R + lag + third);
    sw_data_free(d);
    sw_model_free(m);
    sw_spec_free(s);
  }
}

/* ---- normal response ---- */

/* Claim: at rest the ground carries the weight through its balance term
 * (Gazzola 2018, eq. 4.8), not through the penalty, so the penetration the
 * law implies at rest is zero: the penalty only pushes back what an impact
 * drove in, and the overdamped spring-damper returns it to the surface at the
 * rate k_w / gamma_w = 20 1/s.  A pure penalty would sink the rod by
 * m_e g / k_w = 1.5 mm.  A rod dropped flat from 5 mm settles for 1.5 s
 * (e^-30 of the impact's 1 mm left). */
static void test_rest_penetration(void **state) {
  (void)state;
  const double zero[3] = {0, 0, 0};
  const double start[3] = {0, 0, RR + 0.005}, dir[3] = {1, 0, 0}, nrm[3] = {0, 0, 1};
  const double T = sw_test_sanitized() ? 1.0 : 1.5;
  swSpec *s = sw_spec_new();
  swRodDesc r = rod_at(start, dir, nrm, RR);
  sw_spec_add_rod(s, &r);
  swGroundDesc g = ground_of(KW, GW, zero, zero);
  sw_spec_add_ground(s, &g);
  const double grav[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, grav);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  double deepest = 0;
  while (d->time < T) {
    assert_int_equal(sw_step(m, d), SW_OK);
    for (int rod = 0; rod < m->nrod; rod++)
      for (int i = m->node_adr[rod]; i <= m->node_adr[rod] + m->rod_nelem[rod]; i++)
        deepest = fmax(deepest, RR - SW_AT(m, d->x, i, 2));
  }
  double pen = 0;
  for (int rod = 0; rod < m->nrod; rod++)
    for (int i = m->node_adr[rod]; i <= m->node_adr[rod] + m->rod_nelem[rod]; i++)
      pen = fmax(pen, fabs(RR - SW_AT(m, d->x, i, 2)));
  double me = RHO * M_PI * RR * RR * RL / RN;
  fprintf(stderr, "# %s: deepest penetration of the impact %.3e m; pure penalty m_e g / k_w = %.3e m\n",
          __func__, deepest, me * GRAV / KW);
  SW_EXPECT_ABS("penetration at rest (m)", pen, 0.0, 1e-9);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Claim: with gamma_w = 0 and no friction, a rod bouncing on the ground keeps
 * kinetic + elastic (rod and ground penalty) - work constant up to the
 * integrator's error: the balance term's work is booked by the kick like any
 * external load, and the penalty is conservative.  Two scenes on a stiff
 * ground (k_w = 1000 N/m), 0.5 s each: the elastic rod dropped flat from 2 cm,
 * and the same rod made rigid, tilted by 10 deg with its low end 2 cm up, so
 * that it lands on one end, rocks and rotates.  The largest drift of the
 * balance, relative to the drop's potential energy, is measured at two steps
 * a factor 4 apart and falls as dt^2 (position Verlet; the penalty's kink at
 * the surface and the balance switching on at touchdown do not spoil the
 * order, though they make single halvings scatter between 1.4 and 2.4).
 * (A tilted elastic rod is left out: its impact strains it by a few percent,
 * and the rod model's own balance, whose internal force n = S (s - s0) / e
 * is the gradient of the elastic energy only up to the factor 1/e, then
 * drifts by an amount that does not shrink with dt.) */
static double bounce_drift(double frac, double T, double tilt_deg, int rigid, int *bounces) {
  const double zero[3] = {0, 0, 0}, tilt = tilt_deg * M_PI / 180.0;
  const double dir[3] = {cos(tilt), 0, sin(tilt)}, nrm[3] = {-sin(tilt), 0, cos(tilt)};
  const double start[3] = {0, 0, RR + 0.02};
  swSpec *s = sw_spec_new();
  swRodDesc r = rod_at(start, dir, nrm, RR);
  r.rigid = rigid;
  sw_spec_add_rod(s, &r);
  swGroundDesc g = ground_of(1000, 0, zero, zero);
  sw_spec_add_ground(s, &g);
  const double grav[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, grav);
  swModel *m = sw_test_compile_at(s, frac);
  swData *d = sw_data_new(m);
  double e[3];
  sw_energy(m, d, e);
  const double E0 = e[0] + e[1] - e[2];
  const double scale = RHO * M_PI * RR * RR * RL * GRAV * (0.02 + 0.5 * RL * sin(tilt));
  double drift = 0;
  int contact = 0;
  *bounces = 0;
  while (d->time < T) {
    assert_int_equal(sw_step(m, d), SW_OK);
    sw_energy(m, d, e);
    drift = fmax(drift, fabs(e[0] + e[1] - e[2] - E0) / scale);
    /* the first node is below its touching height */
    int now = SW_AT(m, d->x, m->node_adr[0], 2) < RR;
    if (now && !contact) (*bounces)++;
    contact = now;
  }
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return drift;
}

static void test_bounce_energy(void **state) {
  (void)state;
  const double T = 0.5; /* at least two touchdowns; cheap even under the sanitizers */
  static const struct { const char *what; double tilt; int rigid; double frac[2]; } scene[2] = {
      {"elastic rod dropped flat", 0, 0, {0.25, 0.0625}},
      {"rigid rod dropped tilted", 10, 1, {0.125, 0.03125}},
  };
  for (int k = 0; k < 2; k++) {
    int b1, b2;
    double e1 = bounce_drift(scene[k].frac[0], T, scene[k].tilt, scene[k].rigid, &b1);
    double e2 = bounce_drift(scene[k].frac[1], T, scene[k].tilt, scene[k].rigid, &b2);
    fprintf(stderr, "# %s: %s: %d touchdowns in %.1f s; drift %.3e at %g dt_stable, %.3e at %g\n",
            __func__, scene[k].what, b1, T, e1, scene[k].frac[0], e2, scene[k].frac[1]);
    assert_true(b1 >= 2);
    SW_EXPECT_ABS("energy drift / drop energy at the smaller step", e2, 0.0, 1e-2);
    SW_EXPECT_ABS("order of the drift in dt", log(e1 / e2) / log(scene[k].frac[0] / scene[k].frac[1]),
                  2.0, 0.3);
  }
}

/* ---- friction extras ---- */

/* Claim: rolling friction is a rolling resistance, a couple mu_rolling r N
 * against the spin about the rod's axis, so a rod spinning about its axis on
 * flat ground (N = m_e g per element, J = m_e r^2 / 2 about the axis) slows at
 * 2 mu_rolling g / r and then stays (its contact-point speed r w held below
 * v_eps by the static part).  mu_rolling = 0.05, r = 1 cm: 98.1 rad/s^2 from
 * 20 rad/s, measured between 0.05 s and 0.15 s (stops at 0.204 s). */
static void test_rolling_resistance(void **state) {
  (void)state;
  const double zero[3] = {0, 0, 0}, mu_r = 0.05, w0 = 20;
  swGroundDesc g = ground_of(KW, GW, zero, zero);
  g.mu_rolling = mu_r;
  swSpec *s;
  swModel *m = flat_scene(&g, &s);
  swData *d = sw_data_new(m);
  for (int e = 0; e < m->rod_nelem[0]; e++) SW_AT(m, d->omega, m->elem_adr[0] + e, 2) = w0;
  sw_test_run_to(m, d, 0.05);
  double wa = SW_AT(m, d->omega, m->elem_adr[0] + RN / 2, 2), ta = d->time;
  sw_test_run_to(m, d, 0.15);
  double wb = SW_AT(m, d->omega, m->elem_adr[0] + RN / 2, 2), tb = d->time;
  SW_EXPECT_REL("spin-down rate (rad/s^2)", (wa - wb) / (tb - ta), 2 * mu_r * GRAV / RR, 1e-2);
  sw_test_run_to(m, d, 0.4);
  double wmax = 0;
  for (int e = 0; e < m->rod_nelem[0]; e++)
    wmax = fmax(wmax, fabs(SW_AT(m, d->omega, m->elem_adr[0] + e, 2)));
  fprintf(stderr, "# %s: contact-point speed after stopping %.3e m/s (v_eps %.0e)\n", __func__,
          wmax * RR, g.slip_velocity);
  assert_true(wmax * RR <= g.slip_velocity);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Claim: with mu_static = 0 and mu_rolling = 0 (the reference snake's
 * ground) friction is kinetic anisotropic friction on the element velocity:
 * a rod on flat ground sliding sideways at 0.5 m/s and spinning about its
 * axis at 40 rad/s (its contact point slipping at v + r w = 0.9 m/s)
 * decelerates at mu_sideways g, whatever its spin, and keeps the spin.
 * Measured between 0.02 s and 0.08 s (slip > 0.3 m/s). */
static void test_kinetic_on_element_velocity(void **state) {
  (void)state;
  const double zero[3] = {0, 0, 0}, mu_k[3] = {0.1, 0.2, 0.3}, v0 = 0.5, w0 = 40;
  swGroundDesc g = ground_of(KW, GW, mu_k, zero);
  swSpec *s;
  swModel *m = flat_scene(&g, &s);
  swData *d = sw_data_new(m);
  for (int i = 0; i <= m->rod_nelem[0]; i++) SW_AT(m, d->v, m->node_adr[0] + i, 1) = v0;
  for (int e = 0; e < m->rod_nelem[0]; e++) SW_AT(m, d->omega, m->elem_adr[0] + e, 2) = w0;
  double v[3];
  sw_test_run_to(m, d, 0.02);
  com(m, d->v, v);
  double va = v[1], ta = d->time;
  sw_test_run_to(m, d, 0.08);
  com(m, d->v, v);
  double vb = v[1], tb = d->time;
  SW_EXPECT_REL("sideways deceleration (m/s^2)", (va - vb) / (tb - ta), mu_k[2] * GRAV, 1e-2);
  SW_EXPECT_REL("spin after 0.08 s (rad/s)", SW_AT(m, d->omega, m->elem_adr[0] + RN / 2, 2), w0,
                1e-9);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Claim: an element standing on its end (its tangent along the normal: no
 * direction in the surface) takes isotropic friction along its slip, and
 * its loads stay finite (its directions a and b, which divide by the
 * tangent's part in the surface, are not used; ground.c selects rather than
 * multiplies by 0).  A stubby upright rod (2 elements of 2 cm, r = 3 cm:
 * only the bottom element touches) slides sideways at 0.5 m/s under
 * gravity on a ground of isotropic kinetic friction mu_k = 0.3; after its
 * first step it tilts and the ordinary path takes over.  Over 20 ms its
 * centre of mass slows at mu_k g within 1% (N is the weight once the
 * penalty has settled, to the rod's tilt and the contact's transient). */
static void test_standing_on_end(void **state) {
  (void)state;
  const double zero[3] = {0, 0, 0}, mu_k[3] = {0.3, 0.3, 0.3}, v0 = 0.5, rr = 0.03, len = 0.04;
  const double start[3] = {0, 0, rr - PEN0 - 0.25 * len}, dir[3] = {0, 0, 1}, nrm[3] = {1, 0, 0};
  swSpec *s = sw_spec_new();
  swRodDesc r = rod_at(start, dir, nrm, rr);
  r.nelem = 2;
  r.length = len;
  sw_spec_add_rod(s, &r);
  swGroundDesc g = ground_of(1e4, 150, mu_k, zero);
  assert_int_equal(sw_spec_add_ground(s, &g), 0);
  const double grav[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, grav);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  for (int i = 0; i <= m->rod_nelem[0]; i++) SW_AT(m, d->v, m->node_adr[0] + i, 0) = v0;
  assert_int_equal(sw_step(m, d), SW_OK);
  for (int i = 0; i <= m->rod_nelem[0]; i++)
    for (int k = 0; k < 3; k++) assert_true(isfinite(SW_AT(m, d->v, m->node_adr[0] + i, k)));
  double v[3];
  sw_test_run_to(m, d, 0.01);
  com(m, d->v, v);
  const double va = v[0], ta = d->time;
  sw_test_run_to(m, d, 0.03);
  com(m, d->v, v);
  SW_EXPECT_REL("deceleration on its end (m/s^2)", (va - v[0]) / (d->time - ta), mu_k[0] * GRAV, 1e-2);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Claim: kinetic friction follows the direction of the slip (Hu et al.,
 * PNAS 2009; Gazzola 2018; PyElastica's snake friction): a rod sliding at
 * an angle theta to its tangent is decelerated by
 *   a = -g (mu_forward cos(theta) a + mu_sideways sin(theta) b),
 * each coefficient weighted by the slip's direction cosine, not by its sign
 * (which would give -g (mu_forward a + mu_sideways b)).  Measured over 2 ms,
 * in which the slip turns by less than 0.3 degrees. */
static void test_kinetic_follows_slip_direction(void **state) {
  (void)state;
  const double zero[3] = {0, 0, 0}, mu_k[3] = {0.2, 0.3, 0.5}, v0 = 0.5;
  const double theta = 40 * M_PI / 180;
  swGroundDesc g = ground_of(KW, GW, mu_k, zero);
  swSpec *s;
  swModel *m = flat_scene(&g, &s);
  swData *d = sw_data_new(m);
  for (int i = m->node_adr[0]; i <= m->node_adr[0] + m->rod_nelem[0]; i++) {
    SW_AT(m, d->v, i, 0) = v0 * cos(theta);
    SW_AT(m, d->v, i, 1) = v0 * sin(theta);
  }
  double va[3], vb[3];
  com(m, d->v, va);
  double ta = d->time;
  sw_test_run_to(m, d, 0.002);
  com(m, d->v, vb);
  double dt = d->time - ta;
  double ax = (vb[0] - va[0]) / dt, ay = (vb[1] - va[1]) / dt;
  SW_EXPECT_REL("deceleration along the tangent (m/s^2)", -ax, GRAV * mu_k[0] * cos(theta), 1e-2);
  SW_EXPECT_REL("deceleration sideways (m/s^2)", -ay, GRAV * mu_k[2] * sin(theta), 1e-2);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- friction at the contact point ---- */

/* Mean over the elements of the spin about the rod's axis in the lab frame,
 * w . t (t: the element's unit tangent), rad/s. */
static double axial_spin(const swModel *m, const swData *d) {
  double sum = 0;
  const int n = m->rod_nelem[0];
  for (int i = 0; i < n; i++) {
    const int e = m->elem_adr[0] + i, a = m->node_adr[0] + i;
    double Q[9], w[3], wl[3], t[3];
    sw_getQ(m, d->Q, e, Q);
    sw_get3(m, d->omega, e, w);
    for (int k = 0; k < 3; k++) /* material to lab: sum_j w_j d_j, d_j the rows of Q */
      wl[k] = Q[k] * w[0] + Q[3 + k] * w[1] + Q[6 + k] * w[2];
    for (int k = 0; k < 3; k++) t[k] = SW_AT(m, d->x, a + 1, k) - SW_AT(m, d->x, a, k);
    sum += dot3(wl, t) / sqrt(dot3(t, t));
  }
  return sum / n;
}

/* Claim: with contact_point, sideways friction acts at the contact point
 * -r n, so a rod lying across a slope is a cylinder on an incline.  Slipping
 * (tan a > 3 mu_sideways), its centre accelerates at g (sin a - mu cos a),
 * as with friction at the centreline, and the friction's couple r mu N
 * spins it up about its axis at 2 mu g cos a / r (J = m r^2 / 2).  a = 30
 * deg, mu_sideways = 0.1 (tan a = 0.577 > 0.3): 4.055 m/s^2 and 169.9
 * rad/s^2, measured between 0.1 s and 0.3 s, when the contact point slips
 * at more than 0.4 m/s.  With mu_static = 0.3 >= tan a / 3 the cylinder
 * rolls without slipping instead: static friction holds the contact point,
 * so the centre accelerates at 2/3 g sin a = 3.270 m/s^2 (where friction at
 * the centreline, 0.3 < tan a, lets it slide at g (sin a - 0.25 cos a) =
 * 2.781), its spin follows as v / r, and the contact point's slip stays
 * below v_eps. */
static void test_contact_point_incline(void **state) {
  (void)state;
  const double a = 30.0 * M_PI / 180.0, down[3] = {-cos(a), 0, -sin(a)};
  const double t1 = 0.1, t2 = sw_test_sanitized() ? 0.15 : 0.3;
  for (int rolling = 0; rolling < 2; rolling++) {
    const double mu_k[3] = {0.2, 0.3, rolling ? 0.25 : 0.1};
    const double mu_s[3] = {0, 0, rolling ? 0.3 : 0};
    swSpec *s;
    double slope, v[3];
    swModel *m = slope_scene(a, SIDEWAYS, mu_k, mu_s, CONTACT_POINT, &slope, &s);
    swData *d = sw_data_new(m);
    sw_test_run_to(m, d, t1);
    com(m, d->v, v);
    double u1 = dot3(v, down), w1 = axial_spin(m, d), ta = d->time;
    sw_test_run_to(m, d, t2);
    com(m, d->v, v);
    double u2 = dot3(v, down), w2 = axial_spin(m, d), tb = d->time;
    const double acc = (u2 - u1) / (tb - ta), spin = fabs(w2 - w1) / (tb - ta);
    fprintf(stderr, "# %s: %s: speed %.3f -> %.3f m/s, spin %.2f -> %.2f rad/s, contact-point "
            "slip at the end %.3e m/s\n", __func__, rolling ? "rolling" : "slipping", u1, u2, w1,
            w2, fabs(u2) - RR * fabs(w2));
    if (!rolling) {
      SW_EXPECT_REL("acceleration across the slope, slipping (m/s^2)", acc,
                    GRAV * (sin(a) - mu_k[2] * cos(a)), 1e-2);
      SW_EXPECT_REL("spin-up about the axis, slipping (rad/s^2)", spin,
                    2 * mu_k[2] * GRAV * cos(a) / RR, 1e-2);
    } else {
      SW_EXPECT_REL("acceleration across the slope, rolling (m/s^2)", acc,
                    2.0 / 3.0 * GRAV * sin(a), 1e-2);
      SW_EXPECT_REL("spin-up about the axis, rolling (rad/s^2)", spin,
                    2.0 / 3.0 * GRAV * sin(a) / RR, 1e-2);
      assert_true(fabs(fabs(u2) - RR * fabs(w2)) < 2 * 1e-4); /* below 2 v_eps */
    }
    sw_data_free(d);
    sw_model_free(m);
    sw_spec_free(s);
  }
}

/* Claim: the bowling ball.  A rod on flat ground sliding sideways at v0 =
 * 0.5 m/s and spinning so that its contact point slips at v0 + r w0 = 0.1
 * m/s (r w0 = -0.4 m/s, w0 about +x, its axis) feels kinetic friction
 * against that slip: its angular momentum about the contact line is kept,
 * so it ends rolling at (2 v0 - r w0) / 3 = 0.4667 m/s, after t* = 0.1 /
 * (3 mu g) = 8.5 ms (mu =
 * 0.4), whereas friction at the centreline (test_kinetic_on_element_velocity)
 * would keep the spin and stop the slide.  Once it rolls, the ground sees no
 * slip: the rod travels r times the angle its directors turn, which checks
 * the direction of the couple against the frames the integrator turns. */
static void test_contact_point_bowling(void **state) {
  (void)state;
  const double zero[3] = {0, 0, 0}, mu_k[3] = {0.1, 0.2, 0.4}, v0 = 0.5, w0 = -40;
  swGroundDesc g = ground_of(KW, GW, mu_k, zero);
  g.contact_point = 1;
  swSpec *s;
  swModel *m = flat_scene(&g, &s);
  swData *d = sw_data_new(m);
  for (int i = 0; i <= m->rod_nelem[0]; i++) SW_AT(m, d->v, m->node_adr[0] + i, 1) = v0;
  for (int e = 0; e < m->rod_nelem[0]; e++) SW_AT(m, d->omega, m->elem_adr[0] + e, 2) = w0;
  const double w_lab = axial_spin(m, d); /* +w0: the tangent is +x = d3 */
  /* the contact point -r z moves at v + w x (-r z) = v + r w_x along y */
  SW_EXPECT_ABS("initial contact-point slip (m/s)", v0 + RR * w_lab, 0.1, 1e-12);
  double v[3], c[3];
  sw_test_run_to(m, d, 0.03);
  com(m, d->v, v);
  com(m, d->x, c);
  const int mid = m->elem_adr[0] + RN / 2;
  double Q[9];
  sw_getQ(m, d->Q, mid, Q);
  /* d1 (row 0 of Q) turns in the y-z plane: by phi about +x it is
   * (0, -sin phi, cos phi), and rolling along +y turns it by -y / r */
  const double ya = c[1], phia = -atan2(Q[1], Q[2]);
  SW_EXPECT_REL("rolling speed after the slip stops (m/s)", v[1], (2 * v0 - RR * w_lab) / 3, 1e-2);
  sw_test_run_to(m, d, 0.06); /* 1.4 rad, inside atan2's range */
  com(m, d->x, c);
  sw_getQ(m, d->Q, mid, Q);
  double turn = -atan2(Q[1], Q[2]) - phia;
  fprintf(stderr, "# %s: rolled %.4f m while d1 turned %.4f rad (r x turn = %.4f m)\n", __func__,
          c[1] - ya, turn, RR * turn);
  SW_EXPECT_REL("distance rolled against r x the frame's turn", c[1] - ya, -RR * turn, 1e-2);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* Largest speed across the rod (along y) of the points where its elements
 * touch the ground: the element centre's, plus r w_x with the contact point
 * at -r z when friction acts there (rod along x on the ground z = 0). */
static double largest_slip_across(const swModel *m, const swData *d, int contact_point) {
  double worst = 0;
  for (int i = 0; i < m->rod_nelem[0]; i++) {
    const int e = m->elem_adr[0] + i, a = m->node_adr[0] + i;
    double u = 0.5 * (SW_AT(m, d->v, a, 1) + SW_AT(m, d->v, a + 1, 1));
    if (contact_point) {
      double Q[9], w[3];
      sw_getQ(m, d->Q, e, Q);
      sw_get3(m, d->omega, e, w);
      u += RR * (Q[0] * w[0] + Q[3] * w[1] + Q[6] * w[2]); /* + r (w_lab . x) */
    }
    worst = fmax(worst, fabs(u));
  }
  return worst;
}

/* Claim: kinetic friction never reverses a slip within one step.  With the
 * slip tolerance of PyElastica's snake, v_eps = 1e-8 m/s, Coulomb friction
 * mu N against a slip that a step's kick of mu g h would carry past zero
 * would chatter at +-mu g h (1e-3 m/s here) about rest.  Capped at the
 * force that stops the slip in one step (m u / h, ground.c), a rod sliding
 * sideways at 0.1 m/s with mu = 0.5 stops at 20.4 ms, as g mu gives, and
 * then stays put: below 2 v_eps.  With friction at the contact point the
 * same rod is the bowling ball of test_contact_point_bowling: it ends
 * rolling at 2/3 of its speed, and it is its contact point that stays below
 * 2 v_eps. */
static void test_friction_never_reverses(void **state) {
  (void)state;
  const double zero[3] = {0, 0, 0}, mu_k[3] = {0.3, 0.4, 0.5}, v0 = 0.1;
  for (int cp = 0; cp < 2; cp++) {
    swGroundDesc g = ground_of(KW, GW, mu_k, zero);
    g.slip_velocity = 1e-8;
    g.contact_point = cp;
    swSpec *s;
    swModel *m = flat_scene(&g, &s);
    swData *d = sw_data_new(m);
    for (int i = 0; i <= m->rod_nelem[0]; i++) SW_AT(m, d->v, m->node_adr[0] + i, 1) = v0;
    double v[3];
    sw_test_run_to(m, d, 0.01);
    com(m, d->v, v);
    if (cp) SW_EXPECT_REL("rolling speed at 10 ms (m/s)", v[1], 2.0 / 3.0 * v0, 1e-2);
    else SW_EXPECT_REL("sliding speed at 10 ms (m/s)", v[1], v0 - mu_k[2] * GRAV * d->time, 1e-2);
    double worst = 0;
    while (d->time < 0.05) {
      sw_test_run_to(m, d, d->time + 0.002);
      if (d->time >= 0.025) worst = fmax(worst, largest_slip_across(m, d, cp));
    }
    fprintf(stderr, "# %s: %s: largest slip across, 25-50 ms: %.3e m/s (mu g h = %.3e)\n",
            __func__, cp ? "contact point" : "centreline", worst, mu_k[2] * GRAV * m->dt);
    assert_true(worst < 2 * g.slip_velocity);
    sw_data_free(d);
    sw_model_free(m);
    sw_spec_free(s);
  }
}

/* ---- the roll of a rod on a curved terrain ---- */

/* A valley of radius of curvature VALLEY_R at its bottom, z = x^2 / (2 R). */
static const double VALLEY_R = 0.5;
static double valley(double x, double y, double grad[2], const void *ctx) {
  (void)y;
  (void)ctx;
  grad[0] = x / VALLEY_R;
  grad[1] = 0;
  return 0.5 * x * x / VALLEY_R;
}

/* Arc length of the valley's curve from its bottom to abscissa x. */
static double valley_arc(double x) {
  const double u = x / VALLEY_R;
  return 0.5 * x * sqrt(1 + u * u) + 0.5 * VALLEY_R * asinh(u);
}

/* Claim: a lateral muscle moment cannot spin a rod lying over a curved
 * terrain about its own axis.  The roll of a straight-at-rest, round,
 * isotropic rod has no elastic stiffness and this ground puts no couple on
 * it (friction at the element centre, mu_rolling = 0), so a moment about a
 * lab-fixed axis z, whose part about the element axes
 * sum_i tau_i z . (d3_i - d3_{i-1}) does not depend on the roll, spins the
 * rod up without bound at D / J (how the reference's snake went unstable on
 * the barrier of Zhang 2019 Suppl. Fig. 11).  The wave's moment is
 * body-fixed (wave.c), about d1, which on the draped rod starts along the
 * turn of the tangent d3_i - d3_{i-1}: its part about the axes goes as
 * tau_i |d3_i - d3_{i-1}| cos(roll), so over any roll from rest it does at
 * most the work D = sum_i |tau_i| |d3_i - d3_{i-1}|, which bounds the
 * kinetic energy of the roll.  A soft rod (L = 0.4 m,
 * r = 2 cm, E = 0.1 MPa, so that gravity keeps it draped: E I kappa is a
 * tenth of the weight's w L^2 / 8) lies across the bottom of a valley of
 * radius 0.5 m (tangents +-22 deg at its ends) under a uniform moment
 * tau = E I x 1/m about z, ramped in over 0.05 s, with the reference snake's
 * kinetic friction. */
static void test_roll_on_curved_terrain(void **state) {
  (void)state;
  const int n = 16;
  const double L = 0.4, R = 0.02, E = 1e5, tau = E * M_PI * pow(R, 4) / 4 * 1.0;
  swSpec *s = sw_spec_new();
  const double zero[3] = {0, 0, 0}, mu_k[3] = {0.5, 0.75, 1.0};
  swRodDesc r = rod_at(zero, (const double[3]){1, 0, 0}, (const double[3]){0, 0, 1}, R);
  r.nelem = n;
  r.length = L;
  r.youngs = E;
  sw_spec_add_rod(s, &r);
  swGroundDesc g = ground_of(1000, 40, mu_k, zero);
  g.name = "valley";
  g.height = valley;
  sw_spec_add_ground(s, &g);
  const double grav[3] = {0, 0, -GRAV};
  sw_spec_set_gravity(s, grav);
  swWaveDesc w;
  sw_wave_desc_init(&w);
  w.rod = 0;
  w.ncoef = 4;
  for (int k = 0; k < 4; k++) w.coef[k] = tau; /* beta = tau all along */
  w.wavelength = w.period = 1e12;
  w.phase = M_PI / 2; /* tau(s, t) = ramp(t) beta */
  w.ramp = 0.05;
  w.direction[2] = 1;
  sw_spec_add_wave(s, &w);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  /* drape the rod (straight at rest) over the valley: nodes at equal arc
   * length on the curve offset by r, rows d1 (the normal) d2 d3 (tangent) */
  for (int i = 0; i <= n; i++) {
    double target = L * ((double)i / n - 0.5), xi = target;
    for (int it = 0; it < 50; it++) /* Newton on the arc length */
      xi -= (valley_arc(xi) - target) / sqrt(1 + xi * xi / (VALLEY_R * VALLEY_R));
    double gr[2], h = valley(xi, 0, gr, NULL), sc = sqrt(1 + gr[0] * gr[0]);
    const int ni = m->node_adr[0] + i;
    SW_AT(m, d->x, ni, 0) = xi - (R - PEN0) * gr[0] / sc;
    SW_AT(m, d->x, ni, 1) = 0;
    SW_AT(m, d->x, ni, 2) = h + (R - PEN0) / sc;
  }
  const int e0 = m->elem_adr[0], i0 = m->node_adr[0];
  for (int e = 0; e < n; e++) {
    double t[3];
    for (int k = 0; k < 3; k++) t[k] = SW_AT(m, d->x, i0 + e + 1, k) - SW_AT(m, d->x, i0 + e, k);
    const double len = sqrt(dot3(t, t));
    const double row[9] = {-t[2] / len, 0, t[0] / len, 0, -1, 0, t[0] / len, 0, t[2] / len};
    sw_setQ(m, d->Q, e0 + e, row);
  }
  double bound = 0; /* D on the draped rod: the interior nodes carry tau */
  for (int e = 1; e < n; e++) {
    double turn[3];
    for (int k = 0; k < 3; k++)
      turn[k] = SW_AT(m, d->Q, e0 + e, 6 + k) - SW_AT(m, d->Q, e0 + e - 1, 6 + k);
    bound += tau * sqrt(dot3(turn, turn));
  }
  /* the lab-fixed drive, sum_i tau z . (d3_i - d3_{i-1}) = tau z . (d3_last - d3_first) */
  const double drive = tau * (SW_AT(m, d->Q, e0 + n - 1, 8) - SW_AT(m, d->Q, e0, 8));
  const double T = sw_test_sanitized() ? 0.5 : 1.0;
  double roll_max = 0, w_max = 0;
  while (d->time < T) {
    sw_test_run_to(m, d, d->time + 0.005);
    double roll = 0;
    for (int e = 0; e < n; e++) {
      const double w3 = SW_AT(m, d->omega, e0 + e, 2);
      roll += 0.5 * SW_AT(m, m->inertia, e0 + e, 2) / d->dilatation[e0 + e] * w3 * w3;
      w_max = fmax(w_max, fabs(w3));
    }
    roll_max = fmax(roll_max, roll);
  }
  /* the lab-fixed drive would have turned the rod (J = n J_3) at
   * drive (T - ramp / 2) / J by T */
  fprintf(stderr, "# %s: D = %.3g N m; largest roll rate %.3g rad/s, against %.3g rad/s by %.2f s "
          "for a lab-fixed moment\n", __func__, bound, w_max,
          drive * (T - 0.5 * w.ramp) / (n * SW_AT(m, m->inertia, e0, 2)), T);
  SW_EXPECT_ABS("largest kinetic energy of the roll / D", roll_max / bound, 0.0, 1.0);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- validation ---- */

static void expect_error(const swGroundDesc *g, const char *want) {
  swSpec *s = sw_spec_new();
  const double start[3] = {0, 0, 0.1}, dir[3] = {1, 0, 0}, nrm[3] = {0, 0, 1};
  swRodDesc r = rod_at(start, dir, nrm, RR);
  sw_spec_add_rod(s, &r);
  assert_int_equal(sw_spec_add_ground(s, g), 0);
  char err[256] = "";
  swModel *m = sw_compile(s, err, sizeof err);
  fprintf(stderr, "# %s: \"%s\"\n", __func__, err);
  assert_null(m);
  assert_string_equal(err, want);
  sw_spec_free(s);
}

static void test_validation(void **state) {
  (void)state;
  const double zero[3] = {0, 0, 0};
  swGroundDesc g = ground_of(KW, GW, zero, zero);
  g.name = "slope";
  g.mu_kinetic[0] = -0.1;
  expect_error(&g, "ground 'slope': kinetic friction coefficient forward is -0.1, must be >= 0");
  g = ground_of(KW, GW, zero, zero);
  g.name = "slope";
  g.mu_static[2] = -1;
  expect_error(&g, "ground 'slope': static friction coefficient sideways is -1, must be >= 0");
  g = ground_of(KW, GW, zero, zero);
  g.name = "slope";
  g.normal[2] = 0;
  expect_error(&g, "ground 'slope': normal must be a nonzero vector");
  g = ground_of(-1, GW, zero, zero);
  g.name = "slope";
  expect_error(&g, "ground 'slope': stiffness must be >= 0");
  g = ground_of(KW, GW, zero, zero);
  g.name = "slope";
  g.mu_rolling = -0.5;
  expect_error(&g, "ground 'slope': rolling friction coefficient must be >= 0");
  g = ground_of(KW, GW, zero, zero);
  g.name = "slope";
  g.slip_velocity = 0;
  expect_error(&g, "ground 'slope': slip velocity tolerance must be > 0");
  const int bad = 3;
  g = ground_of(KW, GW, zero, zero);
  g.name = "slope";
  g.nrods = 1;
  g.rods = &bad;
  expect_error(&g, "ground 'slope': rod 3 does not exist (the scene has 1)");
  g = ground_of(KW, GW, zero, zero);
  g.name = "slope";
  g.contact_tolerance = -1e-3;
  expect_error(&g, "ground 'slope': contact tolerance must be >= 0");
}

/* The ground's step limit is its spring's: 0.95 x 2 / w with w^2 = k_w / m_e
 * (undamped), when the ground is stiffer than the rod. */
static void test_stable_dt(void **state) {
  (void)state;
  const double zero[3] = {0, 0, 0}, kw = 1e9;
  const double start[3] = {0, 0, RR}, dir[3] = {1, 0, 0}, nrm[3] = {0, 0, 1};
  swSpec *s = sw_spec_new();
  swRodDesc r = rod_at(start, dir, nrm, RR);
  sw_spec_add_rod(s, &r);
  swGroundDesc g = ground_of(kw, 0, zero, zero);
  sw_spec_add_ground(s, &g);
  swModel *m = sw_test_compile(s);
  double me = RHO * M_PI * RR * RR * RL / RN;
  SW_EXPECT_REL("stable dt with a stiff ground (s)", sw_stable_dt(m), 0.95 * 2 / sqrt(kw / me), 1e-9);
  sw_model_free(m);
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_validation),
      cmocka_unit_test(test_stable_dt),
      cmocka_unit_test(test_static_slope),
      cmocka_unit_test(test_sliding_slope),
      cmocka_unit_test(test_terrain_plane),
      cmocka_unit_test(test_barrier),
      cmocka_unit_test(test_rest_penetration),
      cmocka_unit_test(test_bounce_energy),
      cmocka_unit_test(test_rolling_resistance),
      cmocka_unit_test(test_kinetic_on_element_velocity),
      cmocka_unit_test(test_roll_on_curved_terrain),
      cmocka_unit_test(test_kinetic_follows_slip_direction),
      cmocka_unit_test(test_standing_on_end),
      cmocka_unit_test(test_contact_point_incline),
      cmocka_unit_test(test_contact_point_bowling),
      cmocka_unit_test(test_friction_never_reverses),
  };
  return cmocka_run_group_tests_name("ground", tests, NULL, NULL);
}
