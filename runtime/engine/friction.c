/* friction.c — the elastic-Coulomb law both contact kernels share: rods on
 * rigid obstacles (obstacle.c) and rods on rods (contact.c).
 *
 * Design.  A touching pair keeps an anchor: a material point on each side,
 * tied by a tangential spring k_t with a damper gamma (the "spring and
 * slider" of Cundall & Strack, Geotechnique 29 (1979) 47, eqs. 5-7).  Each
 * kernel knows where its two material points are; given their separation u
 * and relative velocity w, both with the part along the contact normal n
 * taken off (u_t = u - (u.n) n, w_t likewise), the law is
 *   F = -k_t u_t - gamma w_t                                   (trial)
 *   |F| <= mu_s N:  stuck, F acts and the anchor stays;
 *   |F| >  mu_s N:  slipping, F <- mu_k N F / |F|, and the anchor moves so
 *                   that the spring alone gives that force, u_t -> -F / k_t,
 * N the normal force (spring plus damper, >= 0).  A constant load below
 * mu_s N thus finds a static equilibrium, the spring holding exactly (no
 * creep, unlike a regularised Coulomb law whose stuck state is a slow slide);
 * above it the force is mu_k N.  sw_coulomb_cap is that law; where the
 * anchor moves to is the kernel's business (obstacle.c moves the obstacle's
 * point by u_t + F / k_t; contact.c re-anchors at the current closest
 * points with the spring's stretch -F / k_t kept).
 *
 * Both kernels keep their anchors in a table of fixed-width rows, the first
 * number of a row its pair's key, ordered by key.  obstacle.c visits its
 * pairs in key order and merges; contact.c's hash grid visits them in no
 * particular order, so it finds a pair's previous anchor by bisection
 * (sw_anchor_find) and sorts the new table once written (sw_anchor_sort, a
 * heapsort in place: no allocation in the step, and a result that depends
 * only on the rows, so that a continued run repeats the uninterrupted one).
 */
#include <math.h>
#include <string.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

int sw_coulomb_cap(const double ut[3], const double wt[3], double kt, double gamma, double mu_s,
                   double mu_k, double N, double F[3]) {
  for (int q = 0; q < 3; q++) F[q] = -kt * ut[q] - gamma * wt[q];
  const double mag = sw_v3_norm(F);
  if (mag <= mu_s * N) return 1; /* stuck */
  const double scale = mag > 0 ? mu_k * N / mag : 0.0;
  for (int q = 0; q < 3; q++) F[q] *= scale;
  return 0;
}

const double *sw_anchor_find(const double *rows, int n, int width, double key) {
  int lo = 0, hi = n; /* the row is in [lo, hi) if anywhere */
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    const double k = rows[(size_t)mid * (size_t)width];
    if (k == key) return rows + (size_t)mid * (size_t)width;
    if (k < key) lo = mid + 1;
    else hi = mid;
  }
  return NULL;
}

static void swap_rows(double *a, double *b, int width) {
  for (int q = 0; q < width; q++) {
    const double t = a[q];
    a[q] = b[q], b[q] = t;
  }
}

/* Sift row i down the max-heap rows[0..n) by key. */
static void sift(double *rows, int n, int width, int i) {
  for (;;) {
    int big = i;
    const int l = 2 * i + 1, r = l + 1;
    if (l < n && rows[(size_t)l * width] > rows[(size_t)big * width]) big = l;
    if (r < n && rows[(size_t)r * width] > rows[(size_t)big * width]) big = r;
    if (big == i) return;
    swap_rows(rows + (size_t)i * width, rows + (size_t)big * width, width);
    i = big;
  }
}

void sw_anchor_sort(double *rows, int n, int width) {
  for (int i = n / 2 - 1; i >= 0; i--) sift(rows, n, width, i);
  for (int end = n - 1; end > 0; end--) {
    swap_rows(rows, rows + (size_t)end * width, width);
    sift(rows, end, width, 0);
  }
}
