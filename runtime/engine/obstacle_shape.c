/* obstacle_shape.c — the narrow phase of rigid obstacles (obstacle.c):
 * the least signed distance from an element's segment to the surface of a
 * sphere, an infinite cylinder, a capsule, a box or an ellipsoid, the
 * segment's parameter s there and the surface's outward normal, all in the
 * shape's own frame (centre at the origin, axes e1 = normal, e2 = axis x
 * normal, e3 = axis).
 *
 * Design.  Sphere, cylinder and capsule have closed forms: the segment's
 * point nearest the centre, the axis, or the capsule's core segment
 * (sw_segment_closest, Ericson 2005, sec. 5.1.9).  A box (Quilez's signed
 * distance) and an ellipsoid (Newton on the Lagrange condition, in the
 * coordinates scaled by its semi-axes) are convex, so their distance along
 * the segment is convex in s and a golden-section search finds its least
 * value to 1e-12; a segment lying along a face, equally near at both ends,
 * takes its middle.  An ellipsoid far from the segment is rejected first
 * with a lower bound, (rho - 1) a_min, where rho is the segment's least
 * scaled distance from the centre.  Physics: docs/physics.md, "Rigid
 * obstacles".
 */
#include <math.h>
#include <string.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* Signed distance of the local point q to a box of half sizes h, and the
 * outward normal there (Quilez's box distance). */
static double box_distance(const double h[3], const double q[3], double n[3]) {
  double out[3], inside = -INFINITY;
  int face = 0;
  for (int k = 0; k < 3; k++) {
    double g = fabs(q[k]) - h[k];
    out[k] = g > 0 ? g : 0;
    if (g > inside) inside = g, face = k;
  }
  double len = sw_v3_norm(out);
  if (len > 0) {
    for (int k = 0; k < 3; k++) n[k] = copysign(out[k], q[k]) / len;
    return len;
  }
  n[0] = n[1] = n[2] = 0;
  n[face] = q[face] < 0 ? -1 : 1;
  return inside;
}

/* Signed distance of the local point q to the ellipsoid of semi-axes a and
 * the outward normal at its closest point (Eberly 2013): the closest point
 * is x_k = a_k^2 q_k / (t + a_k^2) with t the root of
 *   F(t) = sum_k (a_k q_k / (t + a_k^2))^2 - 1,
 * which is decreasing and convex on (-a_min^2, inf), so Newton's method
 * from a point left of the root, where F >= 0 (t = 0 outside, t = -a_min^2
 * + a_min |q_min| inside), moves right and never passes it (Eberly bisects
 * on the same bracket; Newton takes a few steps instead of ~100).  A
 * coordinate exactly 0 is taken as 1e-12 a_k, so that the root stays right
 * of the pole. */
static double ellipsoid_distance(const double a[3], const double q0[3], double n[3]) {
  double q[3], g = -1;
  int kmin = 0;
  for (int k = 0; k < 3; k++) {
    q[k] = fabs(q0[k]) > 1e-12 * a[k] ? q0[k] : copysign(1e-12 * a[k], q0[k]);
    if (a[k] < a[kmin]) kmin = k;
    g += (q[k] / a[k]) * (q[k] / a[k]);
  }
  double t = g < 0 ? -a[kmin] * a[kmin] + a[kmin] * fabs(q[kmin]) : 0.0;
  for (int it = 0; it < 100; it++) {
    double F = -1, dF = 0;
    for (int k = 0; k < 3; k++) {
      const double den = t + a[k] * a[k], z = a[k] * q[k] / den;
      F += z * z;
      dF -= 2 * z * z / den;
    }
    const double step = F / dF;
    if (!(step < 0) || t - step == t) break; /* at the root to round-off */
    t -= step;
  }
  double x[3], diff[3];
  for (int k = 0; k < 3; k++) {
    x[k] = a[k] * a[k] * q[k] / (t + a[k] * a[k]);
    n[k] = x[k] / (a[k] * a[k]);
    diff[k] = q0[k] - x[k];
  }
  sw_v3_scale(n, n, 1.0 / sw_v3_norm(n));
  const double dist = sw_v3_norm(diff);
  return g < 0 ? -dist : dist;
}

typedef double (*swPointDistance)(const double h[3], const double q[3], double n[3]);

/* min over s in [0, 1] of f(a + s d), convex in s: golden-section search to
 * 1e-12, the middle when both ends are as near (a face along the element). */
static double segment_search(swPointDistance f, const double h[3], const double a[3],
                             const double d[3], double *s_out, double n[3]) {
  const double g = 0.5 * (sqrt(5.0) - 1.0);
  double q[3], nn[3];
  double lo = 0, hi = 1, x1 = hi - g, x2 = lo + g;
#define AT(s) (q[0] = a[0] + (s) * d[0], q[1] = a[1] + (s) * d[1], q[2] = a[2] + (s) * d[2], f(h, q, nn))
  const double f0 = AT(0.0), f1 = AT(1.0);
  double y1 = AT(x1), y2 = AT(x2);
  while (hi - lo > 1e-12) {
    if (y1 <= y2) hi = x2, x2 = x1, y2 = y1, x1 = hi - g * (hi - lo), y1 = AT(x1);
    else lo = x1, x1 = x2, y1 = y2, x2 = lo + g * (hi - lo), y2 = AT(x2);
  }
  double s = 0.5 * (lo + hi), best = AT(s);
  const double tol = 1e-12 * (fabs(best) + sw_v3_norm(d));
  if (fabs(f0 - f1) <= tol && f0 - best <= tol) s = 0.5;  /* lying along a face */
  else if (f0 <= best) s = 0.0;
  else if (f1 <= best) s = 1.0;
  double D = AT(s);
#undef AT
  memcpy(n, nn, sizeof nn);
  *s_out = s;
  return D;
}

/* Unit vector across the segment direction d (for a segment whose nearest
 * point lies on the axis or at the centre itself). */
static void any_normal(double n[3], const double d[3]) {
  const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
  sw_v3_cross(n, d, fabs(d[0]) < 0.9 * sw_v3_norm(d) ? ex : ey);
  double len = sw_v3_norm(n);
  if (len > 0) sw_v3_scale(n, n, 1.0 / len);
  else n[0] = 0, n[1] = 0, n[2] = 1;
}

/* The least signed distance D from the local segment a + s d to obstacle
 * o's surface, its s and the outward normal n (local frame).  *s_out
 * brings in the element's radius: a distance known to exceed it may be
 * returned as a lower bound (the ellipsoid's quick rejection). */
double sw_obstacle_segment_distance(const swObstacleDesc *o, const double a[3], const double d[3],
                               double *s_out, double n[3]) {
  double s = 0.5, p[3], D;
  const double dd = sw_v3_dot(d, d);
  switch (o->shape) {
  case SW_OBSTACLE_SPHERE: /* the projection of the centre, clamped */
    s = dd > 0 ? sw_clamp01(-sw_v3_dot(a, d) / dd) : 0.0;
    for (int k = 0; k < 3; k++) p[k] = a[k] + s * d[k];
    D = sw_v3_norm(p);
    if (D > 0) sw_v3_scale(n, p, 1.0 / D);
    else any_normal(n, d);
    D -= o->radius;
    break;
  case SW_OBSTACLE_CYLINDER: { /* nearest to the e3 axis, across it */
    const double across = d[0] * d[0] + d[1] * d[1];
    s = across > 1e-14 * dd ? sw_clamp01(-(a[0] * d[0] + a[1] * d[1]) / across) : 0.5;
    for (int k = 0; k < 3; k++) p[k] = a[k] + s * d[k];
    p[2] = 0;
    D = sw_v3_norm(p);
    if (D > 0) sw_v3_scale(n, p, 1.0 / D);
    else {
      const double e3[3] = {0, 0, 1};
      any_normal(n, e3);
    }
    D -= o->radius;
    break;
  }
  case SW_OBSTACLE_CAPSULE: { /* two segments' closest points */
    const double b0[3] = {0, 0, -0.5 * o->length}, db[3] = {0, 0, o->length};
    double t, pq[3];
    D = sqrt(sw_segment_closest(a, d, b0, db, &s, &t, pq));
    if (D > 0) sw_v3_scale(n, pq, 1.0 / D);
    else any_normal(n, d);
    D -= o->radius;
    break;
  }
  case SW_OBSTACLE_BOX: D = segment_search(box_distance, o->half, a, d, &s, n); break;
  default: {
    /* in the coordinates scaled by the semi-axes the ellipsoid is the unit
     * ball: a segment whose scaled distance rho from the centre is > 1 is
     * at least (rho - 1) a_min from the surface, which rejects most */
    const double *h = o->half;
    double as[3], ds[3], ps[3];
    for (int k = 0; k < 3; k++) as[k] = a[k] / h[k], ds[k] = d[k] / h[k];
    const double dds = sw_v3_dot(ds, ds), u = dds > 0 ? sw_clamp01(-sw_v3_dot(as, ds) / dds) : 0.0;
    for (int k = 0; k < 3; k++) ps[k] = as[k] + u * ds[k];
    const double rho = sw_v3_norm(ps), hmin = fmin(h[0], fmin(h[1], h[2]));
    if (rho > 1 && (rho - 1) * hmin > *s_out) {
      *s_out = u;
      n[0] = n[1] = 0, n[2] = 1;
      return (rho - 1) * hmin; /* a lower bound, beyond the element's radius */
    }
    D = segment_search(ellipsoid_distance, o->half, a, d, &s, n);
    break;
  }
  }
  *s_out = s;
  return D;
}

