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
 * above it the force is mu_k N.  sw_coulomb_cap is that law.  Both kernels
 * then re-anchor the pair at its current touching points with the spring's
 * tangential stretch kept, u_t while stuck and -F / k_t while slipping
 * (sw_friction_reanchor), so that a rolling rod does not carry its anchor up
 * its side.
 *
 * Both kernels keep their anchors in a table of fixed-width rows, the first
 * number of a row its pair's key, ordered by key.  obstacle.c visits its
 * pairs in key order and merges; contact.c's hash grid visits them in no
 * particular order, so it finds a pair's previous anchor by bisection
 * (sw_anchor_find) and sorts the new table once written (sw_anchor_sort, a
 * heapsort in place: no allocation in the step, and a result that depends
 * only on the rows, so that a continued run repeats the uninterrupted one).
 *
 * On the rod's side both kernels anchor at the element's touching surface
 * point: the centreline point at `at` plus an arm kept in the element's
 * material frame, which moves, turns and rolls with the element; the force
 * acts there, split over the nodes with the couple arm x F on the element
 * (sw_side_point, sw_side_arm, sw_side_apply).  A stuck contact therefore
 * holds sliding but lets the rod roll, and the law stays passive: with the
 * normal held the forces and couples are the gradient of k_t |u_t|^2 / 2,
 * and what turning the normal adds is proportional to u . n, only the
 * overlap for two surface points (docs/physics.md, "Rod-rod contact").
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

/* ---- a rod element's anchor at its surface (both kernels) ---- */

void sw_side_centre(const swModel *m, const double *x, const swFrictionSide *e, double at, double p[3]) {
  for (int q = 0; q < 3; q++)
    p[q] = (1 - at) * SW_AT(m, x, e->node, q) + at * SW_AT(m, x, e->node + 1, q);
}

void sw_side_point(const swModel *m, const swData *d, swFrictionSide *e, double at, const double y[3],
                   double p[3], double v[3]) {
  double Q[9], wm[3], w[3], wr[3];
  sw_getQ(m, d->Q, e->elem, Q);
  sw_matT_vec(e->arm, Q, y);
  sw_get3(m, d->omega, e->elem, wm);
  sw_matT_vec(w, Q, wm);
  sw_v3_cross(wr, w, e->arm);
  sw_side_centre(m, d->x, e, at, p);
  sw_side_centre(m, d->v, e, at, v);
  sw_v3_add(p, p, e->arm);
  sw_v3_add(v, v, wr);
  e->anchor_at = at;
}

void sw_side_arm(const swModel *m, const swData *d, const swFrictionSide *e, const double off[3],
                 double y[3]) {
  double Q[9];
  sw_getQ(m, d->Q, e->elem, Q);
  sw_mat_vec(y, Q, off);
}

void sw_side_apply(const swModel *m, const swData *d, const swFrictionSide *e, const double f[3],
                   double *force, double *ext_force, double *torque, double *ext_torque) {
  const double w[2] = {1 - e->anchor_at, e->anchor_at};
  double c[3], Q[9], cm[3];
  for (int j = 0; j < 2; j++)
    for (int q = 0; q < 3; q++) {
      SW_AT(m, force, e->node + j, q) += w[j] * f[q];
      SW_AT(m, ext_force, e->node + j, q) += w[j] * f[q];
    }
  sw_v3_cross(c, e->arm, f);
  sw_getQ(m, d->Q, e->elem, Q);
  sw_mat_vec(cm, Q, c);
  for (int q = 0; q < 3; q++) {
    SW_AT(m, torque, e->elem, q) += cm[q];
    SW_AT(m, ext_torque, e->elem, q) += cm[q];
  }
}

double sw_friction_reanchor(const swFrictionSide *e, int stuck, const double ut[3], const double F[3],
                            double kt, double stretch[3]) {
  for (int q = 0; q < 3; q++) stretch[q] = stuck ? ut[q] : -F[q] / kt;
  return stuck ? e->anchor_at : e->at;
}
