/* shape.c — the nodes and director frames of a curved rod: a centreline
 * r(s) with parallel-transported frames, a circular helix with its Frenet
 * frames, and the straight rod that unrolls a curved one.
 *
 * Design.  A discrete rod is its n + 1 nodes and one frame per element.  In
 * every shape here d3 lies along the element's chord x_{i+1} - x_i, so that
 * a rod placed in the shape it rests in has no shear strain (Gazzola et al.
 * 2018, eq. 2.7: sigma = Q (x_{i+1} - x_i) / l - d3 = 0 with l the chord)
 * and is exactly in equilibrium; the rest curvature that model.c takes from
 * consecutive frames (the log of Q_{i+1} Q_i^T over the Voronoi length,
 * eq. 3.6) converges to the continuous one at second order in the element
 * length.  What sets d1 differs:
 *   - a centreline r(s) (sw_shape_curve): d1 of the first element is the
 *     given normal made perpendicular to the first chord, and each next
 *     frame is the previous one turned by the smallest rotation that takes
 *     its d3 onto the next chord, the discrete parallel transport (the
 *     Bishop frame of a curve, Bishop 1975): no rest twist, and defined
 *     through straight parts and inflections, where the Frenet frame is not.
 *   - a helix (sw_shape_helix): d1 is the principal normal at the middle of
 *     the element, pointing at the axis, d2 = d3 x d1 the binormal: the
 *     Frenet frame.  Its rest curvature is then (0, kappa, tau), with
 *     kappa = R / (R^2 + c^2) and tau = +-c / (R^2 + c^2) (c = pitch / 2 pi,
 *     + for a right-handed helix), as in the reference's helical rods
 *     (mattialab/elastica, source/RodInitialConfigurations.cpp, helicalRod,
 *     whose d3 is the tangent at the element's middle instead of the chord).
 *     The principal normal at the middle of an element is perpendicular to
 *     its chord exactly, so the frame is orthonormal without projection.
 * Nodes of the helix are at equal arc lengths, the angle about the axis
 * theta_i = i Theta / n with Theta = length / sqrt(R^2 + c^2).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

static int finite3(const double *a) { return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]); }
static int finite_pos(double v) { return isfinite(v) && v > 0; }

static void set_frame(double *Q, const double *d1, const double *d2, const double *d3) {
  for (int k = 0; k < 3; k++) {
    Q[k] = d1[k];
    Q[3 + k] = d2[k];
    Q[6 + k] = d3[k];
  }
}

/* The unit chord of element i into t; 0 when it has no length. */
static int chord(const double *x, int i, double t[3]) {
  sw_v3_sub(t, x + 3 * (i + 1), x + 3 * i);
  double l = sw_v3_norm(t);
  if (!(l > 0) || !isfinite(l)) return 0;
  sw_v3_scale(t, t, 1.0 / l);
  return 1;
}

int sw_shape_curve(int n, double length, swCurveFn curve, const void *ctx,
                   const double normal[3], double *x, double *Q, char *err, size_t errlen) {
  if (n < 1 || !finite_pos(length)) {
    sw_fail(err, errlen, "a curve needs at least one element and a positive length");
    return SW_EMODEL;
  }
  for (int i = 0; i <= n; i++) {
    const double s = length * i / n;
    curve(s, x + 3 * i, ctx);
    if (!finite3(x + 3 * i)) {
      sw_fail(err, errlen, "the centreline is not a finite point at s = %g m", s);
      return SW_EMODEL;
    }
  }
  double d1[3], d2[3], d3[3], t[3];
  for (int i = 0; i < n; i++) {
    if (!chord(x, i, t)) {
      sw_fail(err, errlen, "the centreline has the same point at s = %g m and s = %g m, so "
              "element %d has no length", length * i / n, length * (i + 1) / n, i);
      return SW_EMODEL;
    }
    if (i == 0) {
      /* d1 = the normal without its part along the first chord */
      double p = sw_v3_dot(normal, t);
      for (int k = 0; k < 3; k++) d1[k] = normal[k] - p * t[k];
      double l1 = sw_v3_norm(d1);
      if (!(l1 > 1e-9 * sw_v3_norm(normal))) {
        sw_fail(err, errlen, "the normal (%g, %g, %g) is parallel to the centreline's first "
                "element", normal[0], normal[1], normal[2]);
        return SW_EMODEL;
      }
      sw_v3_scale(d1, d1, 1.0 / l1);
    } else {
      /* parallel transport: v' = c v + b x v + b (b . v) / (1 + c), the
       * rotation about b = d3 x t by the angle between d3 and t (Rodrigues,
       * with sin = |b|, cos = c) */
      double b[3], bv[3];
      sw_v3_cross(b, d3, t);
      double c = sw_v3_dot(d3, t);
      if (!(c > -1 + 1e-12)) {
        sw_fail(err, errlen, "the centreline turns back on itself at s = %g m (element %d "
                "points against element %d)", length * i / n, i, i - 1);
        return SW_EMODEL;
      }
      sw_v3_cross(bv, b, d1);
      double bd = sw_v3_dot(b, d1) / (1 + c);
      for (int k = 0; k < 3; k++) d1[k] = c * d1[k] + bv[k] + bd * b[k];
      /* back onto the plane of t at round-off */
      double p = sw_v3_dot(d1, t);
      for (int k = 0; k < 3; k++) d1[k] -= p * t[k];
      sw_v3_scale(d1, d1, 1.0 / sw_v3_norm(d1));
    }
    memcpy(d3, t, sizeof d3);
    sw_v3_cross(d2, d3, d1);
    set_frame(Q + 9 * i, d1, d2, d3);
  }
  return SW_OK;
}

int sw_shape_helix(int n, double radius, double pitch, double length, int hand,
                   const double start[3], const double axis[3], const double normal[3],
                   double *x, double *Q, char *err, size_t errlen) {
  if (n < 1 || !finite_pos(radius) || !(pitch >= 0) || !isfinite(pitch) ||
      !finite_pos(length) || (hand != 1 && hand != -1)) {
    sw_fail(err, errlen, "a helix needs a positive radius and length, a pitch >= 0 and a "
            "hand of +1 or -1 (got radius %g m, pitch %g m, length %g m, hand %d)", radius,
            pitch, length, hand);
    return SW_EMODEL;
  }
  /* a = the axis, e1 from the axis to the start, e2 = hand a x e1 */
  double F[9];
  if (!sw_frame_from(F, axis, normal)) {
    sw_fail(err, errlen, "a helix's axis is zero or parallel to its normal");
    return SW_EMODEL;
  }
  const double *n0 = F, *a = F + 6;
  double e1[3], e2[3], centre[3];
  sw_v3_scale(e1, n0, -1.0);
  sw_v3_cross(e2, a, e1);
  sw_v3_scale(e2, e2, (double)hand);
  for (int k = 0; k < 3; k++) centre[k] = start[k] + radius * n0[k];
  const double c = pitch / (2 * SW_PI);                      /* rise per radian */
  const double Theta = length / sqrt(radius * radius + c * c); /* the angle it turns */
  for (int i = 0; i <= n; i++) {
    const double th = Theta * i / n;
    for (int k = 0; k < 3; k++)
      x[3 * i + k] = centre[k] + radius * (cos(th) * e1[k] + sin(th) * e2[k]) + c * th * a[k];
  }
  /* the first node exactly at the start, whatever cos(0) rounds the centre to */
  memcpy(x, start, 3 * sizeof *x);
  for (int i = 0; i < n; i++) {
    const double th = Theta * (i + 0.5) / n;
    double d1[3], d2[3], d3[3];
    for (int k = 0; k < 3; k++) d1[k] = -(cos(th) * e1[k] + sin(th) * e2[k]);
    if (!chord(x, i, d3)) {
      sw_fail(err, errlen, "a helix's element %d has no length", i);
      return SW_EMODEL;
    }
    sw_v3_cross(d2, d3, d1);
    set_frame(Q + 9 * i, d1, d2, d3);
  }
  return SW_OK;
}

int sw_shape_straight(int n, const double *rest_x, const double start[3],
                      const double direction[3], const double normal[3], double *x, double *Q,
                      char *err, size_t errlen) {
  double F[9];
  if (n < 1 || !sw_frame_from(F, direction, normal)) {
    sw_fail(err, errlen, "a straight rod needs an element, and a direction neither zero nor "
            "parallel to its normal");
    return SW_EMODEL;
  }
  memcpy(x, start, 3 * sizeof *x);
  double s = 0, dx[3];
  for (int i = 0; i < n; i++) {
    sw_v3_sub(dx, rest_x + 3 * (i + 1), rest_x + 3 * i);
    s += sw_v3_norm(dx);
    for (int k = 0; k < 3; k++) x[3 * (i + 1) + k] = start[k] + s * F[6 + k];
    memcpy(Q + 9 * i, F, sizeof F);
  }
  return SW_OK;
}
