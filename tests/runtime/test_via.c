/* test_via.c — muscle paths through via points (muscle_via.c) against
 * closed forms: the rope over a frictionless pulley (equal tension on both
 * sides, ring reaction 2 T sin(theta/2)); sliding through the ring (the
 * length follows the polyline, the material at the ring follows the uniform
 * stretch, the contact stays at the ring); the moment about a hinge of a
 * muscle wrapped over a via point on the bone (T times the moment arm of the
 * line through the via point, not of the straight line); momentum of a free
 * assembly; the layout at t = 0 (eta = 1, via points on nodes) and the
 * validation messages.
 *
 * Design.  One filament of a muscle, 1 MPa peak stress, radius 8 mm (F_max
 * = 201 N), laid in the x-z plane.  Statics are reached by dynamic relaxation
 * with a heavy, damped filament (statics do not depend on density). */
#include "testutil.h"

#define PI_T 3.14159265358979323846
static const double RADIUS = 0.008, SIGMA = 1e6;

static swMuscleDesc one_filament(int nelem) {
  swMuscleDesc md;
  sw_muscle_desc_init(&md);
  md.name = "m";
  md.filaments = 1;
  md.nelem = nelem;
  md.radius = RADIUS;
  md.sigma_max = SIGMA;
  md.normal[1] = 1;
  return md;
}

static double fmax_one(void) { return SIGMA * PI_T * RADIUS * RADIUS; }

static void unit(double *u, const double *a, const double *b) {
  double n = 0;
  for (int k = 0; k < 3; k++) n += (b[k] - a[k]) * (b[k] - a[k]);
  n = sqrt(n);
  for (int k = 0; k < 3; k++) u[k] = (b[k] - a[k]) / n;
}

static double dist(const double *a, const double *b) {
  double n = 0;
  for (int k = 0; k < 3; k++) n += (b[k] - a[k]) * (b[k] - a[k]);
  return sqrt(n);
}

static double norm3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* Arc length of rod r now. */
static double arc_length(const swModel *m, const swData *d, int r) {
  double l = 0;
  for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) l += d->length[e];
  return l;
}

/* ---- layout ---- */

static void test_layout(void **state) {
  (void)state;
  swMuscleDesc md = one_filament(12);
  const double S[3] = {-0.15, 0, 0}, P[3] = {0, 0, 0.05}, E[3] = {0.1, 0, 0};
  memcpy(md.start, S, sizeof S);
  memcpy(md.end, E, sizeof E);
  md.nvia = 1;
  memcpy(md.via[0], P, sizeof P);
  swSpec *s = sw_spec_new();
  assert_int_equal(sw_spec_add_muscle(s, &md), 0);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double L = dist(S, P) + dist(P, E);
  SW_EXPECT_REL("rest length l0 = polyline length (m)", m->fil_l0[0], L, 1e-14);
  SW_EXPECT_ABS("stretch at t = 0", d->fil_stretch[0], 1.0, 1e-14);
  /* 12 elements over 0.1581 m and 0.1118 m: 7 and 5, the via point is node 7 */
  double x7[3];
  sw_get3(m, d->x, m->node_adr[0] + 7, x7);
  SW_EXPECT_ABS("via point to node 7 (m)", dist(x7, P), 0.0, 1e-15);
  /* straight at rest: no rest curvature at the bend */
  for (int v = m->vor_adr[0]; v < m->vor_adr[0] + 11; v++)
    for (int k = 0; k < 3; k++) assert_true(SW_AT(m, m->rest_kappa, v, k) == 0);
  SW_EXPECT_ABS("ring force at t = 0 (N)", norm3(d->ring_row + 2), 0.0, 1e-9);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 1. the rope over a frictionless pulley ---- */

#ifndef PULLEY_N
#define PULLEY_N 12
#endif
static void test_pulley(void **state) {
  (void)state;
  swMuscleDesc md = one_filament(PULLEY_N);
  const double S[3] = {-0.15, 0, 0}, P[3] = {0, 0, 0.05}, E[3] = {0.1, 0, 0};
  memcpy(md.start, S, sizeof S);
  memcpy(md.end, E, sizeof E);
  md.nvia = 1;
  memcpy(md.via[0], P, sizeof P); /* via_rod -1: fixed in space */
  md.density *= 100;
  md.gamma = 20;
  md.damping = SW_DAMP_ANALYTIC;
  swSpec *s = sw_spec_new();
  assert_int_equal(sw_spec_add_muscle(s, &md), 0);
  swBCDesc b = sw_test_clamp(0, 0);
  sw_spec_add_bc(s, &b);
  /* pull the free end along the second segment: passive stretch */
  double u2[3];
  unit(u2, P, E);
  const double F = 0.05 * fmax_one();
  swLoadDesc l = sw_test_load(SW_LOAD_FORCE, 0, -1, F * u2[0], F * u2[1], F * u2[2]);
  sw_spec_add_load(s, &l);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  const int n0 = m->node_adr[0], n = m->rod_nelem[0];
  double eta_prev = 0;
  while (d->time < 60) {
    sw_test_run_to(m, d, d->time + 0.25);

    if (fabs(d->fil_stretch[0] - eta_prev) < 1e-9) break;
    eta_prev = d->fil_stretch[0];
  }
  fprintf(stderr, "#   relaxed to t = %.3g s, eta = %.6f, contact element %d\n", d->time,
          d->fil_stretch[0], (int)d->ring_row[0]);
  /* tension on each side: the clamp's load at the start, the load at the end */
  double Fs[3], xs[3], xe[3];
  sw_get3(m, d->force, n0, Fs);
  sw_get3(m, d->x, n0, xs);
  sw_get3(m, d->x, n0 + n, xe);
  const double T_start = norm3(Fs), T_end = F;
  SW_EXPECT_REL("tension ratio start / end side", T_start / T_end, 1.0, 1e-3);
  /* the ring's reaction against 2 T sin(theta/2), theta the turn of the
   * filament at the contact (the directions to its two ends) */
  double a[3], e[3], x1[3], xm[3];
  sw_get3(m, d->x, n0 + 1, x1);
  sw_get3(m, d->x, n0 + n - 1, xm);
  unit(a, x1, xs); /* along element 0, toward the start */
  unit(e, xm, xe); /* along the last element, toward the end */
  const double cos_between = a[0] * e[0] + a[1] * e[1] + a[2] * e[2];
  const double theta = PI_T - acos(cos_between);
  const double R = norm3(d->ring_row + 2);
  fprintf(stderr, "#   wrap angle theta = %.4f rad (%.2f deg), T = %.4f N\n", theta,
          theta * 180 / PI_T, T_end);
  SW_EXPECT_REL("ring reaction / 2 T sin(theta/2)", R / (2 * T_end * sin(theta / 2)), 1.0, 1e-3);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 2. sliding through the ring ---- */

/* The pulley's filament, active, its start clamped and its end moved 8 cm
 * outward along the second segment: the filament slides through the fixed
 * ring.  Closed forms: the change of length is the polyline's,
 * |S - P| + |P - E'| - (|S - P| + |P - E|); the material at the ring is at
 * rest arc length l0 |S - P| / L' (uniform stretch); the contact stays at
 * the ring, |c - p| = |F| / k (the penalty's own gap, no drift). */
static void test_sliding(void **state) {
  (void)state;
  swMuscleDesc md = one_filament(12);
  const double S[3] = {-0.15, 0, 0}, P[3] = {0, 0, 0.05}, E[3] = {0.1, 0, 0};
  memcpy(md.start, S, sizeof S);
  memcpy(md.end, E, sizeof E);
  md.nvia = 1;
  memcpy(md.via[0], P, sizeof P);
  md.density *= 100;
  md.gamma = 20;
  md.damping = SW_DAMP_ANALYTIC;
  md.activation = sw_signal_const(0.3);
  swSpec *s = sw_spec_new();
  assert_int_equal(sw_spec_add_muscle(s, &md), 0);
  swBCDesc b0 = sw_test_clamp(0, 0);
  sw_spec_add_bc(s, &b0);
  double u2[3];
  unit(u2, P, E);
  const double v = 0.08, t1 = 1.0, move = v * t1;
  swBCDesc b1 = sw_test_clamp(0, 1);
  b1.kind = SW_BC_VELOCITY;
  for (int k = 0; k < 3; k++) b1.vec[k] = v * u2[k];
  b1.signal = sw_signal_step(1.0, 0.0, t1);
  sw_spec_add_bc(s, &b1);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  const int j0 = (int)d->ring_row[0];
  sw_test_run_to(m, d, 6.0);
  const double L = dist(S, P) + dist(P, E);
  double E1[3];
  for (int k = 0; k < 3; k++) E1[k] = E[k] + move * u2[k];
  const double L1 = dist(S, P) + dist(P, E1);
  const double l = arc_length(m, d, 0);
  fprintf(stderr, "#   contact element %d -> %d, s = %.3f\n", j0, (int)d->ring_row[0], d->ring_row[1]);
  SW_EXPECT_REL("change of length / polyline's", (l - m->fil_l0[0]) / (L1 - L), 1.0, 1e-2);
  /* material at the ring: rest arc length before the contact */
  const int n0 = m->elem_adr[0], j = (int)d->ring_row[0];
  double S_c = 0;
  for (int e = n0; e < n0 + j; e++) S_c += m->rest_len[e];
  S_c += d->ring_row[1] * m->rest_len[n0 + j];
  const double S_ref = m->fil_l0[0] * dist(S, P) / L1;
  fprintf(stderr, "#   slid by %.2f mm (element %.2f mm)\n", 1e3 * (dist(S, P) - S_c),
          1e3 * m->rest_len[n0]);
  fprintf(stderr, "#   material at the ring %.2f mm from the uniform stretch's (%.2f elements)\n",
          1e3 * (S_c - S_ref), (S_c - S_ref) / m->rest_len[n0]);
  assert_true(dist(S, P) - S_c > m->rest_len[n0]); /* it slid past a node */
  /* |F| / k is the gap's part normal to the tangent; |c - p| also has the
   * part along it, which the ring does not hold (a few % of the gap) */
  SW_EXPECT_REL("contact gap |c - p| k / |F|", dist(d->ring_row + 5, P) * m->ring_stiffness[0] /
                norm3(d->ring_row + 2), 1.0, 5e-2);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 3. the moment about a hinge ---- */

/* A bone along +x from the hinge O = 0 (held at O), a muscle from a fixed
 * point S above and behind the hinge over a via point 2 cm off the bone's
 * centreline to an insertion A on the bone.  The muscle's loads on the bone
 * (the insertion joint's and the ring's) have the moment about O
 *   M = T |(p - O) x u|,  u = (S - p) / |S - p|,
 * the line of the segment that crosses the joint (the insertion's pull and
 * the ring's push on the same bone cancel to it), not the straight muscle's
 * T |(A - O) x (S - A)| / |S - A|. */
static void test_hinge_moment(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  swRodDesc bone;
  sw_rod_desc_init(&bone);
  bone.name = "ulna";
  bone.nelem = 10;
  bone.direction[0] = 1, bone.direction[1] = bone.direction[2] = 0;
  bone.normal[2] = 1, bone.normal[0] = bone.normal[1] = 0;
  bone.length = 0.3;
  bone.radius_start = bone.radius_end = 0.015;
  bone.youngs = 1e10;
  bone.density = 1750;
  bone.gamma = 50;
  bone.damping = SW_DAMP_ANALYTIC;
  assert_int_equal(sw_spec_add_rod(s, &bone), 0);
  swBCDesc hold = sw_test_clamp(0, 0);
  sw_spec_add_bc(s, &hold);
  swMuscleDesc md = one_filament(12);
  const double S[3] = {-0.1, 0, 0.08}, P[3] = {0.06, 0, 0.02}, A[3] = {0.21, 0, 0};
  memcpy(md.start, S, sizeof S);
  memcpy(md.end, A, sizeof A);
  md.attach_rod[1] = 0;
  md.attach_node[1] = 7; /* x = 0.21 */
  md.nvia = 1;
  memcpy(md.via[0], P, sizeof P);
  md.via_rod[0] = 0;
  md.via_stiffness = 1e6;
  md.density *= 100;
  md.gamma = 20;
  md.damping = SW_DAMP_ANALYTIC;
  md.activation = sw_signal_const(0.5);
  assert_int_equal(sw_spec_add_muscle(s, &md), 0);
  swBCDesc b0 = sw_test_clamp(1, 0); /* the filament's start at S */
  sw_spec_add_bc(s, &b0);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  sw_test_run_to(m, d, 3.0);
  const int fs = m->node_adr[1];
  double Fs[3], p[3], vp[3], xa[3], xb[3], arm[3], Q[9];
  sw_get3(m, d->force, fs, Fs);
  const double T = norm3(Fs); /* the tension where the muscle leaves S */
  /* via point now: on its bone element */
  const int e = m->ring_elem[0];
  sw_get3(m, d->x, e, xa);
  sw_get3(m, d->x, e + 1, xb);
  sw_getQ(m, d->Q, e, Q);
  for (int k = 0; k < 3; k++) arm[k] = Q[k] * m->ring_point[0] + Q[3 + k] * m->ring_point[1] +
                                       Q[6 + k] * m->ring_point[2];
  for (int k = 0; k < 3; k++) p[k] = 0.5 * (xa[k] + xb[k]) + arm[k];
  (void)vp;
  /* the muscle's moment about O (y): insertion joint (force on the filament
   * is joint_force, the bone gets minus) and ring (bone gets -F at c) */
  double xA[3];
  sw_get3(m, d->x, m->node_adr[0] + 7, xA);
  const double *Fj = d->joint_force, *Fr = d->ring_row + 2, *c = d->ring_row + 5;
  const double My = -(xA[2] * Fj[0] - xA[0] * Fj[2]) - (c[2] * Fr[0] - c[0] * Fr[2]);
  double u[3];
  unit(u, p, S);
  const double r_via = fabs(p[2] * u[0] - p[0] * u[2]);
  double uc[3];
  unit(uc, c, S);
  const double r_contact = fabs(c[2] * uc[0] - c[0] * uc[2]);
  fprintf(stderr, "#   moment arm through the contact c: %.4f mm (gap %.3g mm)\n", 1e3 * r_contact,
          1e3 * dist(c, p));
  double w[3];
  unit(w, A, S);
  const double r_straight = fabs(A[2] * w[0] - A[0] * w[2]);
  fprintf(stderr, "#   T = %.4f N, moment arm through the via point %.4f mm, straight %.4f mm\n",
          T, 1e3 * r_via, 1e3 * r_straight);
  /* tolerance: the tensions on the two sides of a ring differ by up to
   * 1e-3 (test_pulley), and the insertion's segment acts at about 2.5
   * times the via point's arm, so 1e-3 of T there moves M by 2.5e-3 */
  SW_EXPECT_REL("moment about the hinge / (T r_via)", fabs(My) / (T * r_via), 1.0, 5e-3);
  assert_true(fabs(r_via - r_straight) > 0.2 * r_straight);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- 4. momentum ---- */

/* Two free bones, a muscle from one to the other over a via point off the
 * first bone's centreline, no gravity, nothing held: the total linear
 * momentum stays 0 (to round-off of the impulses, F_max t) and so does
 * the angular momentum about the origin. */
static void test_momentum(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  swRodDesc bone;
  sw_rod_desc_init(&bone);
  bone.nelem = 6;
  bone.direction[0] = 1, bone.direction[1] = bone.direction[2] = 0;
  bone.normal[2] = 1, bone.normal[0] = bone.normal[1] = 0;
  bone.length = 0.2;
  bone.radius_start = bone.radius_end = 0.01;
  bone.youngs = 1e8;
  bone.density = 1750;
  bone.name = "a";
  assert_int_equal(sw_spec_add_rod(s, &bone), 0);
  bone.name = "b";
  bone.start[0] = 0.25;
  bone.start[2] = -0.02;
  assert_int_equal(sw_spec_add_rod(s, &bone), 1);
  swMuscleDesc md = one_filament(10);
  const double S[3] = {0.0333333333333333333, 0, 0}, P[3] = {0.2, 0, 0.03},
               A[3] = {0.25 + 0.1, 0, -0.02};
  memcpy(md.start, S, sizeof S);
  memcpy(md.end, A, sizeof A);
  md.attach_rod[0] = 0;
  md.attach_node[0] = 1;
  md.attach_rod[1] = 1;
  md.attach_node[1] = 3;
  md.nvia = 1;
  memcpy(md.via[0], P, sizeof P);
  md.via_rod[0] = 0;
  md.activation = sw_signal_const(1.0);
  assert_int_equal(sw_spec_add_muscle(s, &md), 0);
  swModel *m = sw_test_compile_at(s, 0.5);
  swData *d = sw_data_new(m);
  sw_test_run_to(m, d, 2000 * m->dt);
  double Pm[3] = {0, 0, 0}, Lm[3] = {0, 0, 0};
  for (int r = 0; r < m->nrod; r++) {
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
      double x[3], v[3];
      sw_get3(m, d->x, i, x);
      sw_get3(m, d->v, i, v);
      for (int k = 0; k < 3; k++) Pm[k] += m->mass[i] * v[k];
      Lm[0] += m->mass[i] * (x[1] * v[2] - x[2] * v[1]);
      Lm[1] += m->mass[i] * (x[2] * v[0] - x[0] * v[2]);
      Lm[2] += m->mass[i] * (x[0] * v[1] - x[1] * v[0]);
    }
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++) {
      double w[3], Q[9], Jw[3];
      sw_get3(m, d->omega, e, w);
      for (int k = 0; k < 3; k++) Jw[k] = SW_AT(m, m->inertia, e, k) / d->dilatation[e] * w[k];
      sw_getQ(m, d->Q, e, Q);
      for (int k = 0; k < 3; k++) Lm[k] += Q[k] * Jw[0] + Q[3 + k] * Jw[1] + Q[6 + k] * Jw[2];
    }
  }
  const double impulse = fmax_one() * d->time;
  double ring = 0;
  for (int f = 0; f < 3; f++) ring = fmax(ring, fabs(d->ring_row[2 + f]));
  fprintf(stderr, "#   %ld steps, ring force %.3g N, impulse scale F_max t = %.3g N s\n", d->step,
          norm3(d->ring_row + 2), impulse);
  assert_true(ring > 1e-3); /* the ring acts */
  SW_EXPECT_ABS("|linear momentum| / (F_max t)", norm3(Pm) / impulse, 0.0, 1e-12);
  fprintf(stderr, "#   |angular momentum| / (F_max t 1 m) = %.3g\n", norm3(Lm) / impulse);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

/* ---- validation ---- */

static void test_validation(void **state) {
  (void)state;
  char err[256];
  swMuscleDesc md = one_filament(4);
  md.end[2] = 0.2;
  md.nvia = 1;
  md.via[0][2] = 0.2; /* the end's point */
  swSpec *s = sw_spec_new();
  sw_spec_add_muscle(s, &md);
  assert_null(sw_compile(s, err, sizeof err));
  fprintf(stderr, "#   %s\n", err);
  assert_string_equal(err, "muscle 'm': a via point and end coincide");
  sw_spec_free(s);
  md.nvia = 4;
  for (int k = 0; k < 4; k++) md.via[k][0] = 0.01 * (k + 1);
  s = sw_spec_new();
  sw_spec_add_muscle(s, &md);
  assert_null(sw_compile(s, err, sizeof err));
  assert_string_equal(err, "muscle 'm': 4 via points need at least 5 elements per filament (one "
                           "per segment), have 4");
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_layout),
      cmocka_unit_test(test_pulley),
      cmocka_unit_test(test_sliding),
      cmocka_unit_test(test_hinge_moment),
      cmocka_unit_test(test_momentum),
      cmocka_unit_test(test_validation),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
