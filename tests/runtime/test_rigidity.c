/* test_rigidity.c — the rods' strain and bend peaks the run's summary reads
 * to name rods a scene could hold rigid (engine/rigidity.c), against closed
 * forms of states set by hand:
 *   - a rod stretched uniformly by (1 + eps): every element's axial strain
 *     is eps, nothing bends;
 *   - a straight rod whose element j is turned by j alpha about d1: each of
 *     the n - 1 domains turns by alpha, so the bend end to end is
 *     (n - 1) alpha, and the last element's tangent, seen in its turned
 *     frame, has the shear strain sin((n - 1) alpha);
 *   - the peaks are the largest over the samples (a stretched frame, then
 *     the rest state, keeps the stretch's);
 *   - a rigid rod is not sampled (NaN), and a reset clears the peaks;
 *   - a muscle of three filaments whose first filament's nodes are all
 *     moved by delta, the others not: the mean motion is delta / 3, the
 *     first filament strays from it by 2 delta / 3, so the spread is
 *     2 delta / (3 L); its filaments are not sampled as rods (NaN). */
#include "testutil.h"
#include "internal.h"
#include "vec.h"

enum { N = 10 };

static swSpec *two_rods(void) {
  swSpec *s = sw_spec_new();
  const double o[3] = {0, 0, 0}, o2[3] = {0, 1, 0}, dir[3] = {1, 0, 0}, nrm[3] = {0, 0, 1};
  swRodDesc r = sw_test_rod("bone", N, 1.0, 0.02, o, dir, nrm);
  sw_spec_add_rod(s, &r);
  swRodDesc h = sw_test_rod("held", 4, 0.5, 0.02, o2, dir, nrm);
  h.rigid = 1;
  sw_spec_add_rod(s, &h);
  return s;
}

static void test_stretch_peak(void **state) {
  (void)state;
  swSpec *s = two_rods();
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double eps = 3.7e-3;
  const int a = m->node_adr[0];
  for (int i = 0; i <= N; i++) SW_AT(m, d->x, a + i, 0) *= 1.0 + eps;
  sw_rigidity_sample(m, d);
  fprintf(stderr, "# %s: strain peak %.9e (eps %.9e), bend %.3e, frames %ld\n", __func__,
          d->rod_strain_peak[0], eps, d->rod_bend_peak[0], d->rigidity_frames);
  SW_EXPECT_REL("stretch peak", d->rod_strain_peak[0], eps, 1e-9);
  assert_true(d->rod_bend_peak[0] < 1e-12);
  assert_true(isnan(d->rod_strain_peak[1]) && isnan(d->rod_bend_peak[1])); /* the rigid rod */
  /* back at rest: the peak stays the stretch's */
  for (int i = 0; i <= N; i++) SW_AT(m, d->x, a + i, 0) /= 1.0 + eps;
  sw_rigidity_sample(m, d);
  SW_EXPECT_REL("stretch peak after a rest frame", d->rod_strain_peak[0], eps, 1e-9);
  assert_int_equal(d->rigidity_frames, 2);
  sw_rigidity_reset(m, d);
  assert_true(d->rod_strain_peak[0] == 0 && d->rod_bend_peak[0] == 0 && d->rigidity_frames == 0);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_bend_peak(void **state) {
  (void)state;
  swSpec *s = two_rods();
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double alpha = 2.5e-3;
  const int e0 = m->elem_adr[0];
  for (int j = 0; j < N; j++) { /* element j turned by j alpha about its own d1 */
    double Q[9], phi[3] = {j * alpha, 0, 0};
    sw_getQ(m, d->Q, e0 + j, Q);
    sw_rotate_frame(Q, phi);
    sw_setQ(m, d->Q, e0 + j, Q);
  }
  sw_rigidity_sample(m, d);
  const double bend = (N - 1) * alpha, shear = sin((N - 1) * alpha);
  fprintf(stderr, "# %s: bend peak %.9e (expected %.9e), strain peak %.9e (expected %.9e)\n", __func__,
          d->rod_bend_peak[0], bend, d->rod_strain_peak[0], shear);
  SW_EXPECT_REL("bend end to end (rad)", d->rod_bend_peak[0], bend, 1e-9);
  SW_EXPECT_REL("shear of the last element", d->rod_strain_peak[0], shear, 1e-9);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

static void test_muscle_spread(void **state) {
  (void)state;
  swSpec *s = sw_spec_new();
  swMuscleDesc md;
  sw_muscle_desc_init(&md);
  md.name = "biceps";
  md.filaments = 3;
  md.nelem = 8;
  md.end[2] = 0.2;
  md.normal[0] = 1;
  md.radius = 0.016;
  md.sigma_max = 1e6;
  md.activation = sw_signal_const(0.0);
  assert_int_equal(sw_spec_add_muscle(s, &md), 0);
  swModel *m = sw_test_compile(s);
  swData *d = sw_data_new(m);
  const double delta = 4e-4, L = 0.2;
  const int r0 = m->fil_rod[m->muscle_fil_adr[0]];
  for (int i = 0; i <= m->rod_nelem[r0]; i++) SW_AT(m, d->x, m->node_adr[r0] + i, 2) += delta;
  sw_rigidity_sample(m, d);
  fprintf(stderr, "# %s: spread %.9e (expected 2 delta / (3 L) = %.9e)\n", __func__, d->muscle_spread_peak[0],
          2 * delta / (3 * L));
  SW_EXPECT_REL("spread of the filaments' motion over L", d->muscle_spread_peak[0], 2 * delta / (3 * L), 1e-9);
  assert_true(isnan(d->rod_strain_peak[r0])); /* a filament is not a rod that could be rigid */
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_stretch_peak),
      cmocka_unit_test(test_bend_peak),
      cmocka_unit_test(test_muscle_spread),
  };
  return cmocka_run_group_tests_name("rigidity", tests, NULL, NULL);
}
