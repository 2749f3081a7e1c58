/* band_compare.h — what the band paths' tests share (test_joint_band.c,
 * test_joint_member_band.c): a model switched between a band path and the
 * dense one, a start that moves every node and element alike in every
 * swData, and the largest differences of two runs' x, v and omega. */
#ifndef SW_BAND_COMPARE_H
#define SW_BAND_COMPARE_H
#include <time.h>
#include "testutil.h"
#include "internal.h"

/* Every group to the path `band` (0: dense; 1, 2: joint_groups.c). */
static inline void set_band(swModel *m, int band) {
  for (int g = 0; g < m->nrigid_group; g++) m->rigid_group_band[g] = band;
}

/* A swData made for that path (its workspace is the path's). */
static inline swData *data_for(swModel *m, int band) {
  set_band(m, band);
  swData *d = sw_data_new(m);
  assert_non_null(d);
  return d;
}

/* Every node and element of d started moving, the same in every swData. */
static inline void start_moving(const swModel *m, swData *d) {
  for (int i = 0; i < m->stride; i++) {
    SW_AT(m, d->v, i, 0) = 0.02 * sin(1.3 * i);
    SW_AT(m, d->v, i, 1) = 0.03 * cos(0.7 * i);
    SW_AT(m, d->v, i, 2) = 0.05 * sin(0.4 * i + 1);
    SW_AT(m, d->omega, i, 0) = 0.5 * cos(0.9 * i);
    SW_AT(m, d->omega, i, 1) = 0.3 * sin(1.1 * i);
    SW_AT(m, d->omega, i, 2) = 0.2 * cos(0.3 * i + 2);
  }
}

/* The largest |a - b| over n numbers, and the largest |b|. */
static inline double worst(const double *a, const double *b, size_t n, double *scale) {
  double w = 0;
  *scale = 0;
  for (size_t k = 0; k < n; k++) w = fmax(w, fabs(a[k] - b[k])), *scale = fmax(*scale, fabs(b[k]));
  return w;
}

/* The largest differences of x, v and omega between a and b, each over the
 * largest |.| of b: rel[0 .. 2]. */
static inline void differences(const swModel *m, const swData *a, const swData *b, double *abs_,
                               double *rel) {
  const size_t n3 = 3 * (size_t)m->stride;
  const double *pa[3] = {a->x, a->v, a->omega}, *pb[3] = {b->x, b->v, b->omega};
  for (int q = 0; q < 3; q++) {
    double scale;
    abs_[q] = worst(pa[q], pb[q], n3, &scale);
    rel[q] = abs_[q] / scale;
  }
}

static inline double band_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Seconds per kick of the joints' system on d's state, each factored
 * afresh (sw_implicit_reset, as a moving rod mostly is): the least mean
 * over five batches of at least 3 kicks and 10 ms (the machine is shared;
 * one batch of 2 under the sanitizers, where a dense path of 64 barbs takes
 * a quarter of a second a kick).  Printed by the tests, never asserted. */
static inline double kick_time(const swModel *m, swData *d) {
  const int batches = sw_test_sanitized() ? 1 : 5, least = sw_test_sanitized() ? 2 : 3;
  double best = INFINITY;
  for (int batch = 0; batch < batches; batch++) {
    long k = 0;
    const double t0 = band_now();
    double t = t0;
    while (k < least || t - t0 < 0.01) {
      sw_implicit_reset(m, d);
      assert_int_equal(sw_rigid_joints_kick(m, d, m->dt, d->rigid_load), 1);
      k++;
      t = band_now();
    }
    best = fmin(best, (t - t0) / (double)k);
  }
  return best;
}
#endif
