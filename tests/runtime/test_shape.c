/* test_shape.c — curved rods (shape.c, and model.c's rest and starting
 * shapes) against the closed forms of the curves.
 *
 * A circular helix of radius R and pitch 2 pi c has curvature
 * kappa = R / (R^2 + c^2) and torsion tau = c / (R^2 + c^2), and arc length
 * Theta sqrt(R^2 + c^2) over the angle Theta.  sw_shape_helix must put every
 * node on it (distance R from the axis, rise c per radian), with Frenet
 * frames; the rest curvature the model then computes from the frames must be
 * (0, kappa, +-tau) and converge to it at second order in the element
 * length, as must the total rest length (the sum of the chords).  The
 * parallel-transported frames of sw_shape_curve on the same helix must have
 * no twist (kappa_3 = 0 to round-off) and a bend of magnitude kappa.  A rod
 * that rests as a helix and starts in it is in equilibrium: its largest
 * velocity after a thousand steps is round-off.  A rod that rests as a helix
 * and starts straight (sw_shape_straight) starts unstretched.  The stable
 * step estimate stays safe and tight for a helical rod, measured by
 * bisection as in test_stability.c. */
#include "testutil.h"
#include "internal.h"
#include "vec.h"

static const double R = 0.01, PITCH = 0.425 / 9, TURNS = 9;   /* Zhang 2019, Table 3 */

static double helix_c(void) { return PITCH / (2 * M_PI); }
static double helix_arc(void) { return 2 * M_PI * TURNS * sqrt(R * R + helix_c() * helix_c()); }

/* A rod resting in (and, unless start_straight, starting in) the helix. */
static swModel *helix_rod(int n, int hand, int start_straight, double dt_factor) {
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "coil";
  r.nelem = n;
  r.length = helix_arc();
  r.radius_start = r.radius_end = 0.002;
  r.density = 1670;
  r.youngs = 3e7;
  int id = sw_spec_add_rod(s, &r);
  double *x = malloc(sizeof(double) * 3 * (n + 1)), *Q = malloc(sizeof(double) * 9 * n);
  const double start[3] = {0, 0, 0}, axis[3] = {0, 0, 1}, normal[3] = {1, 0, 0};
  char err[200];
  assert_int_equal(sw_shape_helix(n, R, PITCH, helix_arc(), hand, start, axis, normal, x, Q, err,
                                  sizeof err), SW_OK);
  assert_int_equal(sw_spec_set_rest_shape(s, id, x, Q), SW_OK);
  if (start_straight) {
    double *xs = malloc(sizeof(double) * 3 * (n + 1)), *Qs = malloc(sizeof(double) * 9 * n);
    const double dir[3] = {0, 1, 0};
    assert_int_equal(sw_shape_straight(n, x, start, dir, normal, xs, Qs, err, sizeof err), SW_OK);
    assert_int_equal(sw_spec_set_start_shape(s, id, xs, Qs), SW_OK);
    free(xs);
    free(Qs);
  }
  free(x);
  free(Q);
  swModel *m = dt_factor > 0 ? sw_test_compile_at(s, dt_factor) : sw_test_compile(s);
  sw_spec_free(s);
  return m;
}

/* The largest errors of the discrete helix of n elements: node off the
 * helix, rest curvature components against (0, kappa, hand tau), rest length. */
static void helix_errors(int n, int hand, double *node, double *bend, double *twist,
                         double *length) {
  swModel *m = helix_rod(n, hand, 0, 0);
  const double c = helix_c(), kappa = R / (R * R + c * c), tau = hand * c / (R * R + c * c);
  /* the axis passes through start + R normal = (R, 0, 0) */
  *node = 0;
  for (int i = 0; i <= n; i++) {
    double x[3];
    sw_get3(m, m->x0, m->node_adr[0] + i, x);
    double dx = x[0] - R, dy = x[1], rho = sqrt(dx * dx + dy * dy);
    /* the angle from the start, unwrapped by the node's index, and the rise */
    double th = 2 * M_PI * TURNS * i / n;
    double ex = R * (1 - cos(th)) - x[0], ey = -hand * R * sin(th) - x[1], ez = c * th - x[2];
    (void)dx;
    *node = fmax(*node, fmax(fabs(rho - R), sqrt(ex * ex + ey * ey + ez * ez)));
  }
  *bend = *twist = 0;
  for (int v = 0; v < n - 1; v++) {
    double k[3];
    sw_get3(m, m->rest_kappa, m->vor_adr[0] + v, k);
    *bend = fmax(*bend, fmax(fabs(k[0]), fabs(k[1] - kappa)) / kappa);
    *twist = fmax(*twist, fabs(k[2] - tau) / fabs(tau));
  }
  double L = 0;
  for (int e = 0; e < n; e++) L += m->rest_len[m->elem_adr[0] + e];
  *length = fabs(L / helix_arc() - 1);
  sw_model_free(m);
}

static void test_helix_geometry(void **state) {
  (void)state;
  for (int hand = 1; hand >= -1; hand -= 2) {
    double node[3], bend[3], twist[3], len[3];
    int n0 = 12 * (int)TURNS;   /* the reference's 12 elements a turn */
    for (int k = 0; k < 3; k++) helix_errors(n0 << k, hand, &node[k], &bend[k], &twist[k], &len[k]);
    const double c = helix_c();
    fprintf(stderr, "# %s: %s-handed helix R = %g m, pitch %g m, %g turns: kappa = %.6g 1/m, "
            "tau = %.6g 1/m, arc length %.6g m\n", __func__, hand > 0 ? "right" : "left", R,
            PITCH, TURNS, R / (R * R + c * c), hand * c / (R * R + c * c), helix_arc());
    for (int k = 0; k < 3; k++)
      fprintf(stderr, "#   %4d elements: node off the helix %.2e m, rest kappa_1,2 rel. error "
              "%.3e, rest kappa_3 (tau) rel. error %.3e, rest length rel. error %.3e\n",
              n0 << k, node[k], bend[k], twist[k], len[k]);
    for (int k = 0; k < 2; k++) {
      double ob = log2(bend[k] / bend[k + 1]), ot = log2(twist[k] / twist[k + 1]),
             ol = log2(len[k] / len[k + 1]);
      fprintf(stderr, "#   order %d -> %d elements: curvature %.3f, torsion %.3f, length %.3f\n",
              n0 << k, n0 << (k + 1), ob, ot, ol);
      assert_true(fabs(ob - 2) < 0.1 && fabs(ot - 2) < 0.1 && fabs(ol - 2) < 0.1);
    }
    for (int k = 0; k < 3; k++) assert_true(node[k] < 1e-15 * 50 * helix_arc());
    assert_true(bend[0] < 0.005 && twist[0] < 0.02);   /* 12 a turn: within 0.5% and 2% */
  }
}

static void helix_curve(double s, double r[3], const void *ctx) {
  (void)ctx;
  const double c = helix_c(), th = s / sqrt(R * R + c * c);
  r[0] = R * cos(th);
  r[1] = R * sin(th);
  r[2] = c * th;
}

/* The helix as a centreline r(s): parallel transport, no twist. */
static void test_curve_transport(void **state) {
  (void)state;
  const double c = helix_c(), kappa = R / (R * R + c * c);
  double err[3];
  for (int k = 0; k < 3; k++) {
    int n = (12 * (int)TURNS) << k;
    swSpec *s = sw_spec_new();
    swRodDesc r;
    sw_rod_desc_init(&r);
    r.name = "curve";
    r.nelem = n;
    r.length = helix_arc();
    int id = sw_spec_add_rod(s, &r);
    double *x = malloc(sizeof(double) * 3 * (n + 1)), *Q = malloc(sizeof(double) * 9 * n);
    const double normal[3] = {-1, 0, 0};
    char msg[200];
    assert_int_equal(sw_shape_curve(n, helix_arc(), helix_curve, NULL, normal, x, Q, msg,
                                    sizeof msg), SW_OK);
    assert_int_equal(sw_spec_set_rest_shape(s, id, x, Q), SW_OK);
    free(x);
    free(Q);
    swModel *m = sw_test_compile(s);
    sw_spec_free(s);
    double worst3 = 0;
    err[k] = 0;
    for (int v = 0; v < n - 1; v++) {
      double kv[3];
      sw_get3(m, m->rest_kappa, m->vor_adr[0] + v, kv);
      worst3 = fmax(worst3, fabs(kv[2]) / kappa);
      err[k] = fmax(err[k], fabs(hypot(kv[0], kv[1]) / kappa - 1));
    }
    fprintf(stderr, "# %s: %d elements: |kappa_1,2| rel. error %.3e, kappa_3 / kappa %.2e\n",
            __func__, n, err[k], worst3);
    assert_true(worst3 < 1e-12);
    sw_model_free(m);
  }
  const double o1 = log2(err[0] / err[1]), o2 = log2(err[1] / err[2]);
  fprintf(stderr, "# %s: orders of |kappa|: %.3f, %.3f\n", __func__, o1, o2);
  assert_true(fabs(o1 - 2) < 0.25 && fabs(o2 - 2) < 0.1);
}

/* Resting and starting as the helix, free and weightless: no motion. */
static void test_helix_at_rest(void **state) {
  (void)state;
  swModel *m = helix_rod(108, 1, 0, 0.9);
  swData *d = sw_data_new(m);
  for (int k = 0; k < 1000; k++) assert_int_equal(sw_step(m, d), SW_OK);
  double vmax = 0, wmax = 0;
  for (int i = 0; i <= 108; i++) {
    double v[3];
    sw_get3(m, d->v, m->node_adr[0] + i, v);
    vmax = fmax(vmax, sw_v3_norm(v));
  }
  for (int i = 0; i < 108; i++) {
    double w[3];
    sw_get3(m, d->omega, m->elem_adr[0] + i, w);
    wmax = fmax(wmax, sw_v3_norm(w));
  }
  fprintf(stderr, "# %s: after 1000 steps of %.3g s: largest node speed %.2e m/s, largest "
          "angular speed %.2e rad/s\n", __func__, m->dt, vmax, wmax);
  assert_true(vmax < 1e-9 && wmax < 1e-6);
  sw_data_free(d);
  sw_model_free(m);
}

/* Resting as the helix, starting straight: unstretched, with the helix's
 * rest curvature. */
static void test_start_apart(void **state) {
  (void)state;
  swModel *m = helix_rod(108, 1, 1, 0);
  double worst = 0, k[3], kr[3];
  for (int e = 0; e < 108; e++) {
    double a[3], b[3], dx[3];
    sw_get3(m, m->x0, m->node_adr[0] + e, a);
    sw_get3(m, m->x0, m->node_adr[0] + e + 1, b);
    sw_v3_sub(dx, b, a);
    worst = fmax(worst, fabs(sw_v3_norm(dx) / m->rest_len[m->elem_adr[0] + e] - 1));
    assert_true(fabs(dx[0]) < 1e-15 && fabs(dx[2]) < 1e-15);   /* along y */
  }
  swModel *h = helix_rod(108, 1, 0, 0);
  sw_get3(m, m->rest_kappa, m->vor_adr[0] + 50, k);
  sw_get3(h, h->rest_kappa, h->vor_adr[0] + 50, kr);
  fprintf(stderr, "# %s: straight start: largest stretch - 1 = %.2e; rest kappa (%.6g, %.6g, "
          "%.6g) 1/m\n", __func__, worst, k[0], k[1], k[2]);
  assert_true(worst < 1e-13);
  for (int c = 0; c < 3; c++) assert_true(k[c] == kr[c]);
  sw_model_free(h);
  sw_model_free(m);
}

/* The stable step of a helical rod: bisection on a perturbed rod. */
static int helix_stable(double factor, int steps) {
  swModel *m = helix_rod(108, 1, 0, factor);
  swData *d = sw_data_new(m);
  unsigned seed = 4321;
  for (int i = 0; i <= 108; i++)
    for (int k = 0; k < 3; k++) {
      seed = seed * 1103515245u + 12345u;
      SW_AT(m, d->v, m->node_adr[0] + i, k) = 1e-6 * ((double)(seed >> 8) / (1u << 24) - 0.5);
    }
  return sw_test_stays_bounded(m, d, steps);
}

static void test_helix_stable_dt(void **state) {
  (void)state;
  const int steps = sw_test_sanitized() ? 1000 : 3000;
  assert_true(helix_stable(0.95, steps));
  double lo = 0.95, hi = 4.0;
  assert_false(helix_stable(hi, steps));
  for (int it = 0; it < 10; it++) {
    double mid = 0.5 * (lo + hi);
    if (helix_stable(mid, steps)) lo = mid; else hi = mid;
  }
  fprintf(stderr, "# %s: helical rod (9 turns of 12 elements): measured limit %.4f x the "
          "estimate\n", __func__, lo);
  assert_true(lo >= 1.0 && lo <= 1.5);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_helix_geometry),  cmocka_unit_test(test_curve_transport),
      cmocka_unit_test(test_helix_at_rest),   cmocka_unit_test(test_start_apart),
      cmocka_unit_test(test_helix_stable_dt),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
