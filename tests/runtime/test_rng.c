/* test_rng.c — the runtime's random numbers (rng.c) against the published
 * reference outputs of splitmix64 and xoshiro256**, and the statistics of
 * its uniforms and normals: means, variances and the normal's fourth moment
 * within five standard errors, a jumped stream uncorrelated with its
 * origin, and bitwise reproducibility from one seed. */
#include "testutil.h"
#include "rng.h"

/* splitmix64 from seed 0 (Vigna's splitmix64.c; the values every port
 * tests against): the first three outputs, which sw_rng_seed puts in
 * s[0..2]. */
static void test_splitmix_reference(void **state) {
  (void)state;
  swRng r;
  sw_rng_seed(&r, 0);
  assert_true(r.s[0] == UINT64_C(0xE220A8397B1DCDAF));
  assert_true(r.s[1] == UINT64_C(0x6E789E6AA1B965F4));
  assert_true(r.s[2] == UINT64_C(0x06C45D188009454F));
  fprintf(stderr, "# %s: splitmix64(0) = %016llx %016llx %016llx (reference e220a8397b1dcdaf "
                  "6e789e6aa1b965f4 06c45d188009454f)\n",
          __func__, (unsigned long long)r.s[0], (unsigned long long)r.s[1],
          (unsigned long long)r.s[2]);
}

/* xoshiro256** from the state {1, 2, 3, 4}: the ten outputs of the authors'
 * reference C code, as the rand_xoshiro crate's test `reference` lists them. */
static void test_xoshiro_reference(void **state) {
  (void)state;
  static const uint64_t ref[10] = {
      UINT64_C(11520),                UINT64_C(0),
      UINT64_C(1509978240),           UINT64_C(1215971899390074240),
      UINT64_C(1216172134540287360),  UINT64_C(607988272756665600),
      UINT64_C(16172922978634559625), UINT64_C(8476171486693032832),
      UINT64_C(10595114339597558777), UINT64_C(2904607092377533576)};
  swRng r = {{1, 2, 3, 4}, 0.0, 0};
  int same = 0;
  for (int i = 0; i < 10; i++) same += sw_rng_next(&r) == ref[i];
  fprintf(stderr, "# %s: %d of 10 outputs equal the reference\n", __func__, same);
  assert_int_equal(same, 10);
}

static void test_uniform_and_normal_moments(void **state) {
  (void)state;
  const int N = sw_test_sanitized() ? 200000 : 2000000;
  swRng r;
  sw_rng_seed(&r, 12345);
  double s1 = 0, s2 = 0, umin = 1, umax = 0;
  for (int i = 0; i < N; i++) {
    const double u = sw_rng_uniform(&r);
    assert_true(u >= 0 && u < 1);
    assert_true(u * 0x1.0p53 == floor(u * 0x1.0p53)); /* a multiple of 2^-53 */
    s1 += u;
    s2 += u * u;
    umin = fmin(umin, u);
    umax = fmax(umax, u);
  }
  const double mu = s1 / N, var = s2 / N - mu * mu;
  /* standard errors: sqrt(1/12 / N) for the mean, sqrt(1/180 / N) for the variance */
  SW_EXPECT_ABS("uniform mean", mu, 0.5, 5 * sqrt(1 / 12.0 / N));
  SW_EXPECT_ABS("uniform variance", var, 1 / 12.0, 5 * sqrt(1 / 180.0 / N));
  double m1 = 0, m2 = 0, m4 = 0;
  for (int i = 0; i < N; i++) {
    const double z = sw_rng_normal(&r);
    m1 += z;
    m2 += z * z;
    m4 += z * z * z * z;
  }
  m1 /= N;
  m2 /= N;
  m4 /= N;
  /* standard errors of the sample moments of N(0,1): 1, sqrt 2, sqrt 96 over sqrt N */
  SW_EXPECT_ABS("normal mean", m1, 0.0, 5 / sqrt((double)N));
  SW_EXPECT_ABS("normal variance", m2, 1.0, 5 * sqrt(2.0 / N));
  SW_EXPECT_ABS("normal fourth moment", m4, 3.0, 5 * sqrt(96.0 / N));
}

/* A jumped stream: different numbers, uncorrelated with the origin's. */
static void test_streams(void **state) {
  (void)state;
  const int N = 100000;
  swRng a, b, c;
  sw_rng_stream(&a, 7, 0);
  sw_rng_stream(&b, 7, 1);
  sw_rng_stream(&c, 7, 1);
  double sab = 0, sa = 0, sb = 0, saa = 0, sbb = 0;
  int equal = 0;
  for (int i = 0; i < N; i++) {
    const double x = sw_rng_uniform(&a), y = sw_rng_uniform(&b);
    equal += x == y;
    assert_true(y == sw_rng_uniform(&c)); /* the same stream again, bit for bit */
    sa += x;
    sb += y;
    sab += x * y;
    saa += x * x;
    sbb += y * y;
  }
  const double cov = sab / N - sa / N * sb / N;
  const double corr = cov / sqrt((saa / N - sa * sa / N / N) * (sbb / N - sb * sb / N / N));
  SW_EXPECT_ABS("correlation of stream 0 and stream 1", corr, 0.0, 5 / sqrt((double)N));
  assert_true(equal < 3);
  /* normals of one seed, drawn twice, are bitwise equal */
  swRng p, q;
  sw_rng_seed(&p, 99);
  sw_rng_seed(&q, 99);
  for (int i = 0; i < 1001; i++) {
    const double x = sw_rng_normal(&p), y = sw_rng_normal(&q);
    assert_memory_equal(&x, &y, sizeof x);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_splitmix_reference),
      cmocka_unit_test(test_xoshiro_reference),
      cmocka_unit_test(test_uniform_and_normal_moments),
      cmocka_unit_test(test_streams),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
