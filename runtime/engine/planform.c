/* planform.c — the area a set of rods shows at rest: the sum of their
 * silhouettes and their planform, the outline they cover on their mean
 * plane with overlaps counted once.
 *
 * Design.  A wing's area (Zhang et al. 2019, Suppl. Table 2: 650 cm^2 for
 * the pigeon) is what its feathers cover seen from above: barbs lie side by
 * side and feathers overlap, so the sum of the elements' silhouettes,
 * sum 2 r l, counts some of it twice and none of the gaps.  The planform is
 * measured instead by projecting every element, a rectangle of its length
 * and diameter 2 r, onto the plane the rods span (through their centroid,
 * normal to the direction of least spread: the smallest eigenvector of the
 * covariance of element midpoints weighted by 2 r l, GSL's symmetric
 * eigensolver), and counting the cells of a square grid whose sample
 * points, one placed at random in each (jitter), fall inside at least one
 * rectangle.  The cell is a quarter of the thinnest
 * element's radius, coarsened until the grid has at most SW_PLANFORM_CELLS
 * cells; the count is repeated on cells twice as large and the difference
 * is reported as the area's error.
 * Setup-time only: it allocates and is never called from a step. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

#define SW_PLANFORM_CELLS (64L * 1024 * 1024)

/* one element's two end points and radius */
static void element(const swModel *m, int r, int i, double a[3], double b[3], double *rad) {
  const int na = m->node_adr[r], e = m->elem_adr[r] + i;
  sw_get3(m, m->x0, na + i, a);
  sw_get3(m, m->x0, na + i + 1, b);
  *rad = m->radius[e];
}

/* Element i of rod r: its midpoint, and its silhouette 2 r l as its weight. */
static double element_midpoint(const swModel *m, int r, int i, double mid[3]) {
  double a[3], b[3], rad, d[3];
  element(m, r, i, a, b, &rad);
  sw_v3_sub(d, b, a);
  for (int k = 0; k < 3; k++) mid[k] = 0.5 * (a[k] + b[k]);
  return 2 * rad * sw_v3_norm(d);
}

/* The mean plane: centroid c and unit normal n (smallest eigenvector). */
static int mean_plane(const swModel *m, int nrods, const int *rods, double c[3], double n[3]) {
  double wsum = 0, mid[3], cov[9] = {0};
  c[0] = c[1] = c[2] = 0;
  for (int q = 0; q < nrods; q++)
    for (int i = 0; i < m->rod_nelem[rods[q]]; i++) {
      const double w = element_midpoint(m, rods[q], i, mid);
      wsum += w;
      for (int k = 0; k < 3; k++) c[k] += w * mid[k];
    }
  if (!(wsum > 0)) return 0;
  for (int k = 0; k < 3; k++) c[k] /= wsum;
  for (int q = 0; q < nrods; q++)
    for (int i = 0; i < m->rod_nelem[rods[q]]; i++) {
      const double w = element_midpoint(m, rods[q], i, mid);
      for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++) cov[3 * j + k] += w * (mid[j] - c[j]) * (mid[k] - c[k]);
    }
  gsl_matrix_view A = gsl_matrix_view_array(cov, 3, 3);
  gsl_vector *eval = gsl_vector_alloc(3);
  gsl_matrix *evec = gsl_matrix_alloc(3, 3);
  gsl_eigen_symmv_workspace *ws = gsl_eigen_symmv_alloc(3);
  int ok = eval && evec && ws && gsl_eigen_symmv(&A.matrix, eval, evec, ws) == 0;
  if (ok) {
    gsl_eigen_symmv_sort(eval, evec, GSL_EIGEN_SORT_VAL_ASC);
    for (int k = 0; k < 3; k++) n[k] = gsl_matrix_get(evec, k, 0);
  }
  gsl_eigen_symmv_free(ws);
  gsl_matrix_free(evec);
  gsl_vector_free(eval);
  return ok;
}

/* A cell's sample point, (jx, jy) in [0, 1)^2 of the cell, from a hash of
 * its indices (splitmix64): cell centres would alias with a rod at a
 * rational slope (a strip at 45 deg covers a whole number of the grid's
 * diagonals: 194.4 of 200 mm^2 measured on 0.25 mm cells), and the same
 * bias would come back on cells twice as large, hiding it from the error;
 * a sample placed at random in each cell is unbiased. */
static void jitter(long ix, long iy, double *jx, double *jy) {
  uint64_t z = (uint64_t)ix * 0x9E3779B97F4A7C15ull + (uint64_t)iy * 0xD1B54A32D192ED03ull;
  z ^= z >> 30;
  z *= 0xBF58476D1CE4E5B9ull;
  z ^= z >> 27;
  z *= 0x94D049BB133111EBull;
  z ^= z >> 31;
  *jx = (double)(z >> 40) / (double)(1ull << 24);
  *jy = (double)(z & 0xFFFFFFull) / (double)(1ull << 24);
}

/* The area of the cells of side h over [lo, hi] (plane axes u, v through c)
 * whose sample points lie in some element's rectangle; -1 out of memory. */
static double covered(const swModel *m, int nrods, const int *rods, const double c[3],
                      const double u[3], const double v[3], const double lo[2], const double hi[2],
                      double h) {
  const long nx = (long)ceil((hi[0] - lo[0]) / h) + 1, ny = (long)ceil((hi[1] - lo[1]) / h) + 1;
  unsigned char *hit = calloc((size_t)(nx * ny), 1);
  if (!hit) return -1;
  for (int q = 0; q < nrods; q++)
    for (int i = 0; i < m->rod_nelem[rods[q]]; i++) {
      double a[3], b[3], rad, da[3], db[3];
      element(m, rods[q], i, a, b, &rad);
      sw_v3_sub(da, a, c);
      sw_v3_sub(db, b, c);
      const double pa[2] = {sw_v3_dot(da, u), sw_v3_dot(da, v)};
      const double pb[2] = {sw_v3_dot(db, u), sw_v3_dot(db, v)};
      const double t[2] = {pb[0] - pa[0], pb[1] - pa[1]}, len2 = t[0] * t[0] + t[1] * t[1];
      const long i0 = (long)floor((fmin(pa[0], pb[0]) - rad - lo[0]) / h);
      const long i1 = (long)ceil((fmax(pa[0], pb[0]) + rad - lo[0]) / h);
      const long j0 = (long)floor((fmin(pa[1], pb[1]) - rad - lo[1]) / h);
      const long j1 = (long)ceil((fmax(pa[1], pb[1]) + rad - lo[1]) / h);
      for (long ix = i0 < 0 ? 0 : i0; ix <= i1 && ix < nx; ix++)
        for (long iy = j0 < 0 ? 0 : j0; iy <= j1 && iy < ny; iy++) {
          /* the cell's sample point in the rectangle: along the element
           * within [0, 1], across it within r */
          double jx, jy;
          jitter(ix, iy, &jx, &jy);
          const double px = lo[0] + (ix + jx) * h - pa[0], py = lo[1] + (iy + jy) * h - pa[1];
          const double s = len2 > 0 ? (px * t[0] + py * t[1]) / len2 : 0;
          const double cx = px - s * t[0], cy = py - s * t[1];
          if (s >= 0 && s <= 1 && cx * cx + cy * cy <= rad * rad) hit[ix * ny + iy] = 1;
        }
    }
  long cells = 0;
  for (long k = 0; k < nx * ny; k++) cells += hit[k];
  free(hit);
  return (double)cells * h * h;
}

int sw_rods_area(const swModel *m, int nrods, const int *rods, swArea *out) {
  memset(out, 0, sizeof *out);
  double c[3], n[3], u[3], v[3], thinnest = INFINITY;
  for (int q = 0; q < nrods; q++)
    for (int i = 0; i < m->rod_nelem[rods[q]]; i++) {
      double mid[3];
      out->silhouette += element_midpoint(m, rods[q], i, mid);
      thinnest = sw_min(m->radius[m->elem_adr[rods[q]] + i], thinnest); /* vec.h: not fmin */
    }
  if (!(out->silhouette > 0) || !mean_plane(m, nrods, rods, c, n)) return 0;
  /* in-plane axes u, v: u from the coordinate axis least along n */
  int k0 = 0;
  for (int k = 1; k < 3; k++)
    if (fabs(n[k]) < fabs(n[k0])) k0 = k;
  double ax[3] = {0, 0, 0};
  ax[k0] = 1;
  sw_v3_cross(u, n, ax);
  sw_v3_scale(u, u, 1 / sw_v3_norm(u));
  sw_v3_cross(v, n, u);
  /* the projected rectangles' bounding box */
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (int q = 0; q < nrods; q++)
    for (int i = 0; i <= m->rod_nelem[rods[q]]; i++) {
      double x[3], d[3];
      sw_get3(m, m->x0, m->node_adr[rods[q]] + i, x);
      sw_v3_sub(d, x, c);
      const double p[2] = {sw_v3_dot(d, u), sw_v3_dot(d, v)};
      const double rad = m->radius[m->elem_adr[rods[q]] + (i < m->rod_nelem[rods[q]] ? i : i - 1)];
      for (int k = 0; k < 2; k++) {
        lo[k] = sw_min(p[k] - rad, lo[k]);
        hi[k] = sw_max(p[k] + rad, hi[k]);
      }
    }
  /* the grid: a quarter of the thinnest radius, coarser if too many cells */
  double h = 0.25 * thinnest;
  while (((hi[0] - lo[0]) / h + 2) * ((hi[1] - lo[1]) / h + 2) > SW_PLANFORM_CELLS) h *= 2;
  const double fine = covered(m, nrods, rods, c, u, v, lo, hi, h);
  const double coarse = covered(m, nrods, rods, c, u, v, lo, hi, 2 * h);
  if (fine < 0 || coarse < 0) return 0;
  out->planform = fine;
  out->planform_error = fabs(fine - coarse);
  out->cell = h;
  memcpy(out->normal, n, sizeof out->normal);
  return 1;
}
