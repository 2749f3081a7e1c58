/* band_compare.h — what the band paths' tests share (test_joint_band.c,
 * test_joint_member_band.c): a model switched between a band path and the
 * dense one, a start that moves every node and element alike in every
 * swData, and the largest differences of two runs' x, v and omega. */
#ifndef SW_BAND_COMPARE_H
#define SW_BAND_COMPARE_H
#include <float.h>
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

/* x, v and omega of band - dense after `early` steps (e) and after
 * nsteps (d), and of ulp - dense after early steps (eu) and after nsteps
 * (u): each as the largest difference (a) and relative to dense's largest
 * (r). */
typedef struct {
  double ea[3], er[3], da[3], dr[3], ua[3], ur[3], eua[3], eur[3];
} BandRun;

/* The three runs of a band path's comparison: `band` on the path `path`,
 * `dense` and `ulp` on the dense one, each dense kick factored afresh (and
 * the band's too with reset_band), all started moving alike but ulp, whose
 * every velocity is one unit in the last place off (times 1 + 2^-52): how
 * far the scene itself carries a round-off.  The model is left on `path`. */
static inline BandRun band_against_dense(swModel *m, int path, int reset_band, long nsteps,
                                         long early, swData *band, swData *dense, swData *ulp) {
  BandRun r;
  start_moving(m, band);
  start_moving(m, dense);
  start_moving(m, ulp);
  for (int i = 0; i < 3 * m->stride; i++) ulp->v[i] *= 1 + DBL_EPSILON;
  for (long k = 0; k < nsteps; k++) {
    set_band(m, path);
    if (reset_band) sw_implicit_reset(m, band);
    assert_int_equal(sw_step(m, band), SW_OK);
    set_band(m, 0);
    sw_implicit_reset(m, dense); /* factored afresh, as the band path is */
    assert_int_equal(sw_step(m, dense), SW_OK);
    sw_implicit_reset(m, ulp);
    assert_int_equal(sw_step(m, ulp), SW_OK);
    if (k == early - 1) differences(m, band, dense, r.ea, r.er);
    if (k == early - 1) differences(m, ulp, dense, r.eua, r.eur);
  }
  set_band(m, path);
  differences(m, band, dense, r.da, r.dr);
  differences(m, ulp, dense, r.ua, r.ur);
  return r;
}

/* Its figures, as the tests print them. */
static inline void print_band_run(const BandRun *r, long early, long nsteps) {
  fprintf(stderr, "#   after %ld steps, band - dense: x %.2e m (rel. %.2e), v %.2e m/s (rel. %.2e), "
          "omega %.2e rad/s (rel. %.2e)\n", early, r->ea[0], r->er[0], r->ea[1], r->er[1], r->ea[2],
          r->er[2]);
  fprintf(stderr, "#   after %ld steps, dense from a one-ulp start - dense: x %.2e m (rel. %.2e), "
          "v %.2e m/s (rel. %.2e), omega %.2e rad/s (rel. %.2e)\n",
          early, r->eua[0], r->eur[0], r->eua[1], r->eur[1], r->eua[2], r->eur[2]);
  fprintf(stderr, "#   after %ld steps, band - dense: x %.2e m (rel. %.2e), v %.2e m/s (rel. %.2e), "
          "omega %.2e rad/s (rel. %.2e)\n", nsteps, r->da[0], r->dr[0], r->da[1], r->dr[1], r->da[2],
          r->dr[2]);
  fprintf(stderr, "#   after %ld steps, dense from a one-ulp start - dense: x %.2e m (rel. %.2e), "
          "v %.2e m/s (rel. %.2e), omega %.2e rad/s (rel. %.2e)\n",
          nsteps, r->ua[0], r->ur[0], r->ua[1], r->ur[1], r->ua[2], r->ur[2]);
}

static inline double band_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* kick_time of one kick on the path `path` (band's) and on the dense one
 * (dense's), after three steps of each from the same moving start; the
 * model is left on `path`. */
static inline double kick_time(const swModel *m, swData *d);
static inline void kick_times(swModel *m, int path, swData *band, swData *dense, double *tb,
                              double *td) {
  start_moving(m, band);
  start_moving(m, dense);
  for (int k = 0; k < 3; k++) { /* a state of the run */
    set_band(m, path);
    assert_int_equal(sw_step(m, band), SW_OK);
    set_band(m, 0);
    assert_int_equal(sw_step(m, dense), SW_OK);
  }
  set_band(m, path);
  *tb = kick_time(m, band);
  set_band(m, 0);
  *td = kick_time(m, dense);
  set_band(m, path);
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
