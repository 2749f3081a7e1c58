/* units_dim.c — dimension arithmetic for the checker.
 *
 * Design.  A dimension is a vector of small integer exponents over (kg, m, s,
 * rad), the base of the runtime's unit table (runtime/io/units.c), so the
 * compiler and the simulator's --set agree on every unit.  The angle counts
 * as a dimension so that a bare number is refused where an angle is required
 * and an angle where a plain number is; elsewhere (curvature in rad/m or 1/m,
 * angular velocity in rad/s or 1/s) the angle exponent is not held against
 * the user: see dim_fits().
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sema.h"

const swDim DIM_NONE = {{0, 0, 0, 0}};
const swDim DIM_MASS = {{1, 0, 0, 0}};
const swDim DIM_LENGTH = {{0, 1, 0, 0}};
const swDim DIM_TIME = {{0, 0, 1, 0}};
const swDim DIM_ANGLE = {{0, 0, 0, 1}};
const swDim DIM_PRESSURE = {{1, -1, -2, 0}};
const swDim DIM_DENSITY = {{1, -3, 0, 0}};

swDim dim_make(int kg, int m, int s, int rad) {
  swDim d = {{(signed char)kg, (signed char)m, (signed char)s, (signed char)rad}};
  return d;
}

int dim_eq(swDim a, swDim b) {
  for (int i = 0; i < SW_NDIM; i++)
    if (a.e[i] != b.e[i]) return 0;
  return 1;
}

int dim_fits(swDim want, swDim got) {
  /* a pure angle, and a plain number (poisson, elements, a fraction), must
   * match exactly: 30 deg is not a Poisson ratio */
  if (dim_eq(want, DIM_ANGLE) || dim_is_none(want)) return dim_eq(want, got);
  for (int i = 0; i < SW_NDIM; i++)
    if (i != SW_DIM_ANGLE && want.e[i] != got.e[i]) return 0;
  return 1;
}

int dim_is_none(swDim a) { return dim_eq(a, DIM_NONE); }

/* exponents saturate rather than wrap: a model raising m to the 100th power
 * gets a dimension error, not undefined behaviour */
static signed char clamp_exp(int e) { return (signed char)(e > 99 ? 99 : e < -99 ? -99 : e); }

swDim dim_mul(swDim a, swDim b) {
  swDim d;
  for (int i = 0; i < SW_NDIM; i++) d.e[i] = clamp_exp(a.e[i] + b.e[i]);
  return d;
}

swDim dim_div(swDim a, swDim b) {
  swDim d;
  for (int i = 0; i < SW_NDIM; i++) d.e[i] = clamp_exp(a.e[i] - b.e[i]);
  return d;
}

int dim_pow(swDim a, double p, swDim *out) {
  if (dim_is_none(a)) {
    *out = a;
    return 1;
  }
  if (!(fabs(p) <= 99) || p != floor(p)) return 0;
  for (int i = 0; i < SW_NDIM; i++) out->e[i] = clamp_exp((int)(a.e[i] * (int)p));
  return 1;
}

const char *dim_describe(swArena *a, swDim d) {
  char buf[96];
  sw_dim_describe(buf, sizeof buf, d.e);
  return ast_strdup(a, buf, strlen(buf));
}
